"""The two-bearing analyses on the flexible shaft (gfbopt.rotor.shaft, condensed by
gfbopt.rotor.condensed): a very stiff shaft (Young's modulus × 1e4) is the rigid rotor of the
same mass and inertias (problems/rotors/flexible_rotor.toml's shaft and disks; the rigid
rotor has the shaft's equivalent body and every position re-measured from its centre of
gravity): the onset and whirl frequency of every rigid-body mode within 1e-4; the real
shaft's analysis runs end to end (onset of every mode, Campbell diagram, imbalance
response) with its bending modes named as such.  Coarse grid (36 × 10): both sides are the
same discrete bearings."""
import copy
import math
from pathlib import Path

import pytest

from gfbopt.inputs.bearing_file import read_toml
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import rotor_from_dict
from gfbopt.rotor.condensed import MODES, CondensedStructure
from gfbopt.rotor.diagrams import campbell_diagram, imbalance_response
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine, rotor_onsets

FILE = Path(__file__).resolve().parents[2] / "problems" / "rotors" / "flexible_rotor.toml"
GRID = Grid(36, 10)
RANGE = (6000.0, 40000.0)


def _system(stiffening: float = 1.0):
    data = copy.deepcopy(read_toml(FILE))
    for element in data["shaft"]:
        element["youngs_modulus"] *= stiffening
    return rotor_from_dict(data, directory=FILE.parent, where=str(FILE))


def _rigid_twin(system):
    """The rigid rotor with the shaft's mass and inertias, positions from its CG."""
    data = copy.deepcopy(read_toml(FILE))
    cg, body = system.centre_of_gravity, system.body
    data.pop("shaft"), data.pop("disks")
    data["rotor"] = {"name": "rigid twin", "mass": body.mass,
                     "transverse_inertia": body.transverse_inertia,
                     "polar_inertia": body.polar_inertia}
    for key in ("bearings", "imbalance", "stations"):
        for row in data.get(key, []):
            row["position"] -= cg
    return rotor_from_dict(data, directory=FILE.parent, where=str(FILE))


def _onsets(system):
    rotor = resolve_rotor(system, GRID)
    line = SpeedLine(rotor)
    return rotor, line, rotor_onsets(system, RANGE, grid=GRID, line=line,
                                     show_progress=False, coarse_grid=None)


def test_a_very_stiff_shaft_is_the_rigid_rotor():
    """Loads, and every rigid-body mode's onset and whirl frequency, within 1e-4 (the
    issue's); no other mode (the stiff shaft's bending modes cross only beyond
    SHAFT_SCALE_LIMIT)."""
    stiff = _system(1e4)
    rigid = _rigid_twin(stiff)
    rs, _, a = _onsets(stiff)
    rr, _, b = _onsets(rigid)
    assert isinstance(rs.structure, CondensedStructure)
    for x, y in zip(rs.loads, rr.loads):
        assert x.magnitude == pytest.approx(y.magnitude, rel=1e-9)
    shaft = {m.label: m for m in a.modes}
    assert [m.label for m in b.modes if m.label not in shaft] == []
    for m in b.modes:
        s = shaft[m.label]
        assert s.status == m.status
        if math.isfinite(m.onset_speed_rpm):
            assert s.onset_speed_rpm == pytest.approx(m.onset_speed_rpm, rel=1e-4)
            assert s.whirl_frequency_hz == pytest.approx(m.whirl_frequency_hz, rel=1e-4)
    assert math.isfinite(b.onset_speed_rpm)
    # the stiff shaft's bending modes would whirl only with μ_c ~ 1e6: not reported
    # (matched_whirl.SHAFT_SCALE_LIMIT)
    assert [m.label for m in a.modes if m.label not in {x.label for x in b.modes}] == []


def test_the_flexible_rotor_runs_end_to_end():
    """Onsets of every mode, a Campbell diagram and the imbalance response on the 20-element
    shaft; its bending modes (near 800–900 Hz at 20,000 rpm) carry bending labels."""
    system = _system()
    rotor, line, result = _onsets(system)
    assert rotor.structure.size == 4 + MODES          # both bearing stations + held modes
    assert math.isfinite(result.onset_speed_rpm) and result.first_mode
    # the shaft's first bending mode has a threshold of its own (μ_c 8–43 from 17,000 to
    # 40,000 rpm: stable, it would whirl at half speed on a rotor 8 times heavier)
    bend = [m for m in result.modes if m.label == "forward bending 1"]
    assert bend and bend[0].status == "stable over the range"
    camp = campbell_diagram(line, (8000.0, 20000.0), show_progress=False,
                            onsets=result.modes)
    labels = set(camp.table["shape_label"])
    assert {"forward bending 1", "backward bending 1"} <= labels
    bending = camp.table[camp.table["shape_label"].str.contains("bending")]
    assert bending["whirl_frequency_hz"].min() > 500.0
    resp = imbalance_response(line, (10000.0,), show_progress=False, refine_peaks=False)
    assert set(resp.table["station"]) == {"A", "B", "motor"}
    assert (resp.table["amplitude_um"] > 0).all()


def test_the_comparison_without_gyroscopics_is_refused_for_a_shaft():
    """without_gyroscopics zeroes a rigid body's I_p; a shaft's gyroscopic terms come from its
    elements and disks, so it says so instead of returning the same rotor."""
    from gfbopt.errors import ParameterError
    from gfbopt.rotor.system import without_gyroscopics

    with pytest.raises(ParameterError, match="rigid rotor"):
        without_gyroscopics(_system())


def test_a_mode_first_found_above_every_onset_is_reported():
    """The onset search scans every mode over the whole range: the shaft's second to fourth
    bending tracks first appear (their μ_c falling below SHAFT_SCALE_LIMIT) at about 17,200,
    26,200 and 40,000 rpm, above the first scan speed at which both rigid-body (mixed) modes
    are unstable, and each is reported, stable over the range.  A scan that stopped at the
    first speed where every mode with an onset is unstable — as each one-bearing search stops
    at its own first unstable speed — would drop them: why the rotor's search costs more than
    the two one-bearing searches (benchmarks/bench_rotor_onset_ratio.py,
    ``coarse_scan_above_every_onset``)."""
    from gfbopt.rotor.system import ONSET, STABLE, scan_speeds

    _, _, result = _onsets(_system())
    onsets = [m.onset_speed_rpm for m in result.modes if m.status == ONSET]
    assert len(onsets) == 2
    every_unstable = min(s for s in scan_speeds(*RANGE) if s > max(onsets))
    first = {}
    for row in result.scan:
        label = row["track_label"]
        first[label] = min(first.get(label, math.inf), row["speed_rpm"])
    late = sorted(label for label, s in first.items() if s > every_unstable)
    assert late == ["forward bending 2", "forward bending 3", "forward bending 4"]
    status = {m.label: m.status for m in result.modes}
    assert all(status[label] == STABLE for label in late)
