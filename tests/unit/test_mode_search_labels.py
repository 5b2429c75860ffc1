"""A mode whose shape class first appears along the speed line already unstable (the class of
an unstable mode changes, e.g. conical → mixed with structural damping: measured on the study
rotor at η = 0.25, 36 × 10, between 32 and 40 krpm) has no onset of its own: the search says
so instead of asking Brent's method for a bracket that does not exist (it raised before)."""
import math
from types import SimpleNamespace

import pytest

from gfbopt.rotor.mode_search import APPEARS_UNSTABLE, ONSET, mode_onset


def _crossing(label, mu, whirl=0.49):
    return SimpleNamespace(label=label, inertia_scale=mu, whirl_ratio=whirl,
                           whirl_frequency_hz=100.0, shape={}, note="")


class Line:
    """A speed line given by its crossings at a few speeds, with the real line's rules for
    following a mode (same label, nearest whirl, any label when none has it)."""

    def __init__(self, table, interpolate=None):
        self.table, self.interpolate = table, interpolate

    def crossings(self, speed):
        if speed in self.table:
            return self.table[speed]
        return self.interpolate(speed)

    def follow(self, speed, label, whirl):
        found = self.crossings(speed) or []
        same = [c for c in found if c.label == label] or found
        return min(same, key=lambda c: abs(c.whirl_ratio - whirl), default=None)

    def margin(self, speed, label, whirl):
        c = self.follow(speed, label, whirl)
        return 1.0 if c is None else (c.inertia_scale - 1) / (c.inertia_scale + 1)


def test_a_class_appearing_unstable_has_no_onset_of_its_own():
    line = Line({30000.0: [_crossing("forward conical", 0.15)],
                 40000.0: [_crossing("forward mixed", 0.10)]})
    m = mode_onset(line, [30000.0, 40000.0], "forward mixed", 1e-6)
    assert m.status == APPEARS_UNSTABLE
    assert math.isnan(m.onset_speed_rpm)
    assert "30,000 and 40,000 rpm" in m.note and "0.1" in m.note


def test_a_class_appearing_where_the_others_are_stable_is_still_refined():
    """No crossing of the class at the stable end, and the others stable there: an ordinary
    bracket (μ_c through 1 between the speeds), found by the refinement."""
    def interpolate(speed):           # μ_c = 2 at 30 krpm falling linearly in ln N to 0.5
        t = math.log(speed / 30000.0) / math.log(40000.0 / 30000.0)
        return [_crossing("forward mixed", 2.0 ** (1 - 2 * t))]

    line = Line({30000.0: [_crossing("forward conical", 2.0)],
                 40000.0: interpolate(40000.0)}, interpolate)
    m = mode_onset(line, [30000.0, 40000.0], "forward mixed", 1e-9)
    assert m.status == ONSET
    # μ_c = 1 at t = 1/2: N = 30000 (4/3)^(1/2)
    assert m.onset_speed_rpm == pytest.approx(30000.0 * (4 / 3) ** 0.5, rel=1e-6)


# ------------------------------------------------------------ names of the Campbell tracks
def _mode(label, decrement, hz):
    return SimpleNamespace(label=label, log_decrement=decrement, whirl_frequency_hz=hz)


def _onset(label, speed, hz, status=ONSET):
    return SimpleNamespace(label=label, onset_speed_rpm=speed, whirl_frequency_hz=hz,
                           status=status)


def test_tracks_take_the_onsets_names_one_to_one_and_no_two_alike():
    """Two tracks lose their damping in one diagram interval, at nearly one frequency (the
    5 kg blower at 24 × 8): the first to lose it is the first onset's mode, whatever shape
    its rows have there; the other tracks of a shape class already named are numbered."""
    from gfbopt.rotor.tracking import name_tracks

    speeds = (10000.0, 13000.0, 16000.0)
    first = [(s, _mode("forward cylindrical", d, f)) for s, d, f in
             zip(speeds, (0.4, -0.2, -0.6), (93.0, 112.0, 127.0))]     # zero at 12,000
    second = [(s, _mode(lab, d, f)) for s, lab, d, f in
              zip(speeds, ("forward cylindrical", "forward mixed", "forward conical"),
                  (0.8, -0.1, -0.5), (96.0, 108.0, 116.0))]          # zero at 12,667
    stable = [(s, _mode("forward cylindrical", 1.0, 230.0)) for s in speeds]
    lone = [(s, _mode("backward conical", 1.5, 140.0)) for s in speeds]
    onsets = [_onset("forward conical", 12050.0, 103.0),
              _onset("forward cylindrical", 12700.0, 106.0),
              _onset("forward mixed", math.nan, 80.0, status="stable over the range")]
    names = name_tracks([first, second, stable, lone], onsets)
    assert [n for n, _ in names] == ["forward conical", "forward cylindrical",
                                     "forward cylindrical (2)", "backward conical"]
    assert names[0][1] == pytest.approx(12000.0) and names[1][1] == pytest.approx(12666.67,
                                                                                  rel=1e-6)
    assert math.isnan(names[2][1])
    # an onset no track matches (its frequency is 30 % off) keeps its name to itself
    far = [_onset("forward conical", 12050.0, 150.0)]
    names = name_tracks([first, [(s, _mode("forward conical", 1.0, 300.0)) for s in speeds]],
                        far)
    assert [n for n, _ in names] == ["forward cylindrical", "forward conical (2)"]
