"""Hardening bumps in the one-bearing transient (gfbopt.transient.hardening_recovery): the static
equilibrium is the transient's, small orbits grow at the linear analysis's rate with the
hardened tangent stiffness, and the limit cycle of a rubbing bump with hardening follows the
describing function's verdict.  Ruscitto's bearing at 30,000 rpm, 20 N, 24 × 8 (the statics'
hardened case: n = 3, W_lim = 0.8)."""
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from gfbopt.inputs import load_bearing
from gfbopt.linear import linear_threshold, linearise
from gfbopt.linear.friction_onset import settled_amplitude
from gfbopt.linear.least_stable import least_stable_mode
from gfbopt.transient.friction_orbit import friction_outcome, integrate_friction_orbits
from gfbopt.transient.orbit import integrate_orbits
from gfbopt.transient.system import transient_model
from tests.hardened_case import GRID, HARD, ROOT, solved

_solved = solved


def test_the_hardened_static_equilibrium_is_the_transients():
    # started on the static solution without a kick, a stable (M̄ = 2) and an unstable
    # (M̄ = 6 > M̄c = 3.92) rotor stay on it over 5 revolutions: the right-hand side there is
    # IPOPT's residual (4e-13), and what it seeds grows at σ ≈ 0.03/rad over 31 rad, so the
    # tolerance 1e-10 is the residual's reach with margin (measured 3.5e-14)
    sol = _solved(**HARD)
    tm = transient_model(sol)
    x0 = sol.eccentricity * math.cos(sol.attitude_angle_rad)
    y0 = sol.eccentricity * math.sin(sol.attitude_angle_rad)
    orbit = integrate_orbits(tm, [2.0, 6.0], 5.0, kick=0.0)
    assert orbit.equilibrium == pytest.approx((x0, y0), abs=1e-15)
    assert np.abs(orbit.x - x0).max() < 1e-10 and np.abs(orbit.y - y0).max() < 1e-10
    np.testing.assert_allclose(orbit.min_film[:, -1], sol.film.min(), rtol=0, atol=1e-10)


def test_small_orbits_grow_at_the_linear_rate_with_the_hardened_tangent():
    # M̄ = 1.2 M̄c (hardened tangent, M̄c = 3.916): the kicked orbit's growth rate and whirl
    # against the least-stable root of the linear analysis at that mass, within 2 % (measured
    # −1.3e-6 on σ = 0.014405, RK4); the linear bump's root at the same mass is far from it
    # (the test can fail: without hardening σ, γ differ by more than 10 %)
    sol = _solved(**HARD)
    lin = linearise(sol)
    mass = 1.2 * linear_threshold(lin).critical_mass
    root = least_stable_mode(lin, mass)
    orbit = integrate_orbits(transient_model(sol), [mass], 20.0, kick=1e-4, settle=4.0)
    assert np.nanmax(np.hypot(orbit.x - orbit.equilibrium[0],
                              orbit.y - orbit.equilibrium[1])) < 2e-3
    assert orbit.growth_rate[0] == pytest.approx(root.real, rel=0.02)
    assert orbit.whirl_ratio[0] == pytest.approx(root.imag, rel=0.02)
    bare = least_stable_mode(linearise(_solved()), mass)
    assert abs(bare.real / root.real - 1) > 0.1


@pytest.mark.slow
def test_hardened_rubbing_bump_follows_the_describing_functions_verdict():
    # the friction test's bounded case (S = 1, κ = 2, 60 N, Λ/2, μ_f = 0.05, M̄ = 8) settles
    # on a bounded orbit with the linear bump (tests/verification/test_friction_transient.py);
    # with hardening bumps (n = 3, W_lim = 0.5) the describing function finds no bounded orbit
    # inside the film and the transient (RKC, 80 revolutions) ends in contact (measured at
    # τ = 451 rad; without friction, at 314 rad; the linear bump without friction, at 229):
    # reported, not tuned (docs/PHYSICS.md §7a)
    sys.path.insert(0, str(Path(__file__).parent))
    from test_friction_transient import _bounded_case

    sol = _bounded_case(mu=0.05, hardening_exponent=3.0, hardening_limit=0.5)
    predicted = settled_amplitude(linearise(sol), 8.0, samples=12, smallest=1e-2, xtol=1e-4)
    assert not predicted.bounded
    run = integrate_friction_orbits(transient_model(sol, friction=True), [8.0], 80.0,
                                    kick=0.03, method="rkc")
    out = friction_outcome(run.orbit)
    assert out.kind == "contact", out.verdict
    assert out.min_film <= 0.02


def test_symmetric_rotor_on_hardened_bearings_is_the_one_bearing_transient():
    # the rotor transient takes a hardened bearing on its per-bearing path (the fused films
    # serve the rigid and simple laws only): a symmetric rotor (CG midway, I_p = 0) in
    # cylindrical whirl is the one-bearing engine with half the mass and load, to round-off
    # (measured 5e-15 of the clearance; 1e-12 as tests/verification/test_rotor_transient.py)
    from gfbopt.static import SolverCache
    from gfbopt.transient.rotor_films import fusable
    from gfbopt.transient.rotor_run import integrate_rotor
    from gfbopt.transient.rotor_setup import (
        RotorBearing,
        RotorInput,
        build_model,
        equilibrium_states,
        set_station_velocities,
        static_force_of,
    )
    from gfbopt.transient.rotor_system import rigid_rotor_matrices, runs

    bearing, g, speed = load_bearing(ROOT / "problems/bearings/ruscitto.toml"), 9.80665, 30_000.0
    c = bearing.radial_clearance
    options = {"film": "seam", "seam_angle_deg": 180.0, **HARD}
    m, gyro = rigid_rotor_matrices(3.2, 0.012, 0.0)
    rotor = RotorInput(m, gyro, (RotorBearing(bearing, -0.05, options, "A"),
                                 RotorBearing(bearing, 0.05, options, "B")),
                       static_force_of([(3.2 * g, 0.0, 0.0)]), ())
    model, _ = build_model(rotor, speed, GRID, cache=SolverCache(GRID))
    tm = model.bearings[0].tm
    assert tm.law.name == "hardened" and not fusable(model)
    mbar = 1.6 * c * (speed * math.pi / 30) ** 2 / (1.6 * g)
    step = {"time_step": 0.1, "stages": 6}
    one = integrate_orbits(tm, [mbar], 2.0, kick=1e-3, method="rkc", **step)
    z = set_station_velocities(model, equilibrium_states(model, 1),
                               [[1e-3 / math.sqrt(2)] * 2] * 2)
    run = integrate_rotor(model, runs(1), 4 * math.pi, z, method="rkc", **step)
    assert run.success and run.tau.shape == one.tau.shape
    for k in range(2):
        x, y = run.journal(0, k)
        assert np.max(np.abs(x / c - one.x[0])) < 1e-12
        assert np.max(np.abs(y / c - one.y[0])) < 1e-12
    assert np.max(np.abs(one.x[0] - one.x[0, 0])) > 1e-4
