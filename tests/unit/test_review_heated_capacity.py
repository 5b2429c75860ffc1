"""Load capacity and lift-off of a heated bearing with every point of the search at its
own running condition (review of the heated capacity curve): before the fix the lift-off
curve of ruscitto_thermal.toml was the bearing held at the 1,388 rpm running condition of
its answer (h_min 19.18 µm and 254 W at 100,000 rpm, where ``gfbopt static`` says thermal
runaway), with no thermal column in the CSV and no model in its context or the figure.

Now each row is ``gfbopt static --bearing FILE --speed-rpm N --load-newton F`` (the same
fixed point, then the warm bearing's equilibrium: equal to round-off, measured 1e-13), a
row with no running state is NaN with its thermal_status, and the answer is the root at its
own running condition (no outer iteration): gfbopt static at the answer's load gives h_min
= the limit to 1e-9."""
import json
import math
from pathlib import Path

import pandas as pd
import pytest

from tests.cli_inprocess import run_cli

THERMAL = Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto_thermal.toml"
GRID = "24x8"


def static(speed_rpm: float, load_newton: float) -> dict:
    out = run_cli("static", "--bearing", THERMAL, "--speed-rpm", repr(speed_rpm),
                  "--load-newton", repr(load_newton), "--grid", GRID, "--json")
    return json.loads(out.stdout)


def test_lift_off_curve_rows_are_each_at_their_own_running_condition(tmp_path):
    csv = tmp_path / "cap.csv"
    result = run_cli("capacity", "--bearing", THERMAL, "--lift-off", "--load-newton", "20",
                     "--min-film-um", "5", "--grid", GRID, "--csv", csv, "--figure",
                     tmp_path / "cap.png", "--json")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    table = pd.read_csv(csv)
    context = json.loads((tmp_path / "cap.csv.json").read_text())
    assert context["provenance"]["options"]["thermal_model"] == "heat balance + growth"
    assert {"thermal_status", "running_clearance_um", "film_temperature_c"} <= set(
        context["columns"])
    # 100,000, 80,000 and 64,000 rpm under 20 N: thermal runaway (as gfbopt static says)
    lost = table[table["thermal_status"] == "runaway"]
    assert list(lost["speed_rpm"]) == [100000.0, 80000.0, 64000.0]
    assert lost["min_film_thickness_um"].isna().all() and lost["power_loss_w"].isna().all()
    assert static(100000.0, 20.0)["running"]["thermal_status"] == "runaway"
    assert "no running state at the higher speeds searched (64000–100000 rpm)" in out["answer"]
    running = table[table["thermal_status"] == "running"]
    for speed in (51200.0, 26214.4):       # hot and mild: each row is gfbopt static's
        row = running[(running["speed_rpm"] / speed - 1).abs() < 1e-9].iloc[0]
        alone = static(float(row["speed_rpm"]), 20.0)
        for key in ("min_film_thickness_um", "running_clearance_um", "film_temperature_c",
                    "power_loss_w"):
            assert row[key] == pytest.approx(alone[key], rel=1e-9), key
    # not frozen: 51,200 rpm runs at 15.3 µm, the answer (1,388 rpm) at 19.996 µm
    hot = running[running["speed_rpm"] == 51200.0].iloc[0]
    assert hot["running_clearance_um"] < 0.8 * out["running_clearance_um"]
    # the answer at its own running condition, on the limit
    assert out["running"]["speed_rpm"] == out["lift_off_speed_rpm"]
    assert out["min_film_thickness_um"] == pytest.approx(5.0, rel=1e-9)
    assert 1380 < out["lift_off_speed_rpm"] < 1396          # measured 1,388.0 rpm


def test_load_capacity_is_the_root_at_its_own_running_condition():
    result = run_cli("capacity", "--bearing", THERMAL, "--speed-rpm", "60000",
                     "--min-film-um", "5", "--grid", GRID, "--json")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    load = out["load_capacity_newton"]
    assert 440 < load < 500                                  # measured 469.55 N
    curve = pd.DataFrame(out["curve"])
    # the light loads at 60,000 rpm have no fixed point (measured up to 16.5 N), nor the
    # heavy 636 N the march stepped to; the crossing lies between (bracketed, then refined)
    lost = curve[curve["thermal_status"] == "runaway"]["load_newton"]
    assert (lost < 20.0).sum() >= 3 and ((lost < 20.0) | (lost > load)).all()
    assert "no running state at the lighter loads searched" in out["answer"]
    # gfbopt static at the answer's load: the same running point, and h_min on the limit
    alone = static(60000.0, load)
    assert alone["running_clearance_um"] == pytest.approx(out["running_clearance_um"],
                                                          rel=1e-9)
    assert alone["min_film_thickness_um"] == pytest.approx(5.0, rel=1e-9)
    assert math.isfinite(out["film_temperature_c"]) and out["film_temperature_c"] > 100.0
