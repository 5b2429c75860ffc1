"""The probe below the rotor's first threshold crossing (gfbopt.rotor.probe): its eigenvalues are
the full sparse system's, and it reports the rotor unstable at every inertia scale exactly when
the massless journal whirls — the case the one-bearing threshold reports as M̄c = 0.  Coarse grid
(36 × 10): every comparison is between two routes on the same discrete bearings."""
import math
from pathlib import Path

import numpy as np
import pytest

from gfbopt.inputs import Grid
from gfbopt.inputs.rotor_system import load_rotor, rotor_from_dict
from gfbopt.rotor.analysis import threshold_at
from gfbopt.rotor.campbell import FullSystem
from gfbopt.rotor.matched_whirl import crossings
from gfbopt.rotor.mode_search import UNSTABLE_LOW
from gfbopt.rotor.probe import probe
from gfbopt.rotor.supports import WHIRL_RANGE, resolve_rotor, support_states
from gfbopt.rotor.system import rotor_onsets

ROOT = Path(__file__).resolve().parents[2]
BEARING = str(ROOT / "problems" / "bearings" / "ruscitto.toml")
GRID = Grid(36, 10)


@pytest.fixture(scope="module")
def blower():
    rotor = resolve_rotor(load_rotor(ROOT / "problems" / "rotors" / "blower.toml"), GRID)
    return rotor, support_states(rotor, 15000.0)


def test_probe_eigenvalues_are_the_full_systems(blower):
    """The reduced pencil (each bearing's converged Krylov space) has the full sparse system's
    least-stable whirling eigenvalue: ≤ 1e-9 (the spaces are converged to 1e-11); at μ_c of
    the first crossing it sits on the axis (growth ≤ 1e-9 per radian) at γ_c (≤ 1e-8)."""
    rotor, states = blower
    first = next(c for c in crossings(rotor, states) if c.inertia_scale > 0)
    for mu in (0.5 * first.inertia_scale, 1.0):
        p = probe(rotor, states, mu, WHIRL_RANGE)
        assert p.checked
        s = complex(p.growth_rate, p.whirl_ratio)
        ev, _ = FullSystem(rotor, states, mu).eigen(s + 1e-4, count=4)
        assert np.min(np.abs(ev - s)) <= 1e-9 * abs(s)
    # below the first crossing the blower is stable, at μ = 1 (> μ_c) it grows
    assert probe(rotor, states, 0.5 * first.inertia_scale, WHIRL_RANGE).growth_rate < 0
    on_axis = probe(rotor, states, first.inertia_scale, WHIRL_RANGE)
    assert abs(on_axis.growth_rate) <= 1e-9
    assert on_axis.whirl_ratio == pytest.approx(first.whirl_ratio, abs=1e-8)


@pytest.fixture(scope="module")
def welded_in_load():
    """Both seams 45° from gravity, inside the loaded arc: the massless journal's
    half-frequency mode grows (gfbopt.inputs.options, 'seam 180° from the load')."""
    bearing = {"file": BEARING, "model": {"seam_angle_deg": 45.0}}
    return rotor_from_dict({
        "rotor": {"mass": 3.2, "transverse_inertia": 0.012, "polar_inertia": 0.002},
        "bearings": [bearing | {"position": -0.05}, bearing | {"position": 0.05}]})


def test_massless_journal_instability_is_reported_like_the_one_bearing_threshold(
        welded_in_load):
    """Where each bearing alone has M̄c = 0 (unstable for every rotor mass), the rotor's
    threshold is μ_c = 0 with the probe's reason; the massless rotor's modes are those of the
    bearings' massless journals (gfbopt.rotor.probe), so the two verdicts must agree."""
    rotor = resolve_rotor(welded_in_load, GRID)
    states = support_states(rotor, 10000.0)
    for case in rotor.cases:
        assert threshold_at(case, 10000.0)[2].critical_mass == 0.0
    found = crossings(rotor, states)
    assert found[0].inertia_scale == 0.0
    assert "massless journal is unstable" in found[0].note
    assert 0.02 < found[0].whirl_ratio < 1.2 and math.isfinite(found[0].whirl_frequency_hz)
    result = rotor_onsets(welded_in_load, (9000.0, 11000.0), grid=GRID, show_progress=False)
    assert math.isnan(result.onset_speed_rpm) and result.first_mode is None
    assert any(m.status == UNSTABLE_LOW and m.note for m in result.modes)
    assert "massless journal is unstable" in result.onset_reason
