"""How much load, from what speed: load capacity and lift-off speed for a minimum-film limit.

* **Load capacity** at a speed: the largest static load W [N] the bearing carries with a
  minimum film h_min ≥ H (:func:`load_capacity`).  Physics: at a fixed speed h_min falls as
  the load grows (the journal moves out and the film closes), so the capacity is the root of
  h_min(W) = H.
* **Lift-off speed** at a load: the lowest speed at which the film carries W with h_min ≥ H
  (:func:`lift_off_speed`), the speed above which the journal no longer rubs on start-up or
  coast-down.  Physics: at a fixed load h_min rises with the speed (Λ grows), so the lift-off
  speed is the root of h_min(N) = H.

Both are found by continuation with warm starts (one static build serves the whole curve:
the load and Λ are parameters of the CasADi model): the load is stepped up geometrically
(× :data:`LOAD_STEP`) from a light load, or the speed down (÷ :data:`SPEED_STEP`) from the
highest speed, each solve warm-started from the previous equilibrium, until the limit is
crossed; the crossing is then refined by Brent's method to |h_min/H − 1| ≤
:data:`FILM_TOLERANCE`.  A solve that fails in the continuation (the film cannot carry the
load) counts as below the limit.  Every evaluated point is kept as the curve (plotted by
:func:`gfbopt.plotting.bearing.capacity_curve`).

**At the running condition** (``condition``: a bearing file with ``[journal]``/``[thermal]``,
:func:`gfbopt.rotor.running_bearing.running_load_capacity` / ``running_lift_off``) every
point of the search is the bearing at its own running condition: ``condition(speed, load,
near)`` gives the warm bearing there (:class:`Condition`: the running clearance and μ(T_f)
of the heat balance under that load at that speed), whose equilibrium is then solved from
the fixed point's last film.  The root is then the answer at its own running condition (no
outer iteration), and each curve row carries its running point's columns.  A point with no
running state (thermal runaway, closure) is a row of NaN figures with its
``thermal_status``: the search stops there and the answer says so (an answer, not a failure;
a lift-off search whose top speed has none steps down to the first speed that has one).
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from typing import Callable, Optional

from scipy.optimize import brentq

from ..errors import ParameterError
from ..inputs.bearing import BearingGeometry
from ..inputs.checks import check_positive
from ..inputs.grid import DEFAULT_GRID, Grid, as_grid
from ..inputs.options import ModelOptions, merge_options
from ..inputs.rotor_limits import MAX_SPECIFIC_LOAD_RATIO, MIN_BEARING_NUMBER
from ..physics.torque import drag_torque_and_power
from ..static import SolverCache, StaticSolution, solve_static

#: load step of the continuation [-]
LOAD_STEP = 1.5
#: speed step of the lift-off continuation (speeds fall by this factor) [-]
SPEED_STEP = 1.25
#: the refined point's minimum film equals the limit to this relative tolerance [-]
FILM_TOLERANCE = 1e-7
#: lightest load of the capacity continuation, as W/(p_a L D) [-]
FIRST_LOAD = 0.01
#: a search that meets a point with no running state brackets where it is lost to this
#: relative width [-] (as the running condition's own limit speed, gfbopt.thermal.running)
STATE_BRACKET = 0.005
#: smallest minimum-film limit [µm]: a film of 10 nm is thinner than any real surface's
#: roughness (a polished journal's is about 0.1 µm), so a smaller limit is no limit
MIN_FILM_LIMIT_UM = 0.01


@dataclass(frozen=True)
class Condition:
    """One point's running condition (module docstring): ``bearing`` the warm bearing (SI;
    None: no running state there), ``columns`` the running point's columns of the curve row,
    ``initial`` a StaticSolution near the warm equilibrium (the fixed point's last film, or
    None), ``message`` why there is no running state."""

    bearing: Optional[BearingGeometry]
    columns: dict = field(default_factory=dict)
    initial: Optional[StaticSolution] = field(default=None, repr=False)
    message: str = ""


#: (speed [rpm], load [N], the nearest equilibrium solved or None) → Condition
ConditionFunction = Callable[[float, float, Optional[StaticSolution]], Condition]


@dataclass(frozen=True)
class CurveResult:
    """A load-capacity or lift-off search (SI, per bearing).

    kind : 'capacity' or 'lift_off';  value : the load capacity [N] or the lift-off speed
    [rpm] (nan when there is none);  speed_rpm / load_newton : the fixed speed or load;
    min_film_limit_um : H [µm];  min_film_thickness_um : h_min at the answer [µm];
    curve : one row per solved point (speed_rpm, load_newton, min_film_thickness_um,
    eccentricity, attitude_angle_deg, torque_ratio, drag_torque_nm, power_loss_w, success);
    conventions : the options used and the bearing as built;  success, message,
    wall_time_s [s].
    """

    kind: str
    value: float
    speed_rpm: float
    load_newton: float
    min_film_limit_um: float
    min_film_thickness_um: float
    curve: list = field(repr=False)
    conventions: dict = field(default_factory=dict)
    success: bool = True
    message: str = ""
    wall_time_s: float = 0.0

    @property
    def answer(self) -> str:
        """The answer in one line."""
        if self.message and math.isfinite(self.value):   # an answer the limit did not set
            return self.message
        if self.kind == "capacity":
            if not math.isfinite(self.value):
                return self.message
            return (f"load capacity {self.value:.5g} N at {self.speed_rpm:.6g} rpm "
                    f"(h_min = {self.min_film_limit_um:.4g} µm)")
        if not math.isfinite(self.value):
            return self.message
        return (f"lift-off at {self.value:.6g} rpm under {self.load_newton:.5g} N "
                f"(h_min = {self.min_film_limit_um:.4g} µm)")

    def to_dict(self) -> dict:
        out = {k: getattr(self, k) for k in self.__dataclass_fields__}
        out["answer"] = self.answer
        key = "load_capacity_newton" if self.kind == "capacity" else "lift_off_speed_rpm"
        out[key] = out.pop("value")
        return out


class _Curve:
    """Static equilibria of one bearing along a speed or load, warm-started from the nearest
    point already solved; ``h(x)`` is h_min − H [µm] (−H when the solve fails or there is no
    running state; ``stopped`` holds the x of the latter).  ``condition``: each point at its
    own running condition (module docstring)."""

    def __init__(self, bearing, options, grid, cache, limit_um, *, speed=None, load=None,
                 condition: Optional[ConditionFunction] = None):
        self.bearing, self.options, self.grid = bearing, options, grid
        self.cache = cache if cache is not None else SolverCache(grid)
        self.limit = limit_um
        self.speed, self.load = speed, load
        self.condition = condition
        self.rows: list[dict] = []
        self.stopped: dict = {}          # x -> why there is no running state there
        self._solved: dict = {}
        self._values: dict = {}
        self._clearance: dict = {}       # x -> the radial clearance solved there [m]

    def solve(self, x: float) -> Optional[StaticSolution]:
        speed = self.speed if self.speed is not None else x
        load = self.load if self.load is not None else x
        near = min(self._solved, key=lambda v: abs(math.log(v / x)), default=None)
        initial = self._solved.get(near)
        bearing, extra, fast = self.bearing, {}, False
        row = {"speed_rpm": speed, "load_newton": load, "success": False,
               "min_film_thickness_um": math.nan, "eccentricity": math.nan,
               "attitude_angle_deg": math.nan, "torque_ratio": math.nan,
               "drag_torque_nm": math.nan, "power_loss_w": math.nan}
        if self.condition is not None:
            found = self.condition(speed, load, initial)
            extra = dict(found.columns)
            if found.bearing is None:                 # no running state: the curve stops
                self.stopped[x] = found.message
                self.rows.append({**row, **extra})
                return None
            bearing = found.bearing
            if found.initial is not None:             # the fixed point's last film
                initial, fast = found.initial, True
        model = bearing.model(speed, **self.options.model_kwargs())
        solver = self.cache(model, self.grid)
        w = bearing.nondimensional_load(load)
        sol = solve_static(model, load=w, solver=solver, initial=initial,
                           continuation=initial is None, fast_path=fast)
        if not sol.success and initial is not None:
            sol = solve_static(model, load=w, solver=solver)
        row["success"] = bool(sol.success)
        if sol.success:
            torque, power = drag_torque_and_power(sol.torque_ratio, model.bearing_number,
                                                  bearing)
            row.update(min_film_thickness_um=sol.min_film * bearing.radial_clearance * 1e6,
                       eccentricity=sol.eccentricity,
                       attitude_angle_deg=sol.attitude_angle_deg,
                       torque_ratio=sol.torque_ratio, drag_torque_nm=torque, power_loss_w=power)
            self._solved[x] = sol
            self._clearance[x] = bearing.radial_clearance
        self.rows.append({**row, **extra})
        return sol if sol.success else None

    def h(self, x: float) -> float:
        """h_min − H [µm] at ``x`` (−H when the film cannot carry the load there, or there
        is no running state)."""
        if x not in self._values:
            sol = self.solve(x)
            self._values[x] = (-self.limit if sol is None else
                               sol.min_film * self._clearance[x] * 1e6 - self.limit)
        return self._values[x]

    def refine(self, good: float, bad: float) -> float:
        """The root of h between ``good`` (h ≥ 0) and ``bad`` (h < 0): geometric bisection
        while ``bad`` is a failed solve, then Brent's method."""
        while self.h(bad) <= -self.limit and abs(bad / good - 1.0) > 1e-12:
            middle = math.sqrt(good * bad)
            if self.h(middle) >= 0:
                good = middle
            else:
                bad = middle
        if self.h(bad) <= -self.limit:
            return good
        return brentq(self.h, good, bad, xtol=1e-14 * good, rtol=1e-13, maxiter=100)

    def final(self, x: float) -> float:
        """h_min [µm] at ``x`` (solved again if needed)."""
        sol = self._solved.get(x) or self.solve(x)
        return math.nan if sol is None else sol.min_film * self._clearance[x] * 1e6


def _not_at_limit(film: float, limit: float, what: str) -> str:
    """"" when the answer's h_min is the limit (to 1e-6 relative); else the answer in words:
    the equilibrium was lost (the solve fails) before h_min reached the limit, so the answer
    is where the film stops carrying the load, with the film it has there."""
    if math.isfinite(film) and abs(film / limit - 1.0) <= 1e-6:
        return ""
    return (f"{what}, where the equilibrium is lost before h_min reaches {limit:.4g} µm "
            f"(h_min = {film:.4g} µm there)")


def _march(line: _Curve, start: float, factor: float, end: float) -> tuple:
    """Step x by ``factor`` from ``start`` (h ≥ 0 there) towards ``end`` (never past it)
    until h < 0; then refine the crossing.  Returns (root or None, the last x with h ≥ 0,
    the x with no running state where the march stopped or None)."""
    good = start
    while (good < end) if factor > 1 else (good > end):
        trial = min(good * factor, end) if factor > 1 else max(good * factor, end)
        if line.h(trial) < 0:
            if trial in line.stopped:
                return _bracket_state(line, good, trial)
            return line.refine(good, trial), good, None
        good = trial
    return None, good, None


def _bracket_state(line: _Curve, good: float, bad: float) -> tuple:
    """The march met a point with no running state (``bad``) after ``good`` (h ≥ 0):
    geometric bisection until the two are :data:`STATE_BRACKET` apart, refining the root
    instead where a point between has a state and h < 0 (the film reaches the limit before
    the running state is lost).  Returns as :func:`_march`."""
    while abs(bad / good - 1.0) > STATE_BRACKET:
        middle = math.sqrt(good * bad)
        if line.h(middle) >= 0:
            good = middle
        elif middle in line.stopped:
            bad = middle
        else:
            return line.refine(good, middle), good, None
    return None, good, bad


def _no_state(line: _Curve, x: float, where: str) -> str:
    """The answer's words when the search stops at ``x`` with no running state."""
    why = line.stopped.get(x) or "no running state"
    return f"no running state {where}: {why}"


def _resolve(bearing, options, min_film_um, grid):
    if not isinstance(bearing, BearingGeometry):
        raise ParameterError("bearing", bearing, "must be a BearingGeometry (SI)")
    grid = as_grid(grid)
    limit = check_positive("min_film_um", min_film_um)
    if limit < MIN_FILM_LIMIT_UM:
        raise ParameterError("min_film_um", limit, f"must be >= {MIN_FILM_LIMIT_UM:g} µm: a "
                             "thinner film is below any real surface's roughness")
    clearance_um = bearing.radial_clearance * 1e6
    if limit >= clearance_um:
        raise ParameterError("min_film_um", limit, f"must be below the radial clearance "
                             f"({clearance_um:.4g} µm): a loaded journal's film is thinner")
    resolved = merge_options(options or ModelOptions(), ModelOptions())
    bearing.model(1000.0, **resolved.model_kwargs())       # validates the combination
    return limit, resolved


def _check_speed(bearing, name: str, speed_rpm: float) -> float:
    """``speed_rpm`` > 0 with a bearing number Λ at least the model's floor
    :data:`~gfbopt.inputs.rotor_limits.MIN_BEARING_NUMBER`."""
    speed = check_positive(name, speed_rpm)
    number = bearing.bearing_number(speed)
    if not number >= MIN_BEARING_NUMBER:
        raise ParameterError(name, speed_rpm, f"gives a bearing number Λ = {number:.3g}, "
                             f"below {MIN_BEARING_NUMBER:g}: no film carries a load there (at "
                             f"least {_slowest_speed(bearing):.3g} rpm)")
    return speed


def _slowest_speed(bearing) -> float:
    """The speed [rpm] of the bearing number floor (Λ is proportional to the speed)."""
    return MIN_BEARING_NUMBER / bearing.bearing_number(1.0)


def _conventions(resolved, bearing, grid) -> dict:
    built = {} if bearing.build is None else bearing.build.describe()
    compliance = 0.0 if resolved.foil == "rigid" else bearing.compliance   # the S solved
    return {**resolved.to_dict(), "compliance": compliance, "grid": str(grid), **built}


def _first_state(line: _Curve, start: float, factor: float, end: float) -> tuple:
    """(the first x from ``start`` stepped by ``factor`` towards ``end`` that has a running
    state (or ``end``), the x skipped on the way with none)."""
    x, skipped = start, []
    while line.h(x) < 0 and x in line.stopped and ((x < end) if factor > 1 else (x > end)):
        skipped.append(x)
        x = min(x * factor, end) if factor > 1 else max(x * factor, end)
    return x, skipped


def _noted(result: CurveResult, line: _Curve, skipped: list, unit: str) -> CurveResult:
    """The result with the start of the search that had no running state stated."""
    if not skipped:
        return result
    low, high = min(skipped), max(skipped)
    which = "lighter loads" if unit == "N" else "higher speeds"
    span = f"{low:.6g} {unit}" if low == high else f"{low:.6g}–{high:.6g} {unit}"
    note = _no_state(line, skipped[0], f"at the {which} searched ({span})")
    return dataclasses.replace(result, message=f"{result.message or result.answer}; {note}")


def load_capacity(bearing: BearingGeometry, speed_rpm: float, min_film_um: float, *,
                  options: Optional[ModelOptions] = None, grid: Grid = DEFAULT_GRID,
                  cache: Optional[SolverCache] = None,
                  condition: Optional[ConditionFunction] = None) -> CurveResult:
    """The largest load [N] with h_min ≥ ``min_film_um`` [µm] at ``speed_rpm`` [rpm].

    options : the formulation (e.g. a bearing file's [model] table; defaults otherwise).
    condition : each load at its own running condition (module docstring); light loads
    with no running state are stepped over (× :data:`LOAD_STEP`) to the first that has one.
    The answer's h_min equals the limit to :data:`FILM_TOLERANCE` (relative).
    """
    t0 = time.perf_counter()
    limit, resolved = _resolve(bearing, options, min_film_um, grid)
    speed = _check_speed(bearing, "speed_rpm", speed_rpm)
    line = _Curve(bearing, resolved, grid, cache, limit, speed=speed, condition=condition)
    area = bearing.ambient_pressure * bearing.length * 2 * bearing.radius
    common = dict(speed_rpm=speed, min_film_limit_um=limit, conventions=_conventions(
        resolved, bearing, grid))
    ceiling = (MAX_SPECIFIC_LOAD_RATIO * bearing.ambient_pressure * bearing.length * 2
               * bearing.radius)                 # as BearingGeometry.nondimensional_load
    first = FIRST_LOAD * area
    end = min(first * LOAD_STEP ** 40, ceiling)
    load, skipped = _first_state(line, first, LOAD_STEP, end)

    def result(value, load_newton, film, message, success=True, noted=True):
        found = CurveResult("capacity", value, load_newton=load_newton,
                            min_film_thickness_um=film, curve=line.rows, success=success,
                            wall_time_s=time.perf_counter() - t0, message=message, **common)
        return _noted(found, line, skipped if noted else [], "N")

    if load in line.stopped:                    # no running state at any load searched
        return result(math.nan, load, math.nan, _no_state(
            line, load, f"at {speed:.6g} rpm under {first:.3g} to {load:.4g} N"),
            noted=False)
    if line.h(load) < 0:
        return result(math.nan, load, math.nan, f"h_min < {limit:.4g} µm already at "
                      f"{load:.3g} N ({speed:.6g} rpm): no load capacity above it", False)
    root, good, stop = _march(line, load, LOAD_STEP, end)
    if stop is not None:             # a thermal runaway before the film reaches the limit
        return result(math.nan, stop, math.nan, _no_state(
            line, stop, f"at {speed:.6g} rpm from {good:.5g}–{stop:.5g} N, before h_min "
            f"reaches {limit:.4g} µm (h_min = {line.final(good):.4g} µm under {good:.5g} N)"))
    if root is not None:
        film = line.final(root)
        return result(root, root, film, _not_at_limit(
            film, limit, f"the film cannot carry more than {root:.5g} N at {speed:.6g} rpm"))
    if good >= ceiling:
        return result(math.nan, good, line.final(good), f"capacity above the load ceiling "
                      f"of {ceiling:.4g} N ({MAX_SPECIFIC_LOAD_RATIO:g} p_a L D): h_min stays "
                      f"above {limit:.4g} µm up to it at {speed:.6g} rpm")
    return result(math.nan, good, math.nan, f"h_min stays above {limit:.4g} µm up to "
                  f"{good:.4g} N", False)


def lift_off_speed(bearing: BearingGeometry, load_newton: float, min_film_um: float, *,
                   max_speed_rpm: float = 100_000.0, options: Optional[ModelOptions] = None,
                   grid: Grid = DEFAULT_GRID, cache: Optional[SolverCache] = None,
                   condition: Optional[ConditionFunction] = None) -> CurveResult:
    """The lowest speed [rpm] at which ``load_newton`` [N] is carried with h_min ≥
    ``min_film_um`` [µm], searched below ``max_speed_rpm`` [rpm] (down to 1/1000 of it).

    No lift-off below ``max_speed_rpm`` is an answer ("no lift-off below N rpm",
    ``success`` False).  The answer's h_min equals the limit to :data:`FILM_TOLERANCE`.
    condition : each speed at its own running condition (module docstring); high speeds
    with no running state are stepped over (÷ :data:`SPEED_STEP`) to the first that has
    one, and a speed with none below it ends the search.
    """
    t0 = time.perf_counter()
    load = check_positive("load_newton", load_newton)
    limit, resolved = _resolve(bearing, options, min_film_um, grid)
    bearing.nondimensional_load(load)            # the load's own range, before any solve
    top = _check_speed(bearing, "max_speed_rpm", max_speed_rpm)
    floor = max(top / 1000, _slowest_speed(bearing))
    line = _Curve(bearing, resolved, grid, cache, limit, load=load, condition=condition)
    common = dict(load_newton=load, min_film_limit_um=limit,
                  conventions=_conventions(resolved, bearing, grid))
    start, skipped = _first_state(line, top, 1.0 / SPEED_STEP, floor)

    def result(value, speed, film, message, success=True, noted=True):
        found = CurveResult("lift_off", value, speed_rpm=speed, min_film_thickness_um=film,
                            curve=line.rows, success=success,
                            wall_time_s=time.perf_counter() - t0, message=message, **common)
        return _noted(found, line, skipped if noted else [], "rpm")

    if start in line.stopped:                   # no running state at any speed searched
        return result(math.nan, start, math.nan, "no lift-off: " + _no_state(
            line, start, f"from {top:.6g} down to {start:.6g} rpm under {load:.5g} N"), False,
            noted=False)
    if line.h(start) < 0:
        return result(math.nan, start, math.nan, f"no lift-off below {start:.6g} rpm (h_min < "
                      f"{limit:.4g} µm under {load:.5g} N)", False)
    root, good, stop = _march(line, start, 1.0 / SPEED_STEP, floor)
    if stop is not None:
        return result(math.nan, stop, math.nan, "no lift-off found: " + _no_state(
            line, stop, f"from {good:.6g}–{stop:.6g} rpm under {load:.5g} N, before h_min "
            f"falls to {limit:.4g} µm"), False)
    if root is not None:
        film = line.final(root)
        return result(root, root, film, _not_at_limit(
            film, limit, f"the film first carries {load:.5g} N at {root:.6g} rpm"))
    return result(math.nan, good, math.nan, f"h_min stays above {limit:.4g} µm down to "
                  f"{good:.4g} rpm", False)
