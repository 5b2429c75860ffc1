"""Reference transients shared by test_transient_engine (RK4's own verdicts and rates) and
test_rkc (RKC against RK4).  Both modules ran the same three RK4 orbits on the same operating
point (the simple law at ε = 0.4 on 36 × 10: a 40-revolution limit cycle, the 1.04 M̄c growth
run and the M̄ = 40 rigid contact run), about 16 s of the default tier twice over; here each
is made once per session.  The tests that use them carry
``@pytest.mark.xdist_group("rk4_references")`` so that pytest-xdist (``--dist loadgroup``)
runs them on one worker and each orbit is still made once.  The orbits are read, never
changed, by the tests."""
import pytest

from gfbopt import solve_static, solver_for
from gfbopt.linear import linear_threshold, linearise
from gfbopt.transient import equilibrium_state, integrate_orbits, transient_model

from test_transient_engine import GRID, MODELS, _model


@pytest.fixture(scope="session")
def simple_transient_case():
    """(static solution, linearisation, linear threshold, transient model) of the simple law,
    B = 2, S = 1, ε = 0.4 on 36 × 10."""
    model = MODELS["simple"]
    solver = solver_for(model, GRID)
    sol = solve_static(model, eccentricity=0.4, solver=solver)
    lin = linearise(sol, solver)
    return sol, lin, linear_threshold(lin), transient_model(sol)


@pytest.fixture(scope="session")
def rk4_limit_cycle(simple_transient_case):
    """RK4, M̄ = 1.03 M̄c, kicked 0.25 off the equilibrium, 40 revolutions."""
    _, _, thr, tm = simple_transient_case
    state = equilibrium_state(tm, 1)
    state.x[:] += 0.25
    return integrate_orbits(tm, [1.03 * thr.critical_mass], revolutions=40, initial=state)


@pytest.fixture(scope="session")
def rk4_growth(simple_transient_case):
    """RK4, M̄ = 1.04 M̄c, the default small kick, 5 revolutions (rate fitted after 1)."""
    _, _, thr, tm = simple_transient_case
    return integrate_orbits(tm, [1.04 * thr.critical_mass], revolutions=5, settle=1)


@pytest.fixture(scope="session")
def rk4_heavy_rotor():
    """(transient model, RK4 orbit) of the rigid bearing with M̄ = 40: contact (film 0.05)."""
    _, tm = _model("rigid")
    return tm, integrate_orbits(tm, [40.0], revolutions=30, contact_film=0.05)
