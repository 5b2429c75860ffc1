"""Helpers of the foil laws (:mod:`gfbopt.physics.foil_laws`): row ↔ node layouts, the rows
held at ambient pressure, and the transient recovery of the row films from Φ = P H.

The transient model (``tm``, :class:`gfbopt.transient.system.TransientModel`) gives
``ambient`` (a boolean mask of the θ rows at ambient pressure: the seam rows of a seamed
film and the ends of further pads), ``compliance_rows`` (S per θ row, bump zones), the axial
weights ``z_weight`` and, for the beam, ``foil_data`` (its compliance map).
"""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

from ..errors import ConvergenceError
from .algebra import is_symbolic


def rows_to_nodes(rows, st):
    """Repeat one value per θ row along the axial nodes (flat node order, numbers/symbols)."""
    if is_symbolic(rows):
        return rows[np.repeat(np.arange(st.n_theta_nodes), st.n_z_nodes).tolist()]
    return np.repeat(rows, st.n_z_nodes)


def node_compliance(compliance, st):
    """S at every node (flat) from S per θ row, or the scalar S itself (numbers/symbols)."""
    size = compliance.numel() if is_symbolic(compliance) else np.size(compliance)
    return compliance if size == 1 else rows_to_nodes(compliance, st)


def set_boundary(p: np.ndarray, tm) -> np.ndarray:
    """P = 1 on the axial edges and on the rows at ambient pressure (``tm.ambient``)."""
    p[..., :, 0] = 1.0
    p[..., :, -1] = 1.0
    p[..., tm.ambient, :] = 1.0
    return p


def row_mean_phi(phi: np.ndarray, hr: np.ndarray, tm) -> tuple[np.ndarray, float]:
    """(Φ̃, c) with P̄ = Φ̃/a + c on each row whose film is a (axially uniform film).

    Φ̃ = Σ_interior w Φ / Σ w and c = Σ_ends w / Σ w; rows at ambient carry P = 1, so their
    Φ̃ is set to make P̄ − 1 = 0 there.
    """
    zw = tm.z_weight
    total = zw.sum()
    interior = np.ones(phi.shape[-1], dtype=bool)
    interior[[0, -1]] = False
    phit = (phi[..., interior] @ zw[interior]) / total
    c = zw[~interior].sum() / total
    phit[:, tm.ambient] = (1.0 - c) * hr[:, tm.ambient]
    return phit, c


def beam_film(hr, phit, c, tm, guess, cache: Optional[dict] = None):
    """Solve a = H_r + 𝓛 q, q = Φ̃/a + c − 1 (q = 0 on seam rows), for the row films a
    (B, m), 𝓛 = ``tm.foil_data`` the beam's compliance map.

    Chord iterations a ← a − J⁻¹ f with the inverse Jacobian J = I + 𝓛 diag(Φ̃/a²) kept in
    ``cache`` between evaluations (it changes little from one RK stage to the next); it is
    recomputed when the iteration stalls.  Converged to |f| < 1e-13.
    """
    lmap = tm.foil_data
    live = (~tm.ambient).astype(float)
    a = hr.copy() if guess is None or guess.shape != hr.shape else guess.copy()
    cache = {} if cache is None else cache
    eye = np.eye(a.shape[1])
    previous = math.inf
    err = math.inf
    for _ in range(40):
        q = (phit / a + c - 1.0) * live
        f = a - hr - q @ lmap.T
        err = float(np.abs(f).max())
        if err < 1e-13:
            return a
        jinv = cache.get("jinv")
        if jinv is None or jinv.shape[0] != a.shape[0] or err > 0.1 * previous:
            jac = eye[None] + lmap[None] * (live * phit / (a * a))[:, None, :]
            jinv = np.linalg.inv(jac)
            cache["jinv"] = jinv
        previous = err
        a = a - np.einsum("bij,bj->bi", jinv, f)
    raise ConvergenceError("beam film did not converge in the transient model", "max_iter",
                           err)
