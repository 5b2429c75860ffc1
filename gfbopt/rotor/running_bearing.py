"""The one-bearing analyses at the running condition: stability at an operating
point, onset of whirl, load capacity and lift-off speed, with the running clearance and
viscosity of :mod:`gfbopt.thermal` (growths, Sutherland, the lumped heat balance).

They sit in the rotor's floor because they call the rotor's one-bearing analyses
(:func:`gfbopt.rotor.stability`, :func:`~gfbopt.rotor.onset_speed`,
:mod:`gfbopt.rotor.capacity`) on the warm bearing
(:func:`gfbopt.thermal.bearing.warm_bearing`); :mod:`gfbopt.thermal` itself stays below the
rotor (static solves only).  ``gfbopt stability``/``capacity``, :mod:`gfbopt.api` (a bearing
*file* given to ``stability``, ``onset_speed``, ``load_capacity``, ``lift_off_speed``:
:mod:`.running_files`) and the studies call these same functions, so they give the same
answer.  Without ``[journal]`` and ``[thermal]`` each function is today's analysis, called
once on the bearing as given.

- :func:`running_stability`: the fixed point at the operating point, then
  :func:`gfbopt.rotor.stability` of the warm bearing;
- :func:`running_onset`: :func:`gfbopt.rotor.onset_speed` of the bearing frozen at the
  running condition of a guess, then a Newton step (on the frozen search's slope) and the
  secant method on the mass margin at the running condition of each speed, until the next
  step is below ``tolerance`` (relative): that step's speed is the onset, and the running
  point reported is the last one evaluated (at most ``tolerance`` away in speed);
- :func:`running_load_capacity` / :func:`running_lift_off`: one search with every point
  at its own running condition (:class:`_Conditions`, the ``condition`` of
  :mod:`gfbopt.rotor.capacity`: the fixed point under that load at that speed as ``gfbopt
  static`` solves it, then the warm bearing's equilibrium), so the root is the answer at its
  own running condition and each curve row carries its running point
  (:data:`CURVE_COLUMNS`); a point with no running state is a NaN row with its status.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Optional

from ..errors import ParameterError
from ..inputs.grid import DEFAULT_GRID, Grid
from ..inputs.rotor import OperatingPoint, Rotor
from ..thermal.bearing import FilmCase, FilmDrag, limit_on_line, warm_bearing
from ..thermal.running import (CENTRIFUGAL, HEAT_BALANCE, ISOTHERMAL, RunningPoint, RunningSpec,
                               running_point, without_heat)

#: the clearance at speed's top-level fields of every answer
RUNNING_KEYS = ("thermal_model", "running_clearance_um", "centrifugal_growth_um",
                "thermal_growth_um", "film_temperature_c", "viscosity_pa_s")


@dataclasses.dataclass(frozen=True)
class Formulation:
    """Resolved model keywords as a :class:`~gfbopt.thermal.bearing.FilmCase`'s ``options``
    (``model_kwargs()``), for a route that holds keywords rather than ModelOptions."""

    kwargs: tuple

    def model_kwargs(self) -> dict:
        return dict(self.kwargs)


@dataclasses.dataclass(frozen=True)
class WarmPoint:
    """The running condition under a load: the warm bearing (None: no running state), the
    running point (its status and message say why there is none), the fixed point's static
    solves and its last film solution (a start for the next solve; None without one)."""

    warm: Optional[object]
    point: RunningPoint
    solves: int
    last: object = None


def warm_under_load(spec: RunningSpec, film: FilmCase, speed_rpm: float,
                    start=None) -> WarmPoint:
    """The one step every route at the running condition takes: the fixed point of the heat
    balance under ``film.load_newton`` at ``speed_rpm`` (:func:`running_point` with a
    :class:`FilmDrag` from ``start``, default :func:`coarse_start`), the centrifugal growth
    alone without ``[thermal]``, then :func:`warm_bearing`; a running clearance the bearing
    cannot be analysed at is a point without a state ('runaway', with the reason)."""
    if spec.model_name == HEAT_BALANCE:
        drag = FilmDrag(film, start=start or coarse_start(film.grid, film.cache))
        point, solves, last = running_point(spec, speed_rpm, drag), drag.solves, drag.last
    else:
        point, solves, last = without_heat(spec, speed_rpm), 0, None
    if not point.converged:
        return WarmPoint(None, point, solves, last)
    try:
        return WarmPoint(warm_bearing(film.bearing, point), point, solves, last)
    except ParameterError as exc:
        return WarmPoint(None, dataclasses.replace(point, status="runaway", message=(
            f"the running clearance {point.running_clearance * 1e6:.3g} µm cannot be "
            f"analysed ({exc})")), solves, last)


def _case(bearing, rotor, load_newton, options, grid, cache):
    from ..rotor.analysis import resolve_case

    case = resolve_case(bearing, rotor, load_newton, options=options, grid=grid, cache=cache)
    return case, FilmCase(bearing, case.options, case.grid, case.cache, case.load_newton)


def running_stability(bearing, spec: RunningSpec, rotor: Rotor,
                      operating_point: OperatingPoint, *, options=None,
                      grid: Grid = DEFAULT_GRID, cache=None):
    """(StabilityResult at the running condition or None, the RunningPoint, the bearing
    analysed).  No fixed point (runaway, closure): (None, the point whose message says why,
    the bearing as given)."""
    from ..rotor import stability

    if spec.model_name == ISOTHERMAL:
        return (stability(bearing, rotor, operating_point, options=options, grid=grid,
                          cache=cache), without_heat(spec, operating_point.speed_rpm), bearing)
    cold = without_heat(spec, operating_point.speed_rpm)
    if spec.model_name == CENTRIFUGAL and not cold.converged:    # closed form, no solve
        return None, cold, bearing
    case, film = _case(bearing, rotor, operating_point.load_newton, options, grid, cache)
    found = warm_under_load(spec, film, operating_point.speed_rpm)
    point, warm = found.point, found.warm
    if not point.converged:            # where it happens: bracketed from rest
        limit = limit_on_line(spec, film, 0.0, operating_point.speed_rpm)
        return None, dataclasses.replace(point, message=limit["message"]), bearing
    if warm is None:                   # a running clearance that cannot be analysed
        return None, point, bearing
    result = stability(warm, rotor, operating_point, options=case.options, grid=case.grid,
                       cache=case.cache, initial=found.last)
    return result, point, warm


class _Margin:
    """M_crit/M − 1 at the running condition of each speed, along one search (shared drag:
    warm starts; counts evaluations and static solves).  The threshold is the local crossing
    on the branch of the previous one (:func:`gfbopt.linear.crossings.local_crossing`, as the
    onset search's own secant uses), the full threshold when that fails."""

    def __init__(self, bearing, spec, case, film, rotor, load_newton):
        self.bearing, self.spec, self.case, self.rotor = bearing, spec, case, rotor
        self.load = load_newton
        self.drag = FilmDrag(film, start=coarse_start(case.grid, case.cache))
        self.evaluations = 0
        self.near = None                 # (whirl ratio, root) of the last crossing

    def start_near(self, whirl: float, mass_parameter: float, load_parameter: float):
        """Follow the branch of a crossing at whirl ratio γ, mass M̄, load W̄0."""
        if math.isfinite(whirl) and math.isfinite(mass_parameter):
            self.near = (whirl, mass_parameter * whirl**2 * load_parameter)

    def __call__(self, speed, prior=None):
        """(margin, the running point, (whirl ratio, whirl frequency [Hz]))."""
        from ..inputs.conversions import rpm_to_rad_per_s, whirl_frequency_hz
        from ..linear import linear_threshold, linearise
        from ..linear.crossings import local_crossing
        from ..rotor.analysis import equilibrium, resolve_case
        from ..static import solve_static

        self.evaluations += 1
        point = running_point(self.spec, speed, self.drag, prior=prior)
        if not point.converged:
            return math.nan, point, None
        warm = resolve_case(warm_bearing(self.bearing, point), self.rotor, self.load,
                            options=self.case.options, grid=self.case.grid,
                            cache=self.case.cache)
        sol = None
        if self.drag.last is not None:     # Newton from the fixed point's last film
            model = warm.model(speed)
            sol = solve_static(model, load=warm.load, solver=warm.cache(model, warm.grid),
                               initial=self.drag.last, fast_path=True)
        if sol is None or not sol.success:
            sol = equilibrium(warm, speed, self.drag.last)
        lin = linearise(sol, warm.cache(sol.model, warm.grid))
        found = None if self.near is None else local_crossing(lin, *self.near)
        if found is not None:
            mcrit, whirl = found.mass, found.whirl
            self.near = (found.whirl, found.root)
        else:
            thr = linear_threshold(lin)
            mcrit, whirl = thr.critical_mass, thr.whirl_ratio
            self.start_near(whirl, mcrit, lin.load)
        margin = mcrit / warm.mass_parameter(speed) - 1.0
        return margin, point, (whirl, whirl_frequency_hz(whirl, rpm_to_rad_per_s(speed)))

    def stats(self) -> dict:
        return {"thermal_evaluations": self.evaluations,
                "thermal_static_solves": self.drag.solves}


def running_onset(bearing, spec: RunningSpec, rotor: Rotor, load_newton: Optional[float],
                  speed_range, *, guess_rpm=None, options=None, grid: Grid = DEFAULT_GRID,
                  cache=None, progress=False, tolerance: float = 2e-4,
                  max_steps: int = 8) -> dict:
    """The onset of whirl with the clearance at speed (module docstring): the onset's dict
    (:meth:`~gfbopt.rotor.onset.OnsetResult.to_dict`) with ``onset_speed_rpm`` at the running
    condition, ``frozen_onset_speed_rpm`` (the frozen bearing's), ``running`` (the running
    point there) and ``thermal_evaluations``/``thermal_static_solves``; ``smallest_margin``
    is null (the frozen search's margins are not the running answer's).  A thermal runaway
    or closure before the onset is the answer instead ("thermal runaway from N rpm")."""
    from ..rotor import onset_speed

    low, high = speed_range
    if spec.model_name == ISOTHERMAL:
        found = onset_speed(bearing, rotor, load_newton, speed_range, options=options,
                            grid=grid, cache=cache, progress=progress).to_dict()
        return {**found, "frozen_onset_speed_rpm": found["onset_speed_rpm"],
                "running": None, "thermal_evaluations": 0, "thermal_static_solves": 0}
    case, film = _case(bearing, rotor, load_newton, options, grid, cache)
    margin = _Margin(bearing, spec, case, film, rotor, case.load_newton)
    guess = guess_rpm or math.sqrt(low * high)
    frozen_point = running_point(spec, guess, margin.drag)

    def limited(failing_rpm: float, before: dict) -> dict:
        """A thermal limit below the onset, with every field of an onset's answer."""
        return _complete({**before, **_limited(spec, film, low, failing_rpm, margin)},
                         (low, high), rotor, case.load_newton)

    if not frozen_point.converged:
        return limited(guess, {})
    frozen = onset_speed(warm_bearing(bearing, frozen_point), rotor, load_newton, speed_range,
                         options=case.options, grid=case.grid, cache=case.cache,
                         progress=progress)
    # the frozen search's smallest margin is not the running answer's (null, as the study
    # rows leave it empty); its scan rows stay, under the frozen onset they belong to
    out = {**frozen.to_dict(), "smallest_margin": math.nan,
           "smallest_margin_speed_rpm": math.nan,
           "frozen_onset_speed_rpm": frozen.onset_speed_rpm,
           "frozen_at_rpm": guess, "running": frozen_point.to_dict(), **margin.stats()}
    if not math.isfinite(frozen.onset_speed_rpm):
        out["answer"] = f"{frozen.answer} (the running condition frozen at {guess:.6g} rpm)"
        return out
    a = frozen.onset_speed_rpm
    frozen_case = resolved_case(warm_bearing(bearing, frozen_point), rotor, load_newton,
                                case)
    margin.start_near(frozen.whirl_ratio, frozen_case.mass_parameter(a), frozen_case.load)
    fa, pa, _ = margin(a, frozen_point.sample)
    if not math.isfinite(fa):
        return limited(a, out)
    slope = _frozen_slope(frozen, a)           # d(margin)/d(speed) of the frozen bearing
    step = -fa / slope if slope else -math.copysign(0.02 * a, -fa)
    b = a + max(-0.1 * a, min(0.1 * a, step))  # a Newton step on the frozen slope
    fb, pb, rb = margin(b, pa.sample)
    onset = b
    for _ in range(max_steps):
        if not math.isfinite(fb):
            return limited(b, out)
        if fb == fa:
            break
        onset = b - fb * (b - a) / (fb - fa)
        if abs(onset - b) <= tolerance * onset:
            break                  # the secant's last step: the running point stays at b
        a, fa, pa, b = b, fb, pb, onset
        fb, pb, rb = margin(b, pa.sample)
    ratio, whirl = rb
    b = onset
    out.update(onset_speed_rpm=b, whirl_frequency_hz=whirl,
               whirl_ratio=ratio, running=pb.to_dict(), **margin.stats(),
               answer=(f"onset of whirl at {b:.6g} rpm at the running clearance "
                       f"{pb.running_clearance * 1e6:.4g} µm ({spec.model_name}), whirling "
                       f"at {whirl:.4g} Hz (frozen at {guess:.6g} rpm: "
                       f"{frozen.onset_speed_rpm:.6g} rpm)"))
    return out


def coarse_start(grid: Grid, cache):
    """A FilmDrag ``start`` on fine grids: the equilibrium on the onset search's coarse guide
    grid (:data:`gfbopt.rotor.onset.COARSE_GRID`, on grids with ≥ GUIDE_FACTOR× its cells,
    the same build the guided search uses) interpolated onto the fine grid
    (:func:`gfbopt.rotor.speed_line.transferred_start`), so that the first fine solve is a
    Newton solve instead of a cold IPOPT one; None on coarser grids."""
    from ..rotor.onset import COARSE_GRID, GUIDE_FACTOR
    from ..rotor.speed_line import transferred_start
    from ..static import solve_static

    coarse_cells = COARSE_GRID.n_theta * COARSE_GRID.n_z
    if grid.n_theta * grid.n_z < GUIDE_FACTOR * coarse_cells:
        return None

    def start(model, solver, load):
        sol = solve_static(model, load=load, solver=cache(model, COARSE_GRID))
        return transferred_start(sol, solver, model) if sol.success else None
    return start


def resolved_case(bearing, rotor, load_newton, like):
    """The stability case of ``bearing`` with the options, grid and cache of ``like``."""
    from ..rotor.analysis import resolve_case

    return resolve_case(bearing, rotor, load_newton, options=like.options, grid=like.grid,
                        cache=like.cache)


def _frozen_slope(frozen, onset: float) -> float:
    """d(M_crit/M − 1)/d(speed) [1/rpm] of the frozen search near its onset, from the two
    rows of its scan nearest the onset (0: not available)."""
    rows = sorted((r for r in frozen.scan if math.isfinite(r.get("mass_margin", math.nan))),
                  key=lambda r: abs(r["speed_rpm"] - onset))[:2]
    if len(rows) < 2 or rows[0]["speed_rpm"] == rows[1]["speed_rpm"]:
        return 0.0
    (s0, m0), (s1, m1) = ((r["speed_rpm"], r["mass_margin"]) for r in rows)
    return (m1 - m0) / (s1 - s0)


def _complete(found: dict, speed_range: tuple, rotor: Rotor, load_newton: float) -> dict:
    """``found`` with every field an onset's answer has (OnsetResult.to_dict and the frozen
    search's), null where a thermal limit below the onset leaves it without a value: the same
    fields whatever the answer."""
    from .onset import OnsetResult

    keys = (*OnsetResult.__dataclass_fields__, "answer", "frozen_onset_speed_rpm",
            "frozen_at_rpm", "running")
    base = {**dict.fromkeys(keys), "speed_range_rpm": tuple(speed_range),
            "rotor_mass_kg": rotor.mass_kg, "load_newton": load_newton, "scan": [],
            "coarse_scan": [], "stable_over_range": False, "unstable_at_lower_end": False,
            "method": "secant"}
    return {**base, **{k: v for k, v in found.items() if v is not None or k not in base}}


def _limited(spec, film, low, failing_rpm, margin) -> dict:
    found = limit_on_line(spec, film, low, failing_rpm)
    stats = margin.stats()
    stats["thermal_static_solves"] += found.pop("limit_static_solves")
    return {"onset_speed_rpm": math.nan, "whirl_frequency_hz": math.nan,
            "answer": found["message"], "success": True, **found, **stats}


# ------------------------------------------------------------------ capacity, lift-off
#: the running point's columns of each capacity or lift-off curve row (glossary:
#: gfbopt/terms/thermal.py)
CURVE_COLUMNS = ("thermal_model", "thermal_status", "thermal_message", "running_clearance_um",
                 "centrifugal_growth_um", "thermal_growth_um", "film_temperature_c",
                 "viscosity_pa_s", "thermal_static_solves")


def _answer(result, point: RunningPoint, solves: int) -> dict:
    d = point.to_dict()
    return {**result.to_dict(), "running": d, "thermal_static_solves": solves,
            **{k: d[k] for k in RUNNING_KEYS}}


def _failed(result, point, solves, key) -> dict:
    """No running state at the speed of a load-capacity search (closure by the centrifugal
    growth alone, in closed form): the answer says so, and every figure of the search (its
    value, its load, its film and curve) is null."""
    out = _answer(result, point, solves)
    message = point.message
    out.update({key: math.nan, "min_film_thickness_um": math.nan, "curve": [],
                "load_newton": math.nan, "success": True,
                "answer": f"no load capacity at {result.speed_rpm:,.0f} rpm: {message}",
                "message": message})
    return out


class _Conditions:
    """The ``condition`` of a search at the running condition
    (:class:`gfbopt.rotor.capacity.Condition`): the running point of each (speed, load) as
    ``gfbopt static --bearing FILE --speed-rpm N --load-newton F`` solves it (the fixed point
    of :func:`~gfbopt.thermal.running.running_point` under that load, no prior; the heat
    balance's first static solve warm-started from the search's nearest equilibrium, else
    :func:`coarse_start`), the centrifugal growth alone without ``[thermal]``.  Keeps every
    point (``points``) and counts the fixed points' static solves (``solves``)."""

    def __init__(self, bearing, spec: RunningSpec, options, grid, cache):
        from ..inputs.options import ModelOptions, merge_options

        self.bearing, self.spec, self.grid, self.cache = bearing, spec, grid, cache
        # the search's own resolution (gfbopt.rotor.capacity._resolve): one model
        self.options = merge_options(options or ModelOptions(), ModelOptions())
        self.points: dict = {}
        self.solves = 0

    def __call__(self, speed, load, near):
        from ..rotor.capacity import Condition

        film = FilmCase(self.bearing, self.options, self.grid, self.cache, load)
        found = warm_under_load(self.spec, film, speed, start=(
            (lambda model, solver, w: near) if near is not None else None))
        self.solves += found.solves
        point, warm, initial = found.point, found.warm, found.last
        self.points[(speed, load)] = point
        d = point.to_dict()
        return Condition(warm, {k: d[k] for k in CURVE_COLUMNS}, initial if warm else None,
                         point.message or "no running state")

    def at(self, result) -> RunningPoint:
        """The running point at the search's answer (its speed and load), else the last
        point evaluated."""
        key = (result.speed_rpm, result.load_newton)
        return self.points.get(key) or list(self.points.values())[-1]


def _with_model(result, spec) -> object:
    """The search's conventions with the clearance model named (the CSV context, --json)."""
    return dataclasses.replace(result, conventions={**result.conventions,
                                                    "thermal_model": spec.model_name})


def running_load_capacity(bearing, spec: RunningSpec, speed_rpm, min_film_um, *,
                          options=None, grid: Grid = DEFAULT_GRID, cache=None) -> dict:
    """The load capacity [N] at ``speed_rpm``, every load of the search at its own running
    condition (:class:`_Conditions`): :meth:`CurveResult.to_dict` plus ``running`` (the
    running point at the answer), the clearance at speed's fields and
    ``thermal_static_solves`` (the fixed points' static solves); each curve row carries
    :data:`CURVE_COLUMNS`."""
    from ..rotor.capacity import load_capacity
    from ..static import SolverCache

    cache = cache or SolverCache(grid)
    kw = dict(options=options, grid=grid, cache=cache)
    point = without_heat(spec, speed_rpm)                  # the centrifugal growth only
    if not point.converged:                                # closed form: no search at all
        return _failed(_no_search(bearing, speed_rpm, min_film_um, options, grid), point,
                       0, "load_capacity_newton")
    if spec.model_name == ISOTHERMAL:
        return _answer(load_capacity(bearing, speed_rpm, min_film_um, **kw), point, 0)
    conditions = _Conditions(bearing, spec, options, grid, cache)
    result = load_capacity(bearing, speed_rpm, min_film_um, condition=conditions, **kw)
    return _answer(_with_model(result, spec), conditions.at(result), conditions.solves)


def _no_search(bearing, speed_rpm, min_film_um, options, grid):
    """The CurveResult of a load-capacity search that is not run (no running state at
    the speed): NaN figures, an empty curve, the conventions the search would use."""
    from ..rotor.capacity import CurveResult, _conventions, _resolve

    limit, resolved = _resolve(bearing, options, min_film_um, grid)
    return CurveResult("capacity", math.nan, speed_rpm, math.nan, limit, math.nan, [],
                       conventions=_conventions(resolved, bearing, grid))


def running_lift_off(bearing, spec: RunningSpec, load_newton, min_film_um, *,
                     max_speed_rpm=100_000.0, options=None, grid: Grid = DEFAULT_GRID,
                     cache=None) -> dict:
    """The lift-off speed [rpm] under ``load_newton``, every speed of the search at its own
    running condition (as :func:`running_load_capacity`; a speed with no running state ends
    the search there, a top speed with none starts it at the first speed below that has
    one)."""
    from ..rotor.capacity import lift_off_speed
    from ..static import SolverCache

    cache = cache or SolverCache(grid)
    kw = dict(options=options, grid=grid, cache=cache, max_speed_rpm=max_speed_rpm)
    if spec.model_name == ISOTHERMAL:
        result = lift_off_speed(bearing, load_newton, min_film_um, **kw)
        return _answer(result, without_heat(spec, result.speed_rpm), 0)
    conditions = _Conditions(bearing, spec, options, grid, cache)
    result = lift_off_speed(bearing, load_newton, min_film_um, condition=conditions, **kw)
    return _answer(_with_model(result, spec), conditions.at(result), conditions.solves)
