"""The rotor transient (gfbopt.transient.rotor_*) against the one-bearing engine and the
linear analysis.

* Symmetric rotor (CG midway, I_p = 0), cylindrical motion: both journals see the same film
  and the tilt stays exactly zero, so the rotor transient is the one-bearing engine with half
  the mass and half the load — operation for operation but for the order of the rotor
  sums; the orbits agree to round-off (1e-12 of the clearance; measured ≲ 1e-15).
* Just above / below each mode's linear threshold the growth rate and whirl of the
  transient are the linear characteristic root's (gfbopt.linear).
* Small imbalance below the onset: the settled 1× response at both bearings is the linear
  synchronous response from the bearings' impedances at γ = 1.
"""
import math

import numpy as np
import pytest

from gfbopt.inputs import Grid, load_bearing
from gfbopt.linear import characteristic_root, impedance, linear_threshold, linearise
from gfbopt.static import SolverCache
from gfbopt.transient import fit_growth_rate, integrate_orbits
from gfbopt.transient.rotor_run import integrate_rotor
from gfbopt.transient.rotor_setup import (RotorBearing, RotorInput, build_model,
                                          equilibrium_states, imbalance_planes,
                                          set_station_velocities, static_force_of)
from gfbopt.transient.rotor_system import rigid_rotor_matrices, runs
from gfbopt.transient.spectra import synchronous_fit

BEARING = load_bearing("problems/bearings/ruscitto.toml")
OPTIONS = {"film": "seam", "seam_angle": math.pi}
GRID = Grid.parse("36x10")
G = 9.80665


def symmetric_rotor(mass=3.2, inertia=0.012, polar=0.0, half_span=0.05, imbalance=()):
    m, g = rigid_rotor_matrices(mass, inertia, polar)
    bearings = (RotorBearing(BEARING, -half_span, OPTIONS, "A"),
                RotorBearing(BEARING, half_span, OPTIONS, "B"))
    return RotorInput(m, g, bearings, static_force_of([(mass * G, 0.0, 0.0)]), imbalance)


@pytest.fixture(scope="module")
def cache():
    return SolverCache(GRID)


@pytest.mark.parametrize("method", ["rkc", "rk4"])
def test_symmetric_rotor_is_the_one_bearing_engine_in_cylindrical_whirl(method, cache):
    speed = 30_000.0
    rotor = symmetric_rotor()
    model, sols = build_model(rotor, speed, GRID, cache=cache)
    tm = model.bearings[0].tm
    assert sols[0].load == sols[1].load
    omega = speed * math.pi / 30
    mbar = (3.2 / 2) * BEARING.radial_clearance * omega ** 2 / (3.2 * G / 2)
    step = {"rkc": {"time_step": 0.1, "stages": 6}, "rk4": {"time_step": 0.01}}[method]
    revs = 4.0 if method == "rkc" else 1.5
    one = integrate_orbits(tm, [mbar], revs, kick=1e-3, method=method, **step)
    z = equilibrium_states(model, 1)
    v = 1e-3 / math.sqrt(2)
    z = set_station_velocities(model, z, [[v, v], [v, v]])
    run = integrate_rotor(model, runs(1), 2 * math.pi * revs, z, method=method, **step)
    assert run.success and one.success
    assert run.tau.shape == one.tau.shape
    np.testing.assert_array_equal(run.tau, one.tau)
    c = BEARING.radial_clearance
    for k in range(2):
        x, y = run.journal(0, k)
        # round-off: the rotor's sums (2 p_a R² F + m g)/(m c ω²) against the one-bearing
        # (F + W̄0)/(M̄ W̄0) differ in the last bits only; 1e-12 c leaves 1000× margin
        assert np.max(np.abs(x / c - one.x[0])) < 1e-12
        assert np.max(np.abs(y / c - one.y[0])) < 1e-12
    # the tilt stays at round-off (the equilibrium's 4 × 4 solve leaves ~1e-22 rad)
    assert np.max(np.abs(run.q[0, :, 2:])) * 0.05 / c < 1e-13
    assert np.max(np.abs(one.x[0] - one.x[0, 0])) > 1e-4   # and the orbit moved
