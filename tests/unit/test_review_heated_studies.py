"""A study on a heated bearing file reports a thermal runaway as an answer, not as a failed
solve (review of the heated studies): ``all solves converged`` counts solver failures only
and states the rows with no running state apart; the trend checks skip those rows.  Before
the fix the drag_power study below printed "0/1 consistency checks hold … FAILED: all solves
converged" for its 60,000 rpm / 5 N runaway row."""
import json
import math
import shutil
from pathlib import Path

import pandas as pd

from gfbopt.studies import checks
from tests.cli_inprocess import run_cli

BEARINGS = Path(__file__).resolve().parents[2] / "problems" / "bearings"

STUDY = '''name = "drag_thermal"
kind = "drag_power"
title = "Drag torque and power loss: Ruscitto bump-foil bearing, heated"
grid = "24x8"
bearing = "bearings/ruscitto_thermal.toml"
speeds_rpm = [30000.0, 60000.0]
loads_newton = [5.0, 20.0]
'''


def test_a_runaway_row_of_a_heated_drag_study_is_an_answer(tmp_path):
    (tmp_path / "bearings").mkdir()
    shutil.copy(BEARINGS / "ruscitto_thermal.toml", tmp_path / "bearings")
    (tmp_path / "drag_thermal.toml").write_text(STUDY)
    result = run_cli("run", tmp_path / "drag_thermal.toml", "--results", tmp_path / "out",
                     "--workers", "1")
    assert result.returncode == 0, result.stderr
    folder = tmp_path / "out" / "drag_thermal"
    table = pd.read_csv(folder / "drag.csv")
    runaway = table[table["thermal_status"] == "runaway"]
    # 24x8: 60,000 rpm under 5 N has no fixed point (gfbopt static says so too)
    assert list(zip(runaway["speed_rpm"], runaway["load_newton"])) == [(60000, 5)]
    assert not runaway["success"].any() and runaway["power_loss_w"].isna().all()
    assert table[table["thermal_status"] == "running"]["success"].all()
    summary = json.loads((folder / "summary.json").read_text())
    (found,) = summary["checks"]
    assert found["passed"] and found["value"] == 0.0
    assert "not counted, answers: 1 row with no running state: thermal runaway at " \
           "60,000 rpm under 5 N" in found["what"]
    assert found["what"] in (folder / "README.md").read_text()
    assert "FAILED" not in result.stdout + result.stderr


def test_a_solver_failure_still_counts_and_trends_skip_rows_without_a_state():
    table = pd.DataFrame({
        "speed_rpm": [3e4, 3e4, 3e4, 3e4], "load_newton": [5.0, 10.0, 20.0, 40.0],
        "success": [True, False, False, True],
        "thermal_status": ["running", "running", "runaway", "running"],
        "min_film_thickness_um": [15.0, math.nan, math.nan, 9.0]})
    found = checks.all_converged(table)
    # the failed solve at 10 N (a state, no equilibrium) counts; the runaway at 20 N does not
    assert found["value"] == 1.0 and not found["passed"]
    assert "thermal runaway at 30,000 rpm under 20 N" in found["what"]
    # a table without the column: every False success counts, the text is today's
    plain = checks.all_converged(table.drop(columns="thermal_status"))
    assert plain == {"what": "all solves converged (count of failures)", "value": 2.0,
                     "limit": 0.0, "passed": False}
    (trend,) = checks.monotone(table[table["load_newton"] != 10.0], "min_film_thickness_um",
                               "load_newton", False, ["speed_rpm"], "rise of h_min")
    # 15 -> 9 µm over the rows with a state: falls, so the largest rise is 0
    assert trend["value"] == 0.0 and trend["passed"]
