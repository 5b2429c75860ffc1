"""The impedance along a whirl-ratio interval from one sparse LU: a shift-invariant Krylov space.

Z(s) = F (A + sB)⁻¹ C_ξ (:mod:`gfbopt.linear`) needs one sparse LU per frequency when computed
directly (:func:`gfbopt.linear.impedance`).  Here one LU of M0 = A + s0 B at a shift s0 serves
a whole interval of whirl ratios.  With G = M0⁻¹ B and σ = s − s0,

    A + sB = M0 (I + σ G),        X(s) = (A + sB)⁻¹ C_ξ  solves  (I + σG) X = X0 = M0⁻¹ C_ξ.

Krylov spaces are shift invariant, K_k(I + σG, X0) = K_k(G, X0) for every σ, so one block
Arnoldi process G V_k = V_{k+1} H̄_k started from X0 = V_1 R (one triangular solve with the two
columns per block step) serves every s at once: X(s) ≈ V_k y(s) with

    y(s) = argmin ‖ E_1 R − (Ī + σ H̄_k) y ‖,          Z(s) ≈ (F V_k) y(s),

block GMRES for each shifted system, preconditioned by M0 (Saad 2003, ch. 6; shifted systems:
Frommer & Glässner 1998).  Because V_{k+1} is orthonormal, the least-squares residual
is the true preconditioned residual ‖M0⁻¹(C_ξ − (A + sB) X)‖ / ‖X0‖, available for every s
without touching the large matrices.  Seen as model reduction, Z_k is a rational approximation
of Z that matches its moments at s0 (Bai 2002).

The shift s0 = δ + iγ_m sits over the middle γ_m of the interval, a quarter of its width δ
into the right half plane: the film's own modes (the poles of Z) are damped, Re s < 0, so M0
stays well conditioned even when a weakly damped film mode lies next to the axis (at large Λ
the film has modes near γ = 1/2), and the offset costs at most two block steps (measured).

Measured during development (rigid, axial-mean, local and beam bearings, ε 0.02–0.8,
L/D 0.5–2, η 0 and 0.5; whirl ratios 0.02–1.2): the largest error of Z over 24 whirl ratios
falls below 1e-12 after 8–16 block steps at Λ ≤ 10, ~19 at Λ = 20, ~25 at Λ = 50 (the same at
72 × 20 and 144 × 36: the slow film modes govern, not the mesh), ~28 at Λ = 100 and ~37 at
Λ = 200 (72 × 20).  The test of :meth:`ShiftedImpedance.converged` (residual and change per
step both ≤ 1e-11) never accepted a Z in error by more than 1e-10.  A step costs one
triangular solve (3–4 ms at 144 × 36, against 80–120 ms for a factorisation).

References: Y. Saad, Iterative Methods for Sparse Linear Systems, 2nd ed., SIAM (2003);
A. Frommer, U. Glässner, "Restarted GMRES for shifted linear systems", SIAM J. Sci. Comput.
19(1) (1998) 15–26; Z. Bai, "Krylov subspace techniques for reduced-order modeling of
large-scale dynamical systems", Appl. Numer. Math. 43 (2002) 9–44.
"""
from __future__ import annotations

from typing import Optional, Sequence

import numpy as np
from scipy.linalg import lapack

from ..sparse_lu import factor
from ..threads import single_threaded
from .model import Linearisation

#: LAPACK's complex least-squares solver (3× faster than numpy's qr + solve on these sizes)
_GELS = lapack.get_lapack_funcs("gels", dtype=complex)
#: relative tolerance on the preconditioned residual and on the change of Z per block step
TOLERANCE = 1e-11
#: block steps before the remaining whirl ratios are left to direct solves
MAX_BLOCKS = 48
#: a new block whose norm after orthogonalisation falls below this fraction of its norm
#: before is (numerically) in the space already: the process stops there
BREAKDOWN = 1e-12


class ShiftedImpedance:
    """Z(iγ) for γ in ``whirl_range`` from one LU of A + s0 B (module docstring).

    Only forward whirl (γ > 0) is represented: with structural damping the foundation of the
    upper half plane, k (1 + iη), is used throughout.

    Attributes
    ----------
    shift : s0 [-];  blocks : block Arnoldi steps taken;  solves : triangular solves with the
    LU (each with two right-hand sides);  factorisations : sparse LUs (1)
    """

    @single_threaded
    def __init__(self, lin: Linearisation, whirl_range: Sequence[float],
                 max_blocks: int = MAX_BLOCKS):
        low, high = float(whirl_range[0]), float(whirl_range[1])
        self.shift = complex(0.25 * (high - low), 0.5 * (low + high))
        self.max_blocks = int(max_blocks)
        a, b = lin.system(1j)
        self._b = b.tocsr()
        self._lu = factor((a + self.shift * b).astype(complex), lin.factoriser)
        self.factorisations, self.solves, self.blocks = 1, 1, 0
        self._evaluated: dict = {}                   # (γ, columns) -> (Z, residual)
        n = lin.size
        self._v = np.zeros((n, 2 * (self.max_blocks + 1)), dtype=complex)
        self._h = np.zeros((2 * (self.max_blocks + 1), 2 * self.max_blocks), dtype=complex)
        self._fv = np.zeros((2, 2 * (self.max_blocks + 1)), dtype=complex)
        self._force = lin.force
        q, self._r = np.linalg.qr(self._lu.solve(lin.c_xi.astype(complex)))
        self._v[:, :2] = q
        self._fv[:, :2] = lin.force @ q
        scale = np.abs(np.diag(self._r))
        self.broken = not scale.min() > BREAKDOWN * scale.max()

    @property
    def hessenberg(self) -> np.ndarray:
        """H̄ of the block Arnoldi relation G V_k = V_{k+1} H̄_k: the preallocated array, of
        which the leading (2k + 2) × 2k block is filled after k block steps (read, not
        written)."""
        return self._h

    @property
    def start_factor(self) -> np.ndarray:
        """R (2 × 2) of the start X0 = M0⁻¹ C_ξ = V_1 R."""
        return self._r

    @property
    def force_basis(self) -> np.ndarray:
        """F V: the force rows applied to the basis vectors (2 × preallocated columns, the
        first 2k + 2 filled)."""
        return self._fv

    @single_threaded
    def extend(self) -> bool:
        """One block Arnoldi step (block classical Gram–Schmidt, applied twice).  False when
        the process cannot grow: at ``max_blocks`` or at a breakdown."""
        if self.broken or self.blocks >= self.max_blocks:
            return False
        k = self.blocks
        basis = self._v[:, :2 * k + 2]
        w = self._lu.solve(self._b @ basis[:, 2 * k:2 * k + 2])
        self.solves += 1
        before = np.linalg.norm(w)
        for _ in range(2):
            h = (w.conj().T @ basis).conj().T       # Vᴴ w without copying V
            w -= basis @ h
            self._h[:2 * k + 2, 2 * k:2 * k + 2] += h
        q, r = np.linalg.qr(w)
        if not np.abs(np.diag(r)).min() > BREAKDOWN * before:
            self.broken = True
            return False
        self._v[:, 2 * k + 2:2 * k + 4] = q
        self._h[2 * k + 2:2 * k + 4, 2 * k:2 * k + 2] = r
        self._fv[:, 2 * k + 2:2 * k + 4] = self._force @ q
        self.blocks += 1
        return True

    def evaluate(self, gamma: float, blocks: Optional[int] = None) -> tuple[np.ndarray, float]:
        """(Z(iγ) (2 × 2), relative preconditioned residual) from the space of the first
        ``blocks`` block steps (default: all taken)."""
        m = 2 * (self.blocks if blocks is None else blocks)
        if m == 0:                                   # no step yet: Z ≈ F X0, exact at s0
            return self._fv[:, :2] @ self._r, 1.0
        kept = self._evaluated.get((gamma, m))
        if kept is not None:                         # the space's first m columns are fixed
            return kept[0].copy(), kept[1]
        sigma = 1j * gamma - self.shift
        matrix = np.eye(m + 2, m, dtype=complex) + sigma * self._h[:m + 2, :m]
        rhs = np.zeros((m + 2, 2), dtype=complex)
        rhs[:2] = self._r
        # least squares by Householder QR (LAPACK zgels): rows m: of its answer are Qᴴ rhs
        # beyond the range of the matrix, whose norm is the residual's
        _, solution, info = _GELS(matrix, rhs)
        if info != 0:
            raise np.linalg.LinAlgError(f"reduced least-squares problem singular (zgels {info})")
        y = solution[:m]
        residual = float(np.linalg.norm(solution[m:]) / np.linalg.norm(self._r))
        z = self._fv[:, :m] @ y
        self._evaluated[(gamma, m)] = (z.copy(), residual)
        return z, residual

    def converged(self, gamma: float, tol: float = TOLERANCE) -> bool:
        """True when Z(iγ) has converged: relative residual ≤ ``tol`` and relative change of
        Z over the last block step ≤ ``tol``."""
        if self.blocks == 0:
            return False
        z, residual = self.evaluate(gamma)
        if residual > tol:
            return False
        before = self.evaluate(gamma, self.blocks - 1)[0]
        return bool(np.abs(z - before).max() <= tol * np.abs(z).max())

    @single_threaded
    def converge(self, gammas: Sequence[float], tol: float = TOLERANCE) -> np.ndarray:
        """Extend the space until Z has converged (:meth:`converged`) at every γ in
        ``gammas``; returns the mask of converged whirl ratios (False where ``max_blocks`` or
        a breakdown came first: those are for direct solves).

        After each step the whirl ratios still pending are checked from the farthest from
        the shift inwards, up to the first that has not converged (the far ones converge
        last), so that most steps cost one or two small solves; when the space stops
        growing, every pending one is checked."""
        gammas = np.asarray(gammas, dtype=float)
        done = np.zeros(gammas.size, dtype=bool)
        order = np.argsort(-np.abs(1j * gammas - self.shift), kind="stable")
        while True:
            for j in order[~done[order]]:
                if not self.converged(gammas[j], tol):
                    break
                done[j] = True
            if done.all():
                return done
            if not self.extend():
                for j in order[~done[order]]:
                    done[j] = self.converged(gammas[j], tol)
                return done
