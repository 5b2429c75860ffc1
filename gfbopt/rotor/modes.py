"""Mode shapes of the rotor and their labels: forward/backward, cylindrical/conical/mixed for
the rigid-body modes, bending 1, 2, … for the modes whose shaft bends.

A mode's shape is its complex amplitude q̂ = (x, y, ψx, ψy) in real coordinates, the motion
being Re(q̂ e^{iΩt}) with Ω > 0.  At an axial station z the axis moves by (X, Y) = (x + zψx,
y + zψy): an ellipse, the sum of a forward circle of radius r_f = |X + iY|/2 (turning with the
shaft, x → y) and a backward one of radius r_b = |X − iY|/2.

Labels (:func:`label`):

* **forward / backward**: the larger of Σ r_f² and Σ r_b² over the two bearings;
* **cylindrical / conical / mixed**: from the dominant whirl component p(z) = p_c + z p_ψ
  (p = X ± iY), by the phase between the two bearings, ρ = p(z_B)/p(z_A): in phase
  (|arg ρ| ≤ 60°, the axis translates, its node outside the span) is cylindrical, in
  antiphase (|arg ρ| ≥ 120°, the axis rocks about a node between the bearings) is conical,
  anything between is mixed.  A symmetric rotor's modes are pure (arg ρ = 0 or 180°);
* **bending n** (a structure with a flexible shaft, :mod:`gfbopt.rotor.structure`): the
  dominant component p(z_j) read at stations z_j along the shaft (the structure's
  ``shape_positions`` or its ``nodes`` when it states them, else :data:`SHAPE_STATIONS` evenly between the
  bearings, bearings included) is fitted by the best straight line a + b z (least squares,
  the rigid motion); when the share of Σ|p|² that the line leaves unexplained exceeds
  :data:`BENDING_SHARE`, the shaft's deflection is not a straight line and the mode is
  "forward bending n" / "backward bending n", n the number of nodes of that deflection from
  the line (sign changes along the shaft, of its real part in the phase of its largest
  value) less one — a beam's n-th bending mode, n = 1, 2, … in order of frequency (a
  half-sine has two nodes from its best line, a free–free first mode two).  A rigid
  body never bends (two stations lie on a line).  :func:`mode_label` makes every label.

Crossings along speed (:func:`crossing_tracks`, :func:`continuing`: the tracks of
:mod:`gfbopt.rotor.mode_search`, one per mode): matched from speed to speed by the optimal
assignment on (1 − MAC of :func:`shape_vector`) + :data:`WHIRL_WEIGHT` |Δγ|/γ +
:data:`SCALE_WEIGHT` |ln μ_c − ln μ_pred| (μ_pred extrapolated in ln N), never by label.

The shape reported is the amplitude and phase at each bearing (forward/backward radii
normalised so that the largest radius is 1, phase of the dominant component relative to
bearing A's), the shape class (key ``shape_class``: cylindrical, conical, mixed or bending;
not ``kind``, which in the outputs says why a speed was skipped) and the node.

Node (one definition): ``node_position_m`` is where the dominant whirl |p(z)| of the mode is
least along the rotor's axis as the structure moves it.  A shaft's is read from its shape
along the shaft (:func:`shaft_node`: always on the shaft, from its first end; before, the
straight line through the two bearings, which put a bending mode's node 2.45 m from a 0.4 m
shaft); the rigid body's axis is a straight line, least at −Re(p_c p̄_ψ)/|p_ψ|² from the
centre of gravity (:func:`rigid_node`), which may lie off the rotor: the rigid rotor file
gives the rotor no length, so ``node_location`` says "between the bearings" or "outside the
bearings (it may be off the rotor)", a shaft's "on the shaft", and a translating axis (no
node, p_ψ = 0) has nan with "none (the axis translates)".  ``node_relative_whirl`` is |p| there
over its largest at the stations read (the bearings; a shaft's shape stations): 0 at a true
node, near 1 where the least whirl is no node (a shaft's cylindrical mode, least at an end).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import linear_sum_assignment

from .rigid import station_matrix
from .structure import is_rigid

#: |arg ρ| up to this is cylindrical, from 180° minus this is conical [deg]
PHASE_LIMIT_DEG = 60.0
#: a mode bends when more than this share of Σ|p(z_j)|² is off the best straight line [-]
BENDING_SHARE = 0.25
#: stations between the bearings where a shape is read when the structure states none
SHAPE_STATIONS = 21
#: deflection values below this fraction of the largest are not counted as a sign [-]
NODE_FLOOR = 1e-3
#: ``node_location`` of a node (module docstring, "Node")
ON_SHAFT = "on the shaft"
BETWEEN = "between the bearings"
OUTSIDE = "outside the bearings (it may be off the rotor)"
NO_NODE = "none (the axis translates)"


def ellipse_radii(x_hat, y_hat) -> tuple:
    """(forward radius, backward radius, major semi-axis) of the orbit x = Re(X̂ e^{iϑ}),
    y = Re(Ŷ e^{iϑ}) (complex amplitudes, arrays or scalars): |X̂ + iŶ|/2, |X̂ − iŶ|/2 and
    their sum (the module docstring's forward and backward circles)."""
    forward = np.abs(x_hat + 1j * y_hat) / 2
    backward = np.abs(x_hat - 1j * y_hat) / 2
    return forward, backward, forward + backward


def mode_label(direction: str, shape_class: str, order: int = 0) -> str:
    """The one label of a mode: "forward conical", "backward bending 2", … (``order``: the
    bending mode's number, module docstring)."""
    return (f"{direction} {shape_class} {order}" if shape_class == "bending"
            else f"{direction} {shape_class}")


def family(label: str) -> str:
    """"bending" for a bending mode's label, else "rigid body" (cylindrical, conical,
    mixed)."""
    return "bending" if " bending" in label else "rigid body"


def shape_stations(structure, positions) -> np.ndarray:
    """Where a flexible structure's shape is read (module docstring) [m]."""
    stated = tuple(getattr(structure, "shape_positions", ()) or ()) or tuple(
        getattr(structure, "nodes", ()) or ())
    if stated:
        return np.array(sorted(set(float(z) for z in stated) | set(positions)))
    low, high = min(positions), max(positions)
    return np.linspace(low, high, SHAPE_STATIONS)


def bending(structure, q: np.ndarray, positions, k: int) -> tuple[float, int]:
    """(share of Σ|p|² off the best line, bending number) of component k (0: forward X + iY,
    1: backward X − iY) along the shaft (module docstring)."""
    z = shape_stations(structure, positions)
    xy = np.array([structure.station(zj) @ q for zj in z])            # (m, 2)
    p = xy[:, 0] + (1j if k == 0 else -1j) * xy[:, 1]
    basis = np.column_stack([np.ones_like(z), z - z.mean()])
    coef = np.linalg.lstsq(basis, p, rcond=None)[0]
    resid = p - basis @ coef
    total = float(np.vdot(p, p).real)
    share = float(np.vdot(resid, resid).real) / total if total > 0 else 0.0
    ref = resid[int(np.argmax(np.abs(resid)))]
    real = (resid * np.conj(ref)).real / max(abs(ref), 1e-300)
    signs = np.sign(real[np.abs(real) > NODE_FLOOR * np.abs(real).max()]) if total else []
    changes = int(np.count_nonzero(np.diff(signs))) if len(signs) else 0
    return share, max(1, changes - 1)


def whirl_components(q: np.ndarray, position: float, structure=None
                     ) -> tuple[complex, complex]:
    """(X + iY, X − iY) at axial position z [m] of the amplitude q̂ (twice the forward and
    backward circles' complex radii); ``structure``: the rotor's (None: the rigid body)."""
    if structure is None or is_rigid(structure):
        x = q[0] + position * q[2]
        y = q[1] + position * q[3]
    else:
        x, y = structure.station(position) @ q
    return x + 1j * y, x - 1j * y


def shape(q: np.ndarray, positions, names, structure=None) -> dict:
    """Label and shape of the rotor amplitude ``q`` (module docstring); ``structure``: the
    rotor's :class:`~gfbopt.rotor.structure.Structure` (None: the rigid body's q)."""
    q = np.asarray(q, dtype=complex)
    rigid = structure is None or is_rigid(structure)
    comps = [whirl_components(q, z, structure) for z in positions]
    forward = sum(abs(c[0]) ** 2 for c in comps)
    backward = sum(abs(c[1]) ** 2 for c in comps)
    direction = "forward" if forward >= backward else "backward"
    k = 0 if direction == "forward" else 1
    pa, pb = comps[0][k], comps[1][k]
    if abs(pa) < 1e-300 or abs(pb) < 1e-300:
        phase = 180.0 if abs(pa) + abs(pb) == 0 else 90.0
    else:
        phase = math.degrees(np.angle(pb / pa))
    form = ("cylindrical" if abs(phase) <= PHASE_LIMIT_DEG else
            "conical" if abs(phase) >= 180.0 - PHASE_LIMIT_DEG else "mixed")
    share, order = (0.0, 0) if rigid else bending(structure, q, positions, k)
    if share > BENDING_SHARE:
        form = "bending"
    else:
        order = 0
    node = rigid_node(q, k, positions) if rigid else shaft_node(structure, q, positions, k)
    scale = max(max(abs(c[0]), abs(c[1])) for c in comps) / 2 or 1.0
    ref = np.angle(pa) if abs(pa) > 0 else 0.0
    at = {}
    for name, (f, b) in zip(names, comps):
        dominant = f if k == 0 else b
        at[name] = {"forward_radius": abs(f) / 2 / scale, "backward_radius": abs(b) / 2 / scale,
                    "phase_deg": _wrap(math.degrees(np.angle(dominant) - ref))}
    out = {"label": mode_label(direction, form, order), "direction": direction,
           "shape_class": form,
           "phase_b_from_a_deg": phase, "node_position_m": node["node_position_m"],
           "node_location": node["node_location"],
           "node_relative_whirl": node["node_relative_whirl"], "at_bearings": at}
    if not rigid:
        out["bending_share"] = share
    return out


def _dominant(xy: np.ndarray, k: int) -> np.ndarray:
    """p = X ± iY (k = 0: forward, 1: backward) of (X, Y) rows."""
    return xy[..., 0] + (1j if k == 0 else -1j) * xy[..., 1]


def rigid_node(q: np.ndarray, k: int, positions) -> dict:
    """The rigid body's node (module docstring, "Node"): p(z) = p_c + z p_ψ of component k
    is least at z = −Re(p_c p̄_ψ)/|p_ψ|² [m from the centre of gravity]."""
    pc = q[0] + (1j if k == 0 else -1j) * q[1]
    pp = q[2] + (1j if k == 0 else -1j) * q[3]
    ends = [abs(pc + z * pp) for z in positions]
    if max(ends) == 0 or abs(pp) * (max(positions) - min(positions)) <= 1e-12 * max(ends):
        return {"node_position_m": math.nan, "node_location": NO_NODE,
                "node_relative_whirl": 1.0}
    z = -float(np.real(pc * np.conj(pp))) / abs(pp) ** 2
    where = BETWEEN if min(positions) <= z <= max(positions) else OUTSIDE
    return {"node_position_m": z, "node_location": where,
            "node_relative_whirl": float(abs(pc + z * pp) / max(ends))}


def shaft_node(structure, q: np.ndarray, positions, k: int) -> dict:
    """A shaft's node (module docstring, "Node"): where |p(z)| of component k is least along
    the shaft, from its shape: the least of the shape stations, refined in the elements on
    either side of it, where p is the elements' cubic displacement interpolation (four
    points fix it; |p|² is least at a root of its derivative) [m from the first end]."""
    z = shape_stations(structure, positions)
    values = np.abs(_dominant(np.array([structure.station(zj) @ q for zj in z]), k))
    top = float(values.max())
    j = int(np.argmin(values))
    best_z, best = float(z[j]), float(values[j])
    for a, b in [(z[i], z[i + 1]) for i in (j - 1, j) if 0 <= i < len(z) - 1]:
        xi = np.linspace(0.0, 1.0, 4)
        p = _dominant(np.array([structure.station(a + x * (b - a)) @ q for x in xi]), k)
        cubic = np.polyfit(xi, p, 3)
        square = np.polymul(cubic, np.conj(cubic)).real
        for r in np.roots(np.polyder(square)):
            if abs(r.imag) <= 1e-9 and 0.0 <= r.real <= 1.0:
                value = float(abs(np.polyval(cubic, r.real)))
                if value < best:
                    best_z, best = float(a + r.real * (b - a)), value
    return {"node_position_m": best_z, "node_location": ON_SHAFT,
            "node_relative_whirl": best / top if top > 0 else 1.0}


def label(q: np.ndarray, positions, structure=None) -> str:
    """'forward cylindrical', 'backward conical', 'forward bending 1', … of the amplitude
    ``q``."""
    return shape(q, positions, ("A", "B"), structure)["label"]


def _wrap(deg: float) -> float:
    w = (deg + 180.0) % 360.0 - 180.0
    return 180.0 if w == -180.0 else w


def shape_vector(q: np.ndarray, rotor) -> np.ndarray:
    """d [m] of a rotor amplitude q̂: (X, Y) at each bearing (rigid body) or at each shape
    station along the shaft (module docstring)."""
    structure, positions = rotor.structure, list(rotor.positions)
    if structure is None or is_rigid(structure):
        return np.concatenate([station_matrix(z) @ q for z in positions])
    return np.concatenate([structure.station(z) @ q
                           for z in shape_stations(structure, positions)])


def mac(a: np.ndarray, b: np.ndarray) -> float:
    """Modal assurance criterion |aᴴb|²/(|a|²|b|²) ∈ [0, 1]."""
    den = np.vdot(a, a).real * np.vdot(b, b).real
    return float(abs(np.vdot(a, b)) ** 2 / den) if den > 0 else 0.0


# ------------ matched-whirl crossings along speed: one track per mode (gfbopt.rotor.mode_search)
#: weight of the relative change of the whirl ratio in the cost [-]
WHIRL_WEIGHT = 2.0
#: weight of |ln μ_c − ln μ_pred| in the cost [-]
SCALE_WEIGHT = 0.5
#: a match costing more than this starts a new track [-]
MAX_COST = 1.5
#: d ln μ_c / d ln N of a track of one speed: the inertia terms grow as N² [-]
PREDICTED_SLOPE = -2.0
#: ln μ_c of a crossing with μ_c = 0 (unstable for every inertia scale) [-]
_LOG_FLOOR = math.log(1e-12)


def _log_mu(c) -> float:
    return math.log(c.inertia_scale) if c.inertia_scale > 0 else _LOG_FLOOR


def _predicted(points: list, speed: float) -> float:
    """ln μ_c at ``speed`` from a track's last (speed, crossing) points (module docstring)."""
    s1, c1 = points[-1]
    if len(points) < 2:
        return _log_mu(c1) + PREDICTED_SLOPE * math.log(speed / s1)
    s0, c0 = points[-2]
    slope = (_log_mu(c1) - _log_mu(c0)) / math.log(s1 / s0)
    return _log_mu(c1) + slope * math.log(speed / s1)


def cost(points: list, c, speed: float, d_last: np.ndarray, d_new: np.ndarray) -> float:
    """The cost of continuing a track (its last (speed, crossing) points, its last shape
    ``d_last``) by crossing ``c`` of shape ``d_new`` at ``speed`` (module docstring)."""
    last = points[-1][1]
    whirl = abs(c.whirl_ratio - last.whirl_ratio) / max(abs(last.whirl_ratio), 1e-12)
    return (1.0 - mac(d_last, d_new) + WHIRL_WEIGHT * whirl
            + SCALE_WEIGHT * abs(_log_mu(c) - _predicted(points, speed)))


def crossing_tracks(line, speeds: list) -> list:
    """The tracks of the crossings of ``line`` at ``speeds`` (those with both bearings
    solved), each a list of (speed, crossing or None) over all ``speeds`` (module
    docstring), in the order they start (then by μ_c)."""
    rotor = line.rotor
    tracks: list = []                       # each: list of (speed, crossing, shape)
    active: list = []
    for speed in speeds:
        found = sorted(line.crossings(speed) or [], key=lambda c: c.inertia_scale)
        shapes = [shape_vector(c.vector, rotor) for c in found]
        matrix = np.array([[cost([(s, c) for s, c, _ in tracks[t]], c, speed,
                                 tracks[t][-1][2], d) for c, d in zip(found, shapes)]
                           for t in active]).reshape(len(active), len(found))
        rows, cols = linear_sum_assignment(matrix) if matrix.size else ((), ())
        new_active, used = [], set()
        for i, j in zip(rows, cols):
            if matrix[i, j] <= MAX_COST:
                tracks[active[i]].append((speed, found[j], shapes[j]))
                new_active.append(active[i])
                used.add(j)
        for j, c in enumerate(found):
            if j not in used:
                tracks.append([(speed, c, shapes[j])])
                new_active.append(len(tracks) - 1)
        active = new_active
    out = []
    for tr in tracks:
        at = {s: c for s, c, _ in tr}
        out.append([(s, at.get(s)) for s in speeds])
    return out


def continuing(line, speed: float, ref):
    """The crossing of ``line`` at ``speed`` that continues the crossing ``ref`` (of another
    grid at the same speed): the least :func:`cost` (None when there is none or it exceeds
    :data:`MAX_COST`)."""
    found = line.crossings(speed) or []
    if ref is None or not found:
        return None
    d_ref = shape_vector(ref.vector, line.rotor)
    costs = [cost([(speed, ref)], c, speed, d_ref, shape_vector(c.vector, line.rotor))
             for c in found]
    k = int(np.argmin(costs))
    return found[k] if costs[k] <= MAX_COST else None
