"""argparse's own refusals (a value that is not a number, a negative number in scientific
notation) name the flag once, as typed: ``--bearing-number = 'abc': must be a number``
(0.3.0: ``argument --bearing-number: bearing-number = 'abc': …``; ``--radial-clearance
-30e-6`` was "expected one argument", the value taken for an option)."""
from __future__ import annotations

import pytest

from tests.cli_inprocess import run_cli

DESIGN = ["design", "--target-compliance", "1", "--radial-clearance"]


@pytest.mark.parametrize("argv, line", [
    (["static", "--bearing-number", "abc"], "--bearing-number = 'abc': must be a number"),
    (["static", "--bearing-number", "nan"], "--bearing-number = 'nan': must be finite"),
    (["static", "--bearing-number", "1", "--eccentricity", "0.4", "--seam-angle", "x"],
     "--seam-angle = 'x': must be a number of degrees or 'max_film'"),
    (["run", "x.toml", "--workers", "0"], "--workers = 0: must be >= 1"),
    ([*DESIGN, "-30e-6"], "--radial-clearance = -3e-05: must be finite and > 0"),
    (["static", "--bearing-number", "-1e-3", "--eccentricity", "0.4"],
     "--bearing-number = -0.001: must be > 0"),
    (["static", "--foil", "plastic"], "argument --foil: invalid choice: 'plastic'"),
])
def test_argparse_refusals_name_the_flag_once(argv, line):
    out = run_cli(*argv)
    assert out.returncode == 2 and out.stdout == ""
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"gfbopt: error: {line}"), lines
