"""From what speed does my rotor whirl: the onset speed on the rotor's mass–speed line.

For a rotor of mass M per bearing under a fixed static load W0, the speed changes both
groups: Λ = 6 μ ω R²/(p_a c²) grows as ω and M̄ = M c ω²/W0 as ω², while W̄0 = W0/(p_a R²) stays
fixed.  The rotor whirls where M̄(ω) reaches the threshold M̄c(Λ(ω), W̄0); the onset speed is the
lowest such speed in the range asked (docs/PHYSICS.md §8, "Onset speed").

Scan.  Both searches bracket the onset the same way: the threshold is computed on a scan of
speeds spaced geometrically by a ratio of at most :data:`SCAN_RATIO` = 1.25 (M̄ grows by at
most 1.56× from one scan speed to the next), lowest speed first, and the onset lies in the
first scan interval where the sign of (M̄c − M̄) changes from + to −.  At every scan speed the
threshold is the least-stable one over all root branches (:func:`gfbopt.linear.linear_threshold`
scans whirl ratios 0.02–1.2 and keeps the smallest critical mass, including the extra
low-whirl crossings, and 0 when the massless journal is already unstable).  An unstable
window narrower than one scan interval can be missed; give a narrower range to look closer.
One static build serves the whole line (Λ is a parameter of the CasADi model).

``method="secant"`` (default; :mod:`.speed_line`).  Inside the bracket, secant steps on
g = ln(M̄c/M̄) against ln N (nearly linear: M̄ ∝ N², M̄c varies slowly), safeguarded by
bisection, until its next step is at most :data:`SECANT_TOLERANCE` or its estimate of the
next point's error (the product of the last two steps) is at most :data:`ERROR_TOLERANCE`;
each step's threshold is local — Newton's method on the whirl ratio from the previous
crossing (:func:`gfbopt.linear.crossings.local_crossing`, one sparse LU and a few Krylov
steps) — and each static solve starts from the nearest speed (extrapolated along the line,
its LU reused) with the Newton fast path (:mod:`gfbopt.static.newton`).  The answer is
confirmed by a full threshold at the secant's converged point: it must put the root within
:data:`CONFIRM_TOLERANCE` of it (otherwise another branch took over, and Brent's method on
full thresholds refines the bracket, as the reference does).

Coarse guide (``coarse_grid``; "auto" uses :data:`COARSE_GRID` on grids with at least
:data:`GUIDE_FACTOR` times its cells).  The scan runs on the coarse grid (thresholds there
are ~15× cheaper at 144 × 36); the lowest speed is always solved on the fine grid too (it is
the result's first row and decides "unstable at the lower end"): with a local threshold from
the guide's crossing there when the guide's and the fine local mass margins both reach
:data:`COARSE_MARGIN` (the test every other scan speed passes; a local threshold converges to
the full threshold's own whirl tolerance, so on the same branch the two agree to ~1e-10),
with the full threshold otherwise.  The coarse onset starts the
fine secant (its static from the coarse equilibrium interpolated onto the fine grid, a first
Newton step with the coarse slope).  The first scan speed above the fine onset is then solved
on the fine grid: it must be unstable there, as the end of the fine scan's bracket would be
(otherwise the search goes on as a fine scan); it is also where the scan method finds its
smallest margin.  A local threshold on the onset's branch settles it when it is unstable
(the full threshold, the smallest crossing mass, is no larger — unless the full threshold's
24-point whirl scan would miss that crossing, a crossing the confirmed onset lies on); the
full threshold decides otherwise.  Risk and check: the fine and coarse thresholds differ by the grid error, so
a coarse scan speed could have the wrong sign.  Every scan speed below the fine onset (every
one, when the coarse scan finds no onset) whose coarse mass margin is below
:data:`COARSE_MARGIN` is recomputed on the fine grid, and a fine sign change there restarts the
refinement in that interval on the fine grid.  What is not checked: a scan speed whose coarse
margin exceeds :data:`COARSE_MARGIN` but whose fine threshold is unstable — a grid error of
M̄c larger than that margin, several times the largest difference measured (the constant's
comment).  When the coarse scan finds no onset, the smallest margin is taken on the fine grid
at the coarse scan's smallest-margin speed.  The result says the guide was used
(``coarse_grid``, the answer's text; every scan row names its grid and threshold).  When the
guide itself fails (e.g. the coarse grid cannot carry a load the fine grid carries, its
capacity differing by the grid error), the search goes on without it and ``notes`` says so.

``method="scan"``: the reference search of gfbopt 0.2 — IPOPT warm starts, full thresholds,
Brent's method on f = (M̄c − M̄)/(M̄c + M̄) to :data:`SPEED_TOLERANCE` (relative), the whirl
window narrowed to ±0.1 (8 ratios) when both bracket ends are on one branch.  The two agree to
≤ 1e-6 (tests/verification/test_onset_search.py); their cost is compared in
benchmarks/bench_onset.py.
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from typing import Optional, Union

from scipy.optimize import brentq

from ..errors import ParameterError
from ..inputs.bearing import BearingGeometry
from ..inputs.checks import check_positive
from ..inputs.conversions import rpm_to_rad_per_s, whirl_frequency_hz
from ..inputs.grid import DEFAULT_GRID, Grid, as_grid
from ..inputs.options import ModelOptions
from ..inputs.rotor import Rotor
from ..progress import progress as progress_bar
from ..static import SolverCache
from ..threads import single_threaded
from .analysis import resolve_case
from .speed_line import (BearingLine, Guide, GuideFailed, line_function, onset_whirl_ratio,
                         secant_root)

#: largest ratio between successive scan speeds [-]
SCAN_RATIO = 1.25
#: relative tolerance of the reference (``method="scan"``) onset speed [-]
SPEED_TOLERANCE = 1e-4
#: bracket ends whose threshold whirl ratios differ by less than this are on one branch [-]
SAME_BRANCH = 0.05
#: ways to search (module docstring)
METHODS = ("secant", "scan")
#: the secant refinement stops after a step on ln N of at most this [-]; the error of its
#: last point is then of the order of this times the step before (superlinear convergence;
#: measured ≤ 1e-9 against the reference at a tight tolerance).  Steps much smaller would
#: only resolve the noise of g (~1e-10: the static and threshold tolerances)
SECANT_TOLERANCE = 1e-6
#: the full threshold at the secant's onset must put the root within this of it, in ln N
#: (relative speed; one Newton step on g) [-]
CONFIRM_TOLERANCE = 1e-7
#: the secant also stops when its estimate of the next point's error (the product of the
#: last two steps, :data:`~.speed_line.ERROR_FACTOR` times it) is at most this [-]: a
#: tenth of the 1e-6 the search promises against the reference, so that the estimate may
#: be ten times optimistic
ERROR_TOLERANCE = 1e-7
#: tolerance of the coarse guide's secant (its onset only starts the fine one) [-]
COARSE_TOLERANCE = 1e-5
#: the coarse guide's grid for ``coarse_grid="auto"``
COARSE_GRID = Grid(36, 10)
#: "auto" uses the guide on grids with at least this many times its cells
GUIDE_FACTOR = 8
#: a coarse scan speed with a mass margin below this is recomputed on the fine grid [-]: a
#: coarse margin of 0.15 stays positive on the fine grid unless M̄c(coarse)/M̄c(fine) − 1 >
#: 0.15 (about 13 % of M̄c).  Measured |M̄c(36 × 10)/M̄c(144 × 36) − 1| ≤ 3.0 % (Ruscitto,
#: 2 kg, 20 N: periodic, max-film, seam 180°, local law η = 0.3; 5,000–20,000 rpm), and
#: against 72 × 20 below a third of this margin on 50 random cases
#: (tests/verification/test_onset_search.py, slow tier)
COARSE_MARGIN = 0.15


def check_speed_range(speed_range) -> tuple[float, float]:
    """(low, high) [rpm] with 0 < low < high; ParameterError otherwise."""
    try:
        low, high = (float(v) for v in speed_range)
    except (TypeError, ValueError):
        raise ParameterError("speed_range", speed_range, "must be two speeds in rpm "
                             "(low, high)") from None
    low, high = check_positive("speed_range low", low), check_positive("speed_range high", high)
    if not high > low:
        raise ParameterError("speed_range", speed_range, "must be increasing: low < high [rpm]")
    return low, high


def check_coarse_grid(coarse_grid, grid: Grid) -> Optional[Grid]:
    """The guide's grid: None or "none" (no guide), "auto" (:data:`COARSE_GRID` when ``grid``
    has at least :data:`GUIDE_FACTOR` times its cells), a Grid or 'NTHETAxNZ' coarser than
    ``grid``; ParameterError otherwise."""
    if coarse_grid is None or coarse_grid == "none":
        return None
    if coarse_grid == "auto":
        cells = COARSE_GRID.n_theta * COARSE_GRID.n_z
        return COARSE_GRID if grid.n_theta * grid.n_z >= GUIDE_FACTOR * cells else None
    guide = coarse_grid if isinstance(coarse_grid, Grid) else Grid.parse(coarse_grid)
    if not (guide.n_theta <= grid.n_theta and guide.n_z <= grid.n_z and guide != grid):
        raise ParameterError("coarse_grid", str(guide), f"must be coarser than the grid "
                             f"{grid} (or None, or 'auto')")
    return guide


@dataclass(frozen=True)
class OnsetResult:
    """The onset speed of whirl of a rotor along its mass–speed line (SI, per bearing).

    onset_speed_rpm : lowest speed in the range where the rotor becomes linearly unstable
        [rpm] (nan when there is none in the range, or when it is unstable at the low end)
    whirl_frequency_hz : whirl frequency at the onset [Hz]; whirl_ratio γ there [-]
    stable_over_range : True when the rotor is stable at every scanned speed
    unstable_at_lower_end : True when it is already unstable at the lowest speed
    smallest_margin : smallest M_crit/M − 1 over the speeds evaluated on the grid [-], and
        smallest_margin_speed_rpm where it occurs [rpm]
    speed_range_rpm : the range searched; scan : one row per speed evaluated on the grid
        (speed_rpm, mass_parameter, critical_mass_parameter, mass_margin, whirl_ratio,
        bearing_number, eccentricity, min_film_thickness_um [µm], grid, threshold "full" | "local", static_solver
        "ipopt" | "newton", message), lowest speed first; coarse_scan : the same for the
        coarse guide's evaluations (empty without one)
    method : "secant" or "scan"; coarse_grid : the guide's grid ("" when none was used)
    rotor_mass_kg, load_newton [N], conventions (options used), evaluations (threshold
    computations on the grid), success, message (empty on success), notes (remarks of the
    thresholds, e.g. "stable for every rotor mass" at a speed), wall_time_s [s]
    """

    onset_speed_rpm: float
    whirl_frequency_hz: float
    whirl_ratio: float
    stable_over_range: bool
    unstable_at_lower_end: bool
    smallest_margin: float
    smallest_margin_speed_rpm: float
    speed_range_rpm: tuple
    scan: list = field(repr=False)
    rotor_mass_kg: float = math.nan
    load_newton: float = math.nan
    conventions: dict = field(default_factory=dict)
    evaluations: int = 0
    success: bool = True
    message: str = ""
    wall_time_s: float = 0.0
    method: str = "secant"
    coarse_grid: str = ""
    coarse_scan: list = field(default_factory=list, repr=False)
    notes: str = ""

    @property
    def answer(self) -> str:
        """The answer in one line."""
        low, high = self.speed_range_rpm
        guide = f" (scan guided by a {self.coarse_grid} grid)" if self.coarse_grid else ""
        if self.unstable_at_lower_end:
            return (f"unstable already at {low:.6g} rpm: the onset lies below the range "
                    f"(mass margin there {self.scan[0]['mass_margin']:+.3g})")
        if self.stable_over_range:
            return (f"stable over the whole range {low:.6g}–{high:.6g} rpm (smallest mass "
                    f"margin {self.smallest_margin:+.3g} at {self.smallest_margin_speed_rpm:.6g}"
                    f" rpm){guide}")
        return (f"onset of whirl at {self.onset_speed_rpm:.6g} rpm, whirling at "
                f"{self.whirl_frequency_hz:.4g} Hz (whirl ratio {self.whirl_ratio:.3f})"
                f"{guide}")

    def to_dict(self) -> dict:
        out = {k: getattr(self, k) for k in self.__dataclass_fields__}
        out["answer"] = self.answer
        return out


@single_threaded
def onset_speed(bearing: BearingGeometry, rotor: Rotor, load_newton: Optional[float],
                speed_range, *, film: Optional[str] = None,
                seam_angle_deg: Union[float, str, None] = None, foil: Optional[str] = None,
                deflection_law: Optional[str] = None, loss_factor: Optional[float] = None,
                options: Optional[ModelOptions] = None, grid: Grid = DEFAULT_GRID,
                cache: Optional[SolverCache] = None, method: str = "secant",
                coarse_grid: Union[Grid, str, None] = "auto",
                progress: bool = False, seam_angle=None) -> OnsetResult:
    """The lowest speed in ``speed_range`` [rpm] at which the rotor whirls (module docstring).

    Parameters
    ----------
    bearing : the bearing in SI; rotor : mass per bearing [kg]
    load_newton : static load per bearing W0 [N], fixed along the line (None: W0 = M g)
    speed_range : (low, high) [rpm]
    film, seam_angle_deg, foil, deflection_law, loss_factor, options, grid, cache : as for
        :func:`gfbopt.rotor.stability`
    method : "secant" (default) or "scan" (the reference search of gfbopt 0.2)
    coarse_grid : with "secant", the grid of a coarse scan that guides the search: "auto"
        (default: :data:`COARSE_GRID` on grids with ≥ :data:`GUIDE_FACTOR`× its cells), None
        (none), or a coarser Grid / 'NTHETAxNZ'; refused with "scan"
    progress : report progress on stderr (:mod:`gfbopt.progress`); off for studies/workers

    Returns
    -------
    OnsetResult; "stable over the whole range" and "unstable at the lower end" are answers
    too.  A load the bearing cannot carry at a scanned speed raises LoadCapacityError.
    """
    t0 = time.perf_counter()
    low, high = check_speed_range(speed_range)
    if method not in METHODS:
        raise ParameterError("method", method, f"must be one of: {', '.join(METHODS)}")
    grid = as_grid(grid)
    guide_grid = check_coarse_grid(coarse_grid, grid)
    if method == "scan" and coarse_grid not in (None, "auto", "none"):
        raise ParameterError("coarse_grid", coarse_grid, "is used by method 'secant' only")
    guide_grid = guide_grid if method == "secant" else None
    case = resolve_case(bearing, rotor, load_newton, film=film, seam_angle_deg=seam_angle_deg,
                        seam_angle=seam_angle,
                        foil=foil, deflection_law=deflection_law, loss_factor=loss_factor,
                        options=options, grid=grid, cache=cache)
    count = max(2, math.ceil(math.log(high / low) / math.log(SCAN_RATIO) - 1e-9) + 1)
    speeds = [low * (high / low) ** (k / (count - 1)) for k in range(count)]
    line = BearingLine(case, fast_path=(method == "secant"))
    guide, note = None, ""
    if guide_grid is not None:
        guide = Guide(dataclasses.replace(case, grid=guide_grid))
        line.guide = guide
    with progress_bar(total=count, desc="onset speed", unit="speed",
                      enabled=progress) as bar:
        if method == "scan":
            kind, onset = _scan_search(line, speeds, bar)
        else:
            try:
                kind, onset = _secant_search(line, speeds, guide, bar)
            except GuideFailed as exc:          # e.g. the coarse grid cannot carry the load
                note = f"the {guide_grid} guide failed ({exc}): searched on {grid} alone"
                guide = line.guide = None
                kind, onset = _secant_search(line, speeds, None, bar)
        bar.set_postfix_str("done")
        bar.update(max(0, count - bar.n))
    return _result(line, guide, kind, onset, method, t0, note, speed_range_rpm=(low, high),
                   rotor_mass_kg=rotor.mass_kg, load_newton=case.load_newton,
                   conventions=case.conventions(),
                   margin_upto=min((s for s in speeds if s > onset), default=math.inf))


# ------------------------------------------------------------------- the reference
def _scan_search(line: BearingLine, speeds: list, bar) -> tuple:
    """gfbopt 0.2's search: scan, then Brent's method on f with full thresholds."""
    previous = None
    for speed in speeds:
        value = line.f(speed)
        bar.update(1)
        if value > 0:
            previous = speed
            continue
        if previous is None:
            return "unstable", math.nan
        _narrow(line, previous, speed)
        bar.set_postfix_str("refining")
        root = brentq(line.f, previous, speed, xtol=SPEED_TOLERANCE * previous,
                      rtol=SPEED_TOLERANCE)
        return "onset", root
    return "stable", math.nan


def _narrow(line: BearingLine, low: float, high: float) -> None:
    """Refine between scan speeds ``low`` and ``high``: scan whirl ratios near the
    threshold's branch only, when both ends are on the same one."""
    ends = [r["whirl_ratio"] for r in line.rows if r["speed_rpm"] in (low, high)]
    if len(ends) == 2 and all(map(math.isfinite, ends)) and abs(
            ends[0] - ends[1]) < SAME_BRANCH:
        line.threshold_options = dict(whirl_range=(max(0.02, min(ends) - 0.1),
                                                   max(ends) + 0.1), samples=8)


# --------------------------------------------------------------- the secant search
def _secant_search(line: BearingLine, speeds: list, guide: Optional[BearingLine], bar) -> tuple:
    """Scan (on the guide when there is one), then the secant refinement (module doc)."""
    scan = guide if guide is not None else line
    bracket, first = None, True
    for k, speed in enumerate(speeds):
        value = scan.f(speed)
        bar.update(1)
        if value <= 0:
            bracket = (speeds[k - 1], speed) if k else None
            break
        first = False
    lowest = _lowest(line, guide, speeds[0])
    if guide is not None and lowest > 0 and first:
        # unstable at the low end on the guide only: search without it
        return _secant_search(line, speeds, None, bar)
    if lowest <= 0:
        return "unstable", math.nan
    bar.set_postfix_str("refining")
    if guide is None:
        return ("stable", math.nan) if bracket is None else ("onset", _refine(line, *bracket))
    onset = None
    if bracket is not None:
        onset = _guided(line, guide, *bracket, speeds[0], speeds[-1])
    unstable = _confirm(line, guide, speeds, onset if onset is not None else math.inf)
    if unstable is not None:                 # the fine grid disagrees with the coarse sign
        below = max(s for s in speeds if s < unstable)
        if line.f(below) <= 0:               # and below it too: the plain fine scan
            return _secant_search(line, speeds, None, bar)
        return "onset", _refine(line, below, unstable)
    if onset is None and bracket is not None:    # the guided refinement did not converge
        return _secant_search(line, speeds, None, bar)
    if onset is None:
        worst = min(guide.rows, key=lambda r: r["mass_margin"])["speed_rpm"]
        line.f(worst)                        # the smallest margin, on the fine grid
        return "stable", math.nan
    above = [s for s in speeds if s > onset]
    if above and _stable_above(line, above[0]):  # the fine scan would not bracket it
        return _secant_search(line, speeds, None, bar)
    return "onset", onset


def _lowest(line: BearingLine, guide: Optional[BearingLine], speed: float) -> float:
    """f at the lowest scan speed on the fine grid: a local threshold from the guide's
    crossing there when the guide's mass margin and the fine local one are both at least
    :data:`COARSE_MARGIN` (stable on the fine grid by the guide's own test), else the full
    threshold (which also decides "unstable at the lower end")."""
    if guide is not None:
        coarse = guide.full(speed)
        if math.isfinite(coarse["root"]) and coarse["mass_margin"] >= COARSE_MARGIN:
            row = line.local(speed, near=coarse)
            if row["threshold"] == "local" and row["mass_margin"] >= COARSE_MARGIN:
                return row["f"]
    return line.f(speed)


def _stable_above(line: BearingLine, speed: float) -> bool:
    """True when the fine grid is stable at ``speed`` (the first scan speed above the
    guided onset).  A local threshold (the onset's branch, followed from the nearest
    crossing) that is unstable settles it: the full threshold is the smallest crossing mass,
    so it is no larger (:mod:`gfbopt.linear.threshold`); otherwise the full threshold
    decides."""
    if line.local(speed)["f"] <= 0:
        return False
    return line.f(speed) > 0


def _confirm(line: BearingLine, guide: BearingLine, speeds: list, upto: float) -> Optional[float]:
    """The first scan speed below ``upto`` where the fine grid is unstable, among those whose
    coarse mass margin is below :data:`COARSE_MARGIN` (recomputed on the fine grid); None
    when every scan speed below ``upto`` is stable on the fine grid by that test."""
    for speed in speeds[1:]:
        if speed >= upto:
            break
        coarse = guide.full(speed)
        if coarse["mass_margin"] >= COARSE_MARGIN:
            continue
        if line.f(speed) <= 0:
            return speed
    return None


def _guided(line: BearingLine, guide: BearingLine, low: float, high: float, lowest: float,
            highest: float) -> Optional[float]:
    """The fine onset from the coarse one: the coarse secant in [low, high], then the fine
    secant from there with a first Newton step on the coarse slope; None if it fails."""
    coarse = secant_root(line_function(guide), low, high, COARSE_TOLERANCE)
    if coarse is None:
        return None
    u0, slope = coarse
    row = line.local(math.exp(u0))
    if not (math.isfinite(row["g"]) and slope < 0):
        return None
    u1 = u0 - row["g"] / slope
    found = secant_root(line_function(line), lowest, highest, SECANT_TOLERANCE,
                        start=[(u0, row["g"])],
                        first=u1, error_tol=ERROR_TOLERANCE)
    return _confirmed(line, found)


def _refine(line: BearingLine, low: float, high: float) -> float:
    """The onset in the fine bracket [low, high] (f(low) > 0 ≥ f(high), full thresholds)."""
    found = _confirmed(line, secant_root(line_function(line), low, high, SECANT_TOLERANCE,
                                         error_tol=ERROR_TOLERANCE))
    if found is not None:
        return found
    # another branch took over, or the secant did not converge: the reference refinement
    stable = max(r["speed_rpm"] for r in line.rows if r["f"] > 0 and r["threshold"] == "full"
                 and r["speed_rpm"] < high)
    unstable = min(r["speed_rpm"] for r in line.rows if r["f"] <= 0 and r["speed_rpm"] > stable
                   and r["threshold"] == "full")
    return brentq(line.f, stable, unstable, xtol=SECANT_TOLERANCE * stable,
                  rtol=4 * 2.2e-16)


def _confirmed(line: BearingLine, found) -> Optional[float]:
    """The converged speed if the full threshold there puts the root within
    :data:`CONFIRM_TOLERANCE` of it (one Newton step on g with the secant's slope), else None
    (another branch took over, or the secant failed).  The check bounds the error of the
    speed itself, whatever stopped the secant."""
    if found is None:
        return None
    u, slope = found
    speed = math.exp(u)
    full = line.full(speed)["g"]
    if not (math.isfinite(full) and math.isfinite(slope) and slope != 0):
        return None
    return speed if abs(full / slope) <= CONFIRM_TOLERANCE else None


# --------------------------------------------------------------------- the result
#: scan-row keys kept for the search only
_INTERNAL = ("f", "g", "root")


def _rows(line: Optional[BearingLine]) -> list:
    if line is None:
        return []
    return [{k: v for k, v in r.items() if k not in _INTERNAL}
            for r in sorted(line.rows, key=lambda r: r["speed_rpm"])]


def _result(line: BearingLine, guide: Optional[BearingLine], kind: str, onset: float,
            method: str, t0: float, note: str = "", margin_upto: float = math.inf,
            **common) -> OnsetResult:
    """The result; the smallest margin is taken over the rows up to ``margin_upto`` (the
    first scan speed above the onset, where the scan of every method stops): the secant
    searches also evaluate speeds beyond it (the coarse onset, checks), whose margins would
    make the smallest margin depend on the method."""
    rows = _rows(line)
    worst = min((r for r in rows if r["speed_rpm"] <= margin_upto * (1 + 1e-12)),
                key=lambda r: r["mass_margin"], default=None) or min(
        rows, key=lambda r: r["mass_margin"])
    gamma = frequency = math.nan
    if kind == "onset":
        gamma = onset_whirl_ratio(rows, onset, SAME_BRANCH)
        frequency = whirl_frequency_hz(gamma, rpm_to_rad_per_s(onset))
    notes = sorted({r["message"] for r in rows + _rows(guide) if r["message"]})
    notes += [note] if note else []
    return OnsetResult(onset_speed_rpm=onset, whirl_frequency_hz=frequency, whirl_ratio=gamma,
                       stable_over_range=kind == "stable",
                       unstable_at_lower_end=kind == "unstable",
                       smallest_margin=worst["mass_margin"],
                       smallest_margin_speed_rpm=worst["speed_rpm"], scan=rows,
                       evaluations=len(rows), message="", notes="; ".join(notes),
                       wall_time_s=time.perf_counter() - t0, method=method,
                       coarse_grid=str(guide.case.grid) if guide is not None else "",
                       coarse_scan=_rows(guide), **common)
