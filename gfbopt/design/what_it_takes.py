"""What it would take: the smallest change of one lever outside the design space that makes
a design stable to the top speed, found by a one-dimensional search.

A study names its levers in ``[what_it_would_take]``, each with the bounds it can physically
take (the lever's unit)::

    [what_it_would_take]
    loss_factor = {low = 0.0, high = 0.5}          # η of both bearings' bump foils [-]
    side_load_n = {low = 0.0, high = 60.0}         # a static side load on the rotor [N]
    preload_depth_um = {low = 0.0, high = 14.0}    # a design variable beyond its range
    "A:length_mm" = {low = 20.0, high = 60.0}      # one bearing's length

Levers (:data:`LEVERS`): ``loss_factor`` (the evaluation's η, from the search's, the low end
of the uncertain band), ``side_load_n`` (a static force at ``position`` [m] from the centre
of gravity, default 0, towards ``direction_deg`` [deg from +x in the direction of
rotation], default the gravity's; 0 N is the rotor as it is), and every continuous design
variable of the bearings (:data:`gfbopt.design.rotor_objectives.DESIGN_VARIABLES` except the
whole-number ones), shared or for one bearing (``A:…``).  A design variable's start is the
design's value, or the bearing's as built when the space does not vary it.

:func:`threshold_search` is the search on g(x) = first onset(x) − top speed along one
lever: from the design's value x₀ towards each bound, ``steps`` evenly spaced values until
g ≥ 0 (a bracket), then the Illinois method (secant steps that keep the bracket, never
slower than about bisection) in that bracket to :data:`VALUE_TOLERANCE` of the bounds'
span; the answer is the crossing nearer x₀ (the smallest change).  When no scanned value
reaches the top speed the answer is "none within physical limits", with the first onset
reached at the better bound.  The scan can
miss a crossing that comes and goes between two scanned values (a non-monotone onset);
the values scanned are in the table so the reader can see it.

:func:`gfbopt.design.lever_runs.what_it_would_take` runs it for every lever on one design
(first onsets only, then one full evaluation at each answer: does the changed design still
meet every limit?), each evaluation streamed into a :class:`gfbopt.doe.ResultStore` as it
finishes, keyed by the lever and its value, so a resumed run answers the evaluations it
holds from the store.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Optional

from ..errors import ParameterError
from .rotor_objectives import DESIGN_VARIABLES, zone_variable

#: the answer's value is found to this fraction of the lever's bounds' span [-]
VALUE_TOLERANCE = 1e-5
#: values scanned from the design's towards each bound before the bisection [-]
SCAN_STEPS = 4
#: levers that are not design variables: unit, words
LEVERS = {"loss_factor": ("-", "loss factor η of both bearings' bump foils"),
          "side_load_n": ("N", "static side load on the rotor")}
#: design variables that cannot be a lever (whole numbers: no bisection)
WHOLE_NUMBERS = ("preload_count", "pads")
#: keys of a lever's table
LEVER_KEYS = ("low", "high", "direction_deg", "position")


@dataclass(frozen=True)
class Lever:
    """One lever: its name (``loss_factor``, ``side_load_n`` or a design variable, maybe
    ``A:…``), unit, words and bounds [low, high] in its unit; a side load's direction
    [deg] (None: the gravity's) and axial position [m from the centre of gravity]."""

    name: str
    unit: str
    words: str
    low: float
    high: float
    direction_deg: Optional[float] = None
    position: float = 0.0


def _variable(name: str) -> str:
    return name.split(":", 1)[1] if ":" in name else name


def parse_levers(table, file: str, bearings: tuple = ("A", "B"), variables: tuple = ()
                 ) -> tuple:
    """The levers of a study's ``[what_it_would_take]`` table, checked before any solve:
    a known lever, bounds ``low < high`` inside its physical range, a design variable not
    named both for both bearings and per bearing (``variables``: the names the space
    varies).  A mistake is one :class:`ParameterError` naming ``file`` and the key."""
    if table is None:
        return ()
    if not isinstance(table, dict):
        raise ParameterError(f"{file}: what_it_would_take", table, "must be a table of "
                             "lever = {low = ..., high = ...}")
    out = []
    for name, spec in table.items():
        key = f"{file}: what_it_would_take.{name}"
        bearing, var = (name.split(":", 1) if ":" in name else (None, name))
        if name in LEVERS:
            unit, words = LEVERS[name]
        elif var in DESIGN_VARIABLES and var not in WHOLE_NUMBERS or zone_variable(var):
            unit = DESIGN_VARIABLES[var][0] if var in DESIGN_VARIABLES else \
                DESIGN_VARIABLES[zone_variable(var)[1]][0]
            words = (DESIGN_VARIABLES[var][1] if var in DESIGN_VARIABLES else var)
            words += f" of bearing {bearing}" if bearing else " of both bearings"
        else:
            rule = ("is a whole number: a one-dimensional search needs a continuous lever"
                    if var in WHOLE_NUMBERS else
                    f"is not a lever (known: {', '.join(LEVERS)} and the continuous design "
                    "variables, shared or 'A:name')")
            raise ParameterError(key, name, rule)
        if zone_variable(var) and not any(_variable(v) == var for v in variables):
            raise ParameterError(key, name, "a per-zone bump variable is a lever only when "
                                 "the study varies it (its start is the design's value)")
        if bearing is not None and bearing not in bearings:
            raise ParameterError(key, name, f"names no bearing of the rotor "
                                 f"({', '.join(bearings)})")
        shared = bearing is None and name not in LEVERS
        if shared and any(":" in v and _variable(v) == var for v in variables):
            each = ", ".join(f"{b}:{var}" for b in bearings)
            raise ParameterError(key, name, f"the study designs {var} per bearing: name the "
                                 f"lever per bearing ({each})")
        if not isinstance(spec, dict) or "low" not in spec or "high" not in spec:
            raise ParameterError(key, spec, "a lever needs its physical bounds: "
                                 "{low = ..., high = ...} in its unit "
                                 f"({unit})")
        extra = sorted(set(spec) - set(LEVER_KEYS))
        if extra or (name != "side_load_n" and set(spec) - {"low", "high"}):
            bad = extra[0] if extra else sorted(set(spec) - {"low", "high"})[0]
            known = "low, high" + (", direction_deg, position" if name == "side_load_n" else "")
            raise ParameterError(f"{key}.{bad}", spec[bad], f"is not a key of this lever "
                                 f"(known: {known})")
        numbers = {}
        for k in spec:
            v = spec[k]
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ParameterError(f"{key}.{k}", v, "must be a finite number")
            numbers[k] = float(v)
        low, high = numbers["low"], numbers["high"]
        if not low < high:
            raise ParameterError(key, [low, high], "must have low < high")
        floor, ceiling = _physical(name, var)
        if low < floor or high > ceiling:
            raise ParameterError(key, [low, high], f"must lie in [{floor:g}, {ceiling:g}] "
                                 f"{unit} (the lever's physical range)")
        out.append(Lever(name, unit, words, low, high, numbers.get("direction_deg"),
                         numbers.get("position", 0.0)))
    return tuple(out)


def _physical(name: str, var: str) -> tuple:
    """The physical range of a lever's values (its unit)."""
    if name == "loss_factor":
        return 0.0, 1.0
    if name == "side_load_n" or var == "preload_depth_um":
        return 0.0, math.inf
    if var == "preload_offset_deg":
        return -360.0, 360.0
    if var == "preload_width_deg":
        return math.ulp(0.0), 360.0
    return math.ulp(0.0), math.inf                  # a length, clearance, thickness: > 0


# ---------------------------------------------------------------- the 1-D search
@dataclass(frozen=True)
class Threshold:
    """The answer of :func:`threshold_search`: ``found``; ``value`` (NaN: none) and the
    first onset there [rpm]; of the farthest values reached towards each bound (the bound,
    or the last before an evaluation failed) the one whose onset is the higher and that
    onset [rpm] (what the lever reaches at its limit); every value tried and its onset; a
    note."""

    found: bool
    value: float
    onset_rpm: float
    limit_value: float
    limit_onset_rpm: float
    tried: tuple
    message: str = ""


def scan_values(start: float, low: float, high: float, steps: int = SCAN_STEPS) -> list:
    """The values the scan of :func:`threshold_search` tries, towards ``high`` then
    ``low`` (``steps`` each, evenly spaced from ``start``; none towards a bound equal to
    the start)."""
    return [start + (bound - start) * k / steps for bound in (high, low) if bound != start
            for k in range(1, steps + 1)]


def threshold_search(onset: Callable[[float], float], start: float, low: float,
                     high: float, target: float, start_onset: Optional[float] = None, *,
                     steps: int = SCAN_STEPS,
                     tolerance: float = VALUE_TOLERANCE) -> Threshold:
    """The value nearest ``start`` where ``onset(x) ≥ target`` (module docstring):
    ``onset`` returns the first onset [rpm] at lever value ``x`` (NaN: the evaluation
    failed); ``start_onset``: onset(start) when known.  Each value is evaluated once."""
    tried: dict = {}

    def f(x: float) -> float:
        if x not in tried:
            tried[x] = float(onset(x))
        return tried[x]

    if start_onset is not None:
        tried[start] = float(start_onset)
    y0 = f(start)
    if y0 >= target:
        return Threshold(True, start, y0, start, y0, tuple(tried.items()),
                         "the design already reaches the top speed")
    xtol = tolerance * (high - low)
    found, ends, notes = [], [], []
    values = scan_values(start, low, high, steps)
    for way in range(len(values) // steps):
        previous = start
        for x in values[way * steps:(way + 1) * steps]:
            y = f(x)
            if not math.isfinite(y):
                notes.append(f"the evaluation failed at {x:.4g}")
                break
            if y >= target:
                found.append(_refine(f, previous, x, target, xtol))
                break
            previous = x
        if previous != start:           # the farthest value reached this way
            ends.append((previous, tried[previous]))
    tried_items = tuple(sorted(tried.items()))
    end = max(ends, key=lambda e: e[1], default=(math.nan, math.nan))
    if found:
        value = min(found, key=lambda v: abs(v - start))
        return Threshold(True, value, tried.get(value, math.nan), end[0], end[1],
                         tried_items, "; ".join(notes))
    return Threshold(False, math.nan, math.nan, end[0], end[1], tried_items,
                     "; ".join(notes) or "none within physical limits")


#: most steps of the refinement (the Illinois method halves the bracket at worst every
#: other step: 60 steps take any bracket below 1e-9 of its width)
REFINE_STEPS = 60


def _refine(f, below: float, above: float, target: float, xtol: float) -> float:
    """The crossing in the bracket [below, above] (onset < target at ``below``, ≥ at
    ``above``; either may be the larger value) by the Illinois method (regula falsi whose
    retained end's value is halved when it is kept twice: secant steps on a smooth onset,
    never slower than about bisection), until the bracket is ``xtol`` wide; returns the end
    that reaches the target, so the answer is stable to the top speed.  An evaluation that
    fails inside the bracket stops the refinement there (the ``above`` end is kept)."""
    a, b = below, above
    ga, gb = f(a) - target, f(b) - target
    side = 0
    for _ in range(REFINE_STEPS):
        if abs(b - a) <= xtol or gb == 0.0:          # the bracket is narrow, or exact
            break
        x = b - gb * (b - a) / (gb - ga) if gb != ga else 0.5 * (a + b)
        if not min(a, b) < x < max(a, b):
            x = 0.5 * (a + b)
        y = f(x)
        if not math.isfinite(y):
            break
        gx = y - target
        if gx >= 0.0:
            b, gb = x, gx
            if side == 1:
                ga *= 0.5
            side = 1
        else:
            a, ga = x, gx
            if side == -1:
                gb *= 0.5
            side = -1
    return b
