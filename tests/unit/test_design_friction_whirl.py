"""A rotor design whose bearings carry the bumps' Coulomb friction takes its top-speed whirl
from the same rotor transient as a rotor without friction, the sliders integrated with the
rotor (gfbopt/transient/rotor_friction.py): the whirl stage's keys, the model named, the
describing function's prediction kept beside it, and the verdict's words
(design.robustness.whirl_at_top_speed, studies.rotor_report.whirl_text).  A rotor without
friction gets exactly the orbit's own figures.

The numbers are this grid's own (deterministic runs: rkc at Δτ = 0.1, cylindrical kick 1e-3,
the rotor file's imbalance); the tolerances allow round-off of a different BLAS and thread
count, nothing more — a change of the physics or of the step moves them by more (halving the
step at 72 × 20 moves the settled amplitudes by 0.2–0.5 %, results/rotor_friction_transient)."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from gfbopt.design.robustness import FRICTION_MODEL, whirl_at_top_speed
from gfbopt.design.rotor_objectives import EvaluationSettings
from gfbopt.glossary import GLOSSARY
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.friction_onset import MODEL
from gfbopt.studies.rotor_report import whirl_text
from gfbopt.transient.rotor_analysis import rotor_orbit
from gfbopt.transient.rotor_friction import MODEL_WORDS

ROOT = Path(__file__).resolve().parents[2]
ROTORS = ROOT / "problems" / "rotors"
#: the keys of a bearing's entry without friction, and those friction adds
PLAIN = {"bearing", "min_film_um", "limit_cycle_status", "limit_cycle_amplitude_um",
         "limit_cycle_settled", "limit_cycle_frequency_hz"}
RUBBING = {"friction_orbit_kind", "friction_orbit_amplitude_um",
           "friction_orbit_whirl_frequency_hz", "friction_orbit_verdict",
           "settled_orbit_um", "settled_whirl_hz", "settled_min_film_um"}


def _settings(top_rpm: float, grid: str) -> EvaluationSettings:
    return EvaluationSettings(4000.0, top_rpm, 1.25 * top_rpm, Grid.parse(grid))


@pytest.fixture(scope="module")
def friction_rotor():
    system = load_rotor(ROTORS / "blower_friction.toml")
    assert all(b.options.friction_coefficient > 0 for b in system.bearings)
    return system


def test_at_60000_rpm_the_rubbing_rotor_closes_the_film_at_b(friction_rotor):
    """results/rotor_friction_transient: at 72 × 20 the film closes at B after 7.353 ms; on
    36 × 10 after 7.385 ms (0.4 % later: the grid's).  The describing function agrees: no
    bounded orbit inside the film."""
    whirl = whirl_at_top_speed(friction_rotor, {}, _settings(60000.0, "36x10"), 20.0)
    assert whirl["model"] == FRICTION_MODEL and MODEL_WORDS in whirl["model"]
    assert whirl["success"] and whirl["contact"] and whirl["contact_bearing"] == "B"
    assert whirl["contact_time_s"] == pytest.approx(7.3848e-3, rel=1e-4)
    assert whirl["revolutions"] == pytest.approx(60000.0 / 60.0 * whirl["contact_time_s"],
                                                 rel=1e-12)
    assert [b["bearing"] for b in whirl["bearings"]] == ["A", "B"]
    for b in whirl["bearings"]:
        assert set(b) == PLAIN | RUBBING and all(k in GLOSSARY for k in b)
        assert b["friction_orbit_kind"] == "contact"
        assert b["friction_orbit_verdict"] == "contact after 7.385 ms"
    assert whirl["bearings"][1]["min_film_um"] == pytest.approx(0.3294, rel=1e-3)
    # the second statement, named
    assert whirl["describing_function_model"] == MODEL
    assert whirl["describing_function_verdict"] == "no bounded orbit inside the film"
    assert whirl["describing_function_bounded"] is False
    # no settled orbit: no settled whirl frequency or film either (the reviewer found the
    # threshold's 366.9 Hz stated as settled_whirl_hz on such rows)
    assert all(math.isnan(b[k]) for b in whirl["bearings"]
               for k in ("settled_orbit_um", "settled_whirl_hz", "settled_min_film_um"))
    text = whirl_text(whirl, 60000.0)
    assert text.startswith("at 60,000 rpm contact at bearing B after 7.38 ms (by the rotor "
                           "transient with sliders (")
    assert text.endswith("7.385 revolutions on the 36x10 grid; the describing function of "
                         "the bumps' friction says no bounded orbit inside the film)")


def test_at_13500_rpm_the_transient_bounds_the_whirl_the_describing_function_does_not(
        friction_rotor):
    """Just above the onset the rubbing bumps hold the whirl on a settled limit cycle locked
    at half the shaft speed (112.5 Hz with the imbalance; at 72 × 20 7.24 / 17.2 µm, here on
    24 × 8 4.854 / 13.42 µm, coarser grids giving smaller orbits as the results show for
    36 × 10), while the describing function finds no bounded orbit: both are stated, the
    verdict is the transient's.  200 revolutions (the design's default) settle within 1e-3;
    120 do not (the bearings still move by 0.2 %: 'end of run')."""
    whirl = whirl_at_top_speed(friction_rotor, {}, _settings(13500.0, "24x8"), 200.0)
    assert whirl["success"] and not whirl["contact"]
    assert whirl["revolutions"] == pytest.approx(200.0, abs=0.02)
    a, b = whirl["bearings"]
    assert [x["friction_orbit_kind"] for x in (a, b)] == ["settled limit cycle"] * 2
    assert a["friction_orbit_amplitude_um"] == pytest.approx(4.8539, rel=1e-3)
    assert b["friction_orbit_amplitude_um"] == pytest.approx(13.421, rel=1e-3)
    for x in (a, b):            # locked at 0.5 × 13,500 rpm = 112.5 Hz
        assert x["friction_orbit_whirl_frequency_hz"] == pytest.approx(112.5, rel=2e-5)
        # the orbit's own measure (spectral, largest distance) beside the first harmonic's
        assert x["limit_cycle_status"] == "limit cycle" and x["limit_cycle_settled"]
        assert x["limit_cycle_amplitude_um"] == pytest.approx(
            x["friction_orbit_amplitude_um"], rel=0.01)
    assert b["min_film_um"] == pytest.approx(5.636, rel=1e-3)
    assert whirl["describing_function_verdict"] == "no bounded orbit inside the film"
    text = whirl_text(whirl, 13500.0)
    assert text.startswith("at 13,500 rpm bounded whirl of 4.85 µm at bearing A and 13.4 µm "
                           "at bearing B at 112.5 Hz, minimum film 5.64 µm (by the rotor "
                           "transient with sliders")
    assert "200 revolutions on the 24x8 grid" in text
    assert text.endswith("the describing function of the bumps' friction says no bounded "
                         "orbit inside the film)")


def test_a_rotor_without_friction_gets_the_orbits_own_figures():
    """blower.toml (no friction) at 13,500 rpm, just above its onset, 24 × 8, 30 revolutions
    (the whirl growing at both bearings, no contact yet): every key of the whirl stage is the
    orbit's (rotor_orbit called directly on the same rotor) bit for bit, and nothing of the
    friction models is added."""
    system = load_rotor(ROTORS / "blower.toml")
    whirl = whirl_at_top_speed(system, {}, _settings(13500.0, "24x8"), 30.0)
    d = rotor_orbit(system, 13500.0, 30.0, grid=Grid(24, 8)).to_dict()
    assert set(whirl) == {"revolutions", "limit_cycle_revolutions", "grid", "success",
                          "message", "contact", "contact_bearing", "contact_time_s",
                          "bearings"}
    assert whirl["revolutions"] == d["revolutions_integrated"]
    for key in ("success", "message", "contact", "contact_bearing", "contact_time_s"):
        assert whirl[key] == d[key], key
    for mine, theirs in zip(whirl["bearings"], d["bearings"], strict=True):
        assert set(mine) == PLAIN
        assert {k: mine[k] for k in PLAIN} == {k: theirs[k] for k in PLAIN}
    # the case itself (so that the comparison is of a whirl, not of nulls)
    a, b = whirl["bearings"]
    assert [a["limit_cycle_status"], b["limit_cycle_status"]] == ["growing", "growing"]
    assert a["limit_cycle_amplitude_um"] == pytest.approx(9.091, rel=1e-3)
    assert b["limit_cycle_amplitude_um"] == pytest.approx(16.32, rel=1e-3)
    assert not whirl["contact"] and whirl["contact_time_s"] is None
    text = whirl_text(whirl, 13500.0)
    assert text == ("at 13,500 rpm the whirl limit cycle is 9.09 µm at bearing A and 16.32 µm "
                    "at bearing B with minimum film 5.59 µm (30 revolutions on the 24x8 grid, "
                    "not yet settled)")


def test_the_words_when_the_rubbing_orbit_has_not_settled_or_whirls_at_two_frequencies():
    """The verdict's other two forms, on the stage's keys (no run): an orbit still moving at
    the end of the run says so per bearing (here the 24 × 8 run above stopped at 120
    revolutions), and two settled orbits at different frequencies give each its own."""
    def bearing(name, kind, amp, hz, film, verdict=""):
        return {"bearing": name, "min_film_um": film, "friction_orbit_kind": kind,
                "friction_orbit_amplitude_um": amp, "friction_orbit_whirl_frequency_hz": hz,
                "friction_orbit_verdict": verdict}
    base = {"model": FRICTION_MODEL, "contact": False, "success": True, "revolutions": 120.0,
            "grid": "24x8", "describing_function_verdict": "no bounded orbit inside the film"}
    moving = {**base, "bearings": [
        bearing("A", "end of run", 4.83, 112.52, 11.89, "end of run, decaying: 4.83 µm"),
        bearing("B", "end of run", 13.3, 112.53, 5.636, "end of run, growing: 13.3 µm")]}
    text = whirl_text(moving, 13500.0)
    assert text.startswith("at 13,500 rpm no settled whirl by the end of the run (bearing A "
                           "end of run, decaying: 4.83 µm; bearing B end of run, growing: "
                           "13.3 µm), minimum film 5.64 µm (by the rotor transient with sliders")
    apart = {**base, "bearings": [bearing("A", "settled limit cycle", 4.85, 112.5, 11.89),
                                  bearing("B", "settled limit cycle", 13.4, 120.0, 5.636)]}
    assert whirl_text(apart, 13500.0).startswith(
        "at 13,500 rpm bounded whirl of 4.85 µm at 112.5 Hz at bearing A and 13.4 µm at 120 Hz "
        "at bearing B, minimum film 5.64 µm (by the rotor transient with sliders")
