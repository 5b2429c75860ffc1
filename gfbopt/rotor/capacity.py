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
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Optional

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
#: smallest minimum-film limit [µm]: a film of 10 nm is thinner than any real surface's
#: roughness (a polished journal's is about 0.1 µm), so a smaller limit is no limit
MIN_FILM_LIMIT_UM = 0.01


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
    point already solved; ``h(x)`` is h_min − H [µm] (−H when the solve fails)."""

    def __init__(self, bearing, options, grid, cache, limit_um, *, speed=None, load=None):
        self.bearing, self.options, self.grid = bearing, options, grid
        self.cache = cache if cache is not None else SolverCache(grid)
        self.limit = limit_um
        self.speed, self.load = speed, load
        self.rows: list[dict] = []
        self._solved: dict = {}
        self._values: dict = {}

    def solve(self, x: float) -> Optional[StaticSolution]:
        speed = self.speed if self.speed is not None else x
        load = self.load if self.load is not None else x
        model = self.bearing.model(speed, **self.options.model_kwargs())
        solver = self.cache(model, self.grid)
        near = min(self._solved, key=lambda v: abs(math.log(v / x)), default=None)
        initial = self._solved.get(near)
        w = self.bearing.nondimensional_load(load)
        sol = solve_static(model, load=w, solver=solver, initial=initial,
                           continuation=initial is None)
        if not sol.success and initial is not None:
            sol = solve_static(model, load=w, solver=solver)
        row = {"speed_rpm": speed, "load_newton": load, "success": bool(sol.success),
               "min_film_thickness_um": math.nan, "eccentricity": math.nan,
               "attitude_angle_deg": math.nan, "torque_ratio": math.nan,
               "drag_torque_nm": math.nan, "power_loss_w": math.nan}
        if sol.success:
            torque, power = drag_torque_and_power(sol.torque_ratio, model.bearing_number,
                                                  self.bearing)
            row.update(min_film_thickness_um=sol.min_film * self.bearing.radial_clearance * 1e6,
                       eccentricity=sol.eccentricity,
                       attitude_angle_deg=sol.attitude_angle_deg,
                       torque_ratio=sol.torque_ratio, drag_torque_nm=torque, power_loss_w=power)
            self._solved[x] = sol
        self.rows.append(row)
        return sol if sol.success else None

    def h(self, x: float) -> float:
        """h_min − H [µm] at ``x`` (−H when the film cannot carry the load there)."""
        if x not in self._values:
            sol = self.solve(x)
            self._values[x] = (-self.limit if sol is None else
                               sol.min_film * self.bearing.radial_clearance * 1e6 - self.limit)
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
        return math.nan if sol is None else sol.min_film * self.bearing.radial_clearance * 1e6


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
    until h < 0; then refine the crossing.  Returns (root or None, the last x with h ≥ 0)."""
    good = start
    while (good < end) if factor > 1 else (good > end):
        trial = min(good * factor, end) if factor > 1 else max(good * factor, end)
        if line.h(trial) < 0:
            return line.refine(good, trial), good
        good = trial
    return None, good


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
    return {**resolved.to_dict(), "compliance": bearing.compliance, "grid": str(grid), **built}


def load_capacity(bearing: BearingGeometry, speed_rpm: float, min_film_um: float, *,
                  options: Optional[ModelOptions] = None, grid: Grid = DEFAULT_GRID,
                  cache: Optional[SolverCache] = None) -> CurveResult:
    """The largest load [N] with h_min ≥ ``min_film_um`` [µm] at ``speed_rpm`` [rpm].

    options : the formulation (e.g. a bearing file's [model] table; defaults otherwise).
    The answer's h_min equals the limit to :data:`FILM_TOLERANCE` (relative).
    """
    t0 = time.perf_counter()
    limit, resolved = _resolve(bearing, options, min_film_um, grid)
    speed = _check_speed(bearing, "speed_rpm", speed_rpm)
    line = _Curve(bearing, resolved, grid, cache, limit, speed=speed)
    area = bearing.ambient_pressure * bearing.length * 2 * bearing.radius
    load = FIRST_LOAD * area
    common = dict(speed_rpm=speed, min_film_limit_um=limit, conventions=_conventions(
        resolved, bearing, grid))
    if line.h(load) < 0:
        return CurveResult("capacity", math.nan, load_newton=load, min_film_thickness_um=math.nan,
                           curve=line.rows, success=False, wall_time_s=time.perf_counter() - t0,
                           message=f"h_min < {limit:.4g} µm already at {load:.3g} N "
                           f"({speed:.6g} rpm): no load capacity above it", **common)
    ceiling = (MAX_SPECIFIC_LOAD_RATIO * bearing.ambient_pressure * bearing.length * 2
               * bearing.radius)                 # as BearingGeometry.nondimensional_load
    root, good = _march(line, load, LOAD_STEP, min(load * LOAD_STEP ** 40, ceiling))
    if root is not None:
        film = line.final(root)
        return CurveResult("capacity", root, load_newton=root, min_film_thickness_um=film,
                           curve=line.rows, wall_time_s=time.perf_counter() - t0,
                           message=_not_at_limit(film, limit, f"the film cannot carry more than "
                                                 f"{root:.5g} N at {speed:.6g} rpm"), **common)
    if good >= ceiling:
        return CurveResult("capacity", math.nan, load_newton=good,
                           min_film_thickness_um=line.final(good), curve=line.rows,
                           wall_time_s=time.perf_counter() - t0,
                           message=f"capacity above the load ceiling of {ceiling:.4g} N "
                           f"({MAX_SPECIFIC_LOAD_RATIO:g} p_a L D): h_min stays above "
                           f"{limit:.4g} µm up to it at {speed:.6g} rpm", **common)
    return CurveResult("capacity", math.nan, load_newton=good, min_film_thickness_um=math.nan,
                       curve=line.rows, success=False, wall_time_s=time.perf_counter() - t0,
                       message=f"h_min stays above {limit:.4g} µm up to {good:.4g} N", **common)


def lift_off_speed(bearing: BearingGeometry, load_newton: float, min_film_um: float, *,
                   max_speed_rpm: float = 100_000.0, options: Optional[ModelOptions] = None,
                   grid: Grid = DEFAULT_GRID,
                   cache: Optional[SolverCache] = None) -> CurveResult:
    """The lowest speed [rpm] at which ``load_newton`` [N] is carried with h_min ≥
    ``min_film_um`` [µm], searched below ``max_speed_rpm`` [rpm] (down to 1/1000 of it).

    No lift-off below ``max_speed_rpm`` is an answer ("no lift-off below N rpm",
    ``success`` False).  The answer's h_min equals the limit to :data:`FILM_TOLERANCE`.
    """
    t0 = time.perf_counter()
    load = check_positive("load_newton", load_newton)
    limit, resolved = _resolve(bearing, options, min_film_um, grid)
    bearing.nondimensional_load(load)            # the load's own range, before any solve
    top = _check_speed(bearing, "max_speed_rpm", max_speed_rpm)
    line = _Curve(bearing, resolved, grid, cache, limit, load=load)
    common = dict(load_newton=load, min_film_limit_um=limit,
                  conventions=_conventions(resolved, bearing, grid))
    if line.h(top) < 0:
        return CurveResult("lift_off", math.nan, speed_rpm=top, min_film_thickness_um=math.nan,
                           curve=line.rows, success=False, wall_time_s=time.perf_counter() - t0,
                           message=f"no lift-off below {top:.6g} rpm (h_min < {limit:.4g} µm "
                           f"under {load:.5g} N)", **common)
    root, good = _march(line, top, 1.0 / SPEED_STEP, max(top / 1000, _slowest_speed(bearing)))
    if root is not None:
        film = line.final(root)
        return CurveResult("lift_off", root, speed_rpm=root, min_film_thickness_um=film,
                           curve=line.rows, wall_time_s=time.perf_counter() - t0,
                           message=_not_at_limit(film, limit, f"the film first carries "
                                                 f"{load:.5g} N at {root:.6g} rpm"), **common)
    return CurveResult("lift_off", math.nan, speed_rpm=good, min_film_thickness_um=math.nan,
                       curve=line.rows, success=False, wall_time_s=time.perf_counter() - t0,
                       message=f"h_min stays above {limit:.4g} µm down to {good:.4g} rpm",
                       **common)
