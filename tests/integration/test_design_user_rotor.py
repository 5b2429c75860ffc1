"""The user's own rotor in one command: ``gfbopt run STUDY --rotor my_rotor.toml
--top-speed 60000`` answers what an edited copy of the study file answers (the planted
evaluation of design_decision_evaluation, whose onset depends on the rotor's mass, so the
wrong rotor would show); bad options are one line and exit 2 before any solve; a user's own
study needs no source, a shipped one (in gfbopt's problems/ folder) does."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from cli_inprocess import run_cli
from gfbopt.errors import ParameterError
from gfbopt.inputs import read_toml
from gfbopt.studies.spec import USER_SOURCE, validate
from test_design_decision import STUDY, study  # noqa: F401  (the fixture)

ROOT = Path(__file__).resolve().parents[2]
BLOWER = ROOT / "problems" / "rotors" / "blower.toml"


def _my_rotor(folder: Path) -> Path:
    """The blower made 5 kg, its bearing files named from wherever it is."""
    text = BLOWER.read_text().replace("mass = 3.2 ", "mass = 5.0 ").replace(
        '"../bearings/ruscitto.toml"', f'"{ROOT / "problems" / "bearings" / "ruscitto.toml"}"')
    assert "mass = 5.0" in text
    path = folder / "my_rotor.toml"
    path.write_text(text)
    return path


#: summary.json keys that name the study or time it (everything else must be equal)
NAMING = ("name", "title", "source", "problem_file", "wall_time_s", "provenance")


def _answer(folder: Path) -> dict:
    s = json.loads((folder / "summary.json").read_text())
    s = {k: v for k, v in s.items() if k not in NAMING}
    s["notes"] = [n for n in s["notes"]                 # their rates and wall times, and
                  if not n.startswith(("Search:", "What it would take",   # what --rotor
                                       "Run on the user's rotor"))]       # replaced
    return s


def test_the_override_answers_as_an_edited_copy(study, tmp_path):  # noqa: F811
    (tmp_path / "elsewhere").mkdir()
    rotor = _my_rotor(tmp_path / "elsewhere")
    results = tmp_path / "results"
    cli = run_cli("run", study, "--rotor", rotor, "--top-speed", "60000", "--results",
                  results, "--workers", "1")
    assert cli.returncode == 0, cli.stderr
    folder = results / "rd_decision_on_my_rotor_to_60000rpm"
    summary = json.loads((folder / "summary.json").read_text())
    assert "on the user's rotor my_rotor.toml to 60,000 rpm" in summary["title"]
    assert "5 kg" in summary["title"]
    assert ("- Run on the user's rotor my_rotor.toml to 60,000 rpm: the rotor is "
            in (folder / "README.md").read_text())
    assert summary["verdict"].startswith("No design in this space is stable to 60,000 rpm")
    # the copy: rotor (relative to the copy), top speed, name and title edited, no source
    copy = tmp_path / "elsewhere" / "my_study.toml"
    text = STUDY.replace(f'rotor = "{BLOWER}"', 'rotor = "my_rotor.toml"').replace(
        "speed_range_rpm = [4000.0, 45000.0]", "speed_range_rpm = [4000.0, 60000.0]").replace(
        'name = "rd_decision"', 'name = "my_study"').replace('source = "test"\n', "")
    assert 'rotor = "my_rotor.toml"' in text and "60000.0]" in text and "source" not in text
    copy.write_text(text)
    edited = run_cli("run", copy, "--results", results, "--workers", "1")
    assert edited.returncode == 0, edited.stderr
    mine = json.loads((results / "my_study" / "summary.json").read_text())
    assert mine["source"] == USER_SOURCE
    assert _answer(folder) == _answer(results / "my_study")
    # and the 5 kg rotor changed the answer (1,000 rpm per kg in the planted onset)
    assert run_cli("run", study, "--results", tmp_path / "r0", "--workers", "1"
                   ).returncode == 0
    shipped = json.loads((tmp_path / "r0" / "rd_decision" / "summary.json").read_text())
    assert mine["best_first_onset_rpm"] != shipped["best_first_onset_rpm"]


@pytest.mark.parametrize("options, rule", [
    (["--rotor", "missing.toml"], "--rotor = 'missing.toml': no such rotor file"),
    (["--rotor", "NOT_A_ROTOR"], "is not a valid rotor file"),
    (["--rotor", "."], "is a directory"),
    (["--top-speed", "3000"], "--top-speed = 3000.0: must be above the study's lowest "
                              "speed 4000 rpm"),
    (["--top-speed", "-5"], "--top-speed = -5.0: must be a finite speed > 0"),
    (["--top-speed", "fast"], "--top-speed = 'fast': must be a speed in rpm"),
    (["--top-speed", "inf"], "--top-speed = inf: must be a finite speed > 0")])
def test_bad_options_are_one_line_before_any_solve(study, tmp_path, options,  # noqa: F811
                                                   rule):
    bad = tmp_path / "bad_rotor.toml"
    bad.write_text("[rotor]\nmass = -1.0\n")
    options = [str(bad) if o == "NOT_A_ROTOR" else o for o in options]
    out = run_cli("run", study, *options, "--results", tmp_path / "results", "--workers",
                  "1", cwd=tmp_path)
    assert out.returncode == 2, out.stdout
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and rule in lines[0], lines
    assert not (tmp_path / "calls.log").exists()


def test_rotor_options_on_a_study_without_a_rotor_are_refused(tmp_path):
    out = run_cli("run", ROOT / "problems" / "thesis_table_3_1.toml", "--rotor", BLOWER,
                  "--results", tmp_path)
    assert out.returncode == 2
    assert "--rotor" in out.stderr and "has no rotor" in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1


def test_a_shipped_study_must_cite_its_source_and_a_users_need_not(tmp_path):
    """Shipped: the file is inside gfbopt's problems/ folder (by its resolved path)."""
    file = ROOT / "problems" / "rotor_bearing_design.toml"
    data = read_toml(file)
    del data["source"]
    with pytest.raises(ParameterError) as info:
        validate(data, str(file))
    assert "source" in str(info.value) and "shipped in gfbopt's problems/" in str(info.value)
    copy = tmp_path / "rotor_bearing_design.toml"
    copy.write_text(file.read_text())
    assert validate(data, str(copy))["source"] == USER_SOURCE
