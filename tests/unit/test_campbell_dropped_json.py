"""A Campbell root that continues no track is left out of the diagram and stated in the
command's JSON (``campbell.dropped_roots``), never silently: the blower rotor at 24 × 8 over
nine speeds 4,000–60,000 rpm finds a heavily damped forward conical root (Λ-dependent, log
decrement ≈ 2.5) at 11,000 rpm alone (gfbopt.rotor.tracking.stitch, tests/unit/
test_campbell_tracks_blower.py for the library's side)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tests.cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]


def test_a_root_of_one_speed_is_stated_in_the_json_and_in_no_track(tmp_path):
    run = run_cli("rotor", ROOT / "problems/rotors/blower.toml", "--campbell",
                  "--campbell-speeds", "9", "--speed-range", "4000", "60000",
                  "--grid", "24x8", "--json", "--csv", tmp_path / "csv")
    assert run.returncode == 0, run.stderr
    campbell = json.loads(run.stdout)["campbell"]
    dropped = campbell["dropped_roots"]
    assert len(dropped) == 1
    root = dropped[0]
    assert root["speed_rpm"] == 11000.0
    # the root's frequency as the tracking test finds it (tolerance: solver round-off)
    assert root["whirl_frequency_hz"] == pytest.approx(194.0, rel=1e-4)
    assert "11,000 rpm only" in root["reason"]
    # the diagram's table holds no track of a single point, and no row at that root
    table = pd.read_csv(tmp_path / "csv" / "campbell.csv")
    assert table.groupby("mode").size().min() >= 2
    assert campbell["modes"] == table["mode"].nunique() == len(campbell["tracks"])
    at = table[table["speed_rpm"] == 11000.0]
    assert not np.isclose(at["whirl_frequency_hz"], root["whirl_frequency_hz"],
                          rtol=1e-6).any()
