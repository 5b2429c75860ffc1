"""Which limit binds a design search, and by how much — computed from the evaluated designs.

For every constraint of a :class:`~gfbopt.design.problem.DesignProblem`, over the table of
evaluated designs (one row per design, the constraint columns and the measure of merit,
by default the first onset speed [rpm]):

* how many designs break it (``designs_breaking``) and how many break it and no other limit
  (``designs_excluded_only_by_it``: the designs that relaxing this limit alone would admit);
* for the best design (the chosen feasible one), whether it is *active*: its normalised
  distance to the limit, ``−Constraint.violation`` (the distance over the limit's magnitude
  by default), is at most :data:`ACTIVE_TOLERANCE`;
* the best design that breaks this limit and meets every other one: the merit it reaches,
  its value of the constrained quantity and by how much it breaks the limit — relaxing the
  limit to that value would admit it (e.g. "relaxing the start-up film limit from 1.5 to
  1.0 µm would allow 19,600 rpm": the best onset among the evaluated designs whose film is
  ≥ 1.0 µm and that meet the other limits).  Only designs better than the best feasible one
  are reported (a relaxation that gains nothing is not one).

A failed evaluation (``success`` false) breaks no limit here: it is counted apart
(``failed``).  Nothing is evaluated: this is a reading of the table.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Optional

import pandas as pd

from .problem import DesignProblem

#: largest normalised distance of a met limit for it to count as active [-] (2 % of the
#: limit's magnitude: finer than the search can place a design, coarser than round-off)
ACTIVE_TOLERANCE = 0.02

#: the limits in words for people: column → (what, unit)
LIMIT_WORDS = {
    "min_film_lowest_speed_um": ("start-up film limit", "µm"),   # lowest speed, heaviest load
    "lift_off_speed_rpm": ("lift-off speed limit", "rpm"),
    "capacity_margin": ("load-capacity margin limit", "-"),
    "bump_stress_mpa": ("bump stress limit", "MPa"),
    "top_foil_sag_ratio": ("top-foil sag limit", "-"),
    "bump_closing_ratio": ("bump closing limit", "-"),
    "first_onset_speed_rpm": ("first-onset limit", "rpm"),
}


@dataclass(frozen=True)
class LimitReport:
    """One constraint read over the evaluated designs (module docstring); values in the
    constraint column's unit, merit in the merit column's (rpm for the first onset)."""

    name: str
    words: str
    unit: str
    bound: str                       # "lower" (value ≥ limit) or "upper" (value ≤ limit)
    limit: float
    designs_breaking: int
    designs_excluded_only_by_it: int
    best_value: float                # the best design's value (NaN: no best design)
    best_distance: float             # its normalised distance to the limit (≥ 0: met)
    active: bool
    relaxed_merit: float             # best merit among designs breaking only this limit
    relaxed_value: float             # that design's value: the limit that would admit it
    relaxed_breach: float            # by how much it breaks the limit, relative (> 0)
    relaxed_point: str
    #: the relaxations worth making, least first: (relaxed limit, merit it allows, point)
    #: of every design breaking only this limit that beats every design nearer the limit
    relaxation_steps: tuple = ()

    def to_dict(self) -> dict:
        return asdict(self)


def _value(row, name: str) -> float:
    try:
        return float(row[name])
    except (KeyError, TypeError, ValueError):
        return math.nan


def binding_limits(table: pd.DataFrame, problem: DesignProblem, best: Optional[dict],
                   merit: str = "first_onset_speed_rpm",
                   tolerance: float = ACTIVE_TOLERANCE) -> list:
    """A :class:`LimitReport` per constraint of ``problem`` over ``table`` (module
    docstring); ``best``: the chosen design's row (None: no design meets every limit);
    ``merit``: the column whose larger value is better (the constraint on it, if any, gets
    no relaxation figures: relaxing it would be measured by itself)."""
    rows = table.to_dict(orient="records")
    ok = [r for r in rows if bool(r.get("success", False))]
    broken = [[c.violation(_value(r, c.name)) > 0.0 for c in problem.constraints] for r in ok]
    best_merit = _value(best, merit) if best is not None else -math.inf
    out = []
    for k, c in enumerate(problem.constraints):
        breaking = [r for r, b in zip(ok, broken) if b[k]]
        only = [r for r, b in zip(ok, broken) if b[k] and sum(b) == 1]
        value = _value(best, c.name) if best is not None else math.nan
        distance = -c.violation(value) if math.isfinite(value) else math.nan
        better = [r for r in only if _value(r, merit) > best_merit] if c.name != merit else []
        top = max(better, key=lambda r: _value(r, merit), default=None)
        limit = c.lower if c.lower is not None else c.upper
        relaxed = _value(top, c.name) if top is not None else math.nan
        breach = (c.violation(relaxed) if top is not None else math.nan)
        steps, reached = [], best_merit
        for r in sorted(better, key=lambda r: c.violation(_value(r, c.name))):
            if _value(r, merit) > reached:
                reached = _value(r, merit)
                steps.append((_value(r, c.name), reached, str(r.get("point", ""))))
        words, unit = LIMIT_WORDS.get(c.name, (f"limit on {c.name}", ""))
        out.append(LimitReport(
            c.name, words, unit, "lower" if c.lower is not None else "upper", float(limit),
            len(breaking), len(only), value, distance,
            bool(math.isfinite(distance) and 0.0 <= distance <= tolerance),
            _value(top, merit) if top is not None else math.nan, relaxed, breach,
            str(top.get("point", "")) if top is not None else "", tuple(steps)))
    return out


def failed_count(table: pd.DataFrame) -> int:
    """Designs whose evaluation failed (counted apart from the limits)."""
    if "success" not in table:
        return len(table)
    return int((~table["success"].fillna(False).astype(bool)).sum())


def _number(value: float, unit: str) -> str:
    text = f"{value:,.0f}" if abs(value) >= 1000 else f"{value:.3g}"
    return text + ("" if unit in ("", "-") else f" {unit}")


def limits_text(reports: list, total: int, failed: int, merit_unit: str = "rpm",
                tolerance: float = ACTIVE_TOLERANCE) -> list:
    """The limit report in sentences (README notes): the exclusions, the active limits of
    the best design and each relaxation that would gain something."""
    if not reports:
        return ["Limits: this study has no limit besides the evaluation succeeding."]
    counts = "; ".join(f"{r.words} {'≥' if r.bound == 'lower' else '≤'} "
                       f"{_number(r.limit, r.unit)} broken by {r.designs_breaking} "
                       f"({r.designs_excluded_only_by_it} by it alone)" for r in reports)
    lines = [f"Limits over the {total} designs evaluated ({failed} failed to evaluate): "
             f"{counts}."]
    active = [r for r in reports if r.active]
    if any(math.isfinite(r.best_distance) for r in reports):
        lines.append("Active limits of the chosen design (within "
                     f"{tolerance:.0%} of the limit): "
                     + (", ".join(f"{r.words} ({_number(r.best_value, r.unit)} against "
                                  f"{_number(r.limit, r.unit)})" for r in active)
                        if active else "none (every limit has more than that margin)")
                     + ".")
    for r in reports:
        if math.isfinite(r.relaxed_merit):
            text = (f"Relaxing the {r.words} from {_number(r.limit, r.unit)} to "
                    f"{_number(r.relaxed_value, r.unit)} ({r.relaxed_breach:.0%} past it) "
                    f"would allow a first onset of {_number(r.relaxed_merit, merit_unit)} "
                    f"(design {r.relaxed_point}, the best evaluated design that breaks this "
                    "limit alone)")
            if len(r.relaxation_steps) > 1:
                first = r.relaxation_steps[0]
                text += (f"; the least relaxation that gains anything, to "
                         f"{_number(first[0], r.unit)}, allows "
                         f"{_number(first[1], merit_unit)}")
            lines.append(text + ".")
    return lines


def limits_frame(reports: list) -> pd.DataFrame:
    """The reports as a table (``binding_limits.csv``), one row per constraint."""
    columns = {"name": "limit_name", "words": "limit_words", "unit": "limit_unit",
               "bound": "limit_bound", "limit": "limit_value",
               "designs_breaking": "designs_breaking",
               "designs_excluded_only_by_it": "designs_excluded_only_by_it",
               "best_value": "chosen_value", "best_distance": "chosen_distance_to_limit",
               "active": "active_at_chosen", "relaxed_merit": "relaxed_first_onset_speed_rpm",
               "relaxed_value": "relaxed_limit_value", "relaxed_breach": "relaxed_breach",
               "relaxed_point": "relaxed_point"}
    return pd.DataFrame([{columns[k]: v for k, v in r.to_dict().items() if k in columns}
                         for r in reports], columns=list(columns.values()))
