"""Which limit binds (gfbopt.design.decision) and the one-dimensional search of what it
would take (gfbopt.design.what_it_takes.threshold_search), on analytic surrogates with
planted answers."""
from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from gfbopt.design.decision import ACTIVE_TOLERANCE, binding_limits, limits_text
from gfbopt.design.problem import Constraint, DesignProblem, Objective, Variable
from gfbopt.design.what_it_takes import parse_levers, threshold_search
from gfbopt.errors import ParameterError

PROBLEM = DesignProblem((Variable("c", 10.0, 40.0),), (Objective("onset", "max"),),
                        (Constraint("film", lower=1.5), Constraint("stress", upper=400.0)))


def _table(cs) -> pd.DataFrame:
    """onset = 40,000 − 500 c (higher at a smaller clearance); film = 0.1 c: the film limit
    binds at c = 15; stress = 10 c: the stress limit at c = 40 (far from the optimum)."""
    c = np.asarray(cs, float)
    return pd.DataFrame({"point": [f"p{k}" for k in range(len(c))], "c": c,
                         "onset": 40000.0 - 500.0 * c, "film": 0.1 * c, "stress": 10.0 * c,
                         "success": True})


def _best(table):
    ok = table[[PROBLEM.feasible(r) for r in table.to_dict(orient="records")]]
    return ok.loc[ok["onset"].idxmax()].to_dict()


def test_the_planted_active_limit_is_named_with_its_exclusions_and_relaxation():
    """Designs at c = 12, 13, 14, 15.1 and 16, …, 40: the best feasible is c = 15.1 (film
    1.51, 0.7 % from the limit: active); c = 12, 13, 14 break the film limit alone (3
    designs); the best of them, c = 12 (film 1.2, 20 % past the limit), reaches 34,000 rpm."""
    table = _table([12, 13, 14, 15.1, *range(16, 41)])
    best = _best(table)
    assert best["c"] == 15.1
    film, stress = binding_limits(table, PROBLEM, best, merit="onset")
    assert film.active and not stress.active
    assert film.best_distance == pytest.approx(0.01 / 1.5, rel=1e-9)
    assert stress.best_distance == pytest.approx((400.0 - 10.0 * 15.1) / 400.0)
    assert (film.designs_breaking, film.designs_excluded_only_by_it) == (3, 3)
    assert stress.designs_breaking == 0              # c = 40 meets it: 400 MPa
    assert film.relaxed_merit == 34000.0 and film.relaxed_value == pytest.approx(1.2)
    assert film.relaxed_breach == pytest.approx(0.2)
    text = " ".join(limits_text([film, stress], len(table), 0, "rpm"))
    assert "Active limits of the chosen design (within 2% of the limit): limit on film" in text
    assert "Relaxing the limit on film from 1.5 to 1.2 (20% past it) would allow a first " \
           "onset of 34,000 rpm" in text


def test_no_limit_is_active_when_the_best_design_is_far_from_every_limit():
    table = _table([20.0, 25.0, 30.0])
    film, stress = binding_limits(table, PROBLEM, _best(table), merit="onset")
    assert not film.active and not stress.active and film.best_distance > ACTIVE_TOLERANCE
    assert math.isnan(film.relaxed_merit)            # nothing breaks it: no relaxation
    assert film.designs_breaking == 0 and stress.designs_breaking == 0


def test_a_design_breaking_two_limits_is_not_admitted_by_relaxing_one():
    table = _table([12.0, 20.0])
    table.loc[0, "stress"] = 500.0                    # c = 12 breaks film and stress
    film, stress = binding_limits(table, PROBLEM, _best(table), merit="onset")
    assert film.designs_breaking == 1 and film.designs_excluded_only_by_it == 0
    assert math.isnan(film.relaxed_merit) and math.isnan(stress.relaxed_merit)


def test_threshold_of_a_linear_onset_is_found_to_1e_3():
    """Onset 15,000 + 100,000 η crosses 45,000 rpm at η = 0.3."""
    t = threshold_search(lambda eta: 15000.0 + 100000.0 * eta, 0.0, 0.0, 1.0, 45000.0)
    assert t.found and t.value == pytest.approx(0.3, abs=1e-3) and t.onset_rpm >= 45000.0


def test_threshold_of_a_curved_onset_nearest_the_start_either_way():
    """Onset 60,000 − 2,000 (x − 20)² from x₀ = 15 in [10, 30]: crossings at 20 ± √7.5;
    the nearer one, 17.261 µm, to 1e-3; from x₀ = 29 the nearer is 22.739."""
    f = lambda x: 60000.0 - 2000.0 * (x - 20.0) ** 2          # noqa: E731
    low = threshold_search(f, 15.0, 10.0, 30.0, 45000.0)
    assert low.found and low.value == pytest.approx(20.0 - math.sqrt(7.5), abs=1e-3)
    high = threshold_search(f, 29.0, 10.0, 30.0, 45000.0)
    assert high.found and high.value == pytest.approx(20.0 + math.sqrt(7.5), abs=1e-3)
    down = threshold_search(lambda x: 30000.0 + 1e5 * math.tanh(3.0 - x), 8.0, 0.0, 10.0,
                            45000.0)
    assert down.found and down.value == pytest.approx(3.0 - math.atanh(0.15), abs=1e-3)


def test_none_within_physical_limits_with_the_onset_at_the_limit():
    """Onset 15,000 + 1,000 η never reaches 45,000 rpm in [0, 1]: none, 16,000 rpm at 1."""
    t = threshold_search(lambda eta: 15000.0 + 1000.0 * eta, 0.0, 0.0, 1.0, 45000.0)
    assert not t.found and math.isnan(t.value)
    assert (t.limit_value, t.limit_onset_rpm) == (1.0, 16000.0)
    assert t.message == "none within physical limits"


def test_each_value_is_evaluated_once_and_a_failure_stops_that_direction():
    calls = []

    def onset(x):
        calls.append(x)
        return math.nan if x > 0.5 else 15000.0 + 1000.0 * x
    t = threshold_search(onset, 0.0, 0.0, 1.0, 45000.0, start_onset=15000.0)
    assert not t.found and len(calls) == len(set(calls)) == 3    # 0.25, 0.5, 0.75
    assert "the evaluation failed at 0.75" in t.message


@pytest.mark.parametrize("table, rule", [
    ({"loss_factor": {"low": 0.0}}, "a lever needs its physical bounds"),
    ({"loss_factor": {"high": 0.3}}, "a lever needs its physical bounds"),
    ({"preload_depth_um": {"low": -1.0, "high": 5.0}}, "must lie in [0, inf]"),
    ({"C:length_mm": {"low": 10.0, "high": 50.0}}, "names no bearing"),
    ({"radial_clearance_um": {"low": 10.0, "high": 50.0}}, "name the lever per bearing"),
    ({"loss_factor": {"low": 0.0, "high": 0.5, "direction_deg": 3.0}}, "is not a key"),
    ({"length_mm": {"low": 10.0, "high": True}}, "must be a finite number"),
    ({"zone1_bump_pitch_mm": {"low": 2.0, "high": 5.0}}, "only when the study varies it")])
def test_bad_levers_name_the_file_and_key(table, rule):
    with pytest.raises(ParameterError) as info:
        parse_levers(table, "study.toml", ("A", "B"), ("A:radial_clearance_um",
                                                        "B:radial_clearance_um"))
    text = str(info.value)
    assert rule in text and text.startswith("study.toml: what_it_would_take.")


def test_the_relaxation_steps_run_from_the_least_relaxation_that_gains():
    """c = 12, 13, 14 break the film limit alone (film 1.2, 1.3, 1.4): relaxing to 1.4
    allows 33,000 rpm, to 1.3 33,500, to 1.2 34,000 — each step beats the one before."""
    table = _table([12, 13, 14, 15.1, 20])
    film, _ = binding_limits(table, PROBLEM, _best(table), merit="onset")
    steps = [(round(v, 9), m) for v, m, _ in film.relaxation_steps]
    assert steps == [(1.4, 33000.0), (1.3, 33500.0), (1.2, 34000.0)]
    text = " ".join(limits_text([film], len(table), 0, "rpm"))
    assert "the least relaxation that gains anything, to 1.4, allows 33,000 rpm" in text
