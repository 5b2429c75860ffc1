"""``gfbopt rotor --speed-rpm``: the modes and thresholds at that speed carry the onset list's
names (one name per mode, docs/rotor.md), so two modes of one shape class are told apart: on
the flexible rotor at 13,300 rpm, between the onsets of "forward mixed" (13,044 rpm) and
"forward mixed (2)" (13,552 rpm), the first is the unstable one, in the eigenmodes and in the
thresholds alike, in the JSON and the text; a mode of no onset-list shape there (a backward
one) has no name of the list (null), and the text shows its shape class in parentheses."""
import json
import math
from pathlib import Path

import pytest

from tests.cli_inprocess import run_cli

ROTOR = Path(__file__).resolve().parents[2] / "problems" / "rotors" / "flexible_rotor.toml"


@pytest.fixture(scope="module")
def answer(tmp_path_factory):
    args = (ROTOR, "--speed-range", "5000", "30000", "--grid", "24x8", "--speed-rpm", "13300")
    js, text = run_cli("rotor", *args, "--json"), run_cli("rotor", *args)
    assert js.returncode == 0 and text.returncode == 0, js.stderr + text.stderr
    return json.loads(js.stdout), text.stdout


def test_each_mode_and_threshold_has_one_name(answer):
    out, _ = answer
    at = out["at_speed"]
    labels = {m["label"] for m in out["modes"]}
    for rows in (at["modes"], at["thresholds"]):
        names = [r["track_label"] for r in rows if r["track_label"] is not None]
        assert len(names) == len(set(names)) and set(names) <= labels
    onset = {m["label"]: m["onset_speed_rpm"] for m in out["modes"]}
    assert onset["forward mixed"] < 13300.0 < onset["forward mixed (2)"]
    threshold = {t["track_label"]: t["inertia_margin"] for t in at["thresholds"]}
    assert threshold["forward mixed"] < 0 < threshold["forward mixed (2)"]
    decrement = {m["track_label"]: m["log_decrement"] for m in at["modes"]
                 if math.isfinite(m["log_decrement"])}
    assert decrement["forward mixed"] < 0 < decrement["forward mixed (2)"]


def test_the_text_uses_the_same_names(answer):
    out, text = answer
    for t in out["at_speed"]["thresholds"]:
        assert f"threshold of {t['track_label'] or '(' + t['shape_label'] + ')'}: " in text
    for m in out["at_speed"]["modes"]:
        if math.isfinite(m["log_decrement"]):
            name = m["track_label"] or f"({m['shape_label']})"
            assert f"mode {name:<22} whirl" in text
