"""Each bearing's running line over a speed ramp, for the rotor transient of a heated rotor.

Quasi-steady in temperature: at every instant each bearing is at the running condition of
the **instantaneous** speed — the fixed point of its lumped heat balance, growths and
viscosity at that speed (:func:`gfbopt.rotor.running.running_case`, the rotor's linear
analyses' own), the temperatures taken as settled at each speed.  The thermal time
constants (the journal's, the sleeve's: seconds to minutes) are neglected: a run-up faster
than them heats less than this says, a coast-down cools more slowly.

The running line is solved once, before the integration, on a grid of speeds over the ramp
(nodes at least every :data:`STEP_RPM`, refined where the interpolation misses, below), and
interpolated in speed by a **monotone piecewise cubic** (PCHIP, Fritsch–Carlson): a clearance
that steepens toward a runaway is not overshot into a false closure.  The interpolation
error is measured, not assumed: every interval's midpoint is solved and compared with the
cubic through the nodes without it; an interval whose miss exceeds :data:`CLEARANCE_TOLERANCE`
of the cold clearance or :data:`VISCOSITY_TOLERANCE` of μ is halved (up to
:data:`REFINEMENTS` times), and the midpoints join the nodes — the misses reported
(``running_interpolation_error``) bound the final interpolant's, which has them as nodes.

In the films (:class:`.rotor_films.FusedFilms`) a bearing of cold clearance c (the rotor
model's reference, the clearance of its file) at the running clearance c_run(ω) and
viscosity μ(ω) has, exactly (H = h/c, P = p/p_a, Φ = P H):

* H_r → H_r − (c − c_run)/c — the growth closes the film uniformly;
* Λ → Λ μ/μ_ref in the Couette term **and** in the time scale ω/(2Λ): dΦ/dt =
  (p_a c²/(12 μ R²)) ∇·(P H³ ∇P) − (ω/2) ∂Φ/∂θ, so the diffusion terms carry μ_ref/μ and the
  advection none (the gas is carried at half the surface speed whatever its viscosity);
* the compliance S = p_a α/c stays the cold-c one: the foil's deflection w = α (p − p_a) is
  dimensional, W = w/c = S (P − 1) with the cold c, whatever the running clearance (the
  running-c model's S_run = p_a α/c_run gives the same w: S_run c_run = S c).

A bearing without ``[journal]``/``[thermal]`` has c_run = c and μ = μ_ref at every speed.
"""
from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np
from scipy.interpolate import PchipInterpolator

from ..errors import ParameterError
from ..inputs.grid import Grid

#: the coarsest spacing of the running line's speeds [rpm]
STEP_RPM = 2500.0
#: an interval is halved when its midpoint's clearance misses the cubic by more than this
#: fraction of the cold clearance (1e-3: 20 nm on the Ruscitto bearing's 20 µm) ...
CLEARANCE_TOLERANCE = 1e-3
#: ... or its viscosity by more than this fraction of μ
VISCOSITY_TOLERANCE = 1e-3
#: the most halvings of an interval [-]
REFINEMENTS = 5
#: the failure speed is bracketed to this fraction of it [-]
BRACKET = 0.01
#: what the outputs call the model
QUASI_STEADY = ("heat balance + growth, quasi-steady: each bearing at the running condition "
                "(clearance, film temperature, viscosity) of the instantaneous speed, the "
                "temperatures taken as settled at each speed (thermal time constants "
                "neglected); monotone cubic (PCHIP) in speed between solved speeds")


@dataclass(frozen=True, eq=False)
class RunningSchedule:
    """One bearing's running line at the solved speeds (SI, ascending speeds_rpm [rpm]):
    running clearance [m], viscosity [Pa s], film temperature [°C] (nan: isothermal); the
    cold clearance c [m] and viscosity μ_ref [Pa s] of the rotor model's bearing."""

    speeds_rpm: np.ndarray
    clearance_m: np.ndarray
    viscosity_pa_s: np.ndarray
    film_temperature_c: np.ndarray
    cold_clearance_m: float
    reference_viscosity_pa_s: float
    label: str = ""
    model: str = ""

    def interpolant(self, values: np.ndarray):
        """PCHIP through ``values`` at the speeds (a constant with one speed)."""
        if self.speeds_rpm.size == 1:
            return lambda n: np.full(np.shape(n), float(values[0]))
        return PchipInterpolator(self.speeds_rpm, values, extrapolate=True)

    def at(self, speed_rpm) -> dict:
        """running_clearance_um, film_temperature_c, viscosity_pa_s at ``speed_rpm``
        (clamped to the solved span), interpolated."""
        n = np.clip(np.asarray(speed_rpm, dtype=float), self.speeds_rpm[0], self.speeds_rpm[-1])
        return {"running_clearance_um": self.interpolant(self.clearance_m)(n) * 1e6,
                "film_temperature_c": self.interpolant(self.film_temperature_c)(n),
                "viscosity_pa_s": self.interpolant(self.viscosity_pa_s)(n)}


class SpeedTable:
    """The film offset δ_k = (c − c_run)/c and the inverse viscosity ratio μ_ref/μ of every
    bearing as piecewise cubics of the engine's speed r = ω/ω_ref (the PCHIP of each
    bearing's :class:`RunningSchedule`, evaluated by hand: a few µs a call)."""

    def __init__(self, schedules, reference_speed_rpm: float):
        nodes = schedules[0].speeds_rpm
        if any(s.speeds_rpm.shape != nodes.shape or np.any(s.speeds_rpm != nodes)
               for s in schedules):
            raise ParameterError("running schedules", len(schedules), "the bearings' running "
                                 "lines must share their speeds")
        self.k = len(schedules)
        self.x = nodes / float(reference_speed_rpm)
        self._xs = self.x.tolist()
        cols = [1.0 - s.clearance_m / s.cold_clearance_m for s in schedules]
        cols += [s.reference_viscosity_pa_s / s.viscosity_pa_s for s in schedules]
        if self.x.size == 1:
            self.coef = np.zeros((1, 4, 2 * self.k))
            self.coef[0, 3] = [float(c[0]) for c in cols]
        else:   # PCHIP of each column on the node speeds, as (interval, power, column)
            self.coef = np.stack([PchipInterpolator(self.x, c).c.T for c in cols], axis=-1)

    def at(self, speed) -> tuple:
        """(δ, μ_ref/μ) at ``speed`` (ω/ω_ref: a float, or (B,)): (K,) each, or (B, K);
        clamped to the solved speeds."""
        x, last = self._xs, len(self._xs) - 1
        if isinstance(speed, float):
            r = min(max(speed, x[0]), x[-1])
            i = min(max(bisect.bisect_right(x, r) - 1, 0), max(last - 1, 0))
            t = r - x[i] if last else 0.0
            v = np.dot((t * t * t, t * t, t, 1.0), self.coef[i])    # the cubic, one call
            return v[:self.k], v[self.k:]
        r = np.clip(np.asarray(speed, dtype=float), x[0], x[-1])
        i = np.clip(np.searchsorted(self.x, r, side="right") - 1, 0, max(last - 1, 0))
        t = (r - self.x[i])[:, None] if last else np.zeros((r.size, 1))
        c = self.coef[i]                                       # (B, 4, 2K)
        v = ((c[:, 0] * t + c[:, 1]) * t + c[:, 2]) * t + c[:, 3]
        return v[:, :self.k], v[:, self.k:]


def speed_table(model) -> Optional[SpeedTable]:
    """The SpeedTable of a rotor transient model whose bearings carry a ``running``
    schedule (None when none does: today's films, untouched)."""
    schedules = [getattr(b, "running", None) for b in model.bearings]
    if all(s is None for s in schedules):
        return None
    if any(s is None for s in schedules):
        raise ParameterError("bearings.running", [s is not None for s in schedules],
                             "a heated rotor model carries a running schedule at every bearing "
                             "(an isothermal one: c_run = c, μ = μ_ref)")
    return SpeedTable(schedules, model.reference_speed * 30.0 / math.pi)


# ------------------------------------------------------------------ solving the line
@dataclass
class RunningLinePlan:
    """What :func:`solve_running_line` found: ``schedules`` per bearing (ascending speeds,
    from the ramp's start to ``end_rpm``), ``end_rpm`` where the ramp ends (its end, or the
    last speed below a failure), ``verdict`` (None, or the failure: kind, bearing,
    limit_rpm, message), ``errors`` (the largest midpoint misses: clearance [µm] and
    viscosity [relative]), ``nodes``, ``fixed_points`` and ``static_solves``, and per
    bearing the warm case at the start speed (``start_cases``)."""

    schedules: tuple
    end_rpm: float
    verdict: Optional[dict]
    errors: dict
    nodes: int
    fixed_points: int
    static_solves: int
    start_cases: tuple = field(repr=False, default=())
    start_rpm: float = float("nan")

    def settings(self) -> dict:
        """The outputs' statement of the model and its line (glossary names)."""
        rows = []
        for s in self.schedules:
            for j, n in enumerate(s.speeds_rpm):
                rows.append({"bearing": s.label, "speed_rpm": float(n),
                             "running_clearance_um": float(s.clearance_m[j] * 1e6),
                             "film_temperature_c": float(s.film_temperature_c[j]),
                             "viscosity_pa_s": float(s.viscosity_pa_s[j])})
        return {"clearance_model": QUASI_STEADY,
                "thermal_models": {s.label: s.model for s in self.schedules},
                "running_interpolation": "PCHIP (monotone piecewise cubic) in speed",
                "running_nodes": self.nodes,
                "running_interpolation_error": self.errors,
                "running_fixed_points": self.fixed_points,
                "running_static_solves": self.static_solves,
                "running_end": None if self.verdict is None else self.verdict["message"],
                "running_line": rows}


def _nodes(start: float, end: float, step: float) -> list:
    if start == end:
        return [start]
    n = max(2, int(math.ceil(abs(end - start) / step)))
    return [start + (end - start) * j / n for j in range(n + 1)]


class _Line:
    """The fixed points solved so far, by speed: (RunningPoint per bearing, failure)."""

    def __init__(self, rotor):
        self.rotor = rotor
        self.solved: dict = {}
        self.starts: dict = {}                # speed -> the bearings' static starts
        self.cases: dict = {}

    def solve(self, speed: float):
        from ..rotor.running import running_case
        from ..rotor.supports import COLD_FACTOR, COLD_GRID

        if speed in self.solved:
            return self.solved[speed]
        rc = self.rotor
        near = min(self.starts, key=lambda s: abs(s - speed), default=None)
        points, failure, starts, cases = [], None, [], []
        for k, (case, load) in enumerate(zip(rc.cases, rc.loads)):
            guess = self.starts[near][k] if near is not None else None
            warm, start, point, failed = running_case(rc.running, k, case, load, speed, guess,
                                                      COLD_GRID, COLD_FACTOR)
            if failed is not None:
                failure = failed
                break
            points.append(point)
            starts.append(start)
            cases.append(warm)
        if failure is None:
            self.starts[speed] = tuple(starts)
            self.cases[speed] = tuple(cases)
        self.solved[speed] = (tuple(points), failure)
        return self.solved[speed]

    def ok(self, speed: float) -> bool:
        return self.solve(speed)[1] is None


def _values(rotor, k: int, point) -> tuple:
    """(c_run [m], μ [Pa s], T_f [°C]) of bearing k at a RunningPoint (None: as given)."""
    g = rotor.cases[k].bearing
    if point is None:
        return g.radial_clearance, g.viscosity, math.nan
    d = point.to_dict()
    mu = point.viscosity if math.isfinite(point.viscosity) else g.viscosity
    return point.running_clearance, mu, d["film_temperature_c"]


def solve_running_line(system, grid: Grid, start_rpm: float, end_rpm: float, *,
                       cache=None, step_rpm: float = STEP_RPM) -> RunningLinePlan:
    """Each bearing's running line from ``start_rpm`` toward ``end_rpm`` (module docstring).
    A speed where a bearing's heat balance runs away or its clearance closes ends the line:
    bracketed to :data:`BRACKET` between the last speed that runs and the first that fails,
    the ramp ends at the former, the verdict names the latter ("thermal runaway at bearing B
    from N rpm", "the journal reaches the foil at bearing B from N rpm").  A start speed
    without a running state is refused (ParameterError, one line): there is nothing to
    start from."""
    from ..rotor.running import CLOSURE
    from ..rotor.supports import resolve_rotor

    if not (math.isfinite(step_rpm) and step_rpm > 0):
        raise ParameterError("running_step_rpm", step_rpm, "must be > 0 [rpm]")
    rotor = resolve_rotor(system, grid, cache)
    if rotor.running is None:
        raise ParameterError("rotor", system.name if hasattr(system, "name") else "",
                             "no bearing states [journal]/[thermal]: nothing to schedule")
    line = _Line(rotor)
    nodes = _nodes(float(start_rpm), float(end_rpm), float(step_rpm))
    if not line.ok(nodes[0]):
        raise ParameterError(f"start speed {nodes[0]:,.0f} rpm", "[journal]/[thermal]",
                             "has no running state to start from: "
                             + line.solve(nodes[0])[1]["message"])
    verdict, good = None, [nodes[0]]
    for n in nodes[1:]:
        if line.ok(n):
            good.append(n)
            continue
        low, high = good[-1], n                       # bracket the failure in speed
        while abs(high - low) > BRACKET * abs(high):
            mid = 0.5 * (low + high)
            if line.ok(mid):
                low = mid
            else:
                high = mid
        if low != good[-1]:
            good.append(low)
        failure = line.solve(high)[1]
        kind = failure.get("kind", "thermal runaway")
        words = ("the journal reaches the foil at bearing" if kind == CLOSURE
                 else "thermal runaway at bearing")
        why = failure["message"]
        if why.endswith(")") and " (" in why:          # its own "… at N rpm (why)"
            why = why.partition(" (")[2][:-1]
        verdict = {"kind": kind, "bearing": failure["bearing"], "limit_rpm": high,
                   "last_running_rpm": low,
                   "message": f"{words} {failure['bearing']} from {high:,.0f} rpm (bracketed "
                              f"to {100 * BRACKET:g} %: the run ends at {low:,.0f} rpm): "
                              f"{why}"}
        break
    errors = _refine(rotor, line, sorted(good))
    speeds = sorted(s for s in line.cases if min(good) <= s <= max(good))
    schedules = []
    for k, support in enumerate(system.bearings):
        vals = np.array([_values(rotor, k, line.solved[s][0][k]) for s in speeds])
        spec = rotor.running.specs[k]
        schedules.append(RunningSchedule(
            np.array(speeds), vals[:, 0], vals[:, 1], vals[:, 2],
            rotor.cases[k].bearing.radial_clearance, rotor.cases[k].bearing.viscosity,
            support.name, spec.model_name if spec is not None else "isothermal, cold "
            "clearance"))
    run = rotor.running
    return RunningLinePlan(tuple(schedules), good[-1], verdict, errors, len(speeds),
                           run.fixed_points, run.drag_solves, line.cases[nodes[0]], nodes[0])


def _refine(rotor, line: _Line, speeds: list) -> dict:
    """Halve every interval whose midpoint misses the PCHIP through the speeds without it
    (module docstring); the midpoints join the line.  Returns the largest misses of the
    accepted intervals: clearance [µm], its fraction of the cold clearance, viscosity
    [relative]."""
    worst = {"clearance_um": 0.0, "clearance_fraction": 0.0, "viscosity_relative": 0.0,
             "refinements": 0}
    if len(speeds) < 2:
        return worst
    check = list(zip(speeds[:-1], speeds[1:]))
    for depth in range(REFINEMENTS + 1):
        nodes = sorted(s for s in line.cases if speeds[0] <= s <= speeds[-1])
        cubic = []
        for k in range(len(rotor.cases)):
            vals = np.array([_values(rotor, k, line.solved[s][0][k]) for s in nodes])
            cubic.append((PchipInterpolator(nodes, vals[:, 0]),
                          PchipInterpolator(nodes, vals[:, 1]), vals))
        again = []
        for low, high in check:
            mid = 0.5 * (low + high)
            if not line.ok(mid):      # a failure inside the line: keep the nodes as they are
                worst["note"] = f"no running state at {mid:,.0f} rpm inside the line"
                continue
            miss_c = miss_mu = 0.0
            for k, (cc, cm, _) in enumerate(cubic):
                c, mu, _t = _values(rotor, k, line.solved[mid][0][k])
                cold = rotor.cases[k].bearing.radial_clearance
                miss_c = max(miss_c, abs(float(cc(mid)) - c) / cold)
                miss_mu = max(miss_mu, abs(float(cm(mid)) - mu) / mu)
            if (miss_c > CLEARANCE_TOLERANCE or miss_mu > VISCOSITY_TOLERANCE) \
                    and depth < REFINEMENTS:
                again += [(low, mid), (mid, high)]
                continue
            cold = min(c.bearing.radial_clearance for c in rotor.cases)
            worst["clearance_fraction"] = max(worst["clearance_fraction"], miss_c)
            worst["clearance_um"] = max(worst["clearance_um"], miss_c * cold * 1e6)
            worst["viscosity_relative"] = max(worst["viscosity_relative"], miss_mu)
        if not again:
            break
        worst["refinements"] = depth + 1
        check = again
    return worst
