"""The design optimiser on cheap analytic problems with planted answers
(gfbopt.design.surrogates): fronts, optima, constraints, failures, reproducibility, resume.

Tolerances are set from what the method can reach with the stated budget (measured over
seeds, see each test) with a margin, and each test also shows that a plain sample of the
same budget does NOT pass it, so the test can fail.
"""
import math

import numpy as np
import pytest
from scipy.stats import qmc

from gfbopt.design import surrogates
from gfbopt.design.optimiser import optimise, store_schema
from gfbopt.design.pareto import (
    distance_to_front,
    hypervolume,
    minimised_objectives,
    non_dominated,
    pareto_front,
)
from gfbopt.design.problem import Constraint, DesignProblem, Objective, Variable
from gfbopt.design.search import SearchSettings
from gfbopt.doe.store import ResultStore
from gfbopt.errors import ParameterError

ZDT = DesignProblem(tuple(Variable(f"x{k}", 0.0, 1.0) for k in range(3)),
                    (Objective("f1"), Objective("f2")))
CIRCLE = DesignProblem((Variable("x", 0.0, 1.0), Variable("y", 0.0, 1.0)),
                       (Objective("f1"), Objective("f2")),
                       (Constraint("radius_squared", lower=1.0),))
BOWL = DesignProblem((Variable("x", 0.0, 1.0), Variable("y", 0.0, 1.0)), (Objective("f"),),
                     (Constraint("sum_xy", upper=1.0),))


# ------------------------------------------------------------------ Pareto machinery
def test_non_dominated_and_hypervolume_by_hand():
    F = np.array([[0.0, 1.0], [0.5, 0.5], [1.0, 0.0], [0.6, 0.6], [0.5, 0.5]])
    # (0.6, 0.6) is dominated by (0.5, 0.5); equal points do not dominate each other
    assert non_dominated(F).tolist() == [True, True, True, False, True]
    # staircase of (0,1), (.5,.5), (1,0) up to (2,2): 2*1 + 1.5*0.5 + 1*0.5 = 3.25
    assert hypervolume(F, [2.0, 2.0]) == pytest.approx(3.25, rel=1e-12)
    assert hypervolume(F[:1], [2.0, 2.0]) == pytest.approx(2.0, rel=1e-12)
    assert hypervolume(np.array([[3.0, 3.0]]), [2.0, 2.0]) == 0.0


def test_three_objective_hypervolume_matches_a_box():
    # one point: the box up to the reference; pymoo's indicator must give its volume
    assert hypervolume(np.array([[0.0, 0.5, 0.25]]), [1, 1, 1]) == pytest.approx(0.375)


# ------------------------------------------------------------------ planted fronts
def test_nsga2_reaches_the_planted_zdt1_front():
    """800 evaluations, population 20. Measured over seeds 0-3: hypervolume 98.8-99.1 % of
    the exact front's (0.87667 up to (1.1, 1.1)), mean distance to the front 0.002-0.006.
    The bound 98 % leaves room for the discreteness of a ~140-point front (a deficit of about
    1/(2N) ≈ 0.4 %) and for the last ~1 % of convergence; a Sobol sample of the same 800
    points reaches only 54-68 % (checked below), so the test discriminates."""
    r = optimise(ZDT, surrogates.zdt1, SearchSettings("nsga2", budget=800, population=20,
                                                      seed=0))
    assert len(r.table) == 800 and r.evaluated == 800
    F = minimised_objectives(r.front, ZDT)
    ratio = hypervolume(F, [1.1, 1.1]) / surrogates.ZDT1_HYPERVOLUME
    gd = distance_to_front(F, surrogates.zdt1_front()).mean()
    assert ratio >= 0.98, ratio
    assert gd <= 0.01, gd
    X = qmc.Sobol(3, seed=0).random_base2(10)[:800]
    S = np.array([[row["f1"], row["f2"]] for row in (surrogates.zdt1(*x) for x in X)])
    assert hypervolume(S[non_dominated(S)], [1.1, 1.1]) / surrogates.ZDT1_HYPERVOLUME < 0.98


def test_nsga2_front_respects_the_constraint():
    """min (x, y) with x² + y² ≥ 1: the front lies on the unit arc.  Constraint domination
    drives the search there (the table holds many infeasible designs, the front none);
    measured max distance to the arc 0.026-0.043 over seeds 0-2 at 400 evaluations (the
    front is populated only where the boundary is reached), hence 0.05."""
    r = optimise(CIRCLE, surrogates.quarter_circle,
                 SearchSettings("nsga2", budget=400, population=20, seed=0))
    assert (r.table["radius_squared"] < 1.0).sum() > 50            # it did meet the limit
    assert (r.front["radius_squared"] >= 1.0).all()
    F = r.front[["f1", "f2"]].to_numpy()
    assert np.abs(np.hypot(F[:, 0], F[:, 1]) - 1.0).max() <= 0.05
    assert len(r.front) >= 15


# ------------------------------------------------------------------ planted optima
def test_bayes_finds_the_constrained_optimum():
    """min (x−0.8)² + (y−0.8)² with x + y ≤ 1: 0.18 at (0.5, 0.5) on the constraint.
    24 evaluations (8 Latin hypercube + 16 GP proposals).  Measured with seeds 0-2: f within
    0.09-0.54 % of 0.18, (x, y) within 0.008-0.028 of (0.5, 0.5) (along the constraint line
    f grows only quadratically, so the position is the looser of the two).  Bounds: 2 % on
    f, 0.03 on the position; no reported best may break the constraint."""
    r = optimise(BOWL, surrogates.pinched_bowl, SearchSettings("bayes", budget=24, startup=8,
                                                               seed=0))
    assert r.best["sum_xy"] <= 1.0
    assert r.best["f"] == pytest.approx(0.18, rel=0.02)
    assert math.hypot(r.best["x"] - 0.5, r.best["y"] - 0.5) <= 0.03
    # the same 24 points from a Latin hypercube get nowhere near
    X = qmc.LatinHypercube(2, seed=0).random(24)
    ok = [surrogates.pinched_bowl(*x)["f"] for x in X if x.sum() <= 1.0]
    assert min(ok) > 0.18 * 1.02


def test_failed_evaluations_are_infeasible_and_stay_out_of_the_front():
    """The evaluation raises for x > 0.7: such rows are failures (stored with their message),
    never the best; the optimum (0.3, 0.6) is found anyway (0.01: the population's spread
    after 160 evaluations, measured 0.002)."""
    p = DesignProblem((Variable("x", 0.0, 1.0), Variable("y", 0.0, 1.0)), (Objective("f"),))
    r = optimise(p, surrogates.failing_half, SearchSettings("nsga2", budget=160,
                                                            population=16, seed=3))
    failed = r.table[~r.table["success"]]
    assert len(failed) > 0 and (failed["x"] > 0.7).all()
    assert failed["message"].str.contains("planted failure").all()
    assert r.best["x"] <= 0.7
    assert math.hypot(r.best["x"] - 0.3, r.best["y"] - 0.6) <= 0.01


# ------------------------------------------------------------------ reproducibility
def test_same_seed_same_run_other_seed_other_run():
    s = SearchSettings("nsga2", budget=48, population=8, seed=5)
    a = optimise(ZDT, surrogates.zdt1, s).table
    b = optimise(ZDT, surrogates.zdt1, s).table
    c = optimise(ZDT, surrogates.zdt1, SearchSettings("nsga2", budget=48, population=8,
                                                      seed=6)).table
    assert a[["point", "f1", "f2"]].equals(b[["point", "f1", "f2"]])
    assert set(a["point"]) != set(c["point"])


def test_discrete_levels_are_decoded_and_repeats_answered_once():
    """A discrete variable (e.g. the number of shims 0, 3 or 4) takes the level of the unit
    sub-interval; designs that round to the same levels are evaluated once."""
    v = Variable("shims", values=(4, 0, 3))
    assert v.values == (0.0, 3.0, 4.0)
    assert [v.decode(u) for u in (0.0, 0.33, 0.34, 0.99, 1.0)] == [0.0, 0.0, 3.0, 4.0, 4.0]
    assert v.decode(v.encode(3.0)) == 3.0
    p = DesignProblem((Variable("x", values=(0.0, 0.5, 1.0)),
                       Variable("y", values=(0.0, 0.9))), (Objective("f"),),
                      (Constraint("sum_xy", upper=1.0),))
    r = optimise(p, surrogates.pinched_bowl, SearchSettings("nsga2", budget=40,
                                                            population=8, seed=0))
    assert r.evaluated == len(r.table) <= 6                    # 3 × 2 distinct designs
    assert r.repeated == 40 - r.evaluated                      # the rest: answered once
    # by hand: (0, 0.9) f = 0.65 beats (1, 0) 0.68, (0.5, 0) 0.73; (0.5, 0.9) breaks x + y ≤ 1
    assert (r.best["x"], r.best["y"]) == (0.0, 0.9)


# ------------------------------------------------------------------ the store
def _store(tmp_path, problem, outputs, resume=False, name="run"):
    return ResultStore.create(tmp_path / name, study="t", study_hash="h" * 64,
                              schema=store_schema(problem, outputs), resume=resume)


def test_resume_of_a_finished_run_evaluates_nothing_and_gives_the_same_answer(tmp_path):
    s = SearchSettings("nsga2", budget=48, population=8, seed=1)
    outputs = {"f1": "float64", "f2": "float64"}
    first = optimise(ZDT, surrogates.zdt1, s, store=_store(tmp_path, ZDT, outputs))
    again = optimise(ZDT, surrogates.zdt1, s,
                     store=_store(tmp_path, ZDT, outputs, resume=True))
    assert (first.evaluated, first.reused) == (48, 0)
    assert (again.evaluated, again.reused) == (0, 48)
    cols = ["point", "evaluation", "x0", "x1", "x2", "f1", "f2"]
    assert again.table[cols].equals(first.table[cols])
    stored = _store(tmp_path, ZDT, outputs, resume=True).read()
    assert len(stored) == 48 and stored["point"].is_unique


def test_bayes_resume_asks_the_same_designs(tmp_path):
    """A Bayesian run cut after 12 of 16 evaluations (a smaller budget stands in for the
    kill), then resumed with the full budget: the 12 are answered from the store, 4 are
    new, and the table equals an uninterrupted run's."""
    outputs = {"f": "float64", "sum_xy": "float64"}
    full = optimise(BOWL, surrogates.pinched_bowl, SearchSettings("bayes", budget=16,
                                                                  startup=6, seed=2))
    optimise(BOWL, surrogates.pinched_bowl, SearchSettings("bayes", budget=12, startup=6,
                                                           seed=2),
             store=_store(tmp_path, BOWL, outputs))
    resumed = optimise(BOWL, surrogates.pinched_bowl,
                       SearchSettings("bayes", budget=16, startup=6, seed=2),
                       store=_store(tmp_path, BOWL, outputs, resume=True))
    assert (resumed.reused, resumed.evaluated) == (12, 4)
    assert resumed.table[["point", "f"]].equals(full.table[["point", "f"]])


# ------------------------------------------------------------------ bad input
@pytest.mark.parametrize("make, rule", [
    (lambda: Variable("c", 30e-6, 20e-6), "low < high"),
    (lambda: Variable("c", 1.0, 1.0), "low < high"),
    (lambda: Variable("c", 0.0, 1.0, scale="log"), "low > 0"),
    (lambda: Variable("c", values=()), "must not be empty"),
    (lambda: Constraint("h"), "lower or an upper"),
    (lambda: Constraint("h", lower=2.0, upper=1.0), "lower limit must be <= upper"),
    (lambda: Objective("p", "most"), "must be one of"),
    (lambda: DesignProblem((Variable("x", 0, 1), Variable("x", 0, 2)), (Objective("f"),)),
     "unique"),
    (lambda: SearchSettings("cmaes"), "must be one of"),
    (lambda: SearchSettings(budget=0), ">= 1"),
    (lambda: optimise(ZDT, surrogates.zdt1, SearchSettings("bayes")), "one objective"),
    (lambda: optimise(ZDT, surrogates.zdt1, SearchSettings(), fixed={"x0": 1.0}),
     "also a design variable"),
    (lambda: store_schema(ZDT, {"f1": "float64"}), "not an output column"),
])
def test_bad_input_is_one_parameter_error(make, rule):
    with pytest.raises(ParameterError, match=rule):
        make()


def test_pareto_front_of_an_infeasible_table_is_empty():
    r = optimise(CIRCLE, surrogates.quarter_circle, SearchSettings("nsga2", budget=8,
                                                                   population=8, seed=0))
    strict = DesignProblem(CIRCLE.variables, CIRCLE.objectives,
                           (Constraint("radius_squared", lower=5.0),))   # unreachable
    assert pareto_front(r.table, strict).empty
