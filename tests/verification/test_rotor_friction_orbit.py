"""The rotor's settled whirl above its small-motion onset when its bumps rub
(gfbopt.rotor.friction_onset) against the one-bearing describing function it generalises.

Planted case (the bounded one-bearing case of tests/unit/test_bump_friction_linear.py): the
Ruscitto bearing with bump compliance S = 3 (bump thickness solved for it), μ_f = 0.5, κ = 2,
20 N per bearing, 15,000 rpm, 36 × 10.  A symmetric rotor (bearings at ±50 mm, no weight, a
40 N side load at its centre of gravity, no gyroscopics) whose cylindrical mode carries half
its mass on each bearing, M̄ = (m/2) c ω²/W0, is the one-bearing problem exactly (as in
test_rotor_two_bearings' symmetric onsets), so its settled orbit at each bearing must be the
one-bearing settled amplitude: both searches bisect to 1e-4 relative on the same log grid of
film shares, the tolerance asserted (measured agreement 1e-9)."""
import math
from dataclasses import replace
from pathlib import Path

import pytest
from scipy.optimize import brentq

from gfbopt.errors import ParameterError
from gfbopt.inputs import Grid
from gfbopt.inputs.bearing_file import load_bearing
from gfbopt.inputs.rotor_system import rotor_from_dict
from gfbopt.linear.friction_onset import settled_amplitude
from gfbopt.rotor.friction_onset import MODEL, settled_whirl
from gfbopt.rotor.supports import resolve_rotor, support_states
from gfbopt.rotor.system import without_gyroscopics

ROOT = Path(__file__).resolve().parents[2]
FRICTION = str(ROOT / "problems" / "bearings" / "ruscitto_friction.toml")
PLAIN = str(ROOT / "problems" / "bearings" / "ruscitto.toml")
GRID = Grid(36, 10)
SPEED = 15000.0
LOAD = 20.0
CLEARANCE = 20e-6


def _rotor(mass_parameter: float, file: str = FRICTION):
    """The symmetric rotor whose bearings carry M̄ = mass_parameter each."""
    geometry = load_bearing(file)
    thickness = brentq(lambda t: replace(geometry, bump_thickness=t).compliance - 3.0,
                       40e-6, 101.6e-6, xtol=1e-16)
    omega = SPEED * math.pi / 30.0
    half = mass_parameter * LOAD / (CLEARANCE * omega**2)
    system = rotor_from_dict({
        "rotor": {"mass": 2 * half, "transverse_inertia": 0.004, "polar_inertia": 0.001,
                  "gravity": 0.0},
        "side_loads": [{"force": 2 * LOAD, "direction_deg": 0.0, "position": 0.0}],
        "bearings": [{"file": file, "position": -0.05}, {"file": file, "position": 0.05}]})
    system = replace(without_gyroscopics(system), bearings=tuple(
        replace(b, geometry=replace(b.geometry, bump_thickness=thickness))
        for b in system.bearings))
    rotor = resolve_rotor(system, GRID)
    return rotor, support_states(rotor, SPEED)


@pytest.fixture(scope="module")
def planted():
    return _rotor(4.145)


def test_symmetric_rotor_settles_on_the_one_bearing_orbit(planted):
    rotor, states = planted
    lin = states.states[0].linearisation
    assert lin.static.model.compliance == pytest.approx(3.0, rel=1e-12)
    one = settled_amplitude(lin, 4.145, samples=10, smallest=1e-2, xtol=1e-4)
    assert one.bounded and 0.065 < one.amplitude < 0.11           # the one-bearing case's bracket
    orbit = settled_whirl(rotor, SPEED, states=states)
    assert orbit.bounded and orbit.converged and orbit.label == "forward cylindrical"
    assert orbit.small_motion_inertia_scale == pytest.approx(one.small_motion_mass / 4.145,
                                                             rel=1e-8)
    for amp in orbit.amplitude_um:
        assert amp == pytest.approx(one.amplitude * CLEARANCE * 1e6, rel=1e-4)
    assert orbit.whirl_ratio == pytest.approx(one.whirl_ratio, rel=1e-6)
    omega_hz = SPEED / 60.0
    assert orbit.whirl_frequency_hz == pytest.approx(one.whirl_ratio * omega_hz, rel=1e-6)
    h = float(lin.static.min_film)
    assert orbit.min_film_um == pytest.approx((h - one.amplitude) * CLEARANCE * 1e6, rel=1e-4)
    assert orbit.inertia_scale >= 1.0 and orbit.model == MODEL
    assert orbit.verdict.startswith("bounded whirl of 1.59, 1.59 µm (bearings A, B) at 124.9 "
                                    "Hz, minimum film 15.3 µm")


def test_no_bounded_orbit_and_stable_verdicts(planted):
    """M̄ = 4.3: above every M̄c(A) of this bearing (it rises by 0.15 % only: 4.1429 to
    4.1488), so no bounded orbit; M̄ = 4.10 is below the stuck onset: stable."""
    rotor, states = _rotor(4.3)
    out = settled_whirl(rotor, SPEED, states=states, samples=4)
    assert not out.bounded and out.verdict == "no bounded orbit inside the film"
    assert all(math.isnan(a) for a in out.amplitude_um)
    rotor, states = _rotor(4.10)
    out = settled_whirl(rotor, SPEED, states=states)
    assert out.bounded and out.amplitude_um == (0.0, 0.0)
    assert out.verdict.startswith("stable for small orbits")


def test_refuses_a_rotor_without_friction():
    rotor, states = _rotor(4.145, PLAIN)
    with pytest.raises(ParameterError, match="friction_coefficient"):
        settled_whirl(rotor, SPEED, states=states)


def test_blower_with_rubbing_bumps_at_its_top_speed():
    """problems/rotors/blower_friction.toml at 60,000 rpm: far above its stuck onset
    (forward conical μ_c = 0.0473 at 36 × 10) and the friction's damping does not restore
    it inside the film (μ_c falls to 0.0458 with the orbit filling the film): no bounded
    orbit."""
    from gfbopt.inputs.rotor_system import load_rotor
    from gfbopt.rotor.matched_whirl import crossings

    rotor = resolve_rotor(load_rotor(ROOT / "problems" / "rotors" / "blower_friction.toml"),
                          GRID)
    states = support_states(rotor, 60000.0)
    first = crossings(rotor, states)[0]
    out = settled_whirl(rotor, 60000.0, states=states, samples=4)
    assert out.small_motion_inertia_scale == first.inertia_scale
    assert out.label == first.label == "forward conical"
    assert out.small_motion_inertia_scale == pytest.approx(0.0473, abs=5e-4)
    assert not out.bounded and out.verdict == "no bounded orbit inside the film"
    assert out.inertia_scale < 1.0
