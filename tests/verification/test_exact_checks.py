"""Verification: consequences of the equations that a correct solver meets on any grid.

Tolerances are stated per test: round-off (1e-9 and below) where the discrete scheme is exact,
grid error (measured orders, O(Δθ²)) where it is not.
"""
import math

import numpy as np
import pytest

from gfbopt import BearingModel, Grid, StaticSolver, solve_static
from gfbopt import discretisation as disc
from gfbopt.physics.beam import beam_deflection, beam_matrices
from gfbopt.physics.closed_forms import small_eccentricity_limit


def test_second_order_grid_convergence():
    """Observed order of the load on grids refined by 2 is 2 ± 0.25 (rigid, Λ = 3, ε = 0.6)."""
    model = BearingModel(bearing_number=3.0, foil="rigid")
    loads = [solve_static(model, eccentricity=0.6, grid=Grid(n, n // 3)).load
             for n in (24, 48, 96)]
    order = math.log2(abs(loads[0] - loads[1]) / abs(loads[1] - loads[2]))
    assert order == pytest.approx(2.0, abs=0.25)


def test_concentric_journal_carries_no_load(periodic_solver):
    """ε = 0: P ≡ 1 satisfies the discrete equations exactly; the force is zero."""
    sol = solve_static(BearingModel(bearing_number=2.0, compliance=1.0), eccentricity=0.0,
                       solver=periodic_solver)
    assert sol.success
    assert sol.residual == 0.0
    assert sol.load == 0.0 and sol.force == (0.0, 0.0)
    assert np.all(sol.pressure == 1.0) and sol.min_film == 1.0


@pytest.mark.parametrize("compliance, law", [(0.0, "mean"), (1.0, "mean"), (1.0, "local")])
def test_small_eccentricity_matches_ausman(periodic_solver, local_law_solver, compliance, law):
    """As ε → 0 the load per unit ε and the attitude angle tend to Ausman's first-order values
    (docs/PHYSICS.md).  At ε = 1e-3 the nonlinear terms are O(ε) = 0.1 %; the 72 × 20 grid error is
    ≤ 0.3 % (grid_convergence), hence 0.5 % and 0.3°."""
    foil = "rigid" if compliance == 0 else "simple"
    model = BearingModel(bearing_number=2.0, compliance=compliance, foil=foil,
                         deflection_law=law)
    eps = 1e-3
    solver = local_law_solver if law == "local" else periodic_solver
    sol = solve_static(model, eccentricity=eps, solver=solver)
    stiffness, phi = small_eccentricity_limit(model)
    assert sol.success
    assert sol.load / eps == pytest.approx(stiffness, rel=5e-3)
    assert sol.attitude_angle_deg == pytest.approx(math.degrees(phi), abs=0.3)


def test_force_balance_recomputed_independently(periodic_solver):
    """Given a load, recompute the film force from the returned pressure field with numpy's own
    trapezoid rule in θ (periodic: rectangle rule) and Z; it balances the load to 1e-9."""
    model = BearingModel(bearing_number=1.5, compliance=0.8, foil="simple")
    sol = solve_static(model, load=1.0, solver=periodic_solver)
    assert sol.success
    gauge = sol.pressure - 1.0
    axial = np.trapezoid(gauge, sol.z, axis=1)
    dth = 2 * math.pi / sol.theta.size
    fx = -np.sum(axial * np.cos(sol.theta)) * dth
    fy = -np.sum(axial * np.sin(sol.theta)) * dth
    assert fx == pytest.approx(-1.0, abs=1e-9)
    assert fy == pytest.approx(0.0, abs=1e-9)
    # and the journal position is consistent with the film thickness returned
    h_rigid = 1 - sol.eccentricity * np.cos(sol.theta - sol.attitude_angle_rad)
    np.testing.assert_allclose(sol.film[:, 0], h_rigid + sol.deflection[:, 0], atol=1e-12)
    np.testing.assert_allclose(sol.deflection[:, 0], 0.8 * (sol.mean_pressure - 1), atol=1e-9)


@pytest.mark.parametrize("film, beam, law", [("periodic", False, "mean"), ("seam", True, "mean"),
                                             ("periodic", False, "local")])
def test_casadi_jacobian_matches_finite_differences(film, beam, law):
    """The symbolic Jacobian equals central differences of the residual to 1e-6 (relative to
    the largest entry); FD truncation error at step 1e-6 is ~1e-10."""
    solver = StaticSolver(Grid(16, 4), film=film,
                          foil_law="beam" if beam else ("local" if law == "local" else "simple"))
    model = BearingModel(bearing_number=2.0, compliance=0.7, foil="beam" if beam else "simple",
                         top_foil_coefficient=0.3, film=film, deflection_law=law)
    sol = solve_static(model, eccentricity=0.5, solver=solver)
    rng = np.random.default_rng(1)
    x = sol.state + 1e-3 * rng.standard_normal(sol.state.size)
    p = solver.parameters(model, True, 0.9)
    jac = np.asarray(solver.jacobian_function()(x, p)[1].full())
    g = solver.residual_function
    fd = np.empty_like(jac)
    step = 1e-6
    for k in range(x.size):
        e = np.zeros(x.size)
        e[k] = step
        fd[:, k] = (np.asarray(g(x + e, p)).ravel() - np.asarray(g(x - e, p)).ravel()) / (2 * step)
    assert np.abs(jac - fd).max() <= 1e-6 * np.abs(jac).max()


def test_vanishing_compliance_gives_the_rigid_bearing(periodic_solver):
    """S → 0 in the simple model: load and attitude converge to the rigid bearing's, O(S)."""
    rigid = solve_static(BearingModel(bearing_number=1.0, foil="rigid"), eccentricity=0.7,
                         solver=periodic_solver)
    soft = solve_static(BearingModel(bearing_number=1.0, compliance=1e-7, foil="simple"),
                        eccentricity=0.7, solver=periodic_solver)
    assert soft.load == pytest.approx(rigid.load, rel=1e-6)
    assert soft.attitude_angle_rad == pytest.approx(rigid.attitude_angle_rad, abs=1e-6)


def test_beam_with_vanishing_bending_stiffness_gives_the_simple_model():
    """C → 0: the Hermite beam on the bump foundation reduces to the L² projection of the
    simple law W = S(P̄ − 1); the projection differs from nodal collocation by O(Δθ²), which
    at 72 nodes is ≤ 0.2 % in load and 0.05° in attitude (and shrinks 4× per refinement)."""
    diffs = []
    for grid in (Grid(36, 10), Grid(72, 20)):
        beam = BearingModel(bearing_number=5.0, compliance=1.0, foil="beam", film="seam",
                            top_foil_coefficient=1e-9)
        beam_sol = solve_static(beam, eccentricity=0.3, grid=grid)
        simple_sol = solve_static(beam.replace(foil="simple"), eccentricity=0.3, grid=grid)
        diffs.append(abs(beam_sol.load / simple_sol.load - 1))
        assert math.degrees(abs(beam_sol.attitude_angle_rad - simple_sol.attitude_angle_rad)) < 0.05
    assert diffs[1] < 2e-3
    assert diffs[1] < 0.5 * diffs[0]


def test_hermite_cantilever_is_exact_at_the_nodes():
    """Without foundation (S → ∞) a clamped–free beam C W'''' = q, uniform q over length 2π,
    has tip deflection q (2π)⁴/(8C); cubic Hermite elements are nodally exact."""
    n = 12
    mats = beam_matrices(n, 2 * math.pi / n)
    c, q = 0.5, 0.01
    w = beam_deflection(np.full(n + 1, q), mats, compliance=1e12, coefficient=c)
    assert w[-1] == pytest.approx(q * (2 * math.pi)**4 / (8 * c), rel=1e-9)
    x = np.linspace(0, 2 * math.pi, n + 1)
    exact = q / (24 * c) * (x**4 - 4 * 2 * math.pi * x**3 + 6 * (2 * math.pi)**2 * x**2)
    np.testing.assert_allclose(w, exact, rtol=1e-9, atol=1e-12)


def test_elrod_burgdorfer_invariant_holds_to_round_off(periodic_solver):
    """Rigid aligned bearing, periodic film: Σ_i H_i³ (P_ij² − 1) = 0 at every axial station;
    the conservative scheme keeps it to round-off (here ≤ 1e-9 × the pressure scale)."""
    sol = solve_static(BearingModel(bearing_number=3.0, foil="rigid"), eccentricity=0.8,
                       solver=periodic_solver)
    h3 = sol.film[:, 0] ** 3
    invariant = (h3[:, None] * (sol.pressure**2 - 1)).sum(axis=0)
    assert np.abs(invariant).max() < 1e-9 * np.abs(h3[:, None] * sol.pressure**2).sum(axis=0).max()


def test_numpy_and_casadi_residuals_are_one_definition(periodic_solver):
    """The residual the post-processing evaluates in numpy equals the CasADi one at a random
    state (same function, two backends)."""
    st = periodic_solver.stencil
    rng = np.random.default_rng(0)
    p = 1 + 0.1 * rng.standard_normal(st.n_nodes)
    h = 1 + 0.3 * rng.standard_normal(st.n_nodes) ** 2
    import casadi as ca
    ps, hs = ca.SX.sym("p", st.n_nodes), ca.SX.sym("h", st.n_nodes)
    f = ca.Function("r", [ps, hs], [disc.reynolds_residual(ps, hs, st, 1.7, 0.1)])
    np.testing.assert_allclose(np.asarray(f(p, h)).ravel(),
                               disc.reynolds_residual(p, h, st, 1.7, 0.1), rtol=1e-13, atol=1e-12)
