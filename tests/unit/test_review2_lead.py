"""A second review's findings fixed by the lead (each fails on cf8ea34):

* ``gfbopt rotor --speed-rpm`` where the rotor has no equilibrium (a heated bearing's
  runaway) printed a traceback; it states why, once, and exits 0;
* ``gfbopt.load_bearing(path, running=True)`` loaded a heated file past its refusal and
  ``gfbopt.stability`` on it answered with the cold clearance, silently: the public loader
  has no such switch (the path goes to gfbopt.stability, which applies the running state);
* with ``--foil rigid`` the conventions stated the file's compliance (1.0487) while S = 0
  was solved;
* a Campbell root that continues no track is stated in the rotor study's notes
  (summary.json, README), as in the command's JSON and text."""
from __future__ import annotations

import copy
import json
from pathlib import Path

import pytest

import gfbopt
from gfbopt.errors import ParameterError
from gfbopt.inputs import read_toml
from gfbopt.studies import study_from_dict
from tests.cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]
BEARINGS = ROOT / "problems" / "bearings"


def test_at_speed_without_an_equilibrium_is_stated_not_a_traceback():
    run = run_cli("rotor", ROOT / "problems/rotors/blower_thermal.toml", "--speed-range",
                  "4000", "60000", "--speed-rpm", "80000", "--grid", "24x8")
    assert run.returncode == 0, run.stderr
    assert "Traceback" not in run.stderr
    line = next(t for t in run.stdout.splitlines() if "no equilibrium:" in t)
    assert "thermal runaway at bearing A at 80000 rpm" in line


def test_the_public_loader_refuses_a_heated_file_and_has_no_switch_past_it():
    heated = BEARINGS / "ruscitto_thermal.toml"
    with pytest.raises(ParameterError) as info:
        gfbopt.load_bearing(heated)
    assert "given the file's path" in str(info.value) and "\n" not in str(info.value)
    with pytest.raises(TypeError):
        gfbopt.load_bearing(heated, running=True)
    assert gfbopt.load_bearing(BEARINGS / "ruscitto.toml").radial_clearance == 20e-6


def test_a_rigid_foil_states_the_compliance_it_solves():
    run = run_cli("stability", "--bearing", BEARINGS / "ruscitto.toml", "--rotor-mass-kg",
                  "2", "--load-newton", "20", "--speed-rpm", "30000", "--foil", "rigid",
                  "--grid", "24x8", "--json")
    assert run.returncode == 0, run.stderr
    out = json.loads(run.stdout)
    assert out["conventions"]["foil"] == "rigid" and out["conventions"]["compliance"] == 0.0
    lin = run_cli("linear", "--bearing", BEARINGS / "ruscitto.toml", "--load-newton", "20",
                  "--speed-rpm", "30000", "--foil", "rigid", "--grid", "24x8", "--json")
    assert lin.returncode == 0, lin.stderr
    # the same model: the same M̄c (the review measured 4.5187 on both routes)
    assert json.loads(lin.stdout)["critical_mass"] == pytest.approx(out["critical_mass"],
                                                                   rel=1e-9)


def test_a_dropped_campbell_root_is_in_the_rotor_studys_notes(tmp_path):
    from gfbopt.studies.runner import run_study

    data = copy.deepcopy(read_toml(ROOT / "problems" / "rotor_blower.toml"))
    data.update(name="blower_9", grid="24x8", campbell_speeds=9, imbalance_speeds=4)
    study = study_from_dict(data, name="blower_9", file=str(ROOT / "problems" / "x.toml"),
                            directory=ROOT / "problems")
    result = run_study(study, tmp_path)
    notes = [n for n in result.notes if "left out of the diagram" in n]
    assert len(notes) == 1 and "11,000 rpm" in notes[0] and "194.0 Hz" in notes[0]
    summary = json.loads((tmp_path / "blower_9" / "summary.json").read_text())
    assert any("left out of the diagram" in n for n in summary["notes"])
