"""The rotor command's text reports read JSON fields that may be null (NaN in the result):
an imbalance response with no stable speed below a peak, an orbit's whirl whose change over
the last window was not measured — a line of text, never a TypeError."""
from __future__ import annotations

from gfbopt.cli.rotor import _imbalance_lines
from gfbopt.cli.rotor_time import _whirl
from gfbopt.transient.rotor_result import whirl_words


def test_imbalance_lines_with_null_fields():
    ir = {"peaks": {"A": {"peak_amplitude_um": 1.39, "peak_speed_rpm": 17892.0,
                          "above_first_onset": True, "largest_below_onset_um": None,
                          "largest_below_onset_rpm": None}},
          "unstable_from_rpm": None}
    lines = _imbalance_lines(ir)
    assert lines == ["  imbalance response peak at A: 1.39 µm at 17,892 rpm — where the rotor "
                     "is unstable, not physical"]
    ir["peaks"]["A"].update(largest_below_onset_um=1.33, largest_below_onset_rpm=12051.0)
    ir["unstable_from_rpm"] = 12282.0
    lines = _imbalance_lines(ir)
    assert "largest below the onset 1.33 µm at 12,051 rpm" in lines[0]
    assert lines[1].startswith("    above 12,282 rpm the rotor is unstable")


def test_whirl_words_with_an_unmeasured_change():
    b = {"limit_cycle_status": "growing", "limit_cycle_amplitude_um": 6.5,
         "limit_cycle_frequency_hz": 104.0, "limit_cycle_whirl_ratio": 0.5,
         "limit_cycle_settled": False, "limit_cycle_change": None}
    assert _whirl(b, whirl_words) == "whirl 6.5 µm at 104 Hz (0.500×, growing, not settled)"
    b["limit_cycle_change"] = 0.05
    assert _whirl(b, whirl_words) == whirl_words(b)
    assert "+5 % over the last window" in _whirl(b, whirl_words)
    assert _whirl({"limit_cycle_status": "none"}, whirl_words) == "no subsynchronous whirl"
