"""A bounded one-dimensional search for the best design value of an expensive, possibly
multi-modal figure of merit with a constraint (e.g. the onset speed of instability against the
compliance coefficient S, with the minimum film thickness as a limit).

The figure of merit is not smooth everywhere (a threshold can jump between whirl branches) and
each evaluation costs a static solve and a linear threshold, so the search is

1. a scan on ``n_scan`` points of the interval (logarithmic or linear spacing), evaluated in
   one batch (the caller may run the batch in parallel);
2. a bounded Brent refinement (scipy ``minimize_scalar``, method 'bounded') between the scan
   neighbours of the best feasible scan point, with infeasible or failed points counted as
   worst;
3. the *band*: every scanned or refined value whose figure of merit lies within ``band`` of the
   best (relative), so that a flat optimum is reported as the range it is rather than one
   number.

An optimum on a bound is reported as such (``on_bound``): it says the limit, not the physics,
decides.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Optional, Sequence

import numpy as np
from scipy.optimize import minimize_scalar

from ..errors import ParameterError


@dataclass(frozen=True)
class Evaluation:
    """One evaluated design value: ``merit`` (larger is better), ``feasible`` (constraints
    met), ``success`` (the evaluation itself worked) and the evaluator's row (``details``)."""

    value: float
    merit: float
    feasible: bool
    success: bool
    details: dict


@dataclass(frozen=True)
class SearchResult:
    """The best value, its merit, the band of near-best values and every evaluation.

    best : the design value with the highest feasible merit (nan if none feasible)
    merit : its figure of merit
    band : (low, high) of the values within the relative ``band`` of the best merit
    on_bound : 'low', 'high' or '' — the best value sits on a bound of the interval
    evaluations : every evaluation in the order made (scan first, then refinement)
    success, message
    """

    best: float
    merit: float
    band: tuple
    on_bound: str
    evaluations: tuple
    success: bool
    message: str = ""


def _grid(bounds: tuple, n: int, log: bool) -> np.ndarray:
    lo, hi = bounds
    return np.geomspace(lo, hi, n) if log else np.linspace(lo, hi, n)


def maximise_on_interval(evaluate_batch: Callable[[Sequence[float]], Sequence[Evaluation]],
                         bounds: tuple, *, n_scan: int = 9, log: bool = True,
                         refine: bool = True, xtol: float = 0.01, band: float = 0.02,
                         max_refine: int = 12) -> SearchResult:
    """Maximise a figure of merit on ``bounds`` = (low, high) (see the module docstring).

    Parameters
    ----------
    evaluate_batch : callable taking a list of values and returning one :class:`Evaluation`
        per value (in order); it decides feasibility (limits) and may run in parallel
    bounds : (low, high), low < high (> 0 when ``log``)
    n_scan : number of scan points (≥ 3)
    log : scan and refine in log of the value (for quantities spanning decades, like S)
    refine : run the bounded Brent refinement after the scan
    xtol : relative tolerance of the refinement on the value
    band : relative width of the merit band reported around the best
    max_refine : cap on refinement evaluations
    """
    lo, hi = (float(bounds[0]), float(bounds[1]))
    if not (math.isfinite(lo) and math.isfinite(hi)) or lo >= hi:
        raise ParameterError("bounds", bounds, "must be finite with low < high")
    if log and lo <= 0:
        raise ParameterError("bounds", bounds, "must be > 0 for a logarithmic search")
    if n_scan < 3:
        raise ParameterError("n_scan", n_scan, "must be >= 3")
    values = _grid((lo, hi), n_scan, log)
    evaluations = list(evaluate_batch(list(values)))
    scan = {e.value: e for e in evaluations}

    def score(e: Evaluation) -> float:
        return e.merit if (e.success and e.feasible and math.isfinite(e.merit)) else -math.inf

    ok = [e for e in evaluations if score(e) > -math.inf]
    if not ok:
        return SearchResult(math.nan, math.nan, (math.nan, math.nan), "", tuple(evaluations),
                            False, "no feasible design value in the interval: every scan "
                            "point failed or broke a limit")
    k = int(np.argmax([score(scan[v]) for v in values]))
    if refine and 0 < k < n_scan - 1:
        a, b = values[k - 1], values[k + 1]
        to_x = (lambda v: math.log(v)) if log else (lambda v: v)
        from_x = (lambda x: math.exp(x)) if log else (lambda x: x)
        count = [0]

        def negative(x: float) -> float:
            count[0] += 1
            e = evaluate_batch([from_x(x)])[0]
            evaluations.append(e)
            s = score(e)
            return -s if math.isfinite(s) else 1e300

        minimize_scalar(negative, bounds=(to_x(a), to_x(b)), method="bounded",
                        options={"xatol": xtol if log else xtol * (b - a),
                                 "maxiter": max_refine})
    best = max(evaluations, key=score)
    merit = score(best)
    near = [e.value for e in evaluations if score(e) >= merit - band * abs(merit)]
    on_bound = ("low" if math.isclose(best.value, lo, rel_tol=1e-9) else
                "high" if math.isclose(best.value, hi, rel_tol=1e-9) else "")
    return SearchResult(best.value, merit, (min(near), max(near)), on_bound,
                        tuple(evaluations), True)


def evaluations_frame(result: SearchResult, name: str = "value"):
    """Every evaluation of a search as a pandas table (one row per design value, sorted)."""
    import pandas as pd

    rows = [{name: e.value, "merit": e.merit, "feasible": e.feasible, "success": e.success,
             **e.details} for e in result.evaluations]
    return pd.DataFrame.from_records(rows).sort_values(name).reset_index(drop=True)


def planted_surrogate(optimum: float, width: float = 0.5,
                      limit: Optional[float] = None) -> Callable:
    """A cheap test surrogate: merit = 1 − (log S − log optimum)² / width² (positive near the
    optimum, like an onset speed), feasible below ``limit`` (used by the tests to check the
    search finds a planted optimum)."""
    def evaluate(values):
        out = []
        for v in values:
            merit = 1.0 - ((math.log(v) - math.log(optimum)) / width) ** 2
            feasible = limit is None or v <= limit
            out.append(Evaluation(v, merit, feasible, True, {}))
        return out
    return evaluate
