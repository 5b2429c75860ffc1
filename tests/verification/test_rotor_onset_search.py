"""The rotor onset search's routes give one answer (gfbopt.rotor.system): the secant refinement
against the reference (Brent's method, method="scan"), and the scan guided by a coarse grid
against the fine grid alone.  Narrow range around the study rotor's two onsets (≈ 12,100 and
12,900 rpm), coarse grids."""
from pathlib import Path

import pytest

from gfbopt.inputs import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.system import rotor_onsets

ROOT = Path(__file__).resolve().parents[2]
SPAN = (10000.0, 14000.0)


@pytest.fixture(scope="module")
def system():
    return load_rotor(ROOT / "problems" / "rotors" / "blower.toml")


def _onsets(result):
    return {m.label: m.onset_speed_rpm for m in result.modes if m.status == "onset"}


def test_secant_refinement_agrees_with_the_reference(system):
    """Brent's method stops at 1e-4 relative: the two agree to 2e-4 (the secant's own error is
    ≤ 1e-6); both onsets and the whirl at the first."""
    grid = Grid(36, 10)
    fast = rotor_onsets(system, SPAN, grid=grid, show_progress=False)
    ref = rotor_onsets(system, SPAN, grid=grid, show_progress=False, method="scan")
    assert _onsets(fast).keys() == _onsets(ref).keys() == {"forward conical",
                                                          "forward cylindrical"}
    for label, speed in _onsets(ref).items():
        assert _onsets(fast)[label] == pytest.approx(speed, rel=2e-4)
    assert fast.onset_whirl_frequency_hz == pytest.approx(ref.onset_whirl_frequency_hz,
                                                          rel=2e-4)


def test_coarse_guide_gives_the_fine_grids_answer(system):
    """The guide only brackets: the onsets are the fine grid's (secant to 1e-6, so 1e-5), and
    the result says which grid guided it (its cost is measured in benchmarks/bench_rotor.py:
    it pays on wide ranges and fine grids, not on this narrow one)."""
    grid = Grid(48, 14)                  # any coarser grid may guide when stated
    guided = rotor_onsets(system, SPAN, grid=grid, show_progress=False, coarse_grid="36x10")
    alone = rotor_onsets(system, SPAN, grid=grid, show_progress=False, coarse_grid=None)
    assert guided.conventions["coarse_grid"] == "36x10" and alone.conventions["coarse_grid"] == ""
    assert _onsets(guided).keys() == _onsets(alone).keys()
    for label, speed in _onsets(alone).items():
        assert _onsets(guided)[label] == pytest.approx(speed, rel=1e-5)
    # the lowest speed (it decides "unstable at the lowest speed") is always on the fine grid
    assert SPAN[0] in {r["speed_rpm"] for r in guided.scan if r["grid"] == "48x14"}
    assert {r["grid"] for r in guided.scan} == {"36x10", "48x14"}
