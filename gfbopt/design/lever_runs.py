"""What it would take, on one design: each lever of a study's ``[what_it_would_take]``
(:mod:`.what_it_takes`: the levers and the one-dimensional search) applied to the chosen
design of a bearing-pair design run, its evaluations streamed into a
:class:`gfbopt.doe.ResultStore` keyed by the lever and its value, so a resumed run answers
the evaluations it holds from the store (:func:`what_it_would_take`).

A lever's start (:func:`start_value`) is the design as it is: the evaluation's loss factor,
no side load, the design's value of a variable or the bearing's as built; an evaluation with
the lever moved (:func:`lever_point`) changes the settings' loss factor, adds a static side
load to the rotor (at ``position`` from the centre of gravity, towards ``direction_deg``,
default the gravity's) or sets the design variable (shared, or for one bearing).
"""
from __future__ import annotations

import dataclasses
import hashlib
import math
from dataclasses import dataclass
from typing import Callable, Optional

from ..errors import ParameterError
from ..rotor.mode_search import UNSTABLE_LOW
from .what_it_takes import Lever, scan_values, threshold_search

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


def clearance_bound(lever: Lever, system, design: dict, settings) -> tuple:
    """(the lever, a note): a preload-depth lever whose high bound reaches the smallest
    radial clearance of the bearings it acts on (that of ``design``, or as built) is bounded
    by that clearance — a shim or lobe that deep closes the film, so the evaluation there
    fails — and the note says so; every other lever is returned as it is, with no note."""
    bearing, var = (lever.name.split(":", 1) if ":" in lever.name else (None, lever.name))
    if var != "preload_depth_um":
        return lever, ""
    names = [b.name for b in system.bearings if bearing is None or b.name == bearing]
    clearances = {b: start_value(Lever(f"{b}:radial_clearance_um", "µm", "", 0.0, 1.0),
                                 system, design, settings) for b in names}
    b, c = min(clearances.items(), key=lambda item: item[1])
    if not (math.isfinite(c) and lever.high >= c):
        return lever, ""
    return (dataclasses.replace(lever, high=c),
            f"bounded by bearing {b}'s radial clearance {c:.4g} µm (the study's bound "
            f"{lever.high:g} µm is deeper: a preload as deep as the clearance closes the film)")


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
            # the lever's position is from the centre of gravity (study_file.md); the
            # system's positions are from its own origin (the shaft's first end on a shaft)
            loads = loads + (SideLoad(value, direction,
                                      system.centre_of_gravity + lever.position),)
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
    bounded = [clearance_bound(lever, ev.system, ev.design, ev.settings) for lever in levers]
    levers = tuple(b[0] for b in bounded)
    ev.prefetch([(lever, x, True) for lever, start in zip(levers, starts)   # one batch
                 for x in scan_values(start, lever.low, lever.high)])
    out = []
    for k, (lever, start) in enumerate(zip(levers, starts)):
        before = len(ev.rows)
        known = start_onset if lever.name != "side_load_n" or start == 0.0 else None
        t = threshold_search(ev.onset(lever), start, lever.low, lever.high, top, known)
        meets, film = None, math.nan
        if not t.found and math.isfinite(t.limit_value):
            limit = ev.known.get(point_key(lever, t.limit_value, True)) or {}
            if limit.get("onset_status") == UNSTABLE_LOW:
                t = dataclasses.replace(t, message=(
                    f"at {_number(t.limit_value, lever.unit)} it is still {UNSTABLE_LOW} "
                    f"({_number(t.limit_onset_rpm, 'rpm')})"))
        if bounded[k][1]:                 # the preload lever stops at the clearance
            t = dataclasses.replace(t, message="; ".join(m for m in (bounded[k][1], t.message)
                                                         if m))
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
                       if math.isfinite(a.limit_onset_rpm) and UNSTABLE_LOW not in a.message
                       else a.message)
            note = (f"; {a.message}" if a.message and a.message != reached
                    and a.message != "none within physical limits" else "")
            parts.append(f"{a.words}: none within physical limits "
                         f"[{a.low:g}, {a.high:.4g}] ({reached}{note})")
    return (f"What it would take to be stable to {_number(top, 'rpm')} (the chosen design, "
            f"first onset {_number(onset, 'rpm')}), one lever at a time: "
            + "; ".join(parts) + f" ({evaluated} evaluations"
            + (f" on the {grid} grid" if grid else "") + f", {reused} more answered from "
            "the store" + (f"; {seconds:.1f} s of wall time" if math.isfinite(seconds) else "")
            + ").")
