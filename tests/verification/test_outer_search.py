"""The bounded outer search of the stability-driven design finds planted optima."""
import math

import pytest

from gfbopt.design.outer_search import (Evaluation, maximise_on_interval, planted_surrogate)
from gfbopt.errors import ParameterError


@pytest.mark.parametrize("optimum", [0.13, 0.9, 3.7])
def test_finds_an_interior_planted_optimum(optimum):
    """Brent refinement in log S: the optimum is found to the requested 1 % (xtol = 0.01 in
    log S is a relative 1 % in S)."""
    result = maximise_on_interval(planted_surrogate(optimum), (0.05, 8.0), xtol=0.002)
    assert result.success and result.on_bound == ""
    assert result.best == pytest.approx(optimum, rel=0.01)
    # the 2 % merit band of 1 − (Δ log S / 0.5)² is |Δ log S| ≤ 0.5 √0.02 ≈ 0.071
    assert result.band[0] < optimum < result.band[1]
    assert math.log(result.band[1] / result.band[0]) <= 2 * 0.0708


def test_optimum_on_a_limit_is_reported_on_the_bound_of_the_feasible_set():
    """Planted optimum at S = 3 but a limit allows S <= 1.2 only: the best feasible value is
    the largest feasible scan/refine point, below 1.2."""
    result = maximise_on_interval(planted_surrogate(3.0, limit=1.2), (0.1, 8.0), n_scan=15)
    assert result.success
    assert result.best <= 1.2
    assert all(e.value <= 1.2 or not e.feasible for e in result.evaluations)


def test_optimum_on_the_interval_bound_says_so():
    result = maximise_on_interval(planted_surrogate(20.0), (0.1, 2.0))
    assert result.on_bound == "high" and result.best == pytest.approx(2.0)


def test_nothing_feasible_is_a_failed_result_not_an_exception():
    def failing(values):
        return [Evaluation(v, math.nan, False, False, {"message": "no"}) for v in values]
    result = maximise_on_interval(failing, (0.1, 1.0))
    assert not result.success and "no feasible design value" in result.message


@pytest.mark.parametrize("bounds, match", [((1.0, 0.5), "low < high"),
                                           ((0.0, 1.0), "must be > 0 for a logarithmic")])
def test_bad_bounds(bounds, match):
    with pytest.raises(ParameterError, match=match):
        maximise_on_interval(planted_surrogate(1.0), bounds)
