"""A refusal names the parameter as the user typed it: ``--speed-rpm``, not the library's
``speed_rpm``; one line, exit 2, before anything is solved.

The table is the sample of bad invocations run for the review (one or more per command);
the ``before`` column is what each printed on 0.3.0 where it differed."""
from __future__ import annotations

import time
from pathlib import Path

import pytest

from gfbopt.cli import build_parser
from gfbopt.cli.flags import as_typed, option_flags
from gfbopt.errors import ParameterError
from tests.cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
R = str(REPO / "problems" / "rotors" / "blower.toml")
B = str(REPO / "problems" / "bearings" / "ruscitto.toml")
POINT = ["--bearing-number", "1", "--eccentricity", "0.4", "--grid", "24x8"]
SI = ["--bearing", B, "--speed-rpm", "30000", "--load-newton", "20", "--grid", "24x8"]
SPAN = ["--speed-range", "10000", "60000", "--grid", "24x8"]
DESIGN = ["design", "--target-compliance", "1", "--radial-clearance", "30e-6"]

#: (command line, the parameter as the message must name it, what 0.3.0 named it)
CASES = [
    (["static", "--bearing-number", "-1", *POINT[2:]], "--bearing-number", "bearing_number"),
    (["static", *POINT, "--length-ratio", "0"], "--length-ratio", "length_ratio"),
    (["static", *POINT, "--compliance", "-1"], "--compliance", "compliance"),
    (["static", "--bearing-number", "1", "--eccentricity", "1.5"], "--eccentricity",
     "eccentricity"),
    (["static", "--bearing-number", "1", "--load", "-0.5"], "--load", "load"),
    (["static", *POINT, "--compliance", "1", "--foil", "beam", "--top-foil-coefficient", "-1"],
     "--top-foil-coefficient", "top_foil_coefficient"),
    (["static", *POINT[:4], "--grid", "abc"], "--grid", "grid"),
    (["static", *POINT[:4], "--grid", "2x2"], "--grid n_theta", "grid n_theta"),
    (["static", *SI[:3], "-5", *SI[4:]], "--speed-rpm", "speed_rpm"),
    (["static", *SI[:5], "-20", *SI[6:]], "--load-newton", "load_newton"),
    (["static", "--bearing", "/no/such/bearing.toml", *SI[2:]], "--bearing", "file"),
    (["linear", *POINT, "--compliance", "1", "--loss-factor", "-0.5"], "--loss-factor",
     "loss_factor"),
    (["stability", "--bearing", B, "--rotor-mass-kg", "1", "--speed-rpm", "30000",
      "--frequency-hz", "-5"], "--frequency-hz", "frequency_hz"),
    (["stability", "--bearing", B, "--rotor-mass-kg", "1", "--speed-rpm", "30000",
      "--film", "periodic", "--seam-angle", "90"], "--seam-angle", "seam_angle_deg"),
    (["capacity", "--bearing", B, "--min-film-um", "-1", "--speed-rpm", "30000"],
     "--min-film-um", "min_film_um"),
    (["capacity", "--bearing", B, "--min-film-um", "5", "--speed-rpm", "-3"], "--speed-rpm",
     "speed_rpm"),
    (["capacity", "--bearing", B, "--min-film-um", "5", "--lift-off", "--load-newton", "3",
      "--max-speed-rpm", "-1"], "--max-speed-rpm", "max_speed_rpm"),
    (["capacity", "--bearing", "/no/such/bearing.toml", "--min-film-um", "5", "--speed-rpm",
      "30000"], "--bearing", "file"),
    (["rotor", R, *SPAN, "--imbalance-response", "--imbalance-grade", "-1"],
     "--imbalance-grade", "balance_grade"),
    (["rotor", R, "--orbit", "--speed-rpm", "-30000", "--revolutions", "5"], "--speed-rpm",
     "speed_rpm"),
    (["rotor", R, "--run-up", "-5", "60000", "--rate", "1000"], "--run-up", "start_rpm"),
    (["rotor", R, "--coast-down", "5000", "60000", "--rate", "1000"], "--coast-down",
     "end_rpm"),
    (["rotor", R, "--orbit", "--speed-rpm", "30000", "--revolutions", "5",
      "--reference-whirl-ratio", "-1"], "--reference-whirl-ratio", "(accepted, exit 0)"),
    (["rotor", R, "--orbit", "--speed-rpm", "30000", "--revolutions", "5",
      "--reference-whirl-ratio", "0.5"], "--reference-whirl-ratio", "(ignored, exit 0)"),
    (["rotor", R, "--orbit", "--speed-rpm", "30000", "--revolutions", "5",
      "--subsync-threshold-um", "-1"], "--subsync-threshold-um", "(accepted, exit 0)"),
    (["design", "--target-compliance", "-1", "--radial-clearance", "30e-6"],
     "--target-compliance", "target compliance S"),
    (["design", "--target-compliance", "1", "2", "3", "--radial-clearance", "30e-6"],
     "--target-compliance", "target-compliance"),
    ([*DESIGN, "--pitch-range", "5e-3", "1e-3"], "--pitch-range", "pitch_range"),
    ([*DESIGN, "--youngs-modulus", "-1"], "--youngs-modulus", "youngs_modulus"),
    ([*DESIGN, "--poisson-ratio", "0.7"], "--poisson-ratio", "poisson_ratio"),
    ([*DESIGN, "--gap", "-1"], "--gap", "gap"),
    ([*DESIGN, "--bump-height", "-1"], "--bump-height", "bump_height"),
    ([*DESIGN, "--ambient-pressure", "-1"], "--ambient-pressure", "ambient_pressure"),
    (["orbit", *POINT, "--mass", "-1", "--revolutions", "2"], "--mass", None),
    (["export-ross", R, "--speed-range", "1000", "60000", "--out", "x", "--speeds", "1"],
     "--speeds", None),
]


@pytest.mark.parametrize("argv, flag, before", CASES,
                         ids=[f"{c[0][0]}:{c[1]}" for c in CASES])
def test_a_refusal_names_the_flag_as_typed(argv, flag, before, tmp_path):
    start = time.perf_counter()
    out = run_cli(*argv, cwd=tmp_path)
    seconds = time.perf_counter() - start
    assert out.returncode == 2, (out.returncode, out.stderr)
    assert out.stdout == ""
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1, out.stderr
    assert lines[0].startswith(f"gfbopt: error: {flag} = "), lines[0]
    assert seconds < 20.0                 # refused before any solve (a solve takes longer)


def test_every_option_of_every_command_has_its_flag():
    parser = build_parser()
    commands = parser._subparsers._group_actions[0].choices
    flags = option_flags(commands["rotor"])
    assert flags["speed_rpm"] == "--speed-rpm" and flags["rotor_file"] == "ROTOR.toml"
    assert flags["imbalance_plane"] == "--imbalance-plane"
    for name, command in commands.items():
        for dest, flag in option_flags(command).items():
            if flag.startswith("--"):
                assert flag == "--" + dest.replace("_", "-"), (name, dest, flag)


def test_a_value_the_library_computed_keeps_its_own_name():
    """Only a value the user gave is renamed: a speed the library derived (not --speed-rpm's)
    keeps the library's name — the flag would point at the wrong input."""
    args = build_parser().parse_args(["rotor", R, "--orbit", "--speed-rpm", "30000",
                                      "--revolutions", "5"])
    typed = as_typed(ParameterError("speed_rpm", 30000.0, "must be > 0"), args)
    assert str(typed) == "--speed-rpm = 30000.0: must be > 0"
    kept = as_typed(ParameterError("speed_rpm", 12345.0, "must be > 0"), args)
    assert str(kept) == "speed_rpm = 12345.0: must be > 0"
    keyed = ParameterError("blower.toml: bearings[1].file", "x.toml", "must exist")
    assert as_typed(keyed, args) is keyed                  # a file's key stays the file's
