"""Fuzz set of bad inputs for the command line and bearing files: wrong
types, NaN/inf, extremes, unknown tables and keys, impossible geometry, odd paths.

Every input must end in a result (exit 0), a solver failure that says so (exit 1) or one line
naming the parameter, the value and the rule (exit 2) — never a traceback.  The whole set
(~170 inputs) is in the slow tier; a fast subset (every kind of input once) runs by default.
Study files have their own fuzz set (helper "store").
"""
from __future__ import annotations

from pathlib import Path

import pytest

from gfbopt import cli
from gfbopt.errors import ParameterError
from gfbopt.inputs import load_bearing

ROOT = Path(__file__).resolve().parents[2]
RUSCITTO = ROOT / "problems" / "bearings" / "ruscitto.toml"
GEOMETRY = RUSCITTO.read_text().split("[model]")[0]
#: the coarsest grid gfbopt accepts: an input that passes validation solves in milliseconds
GRID = ["--grid", "12x4"]

BAD_VALUES = {"text": '"big"', "bool": "true", "nan": "nan", "inf": "inf", "-inf": "-inf",
              "zero": "0.0", "negative": "-1.0", "tiny": "1e-300", "huge": "1e300",
              "huge_int": "1" + "0" * 400, "list": "[1.0, 2.0]", "table": "{ a = 1 }"}
BEARING_KEYS = ("radius", "length", "radial_clearance", "bump_pitch", "bump_half_length",
                "bump_thickness", "bump_youngs_modulus", "top_foil_youngs_modulus",
                "poisson_ratio", "top_foil_thickness", "viscosity", "ambient_pressure")


def _replace(key: str, value: str) -> str:
    lines = []
    for line in GEOMETRY.splitlines():
        if line.split("=")[0].strip() == key:
            line = f"{key} = {value}"
        lines.append(line)
    return "\n".join(lines) + "\n"


def _bearing_cases() -> dict:
    cases = {}
    for key in BEARING_KEYS:
        for name, value in BAD_VALUES.items():
            cases[f"{key}={name}"] = _replace(key, value)
    model = {"film": ['"open"', "1", "nan"], "seam_angle_deg": ["360.0", "-1.0", "nan",
                                                                '"north"', "1e308", "true"],
             "foil": ['"elastic"', "[1]"], "deflection_law": ['"median"'],
             "loss_factor": ["-0.1", "2.0", "nan", "inf", '"0.2"']}
    for key, values in model.items():
        for k, value in enumerate(values):
            cases[f"model.{key}#{k}"] = GEOMETRY + f"[model]\n{key} = {value}\n"
    cases.update({
        "misspelt [modle]": GEOMETRY + '[modle]\nfilm = "periodic"\n',
        "unknown [bearings]": GEOMETRY.replace("[bearing]", "[bearings]"),
        "unknown top-level key": "flim = 1\n" + GEOMETRY,
        "misspelt key radious": GEOMETRY.replace("radius =", "radious ="),
        "model key misspelt": GEOMETRY + '[model]\nflim = "seam"\n',
        "model not a table": GEOMETRY.replace("[bearing]", 'model = "seam"\n[bearing]'),
        "bearing not a table": "bearing = 3\n",
        "missing [bearing]": 'source = "x"\n',
        "empty file": "",
        "not TOML": "radius == 3 [[\n",
        "deep nesting": "x = " + "[" * 3000 + "]" * 3000 + "\n",
        "bump thicker than pitch": _replace("bump_thickness", "5e-3"),
        "2 l0 > s": _replace("bump_half_length", "3e-3"),
        "clearance above c/R": _replace("radial_clearance", "1e-3"),
        "L/D above 10": _replace("length", "0.5"),
        "pitch above pi R": _replace("bump_pitch", "0.07"),
        "periodic film with seam angle": GEOMETRY + '[model]\nfilm = "periodic"\n'
                                                    "seam_angle_deg = 90.0\n",
        "max_film with periodic": GEOMETRY + '[model]\nfilm = "periodic"\n'
                                             'seam_angle_deg = "max_film"\n',
        "rigid with loss factor": GEOMETRY + '[model]\nfoil = "rigid"\nloss_factor = 0.2\n',
        "beam with local law": GEOMETRY + '[model]\nfoil = "beam"\ndeflection_law = "local"\n',
        "binary junk": "\x00\x01\x02\xff",
        "name a number": _replace("name", "3"),
        "notes a table": "notes = { a = 1 }\n" + GEOMETRY,
    })
    return cases


BEARING_CASES = _bearing_cases()
#: values that are legitimate (accepted, the answer follows): ν = 0 (e.g. cork), ν = 1e-300
VALID = {"poisson_ratio=zero", "poisson_ratio=tiny"}
#: one bearing case of every kind (default tier)
FAST_BEARING = ("radius=text", "radial_clearance=tiny", "viscosity=nan", "poisson_ratio=huge",
                "bump_thickness=huge_int", "model.seam_angle_deg#0", "misspelt [modle]",
                "unknown top-level key", "deep nesting", "bump thicker than pitch",
                "2 l0 > s", "binary junk")


def _check_bearing(tmp_path: Path, name: str) -> None:
    path = tmp_path / "b.toml"
    text = BEARING_CASES[name]
    if name == "binary junk":
        path.write_bytes(text.encode("latin-1"))
    else:
        path.write_text(text)
    try:
        load_bearing(path)
    except ParameterError as exc:
        assert "\n" not in str(exc) and str(exc).startswith(("b.toml", "file")), str(exc)
        return
    except Exception as exc:                             # noqa: BLE001 - the point of it
        pytest.fail(f"{name}: {type(exc).__name__}: {exc}")
    assert name in VALID, f"{name}: accepted"


@pytest.mark.parametrize("name", FAST_BEARING)
def test_bad_bearing_file_fast(tmp_path, name):
    _check_bearing(tmp_path, name)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(set(BEARING_CASES) - set(FAST_BEARING)))
def test_bad_bearing_file(tmp_path, name):
    _check_bearing(tmp_path, name)


def test_misspelt_model_table_says_did_you_mean(tmp_path):
    """0.2.0 ignored `[modle]` silently (the stated film replaced by the default)."""
    path = tmp_path / "b.toml"
    path.write_text(BEARING_CASES["misspelt [modle]"])
    with pytest.raises(ParameterError, match=r"^b.toml: modle = '…': is not a table of a "
                       r"bearing file \(did you mean 'model'\?\)"):
        load_bearing(path)


# ------------------------------------------------------------------ command-line flags
ND = ["--eccentricity", "0.4", "--bearing-number", "2", "--compliance", "1", *GRID]
SI = ["--bearing", str(RUSCITTO), "--speed-rpm", "30000", "--load-newton", "20", *GRID]
NUMBERS = ("nan", "inf", "-inf", "1e308", "-1e308", "0", "-1", "abc", "")
FLAGS = {
    "static": ND, "linear": ND, "orbit": [*ND, "--mass", "2", "--revolutions", "0.5"],
    "critical-mass": ND, "stability": ["--bearing", str(RUSCITTO), "--rotor-mass-kg", "2",
                                       "--load-newton", "20", "--speed-rpm", "30000", *GRID],
}
NUMERIC = {
    "static": ("--eccentricity", "--bearing-number", "--compliance", "--length-ratio",
               "--seam-angle", "--time-limit"),
    "linear": ("--whirl-ratio", "--loss-factor", "--mass"),
    "orbit": ("--mass", "--revolutions", "--kick", "--time-step", "--stages",
              "--max-steps"),
    "critical-mass": ("--tolerance", "--batch", "--revolutions"),
    "stability": ("--rotor-mass-kg", "--load-newton", "--speed-rpm", "--loss-factor",
                  "--frequency-hz", "--max-memory-gb"),
}


def _flag_cases() -> dict:
    cases = {}
    for command, flags in NUMERIC.items():
        for flag in flags:
            for value in NUMBERS:
                args = [a for a in FLAGS[command]]
                if flag in args:
                    i = args.index(flag)
                    args[i + 1] = value
                else:
                    args += [flag, value]
                if command == "static" and flag == "--seam-angle":
                    args += ["--film", "seam"]
                cases[f"{command} {flag} {value!r}"] = [command, *args]
    cases.update({
        "grid 2000x2000": ["static", *ND[:-2], "--grid", "2000x2000"],
        "grid text": ["static", *ND[:-2], "--grid", "big"],
        "grid 7x3": ["static", *ND[:-2], "--grid", "7x3"],
        "csv into a missing folder": ["stability", *FLAGS["stability"], "--csv",
                                      "/nonexistent/dir/k.csv"],
        "csv is a directory": ["stability", *FLAGS["stability"], "--csv", "/tmp"],
        "plot into a missing folder": ["orbit", *FLAGS["orbit"], "--plot", "/nonexistent/o.png"],
        "bearing file missing": ["stability", "--bearing", "/nonexistent.toml",
                                 "--rotor-mass-kg", "2", "--speed-rpm", "30000"],
        "bearing is a directory": ["stability", "--bearing", "/tmp", "--rotor-mass-kg", "2",
                                   "--speed-rpm", "30000"],
        "top foil coefficient 1e308": ["static", *ND, "--foil", "beam",
                                       "--top-foil-coefficient", "1e308"],
        "SI static": ["static", *SI, "--eccentricity", "0.5"],
        "orbit mass with bearing": ["orbit", *SI, "--mass", "2"],
        "unknown command": ["whirl"],
        "unknown flag": ["static", *ND, "--eccentricty", "0.4"],
    })
    return cases


FLAG_CASES = _flag_cases()
FAST_FLAGS = ("static --eccentricity 'nan'", "orbit --revolutions '1e308'",
              "orbit --time-step '0'", "critical-mass --batch '1e308'",
              "stability --speed-rpm '-inf'", "stability --max-memory-gb '0'",
              "grid 2000x2000", "csv into a missing folder", "top foil coefficient 1e308",
              "unknown flag")


def _check_flags(capsys, name: str) -> None:
    try:
        code = cli.main(FLAG_CASES[name])
    except SystemExit as exc:                       # argparse: one line, exit 2
        code = exc.code
    except Exception as exc:                         # noqa: BLE001 - the point of it
        pytest.fail(f"{name}: {type(exc).__name__}: {exc}")
    err = capsys.readouterr().err
    assert code in (0, 1, 2), (name, code)
    assert "Traceback" not in err
    if code == 2:
        last = err.strip().splitlines()[-1]
        assert last.startswith("gfbopt: error:") or "error:" in last, (name, err)
        assert len([line for line in err.splitlines() if "error" in line]) == 1, (name, err)


@pytest.mark.parametrize("name", FAST_FLAGS)
def test_bad_flags_fast(capsys, name):
    _check_flags(capsys, name)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(set(FLAG_CASES) - set(FAST_FLAGS)))
def test_bad_flags(capsys, name):
    _check_flags(capsys, name)


def test_the_set_has_the_stated_breadth():
    assert len(BEARING_CASES) + len(FLAG_CASES) >= 150
    assert set(FAST_BEARING) <= set(BEARING_CASES) and set(FAST_FLAGS) <= set(FLAG_CASES)
