"""Variance-based global sensitivity (Sobol indices) of a study output to its sampled inputs.

The Saltelli design (A. Saltelli et al., "Variance based sensitivity analysis of model output.
Design and estimator for the total sensitivity index", Comput. Phys. Commun. 181(2) (2010)
259–270) is sampled with SALib (J. Herman, W. Usher, "SALib: an open-source Python library for
sensitivity analysis", J. Open Source Softw. 2(9) (2017) 97) and the first-order (S1) and
total (ST) indices with their bootstrap 95 % confidence intervals are estimated from the study
table.  Log-scale variables are sampled uniformly in their logarithm.

The design comes in blocks of d + 2 rows per base sample (A, the d mixed rows AB_i, B).  A
point that failed (NaN output) invalidates its block only: whole blocks are dropped and the
number of base samples used is reported, so a few failed solves do not void the analysis.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..errors import ParameterError


def _problem(plan) -> dict:
    bounds = []
    for v in plan.variables:
        if v.scale == "log":
            bounds.append([float(np.log(v.low)), float(np.log(v.high))])
        else:
            bounds.append([v.low, v.high])
    return {"num_vars": len(plan.variables), "names": plan.names, "bounds": bounds}


def saltelli_sample(plan) -> pd.DataFrame:
    """The Saltelli design of ``plan`` (method 'saltelli', base size ``plan.n``): N (d + 2)
    rows, no second-order terms, reproducible from ``plan.seed``."""
    from SALib.sample import sobol as sobol_sample

    if plan.n & (plan.n - 1):
        raise ParameterError("sampling.n", plan.n, "must be a power of two for the Saltelli "
                             "design (Sobol sequence balance)")
    x = sobol_sample.sample(_problem(plan), plan.n, calc_second_order=False,
                            seed=plan.seed)
    cols = {}
    for k, v in enumerate(plan.variables):
        cols[v.name] = np.exp(x[:, k]) if v.scale == "log" else x[:, k]
    return pd.DataFrame(cols)


@dataclass(frozen=True)
class SobolIndices:
    """First-order and total Sobol indices of ``output`` per input (table), the number of
    base samples used, and how many points were dropped with their blocks."""

    output: str
    table: pd.DataFrame
    base_samples: int
    dropped_points: int
    success: bool
    message: str = ""

    def to_dict(self) -> dict:
        return {"output": self.output, "base_samples": self.base_samples,
                "dropped_points": self.dropped_points, "success": self.success,
                "message": self.message, "indices": self.table.to_dict(orient="records")}


def sobol_indices(plan, frame: pd.DataFrame, output: str, *, seed: int = 0) -> SobolIndices:
    """Sobol indices of column ``output`` of a finished Saltelli study ``frame`` (rows in
    plan order, identified by ``point``); ``seed`` fixes the bootstrap of the confidence
    intervals (the same table every run)."""
    from SALib.analyze import sobol as sobol_analyze

    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ParameterError("seed", seed, "must be an integer >= 0 (the bootstrap's seed)")
    if plan.method != "saltelli":
        raise ParameterError("sampling.method", plan.method, "Sobol indices need the "
                             "'saltelli' design")
    if output not in frame:
        raise ParameterError("output", output, f"is not a column of the study table "
                             f"(columns: {', '.join(map(str, frame.columns))})")
    d = len(plan.variables)
    frame = frame.sort_values("point")
    y = frame[output].to_numpy(dtype=float)
    if y.size % (d + 2):
        raise ParameterError("frame", y.size, f"must hold whole blocks of {d + 2} rows")
    blocks = y.reshape(-1, d + 2)
    good = np.all(np.isfinite(blocks), axis=1)
    dropped = int((~good).sum() * (d + 2))
    if good.sum() < 2:
        return SobolIndices(output, pd.DataFrame(), int(good.sum()), dropped, False,
                            f"{int(good.sum())} complete blocks: too few for Sobol indices")
    # SALib seeds its bootstrap only for a truthy seed (``if seed:``): 0 would leave the
    # confidence intervals random from run to run, so the seed passed is ``seed + 1``
    res = sobol_analyze.analyze(_problem(plan), blocks[good].ravel(),
                                calc_second_order=False, seed=int(seed) + 1)
    table = pd.DataFrame({"input": plan.names, "S1": res["S1"], "S1_conf": res["S1_conf"],
                          "ST": res["ST"], "ST_conf": res["ST_conf"]})
    return SobolIndices(output, table, int(good.sum()), dropped, True,
                        "" if not dropped else f"{dropped} points dropped with their blocks "
                        "(failed solves)")
