"""A root of the blower's Campbell diagram found at one speed only is stated, not drawn
(gfbopt.rotor.tracking.stitch, gfbopt.rotor.diagrams.CampbellDiagram.dropped).

The blower at 24 × 8, 9 speeds over 4,000–60,000 rpm (steps of 7,000 rpm).  Before, the
table had two tracks of one point (measured): the forward cylindrical mode at 4,000 rpm
(31.8 Hz, log decrement 3.1), which went on as another track, and a root at 11,000 rpm
(194.0 Hz, log decrement 2.49, shape "forward conical") that no other speed finds.  Now the
first is joined to its mode's track (all 9 speeds, 31.8 → 226.4 Hz) and the second is left
out and stated with its speed, frequency and reason: at 11,000 rpm every track has its own
mode, so it continues none."""
import math
from pathlib import Path

import numpy as np
import pytest

from gfbopt.inputs import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.diagrams import campbell_diagram
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine
from gfbopt.rotor.tracking import MIN_POINTS

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def diagram():
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    line = SpeedLine(resolve_rotor(system, Grid(24, 8)))
    return campbell_diagram(line, list(np.linspace(4000.0, 60000.0, 9)), show_progress=False)


def test_no_track_of_one_point_and_the_lone_root_is_stated(diagram):
    table = diagram.table
    sizes = table.groupby("mode").size()
    assert sizes.min() >= MIN_POINTS
    assert len(sizes) == 5 and (sizes == 9).sum() == 4          # four modes at every speed
    assert len(diagram.dropped) == 1
    lone = diagram.dropped[0]
    assert lone["speed_rpm"] == pytest.approx(11000.0)
    assert lone["whirl_frequency_hz"] == pytest.approx(194.0, abs=0.5)
    assert lone["log_decrement"] == pytest.approx(2.49, abs=0.05)
    assert lone["reason"].startswith("found at 11,000 rpm only: ")
    assert "continues none" in lone["reason"]
    # it is in no row of the table
    at = table[np.isclose(table["speed_rpm"], 11000.0)]
    assert not np.isclose(at["whirl_frequency_hz"], lone["whirl_frequency_hz"],
                          rtol=1e-9).any()


def test_the_low_forward_modes_are_one_track_each(diagram):
    """The two forward modes on the half-speed line at 4,000 rpm (31.8 and 32.9 Hz) end at
    226.4 and 295.9 Hz at 60,000 rpm, as in the 20-speed diagram (results/rotor_blower)."""
    table = diagram.table
    first = table[table["speed_rpm"] == 4000.0].sort_values("whirl_frequency_hz")
    ends = []
    for mode in first["mode"].iloc[:2]:
        rows = table[table["mode"] == mode].sort_values("speed_rpm")
        assert len(rows) == 9
        ends.append(rows["whirl_frequency_hz"].iloc[-1])
    assert first["whirl_frequency_hz"].iloc[:2].tolist() == pytest.approx([31.8, 32.9],
                                                                          abs=0.1)
    assert ends == pytest.approx([226.4, 295.9], abs=0.5)
    assert math.isnan(diagram.frequency_limit_hz)                 # a rigid rotor
