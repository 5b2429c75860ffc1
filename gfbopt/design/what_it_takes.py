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

:func:`what_it_would_take` runs it for every lever on one design (first onsets only, then
one full evaluation at each answer: does the changed design still meet every limit?), each
evaluation streamed into a :class:`gfbopt.doe.ResultStore` as it finishes, keyed by the
lever and its value, so a resumed run answers the evaluations it holds from the store.
"""
from __future__ import annotations

import dataclasses
import hashlib
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


# ---------------------------------------------------------------- on a design
def start_value(lever: Lever, system, design: dict, settings) -> float:
    """The lever's value for ``design`` as it is: the evaluation's loss factor, no side
    load (0 N), the design's value of the variable or the bearing's as built."""
    if lever.name == "loss_factor":
        return float(settings.loss_factor)
    if lever.name == "side_load_n":
        return 0.0
    bearing, var = (lever.name.split(":", 1) if ":" in lever.name else (None, lever.name))
    for key in (lever.name, var):
        if key in design:
            return float(design[key])
    support = next((b for b in system.bearings if b.name == bearing), system.bearings[0])
    g = support.geometry
    bore = getattr(g.build, "bore", None)
    preloaded = bore is not None and getattr(bore, "kind", "round") != "round"
    built = {"radial_clearance_um": g.radial_clearance * 1e6, "length_mm": g.length * 1e3,
             "bump_pitch_mm": g.bump_pitch * 1e3, "bump_half_length_mm":
             g.bump_half_length * 1e3, "bump_thickness_um": g.bump_thickness * 1e6,
             "compliance": getattr(g, "compliance", math.nan),
             "preload_depth_um": 1e6 * float(getattr(bore, "preload_depth", 0.0) or 0.0),
             "preload_offset_deg": bore.offset_deg if preloaded else settings.bore_offset_deg,
             "preload_width_deg": bore.width_deg if preloaded else settings.bore_width_deg}
    return float(built.get(var, math.nan))


def check_starts(levers: tuple, system, settings, file: str) -> None:
    """Every lever has a value to start from on this rotor (a design variable the space
    does not vary is taken as built): else one ParameterError naming ``file`` and the key,
    before any solve."""
    for lever in levers:
        if not math.isfinite(start_value(lever, system, {}, settings)):
            raise ParameterError(f"{file}: what_it_would_take.{lever.name}", lever.name,
                                 "has no as-built value on the rotor's bearings to start "
                                 "from: make it a design variable of the study")


def lever_point(lever: Lever, value: float, system, design: dict, settings) -> dict:
    """The keyword arguments of an evaluation of ``design`` with the lever at ``value``."""
    if lever.name == "loss_factor":
        return {"system": system, "settings": dataclasses.replace(settings,
                                                                 loss_factor=value), **design}
    if lever.name == "side_load_n":
        from ..inputs.rotor_system import SideLoad

        loads = system.side_loads
        if value > 0.0:
            direction = (system.gravity_direction_deg if lever.direction_deg is None
                         else lever.direction_deg)
            loads = loads + (SideLoad(value, direction, lever.position),)
        return {"system": dataclasses.replace(system, side_loads=loads),
                "settings": settings, **design}
    return {"system": system, "settings": settings, **{**design, lever.name: value}}


def point_key(lever: Lever, value: float, onset_only: bool) -> str:
    """The store key of one lever evaluation (exact float64 value)."""
    text = f"{lever.name}={float(value).hex()};{int(onset_only)}"
    return hashlib.sha256(text.encode()).hexdigest()[:20]


#: the columns of the what-it-would-take store (and table)
STORE_SCHEMA = {"point": "string", "lever": "string", "lever_value": "float64",
                "onset_only": "bool", "first_onset_speed_rpm": "float64",
                "onset_status": "string", "first_mode": "string",
                "min_film_lowest_speed_um": "float64", "total_power_loss_w": "float64",
                "feasible": "bool", "success": "bool", "message": "string",
                "wall_time_s": "float64"}


def _lever_task(argument: dict) -> dict:
    """One lever evaluation in a worker (or here): ``run_points`` with the worker's solver
    cache, so a failure is a row with ``success = False``."""
    from ..parallel import run_points, worker_cache

    return run_points(argument["function"], [argument["point"]], workers=1,
                      cache=worker_cache())[0]


class LeverEvaluations:
    """Evaluations of one design with a lever moved, each answered from ``store`` when it
    holds it and otherwise evaluated (``evaluate``, through ``run_tasks``, the run's
    executor) and appended to the store as soon as it finishes (a killed run loses only the
    evaluations in flight).  :meth:`prefetch` evaluates many at once (the scans of every
    lever, on the run's workers); :meth:`row` one.  ``evaluated`` counts the evaluations
    made, ``reused`` those answered from the store."""

    def __init__(self, evaluate: Callable, system, design: dict, settings, problem,
                 store=None, run_tasks=None):
        self.evaluate, self.system, self.design = evaluate, system, dict(design)
        self.settings, self.problem, self.store = settings, problem, store
        self.run_tasks = run_tasks
        self.known = {}
        if store is not None:
            frame = store.read()
            frame = frame.astype(object).where(frame.notna(), None)
            self.known = {str(r["point"]): r for r in frame.to_dict(orient="records")}
        self.from_store = set(self.known)
        self.evaluated = self.reused = 0
        self.rows: list = []
        self.seconds = math.nan          # wall time of the searches (set by the caller)

    def prefetch(self, asked: list) -> None:
        """Evaluate the (lever, value, onset_only) triples not yet known, at once."""
        from ..runtime import InfrastructureError
        from .optimiser import executor, lost_designs

        todo, keys = [], set()
        for lever, value, onset_only in asked:
            key = point_key(lever, value, onset_only)
            if key in self.from_store:
                self.from_store.discard(key)            # counted once
                self.reused += 1
            if key not in self.known and key not in keys:
                keys.add(key)
                todo.append((key, lever, float(value), onset_only))
        if not todo:
            return
        arguments = [{"function": self.evaluate, "point": {**lever_point(
            lever, value, self.system, self.design, self.settings), "onset_only": only}}
            for _, lever, value, only in todo]
        lost = []
        for k, result in (self.run_tasks or executor(1))(_lever_task, arguments):
            if k is None:
                continue
            if isinstance(result, BaseException):
                lost.append(result)
                continue
            key, lever, value, onset_only = todo[k]
            row = {c: result.get(c) for c in STORE_SCHEMA if c in result}
            row.update(point=key, lever=lever.name, lever_value=value, onset_only=onset_only,
                       success=bool(result.get("success", False)))
            row["feasible"] = (None if onset_only else         # limits not evaluated
                               bool(row["success"]) and self.problem.feasible(result))
            if self.store is not None:
                self.store.append([row])
            self.known[key] = row
            self.evaluated += 1
        if lost:
            raise InfrastructureError(lost_designs(lost, len(todo), "lever evaluations"))

    def row(self, lever: Lever, value: float, onset_only: bool = True) -> dict:
        """The evaluation of the design with ``lever`` at ``value`` (made if not known)."""
        key = point_key(lever, value, onset_only)
        self.prefetch([(lever, value, onset_only)])
        row = self.known[key]
        self.rows.append(row)
        return row

    def onset(self, lever: Lever) -> Callable[[float], float]:
        def at(value: float) -> float:
            r = self.row(lever, value)
            return float(r["first_onset_speed_rpm"]) if r.get("success") and \
                r.get("first_onset_speed_rpm") is not None else math.nan
        return at


@dataclass(frozen=True)
class LeverAnswer:
    """What one lever would take (:func:`what_it_would_take`): its start and bounds, the
    threshold found (``value`` NaN: none within physical limits), the change from the start,
    the onset there, whether the changed design meets every limit and its start-up film,
    the onset reached at the better bound, the evaluations spent, and a note."""

    lever: str
    unit: str
    words: str
    start: float
    low: float
    high: float
    found: bool
    value: float
    change: float
    onset_rpm: float
    meets_limits: Optional[bool]
    min_film_lowest_speed_um: float
    limit_value: float
    limit_onset_rpm: float
    evaluations: int
    message: str

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


def what_it_would_take(levers: tuple, evaluations: LeverEvaluations, start_onset: float,
                       progress: Optional[Callable[[float], None]] = None) -> list:
    """A :class:`LeverAnswer` per lever for ``evaluations``' design (its first onset
    ``start_onset`` [rpm] at the evaluation's settings), the target the settings' top
    speed; ``progress``: the fraction of the levers done.  The scans of every lever are
    evaluated first, as one batch on the run's workers (a scan value past a crossing is
    then evaluated too: a few evaluations more when a lever crosses early, in return for
    the parallel batch), then each lever's refinement in turn."""
    ev = evaluations
    top = ev.settings.top_speed_rpm
    starts = [start_value(lever, ev.system, ev.design, ev.settings) for lever in levers]
    for lever, start in zip(levers, starts):
        if not math.isfinite(start):
            raise ParameterError(f"what_it_would_take.{lever.name}", lever.name,
                                 "has no value on this rotor's bearings to start from")
    ev.prefetch([(lever, x, True) for lever, start in zip(levers, starts)   # one batch
                 for x in scan_values(start, lever.low, lever.high)])
    out = []
    for k, (lever, start) in enumerate(zip(levers, starts)):
        before = len(ev.rows)
        known = start_onset if lever.name != "side_load_n" or start == 0.0 else None
        t = threshold_search(ev.onset(lever), start, lever.low, lever.high, top, known)
        meets, film = None, math.nan
        if t.found:
            full = ev.row(lever, t.value, onset_only=False)
            meets = bool(full.get("feasible"))
            film = float(full.get("min_film_lowest_speed_um") or math.nan)
        out.append(LeverAnswer(lever.name, lever.unit, lever.words, start, lever.low,
                               lever.high, t.found, t.value, t.value - start
                               if t.found else math.nan, t.onset_rpm, meets, film,
                               t.limit_value, t.limit_onset_rpm, len(ev.rows) - before,
                               t.message))
        if progress is not None:
            progress((k + 1) / len(levers))
    return out


def _number(value: float, unit: str) -> str:
    text = f"{value:,.0f}" if abs(value) >= 1000 else f"{value:.4g}"
    return text + ("" if unit in ("", "-") else f" {unit}")


def answers_text(answers: list, top: float, onset: float, evaluated: int = 0,
                 reused: int = 0, seconds: float = math.nan, grid: str = "") -> str:
    """The answers in one sentence (README notes); ``evaluated``, ``reused``: the
    evaluations made and those answered from the store; ``seconds``: the wall time of
    the levers' searches; ``grid``: the grid they were evaluated on."""
    parts = []
    for a in answers:
        if a.found:
            limits = {True: "meets every limit", False: "but then breaks a limit",
                      None: "limits not evaluated"}[a.meets_limits]
            parts.append(f"{a.words} from {_number(a.start, a.unit)} to "
                         f"{_number(a.value, a.unit)} (a change of {a.change:+.4g}"
                         f"{'' if a.unit in ('', '-') else ' ' + a.unit}; first onset "
                         f"{_number(a.onset_rpm, 'rpm')}, {limits})")
        else:
            reached = (f"at {_number(a.limit_value, a.unit)} the first onset is "
                       f"{_number(a.limit_onset_rpm, 'rpm')}"
                       if math.isfinite(a.limit_onset_rpm) else a.message)
            parts.append(f"{a.words}: none within physical limits "
                         f"[{a.low:g}, {a.high:g}] ({reached})")
    return (f"What it would take to be stable to {_number(top, 'rpm')} (the chosen design, "
            f"first onset {_number(onset, 'rpm')}), one lever at a time: "
            + "; ".join(parts) + f" ({evaluated} evaluations"
            + (f" on the {grid} grid" if grid else "") + f", {reused} more answered from "
            "the store" + (f"; {seconds:.1f} s of wall time" if math.isfinite(seconds) else "")
            + ").")
