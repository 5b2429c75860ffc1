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
bearings d = (X_A, Y_A, X_B, Y_B) [m] (one unit for all four, unlike q = (x, y, ψx, ψy);
read through the structure's stations, S(z_k) q, for any structure),
s_pred the track's prediction (per second). A match costing more than :data:`MAX_COST` starts a
new track instead.

Whirl direction.  A track keeps its whirl direction (forward or backward, the shape's:
:func:`whirl_direction`) at every speed: a root whirling the other way is never its
continuation, nor its nearest root, nor a join of :func:`stitch` (its cost is inf).  Without
this the shape term (1 − MAC ≤ 1) alone could not keep the ways apart: the flexible rotor's
forward conical root at 10,000 rpm (153.1 Hz, log decrement 2.63, 24x8) continued the backward
conical track at 12,632 rpm (161.8 Hz, 1.21) at cost 1.474 ≤ :data:`MAX_COST` (1 − MAC =
0.65 of the elliptical orbits, 4 × 0.206 the eigenvalue's move, mostly its damping), its
forward candidate (248.6 Hz) costing 2.05; now it is dropped (join cost 2.14, stated).

Gaps (:func:`stitch`, after the last speed).  A step of a coarse diagram can change a mode's
damping by more than its frequency: the blower rotor's forward modes on the half-speed line
go from log decrement 3.1 at 4,000 rpm to −0.05 at 13,333 rpm (7 speeds), so the eigenvalue's
jump alone exceeds :data:`MAX_COST` and the mode went on as a new track, leaving a track of
one point with a name of its own.  So every track that ends before the last speed is joined
to a track that starts at the next speed when :func:`join_cost` — :func:`cost` with the jump
of the damped natural frequency alone (the Campbell line is continuous in Hz), the lesser of
the forward prediction from the ending track and the backward one from the starting track —
is at most :data:`MAX_COST`, by the optimal assignment of the ends to the starts at each
speed.  A track still shorter than :data:`MIN_POINTS` (a root found at one speed only that
continues no track) is taken out of the table and stated with its reason
(:attr:`gfbopt.rotor.diagrams.CampbellDiagram.dropped`): no one-point line, no name that
belongs to no mode.

Names (one name per mode, used by every output: the text, JSON, CSV and the figures).  A
mode's name is its shape class (:func:`gfbopt.rotor.modes.label`: "forward conical", …); a
matched-whirl onset's mode keeps the onset's label.  Each Campbell row also keeps its own
shape's class (column ``shape_label``): an asymmetric rotor's mode drifts between
cylindrical, mixed and conical with speed, so a row's shape is not the track's name.
:func:`name_tracks` names the tracks (column ``track_label``):

1. the tracks that lose their damping are matched one to one to the matched-whirl onsets (the
   same event: at the threshold the full system's eigenvector is the matched-whirl mode's) by
   the optimal assignment on |zero − onset|/Δs + |f/f_onset − 1|, Δs the diagram interval
   holding the track's zero, f the track's frequency interpolated at the onset speed; a pair
   is a candidate when the zero is within one interval of the onset and f within
   :data:`SAME_FREQUENCY` of the onset's frequency.  A mode unstable at the lowest speed is
   matched to a track unstable at the diagram's first speed, by frequency alone.  A matched
   track takes the onset's label;
1b. every onset-list mode still unmatched (stable over the range, or no track matched it by
   rule 1) is matched one to one to the unnamed tracks by the optimal assignment on 1 − MAC
   of its shape (the crossing's eigenvector where it is reported, :class:`~gfbopt.rotor.
   mode_search.ModeOnset` ``vector``) and the track's at the diagram speed nearest that
   speed (:func:`gfbopt.rotor.modes.shape_vector`: along the shaft for a shaft); a
   pair is a candidate when that MAC is at least :data:`SAME_SHAPE`.  The track takes the
   mode's label: a bending mode of the onset list and of the diagram are then one name;
2. every other track is named by its shape class where its log decrement first falls
   through zero, else at its first speed when unstable there, else where it is least stable;
3. distinct names: a name already taken — by a matched track, by the label of any mode of
   the onset list (matched or not: it names that mode alone), or by a lower-numbered track —
   gets the suffix " (2)", " (3)", … in the
   order of the track numbers (column ``mode``).

``track_zero_rpm`` is the zero's speed by linear interpolation of the log decrement between
the diagram's speeds (the exact onsets are the threshold's)."""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import linear_sum_assignment

from .mode_search import ONSET, UNSTABLE_LOW
from .modes import mac, shape_vector
from .rigid import station_matrix

#: a match of a mode to a track costing more than this starts a new track [-]
MAX_COST = 1.5
#: weight of the eigenvalue's distance from the track's prediction against the shape change
#: (1 − MAC) in the cost [-]: continuity of the eigenvalue decides, the shape breaks ties
#: (at a veering the shapes of two modes exchange, their eigenvalues do not jump)
FREQUENCY_WEIGHT = 4.0
#: a track of fewer points than this is no line of the diagram: joined to the track it
#: continues (:func:`stitch`) or taken out, stated and counted [-]
MIN_POINTS = 2
#: a track continues at the root nearest its guess when that root is within this of the
#: guess, relative [-]
NEAR = 0.25
#: a track is a matched-whirl onset's mode only when its frequency interpolated to the onset
#: speed is within this of the onset's whirl frequency [-] (two modes crossing zero in one
#: diagram interval are further apart than this, and a Campbell line is smooth in Hz)
SAME_FREQUENCY = 0.05
#: a track and an onset-list mode are one mode (rule 1b) when the MAC of their shapes is at
#: least this [-]
SAME_SHAPE = 0.8
#: the assignment's stand-in for a forbidden pair (a change of whirl direction) [-]
FORBIDDEN = 1e9
#: statuses of a matched-whirl mode that a track losing (or without) damping carries
_UNSTABLE = (ONSET, UNSTABLE_LOW)


def orbit_vector(mode, positions, structure=None) -> np.ndarray:
    """d = (X_A, Y_A, X_B, Y_B) [m] of a mode's rotor amplitude at the bearings (through the
    structure's stations, :mod:`gfbopt.rotor.structure`; None: the rigid body)."""
    if structure is None:
        return np.concatenate([station_matrix(z) @ mode.vector for z in positions])
    return np.concatenate([structure.station(z) @ mode.vector for z in positions])


def whirl_direction(mode, positions, structure=None) -> str:
    """"forward" or "backward": the mode's shape's (:func:`gfbopt.rotor.modes.shape`), else by
    that rule from its orbits at the bearings (Σ|X + iY|² ≥ Σ|X − iY|²: forward)."""
    found = (getattr(mode, "shape", None) or {}).get("direction")
    if found is not None:
        return found
    d = orbit_vector(mode, positions, structure).reshape(-1, 2)
    forward = float(np.sum(np.abs(d[:, 0] + 1j * d[:, 1]) ** 2))
    backward = float(np.sum(np.abs(d[:, 0] - 1j * d[:, 1]) ** 2))
    return "forward" if forward >= backward else "backward"


def _finite(matrix: np.ndarray) -> np.ndarray:
    """``matrix`` with every forbidden pair (inf) at :data:`FORBIDDEN`, for the assignment."""
    return np.where(np.isfinite(matrix), matrix, FORBIDDEN)


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


def cost(track: list, mode, speed: float, omega: float, positions, structure=None,
         frequency_only: bool = False) -> float:
    """(1 − MAC with the track's last mode) + :data:`FREQUENCY_WEIGHT` × the distance of the
    mode's eigenvalue from the track's (nearest) prediction, relative (module docstring);
    ``frequency_only``: the distance of the damped natural frequencies alone (Im s ω), as
    :func:`stitch` measures it.  inf when the mode whirls the other way than the track's
    last mode (:func:`whirl_direction`): a track keeps its whirl direction."""
    if (whirl_direction(mode, positions, structure)
            != whirl_direction(track[-1][1], positions, structure)):
        return math.inf
    if frequency_only:
        jump = min(abs((mode.eigenvalue * omega).imag - g.imag) / abs(g.imag)
                   for g in predicted(track, speed, omega))
    else:
        jump = min(abs(mode.eigenvalue * omega - g) / abs(g)
                   for g in predicted(track, speed, omega))
    shape_change = 1.0 - mac(orbit_vector(track[-1][1], positions, structure),
                             orbit_vector(mode, positions, structure))
    return shape_change + FREQUENCY_WEIGHT * jump


def guesses(tracks: list, active: list, speed: float, omega: float) -> list:
    """The starting points (per radian at shaft speed ``omega`` [rad/s]) of the active
    tracks' modes at ``speed`` [rpm]: their predictions (:func:`predicted`), one per track
    (the first), then the other hypotheses of single-point tracks."""
    first = [predicted(tracks[t], speed, omega)[0] / omega for t in active]
    more = [g / omega for t in active for g in predicted(tracks[t], speed, omega)[1:]]
    return first + more


def assign(tracks: list, active: list, speed: float, omega: float, modes: list,
           positions, starts=(), structure=None) -> list:
    """Append each of ``modes`` to its track (or a new one); the new list of active tracks.
    ``tracks``: lists of (speed, mode, omega); ``starts``: the active tracks' guesses
    (:func:`guesses`).  A track of two points or more whose guess has a root nearest it
    (within :data:`NEAR` of it, and nearest no other track's guess; roots whirling the
    track's way only) continues there — the continuation; the others
    are matched by the optimal assignment on :func:`cost` (module docstring)."""
    new_active, used = [], set()
    linked = {}
    if len(starts) >= len(active) and modes:
        roots = np.array([m.eigenvalue for m in modes])
        ways = [whirl_direction(m, positions, structure) for m in modes]
        nearest = []
        for r, g in enumerate(starts[:len(active)]):     # the nearest root whirling its way
            way = whirl_direction(tracks[active[r]][-1][1], positions, structure)
            gap = np.where([w == way for w in ways], np.abs(roots - g), math.inf)
            nearest.append(int(np.argmin(gap)) if np.isfinite(gap).any() else -1)
        for r, (g, c) in enumerate(zip(starts, nearest)):
            if (c >= 0 and len(tracks[active[r]]) > 1 and nearest.count(c) == 1
                    and abs(roots[c] - g) <= NEAR * abs(g)):
                linked[r] = c
    for r, c in linked.items():
        tracks[active[r]].append((speed, modes[c], omega))
        new_active.append(active[r])
        used.add(c)
    rest = [r for r in range(len(active)) if r not in linked]
    free = [c for c in range(len(modes)) if c not in used]
    matrix = np.array([[cost(tracks[active[r]], modes[c], speed, omega, positions, structure)
                        for c in free] for r in rest])
    rows, cols = linear_sum_assignment(_finite(matrix)) if matrix.size else ((), ())
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


def join_cost(end: list, start: list, positions, structure=None) -> float:
    """The cost of track ``start`` (its first speed the one after ``end``'s last) being the
    continuation of track ``end``: the lesser of :func:`cost` (frequency only) of ``start``'s
    first mode on ``end`` predicted forwards and of ``end``'s last mode on ``start``
    predicted backwards (module docstring, "Gaps")."""
    s1, m1, w1 = start[0]
    s0, m0, w0 = end[-1]
    return min(cost(end, m1, s1, w1, positions, structure, frequency_only=True),
               cost(start[::-1], m0, s0, w0, positions, structure, frequency_only=True))


def stitch(tracks: list, speeds, positions, structure=None) -> tuple[list, list]:
    """(tracks, dropped): the tracks (lists of (speed, mode, omega)) with every track that
    ends at one of ``speeds`` [rpm] (the speeds solved, in order) joined to the track that
    continues it at the next speed — the optimal assignment of the ends to the starts on
    :func:`join_cost`, a pair joined when it costs at most :data:`MAX_COST` — and then every
    track still shorter than :data:`MIN_POINTS` taken out: ``dropped``, (track, the least
    :func:`join_cost` to a kept track ending at the speed before it or starting at the one
    after; inf when there is none, or none whirling its way) (module docstring, "Gaps")."""
    speeds = sorted(set(float(s) for s in speeds))
    out = [list(t) for t in tracks]
    for a, b in zip(speeds, speeds[1:]):
        ends = [i for i, t in enumerate(out) if t and t[-1][0] == a]
        starts = [j for j, t in enumerate(out) if t and t[0][0] == b]
        if not (ends and starts):
            continue
        matrix = np.array([[join_cost(out[i], out[j], positions, structure) for j in starts]
                           for i in ends])
        for r, c in zip(*linear_sum_assignment(_finite(matrix))):
            if matrix[r, c] <= MAX_COST:
                out[ends[r]].extend(out[starts[c]])
                out[starts[c]] = []
    kept = [t for t in out if len(t) >= MIN_POINTS]
    dropped = []
    for t in (t for t in out if 0 < len(t) < MIN_POINTS):
        k = speeds.index(float(t[0][0]))
        before = speeds[k - 1] if k > 0 else None
        after = speeds[k + 1] if k + 1 < len(speeds) else None
        near = [join_cost(u, t, positions, structure) for u in kept if u[-1][0] == before]
        near += [join_cost(t, u, positions, structure) for u in kept if u[0][0] == after]
        dropped.append((t, min(near, default=math.inf)))
    return kept, dropped


def _zero(rows: list):
    """(zero speed [rpm], interval width [rpm], mode nearest the zero) of the first fall of
    the log decrement through zero along one track's rows (speed, mode), or None."""
    for (s0, m0), (s1, m1) in zip(rows, rows[1:]):
        d0, d1 = m0.log_decrement, m1.log_decrement
        if d0 > 0 >= d1:
            zero = s0 + d0 / (d0 - d1) * (s1 - s0)
            return zero, s1 - s0, (m0 if abs(zero - s0) <= abs(s1 - zero) else m1)
    return None


def track_name(rows: list) -> tuple[str, float]:
    """(shape class, speed of the first zero of the log decrement [rpm] or nan) of one
    track's rows (speed, mode) in speed order (module docstring, rule 2)."""
    found = _zero(rows)
    if found is not None:
        return found[2].label, found[0]
    if rows and rows[0][1].log_decrement <= 0:
        return rows[0][1].label, math.nan
    least = min(rows, key=lambda r: r[1].log_decrement)
    return least[1].label, math.nan


def _match_cost(rows: list, onset, first_speed: float) -> float:
    """The cost of naming a track (rows) by a matched-whirl ``onset`` (module docstring,
    rule 1); inf when the pair is no candidate."""
    f_onset = onset.whirl_frequency_hz
    if not (rows and math.isfinite(f_onset) and f_onset > 0) or onset.status not in _UNSTABLE:
        return math.inf
    if onset.status == UNSTABLE_LOW:
        if rows[0][0] != first_speed or rows[0][1].log_decrement > 0:
            return math.inf
        gap = abs(rows[0][1].whirl_frequency_hz / f_onset - 1.0)
        return gap if gap <= SAME_FREQUENCY else math.inf
    found = _zero(rows)
    if found is None:
        return math.inf
    zero, width, _ = found
    f = float(np.interp(onset.onset_speed_rpm, [s for s, _ in rows],
                        [m.whirl_frequency_hz for _, m in rows]))
    gap, far = abs(f / f_onset - 1.0), abs(zero - onset.onset_speed_rpm) / width
    return far + gap if far <= 1.0 and gap <= SAME_FREQUENCY else math.inf


def _same_shape(tracks: list, names: list, onsets: list, matched: set, rotor) -> None:
    """Rule 1b of the module docstring: ``names`` filled in place."""
    free = [t for t in range(len(tracks)) if names[t] is None and tracks[t]]
    left = [k for k, o in enumerate(onsets) if k not in matched
            and getattr(o, "vector", None) is not None
            and math.isfinite(getattr(o, "at_speed_rpm", math.nan))]
    if not (free and left and rotor is not None):
        return
    cost = np.ones((len(free), len(left)))
    for i, t in enumerate(free):
        for j, k in enumerate(left):
            speed = onsets[k].at_speed_rpm
            _, mode = min(tracks[t], key=lambda r: abs(r[0] - speed))
            cost[i, j] = 1.0 - mac(shape_vector(onsets[k].vector, rotor),
                                         shape_vector(mode.vector, rotor))
    for i, j in zip(*linear_sum_assignment(cost)):
        if cost[i, j] <= 1.0 - SAME_SHAPE:
            names[free[i]] = onsets[left[j]].label
            matched.add(left[j])


def name_tracks(tracks: list, onsets=(), rotor=None) -> list:
    """(name, zero-damping speed [rpm] or nan) of each track (rows (speed, mode) in speed
    order), no two names alike (module docstring); ``onsets``: the matched-whirl onsets
    (:class:`~gfbopt.rotor.mode_search.ModeOnset`); ``rotor``: the rotor case whose
    structure reads the shapes (rule 1b; None: no rule 1b)."""
    base = [track_name(rows) for rows in tracks]
    names: list = [None] * len(tracks)
    onsets = list(onsets)
    first = min((rows[0][0] for rows in tracks if rows), default=math.nan)
    matched: set = set()
    if tracks and onsets:
        cost = np.array([[_match_cost(rows, o, first) for o in onsets] for rows in tracks])
        for t, k in zip(*linear_sum_assignment(np.where(np.isfinite(cost), cost, 1e9))):
            if math.isfinite(cost[t, k]):
                names[t] = onsets[k].label
                matched.add(int(k))
        _same_shape(tracks, names, onsets, matched, rotor)
    # every onset-list mode's name is its own: a track of another mode does not take it
    taken = {n for n in names if n} | {o.label for o in onsets}
    for t, (label, _) in enumerate(base):
        if names[t] is None:
            name, k = label, 1
            while name in taken:
                k += 1
                name = f"{label} ({k})"
            names[t] = name
            taken.add(name)
    return [(n, zero) for n, (_, zero) in zip(names, base)]


def names_at_speed(items: list, onsets=(), rotor=None) -> list:
    """The onset-list name of each of ``items`` (one speed's eigenmodes or threshold
    crossings: a ``vector`` each) at that speed (``gfbopt rotor --speed-rpm``): the mode of
    ``onsets`` of the same shape (MAC ≥ :data:`SAME_SHAPE`, one to one by the optimal
    assignment, as rule 1b names a Campbell track); None where no onset-list mode has that
    shape there (the item is then known by its shape class alone, never by another mode's
    name)."""
    onsets = [o for o in onsets if getattr(o, "vector", None) is not None]
    names: list = [None] * len(items)
    if items and onsets and rotor is not None:
        cost = np.array([[1.0 - mac(shape_vector(o.vector, rotor),
                                    shape_vector(item.vector, rotor)) for o in onsets]
                         for item in items])
        for i, k in zip(*linear_sum_assignment(cost)):
            if cost[i, k] <= 1.0 - SAME_SHAPE:
                names[i] = onsets[k].label
    return names
