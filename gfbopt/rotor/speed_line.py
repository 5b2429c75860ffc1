"""One bearing's mass–speed line as a function to search: f(N) and g(N), full or local
thresholds; and the package's one onset secant, :func:`secant_root`.

:class:`BearingLine` evaluates, at a speed N [rpm], the margin of the rotor along its line
(:mod:`gfbopt.rotor.onset`): f = (M̄c − M̄)/(M̄c + M̄) in [−1, 1] (> 0 stable, finite even when
M̄c is 0 or ∞, for the bracketing scan) and g = ln(M̄c/M̄) (for the secant refinement: M̄
grows as N², M̄c slowly, so g is nearly linear in ln N).  Each evaluation

* solves the equilibrium warm from the nearest speed already solved (extrapolated from the
  two nearest when both are close, :data:`EXTRAPOLATION_DISTANCE`), with the Newton fast
  path (:mod:`gfbopt.static.newton`; IPOPT when it does not converge in a few steps, a cold
  IPOPT solve and the load-capacity check of :func:`~gfbopt.rotor.analysis.equilibrium` when
  that fails too), or, on a fine grid guided by a coarse one, from the coarse equilibrium at
  the same speed interpolated onto the fine grid (:func:`transferred_start`);
* computes the threshold either in full (:func:`gfbopt.linear.linear_threshold`: every branch,
  the least-stable one wins) or locally (:func:`gfbopt.linear.crossings.local_crossing`:
  Newton's method on the whirl ratio from the crossing of a nearby evaluation on a Krylov
  space of one sparse LU, instead of a 24-point Krylov scan, a check and an eigenvalue probe;
  the same crossing to ~1e-10 when the branch is the same).  A local threshold
  follows one branch; the search confirms its answer with a full one.

Every evaluation is a row of the result's scan, with the grid it was made on and whether its
threshold was full or local.  :class:`Guide` is the line of a coarse guide (its failures are
:class:`GuideFailed`); :func:`secant_root` is the safeguarded secant on g.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Optional

import numpy as np
from scipy.interpolate import RegularGridInterpolator

from ..errors import ConvergenceError, ParameterError
from ..inputs.conversions import film_thickness_um
from ..linear import linear_threshold, linearise
from ..linear.crossings import local_crossing
from ..static import StaticSolution, consistent_state, solve_static
from ..threads import single_threaded
from .analysis import Case, equilibrium

#: a coarse guide's equilibrium or crossing at a speed is preferred to this grid's own at
#: another speed when it is nearer by more than this, in |ln(speed ratio)| [-]: the grid
#: error of the guide (~1 %) is worth a few per cent of speed
GUIDE_DISTANCE = 0.05
#: a warm start is extrapolated from the two nearest solved speeds when both lie within
#: this of the speed, in |ln(speed ratio)| [-] (farther, the nearest solution is used as it is)
EXTRAPOLATION_DISTANCE = 0.02
#: bound assumed on C = |g''/(2g')| in the secant's error estimate C |step| |step before|
#: (:func:`secant_root`; measured C ≈ 0.03 on the Ruscitto speed line, 5,000–15,000 rpm) [-]
ERROR_FACTOR = 1.0
#: the error estimate stops the secant only for a next step at most this, in ln N [-]: its
#: point is a step from the last one evaluated, and the confirmation there must stay one
#: Newton step (a step of 3e-4, allowed by the product alone, would be several)
ERROR_STOP_STEP = 1e-4
#: the whirl ratio at the onset is interpolated from rows within this of it, in ln N [-]
WHIRL_SPAN = 0.02
#: secant steps before :func:`secant_root` gives up (the onset search then falls back to
#: Brent's method on full thresholds)
SECANT_STEPS = 16


class BearingLine:
    """f and g along one bearing's mass–speed line of ``case`` on its grid (module
    docstring; the rotor's line of both bearings and every mode is
    :class:`gfbopt.rotor.system.SpeedLine`)."""

    def __init__(self, case: Case, threshold_options: Optional[dict] = None,
                 fast_path: bool = True):
        self.case = case
        self.fast_path = fast_path
        self.rows: list[dict] = []
        self.threshold_options = dict(threshold_options or {})
        self._solutions: dict = {}
        self._rows: dict = {}
        self._last = None                            # (speed, equilibrium, linearisation)
        self.guide: Optional["BearingLine"] = None   # a coarse line whose solutions start ours

    @property
    def solutions(self) -> dict:
        """The equilibria solved so far: speed [rpm] → StaticSolution (read, not written)."""
        return self._solutions

    # ----------------------------------------------------------------- evaluations
    @single_threaded
    def full(self, speed: float) -> dict:
        """The row at ``speed`` with the full threshold (cached)."""
        row = self._rows.get(speed)
        if row is not None and row["threshold"] == "full":
            return row
        sol, lin = self._linearised(speed)
        thr = linear_threshold(lin, **self.threshold_options)
        root = (thr.critical_mass * thr.whirl_ratio**2 * lin.load
                if math.isfinite(thr.critical_mass) and thr.critical_mass > 0 else math.nan)
        return self._record(speed, sol, thr.critical_mass, thr.whirl_ratio, root, "full",
                            thr.message)

    @single_threaded
    def local(self, speed: float, near: Optional[dict] = None) -> dict:
        """The row at ``speed`` with a local threshold from the crossing of ``near`` (default:
        the nearest row with a finite crossing, on this grid or the guide's); the full
        threshold when there is none or the local search fails."""
        if speed in self._rows:
            return self._rows[speed]
        near = near or self._nearest_crossing(speed)
        if near is None:
            return self.full(speed)
        sol, lin = self._linearised(speed)
        found = local_crossing(lin, near["whirl_ratio"], near["root"])
        if found is None:
            return self.full(speed)
        return self._record(speed, sol, found.mass, found.whirl, found.root.real, "local", "")

    def f(self, speed: float) -> float:
        """(M̄c − M̄)/(M̄c + M̄) at ``speed`` with the full threshold."""
        return self.full(speed)["f"]

    # -------------------------------------------------------------------- helpers
    def _nearest_crossing(self, speed: float) -> Optional[dict]:
        """The row with a crossing nearest ``speed``: on this grid, or on the guide's when
        its speed is nearer by more than :data:`GUIDE_DISTANCE`."""
        def distance(row, penalty):
            return abs(math.log(row["speed_rpm"] / speed)) + penalty
        rows = [(distance(r, 0.0), k, r) for k, r in enumerate(self.rows)
                if math.isfinite(r["root"])]
        if self.guide is not None:
            rows += [(distance(r, GUIDE_DISTANCE), len(rows) + k, r)
                     for k, r in enumerate(self.guide.rows) if math.isfinite(r["root"])]
        return min(rows, default=(None, None, None))[2]

    def _linearised(self, speed: float):
        if self._last is not None and self._last[0] == speed:
            return self._last[1:]
        sol = self._equilibrium(speed)
        self._solutions[speed] = sol
        lin = linearise(sol, self.case.cache(sol.model, self.case.grid))
        self._last = (speed, sol, lin)
        return sol, lin

    def _equilibrium(self, speed: float) -> StaticSolution:
        case = self.case
        model = case.model(speed)
        solver = case.cache(model, case.grid)
        start = self._start(speed, solver, model)
        if not self.fast_path:                       # the reference: IPOPT from the start
            return equilibrium(case, speed, start)
        if start is not None:
            sol = solve_static(model, load=case.load, solver=solver, initial=start,
                               fast_path=True)
            if sol.success:
                return sol
        return equilibrium(case, speed)              # cold; raises LoadCapacityError

    def _start(self, speed: float, solver, model) -> Optional[StaticSolution]:
        """The warm start: the nearest speed solved on this grid, else the guide's
        equilibrium at the nearest speed interpolated onto this grid."""
        def distance(other):
            return abs(math.log(other / speed))
        nearest = min(self._solutions, key=distance, default=None)
        near = (min(self.guide.solutions, key=distance, default=None)
                if self.guide is not None else None)
        if near is not None and (nearest is None or
                                 distance(near) + GUIDE_DISTANCE < distance(nearest)):
            return transferred_start(self.guide.solutions[near], solver, model)
        if nearest is None:
            return None
        return self._extrapolated(speed, nearest) or self._solutions[nearest]

    def _extrapolated(self, speed: float, nearest: float) -> Optional[StaticSolution]:
        """The state extrapolated linearly in ln N from the two solved speeds nearest
        ``speed`` when both lie within :data:`EXTRAPOLATION_DISTANCE` of it (the secant's
        points: its error is then of the order of the product of the two distances, so the
        Newton fast path needs a step or none); None otherwise."""
        u = math.log(speed)
        others = [v for v in self._solutions if v != nearest]
        if not others:
            return None
        second = min(others, key=lambda v: abs(math.log(v) - u))
        u1, u0 = math.log(nearest), math.log(second)
        if max(abs(u1 - u), abs(u0 - u)) > EXTRAPOLATION_DISTANCE:
            return None
        a, b = self._solutions[nearest], self._solutions[second]
        x = a.state + (a.state - b.state) * (u - u1) / (u1 - u0)
        return dataclasses.replace(a, state=x)

    def _record(self, speed, sol, mcrit, whirl, root, kind, message) -> dict:
        mbar = self.case.mass_parameter(speed)
        f = 1.0 if math.isinf(mcrit) else (mcrit - mbar) / (mcrit + mbar)
        g = (math.inf if math.isinf(mcrit) else -math.inf if mcrit <= 0
             else math.log(mcrit / mbar))
        row = {"speed_rpm": speed, "mass": mbar, "critical_mass": mcrit,
               "mass_margin": mcrit / mbar - 1.0, "whirl_ratio": whirl,
               "bearing_number": sol.model.bearing_number, "eccentricity": sol.eccentricity,
               "min_film_thickness_um": film_thickness_um(
                   sol.min_film, self.case.bearing.radial_clearance),
               "grid": str(self.case.grid), "threshold": kind, "static_solver": sol.solver,
               "message": message, "f": f, "g": g, "root": root}
        if speed in self._rows:
            self.rows.remove(self._rows[speed])
        self._rows[speed] = row
        self.rows.append(row)
        return row


def transferred_start(coarse: StaticSolution, solver, model) -> StaticSolution:
    """A start for ``solver`` (a finer grid) from a coarse equilibrium: its pressure
    interpolated (bilinear in θ from the seam and Z) onto the fine nodes, ε and φ kept, every
    lifted variable made consistent (:func:`~gfbopt.static.consistent_state`).  Only its
    ``state`` is meant to be used (as ``initial`` of a solve)."""
    st = solver.stencil
    psi = coarse.theta - coarse.seam_angle_rad            # θ from the grid origin, 0 first
    psi[0] = 0.0
    pressure = coarse.pressure
    if st.periodic:                                   # close the period for interpolation
        psi = np.append(psi, 2 * math.pi)
        pressure = np.vstack([pressure, pressure[:1]])
    z = st.z_nodes(model.length_ratio)
    interp = RegularGridInterpolator((psi, coarse.z), pressure, bounds_error=False,
                                     fill_value=None)
    grid_psi, grid_z = np.meshgrid(st.psi, z, indexing="ij")
    p_full = interp(np.column_stack([grid_psi.ravel(), grid_z.ravel()]))
    x = consistent_state(solver, model, np.maximum(p_full, 1e-3), coarse.eccentricity,
                         coarse.attitude_angle_rad)
    return dataclasses.replace(coarse, state=x, grid=solver.grid)


class GuideFailed(Exception):
    """An evaluation on the coarse guide failed (a load its grid cannot carry, a solver
    failure): the search goes on without the guide."""


class Guide(BearingLine):
    """The coarse guide's line: its failures are :class:`GuideFailed`, never the answer."""

    def full(self, speed: float) -> dict:
        try:
            return super().full(speed)
        except (ParameterError, ConvergenceError) as exc:
            raise GuideFailed(str(exc)) from exc

    def local(self, speed: float, near: Optional[dict] = None) -> dict:
        try:
            return super().local(speed, near)
        except (ParameterError, ConvergenceError) as exc:
            raise GuideFailed(str(exc)) from exc


@single_threaded
def secant_root(g, low: float, high: float, tol: float, start=None,
                first: Optional[float] = None, error_tol: float = 0.0,
                bracketed: bool = False, last: bool = False,
                steps: int = SECANT_STEPS) -> Optional[tuple]:
    """(u*, dg/du) with g(u*) = 0, u = ln N [rpm], by secant steps safeguarded by bisection:
    the one onset secant of the package (one bearing, :mod:`gfbopt.rotor.onset`; each mode of
    the rotor, :mod:`gfbopt.rotor.mode_search`).

    ``g(speed_rpm, full)`` is the function searched (``full``: the caller's reference
    evaluation, e.g. a full threshold rather than a local one), or a line whose
    ``full(speed)`` and ``local(speed)`` rows carry ``"g"`` (:func:`line_function` reads
    it: a :class:`BearingLine`).  [lo, hi] = [ln ``low``, ln ``high``].  Without ``start``,
    it is a bracket whose ends are evaluated with ``full`` (g(lo) > 0 ≥ g(hi)); with ``start``
    = the points [(u, g), …] already known, the secant starts from the last two of them (or
    from the last one and a ``first`` point), and [lo, hi] is the bracket when ``bracketed``
    (the root lies in it: bisection from the first step), else it only bounds the secant
    until a sign change brackets the root.  Interior points use ``full=False``.

    Converged when the next secant point u* is at most ``tol`` from the last point, or when
    its estimated error is at most ``error_tol``: the secant's error after a step is
    C = |g''/(2g')| times the product of the errors of the two points before, and near the
    root the errors are the steps, so the estimate is :data:`ERROR_FACTOR` (C ≤ 1 assumed;
    measured C ≈ 0.03 on the Ruscitto speed line) times |step to u*| × |step before| (used
    only when the steps shrink and the step is at most :data:`ERROR_STOP_STEP`).  u* is
    returned without evaluating it (the caller confirms it: :func:`gfbopt.rotor.onset`), or,
    with ``last``, the last point evaluated (whose error that step estimates: the rotor's
    mode search, whose answer is read at an evaluated speed).  The convergence test is
    applied from the first point evaluated on (at once when ``start`` and ``first`` are
    given).  None when the secant leaves the bounds without a bracket or does not converge
    in ``steps`` steps."""
    if hasattr(g, "full"):                       # a line: its rows' g
        g = line_function(g)
    lo, hi = math.log(low), math.log(high)
    ends = {lo: low, hi: high} if start is None or bracketed else {}

    def value(u, full=False):
        return g(ends.get(u, math.exp(u)), full)

    if start is None:
        points = [(lo, value(lo, True)), (hi, value(hi, True))]
        a, b = lo, hi
        u = None
    else:
        points = list(start)
        a, b = (lo, hi) if bracketed else (None, None)
        u = first
    early = start is not None and first is not None
    for step in range(steps):
        (u0, g0), (u1, g1) = (points[-2], points[-1]) if len(points) > 1 else (
            (None, None), points[-1])
        predicted = u is not None or (g0 is not None and math.isfinite(g0)
                                      and math.isfinite(g1) and g1 != g0)
        if u is None and predicted:
            u = _secant_point(points)
        if a is not None and (u is None or not a < u < b):
            u, predicted = 0.5 * (a + b), False   # bisection inside the bracket
        if u is None or not lo <= u <= hi:
            return None
        if predicted and (step > 0 or early) and _converged(u, u0, u1, tol, error_tol):
            return (u1 if last else u), slope(points)
        gu = value(u)
        if not math.isfinite(gu) and a is None:
            return None
        if a is None:
            signs = [p for p in points + [(u, gu)] if math.isfinite(p[1])]
            pos = [p[0] for p in signs if p[1] > 0]
            neg = [p[0] for p in signs if p[1] <= 0]
            if pos and neg and max(pos) < min(neg):
                a, b = max(pos), min(neg)
        elif gu > 0:
            a = u
        else:
            b = u
        points.append((u, gu))
        if gu == 0:
            return u, slope(points)
        u = None
    return None


def line_function(line: "BearingLine"):
    """g(speed, full) of one bearing's line for :func:`secant_root`: its row's g with the
    full threshold (``full``) or a local one."""
    def g(speed: float, full: bool = False) -> float:
        return (line.full(speed) if full else line.local(speed))["g"]
    return g


def _secant_point(points: list) -> Optional[float]:
    """The secant's next point from the last two points (None when it is undefined)."""
    (u0, g0), (u1, g1) = points[-2], points[-1]
    if not (math.isfinite(g0) and math.isfinite(g1) and g1 != g0):
        return None
    return u1 - g1 * (u1 - u0) / (g1 - g0)


def _converged(u: float, u0: Optional[float], u1: float, tol: float,
               error_tol: float) -> bool:
    """The stop test of :func:`secant_root`: |u − u1| ≤ ``tol``, or the estimated error of u,
    :data:`ERROR_FACTOR` |u − u1| |u1 − u0|, at most ``error_tol`` while the steps shrink."""
    step = abs(u - u1)
    if step <= tol:
        return True
    if u0 is None or error_tol <= 0:
        return False
    before = abs(u1 - u0)
    return (step <= min(before, ERROR_STOP_STEP)
            and ERROR_FACTOR * step * before <= error_tol)


def onset_whirl_ratio(rows: list, onset: float, same_branch: float) -> float:
    """The whirl ratio at the onset speed [-]: interpolated (or extrapolated) linearly in
    ln N from the two rows nearest the onset when both lie within :data:`WHIRL_SPAN` of it
    on one branch (whirl ratios within ``same_branch``), else the nearest row's.

    The searches stop without evaluating their last point (the secant's next point, Brent's
    root inside its last bracket), so the nearest row can be a step away from the onset
    (up to 1e-4 relative): γ varies along the line by dγ/d ln N times that, while the
    interpolation's error is of the order of the product of the two distances."""
    def distance(r):
        return abs(math.log(r["speed_rpm"] / onset))
    near = sorted((r for r in rows if math.isfinite(r["whirl_ratio"])), key=distance)
    if not near:
        return math.nan
    if len(near) < 2 or distance(near[1]) > WHIRL_SPAN:
        return near[0]["whirl_ratio"]
    (u0, g0), (u1, g1) = ((math.log(r["speed_rpm"]), r["whirl_ratio"]) for r in near[:2])
    if u0 == u1 or abs(g1 - g0) >= same_branch:
        return near[0]["whirl_ratio"]
    return g0 + (g1 - g0) * (math.log(onset) - u0) / (u1 - u0)


def slope(points: list) -> float:
    """dg/du from the last two points (nan when one is not finite)."""
    if len(points) < 2:
        return math.nan
    (v0, h0), (v1, h1) = points[-2], points[-1]
    finite = math.isfinite(h0) and math.isfinite(h1) and v1 != v0
    return (h1 - h0) / (v1 - v0) if finite else math.nan
