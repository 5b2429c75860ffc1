"""What a design search optimises: variables with ranges, objectives, constraints.

A :class:`DesignProblem` is the optimiser-independent statement of a design task:

* :class:`Variable` — a design variable on a range (linear or logarithmic) or a list of
  discrete levels (e.g. the number of shims 0, 3, 4 or of pads 1–3).  The optimisers work in
  the unit cube; :meth:`Variable.decode` maps a unit coordinate to the value (a discrete
  variable takes the level of the sub-interval the coordinate falls in), so the search is
  well scaled whatever the units and a discrete variable needs no special operator.
* :class:`Objective` — a column of the evaluation row to minimise or maximise.
* :class:`Constraint` — a column of the row with a lower and/or upper limit.  Its
  normalised violation ``g`` (≤ 0 feasible) is (value − upper)/scale or (lower − value)/scale,
  with ``scale`` the limit's magnitude unless given, so violations of quantities in different
  units are comparable (pymoo sums them into one constraint violation).

An evaluation that failed (``success`` false, or a NaN objective or constraint) is infeasible
by an extra violation of :data:`FAILED_VIOLATION`: the optimisers never prefer it, and it
never enters a Pareto front.
"""
from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..doe.sampling import Variable as SampledVariable
from ..errors import ParameterError

SENSES = ("min", "max")
#: normalised violation given to a failed evaluation (larger than any physical one we expect)
FAILED_VIOLATION = 1e3


def _finite(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be a real number") from None
    if not math.isfinite(v):
        raise ParameterError(name, value, "must be finite")
    return v


@dataclass(frozen=True)
class Variable(SampledVariable):
    """A design variable: ``low``–``high`` (``scale`` linear or log) or discrete ``values``
    (sorted levels).  Validated as a sampled input of the design-of-experiments machinery
    (:class:`gfbopt.doe.sampling.Variable`); adds the unit-cube coding the optimisers use."""

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.values is not None:
            levels = tuple(sorted({_finite(f"{self.name}.values", v) for v in self.values}))
            object.__setattr__(self, "values", levels)

    @property
    def discrete(self) -> bool:
        return self.values is not None

    def decode(self, u: float) -> float:
        """The value at unit coordinate ``u`` ∈ [0, 1] (clipped)."""
        u = min(max(float(u), 0.0), 1.0)
        if self.discrete:
            return float(self.values[min(int(u * len(self.values)), len(self.values) - 1)])
        if self.scale == "log":
            return float(math.exp(math.log(self.low) + u * math.log(self.high / self.low)))
        return float(self.low + u * (self.high - self.low))

    def encode(self, value: float) -> float:
        """The unit coordinate of ``value`` (a discrete level: the middle of its interval)."""
        if self.discrete:
            k = int(np.argmin([abs(v - value) for v in self.values]))
            return (k + 0.5) / len(self.values)
        if self.scale == "log":
            return math.log(value / self.low) / math.log(self.high / self.low)
        return (value - self.low) / (self.high - self.low)


@dataclass(frozen=True)
class Objective:
    """An output column to minimise (``sense='min'``) or maximise (``'max'``)."""

    name: str
    sense: str = "min"

    def __post_init__(self) -> None:
        if self.sense not in SENSES:
            raise ParameterError(f"objectives.{self.name}", self.sense,
                                 f"must be one of {', '.join(SENSES)}")

    def minimised(self, value: float) -> float:
        """The value in minimisation form (−value for a maximised objective)."""
        return value if self.sense == "min" else -value


@dataclass(frozen=True)
class Constraint:
    """``lower ≤ row[name] ≤ upper`` (either may be None); ``scale`` normalises the
    violation (default: the magnitude of the limit, 1 for a zero limit)."""

    name: str
    lower: Optional[float] = None
    upper: Optional[float] = None
    scale: Optional[float] = None

    def __post_init__(self) -> None:
        if self.lower is None and self.upper is None:
            raise ParameterError(f"constraints.{self.name}", None, "needs a lower or an "
                                 "upper limit")
        if (self.lower is not None and self.upper is not None
                and not self.lower <= self.upper):
            raise ParameterError(f"constraints.{self.name}", (self.lower, self.upper),
                                 "lower limit must be <= upper limit")
        if self.scale is not None and not (math.isfinite(self.scale) and self.scale > 0):
            raise ParameterError(f"constraints.{self.name}.scale", self.scale,
                                 "must be finite and > 0")

    def _scale(self, limit: float) -> float:
        return self.scale if self.scale is not None else (abs(limit) or 1.0)

    def violation(self, value: float) -> float:
        """Normalised violation (≤ 0: met); a NaN value is :data:`FAILED_VIOLATION`."""
        if value is None or not math.isfinite(value):
            return FAILED_VIOLATION
        g = -math.inf
        if self.upper is not None:
            g = max(g, (value - self.upper) / self._scale(self.upper))
        if self.lower is not None:
            g = max(g, (self.lower - value) / self._scale(self.lower))
        return g


def _number(row: dict, name: str) -> float:
    value = row.get(name)
    try:
        v = float(value)
    except (TypeError, ValueError):
        return math.nan
    return v


@dataclass(frozen=True)
class DesignProblem:
    """Variables, objectives (one or more) and constraints of a design search."""

    variables: tuple
    objectives: tuple
    constraints: tuple = ()

    def __post_init__(self) -> None:
        for key in ("variables", "objectives", "constraints"):
            object.__setattr__(self, key, tuple(getattr(self, key)))
        if not self.variables:
            raise ParameterError("variables", (), "must name at least one design variable")
        if not self.objectives:
            raise ParameterError("objectives", (), "must name at least one objective")
        names = [v.name for v in self.variables]
        if len(set(names)) != len(names):
            raise ParameterError("variables", names, "names must be unique")
        outputs = [o.name for o in self.objectives]
        if len(set(outputs)) != len(outputs):
            raise ParameterError("objectives", outputs, "names must be unique")
        clash = sorted(set(names) & (set(outputs) | {c.name for c in self.constraints}))
        if clash:
            raise ParameterError("variables", clash[0], "is a design variable and an output")

    @property
    def names(self) -> list:
        return [v.name for v in self.variables]

    @property
    def dimension(self) -> int:
        return len(self.variables)

    def decode(self, u) -> dict:
        """The design (name → value) at unit coordinates ``u``."""
        return {v.name: v.decode(x) for v, x in zip(self.variables, u)}

    def encode(self, design: dict) -> np.ndarray:
        return np.array([v.encode(design[v.name]) for v in self.variables])

    def key(self, design: dict) -> str:
        """A key of the design (its exact float64 values): the same design, asked again by
        the optimiser or by a resumed run, is answered from the store."""
        text = ";".join(f"{n}={float(design[n]).hex()}" for n in self.names)
        return hashlib.sha256(text.encode()).hexdigest()[:20]

    def failed(self, row: dict) -> bool:
        """A row that cannot be ranked: the evaluation failed or an objective is NaN."""
        if not bool(row.get("success", False)):
            return True
        return any(not math.isfinite(_number(row, o.name)) for o in self.objectives)

    def objective_vector(self, row: dict) -> np.ndarray:
        """The objectives in minimisation form (0 for a failed row: it is infeasible)."""
        if self.failed(row):
            return np.zeros(len(self.objectives))
        return np.array([o.minimised(_number(row, o.name)) for o in self.objectives])

    def violation_vector(self, row: dict) -> np.ndarray:
        """Normalised constraint violations (≤ 0 met), the last entry being the failure
        flag (:data:`FAILED_VIOLATION` for a failed row, else 0)."""
        g = [c.violation(_number(row, c.name)) for c in self.constraints]
        return np.array(g + [FAILED_VIOLATION if self.failed(row) else 0.0])

    def feasible(self, row: dict) -> bool:
        return bool(np.all(self.violation_vector(row) <= 0.0))

    def to_dict(self) -> dict:
        return {"variables": [{"name": v.name, "low": v.low, "high": v.high,
                               "scale": v.scale, "values": v.values}
                              for v in self.variables],
                "objectives": [{"name": o.name, "sense": o.sense} for o in self.objectives],
                "constraints": [{"name": c.name, "lower": c.lower, "upper": c.upper,
                                 "scale": c.scale} for c in self.constraints]}
