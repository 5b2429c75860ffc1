"""The rotor onset's refinement follows one mode with a local crossing (gfbopt.rotor.
matched_whirl.local_crossing: Newton on the whirl ratio, Krylov spaces on a narrow window)
instead of every crossing at every speed: the same crossing and the same onsets to 1e-9.
Coarse grid, the study rotor."""
from pathlib import Path

import pytest

from gfbopt import Grid, SolverCache
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.matched_whirl import by_mode, crossings, local_crossing
from gfbopt.rotor.supports import resolve_rotor, support_states
from gfbopt.rotor.system import SpeedLine, rotor_onsets

ROOT = Path(__file__).resolve().parents[2]
GRID = Grid(36, 10)


@pytest.fixture(scope="module")
def rotor():
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    return resolve_rotor(system, GRID, SolverCache(GRID))


@pytest.mark.parametrize("speed, near_speed", [(12400.0, 12000.0), (12400.0, 12300.0),
                                              (12000.0, 12001.2)])
def test_local_crossing_is_the_scans_crossing(rotor, speed, near_speed):
    """From each mode's crossing 3 %, 0.8 % and 1e-4 away in speed (the refinement's steps),
    Newton on the whirl ratio ends on the crossing the full scan (Brent to 1e-10 in γ) finds
    at this speed: μ_c and γ to 1e-9, the same shape class."""
    here = by_mode(crossings(rotor, support_states(rotor, speed)))
    near = by_mode(crossings(rotor, support_states(rotor, near_speed)))
    assert {"forward conical", "forward cylindrical"} <= here.keys()
    for label, start in near.items():
        found = local_crossing(rotor, support_states(rotor, speed), start)
        assert found is not None and found.label == label
        assert found.inertia_scale == pytest.approx(here[label].inertia_scale, rel=1e-9)
        assert found.whirl_ratio == pytest.approx(here[label].whirl_ratio, rel=1e-9)


def test_onsets_with_local_refinement_equal_the_full_scans(rotor):
    """Every mode's onset, whirl ratio and status with the local refinement equal those with
    every crossing computed at every refinement speed (the reference line) to 1e-9; the
    refinement's speeds were solved locally, and the scan rows still list them."""
    span = (10000.0, 14000.0)
    fast_line = SpeedLine(rotor)
    fast = rotor_onsets(rotor.system, span, line=fast_line, show_progress=False)
    ref = rotor_onsets(rotor.system, span, line=SpeedLine(rotor, local=False),
                       show_progress=False)
    assert fast_line._local, "the refinement did not use local crossings"
    assert [m.label for m in fast.modes] == [m.label for m in ref.modes]
    onsets = [m for m in ref.modes if m.status == "onset"]
    assert {m.label for m in onsets} == {"forward conical", "forward cylindrical"}
    for m in ref.modes:
        got = fast.mode(m.label)
        assert got.status == m.status
        if m.status == "onset":
            assert got.onset_speed_rpm == pytest.approx(m.onset_speed_rpm, rel=1e-9)
            assert got.whirl_ratio == pytest.approx(m.whirl_ratio, rel=1e-9)
    local_speeds = {s for s, _ in fast_line._local}
    assert local_speeds <= {r["speed_rpm"] for r in fast.scan}
