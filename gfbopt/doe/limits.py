"""Bounded work: the size of a sampled job estimated from its inputs, before anything starts.

:func:`plan_size` counts the points of a sample plan without building it (exact integer
arithmetic, so ``n = 2**63 - 1`` or ``levels = 1000`` over five variables is a number, not a
crash), and :func:`check_size` refuses a job beyond :data:`MAX_POINTS` with one line giving
the estimate (points, memory, time) and the option that raises the limit.  The time
estimate is deliberately rough (a cost per point and grid cell per analysis, measured on
one core of the reference machine, docs/doe.md); it is stated as "about".

Fixed inputs are checked against the rules of the analysis's inputs
(:data:`INPUT_RULES`) before any solve, so ``length_ratio = -1`` is exit 2 at once, not
one failed row per point.
"""
from __future__ import annotations

import math

from ..errors import ParameterError

#: largest number of points of one sampled job (``--max-points`` / ``max_points`` raises it)
MAX_POINTS = 100_000
#: seconds per point and per grid cell, one core (static, linear threshold, onset speed)
SECONDS_PER_CELL = {"static": 1.5e-4, "linear_threshold": 6e-4, "onset_speed": 1.2e-2,
                    "function": 0.0}
#: bytes per point and column in memory (the sample table, the rows written)
BYTES_PER_VALUE = 64

#: rule per input name: (test, text of the rule)
INPUT_RULES = {
    "bearing_number": (lambda v: v > 0, "must be > 0"),
    "compliance": (lambda v: v >= 0, "must be >= 0"),
    "length_ratio": (lambda v: v > 0, "must be > 0"),
    "top_foil_coefficient": (lambda v: v >= 0, "must be >= 0"),
    "eccentricity": (lambda v: 0 <= v < 1, "must lie in [0, 1)"),
    "load": (lambda v: v >= 0, "must be >= 0"),
    "seam_angle_deg": (lambda v: 0 <= v < 360, "must lie in [0, 360) degrees"),
    "loss_factor": (lambda v: v >= 0, "must be >= 0"),
    "rotor_mass_kg": (lambda v: v > 0, "must be > 0 (rotor mass per bearing)"),
    "load_newton": (lambda v: v >= 0, "must be >= 0"),
    "speed_low_rpm": (lambda v: v > 0, "must be > 0"),
    "speed_high_rpm": (lambda v: v > 0, "must be > 0"),
    **{name: (lambda v: v > 0, "must be > 0 [m or Pa]")
       for name in ("bump_pitch", "bump_thickness", "bump_half_length", "radial_clearance",
                    "bump_youngs_modulus", "top_foil_thickness", "length", "radius")},
}


def check_fixed(fixed: dict, where) -> None:
    """Every fixed input against its rule (``where``: a :class:`~gfbopt.studies.spec.Where`
    or None for plain names); low < high for the speed range when both are fixed."""
    def error(name, value, rule):
        if where is None:
            return ParameterError(name, value, rule)
        return (where / name).error(value, rule)

    for name, value in fixed.items():
        rule = INPUT_RULES.get(name)
        if rule is None or isinstance(value, (str, bool)) or value is None:
            continue
        if not math.isfinite(value) or not rule[0](value):
            raise error(name, value, rule[1] if math.isfinite(value) else "must be finite")
    low, high = fixed.get("speed_low_rpm"), fixed.get("speed_high_rpm")
    if low is not None and high is not None and not low < high:
        raise error("speed_high_rpm", high, f"must be > speed_low_rpm = {low:g}")


def plan_size(plan) -> int:
    """Number of points of ``plan`` (:class:`~gfbopt.doe.SamplePlan`), computed exactly."""
    variables = plan.variables
    if plan.method == "factorial":
        size = 1
        for v in variables:
            size *= plan.levels if v.is_range else len(v.values)
        return size
    if plan.method == "list":
        return len(variables[0].values)
    if plan.method == "saltelli":
        return int(plan.n) * (2 * len(variables) + 2)
    return int(plan.n)


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    if seconds < 3 * 86400:
        return f"{seconds / 3600:.0f} h"
    return f"{seconds / 86400:.3g} days"


def estimate(points: int, columns: int, analysis: str, cells: int, workers: int) -> str:
    """'N points, about M MB in memory, about T on W workers' (the estimate, as text)."""
    memory = points * max(1, columns) * BYTES_PER_VALUE / 1e6
    seconds = points * cells * SECONDS_PER_CELL.get(analysis, 0.0) / max(1, workers)
    text = f"{points:,} points, about {memory:,.3g} MB in memory"
    if seconds > 0:
        text += f", about {_duration(seconds)} on {workers} worker(s)"
    return text


def check_size(points: int, *, columns: int, analysis: str, cells: int, workers: int,
               max_points: int = MAX_POINTS, name: str = "sampling") -> str:
    """The estimate (text); ParameterError naming ``name`` when ``points > max_points``."""
    text = estimate(points, columns, analysis, cells, workers)
    if points > max_points:
        raise ParameterError(name, points, f"the job is too large: {text}; the limit is "
                             f"{max_points:,} points (raise it with --max-points, or "
                             "max_points= in Python)")
    return text
