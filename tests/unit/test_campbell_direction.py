"""A Campbell track keeps its whirl direction (gfbopt.rotor.tracking: a hard constraint of the
assignment, the continuation and stitch).

The reviewer's case: ``gfbopt rotor problems/rotors/flexible_rotor.toml --speed-range 10000
60000 --grid 24x8 --campbell`` (20 speeds).  At 10,000 rpm the forward conical root at
153.1 Hz (log decrement 2.63) was the first point of the "backward conical" track, whose next
point is a backward root at 161.8 Hz (log decrement 1.21): the step's cost was 1.474, under
MAX_COST = 1.5, because the shape term 1 − MAC is at most 1 (forward against backward:
≈ 1) and the eigenvalue moved 3 %.  Its one forward candidate at 12,632 rpm (the forward
cylindrical track's first point, 248.6 Hz) costs 2.14 to join: the root is now stated as
dropped, and every track whirls one way at every speed.

Synthetic modes of a rigid body as in test_campbell_tracks_stitch.py (q at the centre of
gravity, bearings at −0.035 and 0.065 m)."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from gfbopt.rotor.modes import shape
from gfbopt.rotor.tracking import (
    FREQUENCY_WEIGHT,
    MAX_COST,
    assign,
    cost,
    join_cost,
    stitch,
    whirl_direction,
)
from tests.cli_inprocess import run_cli
from tests.unit.test_campbell_tracks_stitch import _mode, _omega, _track

ROOT = Path(__file__).resolve().parents[2]
POSITIONS = (-0.035, 0.065)
#: the same conical tilt whirling with the shaft (X + iY) and against it (X − iY)
FORWARD = np.array([-0.015, 0.015j, 1.0, -1j]) * 20
BACKWARD = np.conj(FORWARD)




def test_the_direction_is_the_shape_rule():
    """whirl_direction of a mode without a shape dict (from its orbits at the bearings) is
    modes.shape's direction for the same amplitude."""
    for vector, way in ((FORWARD, "forward"), (BACKWARD, "backward")):
        assert shape(vector, POSITIONS, ("A", "B"))["direction"] == way
        assert whirl_direction(_mode(0.5, 1.0, vector), POSITIONS) == way


def test_the_reviewers_step_no_longer_continues_a_track():
    """The flexible rotor's step in whirl ratio and damping (153.08 Hz, δ 2.63 at 10,000 rpm
    → 161.76 Hz, δ 1.21 at 12,632 rpm): the eigenvalue moves 20.6 % (mostly its real part),
    4 × 0.206 = 0.82; of one shape (1 − MAC = 0) that is well under MAX_COST, and the real
    orbits' 1 − MAC = 0.65 (elliptical, MAC 0.35 between the two ways) still left 1.474 <
    1.5.  Of the other direction the cost is now inf and assign starts a new track."""
    # campbell.csv's rows before the fix (whirl_frequency_hz, log_decrement)
    r0 = 153.079902 * 60 / 10000.0
    r1 = 161.763547 * 60 / 12631.5789
    track = _track([(10000.0, r0, 2.628914, FORWARD)])
    s0 = track[0][1].eigenvalue * _omega(10000.0)
    same = _mode(r1, 1.206593, FORWARD)
    s1 = same.eigenvalue * _omega(12631.5789)
    jump = abs(s1 - s0) / abs(s0)                  # the one-point prediction: same Hz
    assert cost(track, same, 12631.5789, _omega(12631.5789), POSITIONS) == pytest.approx(
        FREQUENCY_WEIGHT * jump, rel=1e-9)
    assert FREQUENCY_WEIGHT * jump == pytest.approx(0.822, abs=1e-3)
    assert FREQUENCY_WEIGHT * jump + 0.65 < MAX_COST   # the reviewer's step was accepted
    other = _mode(r1, 1.206593, BACKWARD)
    assert cost(track, other, 12631.5789, _omega(12631.5789), POSITIONS) == math.inf
    tracks = [list(track)]
    active = assign(tracks, [0], 12631.5789, _omega(12631.5789), [other], POSITIONS)
    assert len(tracks) == 2 and len(tracks[0]) == 1 and tracks[1][0][1] is other
    assert active == [1]


def test_the_continuation_skips_a_root_whirling_the_other_way():
    """A two-point forward track whose guess lies nearest a backward root (within NEAR)
    continues at the forward root further off, not at the backward one."""
    track = _track([(8000.0, 0.60, 1.0, FORWARD), (9000.0, 0.60, 1.0, FORWARD)])
    near_back = _mode(0.60, 1.0, BACKWARD)       # exactly at the guess
    fwd = _mode(0.66, 1.0, FORWARD)              # 10 % off it
    tracks = [list(track)]
    guess = [track[-1][1].eigenvalue]            # whirl ratio constant: the same guess
    assign(tracks, [0], 10000.0, _omega(10000.0), [near_back, fwd], POSITIONS, guess)
    assert tracks[0][-1][1] is fwd
    assert len(tracks) == 2 and tracks[1][0][1] is near_back


def test_stitch_joins_no_track_to_one_whirling_the_other_way():
    """An end and a start one speed apart at 1 % in frequency (33.33 Hz; 33.67 Hz held):
    joined when both whirl forward (cost 4 × 20/2020, the start's backward prediction, the
    lesser), not when the start whirls backward — then the one-point end is dropped with
    join cost inf."""
    end = _track([(4000.0, 0.50, 1.0, FORWARD)])
    points = [(8000.0, 0.2525, 1.0), (12000.0, 0.2525 * 8000 / 12000, 1.0)]
    start_f = _track([(s, r, d, FORWARD) for s, r, d in points])
    start_b = _track([(s, r, d, BACKWARD) for s, r, d in points])
    speeds = [4000.0, 8000.0, 12000.0]
    assert join_cost(end, start_f, POSITIONS) == pytest.approx(4 * 20 / 2020, rel=1e-9)
    kept, dropped = stitch([end, start_f], speeds, POSITIONS)
    assert len(kept) == 1 and len(kept[0]) == 3 and not dropped
    assert join_cost(end, start_b, POSITIONS) == math.inf
    kept, dropped = stitch([end, start_b], speeds, POSITIONS)
    assert len(kept) == 1 and kept[0] == start_b
    assert len(dropped) == 1 and dropped[0][0] == end and dropped[0][1] == math.inf


@pytest.fixture(scope="module")
def flexible(tmp_path_factory):
    """The reviewer's command (24x8, 10,000–60,000 rpm, 20 speeds) with --json."""
    folder = tmp_path_factory.mktemp("fx")
    run = run_cli("rotor", ROOT / "problems/rotors/flexible_rotor.toml", "--speed-range",
                  "10000", "60000", "--grid", "24x8", "--campbell", "--json",
                  "--csv", folder / "fx_csv")
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)["campbell"], pd.read_csv(folder / "fx_csv" / "campbell.csv",
                                                           comment="#")


def test_every_flexible_track_whirls_one_way(flexible):
    """Each track's rows have one direction (the first word of shape_label) at every speed,
    and a track named forward/backward is named for that direction."""
    _, table = flexible
    assert table["speed_rpm"].nunique() == 20
    for mode, rows in table.groupby("mode"):
        ways = set(rows["shape_label"].str.split().str[0])
        assert len(ways) == 1, (mode, rows[["speed_rpm", "shape_label"]].to_string())
        assert rows["track_label"].iloc[0].split()[0] in ways


def test_the_153_hz_forward_root_is_stated_as_dropped(flexible):
    """The forward root at 10,000 rpm (153.08 Hz, δ 2.63) continues no forward track (its one
    forward candidate, 248.6 Hz at 12,632 rpm, costs 2.14 > MAX_COST) and is stated, not put
    on the backward conical track; that track starts at 12,632 rpm at 161.8 Hz, backward.
    Tolerances: 24x8 solver round-off on one machine, far inside the 5 % between roots."""
    campbell, table = flexible
    lost = [r for r in campbell["dropped_roots"] if r["speed_rpm"] == 10000.0]
    assert len(lost) == 1
    root = lost[0]
    assert root["whirl_frequency_hz"] == pytest.approx(153.08, rel=1e-3)
    assert root["log_decrement"] == pytest.approx(2.63, abs=0.01)
    assert root["shape_label"].startswith("forward")
    assert "join cost 2.14" in root["reason"]
    at = table[table["speed_rpm"] == 10000.0]
    assert not np.isclose(at["whirl_frequency_hz"], root["whirl_frequency_hz"],
                          rtol=1e-6).any()
    back = table[table["track_label"] == "backward conical"].sort_values("speed_rpm")
    assert back["speed_rpm"].iloc[0] == pytest.approx(12631.58, abs=0.01)
    assert back["whirl_frequency_hz"].iloc[0] == pytest.approx(161.76, rel=1e-3)
    assert set(back["shape_label"]) == {"backward conical"}
