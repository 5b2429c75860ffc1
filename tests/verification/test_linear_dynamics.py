"""Linearised dynamics: coefficients, threshold, and their independent checks."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from gfbopt import BearingModel, Grid, ParameterError, solve_static, solver_for
from gfbopt import discretisation as disc
from gfbopt.linear import (characteristic_root, coefficients, impedance, least_stable_mode,
                           linear_threshold, linearise, semi_discrete_eigenvalues)

GRID = Grid(36, 10)

CASES = {
    "rigid": BearingModel(bearing_number=2.0, foil="rigid"),
    "simple": BearingModel(bearing_number=2.0, compliance=1.0, foil="simple"),
    "local": BearingModel(bearing_number=2.0, compliance=1.0, foil="simple",
                          deflection_law="local"),
    "beam": BearingModel(bearing_number=5.0, compliance=1.0, foil="beam", film="seam",
                         top_foil_coefficient=1.0, seam_angle_deg=200),
}


def _linearised(name, eps=0.4, grid=GRID):
    model = CASES[name]
    solver = solver_for(model, grid)
    sol = solve_static(model, eccentricity=eps, solver=solver)
    return model, solver, sol, linearise(sol, solver)


@pytest.mark.parametrize("name", list(CASES))
def test_stiffness_equals_finite_differences_of_static_forces(name):
    """K(γ → 0) = −∂F/∂(X, Y) from static solves at displaced journal positions (central
    differences, step 1e-5: truncation ~1e-10, solver tolerance ~1e-12) to 1e-6 relative."""
    model, solver, sol, lin = _linearised(name)
    k = coefficients(lin, [0.0]).stiffness[0]
    x0, y0 = sol.eccentricity * math.cos(sol.attitude_angle_rad), sol.eccentricity * math.sin(
        sol.attitude_angle_rad)
    fd = np.zeros((2, 2))
    h = 1e-5
    for j, (dx, dy) in enumerate(((h, 0.0), (0.0, h))):
        forces = []
        for sign in (1, -1):
            x, y = x0 + sign * dx, y0 + sign * dy
            f = solve_static(model, eccentricity=math.hypot(x, y),
                             attitude_angle_deg=math.degrees(math.atan2(y, x)),
                             solver=solver, initial=sol)
            assert f.success
            forces.append(np.array(f.force))
        fd[:, j] = -(forces[0] - forces[1]) / (2 * h)
    np.testing.assert_allclose(k, fd, rtol=1e-6, atol=1e-6 * np.abs(fd).max())


@pytest.mark.parametrize("gamma", [0.1, 0.3, 0.45])
def test_forward_circular_whirl_equals_static_bearing_at_reduced_bearing_number(gamma):
    """docs/PHYSICS.md: a centred circular whirl at ratio ν sees the steady film of Λ(1 − 2ν).
    At ε → 0 the linear forward-whirl force −Re[Z(iν)(1, −i)]ε equals the static force of a
    bearing with Λ(1 − 2ν) at (X, Y) = (ε, 0).  Discretely the identity holds to O(Δθ²) (the
    squeeze term is not a shifted Couette difference), so the discrepancy must fall 4× per
    grid refinement (3.5–4.5 measured) and be < 1.5 % at 72 × 20.  A wrong squeeze factor
    gives a discrepancy that does not shrink."""
    lam, eps = 2.0, 1e-4
    model = BearingModel(bearing_number=lam, foil="rigid")
    gaps = []
    for grid in (GRID, Grid(72, 20)):
        solver = solver_for(model, grid)
        lin = linearise(solve_static(model, eccentricity=eps, solver=solver), solver)
        linear_force = -np.real(impedance(lin, 1j * gamma) @ np.array([1.0, -1.0j])) * eps
        static = solve_static(model.replace(bearing_number=lam * (1 - 2 * gamma)),
                              eccentricity=eps, attitude_angle_deg=0.0, solver=solver)
        gaps.append(np.abs(linear_force - static.force).max() / np.abs(static.force).max())
    assert 3.5 < gaps[0] / gaps[1] < 4.5
    assert gaps[1] < 0.015


def test_half_frequency_whirl_carries_no_force():
    """At ν = 1/2 the forward circular whirl force vanishes for any ε (massless film); the
    discrete force is O(Δθ²): it falls ~4× per refinement and is < 0.3 % of |Z| at 72 × 20."""
    gaps = []
    for grid in (GRID, Grid(72, 20)):
        lin = _linearised("rigid", eps=1e-4, grid=grid)[3]
        z = impedance(lin, 0.5j)
        gaps.append(np.abs(z @ np.array([1.0, -1.0j])).max() / np.abs(z).max())
    assert 3.5 < gaps[0] / gaps[1] < 4.5
    assert gaps[1] < 3e-3


def _transient_rigid_force(model, grid, x0, amplitude, gamma, periods=6):
    """Integrate the time-dependent Reynolds equation (numpy residual, BDF) for a journal
    moving X = X0 + a sin γτ and return the first harmonic of (F_X, F_Y) per unit a."""
    st = disc.make_stencil(grid, periodic=True)
    dz = st.axial_spacing(model.length_ratio)
    theta = st.psi
    lam = model.bearing_number

    def film(t):
        return 1 - (x0 + amplitude * math.sin(gamma * t)) * np.cos(theta)

    def dfilm(t):
        return -amplitude * gamma * math.cos(gamma * t) * np.cos(theta)

    nzn = st.n_z_nodes

    def rhs(t, pu):
        p = np.ones(st.n_nodes)
        p[st.unknown] = pu
        h = np.repeat(film(t), nzn)
        r = disc.reynolds_residual(p, h, st, lam, dz)
        hu = h[st.unknown]
        hdot = np.repeat(dfilm(t), nzn)[st.unknown]
        return (r / (2 * lam) - pu * hdot) / hu       # 2Λ(H Ṗ + P Ḣ) = R

    static = solve_static(model, eccentricity=x0, attitude_angle_deg=0.0, grid=grid)
    p0 = static.pressure.ravel()[st.unknown]
    period = 2 * math.pi / gamma
    t_end = periods * period
    ts = np.linspace(t_end - 2 * period, t_end, 401)
    out = solve_ivp(rhs, (0, t_end), p0, method="BDF", t_eval=ts, rtol=1e-9, atol=1e-11)
    forces = []
    for k in range(ts.size):
        p = np.ones(st.n_nodes)
        p[st.unknown] = out.y[:, k]
        forces.append(disc.film_forces(disc.axial_integral(p, st, dz), theta, st.theta_weight))
    forces = np.array(forces)[:-1]
    ts = ts[:-1]
    s, c = np.sin(gamma * ts), np.cos(gamma * ts)
    # F ≈ F0 − (K a sin γτ + C a γ cos γτ): project on sin and cos over whole periods
    k = -2 * (forces * s[:, None]).mean(axis=0) / amplitude
    cg = -2 * (forces * c[:, None]).mean(axis=0) / amplitude
    return k, cg / gamma


@pytest.mark.parametrize("gamma, lam", [(0.6, 2.0), (0.15, 5.0)])
def test_coefficients_equal_transient_response_to_small_harmonic_motion(gamma, lam):
    """Prescribed X = X0 + a sin γτ in the nonlinear time-dependent model (a = 1e-4): the
    first harmonic of the force gives K_·X and C_·X equal to the perturbation's within
    1 % of the largest coefficient (O(a) nonlinearity, time discretisation ~1e-6, start-up
    transient decayed after 4 periods).  At γ = 0.15, Λ = 5 the direct damping is negative,
    and the transient agrees: a property of the compressible film, not of the linearisation."""
    model = BearingModel(bearing_number=lam, foil="rigid")
    grid = Grid(24, 8)
    solver = solver_for(model, grid)
    x0 = 0.4
    sol = solve_static(model, eccentricity=x0, attitude_angle_deg=0.0, solver=solver)
    # linearise at this (non-equilibrium) position: same algebra, W0 irrelevant here
    lin = linearise(sol.__class__(**{**sol.__dict__, "success": True}), solver)
    coeff = coefficients(lin, [gamma])
    k_t, c_t = _transient_rigid_force(model, grid, x0, 1e-4, gamma)
    scale = np.abs(coeff.stiffness[0]).max()
    np.testing.assert_allclose(k_t, coeff.stiffness[0][:, 0], atol=0.01 * scale)
    np.testing.assert_allclose(c_t, coeff.damping[0][:, 0],
                               atol=0.01 * np.abs(coeff.damping[0]).max())


@pytest.mark.parametrize("name", ["rigid", "simple", "beam"])
def test_threshold_is_where_a_semi_discrete_eigenvalue_crosses_the_axis(name):
    """The impedance root (M̄c, γc) is an eigenvalue ±iγc of the linearised semi-discrete
    system at M̄c (to 1e-8), with growth rate < 0 below and > 0 above M̄c (±5 %)."""
    _, _, _, lin = _linearised(name)
    thr = linear_threshold(lin)
    assert not thr.stable_for_all_masses and 0.3 < thr.whirl_ratio < 0.6
    ev = semi_discrete_eigenvalues(lin, thr.critical_mass, 1j * thr.whirl_ratio)
    nearest = ev[np.argmin(np.abs(ev - 1j * thr.whirl_ratio))]
    assert abs(nearest.real) < 1e-8 and nearest.imag == pytest.approx(thr.whirl_ratio, abs=1e-8)
    for factor, sign in ((0.95, -1), (1.05, 1)):
        ev = semi_discrete_eigenvalues(lin, factor * thr.critical_mass, 1j * thr.whirl_ratio)
        nearest = ev[np.argmin(np.abs(ev - 1j * thr.whirl_ratio))]
        assert np.sign(nearest.real) == sign
        root = characteristic_root(lin, factor * thr.critical_mass, 1j * thr.whirl_ratio)
        assert root == pytest.approx(nearest, abs=1e-8)


def test_critical_mass_converges_with_the_grid():
    """Observed order of M̄c on grids 24x8, 48x16, 96x32 is 2 ± 0.4."""
    values = []
    for grid in (Grid(24, 8), Grid(48, 16), Grid(96, 32)):
        values.append(linear_threshold(_linearised("simple", grid=grid)[3]).critical_mass)
    order = math.log2(abs(values[0] - values[1]) / abs(values[1] - values[2]))
    assert order == pytest.approx(2.0, abs=0.4)


def test_concentric_limit_threshold_goes_to_zero_mass_and_half_whirl():
    """docs/PHYSICS.md: as ε → 0, M̄c → 0 and the whirl ratio → 1/2."""
    results = [linear_threshold(_linearised("rigid", eps=e)[3]) for e in (0.05, 0.02)]
    assert results[1].critical_mass < results[0].critical_mass < 0.5
    assert results[1].whirl_ratio == pytest.approx(0.5, abs=0.01)


def test_line_of_centres_frame_is_a_rotation():
    _, _, sol, lin = _linearised("simple")
    c = coefficients(lin, [0.0, 0.4])
    r = c.in_line_of_centres_frame()
    for a, b in ((c.stiffness, r.stiffness), (c.damping, r.damping)):
        np.testing.assert_allclose(np.trace(a, axis1=1, axis2=2), np.trace(b, axis1=1, axis2=2))
        np.testing.assert_allclose(np.linalg.det(a), np.linalg.det(b))


def test_bad_linear_input():
    _, _, sol, lin = _linearised("rigid")
    with pytest.raises(ParameterError, match=r"^whirl_ratio = -0.1: must be finite and >= 0"):
        coefficients(lin, [0.2, -0.1])
    with pytest.raises(ParameterError, match=r"^whirl_ratio = nan"):
        coefficients(lin, [float("nan")])
    with pytest.raises(ParameterError, match=r"^mass = -1.0: must be finite and > 0"):
        semi_discrete_eigenvalues(lin, -1.0, 0.5j)
    failed = sol.__class__(**{**sol.__dict__, "success": False, "status": "Infeasible"})
    with pytest.raises(ParameterError, match=r"status Infeasible.*did not converge"):
        linearise(failed)


def test_least_stable_mode_changes_sign_at_the_threshold():
    _, _, _, lin = _linearised("simple")
    thr = linear_threshold(lin)
    below = least_stable_mode(lin, 0.9 * thr.critical_mass, thr)
    above = least_stable_mode(lin, 1.1 * thr.critical_mass, thr)
    assert below.real < 0 < above.real
    assert below.imag == pytest.approx(thr.whirl_ratio, abs=0.02)


@pytest.mark.parametrize("seam_deg, unstable", [(90.0, True), (180.0, False)])
def test_unstable_massless_journal_gives_zero_critical_mass(seam_deg, unstable):
    """A seam inside the loaded arc (welded end 90° from the load; the Ruscitto bearing at
    20,000 rpm and 20 N: Λ = 3.4, S = 1.05, W̄ = 0.55) pushes the massless journal's
    half-frequency mode — neutral for a concentric periodic film — into the right half plane:
    the rotor whirls at every mass.  The impedance scan finds no crossing with M̄ > 0 there (the
    roots cross at negative u), which linear_threshold once reported as 'stable for every
    rotor mass'; its stability probe below the crossings now gives M̄c = 0.  Checked against
    eigenvalues at M̄ = 0.01, 1 and 5 (growth > 0; the nonlinear transient agrees: growth
    0.020 and 0.037 per rad at M̄ = 0.2 and 1 on this grid).  With the welded end opposite the
    load (180°) small rotors are stable and M̄c > 0."""
    model = BearingModel(bearing_number=3.4, compliance=1.05, film="seam",
                         seam_angle_deg=seam_deg)
    lin = linearise(solve_static(model, load=0.55, grid=GRID))
    thr = linear_threshold(lin)
    assert bool(thr.critical_mass == 0.0) == unstable
    assert bool(thr.probe_growth_rate > 0) == unstable and not thr.stable_for_all_masses
    for mass in (0.01, 1.0):
        assert bool(least_stable_mode(lin, mass, thr).real > 0) == unstable
    if unstable:
        assert "unstable for every rotor mass" in thr.message
        assert least_stable_mode(lin, 5.0, thr).real > 0
    else:
        assert 1.0 < thr.critical_mass < 5.0 and thr.message == ""
