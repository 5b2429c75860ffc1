"""Gaps in the Campbell diagram's tracks (gfbopt.rotor.tracking.stitch): a mode whose damping
changes more than its frequency in one speed step went on as a new track and left a track of
one point, with a name of its own, in campbell.csv and the figure's legend.  Now the track
that ends is joined to the one that starts at the next speed when the join costs at most
MAX_COST with the jump of the damped natural frequency alone; a track still shorter than
MIN_POINTS is taken out and returned with its least join cost.

Synthetic modes of a rigid body (q at the centre of gravity, bearings at −0.035 and 0.065 m):
a cylindrical shape (both bearings in phase) and a conical one (in antiphase), MAC 0 between
them at the bearings; eigenvalues s per radian, so a mode on the half-speed line keeps its
whirl ratio 0.5 while its frequency in Hz grows with speed."""
import math
from types import SimpleNamespace

import numpy as np
import pytest

from gfbopt.rotor.modes import mac
from gfbopt.rotor.tracking import FREQUENCY_WEIGHT, MAX_COST, MIN_POINTS, cost, join_cost, orbit_vector, stitch

POSITIONS = (-0.035, 0.065)
CYLINDRICAL = np.array([1.0, -1j, 0.0, 0.0])
#: tilt about z = 0.015 m, midway: equal and opposite whirl at the bearings
CONICAL = np.array([-0.015, 0.015j, 1.0, -1j]) * 20


def _mode(whirl_ratio: float, log_decrement: float, vector) -> SimpleNamespace:
    s = complex(-log_decrement * whirl_ratio / (2 * math.pi), whirl_ratio)
    return SimpleNamespace(eigenvalue=s, vector=vector, log_decrement=log_decrement,
                           label="x", whirl_frequency_hz=math.nan)


def _omega(rpm: float) -> float:
    return rpm * math.pi / 30


def _track(points) -> list:
    """[(speed, mode, omega)] of (speed, whirl ratio, log decrement, vector) tuples."""
    return [(s, _mode(r, d, v), _omega(s)) for s, r, d, v in points]


def test_the_shapes_are_apart():
    assert mac(orbit_vector(_mode(0.5, 1, CYLINDRICAL), POSITIONS),
               orbit_vector(_mode(0.5, 1, CONICAL), POSITIONS)) == pytest.approx(0, abs=1e-12)


def test_a_damping_jump_no_longer_splits_a_mode():
    """The blower's case (7 speeds, 4,000 → 13,333 rpm): log decrement 3.1 → −0.05 on the
    half-speed line.  The step's own cost exceeds MAX_COST (the real part of s moved by half
    its frequency), the frequency-only join does not: the two tracks become one."""
    end = _track([(4000.0, 0.48, 3.13, CYLINDRICAL)])
    start = _track([(13333.3, 0.496, -0.05, CYLINDRICAL), (22666.7, 0.39, -1.18, CYLINDRICAL),
                    (32000.0, 0.33, -1.51, CYLINDRICAL)])
    s, m, w = start[0]
    assert cost(end, m, s, w, POSITIONS) > MAX_COST            # why the track broke
    assert join_cost(end, start, POSITIONS) < 0.2              # 4 × 3 % in frequency
    kept, dropped = stitch([end, start], [4000.0, 13333.3, 22666.7, 32000.0], POSITIONS)
    assert dropped == [] and len(kept) == 1 and len(kept[0]) == 4
    assert [p[0] for p in kept[0]] == [4000.0, 13333.3, 22666.7, 32000.0]


def test_two_broken_modes_are_joined_each_to_its_own_shape():
    """Two modes at one frequency broken at the same step: the optimal assignment pairs each
    end with the start of its shape (frequency cannot tell them apart, the MAC can); a third
    mode starting there (another frequency) stays a track of its own."""
    ends = [_track([(4000.0, 0.48, 3.1, CYLINDRICAL)]), _track([(4000.0, 0.49, 1.8, CONICAL)])]
    starts = [_track([(13333.3, 0.49, -0.1, CONICAL), (22666.7, 0.44, -1.0, CONICAL)]),
              _track([(13333.3, 0.50, -0.05, CYLINDRICAL), (22666.7, 0.39, -1.2, CYLINDRICAL)]),
              _track([(13333.3, 0.85, 1.4, CONICAL), (22666.7, 0.48, 1.3, CONICAL)])]
    kept, dropped = stitch(ends + starts, [4000.0, 13333.3, 22666.7], POSITIONS)
    assert dropped == [] and len(kept) == 3
    by_shape = {(k[0][1].vector is CYLINDRICAL, len(k)) for k in kept}
    assert by_shape == {(True, 3), (False, 3), (False, 2)}
    for k in kept:                              # no track changes shape along itself
        assert all(p[1].vector is k[0][1].vector for p in k)


def test_a_root_found_at_one_speed_only_is_taken_out_and_stated():
    """A root at the middle speed where every track already has a mode continues no track:
    it is returned as dropped (join cost inf: no track lacks that speed), not left as a
    one-point track; MIN_POINTS is 2, so no line of one point is drawn."""
    assert MIN_POINTS == 2
    a = _track([(s, 0.5, 1.0, CYLINDRICAL) for s in (4000.0, 8000.0, 12000.0)])
    b = _track([(s, 0.9, 0.5, CONICAL) for s in (4000.0, 8000.0, 12000.0)])
    lone = _track([(8000.0, 0.7, 2.5, CONICAL)])
    kept, dropped = stitch([a, lone, b], [4000.0, 8000.0, 12000.0], POSITIONS)
    assert len(kept) == 2 and all(len(k) == 3 for k in kept)
    assert len(dropped) == 1 and dropped[0][0] == lone and dropped[0][1] == math.inf


def test_an_unrelated_mode_starting_where_another_ends_is_not_joined():
    """A mode leaving at 8,000 rpm at whirl ratio 0.5 and another entering at 12,000 rpm at
    2.0 (another shape): the frequency jump alone costs more than MAX_COST; both stay tracks
    (two points each).  The same entering mode found at one speed only is dropped with its
    least join cost, the lesser of the two directions: forwards, the ending track's
    prediction (whirl ratio 0.5 at 12,000 rpm: the track is on the half-speed line) against
    2.0 is a jump of 3 (cost 4 × 3 + 1 − MAC = 13); backwards, from one point, the nearer
    hypothesis (the same whirl ratio, 2.0 at 8,000 rpm) against 0.5 there is a jump of 0.75
    (cost 4 × 0.75 + 1 = 4).  A point two speeds after the end joins nothing (inf)."""
    leaving = _track([(4000.0, 0.5, 1.0, CYLINDRICAL), (8000.0, 0.5, 1.0, CYLINDRICAL)])
    entering = _track([(12000.0, 2.0, 0.1, CONICAL), (16000.0, 2.0, 0.1, CONICAL)])
    kept, dropped = stitch([leaving, entering], [4000.0, 8000.0, 12000.0, 16000.0],
                           POSITIONS)
    assert len(kept) == 2 and not dropped
    lone = _track([(12000.0, 2.0, 0.1, CONICAL)])
    kept, dropped = stitch([leaving, lone], [4000.0, 8000.0, 12000.0, 16000.0], POSITIONS)
    assert len(kept) == 1 and len(dropped) == 1
    assert dropped[0][1] == pytest.approx(FREQUENCY_WEIGHT * 0.75 + 1.0, rel=1e-9)
    far = _track([(16000.0, 0.5, 1.0, CYLINDRICAL)])       # two speeds after the end
    kept, dropped = stitch([leaving, far], [4000.0, 8000.0, 12000.0, 16000.0], POSITIONS)
    assert len(kept) == 1 and dropped[0][1] == math.inf
