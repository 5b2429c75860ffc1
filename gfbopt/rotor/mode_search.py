"""Each mode's onset along the speed line, from the threshold crossings at the scan speeds
(:mod:`gfbopt.rotor.system` states the search; this module is its mode-by-mode part).

A ``line`` is a :class:`gfbopt.rotor.system.SpeedLine` (crossings per speed, cached);
``rows`` are one mode's (speed, crossing or None) at the scan speeds, the crossing of that
label with the smallest μ_c (None: the mode has no crossing there, stable for every inertia
scale).

Coarse guide (:func:`guided_onset`, fine grids only).  The scan runs on a coarse grid; the fine
grid is solved where the answer needs it:

* at every scan speed below the mode's coarse bracket whose coarse inertia margin μ_c − 1 is
  below :data:`COARSE_MARGIN` (and at the lowest speed, which decides "unstable at the lowest
  speed"): a fine sign change there is the bracket instead;
* at the bracket's unstable end unless its coarse margin is below −:data:`COARSE_MARGIN` (it
  must be unstable on the fine grid too, else the scan goes on from there);
* inside the bracket, the secant refinement on the fine grid starts from the coarse onset
  with the coarse slope (2–3 fine speeds).

Assumption (the risk): the fine and coarse μ_c differ by less than :data:`COARSE_MARGIN`
relative wherever the check is skipped.  Measured on the study rotor: ≤ 3.1 % between 36 × 10
and 144 × 36 (μ_c at the scan speeds; benchmarks/bench_rotor.py records it).  When a fine
evaluation contradicts the coarse bracket, the mode is searched on the fine grid alone.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

from scipy.optimize import brentq

from .speed_line import secant_root

#: the secant refinement stops when the next secant step from its latest point would be at
#: most this on ln N [-]: that step estimates the latest point's error (superlinear
#: convergence of a nearly linear g), which is returned
SECANT_TOLERANCE = 1e-6
#: secant steps before the refinement falls back to Brent's method
SECANT_STEPS = 12
#: a coarse inertia margin |μ_c − 1| below this is checked on the fine grid [-] (module doc)
COARSE_MARGIN = 0.15

#: d ln μ_c / d ln N when the coarse grid gives no slope: the inertia terms grow as N² [-]
NOMINAL_SLOPE = -2.0

ONSET, UNSTABLE_LOW, STABLE = "onset", "unstable at the lowest speed", "stable over the range"
#: a shape class (label) that first appears along the speed line with μ_c ≤ 1 where the other
#: classes are already unstable at the speed below: it continues an unstable mode whose shape
#: changed class (e.g. conical → mixed with structural damping), so it has no onset of its own
APPEARS_UNSTABLE = "unstable where its shape first appears"


@dataclass(frozen=True)
class ModeOnset:
    """The onset of one mode along the speed line.

    label ('forward conical', …); onset_speed_rpm [rpm] (nan: none in the range, see
    status); whirl_ratio, whirl_frequency_hz [Hz] at the onset; shape at the onset
    (:func:`gfbopt.rotor.modes.shape`); status: 'onset', 'unstable at the lowest speed',
    'stable over the range' or 'unstable where its shape first appears'
    (:data:`APPEARS_UNSTABLE`); smallest_inertia_margin: the least μ_c − 1 over the scan [-];
    note: the probe's message when the mode is unstable for every inertia scale there
    (μ_c = 0: the massless journal whirls, :mod:`gfbopt.rotor.probe`)."""

    label: str
    onset_speed_rpm: float
    whirl_ratio: float
    whirl_frequency_hz: float
    shape: dict
    status: str
    smallest_inertia_margin: float
    note: str = ""

    def to_dict(self) -> dict:
        return {"label": self.label, "onset_speed_rpm": self.onset_speed_rpm,
                "whirl_ratio": self.whirl_ratio,
                "whirl_frequency_hz": self.whirl_frequency_hz, "status": self.status,
                "smallest_inertia_margin": self.smallest_inertia_margin, "shape": self.shape,
                "note": self.note}


def mode_rows(line, speeds: list, label: str) -> list:
    """(speed, crossing of ``label`` with the least μ_c, or None) at each of ``speeds``."""
    rows = []
    for s in speeds:
        own = [c for c in line.crossings(s) or [] if c.label == label]
        rows.append((s, min(own, key=lambda c: c.inertia_scale) if own else None))
    return rows


def _stable(c) -> bool:
    return c is None or c.inertia_scale > 1.0


def _margin(rows: list) -> float:
    present = [c.inertia_scale for _, c in rows if c is not None]
    return min(present) - 1.0 if present else math.inf


def mode_onset(line, speeds: list, label: str, tol: float, method: str = "secant",
               rows: Optional[list] = None) -> ModeOnset:
    """One mode's onset on the scanned ``speeds`` (those with both bearings solved) of one
    grid: the first interval where μ_c falls through 1, refined by the secant (or, with
    method "scan", Brent's method to the relative tolerance ``tol``)."""
    rows = rows if rows is not None else mode_rows(line, speeds, label)
    margin = _margin(rows)
    previous = None
    for s, c in rows:
        if _stable(c):
            previous = (s, c)
            continue
        if previous is None:
            return ModeOnset(label, math.nan, c.whirl_ratio, c.whirl_frequency_hz, c.shape,
                             UNSTABLE_LOW, margin, c.note)
        return _refined(line, label, previous, (s, c), tol, method, margin)
    best = min((c for _, c in rows if c is not None), key=lambda c: c.inertia_scale)
    return ModeOnset(label, math.nan, best.whirl_ratio, best.whirl_frequency_hz, best.shape,
                     STABLE, margin)


def _refined(line, label, stable, unstable, tol, method, margin, seed=None) -> ModeOnset:
    whirl = unstable[1].whirl_ratio
    if stable[1] is None and line.margin(stable[0], label, whirl) <= 0:
        # No crossing of this class at the stable end, and the mode it continues (another
        # class, :meth:`SpeedLine.follow`) is unstable there: no bracket of this mode's onset.
        c = unstable[1]
        return ModeOnset(label, math.nan, c.whirl_ratio, c.whirl_frequency_hz, c.shape,
                         APPEARS_UNSTABLE, margin,
                         f"its shape first appears between {stable[0]:,.0f} and "
                         f"{unstable[0]:,.0f} rpm, already unstable (μ_c = "
                         f"{c.inertia_scale:.3g}): it continues a mode of another shape")
    root = None
    if method == "secant":
        a, b = math.log(stable[0]), math.log(unstable[0])
        if seed is None:
            first = (a, _log_scale(stable[1])), (b, _log_scale(unstable[1])), unstable[1]
        else:
            first = seed(line, label, whirl)
        root = _onset_secant(line, label, a, b, *first[:2], whirl, first[2])[0]
    if root is None:
        root = brentq(lambda x: line.margin(x, label, whirl), stable[0], unstable[0],
                      xtol=tol * stable[0], rtol=tol)
    at = line.follow(root, label, whirl)
    return ModeOnset(label, root, at.whirl_ratio, at.whirl_frequency_hz, at.shape, ONSET,
                     margin, at.note)


def _log_scale(crossing) -> float:
    """ln μ_c of a crossing; +inf when the mode has none (stable for every inertia scale),
    −inf when μ_c = 0 (unstable for every inertia scale)."""
    if crossing is None:
        return math.inf
    return math.log(crossing.inertia_scale) if crossing.inertia_scale > 0 else -math.inf


def _onset_secant(line, label: str, a: float, b: float, p0: tuple, p1: tuple,
            whirl: float, near=None) -> tuple:
    """(onset [rpm] or None, last slope dg/d ln N or nan) of mode ``label`` in the bracket
    ln N ∈ (a, b), g = ln μ_c > 0 at a and ≤ 0 at b: the package's one onset secant
    (:func:`gfbopt.rotor.speed_line.secant_root`, bracketed, from the points p0, p1 =
    (ln N, g), bisection whenever a step would leave the bracket or a value is not finite;
    module docstring of :mod:`gfbopt.rotor.system`), stopped when its next step from the
    latest point evaluated would be at most :data:`SECANT_TOLERANCE` and that point
    returned.  None when not converged.  Each step follows the mode from the latest
    crossing (``near`` at first: :func:`_follow`)."""
    state = {"whirl": whirl, "near": near}

    def g(speed: float, full: bool = False) -> float:
        c = _follow(line, speed, label, state["whirl"], state["near"])
        if c is not None:
            state["whirl"], state["near"] = c.whirl_ratio, c
        return _log_scale(c)

    found = secant_root(g, math.exp(a), math.exp(b), SECANT_TOLERANCE, start=[p0, p1],
                        bracketed=True, last=True, steps=SECANT_STEPS)
    if found is None:
        return None, math.nan
    return math.exp(found[0]), found[1]


def _follow(line, speed: float, label: str, whirl: float, near):
    """The mode's crossing at ``speed`` followed from ``near`` (:meth:`gfbopt.rotor.system.
    SpeedLine.follow_from`), or by ``follow`` alone on a line without that search."""
    local = getattr(line, "follow_from", None)
    return local(speed, label, whirl, near) if local else line.follow(speed, label, whirl)


def guided_onset(fine, coarse, speeds: list, label: str, tol: float) -> Optional[ModeOnset]:
    """One mode's onset on the ``fine`` line with the scan on the ``coarse`` one (module
    docstring); None when the fine grid contradicts the coarse bracket (the caller then
    searches the fine grid alone)."""
    rows = mode_rows(coarse, speeds, label)
    merged = list(rows)                       # fine where checked, else coarse
    for k, (s, c) in enumerate(rows):
        if k == 0 or (c is not None and abs(c.inertia_scale - 1.0) < COARSE_MARGIN):
            merged[k] = mode_rows(fine, [s], label)[0]
        if not _stable(merged[k][1]):
            break
    margin = _margin(merged)
    first_unstable = next((k for k, (_, c) in enumerate(merged) if not _stable(c)), None)
    if first_unstable is None:
        best = min((c for _, c in merged if c is not None), key=lambda c: c.inertia_scale)
        return ModeOnset(label, math.nan, best.whirl_ratio, best.whirl_frequency_hz,
                         best.shape, STABLE, margin)
    s, c = merged[first_unstable]
    if first_unstable == 0:
        return ModeOnset(label, math.nan, c.whirl_ratio, c.whirl_frequency_hz, c.shape,
                         UNSTABLE_LOW, margin, c.note)
    stable, unstable = merged[first_unstable - 1], merged[first_unstable]
    coarse_stable, coarse_unstable = rows[first_unstable - 1], rows[first_unstable]

    def seed(line, label, whirl):
        """The fine secant's start: the coarse onset and the coarse slope."""
        a, b = math.log(coarse_stable[0]), math.log(coarse_unstable[0])
        root, slope = _onset_secant(coarse, label, a, b,
                                    (a, _log_scale(coarse_stable[1])),
                                    (b, _log_scale(coarse_unstable[1])), whirl,
                                    coarse_unstable[1])
        x0 = math.log(root) if root is not None else 0.5 * (a + b)
        near = coarse.follow(math.exp(x0), label, whirl) if root is not None else None
        at = _follow(line, math.exp(x0), label, whirl, near)
        if not (math.isfinite(slope) and slope < 0):
            slope = NOMINAL_SLOPE
        g0 = _log_scale(at)
        return (x0 - 1.0, g0 - slope), (x0, g0), at

    try:
        return _refined(fine, label, stable, unstable, tol, "secant", margin, seed=seed)
    except ValueError:                       # Brent's fallback found no fine bracket
        return None
