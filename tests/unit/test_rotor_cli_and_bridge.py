"""gfbopt rotor on the command line: bad input is one line and exit 2 before any solve; the JSON
names the fields of the issue; the ROSS bridge's tables are the rotated impedances (ROSS itself
is an optional extra, and the test that builds a ROSS element skips when it is absent)."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from gfbopt.cli import main
from gfbopt.inputs import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.rigid import rotation
from gfbopt.rotor.ross_bridge import bearing_element, bearing_tables, ross_available
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine

ROOT = Path(__file__).resolve().parents[2]
BLOWER = ROOT / "problems" / "rotors" / "blower.toml"
BEARING = (ROOT / "problems" / "bearings" / "ruscitto.toml").as_posix()


def _file(tmp_path, body: str) -> str:
    path = tmp_path / "r.toml"
    path.write_text(body)
    return str(path)


_ROTOR = '[rotor]\nmass = {m}\ntransverse_inertia = 0.012\npolar_inertia = 0.002\n'
_BEARING = '[[bearings]]\nfile = "{f}"\nposition = {z}\n'


@pytest.mark.parametrize("text,expect", [
    (_ROTOR.format(m=0) + _BEARING.format(f=BEARING, z=-0.03) + _BEARING.format(f=BEARING, z=0.03),
     "rotor.mass = 0: must be > 0"),
    (_ROTOR.format(m=3) + _BEARING.format(f=BEARING, z=0.03) + _BEARING.format(f=BEARING, z=0.03),
     "bearings[2].position = 0.03: must differ"),
    (_ROTOR.format(m=3) + _BEARING.format(f=BEARING, z=0.03),
     "exactly two bearings are supported"),
    (_ROTOR.format(m=3) + _BEARING.format(f="missing.toml", z=-0.03)
     + _BEARING.format(f=BEARING, z=0.03), "bearings[1].file = 'missing.toml'"),
    (_ROTOR.format(m=3) + _BEARING.format(f=BEARING, z=-0.03) + _BEARING.format(f=BEARING, z=0.03)
     + "[[imbalance]]\nposition = 0.1\n", "imbalance[1].amount_kg_m (not given): is required"),
])
def test_bad_rotor_file_exits_2_with_one_line(tmp_path, capsys, text, expect):
    code = main(["rotor", _file(tmp_path, text), "--speed-range", "5000", "10000"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and expect in err and "r.toml" in err and "\n" not in err


def test_imbalance_response_without_planes_is_refused(tmp_path, capsys):
    text = _ROTOR.format(m=3) + _BEARING.format(f=BEARING, z=-0.03) + _BEARING.format(
        f=BEARING, z=0.05)
    code = main(["rotor", _file(tmp_path, text), "--speed-range", "5000", "10000",
                 "--imbalance-response"])
    err = capsys.readouterr().err
    assert code == 2 and "needs an imbalance: an [[imbalance]] plane" in err
    assert "--imbalance-plane" in err and "--imbalance-grade" in err


def test_json_carries_the_issue_fields(capsys):
    """A narrow range around the study rotor's first onset at 36 × 10 (≈ 12,150 rpm)."""
    code = main(["rotor", str(BLOWER), "--speed-range", "11000", "13500", "--grid", "36x10",
                 "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert out["first_mode"] == "forward conical"
    assert 11000 < out["onset_speed_rpm"] < 13500
    assert out["onset_whirl_frequency_hz"] == pytest.approx(
        out["modes"][0]["whirl_frequency_hz"], rel=1e-12)
    assert set(out["bearing_loads_newton"]) == {"A", "B"}
    # lever rule: A carries 65/100 of the weight (exact to round-off)
    assert out["bearing_loads_newton"]["A"] == pytest.approx(3.2 * 9.80665 * 0.65, rel=1e-12)
    assert {"label", "onset_speed_rpm", "whirl_frequency_hz", "shape"} <= set(out["modes"][0])
    assert "frame" in out["conventions"] and "source_commit" in out["provenance"]


def test_ross_tables_are_the_impedance_in_the_rotor_frame():
    """K = Re Z, C = Im Z/Ω of the bearing's impedance rotated to x–y: exact (same numbers)."""
    system = load_rotor(BLOWER)
    line = SpeedLine(resolve_rotor(system, Grid(36, 10)))
    tables = bearing_tables(line, 0, [20000.0], [100.0, 160.0])
    state = line.states(20000.0).states[0]
    omega = 20000.0 * math.pi / 30
    big = 2 * math.pi * 160.0
    rot = rotation(line.rotor.loads[0].direction_rad)
    z = rot @ state.impedance(big / omega) @ rot.T
    assert tables["kxy"][0, 1] == z[0, 1].real
    assert tables["cyy"][0, 1] == pytest.approx(z[1, 1].imag / big, rel=1e-15)
    assert tables["frequency"][1] == pytest.approx(big, rel=1e-15)
    assert np.all(tables["kxx"] > 0)


_ROSS, _WHY = ross_available()


@pytest.mark.skipif(not _ROSS, reason=_WHY)
def test_ross_bearing_element_takes_the_tables():  # pragma: no cover - needs the extra
    system = load_rotor(BLOWER)
    line = SpeedLine(resolve_rotor(system, Grid(36, 10)))
    tables = bearing_tables(line, 0, [10000.0, 20000.0], [50.0, 100.0, 200.0])
    element = bearing_element(0, tables)
    assert element.n == 0
