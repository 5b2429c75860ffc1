"""Verification of the static build (gfbopt.static.model): the θ-strip Reynolds assembly and
the hand-assembled Jacobian against CasADi's own AD of the same equations.

The build evaluates Reynolds on three-row patches mapped over the θ-rows and forms the
Jacobian by the chain rule (docs/PHYSICS.md, numerical notes).  These tests check, on small
grids and for every static structure and film, that
* the residual is the one definition of the film physics: the Reynolds rows equal
  :func:`gfbopt.discretisation.reynolds_residual` on numpy arrays (round-off, 1e-13);
* the Jacobian has exactly the sparsity of CasADi's AD of the flattened (expanded) residual
  and the same entries to round-off (1e-13 relative to the largest entry);
* IPOPT is given that Jacobian and an empty Hessian, and the build is deterministic;
* bad inputs are refused with a one-line :class:`ParameterError`.
"""
import casadi as ca
import numpy as np
import pytest

from gfbopt import BearingModel, Grid, ParameterError, StaticSolver, solve_static
from gfbopt import discretisation as disc
from gfbopt.static import solver_key
from gfbopt.static.solution import foil_parameters

CASES = [("periodic", "simple"), ("seam", "simple"), ("periodic", "local"),
         ("seam", "local"), ("periodic", "beam"), ("seam", "beam")]


def _model(film: str, structure: str) -> BearingModel:
    foil = "beam" if structure == "beam" else "simple"
    return BearingModel(bearing_number=1.7, compliance=0.6, top_foil_coefficient=0.2,
                        foil=foil, film=film, length_ratio=0.8,
                        deflection_law="local" if structure == "local" else "mean",
                        subambient="gumbel" if film == "seam" else "full")


def _random_state(solver: StaticSolver, seed: int) -> np.ndarray:
    """A state near a physical one (P ≈ 1, H ≈ 1, ε ≈ 0.4), generic enough that no
    derivative vanishes by accident."""
    rng = np.random.default_rng(seed)
    lay = solver.layout
    x = 0.1 * rng.standard_normal(lay.size)
    x[lay.pressure] += 1.0
    x[lay.film] += 1.0
    x[lay.eccentricity] = 0.4
    x[lay.attitude] = 0.7
    return x


@pytest.fixture(scope="module", params=CASES, ids=["-".join(c) for c in CASES])
def built(request):
    film, structure = request.param
    grid = Grid(16, 6)
    return StaticSolver(grid, film=film, foil_law=structure), _model(film, structure)


def test_reynolds_rows_are_the_numpy_residual(built):
    """g[:n_unknown] equals reynolds_residual on numpy arrays of the same P and H."""
    solver, model = built
    st, lay = solver.stencil, solver.layout
    x = _random_state(solver, 0)
    p = solver.parameters(model, True, 0.7)
    g = np.asarray(solver.residual_function(x, p)).ravel()
    p_full = np.ones(st.n_nodes)
    p_full[st.unknown] = x[lay.pressure]
    dz = st.axial_spacing(model.length_ratio)
    mean_gauge = disc.axial_integral(p_full, st, dz) / (2 * model.length_ratio)
    w_nodes, _ = solver.law.deflection(p_full, mean_gauge, x[lay.beam],
                                       foil_parameters(model), st, solver.law_data)
    # the lifted film is the whole H (simple, beam) or its rigid part (local law)
    lifted = np.repeat(x[lay.film], st.n_z_nodes)
    h = lifted if solver.law.lifted_film_is_total else lifted + w_nodes
    expected = disc.reynolds_residual(p_full, h, st, model.bearing_number, dz)
    assert g.size == solver.n_equations == lay.size
    np.testing.assert_allclose(g[:st.n_unknown], expected, rtol=1e-13,
                               atol=1e-13 * np.abs(expected).max())


def test_jacobian_equals_casadi_ad_of_the_flat_residual(built):
    """Same sparsity as AD of the expanded (flat SX) residual, same entries to round-off."""
    solver, model = built
    flat = solver.residual_function.expand()
    xs = ca.SX.sym("x", solver.layout.size)
    ps = ca.SX.sym("p", solver.n_parameters)
    reference = ca.Function("reference", [xs, ps], [ca.jacobian(flat(xs, ps), xs)])
    for seed in (1, 2):
        x = _random_state(solver, seed)
        p = solver.parameters(model, seed == 1, 0.7)
        g, jac = solver.jacobian_function()(x, p)
        ref = reference(x, p)
        assert jac.sparsity() == ref.sparsity()
        scale = float(np.abs(ref.nonzeros()).max())
        assert np.abs(np.array(jac.nonzeros()) - np.array(ref.nonzeros())).max() \
            <= 1e-13 * scale
        np.testing.assert_array_equal(np.asarray(g).ravel(),
                                      np.asarray(solver.residual_function(x, p)).ravel())


def test_ipopt_gets_the_assembled_jacobian_and_an_empty_hessian(built):
    """The nlpsol's Jacobian is the build's own function; the Hessian of the Lagrangian is
    structurally empty (square system)."""
    solver, _ = built
    nlp = solver._nlp
    assert solver.jacobian_function().name() == "nlp_jac_g"
    assert nlp.get_function("nlp_hess_l").sparsity_out(0).nnz() == 0
    assert solver.jacobian_function().sparsity_out(1).shape == (solver.n_equations,
                                                                  solver.layout.size)


def test_two_builds_give_identical_solutions():
    """The build is deterministic: two builds solve to the same bits."""
    model = _model("periodic", "simple")
    grid = Grid(24, 8)
    a = solve_static(model, load=0.6, solver=StaticSolver(grid))
    b = solve_static(model, load=0.6, solver=StaticSolver(grid))
    assert a.success and b.success
    np.testing.assert_array_equal(a.state, b.state)


def test_user_ipopt_options_override_the_defaults():
    """An IPOPT option given by the caller wins (one iteration cannot converge a cold start)."""
    solver = StaticSolver(Grid(16, 4), ipopt_options={"ipopt.max_iter": 1})
    sol = solve_static(BearingModel(bearing_number=1.0), eccentricity=0.6, solver=solver,
                       continuation=False)
    assert not sol.success
    assert sol.status == "Maximum_Iterations_Exceeded"


def test_solver_key_matches_the_build():
    model = _model("seam", "local")
    solver = StaticSolver(Grid(16, 4), film="seam", foil_law="local")
    assert solver.key == solver_key(model, Grid(16, 4))
    assert solver.matches(model, Grid(16, 4))
    assert not solver.matches(model, Grid(16, 6))


@pytest.mark.parametrize("kwargs, name", [
    ({"grid": (72, 20)}, "grid"),           # a Grid or "72x20" is a grid; a tuple is not
    ({"grid": "72x"}, "grid"),
    ({"film": "open"}, "film"),
    ({"foil_law": "rigid"}, "foil_law"),
    ({"ipopt_options": ["ipopt.max_iter", 3]}, "ipopt_options"),
])
def test_bad_build_input_is_refused_in_one_line(kwargs, name):
    with pytest.raises(ParameterError) as info:
        StaticSolver(**kwargs)
    message = str(info.value)
    assert name in message and "\n" not in message
