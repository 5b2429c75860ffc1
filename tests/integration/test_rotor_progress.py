"""The rotor's onset search shows every stage of its work: the scan (on the coarse guide's
grid when there is one) and then the refinement of each mode on the analysis grid, which on
a fine grid is most of the work (before, the bar ended at 'onset scan 13/13 (100 %)' and the
refinement ran silently)."""
from __future__ import annotations

import re
from pathlib import Path

from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.system import rotor_onsets

ROOT = Path(__file__).resolve().parents[2]


def test_the_refinement_after_the_scan_is_a_stage_of_the_progress(capsys, monkeypatch):
    monkeypatch.setenv("GFBOPT_PROGRESS", "1")
    result = rotor_onsets(load_rotor(ROOT / "problems" / "rotors" / "blower.toml"),
                          (8000, 16000), grid=Grid(48, 12), coarse_grid="24x8",
                          show_progress=True)
    err = capsys.readouterr().err
    scan = re.findall(r"rotor onset scan on 24x8 (\d+)/(\d+) speed \(100 %\)", err)
    refine = re.findall(r"rotor onset refinement on 48x12 (\d+)/(\d+) mode \(100 %\)", err)
    assert scan and scan[-1][0] == scan[-1][1], err
    assert refine, err
    assert int(refine[-1][0]) == int(refine[-1][1]) == len(result.modes) >= 2, err
    assert err.index("rotor onset scan") < err.index("rotor onset refinement"), err
