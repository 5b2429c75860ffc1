"""The two-bearing rotor's linear analyses when the bearing files state Coulomb friction in the
bumps: the seam re-measured from each bearing's load keeps the bump options, the
Campbell diagram's full system carries the stuck friction springs (the small-motion foundation
the matched-whirl onset sees), and friction 0 is today's system exactly.  Coarse grid 36 × 10:
every comparison is between two routes on the same discrete bearing."""
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import Grid
from gfbopt.inputs.options import ModelOptions
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.campbell import FullSystem
from gfbopt.rotor.matched_whirl import crossings
from gfbopt.rotor.rigid import seam_from_load
from gfbopt.rotor.supports import resolve_rotor, support_states

ROOT = Path(__file__).resolve().parents[2]
GRID = Grid(36, 10)
SPEED = 15000.0


def _blower(**bump):
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    if not bump:
        return system
    bearings = tuple(replace(b, options=replace(b.options, **bump)) for b in system.bearings)
    return replace(system, bearings=bearings)


def test_seam_from_load_keeps_the_bump_options():
    """The seam re-measured from a bearing's own load changes the seam only: friction and
    hardening stated in the bearing file reach the rotor's bearings."""
    opts = ModelOptions(film="seam", seam_angle_deg=180.0, foil="simple", deflection_law="mean",
                        loss_factor=0.0, friction_coefficient=0.3,
                        friction_stiffness_ratio=2.0)
    out = seam_from_load(opts, 30.0)
    assert out.seam_angle_deg == pytest.approx(150.0, abs=1e-12)
    assert (out.friction_coefficient, out.friction_stiffness_ratio) == (0.3, 2.0)
    assert replace(out, seam_angle_deg=180.0) == opts


def test_rotor_cases_carry_the_bearing_files_friction():
    rotor = resolve_rotor(_blower(friction_coefficient=0.5), GRID)
    assert [c.options.friction_coefficient for c in rotor.cases] == [0.5, 0.5]
    states = support_states(rotor, SPEED)
    assert all(st.linearisation.friction is not None for st in states.states)


def _eigs(system, shift):
    rotor = resolve_rotor(system, GRID)
    states = support_states(rotor, SPEED)
    full = FullSystem(rotor, states)
    ev, _ = full.eigen(shift, count=4)
    return np.sort_complex(ev), full


def test_friction_zero_is_todays_full_system_exactly():
    """μ_f = 0 stated: the pencil and its eigenvalues equal the file without friction to 1e-12
    (the same matrices: the model has no friction elements)."""
    shift = 0.3j
    today, f0 = _eigs(_blower(), shift)
    zero, f1 = _eigs(_blower(friction_coefficient=0.0), shift)
    assert abs(f0.j - f1.j).max() <= 1e-12 * abs(f0.j).max()
    assert abs(f0.e - f1.e).max() <= 1e-12 * abs(f0.e).max()
    assert np.max(np.abs(today - zero)) <= 1e-12 * np.max(np.abs(today))


def test_full_system_with_stuck_friction_sits_on_the_axis_at_the_matched_whirl_threshold():
    """With μ_f = 0.5 in both bearing files, each of the first two modes' matched-whirl
    thresholds (stuck friction springs for small orbits) puts a full-system eigenvalue on the
    imaginary axis to the tolerance of the frictionless agreement
    (test_rotor_two_bearings: growth per revolution 2π Re s ≤ 1e-6, Im s = γ_c to 1e-4); the
    bare bump's full system (the pre-issue-29 Campbell) does not."""
    system = _blower(friction_coefficient=0.5)
    rotor = resolve_rotor(system, GRID)
    states = support_states(rotor, SPEED)
    found = crossings(rotor, states)
    assert {c.label for c in found} >= {"forward conical", "forward cylindrical"}
    for c in found[:2]:
        full = FullSystem(rotor, states, c.inertia_scale)
        ev, _ = full.eigen(1j * c.whirl_ratio * (1 + 1e-7), count=4)
        s = ev[np.argmin(np.abs(ev - 1j * c.whirl_ratio))]
        assert abs(2 * math.pi * s.real) <= 1e-6
        assert s.imag == pytest.approx(c.whirl_ratio, rel=1e-4)
    c = found[0]
    for st in states.states:                   # the bare bump: friction dropped
        st.linearisation = replace(st.linearisation, friction=None)
    ev, _ = FullSystem(rotor, states, c.inertia_scale).eigen(1j * c.whirl_ratio, count=4)
    s = ev[np.argmin(np.abs(ev - 1j * c.whirl_ratio))]
    assert abs(2 * math.pi * s.real) > 1e-3


def test_campbell_refuses_friction_with_a_loss_factor():
    rotor = resolve_rotor(_blower(friction_coefficient=0.5, loss_factor=0.1), GRID)
    states = support_states(rotor, SPEED)
    with pytest.raises(ParameterError, match="loss_factor"):
        FullSystem(rotor, states, 1.0, reference_whirl=0.4)


def test_onset_conventions_study_states_and_uses_the_bearing_files_friction():
    """gfbopt.studies.stability merges the bearing file's bump options (not only foil,
    deflection law and loss factor): the plan states them, and the onset point of the study
    with friction is the stuck onset (above the bare bump's); without friction the plan's bump
    options are empty (today's outputs)."""
    from gfbopt.studies import study_from_dict
    from gfbopt.studies.stability import onset_point

    def plan(bearing):
        study = study_from_dict({
            "kind": "onset_conventions", "title": "t", "source": "a test", "grid": "24x8",
            "bearing": bearing, "rotor_mass_kg": 2.0, "load_newton": 20.0,
            "speed_range_rpm": [8000.0, 30000.0], "seam_angles_deg": [180.0]},
            name="tiny", file="tiny.toml", directory=ROOT / "problems")
        return study.plan

    bare, rubbing = plan("bearings/ruscitto.toml"), plan("bearings/ruscitto_friction.toml")
    assert bare["bump"] == {}
    assert rubbing["bump"] == {"friction_coefficient": 0.5, "friction_stiffness_ratio": 2.0}
    point = {k: v for k, v in rubbing["points"][2].items()}        # seam at 180°
    assert point["seam_angle_deg"] == 180.0
    stuck = onset_point(**point)
    plain = onset_point(**{**bare["points"][2]})
    assert stuck["onset_status"] == plain["onset_status"] == "onset"
    assert stuck["onset_speed_rpm"] > 1.02 * plain["onset_speed_rpm"]


def test_campbell_rows_with_friction_zero_are_todays():
    """The Campbell diagram's rows with μ_f = 0 stated in both bearing files equal the file
    without friction to 1e-12 (3 speeds around the onsets)."""
    from gfbopt.rotor.diagrams import campbell_diagram
    from gfbopt.rotor.system import SpeedLine

    speeds = [11000.0, 13000.0, 15000.0]
    tables = [campbell_diagram(SpeedLine(resolve_rotor(s, GRID)), speeds,
                               show_progress=False).table
              for s in (_blower(), _blower(friction_coefficient=0.0))]
    a, b = tables
    assert list(a.columns) == list(b.columns) and len(a) == len(b) >= 12
    for col in a.columns:
        if a[col].dtype.kind in "fc":
            x, y = a[col].to_numpy(), b[col].to_numpy()
            same = np.isnan(x) == np.isnan(y)
            assert same.all(), col
            ok = ~np.isnan(x)
            assert np.all(np.abs(x[ok] - y[ok]) <= 1e-12 * np.maximum(1.0, np.abs(x[ok]))), col
        else:
            assert (a[col].astype(str) == b[col].astype(str)).all(), col


def test_campbell_with_friction_crosses_zero_at_the_stuck_onsets():
    """blower_friction.toml (μ_f = 0.5, κ = 2): each matched-whirl onset (stuck bumps) has one
    Campbell track named by its label whose log decrement falls through zero in the diagram
    interval holding that onset — the agreement test_rotor_campbell_tracking asserts without
    friction, to its tolerance (the 1,167 rpm interval) — stuck onsets 12,935 and 14,004 rpm
    at 36 × 10."""
    from gfbopt.rotor.diagrams import campbell_diagram
    from gfbopt.rotor.system import SpeedLine, rotor_onsets

    system = load_rotor(ROOT / "problems" / "rotors" / "blower_friction.toml")
    line = SpeedLine(resolve_rotor(system, GRID))
    onsets = rotor_onsets(system, (9000.0, 16000.0), line=line, show_progress=False)
    table = campbell_diagram(line, list(np.linspace(9000.0, 16000.0, 7)),
                             show_progress=False, onsets=onsets.modes).table
    found = [m for m in onsets.modes if math.isfinite(m.onset_speed_rpm)]
    assert {m.label for m in found} == {"forward conical", "forward cylindrical"}
    for m in found:
        tracks = table[(table["track_label"] == m.label) & table["track_zero_rpm"].notna()]
        assert tracks["mode"].nunique() == 1
        zero = tracks["track_zero_rpm"].iloc[0]
        assert abs(zero - m.onset_speed_rpm) <= 7000.0 / 6
        # sharper: measured 5 and 15 rpm; a tenth of the interval, while the bare bumps'
        # onsets (12,147 and 12,970 rpm) lie 788 and 1,034 rpm away from these
        assert abs(zero - m.onset_speed_rpm) <= 0.1 * 7000.0 / 6


def test_onset_conventions_refuses_friction_with_the_beam_foil_before_any_solve():
    from gfbopt.studies import study_from_dict

    with pytest.raises(ParameterError) as info:
        study_from_dict({
            "kind": "onset_conventions", "title": "t", "source": "a test", "grid": "24x8",
            "bearing": "bearings/ruscitto_friction.toml", "rotor_mass_kg": 2.0,
            "load_newton": 20.0, "speed_range_rpm": [8000.0, 30000.0],
            "seam_angles_deg": [180.0], "model": {"foil": "beam"}},
            name="tiny", file="tiny.toml", directory=ROOT / "problems")
    text = str(info.value)
    assert "tiny.toml" in text and "friction_coefficient = 0.5" in text and "beam" in text
    assert "\n" not in text


def test_rotor_onsets_with_friction_zero_are_todays():
    """μ_f = 0 stated in both bearing files: the rotor's matched-whirl onsets equal the file
    without friction to 1e-12; μ_f = 0.5 (κ = 1) raises both (stuck bumps: forward conical
    12,147 -> 12,723 rpm, +4.7 %, at 36 × 10)."""
    from gfbopt.rotor.system import rotor_onsets

    span = (9000.0, 16000.0)
    runs = [rotor_onsets(s, span, grid=GRID, show_progress=False)
            for s in (_blower(), _blower(friction_coefficient=0.0),
                      _blower(friction_coefficient=0.5))]
    for label in ("forward conical", "forward cylindrical"):
        today, zero, rub = (r.mode(label) for r in runs)
        assert zero.onset_speed_rpm == pytest.approx(today.onset_speed_rpm, rel=1e-12)
        assert zero.whirl_ratio == pytest.approx(today.whirl_ratio, rel=1e-12)
        assert rub.onset_speed_rpm > 1.03 * today.onset_speed_rpm
