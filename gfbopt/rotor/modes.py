"""Mode shapes of the rigid rotor and their labels: forward/backward, cylindrical/conical/mixed.

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
  anything between is mixed.  A symmetric rotor's modes are pure (arg ρ = 0 or 180°).

The shape reported is the amplitude and phase at each bearing (forward/backward radii
normalised so that the largest radius is 1, phase of the dominant component relative to
bearing A's) and the node position (where |p(z)| is least) [m].
"""
from __future__ import annotations

import math

import numpy as np

#: |arg ρ| up to this is cylindrical, from 180° minus this is conical [deg]
PHASE_LIMIT_DEG = 60.0


def whirl_components(q: np.ndarray, position: float) -> tuple[complex, complex]:
    """(X + iY, X − iY) at axial position z [m] of the amplitude q̂ (twice the forward and
    backward circles' complex radii)."""
    x = q[0] + position * q[2]
    y = q[1] + position * q[3]
    return x + 1j * y, x - 1j * y


def shape(q: np.ndarray, positions, names) -> dict:
    """Label and shape of the rotor amplitude ``q`` (module docstring)."""
    q = np.asarray(q, dtype=complex)
    comps = [whirl_components(q, z) for z in positions]
    forward = sum(abs(c[0]) ** 2 for c in comps)
    backward = sum(abs(c[1]) ** 2 for c in comps)
    direction = "forward" if forward >= backward else "backward"
    k = 0 if direction == "forward" else 1
    pa, pb = comps[0][k], comps[1][k]
    if abs(pa) < 1e-300 or abs(pb) < 1e-300:
        phase = 180.0 if abs(pa) + abs(pb) == 0 else 90.0
    else:
        phase = math.degrees(np.angle(pb / pa))
    kind = ("cylindrical" if abs(phase) <= PHASE_LIMIT_DEG else
            "conical" if abs(phase) >= 180.0 - PHASE_LIMIT_DEG else "mixed")
    # p(z) = p_c + z p_ψ (dominant component): least |p| at z = −Re(p_c p̄_ψ)/|p_ψ|²
    pc = q[0] + (1j if k == 0 else -1j) * q[1]
    pp = q[2] + (1j if k == 0 else -1j) * q[3]
    node = (-float(np.real(pc * np.conj(pp))) / abs(pp) ** 2 if abs(pp) > 0 else math.inf)
    scale = max(max(abs(c[0]), abs(c[1])) for c in comps) / 2 or 1.0
    ref = np.angle(pa) if abs(pa) > 0 else 0.0
    at = {}
    for name, (f, b) in zip(names, comps):
        dominant = f if k == 0 else b
        at[name] = {"forward_radius": abs(f) / 2 / scale, "backward_radius": abs(b) / 2 / scale,
                    "phase_deg": _wrap(math.degrees(np.angle(dominant) - ref))}
    return {"label": f"{direction} {kind}", "direction": direction, "kind": kind,
            "phase_b_from_a_deg": phase, "node_position_m": node, "at_bearings": at}


def label(q: np.ndarray, positions) -> str:
    """'forward cylindrical', 'backward conical', … of the amplitude ``q``."""
    return shape(q, positions, ("A", "B"))["label"]


def _wrap(deg: float) -> float:
    w = (deg + 180.0) % 360.0 - 180.0
    return 180.0 if w == -180.0 else w
