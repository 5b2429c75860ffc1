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


R = REPO / "problems" / "rotors"
POINT = ("--speed-rpm", "30000", "--grid", "24x8")


def test_one_value_of_a_list_option_names_the_flag():
    line = _refused("stability", "--bearing", str(B / "ruscitto.toml"), "--rotor-mass-kg", "2",
                    "--load-newton", "20", *POINT, "--frequency-hz", "100", "-5")
    assert line == "--frequency-hz = -5.0: must be finite and > 0 [Hz]"


def test_a_hardening_bump_refused_for_the_local_law_names_the_flag(tmp_path):
    hard = tmp_path / "hard.toml"
    hard.write_text((B / "ruscitto.toml").read_text().replace(
        "[model]", "[model]\nbump_height = 0.5e-3\nhardening_limit = 15e-6\n"
        "hardening_exponent = 2.0", 1))
    line = _refused("stability", "--bearing", str(hard), "--rotor-mass-kg", "2",
                    "--load-newton", "20", *POINT, "--deflection-law", "local")
    assert line.startswith(f"--deflection-law = 'local': {hard}: hardening_exponent = 2.0: ")


@pytest.mark.parametrize("rotor, rule", [("blower.toml", "must lie within 50 journal"),
                                          ("flexible_rotor.toml", "must lie on the shaft")])
def test_an_imbalance_plane_of_the_command_line_is_refused_as_typed(rotor, rule):
    line = _refused("rotor", str(R / rotor), "--speed-range", "5000", "30000",
                    "--imbalance-response", "--imbalance-plane", "1", "0", "0.1",
                    "--imbalance-plane", "1", "0", "5", "--grid", "24x8")
    assert line.startswith("--imbalance-plane[2] position = 5.0: " + rule)


@pytest.mark.parametrize("args, name", [
    (("rotor", "x.toml", "--speed-range", "5000", "30000"), "ROTOR.toml"),
    (("run", "x.toml"), "STUDY.toml")])
def test_a_missing_positional_file_names_the_argument(args, name):
    assert _refused(*args) == f"{name} = 'x.toml': must be an existing TOML file"


def test_an_overloaded_orbit_says_what_the_bearing_carries():
    line = _refused("orbit", "--bearing", str(B / "ruscitto.toml"), "--rotor-mass-kg", "2",
                    "--load-newton", "2000", *POINT)
    stability = _refused("stability", "--bearing", str(B / "ruscitto.toml"),
                         "--rotor-mass-kg", "2", "--load-newton", "2000", *POINT)
    assert line == stability
    assert line.startswith("--load-newton = 2000.0: load exceeds the load capacity at this "
                           "speed (30000 rpm): the largest load that converged is ")


def test_critical_mass_says_it_does_not_model_friction():
    line = _refused("critical-mass", "--bearing", FRICTION, "--load-newton", "20", *POINT)
    assert line.startswith(f"--bearing = '{FRICTION}': friction_coefficient = 0.5: gfbopt "
                           "critical-mass does not model the bumps' Coulomb friction")
    assert "gfbopt orbit" in line


def test_export_ross_is_guarded_like_every_command(tmp_path):
    line = _refused("export-ross", str(R / "blower.toml"), "--speed-range", "5000", "60000",
                    "--speeds", "400", "--frequencies", "400", "--out", str(tmp_path / "r"),
                    "--grid", "144x36", "--max-minutes", "1")
    assert line.startswith("--speeds = 400: 400 table speeds × 2 bearing(s) at 144x36")
    assert line.endswith("raise --max-minutes")
    assert not (tmp_path / "r").exists()
