"""The matched-whirl scan's halving rule (gfbopt.rotor.matched_whirl._ambiguous): a root's
move measured from the inertia term's trend ν ∝ γ² and a decisive shape match stop the scan
from halving where following the branches is sure, and no crossing is lost by it.

Each default scan (24 points, halved where ambiguous) is checked against a scan ten times
denser (241 points, halved by the same rule): the same crossings — labels, μ_c and whirl
ratios to 1e-9, both refined by Brent's method to 1e-10 in γ.  The blower at 32,118 rpm
on 36 × 10 is where its two forward modes cross the axis together near γ = 1/2 (a looser
decisive rule, without the move bound, lost the forward conical crossing there); the
flexible rotor at 30,000 rpm on 36 × 10 is where the plain rule reached the 240-point cap."""
import sys
from pathlib import Path

import numpy as np
import pytest

from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor import matched_whirl as mw
from gfbopt.rotor.supports import resolve_rotor, support_states

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_rotor_flexible_shaft import _system  # noqa: E402

GRID = Grid(36, 10)


def _same_crossings(rotor, states):
    default = mw.crossings(rotor, states)
    dense = mw.crossings(rotor, states, samples=241)
    assert [c.label for c in default] == [c.label for c in dense]
    for a, b in zip(default, dense):
        assert abs(a.inertia_scale / b.inertia_scale - 1) < 1e-9
        assert abs(a.whirl_ratio - b.whirl_ratio) < 1e-9
    return default


def test_the_blowers_two_forward_crossings_near_half_whirl_are_kept():
    rotor = resolve_rotor(load_rotor(ROOT / "problems" / "rotors" / "blower.toml"), GRID)
    states = support_states(rotor, 32117.784161)
    found = _same_crossings(rotor, states)
    labels = {c.label for c in found}
    assert {"forward conical", "forward cylindrical"} <= labels


def test_a_shafts_scan_stays_short_and_keeps_every_crossing():
    rotor = resolve_rotor(_system(), GRID)
    states = support_states(rotor, 30000.0)
    found = _same_crossings(rotor, states)
    assert any(c.label.startswith("forward bending") for c in found)
    gammas = np.linspace(*mw.WHIRL_RANGE, mw.SAMPLES)
    for st in states.states:
        st.prepare(gammas)
    points, _ = mw._adaptive_scan(
        lambda g: mw.inertia_roots_many(rotor, states, g, vectors=True),
        rotor.structure.mass(), gammas, 1.0 / mw.SHAFT_SCALE_LIMIT)
    # measured 40-92 points a speed at 72 x 20 (6,000-60,000 rpm); the plain rule: 112-240
    assert len(points) <= 120


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))
