"""The Campbell diagram's modes tracked over speed by continuity, and named consistently with the
matched-whirl threshold.

Continuation. At each speed after the first, every track's mode is looked for first where it is
predicted: its eigenvalue per second extrapolated linearly from its last two speeds (a Campbell
line is continuous in Hz, not in whirl ratio): :func:`gfbopt.rotor.campbell.system_modes`
follows these guesses to roots of the exact characteristic equation before its own estimates,
so a mode is not lost to another root between speeds.

Assignment. A track continues at the root nearest its guess when that root is near (within
:data:`NEAR`) and nearest no other track's guess — at a veering of two modes (the study rotor's
forward modes near 12,000 rpm) their shapes exchange within one speed step, so the shape cannot
decide there but the continuation can. The other modes at a speed are matched to the remaining
tracks' last modes by the optimal assignment on the cost (1 − MAC) + 4 |s − s_pred|/|s_pred|,
MAC = |d_aᴴ d_b|²/(|d_a|² |d_b|²) the modal assurance criterion of the orbits at the two
bearings d = (X_A, Y_A, X_B, Y_B) [m] (one unit for all four, unlike q = (x, y, ψx, ψy)),
s_pred the track's prediction (per second). A match costing more than :data:`MAX_COST` starts a
new track instead.

Names. Each row keeps its own shape's label (the shape of an asymmetric rotor's mode drifts
between cylindrical, mixed and conical with speed). A track is named by the label where its log
decrement first falls through zero — at the threshold the full system's eigenvector is the
matched-whirl mode's, so the name is the threshold's onset label (a test) — and, for a track
that stays stable, by its label where it is least stable. ``track_zero_rpm`` is that zero's
speed by linear interpolation of the log decrement between the diagram's speeds (the exact
onsets are the threshold's)."""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import linear_sum_assignment

from .rigid import station_matrix

#: a match of a mode to a track costing more than this starts a new track [-]
MAX_COST = 1.5
#: weight of the eigenvalue's distance from the track's prediction against the shape change
#: (1 − MAC) in the cost [-]: continuity of the eigenvalue decides, the shape breaks ties
#: (at a veering the shapes of two modes exchange, their eigenvalues do not jump)
FREQUENCY_WEIGHT = 4.0
#: a track continues at the root nearest its guess when that root is within this of the
#: guess, relative [-]
NEAR = 0.25


def orbit_vector(mode, positions) -> np.ndarray:
    """d = (X_A, Y_A, X_B, Y_B) [m] of a mode's rotor amplitude at the bearings."""
    return np.concatenate([station_matrix(z) @ mode.vector for z in positions])


def mac(a: np.ndarray, b: np.ndarray) -> float:
    """Modal assurance criterion |aᴴb|²/(|a|²|b|²) ∈ [0, 1]."""
    den = np.vdot(a, a).real * np.vdot(b, b).real
    return float(abs(np.vdot(a, b)) ** 2 / den) if den > 0 else 0.0


def predicted(track: list, speed: float, omega: float) -> list:
    """A track's eigenvalue per second at ``speed`` [rpm] (shaft ``omega`` [rad/s]): linear
    extrapolation in speed of its last two, s ω being continuous along a Campbell line; from
    one point, both hypotheses — the same frequency in Hz (a rotor mode) and the same whirl
    ratio (a mode locked to the shaft, e.g. near half-speed whirl)."""
    s1, m1, w1 = track[-1]
    if len(track) < 2:
        return [m1.eigenvalue * w1, m1.eigenvalue * omega]
    s0, m0, w0 = track[-2]
    return [m1.eigenvalue * w1 + (m1.eigenvalue * w1 - m0.eigenvalue * w0) * (
        (speed - s1) / (s1 - s0))]


def cost(track: list, mode, speed: float, omega: float, positions) -> float:
    """(1 − MAC with the track's last mode) + :data:`FREQUENCY_WEIGHT` × the distance of the
    mode's eigenvalue from the track's (nearest) prediction, relative (module docstring)."""
    jump = min(abs(mode.eigenvalue * omega - g) / abs(g)
               for g in predicted(track, speed, omega))
    shape_change = 1.0 - mac(orbit_vector(track[-1][1], positions),
                             orbit_vector(mode, positions))
    return shape_change + FREQUENCY_WEIGHT * jump


def guesses(tracks: list, active: list, speed: float, omega: float) -> list:
    """The starting points (per radian at shaft speed ``omega`` [rad/s]) of the active
    tracks' modes at ``speed`` [rpm]: their predictions (:func:`predicted`), one per track
    (the first), then the other hypotheses of single-point tracks."""
    first = [predicted(tracks[t], speed, omega)[0] / omega for t in active]
    more = [g / omega for t in active for g in predicted(tracks[t], speed, omega)[1:]]
    return first + more


def assign(tracks: list, active: list, speed: float, omega: float, modes: list,
           positions, starts=()) -> list:
    """Append each of ``modes`` to its track (or a new one); the new list of active tracks.
    ``tracks``: lists of (speed, mode, omega); ``starts``: the active tracks' guesses
    (:func:`guesses`).  A track of two points or more whose guess has a root nearest it
    (within :data:`NEAR` of it, and nearest no other track's guess) continues there — the
    continuation; the others
    are matched by the optimal assignment on :func:`cost` (module docstring)."""
    new_active, used = [], set()
    linked = {}
    if len(starts) >= len(active) and modes:
        roots = np.array([m.eigenvalue for m in modes])
        nearest = [int(np.argmin(np.abs(roots - g))) for g in starts[:len(active)]]
        for r, (g, c) in enumerate(zip(starts, nearest)):
            if (len(tracks[active[r]]) > 1 and nearest.count(c) == 1
                    and abs(roots[c] - g) <= NEAR * abs(g)):
                linked[r] = c
    for r, c in linked.items():
        tracks[active[r]].append((speed, modes[c], omega))
        new_active.append(active[r])
        used.add(c)
    rest = [r for r in range(len(active)) if r not in linked]
    free = [c for c in range(len(modes)) if c not in used]
    matrix = np.array([[cost(tracks[active[r]], modes[c], speed, omega, positions)
                        for c in free] for r in rest])
    rows, cols = linear_sum_assignment(matrix) if matrix.size else ((), ())
    for i, j in zip(rows, cols):
        if matrix[i, j] <= MAX_COST:
            tracks[active[rest[i]]].append((speed, modes[free[j]], omega))
            new_active.append(active[rest[i]])
            used.add(free[j])
    for c, m in enumerate(modes):
        if c not in used:
            tracks.append([(speed, m, omega)])
            new_active.append(len(tracks) - 1)
    return new_active


def track_name(rows: list) -> tuple[str, float]:
    """(name, speed of the first zero of the log decrement [rpm] or nan) of one track's rows
    (speed, mode) in speed order (module docstring)."""
    for (s0, m0), (s1, m1) in zip(rows, rows[1:]):
        d0, d1 = m0.log_decrement, m1.log_decrement
        if d0 > 0 >= d1:
            zero = s0 + d0 / (d0 - d1) * (s1 - s0)
            nearest = m0 if abs(zero - s0) <= abs(s1 - zero) else m1
            return nearest.label, zero
    if rows and rows[0][1].log_decrement <= 0:
        return rows[0][1].label, math.nan
    least = min(rows, key=lambda r: r[1].log_decrement)
    return least[1].label, math.nan
