"""results/blower_cooling/README.md states the numbers of the shipped CSVs (speeds.csv,
onsets.csv, limits.csv): each table row of the README is rebuilt here from the CSVs, with the
README's rounding, and must be the README's row exactly (reading files only, no solve)."""
from __future__ import annotations

import math
from pathlib import Path

import pandas as pd
import pytest

FOLDER = Path(__file__).resolve().parents[2] / "results" / "blower_cooling"
TOP_SPEED = 60000.0


def _fmt(x, spec):
    return "—" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def onset_rows(onsets: pd.DataFrame) -> list:
    """| variant | conical onset | cylindrical onset | A: clearance, film at the first onset |
    B: clearance, film at the first onset |"""
    rows = []
    for variant, g in onsets.groupby("variant", sort=False):
        cells = [variant]
        for mode in ("forward conical", "forward cylindrical"):
            cells.append(_fmt(g[g["label"] == mode]["onset_speed_rpm"].iloc[0], ",.1f"))
        found = g[g["onset_speed_rpm"].notna()]
        first = found[found["onset_speed_rpm"] == found["onset_speed_rpm"].min()]
        for name in ("A", "B"):
            r = first[first["bearing"] == name].iloc[0]
            cells.append(f"{_fmt(r['running_clearance_um'], '.2f')} / "
                         f"{_fmt(r['film_temperature_c'], '.1f')}")
        rows.append("| " + " | ".join(cells) + " |")
    return rows


def top_rows(speeds: pd.DataFrame, limits: pd.DataFrame) -> list:
    """| variant | per bearing at the top speed: clearance / film / drag / h_min | runaway |"""
    rows = []
    top = speeds[speeds["speed_rpm"] == TOP_SPEED]
    for variant, g in top.groupby("variant", sort=False):
        cells = [variant]
        for name in ("A", "B"):
            r = g[g["bearing"] == name].iloc[0]
            if r["thermal_status"] != "running":
                cells.append("runaway")
                continue
            cells.append(" / ".join((_fmt(r["running_clearance_um"], ".2f"),
                                     _fmt(r["film_temperature_c"], ".1f"),
                                     _fmt(r["power_loss_w"], ".1f"),
                                     _fmt(r["min_film_thickness_um"], ".2f"))))
        lim = limits[(limits["variant"] == variant) & limits["limit_rpm"].notna()]
        cells.append("; ".join(f"bearing {b} from {s:,.0f} rpm"
                               for b, s in zip(lim["bearing"], lim["limit_rpm"])) or "none")
        rows.append("| " + " | ".join(cells) + " |")
    return rows


@pytest.fixture(scope="module")
def shipped():
    readme = (FOLDER / "README.md").read_text(encoding="utf-8")
    tables = {n: pd.read_csv(FOLDER / f"{n}.csv") for n in ("speeds", "onsets", "limits")}
    return readme, tables


def test_readme_onset_table_is_the_csv(shipped):
    readme, t = shipped
    rows = onset_rows(t["onsets"])
    assert len(rows) == 7
    for row in rows:
        assert row in readme.splitlines(), row


def test_readme_top_speed_table_is_the_csv(shipped):
    readme, t = shipped
    rows = top_rows(t["speeds"], t["limits"])
    assert len(rows) == 7
    for row in rows:
        assert row in readme.splitlines(), row


def test_only_the_uncooled_bearing_b_runs_away_below_the_top_speed(shipped):
    """The README's sentence on runaway rests on limits.csv: exactly one bearing fails, B
    without cooling flow, between its last running and first failing speeds."""
    _, t = shipped
    lim = t["limits"][t["limits"]["limit_rpm"].notna()]
    assert list(zip(lim["variant"], lim["bearing"])) == [("heat balance, no cooling flow",
                                                          "B")]
    r = lim.iloc[0]
    assert r["last_running_rpm"] < r["limit_rpm"] <= r["first_failing_rpm"] <= TOP_SPEED
