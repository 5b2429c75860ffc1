"""Campbell diagram of the study rotor (gfbopt.rotor.tracking): modes tracked by continuity over
speed, and the tracks that lose their damping named as — and crossing zero next to — the
matched-whirl onsets of the same modes.  Coarse grid (36 × 10) and 7 speeds around the two
onsets: the comparison is between two routes on the same discrete bearings."""
import math
from pathlib import Path

import numpy as np
import pytest

from gfbopt.inputs import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.diagrams import campbell_diagram
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine, rotor_onsets

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def diagram():
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    line = SpeedLine(resolve_rotor(system, Grid(36, 10)))
    onsets = rotor_onsets(system, (9000.0, 16000.0), line=line, show_progress=False)
    table = campbell_diagram(line, list(np.linspace(9000.0, 16000.0, 7)),
                             show_progress=False, onsets=onsets.modes).table
    return onsets, table


def test_tracks_are_continuous(diagram):
    """Every track has one mode per speed, and its eigenvalue per second moves by less than a
    fifth of itself per step (steps of 1,167 rpm; a jump to another mode's line would be a
    change of ≥ 30 % here: the modes are at 90–300 Hz)."""
    _, table = diagram
    for _, part in table.groupby("mode"):
        assert part["speed_rpm"].is_unique
        s = (part["growth_rate_per_s"] + 2j * np.pi * part["whirl_frequency_hz"]).to_numpy()
        assert np.all(np.abs(np.diff(s)) <= 0.2 * np.abs(s[:-1]))
    # the four rigid-body modes (forward/backward, cylindrical/conical) at every speed
    assert table.groupby("speed_rpm")["mode"].nunique().min() >= 4


def test_tracks_losing_damping_carry_the_onset_labels(diagram):
    """Each matched-whirl onset in the range has exactly one track named by its label whose log
    decrement falls through zero in the diagram interval holding the onset (the interval is
    1,167 rpm wide: linear interpolation of the log decrement puts the zero within it)."""
    onsets, table = diagram
    found = [m for m in onsets.modes if math.isfinite(m.onset_speed_rpm)]
    assert {m.label for m in found} == {"forward conical", "forward cylindrical"}
    for m in found:
        tracks = table[(table["track_label"] == m.label) & table["track_zero_rpm"].notna()]
        assert tracks["mode"].nunique() == 1
        zero = tracks["track_zero_rpm"].iloc[0]
        assert abs(zero - m.onset_speed_rpm) <= 7000.0 / 6
