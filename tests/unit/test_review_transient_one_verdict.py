"""One orbit, one verdict: a rotor whose bumps rub states its limit cycle once.

Before, blower_friction at 13,500 rpm (24 × 8, 120 revolutions, the file's imbalance) carried
two amplitudes and two settled tests per bearing: limit_cycle_* (largest distance over 10
whirl periods, within 1 %) said bearing B was *decaying* by 3.1 % while friction_orbit_* (the
first harmonic over 6 periods, within 1e-3) said it was *growing* by 0.17 %.  Now the
limit_cycle_* fields carry the sliders' measure (limit_cycle_measure 'first harmonic'), and
status and friction_orbit_kind are the same verdict.

The numbers are the run's own (rkc, deterministic); the tolerances allow another BLAS's
round-off, not a change of the measure (the two measures differ by 0.1–2 % here)."""
from __future__ import annotations

from pathlib import Path

import pytest

from gfbopt.glossary import GLOSSARY
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.transient import rotor_friction, spectra
from gfbopt.transient.rotor_analysis import rotor_orbit

ROTORS = Path(__file__).resolve().parents[2] / "problems" / "rotors"


@pytest.fixture(scope="module")
def rubbing_orbit():
    system = load_rotor(ROTORS / "blower_friction.toml")
    return rotor_orbit(system, 13500.0, 120, grid=Grid(24, 8))


def test_the_limit_cycle_and_the_friction_outcome_are_one_measure(rubbing_orbit):
    rubbing_orbit = rubbing_orbit.to_dict()
    assert rubbing_orbit["success"] and not rubbing_orbit["contact"]
    for b in rubbing_orbit["bearings"]:
        # one verdict: the direction the sliders' outcome states (B was 'decaying' vs
        # 'growing' before)
        growing = b["friction_orbit_verdict"].startswith("end of run, growing")
        assert b["limit_cycle_status"] == ("growing" if growing else "decaying")
        assert b["limit_cycle_amplitude_um"] == b["friction_orbit_amplitude_um"]
        assert b["limit_cycle_measure"] == "first harmonic"
        assert b["limit_cycle_previous_amplitude_um"] == b["friction_orbit_previous_amplitude_um"]
        assert abs(b["limit_cycle_frequency_hz"]) == b["friction_orbit_whirl_frequency_hz"]
        assert b["limit_cycle_tolerance"] == rotor_friction.TOLERANCE
        # one verdict: settled exactly where the sliders' outcome is a settled limit cycle
        assert b["limit_cycle_settled"] == (b["friction_orbit_kind"] == "settled limit cycle")
        direction = "growing" if b["limit_cycle_change"] > 0 else "decaying"
        assert b["limit_cycle_status"] == direction
        assert b["friction_orbit_verdict"].startswith(f"end of run, {direction}")
        # the window is 6 whirl periods of the measured frequency
        assert b["limit_cycle_window_s"] == pytest.approx(
            rotor_friction.PERIODS / b["friction_orbit_whirl_frequency_hz"], rel=1e-12)
    a, b = rubbing_orbit["bearings"]
    # bearing B grows by 0.17 % (it was reported decaying by 3.1 % before); A decays 0.23 %
    assert b["limit_cycle_status"] == "growing"
    assert b["limit_cycle_change"] == pytest.approx(1.658e-3, rel=0.01)
    assert b["limit_cycle_amplitude_um"] == pytest.approx(13.303, rel=1e-3)
    assert a["limit_cycle_status"] == "decaying"
    assert a["limit_cycle_change"] == pytest.approx(-2.312e-3, rel=0.01)
    assert a["limit_cycle_amplitude_um"] == pytest.approx(4.8267, rel=1e-3)
    assert "limit_cycle_measure" in GLOSSARY


def test_the_text_states_each_bearing_s_verdict_once(rubbing_orbit, capsys):
    from gfbopt.cli.rotor_time import _emit

    _emit(rubbing_orbit.to_dict(), False, {}, rubbing_orbit)
    text = capsys.readouterr().out
    assert text.count("whirl 13.3 µm") + text.count(": 13.3 µm at") == 1
    assert "bearing B with friction: end of run, growing: 13.3 µm at 112.5 Hz" in text
    assert "bearing A with friction: end of run, decaying: 4.83 µm at 112.5 Hz" in text
    assert "decaying: -3.1 %" not in text and "whirl 4.86" not in text


def test_a_rotor_without_friction_keeps_the_largest_distance():
    d = rotor_orbit(load_rotor(ROTORS / "blower.toml"), 13500.0, 30,
                    grid=Grid(24, 8)).to_dict()
    for b in d["bearings"]:
        assert b["limit_cycle_measure"] == "largest distance"
        assert b["limit_cycle_tolerance"] == 0.01
        assert "friction_orbit_kind" not in b


def test_no_spectral_whirl_is_no_whirl_in_both_forms():
    none = spectra.LimitCycle("none", "no subsynchronous whirl: below the threshold",
                              *[float("nan")] * 4, None, float("nan"), 0.01, 0.4, 0.09)
    entry = {"bearing": "A", "amplitude_um": 0.01, "previous_amplitude_um": 0.01,
             "whirl_frequency_hz": 100.0, "whirl_ratio": 0.5, "kind": "settled limit cycle",
             "verdict": "settled limit cycle of 0.01 µm"}
    lc, out = rotor_friction.limit_cycle_of(entry, none)
    assert lc.status == "none" and lc.measure == "first harmonic"
    assert out["kind"] == "end of run"
    assert out["verdict"] == "end of run: no subsynchronous whirl: below the threshold"
    # contact (no spectral limit cycle computed): the outcome stands alone
    assert rotor_friction.limit_cycle_of(entry, None) == (None, entry)
