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
