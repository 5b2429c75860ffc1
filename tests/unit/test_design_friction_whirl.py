"""A rotor design whose bearings carry the bumps' Coulomb friction takes its top-speed whirl
from the describing function (the rotor transient carries no sliders): the whirl stage's keys,
the model named, and the verdict's words (design.robustness, studies.rotor_report)."""
from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

from gfbopt.design.robustness import friction_whirl_at_top_speed
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.friction_onset import MODEL
from gfbopt.studies.rotor_report import whirl_text

ROOT = Path(__file__).resolve().parents[2]


def test_friction_rotor_whirl_at_top_speed_is_the_describing_functions():
    system = load_rotor(ROOT / "problems" / "rotors" / "blower_friction.toml")
    assert all(b.options.friction_coefficient > 0 for b in system.bearings)
    settings = SimpleNamespace(grid=Grid.parse("24x8"), top_speed_rpm=30000.0)
    whirl = friction_whirl_at_top_speed(system, settings)
    assert whirl["model"] == MODEL and whirl["grid"] == "24x8"
    assert [b["bearing"] for b in whirl["bearings"]] == [b.name for b in system.bearings]
    # results/bumps_that_rub: on the Ruscitto bearings this rotor is never bounded
    assert "no bounded orbit" in whirl["verdict"]
    assert not any(b["limit_cycle_settled"] for b in whirl["bearings"])
    text = whirl_text(whirl, 30000.0)
    assert text.startswith("at 30,000 rpm no bounded orbit") and MODEL in text
