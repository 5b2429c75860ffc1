"""``gfbopt export-ross`` and the ROSS coefficient-table file (gfbopt.rotor.ross_bridge).

The reader here does what ROSS 3.1 does without ROSS (``BearingElement.load``:
``ross.utils.load_data`` reads TOML or JSON by the suffix, takes the first table and passes
its keys to ``BearingElement(**keys)``, whose ``BearingCoefficient`` needs every table of
shape (len(speed), len(frequency)) on strictly increasing axes)."""
import contextlib
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

try:                                   # the standard library's reader (Python >= 3.11)
    import tomllib
except ImportError:                    # pragma: no cover - Python 3.10: its backport
    import tomli as tomllib

from gfbopt.cli import export_ross
from gfbopt.cli.common import Parser
from gfbopt.errors import GfboptError, ParameterError
from gfbopt.inputs import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.ross_bridge import NAMES, ZERO_COEFFICIENTS, bearing_tables, write_ross_table
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine

ROOT = Path(__file__).resolve().parents[2]
BLOWER = ROOT / "problems" / "rotors" / "blower.toml"
FLEX = ROOT / "problems" / "rotors" / "flexible_rotor.toml"
#: the parameters of ROSS 3.1's BearingElement.__init__ (ross/bearing_seal_element.py)
ROSS_INIT = {"n", "kxx", "cxx", "mxx", "kyy", "kxy", "kyx", "cyy", "cxy", "cyx", "myy", "mxy",
             "myx", "kzz", "czz", "mzz", "speed", "frequency", "tag", "n_link",
             "scale_factor", "color", "interpolation", "radial_clearance"}
COEFFICIENTS = set(NAMES) | set(ZERO_COEFFICIENTS)


def ross_like_load(path: Path) -> dict:
    """The first table of the file, checked as ROSS's BearingElement would take it."""
    with open(path, "rb") as f:
        data = json.load(f) if path.suffix == ".json" else tomllib.load(f)
    name, section = next(iter(data.items()))
    assert name.startswith("BearingElement_")
    assert set(section) <= ROSS_INIT and COEFFICIENTS <= set(section)
    speed, freq = np.asarray(section["speed"]), np.asarray(section["frequency"])
    assert np.all(np.diff(speed) > 0) and np.all(np.diff(freq) > 0)
    out = {"n": section["n"], "tag": section["tag"], "speed": speed, "frequency": freq}
    for key in COEFFICIENTS:
        out[key] = np.asarray(section[key], dtype=np.float64)
        assert out[key].shape == (speed.size, freq.size)
    return out


def _tables(rng):
    tables = {n: rng.normal(scale=1e6 if n[0] == "k" else 1e2, size=(3, 4)) for n in NAMES}
    tables["kxx"][0, 0] = 1.0e-300            # extremes of the float range survive
    tables["cyy"][2, 3] = -1.2345678901234567e+250
    tables["speed"] = np.array([1000.0, 2000.5, 3141.592653589793])
    tables["frequency"] = np.array([1e-3, 10.0, 100.0, 6283.185307179586])
    return tables


@pytest.mark.parametrize("suffix", [".toml", ".json"])
@pytest.mark.parametrize("tag", ["A", "journal 2 (aft)"])
def test_table_file_round_trips_bit_for_bit(tmp_path, suffix, tag):
    tables = _tables(np.random.default_rng(7))
    path = write_ross_table(tmp_path / f"b{suffix}", tables, 5, tag, 2e-5,
                            header=("a comment", "another — with unicode"))
    back = ross_like_load(path)
    assert back["n"] == 5 and back["tag"] == tag
    for key in ("speed", "frequency", *NAMES):
        assert np.array_equal(back[key], tables[key])      # identical, not approximately
    for key in ZERO_COEFFICIENTS:
        assert not back[key].any()


def test_bad_tables_are_refused(tmp_path):
    tables = _tables(np.random.default_rng(1))
    bad = dict(tables, speed=tables["speed"][::-1])
    with pytest.raises(ParameterError, match="speed = .*strictly increasing"):
        write_ross_table(tmp_path / "b.toml", bad, 0, "A")
    bad = dict(tables, kxy=np.where(tables["kxy"] > 0, np.nan, tables["kxy"]))
    with pytest.raises(ParameterError, match="kxy = .*finite 3 × 4"):
        write_ross_table(tmp_path / "b.toml", bad, 0, "A")


def _run(*argv):
    """``gfbopt export-ross …`` as gfbopt.cli.main runs it (exit 2 on bad input)."""
    parser = Parser(prog="gfbopt")
    export_ross.register(parser.add_subparsers(dest="command", required=True,
                                               parser_class=Parser))
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            args = parser.parse_args(["export-ross", *map(str, argv)])
            code = args.handler(args)
        except GfboptError as exc:
            print(f"gfbopt: error: {exc}", file=err)
            code = 2
        except SystemExit as exc:
            code = exc.code
    return code, out.getvalue(), err.getvalue()


def test_export_writes_each_bearings_tables_and_states_the_span(tmp_path):
    code, out, _ = _run(BLOWER, "--speed-range", 20000, 30000, "--speeds", 2,
                        "--frequency-range", 100, 300, "--frequencies", 3, "--grid", "36x10",
                        "--out", tmp_path / "ross")
    assert code == 0
    assert "ROSS extrapolates linearly outside this span" in out
    assert "speeds 20000–30000 rpm (2), whirl frequencies 100–300 Hz (3)" in out
    line = SpeedLine(resolve_rotor(load_rotor(BLOWER), Grid(36, 10)))
    for k, name in enumerate("AB"):
        back = ross_like_load(tmp_path / "ross" / f"bearing_{name}.toml")
        ref = bearing_tables(line, k, [20000.0, 30000.0], [100.0, 200.0, 300.0])
        assert back["n"] == (0, 2)[k] and back["tag"] == name   # nodes: A, CG, B
        assert np.array_equal(back["speed"], ref["speed"])
        for key in NAMES:
            assert np.array_equal(back[key], ref[key])
    assert back["frequency"][-1] == pytest.approx(2 * math.pi * 300, rel=1e-15)


def test_export_of_a_shaft_names_the_shaft_nodes(tmp_path):
    code, out, _ = _run(FLEX, "--speed-range", 20000, 30000, "--speeds", 2,
                        "--frequencies", 2, "--grid", "36x10", "--out", tmp_path,
                        "--json-format", "--json")
    assert code == 0
    report = json.loads(out)
    assert [f["node"] for f in report["files"]] == [3, 15]      # z = 0.06 and 0.30 m
    assert report["frequency_range_hz"] == pytest.approx([0.1 * 20000 / 60, 1.5 * 30000 / 60])
    assert "extrapolates" in report["extrapolation"] and report["few_points"]
    assert ross_like_load(tmp_path / "bearing_B.json")["n"] == 15


@pytest.mark.parametrize("argv, message", [
    (("--speeds", 1), "--speeds = 1: must be >= 2"),
    (("--frequency-range", 300, 100), "--frequency-range = [300.0, 100.0]: must be two"),
    (("--speed-range", 0, 100), "--speed-range = [0.0, 100.0]: must be two"),
])
def test_bad_options_exit_2_before_any_solve(tmp_path, argv, message):
    base = ["--speed-range", 20000, 30000, "--out", tmp_path]
    code, _, err = _run(BLOWER, *base, *argv)
    assert code == 2 and message in err and err.count("\n") == 1


def test_out_that_is_a_file_and_a_bad_rotor_exit_2(tmp_path):
    plain = tmp_path / "plain"
    plain.write_text("x")
    code, _, err = _run(BLOWER, "--speed-range", 20000, 30000, "--out", plain)
    assert code == 2 and "--out" in err and "is a file" in err
    bad = tmp_path / "bad.toml"
    bad.write_text(FLEX.read_text().replace("position = 0.30 ", "position = 0.52 ").replace(
        '"../bearings/ruscitto.toml"', json.dumps(str(ROOT / "problems" / "bearings"
                                                      / "ruscitto.toml"))))
    code, _, err = _run(bad, "--speed-range", 20000, 30000, "--out", tmp_path / "o")
    assert code == 2 and "bearings[2].position = 0.52: must lie on the shaft" in err
    assert not (tmp_path / "o").exists()
