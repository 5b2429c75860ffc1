"""Studies on a bearing file with [journal]/[thermal]: ``onset_conventions`` evaluates each
onset at the running condition through the functions ``gfbopt stability`` and gfbopt.api
call (one answer whatever the route), naming the model in summary.json and the README;
kinds that do not read the tables refuse the file in one line naming the kind, before any
solve."""
import json
import math
import re
import shutil
from pathlib import Path

import pytest

from gfbopt import StaticSolver
from gfbopt.inputs import Grid, Rotor, load_bearing
from gfbopt.inputs.bearing_file import RUNNING_ROUTES, RUNNING_STUDY_KINDS
from gfbopt.studies import compute, load_study, run_study
from gfbopt.thermal.running import HEAT_BALANCE
from tests.cli_inprocess import run_cli

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"
THERMAL = PROBLEMS / "bearings" / "ruscitto_thermal.toml"
GRID = "36x10"
STUDY = f"""
name = "heated_conventions"
kind = "onset_conventions"
title = "Onset against the film convention at the running condition"
source = "gfbopt"
grid = "{GRID}"
bearing = "bearings/BEARING"
rotor_mass_kg = 2.0
load_newton = 20.0
speed_range_rpm = [3000.0, 60000.0]
seam_angles_deg = [180.0]
"""
#: convention → the formulation flags of ``gfbopt stability``
FLAGS = {"periodic": ("--film", "periodic"),
         "max_film": ("--film", "seam", "--seam-angle", "max_film"),
         "seam_180": ("--film", "seam", "--seam-angle", "180")}
RUNNING = ("running_clearance_um", "centrifugal_growth_um", "thermal_growth_um",
           "film_temperature_c", "viscosity_pa_s")


def _study(tmp_path, bearing="ruscitto_thermal.toml", text=STUDY):
    (tmp_path / "bearings").mkdir(exist_ok=True)
    shutil.copy(PROBLEMS / "bearings" / bearing, tmp_path / "bearings" / bearing)
    path = tmp_path / "study.toml"
    path.write_text(text.replace("BEARING", bearing))
    return path


@pytest.fixture(scope="module")
def heated(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("heated")
    result = run_study(_study(tmp), results_root=tmp / "results")
    return result, tmp / "results" / "heated_conventions"


def test_the_study_kinds_reading_the_tables_are_listed_in_the_routes():
    assert RUNNING_STUDY_KINDS == ("onset_conventions",)
    assert "`onset_conventions`" in RUNNING_ROUTES and "`gfbopt orbit`" in RUNNING_ROUTES


@pytest.mark.parametrize("convention", sorted(FLAGS))
def test_a_study_row_is_the_stability_commands_onset(heated, convention):
    result, _ = heated
    table = result.tables["onset.csv"].set_index("convention")
    row = table.loc[convention]
    cli = run_cli("stability", "--bearing", THERMAL, "--rotor-mass-kg", "2", "--load-newton",
                  "20", "--speed-range", "3000", "60000", *FLAGS[convention], "--grid", GRID,
                  "--json")
    assert cli.returncode == 0, cli.stderr
    out = json.loads(cli.stdout)
    assert out["thermal_model"] == HEAT_BALANCE == row["thermal_model"]
    # one route: the same secant search on the same running points (1e-9: rounding only)
    assert row["onset_status"] == "onset"
    assert row["onset_speed_rpm"] == pytest.approx(out["onset_speed_rpm"], rel=1e-9)
    assert row["whirl_frequency_hz"] == pytest.approx(out["onset_whirl_frequency_hz"],
                                                      rel=1e-9)
    assert row["frozen_onset_speed_rpm"] == pytest.approx(
        out["onset"]["frozen_onset_speed_rpm"], rel=1e-9)
    for key in RUNNING:                          # the running point at the onset
        assert row[key] == pytest.approx(out[key], rel=1e-9), key
    assert row["running_clearance_um"] < 20.0 and row["film_temperature_c"] > 20.0


def test_a_study_row_is_the_apis_onset(heated):
    from gfbopt import api

    row = heated[0].tables["onset.csv"].set_index("convention").loc["seam_180"]
    found = api.onset_speed(str(THERMAL), Rotor(2.0), 20.0, (3000.0, 60000.0), film="seam",
                            seam_angle_deg=180.0, grid=Grid.parse(GRID))
    assert row["onset_speed_rpm"] == pytest.approx(found["onset_speed_rpm"], rel=1e-9)
    assert row["running_clearance_um"] == pytest.approx(
        found["running"]["running_clearance_um"], rel=1e-9)


def test_summary_and_readme_name_the_thermal_model(heated):
    _, folder = heated
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["thermal_model"] == HEAT_BALANCE
    assert summary["provenance"]["options"]["thermal_model"] == HEAT_BALANCE
    assert any("heat balance + growth" in n for n in summary["notes"])
    readme = (folder / "README.md").read_text()
    assert f"thermal_model = {HEAT_BALANCE}" in readme
    header = (folder / "onset.csv").read_text().splitlines()[0].split(",")
    for column in ("thermal_model", *RUNNING, "frozen_onset_speed_rpm"):
        assert column in header, column


def test_a_file_without_the_tables_gives_todays_study(tmp_path):
    """No clearance-at-speed column or option, and the row is the isothermal onset of the
    cold bearing (gfbopt.rotor.onset_speed on the file's geometry)."""
    from gfbopt.rotor import onset_speed

    loaded = load_study(_study(tmp_path, "ruscitto.toml"))
    assert all("running" not in p for p in loaded.plan["points"])
    result = compute(loaded)
    table = result.tables["onset.csv"].set_index("convention")
    assert not set(table.columns) & {"thermal_model", *RUNNING}
    assert "thermal_model" not in result.options and result.answer == {}
    bearing = load_bearing(PROBLEMS / "bearings" / "ruscitto.toml")
    found = onset_speed(bearing, Rotor(2.0), 20.0, (3000.0, 60000.0), film="seam",
                        seam_angle_deg=180.0, foil="simple", deflection_law="mean",
                        loss_factor=0.0, grid=Grid.parse(GRID))
    assert table.loc["seam_180", "onset_speed_rpm"] == found.onset_speed_rpm
    assert math.isfinite(found.onset_speed_rpm)


@pytest.fixture
def no_solver(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("a solver was built before the file was refused")
    monkeypatch.setattr(StaticSolver, "__init__", refuse)


@pytest.mark.parametrize("problem, kind", [
    ("loss_factor", "loss_factor_map"), ("ruscitto_coefficients", "linear_coefficients"),
    ("ruscitto_static", "load_sweep"), ("ruscitto_drag", "drag_power"),
    ("ruscitto_pitch_design", "pitch_design"), ("ruscitto_preload", "onset_as_built")])
def test_kinds_that_do_not_read_the_tables_refuse_in_one_line(tmp_path, no_solver, problem,
                                                               kind):
    text = (PROBLEMS / f"{problem}.toml").read_text()
    assert '"bearings/ruscitto.toml"' in text
    path = _study(tmp_path, text=text.replace('"bearings/ruscitto.toml"',
                                              '"bearings/BEARING"'))
    result = run_cli("run", path, "--results", tmp_path / "results")
    assert result.returncode == 2 and result.stdout == ""
    line = result.stderr.strip()
    assert len(line.splitlines()) == 1
    assert f"the study kind '{kind}' does not read" in line
    assert re.search(r"states \[journal\] and \[thermal\]", line)
    assert "`onset_conventions`" in line and "`gfbopt stability`" in line
    assert not (tmp_path / "results").exists() or not any((tmp_path / "results").iterdir())
