"""The side-load lever of "what it would take" sits where study_file.md says: its position is
from the centre of gravity (default 0) on every rotor -- on a shaft rotor, whose positions run
from the shaft's first end, too; and a lever that stays unstable at the lowest speed says so."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from gfbopt.design.lever_runs import LeverAnswer, answers_text, lever_point
from gfbopt.design.what_it_takes import Lever
from gfbopt.inputs.rotor_system import load_rotor

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("rotor", ["flexible_rotor.toml", "blower.toml"])
def test_side_load_lever_is_placed_from_the_centre_of_gravity(rotor):
    system = load_rotor(ROOT / "problems" / "rotors" / rotor)
    cg = system.centre_of_gravity
    for offset in (0.0, 0.01):
        lever = Lever("side_load_n", "N", "a side load", 0.0, 100.0, position=offset)
        loaded = lever_point(lever, 50.0, system, {}, None)["system"]
        added = loaded.side_loads[-1]
        # the system's own frame: the CG plus the offset (exact float sum)
        assert added.position == cg + offset
    if rotor == "flexible_rotor.toml":
        assert cg > 0.05                      # the shaft's CG is far from its first end
        # a load at the CG splits between the bearings as the weight does
        lever = Lever("side_load_n", "N", "a side load", 0.0, 100.0,
                      direction_deg=system.gravity_direction_deg)
        weight = [math.hypot(*s) for s in system.static_shares()]
        w = system.total_mass * system.gravity
        loaded = lever_point(lever, w, system, {}, None)["system"]
        doubled = [math.hypot(*s) for s in loaded.static_shares()]
        assert doubled == pytest.approx([2 * x for x in weight], rel=1e-9)


def test_lever_unstable_at_the_lowest_speed_says_so():
    a = LeverAnswer("side_load_n", "N", "a side load", 0.0, 0.0, 200.0, False, math.nan,
                    math.nan, math.nan, None, math.nan, 200.0, 4000.0, 9,
                    "at 200 N it is still unstable at the lowest speed (4,000 rpm)")
    text = answers_text([a], 30000.0, 4000.0)
    assert "unstable at the lowest speed" in text
    assert "the first onset is 4,000 rpm" not in text


def test_what_it_would_take_names_a_lever_stuck_unstable_at_the_lowest_speed():
    """Every evaluation is unstable at the lowest speed (its 'first onset' is the lowest
    speed, 4,000 rpm): the answer says that, not 'the first onset is 4,000 rpm'."""
    from types import SimpleNamespace

    from gfbopt.design.lever_runs import LeverEvaluations, what_it_would_take

    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    settings = SimpleNamespace(top_speed_rpm=30000.0, loss_factor=0.0)
    problem = SimpleNamespace(feasible=lambda result: True)

    def run_tasks(function, arguments):          # no workers: a planted evaluation
        return [(k, {"first_onset_speed_rpm": 4000.0, "success": True,
                     "onset_status": "unstable at the lowest speed"})
                for k, _ in enumerate(arguments)]

    ev = LeverEvaluations(None, system, {}, settings, problem, run_tasks=run_tasks)
    lever = Lever("side_load_n", "N", "a side load", 0.0, 200.0)
    (answer,) = what_it_would_take((lever,), ev, 4000.0)
    assert not answer.found and answer.limit_onset_rpm == 4000.0
    assert "still unstable at the lowest speed (4,000 rpm)" in answer.message
    text = answers_text([answer], 30000.0, 4000.0)
    assert "unstable at the lowest speed" in text and "the first onset is" not in text
