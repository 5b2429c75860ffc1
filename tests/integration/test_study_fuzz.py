"""Study-file fuzz set: about 125 broken or extreme study files —
wrong types, NaN/inf, extremes, unknown and misspelt keys, paths, names, sizes, malformed
TOML — each run through ``gfbopt run`` in this process.  Every one must end as an answer
(exit 0 or 1) or one ``gfbopt: error:`` line with exit 2; an exception escaping ``main`` (a
traceback for the user) fails the test and names the input.

The whole set is in the slow tier (most files are refused in milliseconds, the valid ones
run a 1-3 point sweep on a 12x4 grid); every fifth input runs in the default tier."""
from __future__ import annotations

import contextlib
import io
import math
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

STATIC = {
    "kind": "sweep", "title": "fuzz static", "source": "test", "analysis": "static",
    "grid": "12x4", "chunk_size": 2, "batch_rows": 4, "min_success_fraction": 0.0,
    "model": {"foil": "simple"}, "fixed": {"length_ratio": 1.0},
    "sampling": {"method": "lhs", "n": 2, "seed": 5, "variables": [
        {"name": "bearing_number", "low": 0.5, "high": 3.0},
        {"name": "eccentricity", "low": 0.2, "high": 0.7}]},
}
ONSET = {
    "kind": "sweep", "title": "fuzz onset", "source": "test", "analysis": "onset_speed",
    "grid": "12x4", "bearing": "bearing.toml",
    "fixed": {"rotor_mass_kg": 2.0, "speed_low_rpm": 9000.0, "speed_high_rpm": 15000.0},
    "sampling": {"method": "list", "variables": [
        {"name": "radial_clearance", "values": [3.0e-5]}]},
}
TABLE = {
    "kind": "static_table", "title": "fuzz table", "source": "test", "grid": "12x4",
    "references": ["yang"], "model": {"foil": "rigid", "film": "periodic"},
    "rows": [{"bearing_number": 0.6, "eccentricity": 0.2,
              "published": {"yang": {"load": 0.1806}}}],
    "comparisons": [{"variant": "default", "reference": "yang",
                     "tolerance": {"load": 0.5}}],
}

BAD_VALUES = ["text", True, [1.0, 2.0], {"a": 1}, math.nan, math.inf, -math.inf, 1e308,
              -1e308, 1e-300, 0, -1, 2 ** 63 - 1]


def _with(base: dict, path: tuple, value) -> dict:
    data = _copy(base)
    target = data
    for key in path[:-1]:
        target = target[key]
    if value is _DELETE:
        target.pop(path[-1], None)
    else:
        target[path[-1]] = value
    return data


def _copy(value):
    if isinstance(value, dict):
        return {k: _copy(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_copy(v) for v in value]
    return value


_DELETE = object()


def _cases() -> list:
    cases = []

    def add(label, data=None, text=None):
        cases.append((label, data, text))

    for key in ("n", "seed"):
        for value in BAD_VALUES:
            add(f"sampling.{key}={value!r}", _with(STATIC, ("sampling", key), value))
    for key in ("chunk_size", "batch_rows", "min_success_fraction", "max_points"):
        for value in ("x", -1, 0, 10 ** 12, math.nan):
            add(f"{key}={value!r}", _with(STATIC, (key,), value))
    for value in BAD_VALUES[:9]:
        add(f"fixed.length_ratio={value!r}", _with(STATIC, ("fixed", "length_ratio"), value))
        add(f"variable.low={value!r}", _with(STATIC, ("sampling", "variables", 0, "low"), value))
    for key, value in (("rotor_mass_kg", -2.0), ("rotor_mass_kg", 0.0),
                       ("rotor_mass_kg", math.inf), ("speed_low_rpm", 20000.0),
                       ("speed_high_rpm", -1.0), ("load_newton", -5.0),
                       ("loss_factor", -0.1), ("radial_clearance", 1e-300),
                       ("bump_pitch", 0.0), ("speed_low_rpm", "fast")):
        add(f"onset fixed.{key}={value!r}", _with(ONSET, ("fixed", key), value))
    for name in ("..", "../../x", "/tmp/abs", "a/b", "", ".", " ", "x" * 300, "ok-name",
                 "naïve", 3, ["a"]):
        add(f"name={name!r}", _with(STATIC, ("name",), name))
    for grid in ("2000x2000", "0x0", "axb", "72x21", "12x4x3", "", 72, "-12x4", "1e9x4"):
        add(f"grid={grid!r}", _with(STATIC, ("grid",), grid))
    for bearing in ("../../etc/passwd", "/dev/null", "missing.toml", ".", "", 5,
                    "bad_bearing.toml", "bearing.toml"):
        add(f"bearing={bearing!r}", _with(ONSET, ("bearing",), bearing))
    add("bearing= in a static sweep", _with(STATIC, ("bearing",), "bearing.toml"))
    for key in ("kind", "title", "source", "analysis", "sampling"):
        add(f"missing {key}", _with(STATIC, (key,), _DELETE))
    for key, value in (("modle", {"foil": "simple"}), ("samplng", {}), ("extra", 1),
                       ("Notes", ["x"]), ("chunksize", 4)):
        add(f"unknown key {key}", _with(STATIC, (key,), value))
    for method in ("grid", "", "LHS", 3):
        add(f"method={method!r}", _with(STATIC, ("sampling", "method"), method))
    add("factorial levels 1000", _with(_with(STATIC, ("sampling", "method"), "factorial"),
                                       ("sampling", "levels"), 1000))
    add("saltelli huge", _with(_with(STATIC, ("sampling", "method"), "saltelli"),
                               ("sampling", "n"), 10 ** 15))
    add("variable unknown", _with(STATIC, ("sampling", "variables", 0, "name"), "bearng"))
    add("variable low>high", _with(STATIC, ("sampling", "variables", 0, "high"), 0.1))
    add("variable log low 0", _with(_with(STATIC, ("sampling", "variables", 0, "scale"), "log"),
                                    ("sampling", "variables", 0, "low"), 0.0))
    add("variable values empty", _with(STATIC, ("sampling", "variables", 0),
                                       {"name": "bearing_number", "values": []}))
    add("variables duplicated", _with(STATIC, ("sampling", "variables"),
                                      [STATIC["sampling"]["variables"][0]] * 2))
    add("variables not tables", _with(STATIC, ("sampling", "variables"), [1, 2]))
    add("both eccentricity and load", _with(STATIC, ("fixed", "load"), 0.5))
    add("model foil unknown", _with(STATIC, ("model", "foil"), "steel"))
    add("model seam angle 400", _with(STATIC, ("model", "seam_angle_deg"), 400.0))
    add("sensitivity without saltelli", _with(STATIC, ("sensitivity_outputs",), ["load"]))
    add("valid static sweep", _copy(STATIC))
    add("valid onset sweep", _copy(ONSET))
    add("valid static table", _copy(TABLE))
    for key, value in (("rows", []), ("rows", [{"eccentricity": 0.2}]),
                       ("references", "yang"), ("comparisons", [{"reference": "nobody",
                                                                 "tolerance": {"load": 1}}])):
        add(f"table {key}={value!r}", _with(TABLE, (key,), value))
    add("not TOML", text="kind = \n[[[")
    add("binary", text="\x00\x01\x02")
    add("deep nesting", text="x = " + "[" * 100_000 + "]" * 100_000 + "\n")
    add("empty file", text="")
    add("kind not a string", text="kind = 5\n")
    return cases


CASES = _cases()
FAST = CASES[::5]


def toml_value(v) -> str:
    """One TOML value (floats written so that NaN/inf survive; used by the other fuzz sets)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f'"{k}" = {toml_value(x)}' for k, x in v.items()) + "}"
    raise TypeError(v)


def _toml(data: dict) -> str:
    """A minimal TOML writer for the fuzz inputs."""
    return "\n".join(f'"{k}" = {toml_value(v)}' for k, v in data.items()) + "\n"


def _run(tmp_path: Path, label: str, data, text) -> tuple:
    from gfbopt.cli import main

    shutil.copy(ROOT / "problems" / "bearings" / "ruscitto.toml", tmp_path / "bearing.toml")
    (tmp_path / "bad_bearing.toml").write_text("[bearing]\nradius = -1\n[modle]\nx = 1\n")
    study = tmp_path / "fuzz.toml"
    study.write_text(text if text is not None else _toml(data), encoding="utf-8",
                     errors="surrogateescape")
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = main(["run", str(study), "--workers", "1", "--results",
                           str(tmp_path / "results")])
        except SystemExit as exc:          # argparse
            status = exc.code
    return status, err.getvalue()


def _check(tmp_path, label, data, text):
    try:
        status, err = _run(tmp_path, label, data, text)
    except Exception as exc:  # noqa: BLE001 - the point of the test
        message = f"{label}: traceback {type(exc).__name__}: {exc}"[:500]
    else:
        message = None
    if message:                  # outside the except: no 1000-frame context to render
        pytest.fail(message)
    assert status in (0, 1, 2), (label, status, err)
    if status == 2:
        errors = [line for line in err.splitlines() if line.startswith("gfbopt: error:")]
        assert len(errors) == 1, (label, err)


@pytest.mark.parametrize("label,data,text", FAST, ids=[c[0][:60] for c in FAST])
def test_fast_subset_of_study_files_ends_without_a_traceback(tmp_path, label, data, text):
    _check(tmp_path, label, data, text)


@pytest.mark.slow
@pytest.mark.parametrize("label,data,text", CASES, ids=[c[0][:60] for c in CASES])
def test_every_fuzzed_study_file_ends_without_a_traceback(tmp_path, label, data, text):
    _check(tmp_path, label, data, text)


def test_the_fuzz_set_has_the_breadth_the_issue_asks_for():
    assert len(CASES) >= 125
    assert len({c[0] for c in CASES}) == len(CASES)
