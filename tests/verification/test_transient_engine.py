"""Transient engine: one physics with the static model, RK4 order, step control, verdicts,
and the nonlinear threshold against the linear one."""
import math

import numpy as np
import pytest

from gfbopt import BearingModel, Grid, ParameterError, solve_static, solver_for
from gfbopt import discretisation as disc
from gfbopt.linear import linear_threshold, linearise, semi_discrete_eigenvalues
from gfbopt.transient import (RightHandSide, State, equilibrium_state, find_critical_mass,
                              fit_growth_rate, flux_residual, integrate_orbits,
                              pressure_and_film, rk4_step, stiffness_bound, transient_model)

GRID = Grid(36, 10)
MODELS = {
    "rigid": BearingModel(bearing_number=2.0, foil="rigid"),
    "simple": BearingModel(bearing_number=2.0, compliance=1.0),
    "simple_seam_co": BearingModel(bearing_number=2.0, compliance=1.0, film="seam",
                                   compression_only=True),
    "local": BearingModel(bearing_number=2.0, compliance=1.0, deflection_law="local"),
    "beam_seam": BearingModel(bearing_number=5.0, compliance=1.0, foil="beam",
                              top_foil_coefficient=1.0, film="seam"),
    "beam_periodic": BearingModel(bearing_number=5.0, compliance=1.0, foil="beam",
                                  top_foil_coefficient=1.0),
}


def _model(name, eps=0.4, grid=GRID):
    sol = solve_static(MODELS[name], eccentricity=eps, grid=grid)
    assert sol.success
    return sol, transient_model(sol)


@pytest.mark.parametrize("periodic", [True, False])
def test_fast_stencil_equals_the_definition(periodic):
    """The slicing kernel equals discretisation.reynolds_residual to round-off."""
    model = BearingModel(bearing_number=1.7, compliance=0.5,
                         film="periodic" if periodic else "seam")
    sol = solve_static(model, eccentricity=0.5, grid=GRID)
    tm = transient_model(sol)
    st = disc.make_stencil(GRID, periodic=periodic)
    rng = np.random.default_rng(3)
    p = 1 + 0.2 * rng.standard_normal(sol.pressure.shape)
    h = 1 + 0.3 * rng.random(sol.pressure.shape)
    fast = flux_residual(p[None], h[None], tm)[0].ravel()[st.unknown]
    slow = disc.reynolds_residual(p.ravel(), h.ravel(), st, 1.7, tm.dz)
    np.testing.assert_allclose(fast, slow, rtol=1e-12, atol=1e-12)
    rows = flux_residual(p[None], h[None, :, :1], tm)[0].ravel()[st.unknown]
    np.testing.assert_allclose(rows, disc.reynolds_residual(
        p.ravel(), np.repeat(h[:, 0], h.shape[1]), st, 1.7, tm.dz), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("name", list(MODELS))
def test_static_equilibrium_is_a_fixed_point(name):
    """The transient right-hand side vanishes at the IPOPT equilibrium: same film, foil and
    force physics (to the static solver's tolerance, ~1e-10)."""
    sol, tm = _model(name)
    state = equilibrium_state(tm, 2)
    d = RightHandSide(tm, np.array([1.0, 3.0]))(state)
    assert np.abs(d.phi).max() < 1e-9
    assert np.abs(d.u).max() < 1e-9 and np.abs(d.v).max() < 1e-9
    p, h = pressure_and_film(state.phi, state.x, state.y, tm)
    np.testing.assert_allclose(p[0], sol.pressure, atol=1e-10)
    np.testing.assert_allclose(np.broadcast_to(h[0], sol.film.shape), sol.film, atol=1e-10)


@pytest.mark.parametrize("name", ["rigid", "simple", "beam_seam"])
def test_stability_bound_covers_the_spectrum(name):
    """Gershgorin bound ≥ the largest |eigenvalue| of the Φ-Jacobian (finite differences,
    dense) and within 20 % of it (measured 1–12 %), so the automatic step (0.9 × the bound's
    limit) uses ≥ 75 % of the true limit."""
    _, tm = _model(name, grid=Grid(24, 8))
    state = equilibrium_state(tm, 1)
    rhs = RightHandSide(tm, np.ones(1))
    f0 = rhs(state).phi.ravel()
    n = f0.size
    jac = np.zeros((n, n))
    flat = state.phi.ravel()
    for k in range(n):
        ph = flat.copy()
        ph[k] += 1e-7
        jac[:, k] = (rhs(State(ph.reshape(state.phi.shape), state.x, state.y, state.u,
                                   state.v)).phi.ravel() - f0) / 1e-7
    radius = np.abs(np.linalg.eigvals(jac)).max()
    bound = stiffness_bound(state, tm)
    assert radius <= bound <= 1.2 * radius


class _Vec:
    """A plain vector with axpy, to test rk4_step alone."""

    def __init__(self, v):
        self.v = np.asarray(v, dtype=float)

    def axpy(self, a, d):
        return _Vec(self.v + a * d.v)


def test_rk4_is_fourth_order_on_a_known_solution():
    """y'' = −y (y = cos τ): the error at τ = 2 falls by 2⁴ = 16 per halving of the step."""
    def f(y):
        return _Vec([y.v[1], -y.v[0]])

    errors = []
    for n in (20, 40, 80):
        y, dt = _Vec([1.0, 0.0]), 2.0 / n
        for _ in range(n):
            y = rk4_step(f, y, dt)
        errors.append(abs(y.v[0] - math.cos(2.0)))
    assert math.log2(errors[0] / errors[1]) == pytest.approx(4.0, abs=0.1)
    assert math.log2(errors[1] / errors[2]) == pytest.approx(4.0, abs=0.1)


def test_engine_converges_at_fourth_order_in_time():
    """The full engine on the bearing: the journal position after 0.3 revolution with steps
    Δ, Δ/2, Δ/4 (Richardson): error ratio 16 ± 3."""
    _, tm = _model("simple")
    ends = []
    t_end = 2 * math.pi * 0.3
    steps = math.ceil(t_end / (0.9 * 2.78 / stiffness_bound(equilibrium_state(tm, 1), tm)))
    for k in range(3):              # steps that land exactly on τ_end
        orbit = integrate_orbits(tm, [3.0], revolutions=0.3, kick=0.05,
                                 time_step=t_end / (steps * 2**k), sample_every=10.0)
        ends.append(np.array([orbit.x[0, -1], orbit.y[0, -1]]))
    ratio = np.linalg.norm(ends[0] - ends[1]) / np.linalg.norm(ends[1] - ends[2])
    assert ratio == pytest.approx(16.0, abs=3.0)


def test_time_step_above_the_stability_limit_is_refused():
    _, tm = _model("rigid")
    limit = 2.78 / stiffness_bound(equilibrium_state(tm, 1), tm)
    with pytest.raises(ParameterError, match=r"^time_step = .*exceeds the RK4 stability limit"):
        integrate_orbits(tm, [2.0], revolutions=1, time_step=1.5 * limit)


@pytest.mark.parametrize("kwargs, match", [
    (dict(mass=[-1.0]), r"^mass = -1.0: must be finite and > 0"),
    (dict(mass=[1.0], revolutions=0), r"^revolutions = 0: must be finite and > 0"),
    (dict(mass=[float("nan")]), r"^mass = nan"),
])
def test_bad_transient_input(kwargs, match):
    _, tm = _model("rigid")
    mass = kwargs.pop("mass")
    with pytest.raises(ParameterError, match=match):
        integrate_orbits(tm, mass, **kwargs)


def test_bad_critical_mass_input():
    _, tm = _model("rigid")
    with pytest.raises(ParameterError, match=r"^tolerance = 0: must be finite and > 0"):
        find_critical_mass(tm, tolerance=0)
    sol = solve_static(MODELS["rigid"], eccentricity=0.4, grid=GRID)
    failed = sol.__class__(**{**sol.__dict__, "success": False, "status": "Infeasible"})
    with pytest.raises(ParameterError, match=r"did not converge"):
        transient_model(failed)


@pytest.mark.xdist_group("rk4_references")
def test_growth_rate_and_whirl_match_the_linear_eigenvalue(simple_transient_case, rk4_growth):
    """Small kick at 1.04 M̄c: the fitted growth rate and whirl ratio equal the least stable
    eigenvalue of the linearised semi-discrete system (1 % of σ, 1e-3 in whirl).  (The RK4 run
    is shared with test_rkc: tests/verification/conftest.py.)"""
    _, lin, thr, _ = simple_transient_case
    mass = 1.04 * thr.critical_mass
    ev = semi_discrete_eigenvalues(lin, mass, 1j * thr.whirl_ratio)
    ev = ev[np.argmin(np.abs(ev - 1j * thr.whirl_ratio))]
    orbit = rk4_growth
    assert orbit.growth_rate[0] == pytest.approx(ev.real, rel=0.01)
    assert orbit.whirl_ratio[0] == pytest.approx(ev.imag, abs=1e-3)
    assert orbit.verdict[0] == "unstable"


@pytest.mark.parametrize("name, eps", [("rigid", 0.4), ("simple", 0.4)])
def test_nonlinear_critical_mass_equals_the_linear_threshold(name, eps):
    """Issue acceptance (at a coarse grid here; 72 × 20 in results/nonlinear_vs_linear):
    small-kick transients find the linear threshold within 1 %."""
    model = MODELS[name]
    solver = solver_for(model, GRID)
    sol = solve_static(model, eccentricity=eps, solver=solver)
    thr = linear_threshold(linearise(sol, solver))
    result = find_critical_mass(transient_model(sol), linear_estimate=thr.critical_mass)
    assert result.success, result.message
    assert result.critical_mass == pytest.approx(thr.critical_mass, rel=0.01)
    lo, hi = result.bracket
    assert lo < result.critical_mass < hi and (hi - lo) <= 0.01 * result.critical_mass
    assert result.whirl_ratio == pytest.approx(thr.whirl_ratio, abs=0.01)


def test_critical_mass_without_a_linear_estimate():
    """Cold search (geometric first batch) reaches the same threshold to 1 %."""
    model = MODELS["rigid"]
    sol = solve_static(model, eccentricity=0.4, grid=Grid(24, 8))
    tm = transient_model(sol)
    solver = solver_for(model, Grid(24, 8))
    thr = linear_threshold(linearise(solve_static(model, eccentricity=0.4, solver=solver),
                                     solver))
    result = find_critical_mass(tm, tolerance=0.005)
    assert result.success
    assert result.critical_mass == pytest.approx(thr.critical_mass, rel=0.01)
    assert len({h["round"] for h in result.history}) >= 3


@pytest.mark.xdist_group("rk4_references")
def test_heavy_rotor_ends_in_contact_not_nan(rk4_heavy_rotor):
    _, orbit = rk4_heavy_rotor         # rigid, M̄ = 40, 30 revolutions (shared with test_rkc)
    assert orbit.verdict[0] == "contact"
    assert orbit.contact[0] and np.isfinite(orbit.contact_tau[0])
    valid = np.isfinite(orbit.x[0])
    assert valid.sum() > 10 and np.all(orbit.tau[valid] <= orbit.contact_tau[0])
    # detected within one RK4 step: the film at detection is just below the threshold
    assert 0.0 < np.nanmin(orbit.min_film[0]) <= 0.05
    table = orbit.to_frame(0)
    assert table["min_film"].notna().sum() == valid.sum()


@pytest.mark.xdist_group("rk4_references")
def test_large_kick_above_threshold_is_a_limit_cycle_not_stable(rk4_limit_cycle):
    """docs/PHYSICS.md trap: just above threshold a large orbit shrinks onto the limit cycle; its
    envelope falls, yet it must not be called stable.  (M̄ = 1.03 M̄c, kick 0.25, 40
    revolutions of RK4, shared with test_rkc: tests/verification/conftest.py.)"""
    orbit = rk4_limit_cycle
    assert orbit.verdict[0] == "limit cycle"
    assert orbit.amplitude[0] > 0.05


def test_fit_growth_rate_on_synthetic_modes():
    tau = np.arange(0, 60, 0.2)
    dx = (np.exp(-0.01 * tau) * np.cos(0.47 * tau) + 0.5 * np.exp(-0.3 * tau) * np.cos(1.3 * tau))
    dy = (np.exp(-0.01 * tau) * np.sin(0.47 * tau) - 0.4 * np.exp(-0.3 * tau) * np.sin(1.3 * tau))
    sigma, whirl = fit_growth_rate(tau, dx, dy)
    assert sigma == pytest.approx(-0.01, abs=1e-6) and whirl == pytest.approx(0.47, abs=1e-6)


@pytest.mark.parametrize("name", ["rigid", "simple", "simple_seam_co"])
def test_bdf_and_rk4_give_the_same_orbit(name):
    """The implicit path integrates the same right-hand side: positions agree to the BDF
    tolerance (rtol 1e-6 → 1e-7 of the clearance here) and the growth rates to 1 %."""
    _, tm = _model(name, grid=Grid(24, 8))
    rk4 = integrate_orbits(tm, [3.0], revolutions=4, kick=0.01, settle=1)
    bdf = integrate_orbits(tm, [3.0], revolutions=4, kick=0.01, settle=1, method="bdf",
                           sample_every=0.02)
    inside = rk4.tau <= bdf.tau[-1]         # RK4 samples on its own step grid
    x_bdf = np.interp(rk4.tau[inside], bdf.tau, bdf.x[0])
    # linear interpolation between 0.02-rad samples adds < 1e-6 for a 0.01-clearance orbit
    assert np.abs(x_bdf - rk4.x[0, inside]).max() < 1e-5
    assert bdf.growth_rate[0] == pytest.approx(rk4.growth_rate[0], rel=0.01, abs=1e-4)


def test_bdf_refuses_models_it_does_not_cover():
    _, tm = _model("beam_seam", grid=Grid(24, 8))
    with pytest.raises(ParameterError, match=r"^method = 'bdf': does not support the beam foil law"):
        integrate_orbits(tm, [3.0], revolutions=1, method="bdf")
    with pytest.raises(ParameterError,
                       match=r"^method = 'euler': must be one of rk4, rkc, bdf"):
        integrate_orbits(tm, [3.0], revolutions=1, method="euler")


@pytest.mark.parametrize("name", ["rigid", "simple_seam_co"])
def test_bdf_sparse_jacobian_equals_dense_finite_differences(name):
    """Grouped finite differences + analytic force rows = column-by-column differences
    (to 1e-6 of the largest entry: FD truncation), and nothing lies outside the pattern."""
    from gfbopt.transient.bdf import FlatRotor

    _, tm = _model(name, grid=Grid(24, 8))
    rotor = FlatRotor(tm, 2.0)
    s = equilibrium_state(tm, 1)
    s.x += 0.01
    s.u[:] = 0.02
    y = rotor.pack(s)
    sparse = rotor.jacobian(0.0, y).toarray()
    f0 = rotor(0.0, y)
    dense = np.empty_like(sparse)
    for k in range(y.size):
        yk = y.copy()
        yk[k] += 1e-7
        dense[:, k] = (rotor(0.0, yk) - f0) / 1e-7
    assert np.abs(sparse - dense).max() < 1e-5 * np.abs(dense).max()
