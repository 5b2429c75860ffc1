"""Is the rotor stable below its first threshold crossing?  The probe of the two-bearing
threshold, as :func:`gfbopt.linear.linear_threshold` probes the one-bearing one.

The crossings of :mod:`.matched_whirl` are the only inertia scales μ at which a mode crosses
the imaginary axis, so the number of growing modes is the same for every μ below the smallest
crossing μ_1.  One eigenvalue check at μ_p = μ_1/2 (μ_p = 1, the rotor itself, when nothing
crosses) decides whether rotors below μ_1 are stable.  They usually are; they are not when the
massless journal is itself unstable: with μ → 0 the dynamic stiffness tends to
Σ T_kᵀ Z_k(s) T_k = Tᵀ diag(Z_A, Z_B) T with T = [T_A; T_B] regular (two bearings at different
positions), so the massless rotor's modes are those of each bearing's massless journal — the
one-bearing case (a seam inside the loaded arc can make its half-frequency mode grow).  Then
the rotor whirls at every inertia scale below μ_1: its threshold μ_c is 0 (the one-bearing
M̄c = 0, "unstable for every rotor mass"), reported as a crossing with μ_c = 0.

Eigenvalues.  Each bearing's Krylov space in Schur form (:mod:`.reduced`) is a linear model of
its impedance, Z̄_k(s) = f_k (I + (s − s0_k) T_k)⁻¹ c_k.  With its states u_k (s T_k u_k =
−(I − s0_k T_k) u_k + c_k ξ_k, ξ_k = P_k q the journal motion, P_k the 2 × 4 transformation)
and the rotor's q, v = s q (per radian of shaft rotation),

    s q = v,     s μω² M v = −(μω² G + ω C) v − K q − Σ_k P_kᵀ (p_a R_k²/c_k) f_k u_k,

(K, C the shaft's, zero for the rigid body) is one small dense pencil (2n + Σ m_k states): all its eigenvalues at once.  An eigenvalue is
kept when each bearing's space has converged at it (:meth:`ReducedImpedance.evaluate`: the
model is then the exact impedance there to 1e-11) — or, for an eigenvalue at least
:data:`FAR_LEFT` left of the axis, when each space's residual there is at most
:data:`FAR_RESIDUAL` — otherwise the space is extended and the pencil rebuilt, and when it
whirls in the scanned range (whirl ratio inside it, as the one-bearing probe looks at the eigenvalues near the threshold's whirl).  A test compares these
eigenvalues with the full sparse system's (:class:`gfbopt.rotor.campbell.FullSystem`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..linear.threshold import STABILITY_TOLERANCE
from .structure import is_rigid

#: the inertia scale probed when no mode crosses: the rotor itself [-]
PROBE_SCALE = 1.0
#: the shift of the reduced eigenproblem (a regular point: right half plane, whirl 1/2) [-]
SHIFT = 0.3 + 0.5j
#: passes of (pencil, convergence check at its eigenvalues, extension) before giving up
PASSES = 4
#: eigenvalues with a growth rate below this per radian are not checked (far from the axis:
#: they cannot decide stability) [-]
CHECK_BELOW = -0.5
#: an eigenvalue at least FAR_LEFT left of the axis [per radian] is confirmed when each
#: bearing's Krylov residual there is at most FAR_RESIDUAL (relative) instead of the space's
#: convergence tolerance 1e-11: an impedance error ε moves it by about ε |s| times its
#: condition, far less than FAR_LEFT (measured on the blower rotor at 40–60 krpm: such
#: eigenvalues at Re s ≈ −0.34…−0.46 with residuals 1e-9 moved by 1e-12 over three more
#: passes of extension)
FAR_LEFT = 0.1
FAR_RESIDUAL = 1e-6


@dataclass(frozen=True)
class Probe:
    """The least-stable whirling eigenvalue at the probed inertia scale.

    inertia_scale μ_p [-]; growth_rate per radian (−inf: none in the range) [-];
    whirl_ratio [-]; vector q̂ of the rotor (4,) (only when unstable); unstable: growth above
    :data:`~gfbopt.linear.threshold.STABILITY_TOLERANCE`; checked: every eigenvalue that
    could decide was confirmed on converged impedances."""

    inertia_scale: float
    growth_rate: float
    whirl_ratio: float
    vector: Optional[np.ndarray]
    unstable: bool
    checked: bool


def _pencil(rotor, states, inertia_scale: float) -> tuple[np.ndarray, np.ndarray]:
    """(A, E) of the reduced pencil s E x = A x (module docstring)."""
    structure = rotor.structure
    nq = structure.size
    omega = states.omega
    w2 = inertia_scale * omega**2
    blocks = [st.schur_model() for st in states.states]
    sizes = [b.t.shape[0] for b in blocks]
    n = 2 * nq + sum(sizes)
    a = np.zeros((n, n), dtype=complex)
    e = np.zeros((n, n), dtype=complex)
    q, v = slice(0, nq), slice(nq, 2 * nq)
    e[q, q] = np.eye(nq)
    a[q, v] = np.eye(nq)
    e[v, v] = w2 * structure.mass()
    a[v, v] = -w2 * structure.gyroscopic()
    if not is_rigid(structure):          # the shaft's own K and C ω (per radian, not scaled)
        a[v, q] = -structure.stiffness()
        a[v, v] -= omega * structure.damping()
    start = 2 * nq
    for st, p, blk, m in zip(states.states, rotor.transforms, blocks, sizes):
        rows = slice(start, start + m)
        a[v, rows] = -st.scale * p.T @ blk.f
        a[rows, q] = blk.c @ p
        e[rows, rows] = blk.t
        a[rows, rows] = -(np.eye(m) - blk.shift * blk.t)
        start += m
    return a, e


def reduced_eigen(rotor, states, inertia_scale: float) -> np.ndarray:
    """The finite eigenvalues s [per radian] of the reduced pencil (module docstring)."""
    a, e = _pencil(rotor, states, inertia_scale)
    # shift-invert: the eigenvalues λ of (A − σE)⁻¹E are 1/(s − σ) (the standard problem costs
    # a third of the generalised one); λ ≈ 0 are the pencil's infinite eigenvalues
    lam = np.linalg.eigvals(np.linalg.solve(a - SHIFT * e, e))
    big = np.abs(lam) > 1e-12 * np.abs(lam).max()
    return SHIFT + 1.0 / lam[big]


def reduced_vector(rotor, states, inertia_scale: float, s: complex) -> np.ndarray:
    """The rotor amplitude q̂ (n,) of the reduced pencil's eigenvector at eigenvalue s (the
    right singular vector of A − sE with the least singular value)."""
    a, e = _pencil(rotor, states, inertia_scale)
    return np.linalg.svd(a - s * e)[2][-1].conj()[:rotor.structure.size]


def probe(rotor, states, inertia_scale: float, whirl_range) -> Probe:
    """The least-stable eigenvalue whirling in ``whirl_range`` at ``inertia_scale``
    (module docstring)."""
    low, high = whirl_range
    checked = False
    if any(st.schur_model() is None for st in states.states):
        return Probe(inertia_scale, -math.inf, math.nan, None, False, False)
    for _ in range(PASSES):
        values = reduced_eigen(rotor, states, inertia_scale)
        values = values[(values.imag >= low) & (values.imag <= high)]
        doubtful = [s for s in values[values.real > CHECK_BELOW]
                    if not _settled(states, s)]
        if not doubtful:
            checked = True
            break
        if not any(st.extend_at(s) for s in doubtful for st in states.states):
            break
    if values.size == 0:
        return Probe(inertia_scale, -math.inf, math.nan, None, False, checked)
    best = complex(values[int(np.argmax(values.real))])
    unstable = best.real > STABILITY_TOLERANCE
    vector = reduced_vector(rotor, states, inertia_scale, best) if unstable else None
    return Probe(inertia_scale, best.real, best.imag, vector, unstable, checked)


def _settled(states, s: complex) -> bool:
    """True when eigenvalue s of the reduced pencil is confirmed: each bearing's Krylov space
    has converged at s (:meth:`~gfbopt.rotor.supports.BearingState.converged_at`), or s lies
    at least :data:`FAR_LEFT` left of the axis and each space's relative residual there is at
    most :data:`FAR_RESIDUAL` (module docstring)."""
    if all(st.converged_at(s) for st in states.states):
        return True
    if not s.real <= -FAR_LEFT:
        return False
    for st in states.states:
        model = st.schur_model()
        if model is None or not model.solve(s - model.shift)[1] <= FAR_RESIDUAL:
            return False
    return True


def probe_scale(crossing_scales) -> float:
    """μ_p: half the smallest crossing's μ_c, or :data:`PROBE_SCALE` when none."""
    scales = [s for s in crossing_scales if s > 0]
    return 0.5 * min(scales) if scales else PROBE_SCALE
