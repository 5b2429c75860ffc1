"""Euler–Bernoulli top foil on the bump foundation: cubic Hermite finite elements.

Thesis eq. (4.2) (Mohan, IIT Guwahati; ``docs/PHYSICS.md``): C d⁴W/dθ⁴ + W/S = q with
q = P̄ − 1 the axially averaged gauge pressure, W the top-foil deflection over the clearance
(positive away from the journal).  The welded end (θ = seam) is clamped, W = dW/dθ = 0; the
other end is free.  Cubic Hermite elements on the θ grid (thesis Appendix B; J. N. Reddy,
*An Introduction to the Finite Element Method*, 3rd ed., McGraw-Hill, 2006, ch. 5).  With
``compression_only`` the bump reaction is max(W, 0)/S.

The equations are assembled multiplied by S, S C K_b u + M r(u) = S G q, so that S = 0 gives
W = 0 (rigid) without dividing by zero and C = 0 gives the L²-projection of the simple law.
"""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg  # noqa: F401  (sp.linalg)

from .algebra import is_symbolic, positive_part


@dataclass(frozen=True)
class BeamMatrices:
    """Assembled Hermite-element matrices of the top foil on ``n_elements`` equal elements.

    ``bending`` (K_b without the factor C), ``foundation`` (M, consistent, without 1/S) and
    ``load`` (G, maps nodal q to consistent nodal forces) act on the free degrees of freedom
    (W_k, W'_k for nodes k = 1..n; node 0 is the clamped welded end).  Sparse CSC.
    """

    n_elements: int
    element_length: float
    bending: sp.csc_matrix
    foundation: sp.csc_matrix
    load: sp.csc_matrix   # shape (2n, n+1): q at all n+1 nodes → forces on free dofs

    @property
    def n_dofs(self) -> int:
        return 2 * self.n_elements


def beam_matrices(n_elements: int, element_length: float) -> BeamMatrices:
    """Assemble the Hermite beam-on-foundation matrices (thesis Appendix B).

    n_elements : number of elements over the foil [-]; element_length : Δθ [rad].
    """
    h = element_length
    kb = np.array([[12, 6 * h, -12, 6 * h],
                   [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                   [-12, -6 * h, 12, -6 * h],
                   [6 * h, 2 * h * h, -6 * h, 4 * h * h]]) / h**3
    mf = np.array([[156, 22 * h, 54, -13 * h],
                   [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                   [54, 13 * h, 156, -22 * h],
                   [-13 * h, -3 * h * h, -22 * h, 4 * h * h]]) * h / 420.0
    # consistent load of a linearly varying q (q1, q2) on one element
    ge = np.array([[21, 9], [3 * h, 2 * h], [9, 21], [-2 * h, -3 * h]]) * h / 60.0
    n = n_elements
    ndof = 2 * (n + 1)
    rows, cols, kv, mv = [], [], [], []
    grow, gcol, gv = [], [], []
    for e in range(n):
        dofs = np.arange(2 * e, 2 * e + 4)
        r, c = np.meshgrid(dofs, dofs, indexing="ij")
        rows.append(r.ravel()); cols.append(c.ravel())
        kv.append(kb.ravel()); mv.append(mf.ravel())
        r2, c2 = np.meshgrid(dofs, [e, e + 1], indexing="ij")
        grow.append(r2.ravel()); gcol.append(c2.ravel()); gv.append(ge.ravel())
    rows = np.concatenate(rows); cols = np.concatenate(cols)
    kmat = sp.csc_matrix((np.concatenate(kv), (rows, cols)), shape=(ndof, ndof))
    mmat = sp.csc_matrix((np.concatenate(mv), (rows, cols)), shape=(ndof, ndof))
    gmat = sp.csc_matrix((np.concatenate(gv), (np.concatenate(grow), np.concatenate(gcol))),
                         shape=(ndof, n + 1))
    free = np.arange(2, ndof)
    return BeamMatrices(n, h, kmat[free][:, free].tocsc(), mmat[free][:, free].tocsc(),
                        gmat[free].tocsc())


def _to_dm(m: sp.spmatrix) -> ca.DM:
    m = m.tocsc()
    return ca.DM(ca.Sparsity(m.shape[0], m.shape[1], m.indptr.tolist(), m.indices.tolist()),
                 m.data.tolist())


def foundation_reaction_dofs(u, compression_only):
    """Hermite dofs of the bump reaction S·(bump force): u itself, or its positive part.

    u : free dofs (W_1, W'_1, …, W_n, W'_n).  With ``compression_only`` the reaction is
    interpolated from (max(W_k, 0), W'_k·[W_k > 0]) — exact wherever W > 0 on an element.
    """
    if is_symbolic(u, compression_only):
        w = u[0::2]
        dw = u[1::2]
        rw = positive_part(w)
        rdw = dw * (w > 0)
        r = ca.reshape(ca.horzcat(rw, rdw).T, -1, 1)  # interleave (W, W') per node
        return (1 - compression_only) * u + compression_only * r
    u = np.asarray(u, dtype=float)
    r = u.copy()
    w = u[0::2]
    r[0::2] = np.maximum(w, 0.0)
    r[1::2] = u[1::2] * (w > 0)
    return (1 - compression_only) * u + compression_only * r


def beam_residual(u, q_nodes, mats: BeamMatrices, compliance, coefficient, compression_only):
    """Residual of S C K_b u + M r(u) − S G q = 0 on the free dofs [-].

    u : free dofs; q_nodes : P̄ − 1 at the n + 1 beam nodes, welded end first [-];
    compliance S, coefficient C [-]; compression_only 0/1.
    """
    r = foundation_reaction_dofs(u, compression_only)
    if is_symbolic(u, q_nodes, compliance, coefficient):
        kb, mf, gl = _to_dm(mats.bending), _to_dm(mats.foundation), _to_dm(mats.load)
        return (compliance * coefficient * ca.mtimes(kb, u) + ca.mtimes(mf, r)
                - compliance * ca.mtimes(gl, q_nodes))
    return (compliance * coefficient * (mats.bending @ u) + mats.foundation @ r
            - compliance * (mats.load @ q_nodes))


def beam_dofs(q_nodes, mats: BeamMatrices, compliance, coefficient) -> np.ndarray:
    """Free dofs u of the linear beam (bumps in contact everywhere) under nodal loads q.

    q_nodes : P̄ − 1 at the n + 1 beam nodes (shape (n+1,), or (n+1, k) for k load cases) [-];
    compliance S, coefficient C [-].  Solves (S C K_b + M) u = S G q.
    """
    a = (compliance * coefficient * mats.bending + mats.foundation).tocsc()
    rhs = compliance * (mats.load @ np.asarray(q_nodes, float))
    return sp.linalg.splu(a).solve(np.asarray(rhs, dtype=float))


def beam_deflection(q_nodes, mats: BeamMatrices, compliance, coefficient) -> np.ndarray:
    """W at the n + 1 beam nodes (welded end first) under nodal loads q [-]."""
    u = beam_dofs(q_nodes, mats, compliance, coefficient)
    return np.concatenate([np.zeros((1,) + u.shape[1:]), u[0::2]])
