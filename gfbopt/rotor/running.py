"""The rotor's two bearings at their running condition: each bearing at its own
running clearance c(ω, T) and film viscosity μ(T_f) at each speed of the linear analyses
(onset of every mode, Campbell diagram, imbalance response).

A bearing whose file states ``[journal]`` and/or ``[thermal]`` (read by
``load_rotor(path, running=True)``, kept on :attr:`~gfbopt.inputs.rotor_system.
BearingSupport.running_tables`) gets at each speed N, before its equilibrium in
:func:`gfbopt.rotor.supports.support_states`:

1. the fixed point of :func:`gfbopt.thermal.running.running_point` under its own static load
   (:class:`~gfbopt.thermal.bearing.FilmDrag` on the bearing's own case: options, seam from
   its load, grid and build), seeded (``prior``) by the running point of the nearest speed
   already solved for that bearing on the same grid (else on any grid: the coarse guide's);
   its first static solve warm-starts from the support's own guess at N (the nearest
   speed's equilibrium, extrapolated);
2. the bearing at that running condition (:func:`gfbopt.thermal.bearing.warm_bearing`:
   ``radial_clearance`` = the running clearance, ``viscosity`` = μ(T_f)), whose
   equilibrium, linearisation and impedance are then today's, from the fixed point's last
   film (Newton fast path).

Λ, S, C and M̄ follow from the SI bearing (one conversion module); the build is the same
(the clearance is a parameter, no rebuild).  A rotor none of whose bearing files states the
tables has no running line (``RotorCase.running`` is None) and every analysis is today's,
bit for bit.  A bearing with ``[journal]`` alone has the centrifugal growth only (no static
solve).  No fixed point (thermal runaway) or a clearance that closes at a speed is a failure
of that speed, like a load beyond capacity: reported (``kind`` "thermal runaway" or
"closure"), never raised; :func:`runaway_limits` brackets the speed it starts from.
"""
from __future__ import annotations

import math
from dataclasses import replace
from typing import Optional

from ..errors import ParameterError
from ..thermal.bearing import FilmCase, FilmDrag, warm_bearing
from ..thermal.files import running_spec
from ..thermal.running import ISOTHERMAL, RunningPoint, running_point, speed_line

#: the kinds of a speed's failure at the running condition (SpeedStates.failure["kind"])
RUNAWAY, CLOSURE = "thermal runaway", "closure"
#: the fixed point's tolerance on the film temperature [K] (gfbopt.thermal.running)
TOLERANCE_K = 1e-2


class RunningLine:
    """Each bearing's :class:`~gfbopt.thermal.running.RunningSpec` (None: isothermal, cold
    clearance) and the running points solved so far, per (grid, bearing) and speed — the
    priors of the next speeds.  ``tolerance_k``: the fixed point's tolerance [K]."""

    def __init__(self, specs: tuple, names: tuple, tolerance_k: float = TOLERANCE_K):
        if not (isinstance(tolerance_k, (int, float)) and tolerance_k > 0):
            raise ParameterError("tolerance_k", tolerance_k, "must be > 0 [K]")
        self.specs, self.names, self.tolerance_k = tuple(specs), tuple(names), tolerance_k
        self.points: dict = {}              # (grid str, k) -> {speed: RunningPoint}
        self.drag_solves = 0                # the fixed points' static solves, all speeds
        self.fixed_points = 0

    def models(self) -> dict:
        """bearing name → which model is used (gfbopt.thermal.running's three names)."""
        return {n: (s.model_name if s is not None else ISOTHERMAL)
                for n, s in zip(self.names, self.specs)}

    def prior(self, grid, k: int, speed: float):
        """The prior of bearing ``k``'s fixed point at ``speed``: the DragSample of the
        nearest speed solved (this grid first, else any grid's), its torque ratio τ and
        outflow q̄ extrapolated (or interpolated) linearly in ln N through the next nearest
        speed's (as the equilibria's starts are, :func:`gfbopt.rotor.supports.
        predicted_starts`) — the first static solve is then close to the fixed point."""
        def good(points):
            return {s: p.sample for s, p in points.items()
                    if p.converged and p.sample is not None}
        samples = good(self.points.get((str(grid), k), {}))
        if not samples:
            samples = good({s: p for (g, j), pts in self.points.items() if j == k
                            for s, p in pts.items()})
        near = sorted(samples, key=lambda s: abs(math.log(s / speed)))[:2]
        if not near:
            return None
        first = samples[near[0]]
        if len(near) < 2 or near[0] == near[1]:
            return first
        second = samples[near[1]]
        step = math.log(speed / near[0]) / math.log(near[0] / near[1])
        step = max(-1.0, min(1.0, step))        # no farther than the two points apart
        tau = first.torque_ratio + step * (first.torque_ratio - second.torque_ratio)
        outflow = first.outflow + step * (first.outflow - second.outflow)
        if not (tau > 0 and outflow >= 0):
            return first
        return replace(first, torque_ratio=tau, outflow=outflow)

    def store(self, grid, k: int, point: RunningPoint) -> None:
        self.points.setdefault((str(grid), k), {})[point.speed_rpm] = point

    def at(self, grid, k: int, speed: float) -> Optional[RunningPoint]:
        return self.points.get((str(grid), k), {}).get(speed)


def running_line(system, tolerance_k: float = TOLERANCE_K) -> Optional[RunningLine]:
    """The running line of a rotor whose bearing files state ``[journal]``/``[thermal]``
    (each checked against its bearing before any solve: ParameterError names the bearing);
    None when neither bearing states them (today's analyses)."""
    specs = []
    for support in system.bearings:
        tables = support.tables()
        if not tables:
            specs.append(None)
            continue
        where = f"bearing {support.name} ({support.file or 'in Python'})"
        specs.append(running_spec(tables, support.geometry, where=where))
    if all(s is None for s in specs):
        return None
    return RunningLine(tuple(specs), tuple(b.name for b in system.bearings), tolerance_k)


def running_case(line: RunningLine, k: int, case, load, speed_rpm: float, guess,
                 cold_grid=None, cold_factor: int = 4):
    """(the case at the running condition, the equilibrium's start, the RunningPoint,
    failure dict or None) of bearing ``k`` at ``speed_rpm`` (module docstring).  Without a
    ``guess``, on a grid of at least ``cold_factor`` × ``cold_grid``'s cells, the first
    static solve starts from the equilibrium on ``cold_grid`` interpolated (as
    :func:`gfbopt.rotor.supports._equilibrium` does)."""
    from .analysis import resolve_case

    spec = line.specs[k]
    if spec is None:
        return case, guess, None, None
    film = FilmCase(case.bearing, case.options, case.grid, case.cache, case.load_newton)
    drag = FilmDrag(film, start=_start(case, guess, cold_grid, cold_factor))
    point = running_point(spec, speed_rpm, drag, prior=line.prior(case.grid, k, speed_rpm),
                          tolerance_k=line.tolerance_k)
    line.drag_solves += drag.solves
    line.fixed_points += 1
    line.store(case.grid, k, point)
    if not point.converged:
        return case, guess, point, _failure(line, k, load, speed_rpm, point, point.message)
    try:
        warm = warm_bearing(case.bearing, point)
        warm_case = resolve_case(warm, case.rotor, case.load_newton, options=case.options,
                                 grid=case.grid, cache=case.cache)
    except ParameterError as exc:
        return case, guess, point, _failure(
            line, k, load, speed_rpm, point, f"the running clearance "
            f"{point.running_clearance * 1e6:.3g} µm cannot be analysed ({exc})")
    warm_case = replace(warm_case, load_source=case.load_source)
    return warm_case, (drag.last if drag.last is not None else guess), point, None


def _start(case, guess, cold_grid, cold_factor: int):
    """The first drag solve's start (:func:`running_case`); None: a cold solve."""
    from ..static import solve_static
    from .speed_line import transferred_start

    if guess is not None:
        return lambda model, solver, load: guess
    if cold_grid is None or (case.grid.n_theta * case.grid.n_z
                             < cold_factor * cold_grid.n_theta * cold_grid.n_z):
        return None

    def start(model, solver, load):
        sol = solve_static(model, load=load, solver=case.cache(model, cold_grid))
        return transferred_start(sol, solver, model) if sol.success else None
    return start


def _failure(line, k, load, speed_rpm, point, why) -> dict:
    kind = CLOSURE if point.status == "closure" else RUNAWAY
    name = line.names[k]
    text = (f"the journal reaches the foil at bearing {name} at {speed_rpm:.6g} rpm"
            if kind == CLOSURE else f"thermal runaway at bearing {name} at "
            f"{speed_rpm:.6g} rpm")
    reason = why
    if why == point.message and why.endswith(")") and " (" in why:
        reason = why.partition(" (")[2][:-1]         # the point's own "… at N rpm (why)"
    return {"bearing": load.name, "speed_rpm": speed_rpm, "load_newton": load.magnitude,
            "kind": kind, "message": f"{text} ({reason})", "running": point.to_dict()}


#: the running condition's columns of each bearing's equilibrium row (gfbopt/terms/thermal.py)
COLUMNS = ("thermal_model", "thermal_status", "cold_clearance_um", "running_clearance_um",
           "centrifugal_growth_um", "thermal_growth_um", "film_temperature_c",
           "viscosity_pa_s", "heat_generated_w", "thermal_static_solves")


def running_columns(point: Optional[RunningPoint]) -> dict:
    """The COLUMNS of a bearing's running point ({} for a bearing analysed as given, so
    that a rotor without the tables keeps today's rows)."""
    if point is None:
        return {}
    d = point.to_dict()
    return {k: d[k] for k in COLUMNS}


#: the running condition's columns per bearing in the Campbell and imbalance tables
SPEED_COLUMNS = ("running_clearance_um", "film_temperature_c", "viscosity_pa_s")


def speed_columns(states) -> dict:
    """{"running_clearance_um_A": ..., "film_temperature_c_A": ..., ...} of the bearings at
    their running condition in ``states`` (a SpeedStates); {} when none is (today's
    tables)."""
    out = {}
    for st in states.states:
        if st is not None and st.running is not None:
            d = st.running.to_dict()
            out.update({f"{k}_{st.load.name}": d[k] for k in SPEED_COLUMNS})
    return out


def runaway_limits(rotor, speeds_solved, states_at, bracket: float = 0.01) -> list:
    """For each bearing whose running condition fails at a speed solved: the speed it fails
    from, bracketed between the highest speed below where it ran and the lowest
    where it failed (bisection in speed, :func:`gfbopt.thermal.running.speed_line`, its first
    static solve from the equilibrium at the speed below: ``bracket`` relative, 1 %), with
    the sentence
    "thermal runaway at bearing A from N rpm" (or "the journal reaches the foil at bearing
    A from N rpm").  ``states_at``: speed → SpeedStates."""
    line = rotor.running
    if line is None:
        return []
    out = []
    for k, (case, name) in enumerate(zip(rotor.cases, rotor.names)):
        spec = line.specs[k]
        points = line.points.get((str(rotor.grid), k), {})
        bad = sorted(s for s, p in points.items() if not p.converged)
        if spec is None or not bad:
            continue
        fail = bad[0]
        good = [s for s, p in points.items() if p.converged and s < fail]
        low = max(good, default=0.0)
        below = states_at(low).states[k] if good else None
        drag = FilmDrag(FilmCase(case.bearing, case.options, case.grid, case.cache,
                                 case.load_newton),
                        start=_start(case, below.solution if below else None, None, 0))
        found = speed_line(spec, [low, fail] if low else [fail], drag, bracket=bracket,
                           tolerance_k=line.tolerance_k)
        limit = found.limit_rpm if math.isfinite(found.limit_rpm) else fail
        found = {"thermal_limit_kind": found.limit_kind or "runaway",
                 "thermal_limit_rpm": limit, "limit_static_solves": drag.solves}
        kind = CLOSURE if found["thermal_limit_kind"] == "closure" else RUNAWAY
        limit = found["thermal_limit_rpm"]
        text = (f"the journal reaches the foil at bearing {name} from {limit:,.0f} rpm"
                if kind == CLOSURE else f"thermal runaway at bearing {name} from "
                f"{limit:,.0f} rpm")
        out.append({"bearing": name, "kind": kind, "limit_rpm": limit,
                    "last_running_rpm": low, "first_failing_rpm": fail, "message": text,
                    "static_solves": found["limit_static_solves"]})
    return out


def running_summary(line, onset_rpm: float) -> Optional[dict]:
    """What the answers report of the running condition (None without a running line):
    ``at_onset`` (bearing → its running point at the first onset: the point of the speed
    solved nearest it, whose ``speed_rpm`` says which; nan when no onset), ``table`` (one
    row per speed solved on the analysis grid and bearing), ``thermal_limits``
    (:func:`runaway_limits`) and the cost (``fixed_points``, ``static_solves`` of the fixed
    points, and per fixed point)."""
    rotor = line.rotor
    run = rotor.running
    if run is None:
        return None
    grid = rotor.grid
    at_onset = {}
    for k, name in enumerate(rotor.names):
        points = run.points.get((str(grid), k), {})
        if run.specs[k] is None:
            at_onset[name] = {"thermal_model": ISOTHERMAL}
            continue
        near = (min(points, key=lambda s: abs(s - onset_rpm), default=None)
                if math.isfinite(onset_rpm) else None)
        at_onset[name] = points[near].to_dict() if near is not None else {
            "thermal_model": run.specs[k].model_name, "running_clearance_um": math.nan}
    rows = [{"bearing": name, **run.at(grid, k, s).to_dict()}
            for s in line.speeds_solved for k, name in enumerate(rotor.names)
            if run.at(grid, k, s) is not None]
    limits = runaway_limits(rotor, line.speeds_solved, line.states)
    return {"thermal_models": run.models(), "at_onset": at_onset, "table": rows,
            "thermal_limits": limits, "fixed_points": run.fixed_points,
            "static_solves": run.drag_solves,
            "max_static_solves": max((p.static_solves for pts in run.points.values()
                                      for p in pts.values()), default=0),
            "static_solves_per_point": (run.drag_solves / run.fixed_points
                                        if run.fixed_points else 0.0)}
