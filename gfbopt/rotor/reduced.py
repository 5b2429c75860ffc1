"""A bearing's impedance Z̄(s) at any complex s near the whirl axis from its Krylov space, in
Schur form: tens of microseconds per evaluation instead of a QR (or a sparse LU) each.

:class:`gfbopt.linear.krylov.ShiftedImpedance` builds one block Arnoldi process
G V_k = V_{k+1} H̄_k on the LU of M0 = A + s0 B (G = M0⁻¹ B, X0 = M0⁻¹ C_ξ = V_1 R) and
evaluates Z̄(s) by block GMRES, a QR of the (m + 2) × m matrix Ī + σ H̄ per s (σ = s − s0,
m = 2k).  The same space with the Galerkin (FOM) condition instead,

    (I + σ H_m) y = E_1 R,      Z̄(s) ≈ (F V_m) y,       H_m the square part of H̄,

needs no factorisation per s once H_m = Q T Qᴴ is in complex Schur form: u = (I + σT)⁻¹ Qᴴ E_1 R
is one triangular solve of order m, Z̄ = (F V_m Q) u.  Its residual is exact and as cheap: the
first m rows of E_1 R − (Ī + σH̄) y vanish by construction and the last two are −σ H̄[m:, :m] y,
so ‖M0⁻¹(C_ξ − (A + sB) V_m y)‖/‖X0‖ = |σ| ‖(H̄[m:, :m] Q) u‖/‖R‖ (V_{k+1} orthonormal).  A
value is accepted under the test of :meth:`ShiftedImpedance.converged` — relative residual and
relative change of Z̄ over the last block step both ≤ :data:`~gfbopt.linear.krylov.TOLERANCE`
(1e-11; the change from a second Schur form of H_{m−2}) — else the space is extended (a block
step: one triangular solve with the sparse LU), up to its ``max_blocks``; where it still has not
converged the caller makes a direct LU.  Converged FOM and GMRES values agree to the tolerance
(both are within it of the exact Z̄; a test compares them with direct solves).

The model is valid wherever the test passes, on the axis (s = iγ, the threshold's whirl
ratios) and off it (the Campbell diagram's eigenvalues s, damped or growing), for the
hysteretic foundation of the upper half plane the Krylov space was built with: with η = 0 the
impedance is analytic in s and this is the exact Z̄(s); with η > 0 the Campbell diagram's
Kelvin–Voigt foundation is another function and is not taken from here.

This module reads the Krylov space's arrays (H̄, F V, R, the shift) from the
:class:`ShiftedImpedance` it is given; it does not change it except by :meth:`extend`.
"""
from __future__ import annotations

from typing import Optional

import numpy as np
import scipy.linalg as sla

from ..linear.krylov import TOLERANCE, ShiftedImpedance

#: LAPACK's triangular solve, called directly (scipy's wrapper checks cost more than the
#: solve at this size)
_TRTRS = sla.get_lapack_funcs("trtrs", dtype=np.complex128)


class _Schur:
    """The FOM solution on the first ``m`` columns of the space in Schur form."""

    def __init__(self, model: ShiftedImpedance, m: int):
        h = model.hessenberg
        t, q = sla.schur(h[:m, :m], output="complex")
        rhs = np.zeros((m, 2), dtype=complex)
        rhs[:2] = model.start_factor
        self.shift = model.shift
        self.t = np.asfortranarray(t)
        self.c = q.conj().T @ rhs
        self.f = model.force_basis[:, :m] @ q
        self.tail = h[m:m + 2, :m] @ q
        self.diagonal = np.diag_indices(m)
        self.norm_r = float(np.linalg.norm(model.start_factor))

    def solve(self, sigma: complex) -> tuple[np.ndarray, float]:
        """(Z̄ (2 × 2), relative residual) at σ = s − s0 (inf when I + σT is singular)."""
        matrix = sigma * self.t
        matrix[self.diagonal] += 1.0
        u, info = _TRTRS(matrix, self.c)
        if info != 0:
            return np.full((2, 2), np.nan, dtype=complex), np.inf
        return self.f @ u, float(abs(sigma) * np.linalg.norm(self.tail @ u) / self.norm_r)


    def solve_many(self, sigma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`solve` at every σ of an array: (Z̄ (n, 2, 2), relative residuals (n,)) —
        the same triangular solves (a quarter cheaper than numpy's batched LU at m ≈ 24)."""
        u = np.empty((sigma.size,) + self.c.shape, dtype=complex)
        singular = np.zeros(sigma.size, dtype=bool)
        for k, s in enumerate(sigma):
            matrix = s * self.t
            matrix[self.diagonal] += 1.0
            u[k], info = _TRTRS(matrix, self.c)
            singular[k] = info != 0
        residual = np.abs(sigma) * np.linalg.norm(self.tail @ u, axis=(1, 2)) / self.norm_r
        z = self.f @ u
        z[singular], residual[singular] = np.nan, np.inf
        return z, residual


class ReducedImpedance:
    """Z̄(s) of one bearing from its :class:`ShiftedImpedance` (module docstring)."""

    def __init__(self, model: ShiftedImpedance, tol: float = TOLERANCE):
        self.model, self.tol = model, tol
        self._blocks = -1
        self._last: Optional[_Schur] = None
        self._previous: Optional[_Schur] = None
        #: (points, Z̄, accepted) of the last batch :meth:`converge` evaluated on the space as
        #: it ended (the values a later :meth:`evaluate_many` would give)
        self.last_batch: Optional[tuple] = None

    def _schur(self, previous: bool = False) -> Optional[_Schur]:
        """The Schur form on all the space's columns (``previous``: without the last block),
        computed when first asked after the space has grown; None before two blocks."""
        k = self.model.blocks
        if k < 2:
            return None
        if k != self._blocks:
            self._last = self._previous = None
            self._blocks = k
        if previous:
            if self._previous is None:
                self._previous = _Schur(self.model, 2 * k - 2)
            return self._previous
        if self._last is None:
            self._last = _Schur(self.model, 2 * k)
        return self._last

    def evaluate(self, s: complex) -> tuple[np.ndarray, bool]:
        """(Z̄(s), converged) from the space as it is."""
        last = self._schur()
        if last is None:
            return np.full((2, 2), np.nan, dtype=complex), False
        sigma = complex(s) - self.model.shift
        z, residual = last.solve(sigma)
        if not residual <= self.tol:
            return z, False
        before = self._schur(previous=True).solve(sigma)[0]
        return z, bool(np.abs(z - before).max() <= self.tol * np.abs(z).max())

    def schur(self) -> Optional[_Schur]:
        """The Schur form on the whole space (None before two blocks): its ``t``, ``c``,
        ``f`` and ``shift`` give Z̄(s) = f (I + (s − shift) t)⁻¹ c."""
        return self._schur()

    def evaluate_many(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`evaluate` at every complex s of an array: (Z̄ (n, 2, 2), converged (n,))."""
        points = np.asarray(points, dtype=complex)
        last = self._schur()
        if last is None:
            return (np.full((points.size, 2, 2), np.nan, dtype=complex),
                    np.zeros(points.size, dtype=bool))
        sigma = points - self.model.shift
        z, residual = last.solve_many(sigma)
        before = self._schur(previous=True).solve_many(sigma)[0]
        change = np.abs(z - before).max(axis=(1, 2)) <= self.tol * np.abs(z).max(axis=(1, 2))
        return z, (residual <= self.tol) & change

    def value(self, s: complex) -> Optional[np.ndarray]:
        """Z̄(s) once converged, extending the space as needed; None when it cannot be (at
        the space's ``max_blocks`` or a breakdown: the caller solves directly)."""
        while True:
            z, ok = self.evaluate(s)
            if ok:
                return z
            if not self.model.extend():
                return None

    def _accepted_dense(self, s: complex) -> bool:
        """:meth:`evaluate`'s test by dense solves of the FOM system (no Schur form: cheaper
        while the space is still growing)."""
        k = self.model.blocks
        if k < 2:
            return False
        h, fv, r = self.model.hessenberg, self.model.force_basis, self.model.start_factor
        sigma = complex(s) - self.model.shift
        values = []
        for m in (2 * k, 2 * k - 2):
            rhs = np.zeros((m, 2), dtype=complex)
            rhs[:2] = r
            y = np.linalg.solve(np.eye(m) + sigma * h[:m, :m], rhs)
            values.append(fv[:, :m] @ y)
            if m == 2 * k:
                residual = abs(sigma) * np.linalg.norm(h[m:m + 2, :m] @ y) / np.linalg.norm(r)
                if not residual <= self.tol:
                    return False
        z, before = values
        return bool(np.abs(z - before).max() <= self.tol * np.abs(z).max())

    def converge(self, points) -> np.ndarray:
        """Extend the space until :meth:`evaluate`'s test accepts every complex s in
        ``points``; the mask of those accepted.  Each step checks only the pending point
        farthest from the shift (the far ones converge last) by dense solves, and once it
        passes, every pending point at once in Schur form."""
        points = np.asarray(points, dtype=complex)
        done = np.zeros(points.size, dtype=bool)
        distance = np.abs(points - self.model.shift)
        while True:
            pending = np.flatnonzero(~done)
            far = pending[np.argmax(distance[pending])]
            if self._accepted_dense(points[far]):
                z, done[pending] = self.evaluate_many(points[pending])
                self.last_batch = (points[pending], z, done[pending].copy(),
                                   self.model.blocks)
                done[far] = True
                if done.all():
                    return done
            if not self.model.extend():
                return done


class TaylorImpedance:
    """Z̄(iγ) near one whirl ratio γ0 from one direct LU of M = A + iγ0 B: the Taylor series
    Z̄(iγ0 + σ) = Σ σᵏ F Xₖ, X₀ = M⁻¹ C_ξ, Xₖ₊₁ = −M⁻¹ B Xₖ, one triangular solve a term,
    extended on demand: the local search's model (:func:`gfbopt.rotor.matched_whirl.
    local_crossing`, ``direct``), whose Newton steps stay within ~1e-3 of the start (a secant
    step's whirl ratio moves by 1e-7–3e-5, the coarse grid's crossing lies 2e-3 from the
    fine one).  A value is accepted when the last two terms are each at most
    :data:`~gfbopt.linear.krylov.TOLERANCE` (1e-11) of Z̄: the terms fall by |σ|/r a step,
    r the distance from iγ0 to the nearest pole of Z̄ (measured r ≈ 0.6 on the blower's
    bearings at 72 × 20 and 144 × 36: the film's modes are well damped there), so the ones
    dropped are smaller still; beyond :data:`MAX_TERMS` terms it is refused (the caller then
    uses a Krylov space).  The same foundation of the upper half plane as
    :class:`ShiftedImpedance`; measured against direct LUs: ≤ 3e-14 relative within 1e-4 of
    γ0 (tests/unit/test_rotor_onset_speed_direct.py checks 1e-10)."""

    #: most terms of the series before a value is refused
    MAX_TERMS = 12

    def __init__(self, lin, whirl_ratio: float, tol: float = TOLERANCE):
        from ..sparse_lu import factor
        s0 = 1j * float(whirl_ratio)
        a, b = lin.system(s0)
        self._lu = factor((a + s0 * b).astype(complex), lin.factoriser)
        self._b, self._force = b.tocsr(), lin.force
        self._x = self._lu.solve(lin.c_xi.astype(complex))
        self._terms = [self._force @ self._x]
        self._sizes = [float(np.abs(self._terms[0]).max())]
        self.centre, self.tol = float(whirl_ratio), tol

    def _extend(self) -> None:
        self._x = -self._lu.solve(self._b @ self._x)
        self._terms.append(self._force @ self._x)
        self._sizes.append(float(np.abs(self._terms[-1]).max()))

    def evaluate(self, gamma: float) -> tuple[np.ndarray, bool]:
        """(Z̄(iγ), accepted), the series extended until its last two terms are negligible
        there (or :data:`MAX_TERMS` reached: not accepted)."""
        sigma = abs(float(gamma) - self.centre)
        while len(self._terms) < 2 or not all(
                sigma ** k * self._sizes[k] <= self.tol * self._sizes[0]
                for k in (len(self._terms) - 2, len(self._terms) - 1) if k > 0):
            if len(self._terms) >= self.MAX_TERMS:
                break
            self._extend()
        powers = (1j * (float(gamma) - self.centre)) ** np.arange(len(self._terms))
        z = np.tensordot(powers, np.array(self._terms), axes=1)
        last = [abs(powers[k]) * self._sizes[k] for k in (-2, -1)]
        return z, bool(max(last) <= self.tol * np.abs(z).max() or sigma == 0.0)
