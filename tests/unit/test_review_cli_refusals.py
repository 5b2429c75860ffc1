"""The reviewer's refusals (gfbopt/cli): each names the flag typed, exit 2, before any solve —
``run --grid`` (not the study file's key), ``orbit --method bdf`` on a rubbing bearing (not
friction_coefficient), a missing value as '(not given)' with what to give (not ``= None``),
and an infinite number as 'must be finite' (not '(not NaN)')."""
from __future__ import annotations

from pathlib import Path

import pytest

from tests.cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
B = REPO / "problems" / "bearings"
FRICTION = str(B / "ruscitto_friction.toml")


def _refused(*args) -> str:
    out = run_cli(*args)
    assert out.returncode == 2, (out.returncode, out.stderr)
    assert out.stdout == ""
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1, out.stderr
    assert lines[0].startswith("gfbopt: error: ")
    return lines[0][len("gfbopt: error: "):]


def test_run_grid_names_the_flag():
    line = _refused("run", str(REPO / "problems" / "rotor_bearing_design.toml"), "--grid",
                    "24x8")
    assert line.startswith("--grid = '24x8': must be at least as fine as search_grid")
    assert "rotor_bearing_design.toml" in line       # the file whose grid it replaces


def test_orbit_method_bdf_on_friction_names_method():
    line = _refused("orbit", "--bearing", FRICTION, "--load-newton", "20", "--speed-rpm",
                    "30000", "--rotor-mass-kg", "2", "--revolutions", "30", "--grid", "24x8",
                    "--method", "bdf")
    assert line.startswith("--method = 'bdf': ")
    assert "friction_coefficient = 0.5" in line and "not by the bdf engine" in line


def test_static_foil_beam_on_friction_names_foil():
    line = _refused("static", "--bearing", FRICTION, "--load-newton", "20", "--speed-rpm",
                    "30000", "--grid", "24x8", "--foil", "beam")
    assert line.startswith("--foil = 'beam': ")
    assert "friction_coefficient = 0.5" in line


def test_foil_from_the_file_keeps_the_file_key():
    """Without --foil typed the refusal is not moved onto --foil (the user chose nothing)."""
    from argparse import Namespace

    from gfbopt.cli.flags import as_typed
    from gfbopt.errors import ParameterError

    exc = ParameterError("friction_coefficient", 0.5, "is not carried by the beam foil model")
    args = Namespace(foil="beam", bearing="x.toml", option_flags={"foil": "--foil"},
                     command_line=("gfbopt", "static", "--bearing", "x.toml"))
    assert as_typed(exc, args) is exc
    typed = Namespace(**{**vars(args), "command_line": ("gfbopt", "static", "--foil", "beam")})
    assert str(as_typed(exc, typed)).startswith("--foil = 'beam': x.toml: friction_coefficient")


def test_capacity_missing_speed_says_what_to_give():
    line = _refused("capacity", "--bearing", str(B / "ruscitto.toml"), "--min-film-um", "5")
    assert "= None" not in line
    assert line.startswith("--speed-rpm (not given): ")
    assert "--lift-off" in line


@pytest.mark.parametrize("value, rule", [("inf", "must be finite"),
                                         ("-inf", "must be finite"),
                                         ("nan", "must be finite (not NaN)")])
def test_non_finite_numbers(value, rule):
    line = _refused("static", "--bearing", str(B / "ruscitto.toml"), "--speed-rpm", "30000",
                    f"--load-newton={value}")
    assert line == f"--load-newton = {value!r}: {rule}"
