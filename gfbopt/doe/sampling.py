"""Design-of-experiments samples of operating points and bump geometries.

A sample plan names its variables (each a range in linear or log scale, or an explicit list of
values) and a method:

=================  ====================================================================
method             what it gives
=================  ====================================================================
``factorial``      every combination of ``levels`` values per range variable
``lhs``            Latin hypercube, ``n`` points (scipy.stats.qmc.LatinHypercube)
``sobol``          scrambled Sobol sequence, ``n`` points (a power of two is best)
``list``           the explicit ``values`` of every variable, zipped (equal lengths)
``saltelli``       the Saltelli/Sobol design for variance-based sensitivity
                   (N (2d + 2) points; :mod:`gfbopt.doe.sensitivity`)
=================  ====================================================================

Every random method takes a ``seed``, so a plan is reproducible from the study file alone.
References: M. D. McKay, R. J. Beckman, W. J. Conover, Technometrics 21(2) (1979) 239–245
(LHS); I. M. Sobol', USSR Comput. Math. Math. Phys. 7(4) (1967) 86–112; A. B. Owen,
"Scrambling Sobol' and Niederreiter–Xing points", J. Complexity 14(4) (1998) 466–489;
A. Saltelli et al., Comput. Phys. Commun. 181(2) (2010) 259–270.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np
import pandas as pd
from scipy.stats import qmc

from ..errors import ParameterError

METHODS = ("factorial", "lhs", "sobol", "list", "saltelli")
SCALES = ("linear", "log")


@dataclass(frozen=True)
class Variable:
    """One sampled input: a ``low``–``high`` range (``scale`` linear or log) or explicit
    ``values``.  The name is the input's name in the analysis (e.g. ``bearing_number``)."""

    name: str
    low: Optional[float] = None
    high: Optional[float] = None
    scale: str = "linear"
    values: Optional[tuple] = None

    def __post_init__(self) -> None:
        if self.values is not None:
            if self.low is not None or self.high is not None:
                raise ParameterError(f"{self.name}", self.values, "give either values or a "
                                     "low–high range, not both")
            if len(self.values) == 0:
                raise ParameterError(f"{self.name}.values", self.values, "must not be empty")
            object.__setattr__(self, "values", tuple(self.values))
            return
        if self.low is None or self.high is None:
            raise ParameterError(f"{self.name}", None, "needs low and high (or values)")
        lo, hi = float(self.low), float(self.high)
        if not (math.isfinite(lo) and math.isfinite(hi)) or lo >= hi:
            raise ParameterError(f"{self.name}", (self.low, self.high),
                                 "range must be finite with low < high")
        if self.scale not in SCALES:
            raise ParameterError(f"{self.name}.scale", self.scale,
                                 f"must be one of {', '.join(SCALES)}")
        if self.scale == "log" and lo <= 0:
            raise ParameterError(f"{self.name}", (self.low, self.high),
                                 "a log-scale range must have low > 0")
        object.__setattr__(self, "low", lo)
        object.__setattr__(self, "high", hi)

    @property
    def is_range(self) -> bool:
        return self.values is None

    def from_unit(self, u: np.ndarray) -> np.ndarray:
        """Map u ∈ [0, 1] to the range (linear or logarithmic)."""
        if self.scale == "log":
            return np.exp(np.log(self.low) + u * (np.log(self.high) - np.log(self.low)))
        return self.low + u * (self.high - self.low)


@dataclass(frozen=True)
class SamplePlan:
    """Variables, method and its settings: ``n`` points (lhs, sobol, saltelli base N),
    ``levels`` per range variable (factorial), ``seed`` (lhs, sobol, saltelli)."""

    variables: tuple
    method: str = "lhs"
    n: int = 0
    levels: int = 0
    seed: Optional[int] = 0
    fixed: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "variables", tuple(self.variables))
        if self.method not in METHODS:
            raise ParameterError("sampling.method", self.method,
                                 f"must be one of {', '.join(METHODS)}")
        if not self.variables:
            raise ParameterError("sampling.variables", (), "must name at least one variable")
        names = [v.name for v in self.variables]
        if len(set(names)) != len(names):
            raise ParameterError("sampling.variables", names, "names must be unique")
        clash = sorted(set(names) & set(self.fixed))
        if clash:
            raise ParameterError(f"sampling.variables.{clash[0]}", clash[0],
                                 "is both sampled and fixed")
        if self.method in ("lhs", "sobol", "saltelli"):
            if not isinstance(self.n, int) or isinstance(self.n, bool) or self.n < 1:
                raise ParameterError("sampling.n", self.n, f"must be an integer >= 1 for "
                                     f"method '{self.method}'")
            lists = [v.name for v in self.variables if not v.is_range]
            if lists:
                raise ParameterError(f"sampling.variables.{lists[0]}", "values",
                                     f"method '{self.method}' samples ranges; give low and "
                                     "high")
        if self.method == "factorial":
            if any(v.is_range for v in self.variables) and (
                    not isinstance(self.levels, int) or self.levels < 2):
                raise ParameterError("sampling.levels", self.levels, "must be an integer >= 2 "
                                     "for a factorial plan with ranges")
        if self.method == "list":
            ranges = [v.name for v in self.variables if v.is_range]
            if ranges:
                raise ParameterError(f"sampling.variables.{ranges[0]}", "range",
                                     "method 'list' needs explicit values")
            lengths = {len(v.values) for v in self.variables}
            if len(lengths) != 1:
                raise ParameterError("sampling.variables", sorted(lengths),
                                     "explicit value lists must have equal lengths")

    @property
    def names(self) -> list[str]:
        return [v.name for v in self.variables]


def _unit_sample(plan: SamplePlan, d: int) -> np.ndarray:
    if plan.method == "lhs":
        return qmc.LatinHypercube(d=d, seed=plan.seed).random(plan.n)
    if plan.method == "sobol":
        return qmc.Sobol(d=d, scramble=True, seed=plan.seed).random(plan.n)
    raise AssertionError(plan.method)


def sample(plan: SamplePlan) -> pd.DataFrame:
    """The sample as a table: one row per point, one column per variable, plus the fixed
    inputs and a ``point`` index (0, 1, …) that identifies the point in the plan."""
    if plan.method == "factorial":
        axes = [np.asarray(v.values) if not v.is_range
                else v.from_unit(np.linspace(0.0, 1.0, plan.levels)) for v in plan.variables]
        rows = list(itertools.product(*axes))
        frame = pd.DataFrame(rows, columns=plan.names)
    elif plan.method == "list":
        frame = pd.DataFrame({v.name: list(v.values) for v in plan.variables})
    elif plan.method == "saltelli":
        from .sensitivity import saltelli_sample

        frame = saltelli_sample(plan)
    else:
        u = _unit_sample(plan, len(plan.variables))
        frame = pd.DataFrame({v.name: v.from_unit(u[:, k]) for k, v in enumerate(plan.variables)})
    for key, value in plan.fixed.items():
        frame[key] = value
    frame.insert(0, "point", np.arange(len(frame)))
    return frame
