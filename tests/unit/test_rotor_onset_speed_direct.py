"""The rotor onset's last secant step is followed by a direct search (gfbopt.rotor.
matched_whirl.local_crossing with ``direct``: one LU per bearing at the start and its Taylor
series, gfbopt.rotor.reduced.TaylorImpedance) instead of a Krylov space: the same crossing
to 1e-10 and the same onsets as the reference line (every crossing at every speed) to 1e-9.
Coarse grid (36 × 10), the study rotor."""
import dataclasses
from pathlib import Path

import numpy as np
import pytest

from gfbopt import Grid, SolverCache
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.linear import impedance
from gfbopt.rotor import system as system_module
from gfbopt.rotor.matched_whirl import by_mode, crossings, local_crossing
from gfbopt.rotor.reduced import TaylorImpedance
from gfbopt.rotor.supports import resolve_rotor, support_states
from gfbopt.rotor.system import SpeedLine, rotor_onsets

ROOT = Path(__file__).resolve().parents[2]
GRID = Grid(36, 10)


@pytest.fixture(scope="module")
def rotor():
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    return resolve_rotor(system, GRID, SolverCache(GRID))


def test_taylor_impedance_is_the_direct_one_within_its_reach(rotor):
    """Z̄(iγ) 1e-6 and 2e-3 from the LU's whirl ratio (a secant step; the coarse grid's
    crossing against the fine one) equals a direct LU there to 1e-10 (accepted: its last
    terms ≤ 1e-11 of Z̄); 0.5 away, beyond the nearest pole (r ≈ 0.6), it is refused (the
    search then uses a Krylov space)."""
    lin = support_states(rotor, 12000.0).states[0].linearisation
    model = TaylorImpedance(lin, 0.5)
    for gamma in (0.5 + 1e-6, 0.5 - 2e-3):
        z, ok = model.evaluate(gamma)
        exact = impedance(lin, 1j * gamma)
        assert ok and np.abs(z - exact).max() <= 1e-10 * np.abs(exact).max()
    assert not model.evaluate(1.0)[1]


def test_direct_crossing_is_the_krylov_one(rotor):
    """From each mode's crossing 5e-6 away in speed (the secant's last step), its whirl ratio
    extrapolated from a speed 1 % away, the direct search ends on the crossing the Krylov
    search finds: μ_c and γ to 1e-10, the same label."""
    speeds = (11880.0, 12000.0, 12000.0 * (1 + 5e-6))
    states = [support_states(rotor, s) for s in speeds]
    far, near = (by_mode(crossings(rotor, st)) for st in states[:2])
    for label in ("forward conical", "forward cylindrical"):
        step = np.log(speeds[2] / speeds[1]) / np.log(speeds[1] / speeds[0])
        gamma = near[label].whirl_ratio + step * (near[label].whirl_ratio
                                                  - far[label].whirl_ratio)
        start = dataclasses.replace(near[label], whirl_ratio=gamma)
        direct = local_crossing(rotor, states[2], start, direct=True)
        krylov = local_crossing(rotor, states[2], near[label])
        assert direct is not None and direct.label == krylov.label == label
        assert direct.inertia_scale == pytest.approx(krylov.inertia_scale, rel=1e-10)
        assert direct.whirl_ratio == pytest.approx(krylov.whirl_ratio, rel=1e-10)


def test_onsets_with_the_direct_step_equal_the_reference_line(rotor, monkeypatch):
    """Every mode's onset and whirl ratio equal the reference line's to 1e-9 with the direct
    search used at the secant's last steps (measured 1e-12 at 144 × 36 and 72 × 20:
    results/benchmarks/rotor_onset_ratio.json)."""
    used = []

    def counted(*args, **kwargs):
        found = local_crossing(*args, **kwargs)
        if kwargs.get("direct") and found is not None:
            used.append(found)
        return found

    monkeypatch.setattr(system_module, "local_crossing", counted)
    span = (10000.0, 14000.0)
    fast = rotor_onsets(rotor.system, span, line=SpeedLine(rotor), show_progress=False)
    ref = rotor_onsets(rotor.system, span, line=SpeedLine(rotor, local=False),
                       show_progress=False)
    assert used, "no secant step was followed by the direct search"
    onsets = [m for m in ref.modes if m.status == "onset"]
    assert {m.label for m in onsets} == {"forward conical", "forward cylindrical"}
    for m in onsets:
        got = fast.mode(m.label)
        assert got.onset_speed_rpm == pytest.approx(m.onset_speed_rpm, rel=1e-9)
        assert got.whirl_ratio == pytest.approx(m.whirl_ratio, rel=1e-9)


def test_a_refused_direct_search_falls_back_to_krylov(rotor, monkeypatch):
    """With the series cut at two terms the direct search from a start 2e-3 off (the coarse
    crossing) is refused (None), and the speed line's search still finds the crossing, by
    a Krylov space: the full scan's to 1e-9."""
    speed = 12000.0
    here = by_mode(crossings(rotor, support_states(rotor, speed)))["forward conical"]
    start = dataclasses.replace(here, whirl_ratio=here.whirl_ratio - 2e-3)
    monkeypatch.setattr(TaylorImpedance, "MAX_TERMS", 2)
    states = support_states(rotor, speed)
    assert local_crossing(rotor, states, start, direct=True) is None
    line = SpeedLine(rotor)
    found = line.follow_from(speed, "forward conical", start.whirl_ratio, start)
    assert found is not None and not line.computed(speed)
    assert found.inertia_scale == pytest.approx(here.inertia_scale, rel=1e-9)
    assert found.whirl_ratio == pytest.approx(here.whirl_ratio, rel=1e-9)
