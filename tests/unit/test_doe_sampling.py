"""Sample plans: reproducible, in range, the right size, bad plans refused in one line."""
import numpy as np
import pytest

from gfbopt.doe import SamplePlan, Variable, sample
from gfbopt.errors import ParameterError

VARS = (Variable("bearing_number", 0.5, 10.0, "log"), Variable("eccentricity", 0.1, 0.8))


@pytest.mark.parametrize("method, n", [("lhs", 37), ("sobol", 32)])
def test_random_plans_are_reproducible_and_in_range(method, n):
    plan = SamplePlan(VARS, method=method, n=n, seed=7, fixed={"compliance": 1.0})
    a, b = sample(plan), sample(plan)
    assert len(a) == n and a.equals(b)
    assert list(a["point"]) == list(range(n))
    assert a["bearing_number"].between(0.5, 10.0).all()
    assert a["eccentricity"].between(0.1, 0.8).all()
    assert (a["compliance"] == 1.0).all()
    assert not a.equals(sample(SamplePlan(VARS, method=method, n=n, seed=8)))


def test_lhs_puts_one_point_in_every_stratum():
    """Latin hypercube: each of the n equal-probability strata of each variable (in log for
    a log-scale range) holds exactly one point."""
    frame = sample(SamplePlan(VARS, method="lhs", n=20, seed=1))
    u = (np.log(frame["bearing_number"]) - np.log(0.5)) / (np.log(10.0) - np.log(0.5))
    assert sorted(np.floor(u * 20).astype(int)) == list(range(20))


def test_factorial_and_lists():
    plan = SamplePlan((Variable("bearing_number", 1.0, 4.0, "log"),
                       Variable("compliance", values=(0.0, 1.0, 2.0))),
                      method="factorial", levels=3)
    frame = sample(plan)
    assert len(frame) == 9
    assert sorted(set(np.round(frame["bearing_number"], 12))) == [1.0, 2.0, 4.0]
    listed = sample(SamplePlan((Variable("eccentricity", values=(0.2, 0.4)),
                                Variable("compliance", values=(1.0, 2.0))), method="list"))
    assert listed[["eccentricity", "compliance"]].values.tolist() == [[0.2, 1.0], [0.4, 2.0]]


@pytest.mark.parametrize("make, match", [
    (lambda: Variable("eccentricity", 0.8, 0.1), r"range must be finite with low < high"),
    (lambda: Variable("bearing_number", 0.0, 1.0, "log"), "log-scale range must have low > 0"),
    (lambda: SamplePlan(VARS, method="latin"), "sampling.method = 'latin': must be one of"),
    (lambda: SamplePlan(VARS, method="lhs", n=0), "sampling.n = 0: must be an integer >= 1"),
    (lambda: SamplePlan(VARS, method="saltelli", n=12).__class__ and
     sample(SamplePlan(VARS, method="saltelli", n=12)), "must be a power of two"),
    (lambda: SamplePlan(VARS, method="factorial", levels=1), "levels = 1: must be an integer"),
])
def test_bad_plans(make, match):
    with pytest.raises(ParameterError, match=match):
        make()
