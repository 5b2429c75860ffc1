"""Each mode's onset along the speed line, from the threshold crossings at the scan speeds
(:mod:`gfbopt.rotor.system` states the search; this module is its mode-by-mode part).

A ``line`` is a :class:`gfbopt.rotor.system.SpeedLine` (crossings per speed, cached);
``rows`` are one mode's (speed, crossing or None) at the scan speeds (None: the mode has no
crossing there, stable for every inertia scale): one track (below).

Tracks: one identity per mode (:func:`gfbopt.rotor.modes.crossing_tracks`: the crossings
matched from speed to speed by the MAC of their shapes, the whirl ratio and the trend of
ln μ_c, never by label — an asymmetric rotor's mode drifts between mixed, conical and
cylindrical along speed).  Each track's onset is :func:`mode_onset` on its own rows (on a
fine grid, :func:`guided_onset` on the coarse track, the fine crossing continuing each coarse
row by the same cost, :func:`gfbopt.rotor.modes.continuing`); inside the bracket the
refinement follows the label of the bracket's unstable crossing
(:meth:`~gfbopt.rotor.system.SpeedLine.follow`).

Names (:func:`named`; one per mode, used in the text, JSON, CSV and figures): a track is named
once, by its shape class where it is reported — at its onset; at the lowest speed when
unstable there; where its μ_c is least when stable over the range — and a name already taken
by a mode listed before it (onsets first, lowest first) gets " (2)", " (3)", ….

Whirl: a mode's ``whirl_frequency_hz`` is its own at its onset (μ_c = 1 there: the threshold
problem is the rotor itself).  A mode stable over the range has none in the range (null); the
frequency at which a rotor μ_c times heavier would whirl in it, at its least μ_c, is kept as
``threshold_whirl_frequency_hz`` (a shaft's bending mode: μ_c of hundreds, near half the
running speed; its own frequency is the Campbell diagram's).

Coarse guide (:func:`guided_onset`, fine grids only).  The scan runs on a coarse grid; the fine
grid is solved where the answer needs it:

* at every scan speed below the mode's coarse bracket whose coarse inertia margin μ_c − 1 is
  below :data:`COARSE_MARGIN` (and at the lowest speed, which decides "unstable at the lowest
  speed"): a fine sign change there is the bracket instead;
* at the bracket's unstable end unless its coarse margin is below −:data:`COARSE_MARGIN` (it
  must be unstable on the fine grid too, else the scan goes on from there); each check above
  the lowest speed by the local crossing from the coarse one when it is unstable there
  (:func:`_fine_row`), else by every fine crossing;
* inside the bracket, the secant refinement on the fine grid starts from the coarse onset
  with the coarse slope (2–3 fine speeds).

Assumption (the risk): the fine and coarse μ_c differ by less than :data:`COARSE_MARGIN`
relative wherever the check is skipped.  Measured on the study rotor: ≤ 3.1 % between 36 × 10
and 144 × 36 (μ_c at the scan speeds; benchmarks/bench_rotor.py records it).  When a fine
evaluation contradicts the coarse bracket, the mode is searched on the fine grid alone.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Optional

import numpy as np
from scipy.optimize import brentq

from ..progress import progress
from .modes import continuing, crossing_tracks
from .running import CLOSURE, RUNAWAY
from .speed_line import secant_root

#: the secant refinement stops when the next secant step from its latest point would be at
#: most this on ln N [-]: that step estimates the latest point's error (superlinear
#: convergence of a nearly linear g), which is returned
SECANT_TOLERANCE = 1e-6
#: secant steps before the refinement falls back to Brent's method
SECANT_STEPS = 12
#: a coarse inertia margin |μ_c − 1| below this is checked on the fine grid [-] (module doc)
COARSE_MARGIN = 0.15

#: a secant step of at most this from the latest speed, in ln N, starts the mode's crossing
#: from the whirl ratio extrapolated through the two latest (:func:`_predicted`) [-]
PREDICT_DISTANCE = 1e-4

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

    label ('forward conical', …; one per mode, module docstring); onset_speed_rpm [rpm]
    (nan: none in the range, see status); whirl_ratio, whirl_frequency_hz [Hz] at the onset
    (the mode's own: μ_c = 1 there; nan when stable over the range, see
    threshold_whirl_frequency_hz); shape at the onset
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
    #: a mode stable over the range: the whirl frequency of the threshold at its least μ_c
    #: (a rotor μ_c times heavier whirling in it), its own being none in the range [Hz]
    threshold_whirl_frequency_hz: float = math.nan
    #: where the shape was taken [rpm] and the rotor amplitude q̂ there (the crossing's
    #: eigenvector): what a Campbell track is compared with (:mod:`.tracking`); not output
    at_speed_rpm: float = field(default=math.nan, compare=False)
    vector: Optional[np.ndarray] = field(default=None, repr=False, compare=False)

    def to_dict(self) -> dict:
        return {"label": self.label, "onset_speed_rpm": self.onset_speed_rpm,
                "whirl_ratio": self.whirl_ratio,
                "whirl_frequency_hz": self.whirl_frequency_hz, "onset_status": self.status,
                "smallest_inertia_margin": self.smallest_inertia_margin, "shape": self.shape,
                "note": self.note,
                "threshold_whirl_frequency_hz": self.threshold_whirl_frequency_hz}


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


def _where(onset: ModeOnset, speed: float, crossing) -> ModeOnset:
    """``onset`` with the speed [rpm] and the eigenvector of the crossing its shape is of."""
    return replace(onset, at_speed_rpm=float(speed), vector=getattr(crossing, "vector", None))


def mode_onset(line, speeds: list, label: str, tol: float, method: str = "secant",
               rows: Optional[list] = None) -> ModeOnset:
    """One mode's onset on the scanned ``speeds`` (those with both bearings solved) of one
    grid: the first interval where μ_c falls through 1, refined by the secant (or, with
    method "scan", Brent's method to the relative tolerance ``tol``).  ``rows``: the mode's
    (speed, crossing or None) when given (one track, module docstring), else the
    crossings of ``label``; ``label`` is what the refinement follows inside the bracket."""
    rows = rows if rows is not None else mode_rows(line, speeds, label)
    margin = _margin(rows)
    previous = None
    for s, c in rows:
        if _stable(c):
            previous = (s, c)
            continue
        if previous is None:
            return _where(ModeOnset(label, math.nan, c.whirl_ratio, c.whirl_frequency_hz,
                                    c.shape, UNSTABLE_LOW, margin, c.note), s, c)
        return _refined(line, label, previous, (s, c), tol, method, margin)
    s, best = min(((s, c) for s, c in rows if c is not None),
                  key=lambda sc: sc[1].inertia_scale)
    return _where(ModeOnset(label, math.nan, best.whirl_ratio, best.whirl_frequency_hz,
                            best.shape, STABLE, margin), s, best)


def _refined(line, label, stable, unstable, tol, method, margin, seed=None) -> ModeOnset:
    whirl = unstable[1].whirl_ratio
    if stable[1] is None and line.margin(stable[0], label, whirl) <= 0:
        # No crossing of this class at the stable end, and the mode it continues (another
        # class, :meth:`SpeedLine.follow`) is unstable there: no bracket of this mode's onset.
        c = unstable[1]
        return _where(ModeOnset(label, math.nan, c.whirl_ratio, c.whirl_frequency_hz, c.shape,
                                APPEARS_UNSTABLE, margin,
                                f"its shape first appears between {stable[0]:,.0f} and "
                                f"{unstable[0]:,.0f} rpm, already unstable (μ_c = "
                                f"{c.inertia_scale:.3g}): it continues a mode of another "
                                "shape"), unstable[0], c)
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
    return _where(ModeOnset(label, root, at.whirl_ratio, at.whirl_frequency_hz, at.shape,
                            ONSET, margin, at.note), root, at)


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
    seen = [(math.exp(p1[0]), near)] if near is not None else []

    def g(speed: float, full: bool = False) -> float:
        start = _predicted(seen, speed) if hasattr(line, "follow_from") else None
        c = _follow(line, speed, label, state["whirl"], start or state["near"])
        if c is not None:
            state["whirl"], state["near"] = c.whirl_ratio, c
            seen.append((speed, c))
        return _log_scale(c)

    found = secant_root(g, math.exp(a), math.exp(b), SECANT_TOLERANCE, start=[p0, p1],
                        bracketed=True, last=True, steps=SECANT_STEPS)
    if found is None:
        return None, math.nan
    return math.exp(found[0]), found[1]


def _predicted(seen: list, speed: float):
    """The start of the crossing at ``speed`` from the crossings ``seen`` ((speed, crossing),
    in order) when the latest lies within :data:`PREDICT_DISTANCE` of it in ln N: that
    crossing with its whirl ratio extrapolated linearly in ln N through the one before (its
    error of the order of the two distances' product: ~1e-9 at the secant's last step, a
    Newton step on the whirl ratio fewer); None otherwise (the latest crossing starts it)."""
    if not seen or abs(math.log(speed / seen[-1][0])) > PREDICT_DISTANCE:
        return None
    (s1, c1), gamma = seen[-1], seen[-1][1].whirl_ratio
    if len(seen) > 1 and seen[-2][0] != s1:
        s0, c0 = seen[-2]
        gamma += (gamma - c0.whirl_ratio) * math.log(speed / s1) / math.log(s1 / s0)
    return replace(c1, whirl_ratio=gamma)


def _follow(line, speed: float, label: str, whirl: float, near):
    """The mode's crossing at ``speed`` followed from ``near`` (:meth:`gfbopt.rotor.system.
    SpeedLine.follow_from`), or by ``follow`` alone on a line without that search."""
    local = getattr(line, "follow_from", None)
    return local(speed, label, whirl, near) if local else line.follow(speed, label, whirl)


def guided_onset(fine, coarse, speeds: list, label: str, tol: float,
                 rows: Optional[list] = None, fine_row=None) -> Optional[ModeOnset]:
    """One mode's onset on the ``fine`` line with the scan on the ``coarse`` one (module
    docstring); None when the fine grid contradicts the coarse bracket (the caller then
    searches the fine grid alone).  ``rows``: the mode's coarse (speed, crossing or None)
    (one track, module docstring) and ``fine_row(speed, coarse crossing)``: the fine
    crossing continuing it; by default the crossings of ``label`` on both grids.  The
    refinement follows the label of the bracket's unstable crossing."""
    rows = rows if rows is not None else mode_rows(coarse, speeds, label)
    if fine_row is None:
        def fine_row(s, _c):
            return mode_rows(fine, [s], label)[0][1]
    merged = list(rows)                       # fine where checked, else coarse
    for k, (s, c) in enumerate(rows):
        if k == 0 or (c is not None and abs(c.inertia_scale - 1.0) < COARSE_MARGIN):
            merged[k] = (s, fine_row(s, c))
        if not _stable(merged[k][1]):
            break
    margin = _margin(merged)
    first_unstable = next((k for k, (_, c) in enumerate(merged) if not _stable(c)), None)
    if first_unstable is None:
        s, best = min(((s, c) for s, c in merged if c is not None),
                      key=lambda sc: sc[1].inertia_scale)
        return _where(ModeOnset(best.label if label is None else label, math.nan,
                                best.whirl_ratio, best.whirl_frequency_hz, best.shape, STABLE,
                                margin), s, best)
    s, c = merged[first_unstable]
    label = c.label if label is None else label
    if first_unstable == 0:
        return _where(ModeOnset(label, math.nan, c.whirl_ratio, c.whirl_frequency_hz, c.shape,
                                UNSTABLE_LOW, margin, c.note), s, c)
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


def _fine_row(line, speed: float, coarse, lowest: float):
    """The fine crossing continuing the coarse crossing ``coarse`` at ``speed`` (a check of
    :func:`guided_onset`): the local crossing of its branch (:meth:`~gfbopt.rotor.system.
    SpeedLine.follow_from`, from the coarse crossing at the same speed) when it keeps the label
    and is unstable (μ_c ≤ 1: the mode is unstable there whatever the other crossings, as
    the one-bearing search settles its check above the onset), else every crossing at the
    speed and the one :func:`~gfbopt.rotor.modes.continuing` it (always at the ``lowest``
    speed, whose every crossing the search needs)."""
    if speed != lowest and coarse is not None and getattr(line, "local", False):
        found = line.follow_from(speed, coarse.label, coarse.whirl_ratio, coarse)
        if (found is not None and found.label == coarse.label
                and found.inertia_scale <= 1.0 and not line.computed(speed)):
            return found
    return continuing(line, speed, coarse)


def _follow_label(rows: list) -> str:
    """The label the refinement follows: that of the first unstable crossing, else of the
    crossing with the least μ_c."""
    present = [c for _, c in rows if c is not None]
    unstable = [c for c in present if c.inertia_scale <= 1.0]
    return (unstable[0] if unstable else min(present, key=lambda c: c.inertia_scale)).label


def track_onset(line, rows: list, tol: float, method: str) -> ModeOnset:
    """One track's onset on its own rows (fine grid alone)."""
    return mode_onset(line, [s for s, _ in rows], _follow_label(rows), tol, method, rows=rows)


def _order(m: ModeOnset) -> tuple:
    """Onsets first, lowest first (then unstable at the lowest speed, then the others)."""
    return math.isnan(m.onset_speed_rpm), m.onset_speed_rpm, m.status != UNSTABLE_LOW


def named(modes: list) -> list:
    """The modes (each one track's :class:`ModeOnset`) sorted onsets first, lowest first,
    each named once (module docstring), with its own whirl (stable: null, the threshold's
    kept as ``threshold_whirl_frequency_hz``)."""
    modes = sorted(modes, key=_order)
    taken, out = set(), []
    for m in modes:
        base = (m.shape or {}).get("label") or m.label
        name, k = base, 1
        while name in taken:
            k += 1
            name = f"{base} ({k})"
        taken.add(name)
        if m.status == STABLE:
            m = replace(m, whirl_ratio=math.nan, whirl_frequency_hz=math.nan,
                        threshold_whirl_frequency_hz=m.whirl_frequency_hz)
        out.append(replace(m, label=name))
    return out


class _Recording:
    """A speed line that records every crossing its mode searches follow (``seen``)."""

    def __init__(self, line, seen: list):
        self._line, self.seen = line, seen

    def __getattr__(self, name):
        return getattr(self._line, name)

    def follow(self, *args):
        found = self._line.follow(*args)
        self.seen.append(found)
        return found

    def follow_from(self, *args):
        found = self._line.follow_from(*args)
        self.seen.append(found)
        return found


def track_onsets(line, guide, speeds: list, tol: float, method: str,
                 show_progress: bool = False, names: Optional[dict] = None) -> list:
    """Every mode's onset, one per track (module docstring): on ``line`` alone, or guided by
    the coarse ``guide``'s tracks (a mode the fine grid contradicts is searched on the fine
    grid's own tracks; a bearing over capacity on either grid: everything on ``line``
    alone).  The drop-in for the search by label of :mod:`gfbopt.rotor.system`; the
    refinement after the scan is a stage of its own in the progress (one step a mode).
    ``names``: filled with id(crossing) → the name of the mode it belongs to, for every
    crossing of a track and every crossing its refinement followed (the scan's rows)."""
    seen: list = []
    line = _Recording(line, seen)
    guide = _Recording(guide, seen) if guide is not None else None
    fine_tracks: list = []

    def fine_alone(rows_coarse):
        """The fine track continuing a coarse one, searched on the fine grid alone."""
        if not fine_tracks:
            valid = [s for s in speeds if line.crossings(s) is not None]
            fine_tracks.extend(crossing_tracks(line, valid))
        k = next((k for k, (_, c) in enumerate(rows_coarse) if c is not None
                  and c.inertia_scale <= 1.0), None)
        if k is None:
            k = min((k for k, (_, c) in enumerate(rows_coarse) if c is not None),
                    key=lambda k: rows_coarse[k][1].inertia_scale)
        s, ref = rows_coarse[k]
        best = continuing(line, s, ref)
        track = next((tr for tr in fine_tracks if any(c is best for _, c in tr)), None)
        if track is None:
            return None
        seen.extend(c for _, c in track)
        return track_onset(line, track, tol, method)

    def refined(tracks, search) -> list:
        out, own, followed = [], [], []
        with progress(total=len(tracks), desc=f"rotor onset refinement on {line.rotor.grid}",
                      unit="mode", enabled=show_progress) as bar:
            for rows in tracks:
                seen.clear()
                found = search(rows)
                if found is not None:
                    out.append(found)
                    own.append([c for _, c in rows if c is not None])
                    followed.append([c for c in seen if c is not None])
                bar.update(1)
        final = named(out)
        if names is not None:        # a track's own crossings first, then those followed
            by_id = {id(m): n for m, n in zip(sorted(out, key=_order), final)}
            for m, crossings in zip(out, own):
                names.update({id(c): by_id[id(m)].label for c in crossings})
            for m, crossings in zip(out, followed):
                for c in crossings:
                    names.setdefault(id(c), by_id[id(m)].label)
        return final

    below = _below_thermal_limit(guide, speeds) if guide is not None else speeds
    if guide is not None and len(below) >= 2 and \
            all(guide.crossings(s) is not None for s in below) and \
            line.crossings(below[0]) is not None:
        coarse = crossing_tracks(guide, below)
        firsts = [continuing(line, below[0], rows[0][1]) for rows in coarse]
        # a fine crossing at the lowest speed that continues no coarse track: its own mode
        extra = [[(below[0], c)] + [(s, None) for s in below[1:]]
                 for c in line.crossings(below[0]) if not any(c is f for f in firsts)]

        def guided(rows):
            if rows[0][1] is not None and all(c is None for _, c in rows[1:]) and \
                    any(rows is e for e in extra):
                return track_onset(line, rows, tol, method)
            found = guided_onset(line, guide, below, None, tol, rows=rows,
                                 fine_row=lambda s, c: _fine_row(line, s, c, below[0]))
            return found if found is not None else fine_alone(rows)

        out = refined(coarse + extra, guided)
        if len(below) < len(speeds):     # the fine line's own state at the guide's limit:
            line.states(speeds[len(below)])    # its thermal limit is bracketed from there
        if not any(line.states(s).failure and not _thermal(line.states(s).failure)
                   for s in line.speeds_solved):
            return out
    if guide is not None:                 # the fine grid's own scan (on line: done above)
        with progress(total=len(speeds), desc=f"rotor onset scan on {line.rotor.grid}",
                      unit="speed", enabled=show_progress) as bar:
            for speed in speeds:
                line.crossings(speed)
                bar.update(1)
    valid = [s for s in speeds if line.crossings(s) is not None]
    return refined(crossing_tracks(line, valid),
                   lambda rows: track_onset(line, rows, tol, method))


#: a speed's failures that are a bearing's thermal limit, not its load capacity
THERMAL_KINDS = (RUNAWAY, CLOSURE)


def _thermal(failure: dict) -> bool:
    """A speed's failure is a bearing's thermal runaway or closed clearance (rotor.running)."""
    return failure.get("kind") in THERMAL_KINDS


def _below_thermal_limit(guide, speeds: list) -> list:
    """The scan speeds below the first one where the guide's bearings run away thermally or
    their clearance closes (a heated rotor's top speeds): the guided search runs over them, as
    there is no state above to guide; any other failure keeps every speed (today's rule:
    everything on the fine line alone)."""
    for k, s in enumerate(speeds):
        failure = guide.states(s).failure
        if failure:
            return speeds[:k] if _thermal(failure) and all(
                not guide.states(x).failure or _thermal(guide.states(x).failure)
                for x in speeds[k:]) else speeds
    return speeds
