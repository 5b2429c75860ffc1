"""Damped RKC2 (gfbopt.transient.rkc): coefficients, order, stability region, agreement with
RK4 and with the linear eigenvalue, contact and limit-cycle verdicts, every foil law, bad
input.  Coarse grids (36 × 10, 24 × 8): the default suite stays cheap."""
import dataclasses
import math

import numpy as np
import pytest

from gfbopt import Grid, ParameterError
from gfbopt.linear import least_stable_mode
from gfbopt.transient import (RightHandSide, equilibrium_state, integrate_orbits,
                              rkc_coefficients, rkc_stability_interval, rkc_step, stages_for,
                              stiffness_bound)
from gfbopt.transient.rkc import pack, unpack

# the same operating points as the RK4 engine's tests, so the two methods are compared on one set
from test_transient_engine import MODELS, _model  # noqa: E402  (tests/verification)


@pytest.fixture(scope="module")
def simple_case(simple_transient_case):
    return simple_transient_case        # the RK4 tests' operating point (conftest.py)


# ------------------------------------------------------------------ the method itself
@pytest.mark.parametrize("stages", [2, 3, 7, 18, 60])
def test_stability_polynomial_and_interval(stages):
    """R_s(z) (one step on y' = z y) stays within |R| ≤ 1 on [−β(s), 0]; β(s) → 0.653 s²
    (Sommeijer et al. 1998: ≈ 0.65 s² for ε = 2/13); R − e^z = O(z³) (second order)."""
    beta = rkc_stability_interval(stages)
    z = -np.linspace(0.0, beta, 2001)
    r = rkc_step(lambda y: z * y, np.ones_like(z), 1.0, stages)
    assert np.abs(r).max() <= 1.0 + 1e-9
    assert beta / stages**2 >= 0.49                   # 0.49 at s = 2, 0.64 at s = 7
    if stages >= 18:
        assert beta / stages**2 == pytest.approx(0.653, abs=0.003)
    local = [abs(rkc_step(lambda y: h * y, np.ones(1), 1.0, stages)[0] - math.exp(h))
             for h in (-0.02, -0.01)]
    assert math.log2(local[0] / local[1]) == pytest.approx(3.0, abs=0.05)


def test_stage_count_covers_the_product():
    for product in (0.5, 10.0, 157.0, 3000.0):
        s = stages_for(product)
        assert 0.9 * rkc_stability_interval(s) >= product
        assert s == 2 or 0.9 * rkc_stability_interval(s - 1) < product


def test_second_order_on_a_stiff_linear_problem():
    """y' = A y, A = a 1-D diffusion matrix (spectral radius 400) ⊕ an oscillator: with the
    stages fixed (stable for every step), the error at τ = 1 falls by 2² = 4 per halving."""
    n = 40
    lap = (np.diag(-2 * np.ones(n)) + np.diag(np.ones(n - 1), 1) + np.diag(np.ones(n - 1), -1))
    a = np.zeros((n + 2, n + 2))
    a[:n, :n] = 100 * lap
    a[n:, n:] = [[0.0, 1.0], [-1.0, 0.0]]
    y0 = np.concatenate([np.sin(np.linspace(0, math.pi, n + 2)[1:-1]), [1.0, 0.0]])
    w, v = np.linalg.eig(a)
    exact = (v @ (np.exp(w) * np.linalg.solve(v, y0))).real
    stages = stages_for(0.1 * 400)
    errors = []
    for k in (10, 20, 40):
        y = y0.copy()
        for _ in range(k):
            y = rkc_step(lambda u: a @ u, y, 1.0 / k, stages)
        errors.append(np.abs(y - exact).max())
    assert math.log2(errors[0] / errors[1]) == pytest.approx(2.0, abs=0.25)
    assert math.log2(errors[1] / errors[2]) == pytest.approx(2.0, abs=0.25)


def test_coefficients_are_consistent():
    """First-order consistency of every stage: Y_j for y' = 1 equals c_j Δτ with
    c_j increasing to c_s = 1 (the internal stages stay inside the step)."""
    for s in (2, 5, 17):
        co = rkc_coefficients(s)
        c = [0.0, co.mu_tilde[1]]
        for j in range(2, s + 1):
            c.append((co.mu[j] * c[-1] + co.nu[j] * c[-2] + co.mu_tilde[j]
                      + co.gamma_tilde[j]))
        assert c[-1] == pytest.approx(1.0, abs=1e-12)
        assert np.all(np.diff(c) > 0)


# --------------------------------------------------------------- on the real system
def test_engine_converges_at_second_order_in_time(simple_case):
    """The journal position after 0.3 revolution with steps Δ, Δ/2, Δ/4 at a fixed stage
    count (stable for all three): error ratio 4 (second order), measured 4.0 ± 0.3."""
    _, _, _, tm = simple_case
    t_end = 2 * math.pi * 0.3
    ends = []
    for k in range(3):
        orbit = integrate_orbits(tm, [3.0], revolutions=0.3, kick=0.05, method="rkc",
                                 time_step=t_end / (8 * 2**k), stages=12, sample_every=10.0)
        assert orbit.tau[-1] == pytest.approx(t_end, rel=1e-12)
        ends.append(np.array([orbit.x[0, -1], orbit.y[0, -1]]))
    ratio = np.linalg.norm(ends[0] - ends[1]) / np.linalg.norm(ends[1] - ends[2])
    assert ratio == pytest.approx(4.0, abs=0.6)


@pytest.mark.xdist_group("rk4_references")
def test_growth_rate_and_whirl_equal_rk4_and_the_linear_eigenvalue(simple_case, rk4_growth):
    """M̄ = 1.04 M̄c, same kick: RKC's σ equals RK4's to 2e-5 (step error measured 3e-6 at
    Δτ = 0.1, rkc module docstring) and the least stable eigenvalue to 1 % of σ; whirl to
    1e-3 (measured 8e-5)."""
    sol, lin, thr, tm = simple_case
    mass = 1.04 * thr.critical_mass
    ev = least_stable_mode(lin, mass, thr)
    rk4 = rk4_growth                    # the same run with method="rk4" (conftest.py)
    rkc = integrate_orbits(tm, [mass], revolutions=5, settle=1, method="rkc")
    assert rkc.time_step == pytest.approx(0.1)
    assert rkc.growth_rate[0] == pytest.approx(rk4.growth_rate[0], abs=2e-5)
    assert rkc.growth_rate[0] == pytest.approx(ev.real, rel=0.01)
    assert rkc.whirl_ratio[0] == pytest.approx(rk4.whirl_ratio[0], abs=1e-3)
    assert rkc.whirl_ratio[0] == pytest.approx(ev.imag, abs=1e-3)
    assert rkc.verdict == rk4.verdict == ("unstable",)
    assert rkc.evaluations < rk4.evaluations / 3
    assert rkc.success and rkc.message == "" and rkc.method == "rkc"


@pytest.mark.xdist_group("rk4_references")
def test_heavy_rotor_ends_in_contact_like_rk4(rk4_heavy_rotor):
    """The RK4 contact case (rigid, M̄ = 40): contact with RKC too, the orbit ends there and
    the contact time agrees with RK4's within one RKC step plus 1 % (contact is detected at
    every stage, at most one step late)."""
    tm, rk4 = rk4_heavy_rotor           # the RK4 engine test's run (conftest.py)
    rkc = integrate_orbits(tm, [40.0], revolutions=30, contact_film=0.05, method="rkc")
    assert rkc.verdict[0] == rk4.verdict[0] == "contact"
    assert rkc.contact_tau[0] == pytest.approx(rk4.contact_tau[0],
                                               abs=rkc.time_step + 0.01 * rk4.contact_tau[0])
    valid = np.isfinite(rkc.x[0])
    assert np.all(rkc.tau[valid] <= rkc.contact_tau[0])
    assert 0.0 < np.nanmin(rkc.min_film[0]) <= 0.05


def test_contact_rotor_leaves_the_batch_the_others_go_on():
    _, tm = _model("rigid")
    orbit = integrate_orbits(tm, [40.0, 1.0], revolutions=20, contact_film=0.05,
                             method="rkc")
    alone = integrate_orbits(tm, [1.0], revolutions=20, contact_film=0.05, method="rkc")
    assert orbit.verdict[0] == "contact" and orbit.verdict[1] == alone.verdict[0]
    np.testing.assert_allclose(orbit.x[1], alone.x[0], rtol=0, atol=1e-12)


@pytest.mark.xdist_group("rk4_references")
def test_large_kick_above_threshold_is_a_limit_cycle_like_rk4(simple_case, rk4_limit_cycle):
    """The RK4 limit-cycle case: same verdict, and the cycle amplitudes agree to 1 %."""
    _, _, thr, tm = simple_case
    rk4 = rk4_limit_cycle               # kick 0.25, 40 revolutions of RK4 (conftest.py)
    state = equilibrium_state(tm, 1)
    state.x[:] += 0.25
    rkc = integrate_orbits(tm, [1.03 * thr.critical_mass], method="rkc", revolutions=40,
                           initial=state)
    assert rkc.verdict[0] == rk4.verdict[0] == "limit cycle"
    assert rkc.amplitude[0] == pytest.approx(rk4.amplitude[0], rel=0.01)


# ------------------------------------------------------------------- every foil law
@pytest.mark.parametrize("name", list(MODELS))
def test_every_foil_law_gives_the_rk4_orbit(name):
    """All laws the RK4 path supports run with RKC: over 2 revolutions (kick 0.01) the
    orbits agree to 0.3 % of their size (RKC's step error at Δτ = 0.1: measured 0.07–0.18 %
    over the six laws, falling as Δτ²).  The RK4 reference at Δτ = 0.02, sampled every step:
    it differs from RK4 at Δτ = 0.005 by ≤ 4e-9 of the orbit size for every law (measured;
    interpolating its samples included), so the gap is RKC's alone, and costs a quarter of
    the 0.005 run."""
    _, tm = _model(name, grid=Grid(24, 8))
    rk4 = integrate_orbits(tm, [3.0], revolutions=2, kick=0.01, sample_every=1e-3,
                           time_step=0.02)
    rkc = integrate_orbits(tm, [3.0], revolutions=2, kick=0.01, method="rkc")
    assert rkc.success, rkc.message
    inside = rkc.tau <= rk4.tau[-1]
    size = max(np.ptp(rk4.x[0]), np.ptp(rk4.y[0]))
    for a, b in ((rk4.x, rkc.x), (rk4.y, rkc.y)):
        gap = np.abs(np.interp(rkc.tau[inside], rk4.tau, a[0]) - b[0, inside]).max()
        assert gap < 3e-3 * size


def test_beam_cache_stays_valid_across_rkc_stages():
    """The beam recovery carries chord-iteration data between evaluations; at the stage
    states of an RKC step the right-hand side with the carried cache equals a fresh one to
    1e-11 (both converge the film to 1e-13)."""
    _, tm = _model("beam_periodic", grid=Grid(24, 8))
    state = equilibrium_state(tm, 2)
    state.u[:] = [0.02, -0.01]
    carried = RightHandSide(tm, np.array([3.0, 5.0]))
    seen = []

    def f(z):
        seen.append(z.copy())
        return pack(carried(unpack(z, tm.shape)))

    rkc_step(f, pack(state), 0.1, 9)
    assert len(seen) == 9
    for z in seen:
        fresh = pack(RightHandSide(tm, np.array([3.0, 5.0]))(unpack(z, tm.shape)))
        again = pack(carried(unpack(z, tm.shape)))
        np.testing.assert_allclose(again, fresh, rtol=0, atol=1e-11)


def test_a_law_without_rkc_is_refused():
    _, tm = _model("rigid", grid=Grid(24, 8))
    law = type(tm.law)()
    law.engines = ("static", "linear", "rk4")
    with pytest.raises(ParameterError, match=r"^method = 'rkc': does not support the rigid "
                                             r"foil law"):
        integrate_orbits(dataclasses.replace(tm, law=law), [2.0], method="rkc")


# ------------------------------------------------------------------------- bad input
def test_step_or_stages_outside_the_stability_region_are_refused():
    _, tm = _model("rigid")
    rho = stiffness_bound(equilibrium_state(tm, 1), tm)
    with pytest.raises(ParameterError, match=r"^time_step = 0.5: Δτ·ρ = 0.5 × .* exceeds "
                                             r"the RKC stability interval β\(2\) = 1.963"):
        integrate_orbits(tm, [2.0], method="rkc", time_step=0.5, stages=2)
    limit = rkc_stability_interval(3) / rho
    with pytest.raises(ParameterError, match=r"^time_step = .*β\(3\)"):
        integrate_orbits(tm, [2.0], method="rkc", time_step=1.01 * limit, stages=3)
    ok = integrate_orbits(tm, [2.0], revolutions=0.2, method="rkc", time_step=0.99 * limit,
                          stages=3)
    assert ok.success
    # a stage count alone: the automatic step shrinks into its stability interval
    auto = integrate_orbits(tm, [2.0], revolutions=0.2, method="rkc", stages=2)
    assert auto.time_step * rho <= rkc_stability_interval(2)
    with pytest.raises(ParameterError, match=r"^time_step = 1000000.0: .*at most 250 stages"):
        integrate_orbits(tm, [2.0], method="rkc", time_step=1e6)


def test_bound_violated_during_the_run_is_reported_not_raised():
    """Step and stages both given, just inside the region at the equilibrium: as the orbit
    grows the bound is exceeded; the run stops with success False and the bound stated."""
    _, tm = _model("rigid", grid=Grid(24, 8))
    state = equilibrium_state(tm, 1)
    limit = rkc_stability_interval(3) / stiffness_bound(state, tm)
    state.x[:] -= 0.3
    orbit = integrate_orbits(tm, [2.0], revolutions=2, method="rkc", initial=state,
                             time_step=0.999 * limit, stages=3, check_every=1)
    assert not orbit.success and orbit.revolutions < 2
    assert "exceeds the RKC stability interval β(3)" in orbit.message
    assert "reached at τ" in orbit.message


@pytest.mark.parametrize("kwargs, match", [
    (dict(method="rkc", stages=1), r"^stages = 1: must be an integer in \[2, 250\]"),
    (dict(method="rkc", stages=2.5), r"^stages = 2.5: must be an integer >= 2"),
    (dict(method="rkc", time_step=-1.0), r"^time_step = -1.0: must be finite and > 0"),
    (dict(method="rk4", stages=4), r"^stages = 4: applies to method=rkc only"),
    (dict(method="bdf", time_step=0.1), r"^time_step = 0.1: applies to method=rk4/rkc only"),
    (dict(method="euler"), r"^method = 'euler': must be one of rk4, rkc, bdf"),
])
def test_bad_rkc_options(kwargs, match):
    _, tm = _model("rigid", grid=Grid(24, 8))
    with pytest.raises(ParameterError, match=match):
        integrate_orbits(tm, [2.0], revolutions=0.1, **kwargs)


def test_progress_fractions_are_monotone_in_unit_interval():
    _, tm = _model("rigid", grid=Grid(24, 8))
    seen = []
    integrate_orbits(tm, [2.0], revolutions=1, method="rkc", progress=seen.append)
    assert seen and seen[-1] == 1.0 and min(seen) >= 0.0
    assert all(b >= a for a, b in zip(seen, seen[1:]))


# ------------------------------------------------------------------------------- CLI
def _cli(capsys, *args):
    from gfbopt.cli import main

    code = main(list(args))
    out = capsys.readouterr()
    return code, out.out, out.err


OP = ["--eccentricity", "0.4", "--bearing-number", "2", "--compliance", "1", "--grid", "24x8"]


@pytest.mark.parametrize("args, message", [
    (["orbit", *OP, "--mass", "2", "--method", "rk4", "--stages", "3"],
     "--stages = 3.0: applies to --method rkc only, not to --method rk4"),
    (["orbit", *OP, "--mass", "2", "--method", "bdf", "--time-step", "0.1"],
     "--time-step = 0.1: applies to --method rk4/rkc only, not to --method bdf"),
    (["orbit", *OP, "--mass", "2", "--stages", "1"], "--stages = 1.0: must be an integer in [2, 1000]"),
    (["orbit", *OP, "--mass", "2", "--time-step", "0.5", "--stages", "2"],
     "exceeds the RKC stability interval β(2)"),
    (["orbit", *OP, "--mass", "2", "--method", "rk4", "--time-step", "0.5"],
     "exceeds the RK4 stability limit"),
    (["critical-mass", *OP, "--start", "mode", "--no-linear-start"],
     "--start = 'mode': needs the linear threshold"),
])
def test_cli_refuses_options_with_a_reason(capsys, args, message):
    code, out, err = _cli(capsys, *args)
    assert code == 2 and message in err and out == ""


def test_cli_defaults_to_rkc_and_keeps_stdout_json(capsys):
    """stdout is one JSON object; off a terminal stderr has one status line per command
    (gfbopt.progress), nothing else."""
    import json

    code, out, err = _cli(capsys, "orbit", *OP, "--mass", "2.5", "--revolutions", "2",
                          "--json")
    data = json.loads(out)
    assert code == 0 and err.startswith("gfbopt: orbit 100 %,") and err.count("\n") == 1
    assert data["method"] == "rkc" and data["success"]
    code, out, err = _cli(capsys, "critical-mass", *OP, "--json")
    data = json.loads(out)
    assert code == 0 and err.startswith("gfbopt: critical mass") and err.count("\n") == 1
    assert data["method"] == "rkc" and data["start"] == "linear mode"
    assert data["transients"] == 2 and data["rounds"] == 1
    assert data["critical_mass"] == pytest.approx(data["linear_critical_mass"], rel=0.005)
