"""A ramp's speed-following step caps Δτ at T_rotor/30 with the rotor's period at the current
state (gfbopt.transient.rotor_run._SpeedStep), not the start's: after a refresh its cap is
2π/(30 × the fastest frequency there), and a state where the films are softer (the damped
foil deflected further, a thicker film: as the run-up's films soften from the stiff start)
lengthens it."""
import math

import numpy as np
import pytest

from gfbopt.inputs import Grid, load_bearing
from gfbopt.static import SolverCache
from gfbopt.transient.rkc import STEPS_PER_ROTOR_PERIOD
from gfbopt.transient.rotor_run import _SpeedStep, rotor_frequency
from gfbopt.transient.rotor_setup import (RotorBearing, RotorInput, build_model,
                                          equilibrium_states, static_force_of)
from gfbopt.transient.rotor_system import (RotorRightHandSide, layout, rigid_rotor_matrices,
                                           runs)

BEARING = load_bearing("problems/bearings/ruscitto.toml")
GRID = Grid.parse("24x8")


def test_the_rotor_period_cap_follows_the_current_state():
    m, g = rigid_rotor_matrices(3.2, 0.012, 0.002)
    opts = {"film": "seam", "seam_angle_deg": 180.0, "loss_factor": 0.3}
    bearings = (RotorBearing(BEARING, -0.08, opts, "A"), RotorBearing(BEARING, 0.02, opts, "B"))
    rotor = RotorInput(m, g, bearings, static_force_of([(3.2 * 9.80665, 0.0, 0.0)]), ())
    model = build_model(rotor, 30_000.0, GRID, cache=SolverCache(GRID))[0]
    batch = runs(1, speed=0.2, ramp=0.01)
    rhs = RotorRightHandSide(model, batch)
    z0 = equilibrium_states(model, 1)
    step = _SpeedStep(rhs, z0, 0.2)
    start = step.cap
    assert start == pytest.approx(min(step.film_cap, 2 * math.pi / rotor_frequency(rhs, z0)
                                      / STEPS_PER_ROTOR_PERIOD), rel=1e-12)
    z1 = z0.copy()
    for k in range(2):
        layout(model).foil_of(z1, k)[...] += 0.2
    fastest = rotor_frequency(rhs, z1)
    step.refresh(rhs, z1)
    assert step.cap == pytest.approx(2 * math.pi / fastest / STEPS_PER_ROTOR_PERIOD, rel=1e-12)
    assert step.cap > 1.1 * start            # the start's period would have held it shorter
    # the step is the speed's or the cap, whichever is shorter
    speed_step = 0.2 / float(np.max(batch.speed_at(0.2 / 0.2)))
    assert step(0.0, batch) == pytest.approx(min(speed_step, step.cap), rel=1e-12)
