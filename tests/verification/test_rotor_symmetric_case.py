"""The one-bearing answers are the rotor system's symmetric case: a symmetric rigid
rotor (CG midway, z_A = −z_B = −a) on identical bearings decouples exactly — K_b = Σ T_kᵀ Z T_k
has no translation–tilt terms (z_A Z + z_B Z = 0) and G acts on the tilts alone — so its
cylindrical block −Ω² μ m + 2 Z = 0 is one bearing carrying half the mass,
−Ω² μ (m/2) + Z = 0, at the same load m g/2, and (I_p = 0) its conical block is one bearing
carrying I_t/(2a²).

* stability(): at a fixed speed the rotor's forward cylindrical μ_c is the one-bearing
  M̄c/M̄ and its whirl ratio the one-bearing threshold's: both routes solve the same static
  equilibrium and refine the whirl ratio by Brent to 1e-10 on Krylov impedances converged to
  1e-11, so they agree to 1e-9 (measured 4e-11);
* onset_speed(): the same root of the same function g = ln μ_c(N) = ln(M̄c/M̄); the one-bearing
  secant returns its converged next point, the rotor's mode search the last speed it
  evaluated, whose error is at most its stop test's next step, SECANT_TOLERANCE = 1e-6 on
  ln N: tolerance 1e-6 relative (measured 1.7e-7 cylindrical, 4.9e-7 conical)."""
from pathlib import Path

import pytest

from gfbopt.inputs import Grid
from gfbopt.inputs.rotor import OperatingPoint
from gfbopt.inputs.rotor_system import rotor_from_dict
from gfbopt.rotor import Rotor, onset_speed, stability
from gfbopt.rotor.mode_search import SECANT_TOLERANCE
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine, rotor_onsets, without_gyroscopics

BEARING = str(Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto.toml")
GRID = Grid(36, 10)
A, MASS, IT = 0.05, 3.2, 0.012
LOAD = MASS * 9.80665 / 2
SPAN = (8000.0, 20000.0)


@pytest.fixture(scope="module")
def symmetric():
    return rotor_from_dict({
        "rotor": {"mass": MASS, "transverse_inertia": IT, "polar_inertia": 0.002},
        "bearings": [{"file": BEARING, "position": -A}, {"file": BEARING, "position": A}]})


@pytest.mark.parametrize("speed", [10000.0, 14000.0])
def test_stability_is_the_cylindrical_mode_of_the_symmetric_rotor(symmetric, speed):
    line = SpeedLine(resolve_rotor(symmetric, GRID), local=False)
    cyl = [c for c in line.crossings(speed) if c.label == "forward cylindrical"]
    assert len(cyl) == 1
    b = symmetric.bearings[0]
    one = stability(b.geometry, Rotor(MASS / 2), OperatingPoint(speed, LOAD), options=b.options,
                    grid=GRID)
    assert cyl[0].inertia_scale == pytest.approx(
        one.critical_mass_parameter / one.mass_parameter, rel=1e-9)
    assert cyl[0].whirl_ratio == pytest.approx(one.threshold_whirl_ratio, rel=1e-9)
    assert (cyl[0].inertia_scale > 1) == one.stable


def test_onset_speed_is_the_symmetric_rotors_onset(symmetric):
    b = symmetric.bearings[0]
    two = rotor_onsets(symmetric, SPAN, grid=GRID, show_progress=False)
    cyl = onset_speed(b.geometry, Rotor(MASS / 2), LOAD, SPAN, options=b.options, grid=GRID)
    assert two.mode("forward cylindrical").onset_speed_rpm == pytest.approx(
        cyl.onset_speed_rpm, rel=SECANT_TOLERANCE)
    flat = rotor_onsets(without_gyroscopics(symmetric), SPAN, grid=GRID, show_progress=False)
    con = onset_speed(b.geometry, Rotor(IT / (2 * A**2)), LOAD, SPAN, options=b.options,
                      grid=GRID)
    assert flat.mode("forward conical").onset_speed_rpm == pytest.approx(
        con.onset_speed_rpm, rel=SECANT_TOLERANCE)
    assert flat.mode("forward conical").whirl_ratio == pytest.approx(con.whirl_ratio,
                                                                       rel=1e-6)


def test_the_onset_is_the_same_root_to_1e_9(symmetric):
    """The two searches stop differently (above: within SECANT_TOLERANCE), but they seek the
    same root of the same function: ln μ_c(N) of the rotor's forward cylindrical mode and
    ln(M̄c/M̄) of one bearing carrying half the mass, each solved by Brent to 1e-12 relative in
    N inside the one-bearing search's bracket, agree to 1e-9 (the function agrees to 1e-9
    at every speed, test above; so its root does where the slope is O(1) in ln N). Measured:
    12,915.137814 rpm both, 1.4e-11 apart (blower-like rotor on Ruscitto bearings, 36x10)."""
    import math

    from scipy.optimize import brentq

    b = symmetric.bearings[0]
    line = SpeedLine(resolve_rotor(symmetric, GRID), local=False)

    def rotor_g(speed):
        cyl = [c for c in line.crossings(speed) if c.label == "forward cylindrical"]
        return math.log(cyl[0].inertia_scale)

    def one_g(speed):
        one = stability(b.geometry, Rotor(MASS / 2), OperatingPoint(speed, LOAD),
                        options=b.options, grid=GRID)
        return math.log(one.critical_mass_parameter / one.mass_parameter)

    guess = onset_speed(b.geometry, Rotor(MASS / 2), LOAD, SPAN, options=b.options,
                        grid=GRID).onset_speed_rpm
    low, high = guess * (1 - 2e-3), guess * (1 + 2e-3)
    roots = [brentq(g, low, high, xtol=1e-12 * guess, rtol=1e-14) for g in (rotor_g, one_g)]
    assert roots[0] == pytest.approx(roots[1], rel=1e-9)
    assert roots[0] == pytest.approx(guess, rel=SECANT_TOLERANCE)
