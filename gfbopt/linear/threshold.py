"""Stability of the rigid rotor from the linearised bearing: the threshold (critical mass and
whirl ratio), characteristic roots, semi-discrete eigenvalues and the least-stable mode.

See the package docstring (:mod:`gfbopt.linear`) for the characteristic equation and the
treatment of structural damping (sign(Im s)).

Speed of :func:`linear_threshold`.  The reference search (``method="scan"``) solves one sparse
LU of A + iγB per impedance evaluation: 24 scan points and ~7 per crossing, ≈ 32
factorisations (3–4 s CPU at 144 × 36).  The default (``method="krylov"``) reads Z(iγ) for the
same scan and the same Brent iterations from a block Krylov space built on one LU
(:mod:`.krylov`), checks the crossing that can be the threshold on the exact impedance (one
more LU, :mod:`.crossings`), and reuses that LU for the stability probe below the threshold:
shift-invert Arnoldi on the semi-discrete system by block elimination of the rotor
(:func:`_bordered_eigenvalues`) instead of an LU of the bordered matrix.  Two factorisations
in all (three when nothing crosses, four at a jump of the branch function), ~15 Krylov solves
and the probe's ~45 Arnoldi solves, which are now the largest part.

Evidence.  benchmarks/bench_linear.py (results/benchmarks/linear_speed.json; CPU time, one
BLAS thread): simple, local, beam, seam, η = 0.3 and a seven-crossing case are 3.9–14× faster at
144 × 36 (e.g. simple 4.2 s → 0.39 s) and 3.0–6.8× at 72 × 20, critical mass and whirl ratio
equal to ≤ 5e-13 relative; ``gfbopt linear`` at 144 × 36 takes 2.3 s end to end against 5.4 s.
A sweep of 1086 thresholds at 36 × 10 and 1084 at 72 × 20 (Λ 0.5–40, ε 0.2–0.8, S 0–5, rigid,
axial-mean and local laws, η 0 and 0.3, periodic and seam films, L/D 0.5 and 1.5, each also
with the onset search's 8-point window) gave equal answers to ≤ 5.3e-11 relative with at most
4 factorisations (mean 2.1).  tests/verification/test_threshold_speed_paths.py keeps the
comparison, including several crossing branches, M̄c = 0, M̄c = ∞ and the fallbacks.
Not adopted: fewer scan points — the answer depends on the scan (on 216 cases at 36 × 10, 16,
12 and 8 points changed the threshold in 2, 7 and 22; 48 and 96 points in 9 and 13: crossings
narrower than the spacing near γ = 1/2 at Λ ≈ 10 are missed by 24 points, a property of the
reference kept here), while scan points on the Krylov model cost ~0.1 ms each; GMRES for each
γ preconditioned by a nearby LU (each γ would need about as many solves as the shared space
needs for all of them); SuperLU with a reused ordering (slower,
:func:`~gfbopt.linear.coefficients`).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Optional

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ConvergenceError, ParameterError
from .crossings import Cost, DirectImpedance, krylov_crossings, scan_crossings
from ..sparse_lu import factor
from ..threads import single_threaded
from .model import Linearisation, impedance

#: ways to evaluate the impedance in :func:`linear_threshold` (module docstring)
METHODS = ("krylov", "scan")


@dataclass(frozen=True)
class LinearThreshold:
    """Linear stability threshold of the rigid rotor.

    critical_mass : M̄_crit = M c ω²/W0 [-]: rotors with M̄ < M̄_crit are stable (inf if
        stable for every mass; 0 if unstable already for the lightest rotor)
    whirl_ratio : whirl frequency over shaft speed at the threshold [-] (nan if none)
    stable_for_all_masses : True when no real threshold exists on (0, γ_max) and the
        rotor is stable
    message, wall_time_s
    evaluations : direct impedance solves of the search (a sparse LU each; with method
        "krylov" the Krylov model's evaluations are not counted)
    probe_mass : the mass M̄ [-] below every crossing at which stability was checked
    probe_growth_rate : growth rate per radian of the least-stable whirling mode there
        (< 0 means the rotor is stable below the threshold)
    method : "krylov" or "scan" (module docstring); factorisations : sparse LUs, the
        stability probe's included; solves : triangular solves of the search (two
        right-hand sides each; the probe's Arnoldi solves are not counted)
    """

    critical_mass: float
    whirl_ratio: float
    stable_for_all_masses: bool
    message: str
    evaluations: int
    wall_time_s: float
    probe_mass: float = math.nan
    probe_growth_rate: float = math.nan
    method: str = "scan"
    factorisations: int = 0
    solves: int = 0

    @property
    def success(self) -> bool:
        return math.isfinite(self.critical_mass) or self.stable_for_all_masses


@single_threaded
def linear_threshold(lin: Linearisation, whirl_range: tuple = (0.02, 1.2),
                     samples: int = 24, method: str = "krylov") -> LinearThreshold:
    """The critical mass and whirl ratio where det(−M̄W̄0γ² I + K + iγC) = 0 (module doc).

    Scans γ on ``samples`` points of ``whirl_range``, finds where a root u(γ) becomes real
    (Im u = 0 with Re u > 0) and refines with Brent's method: these crossings are the only
    masses at which a mode crosses the imaginary axis.  The number of unstable modes is
    therefore the same for every mass below the smallest crossing, and one eigenvalue check
    at half that mass (or at M̄ = 1 when there is no crossing) decides whether rotors below
    it are stable.  They usually are, and the smallest crossing is the threshold.  They are
    not when the massless journal is itself unstable — its half-frequency mode, neutral for
    a concentric periodic film, can be pushed either way by a seam (e.g. a welded end inside
    the loaded arc) — and then the critical mass is 0: unstable for every rotor mass.

    Parameters
    ----------
    lin : the linearised bearing
    whirl_range : (low, high) whirl ratios scanned, 0 < low < high [-]
    samples : number of scan points, an integer ≥ 2
    method : "krylov" (default: Z from a Krylov space on one LU, the threshold's crossing
        checked on the exact impedance) or "scan" (the reference: one LU per evaluation);
        they agree to Brent's tolerance (module docstring)
    """
    low, high = _check_whirl_range(whirl_range)
    samples = _check_samples(samples)
    if method not in METHODS:
        raise ParameterError("method", method, f"must be one of: {', '.join(METHODS)}")
    t0 = time.perf_counter()
    gammas = np.linspace(low, high, samples)
    cost = Cost()
    search = scan_crossings if method == "scan" else krylov_crossings
    found = search(lin, gammas, cost)
    first = min(found, key=lambda c: (c.mass, c.whirl)) if found else None
    probe = 0.5 * first.mass if first else PROBE_MASS
    near = first.whirl if first else 0.5
    if method == "scan":
        cost.factorisations += 1
        growth, probe_whirl = _least_stable_whirl(lin, probe, near)
    else:
        factorised = first.factorised if first else None
        if factorised is None:
            factorised = DirectImpedance(lin, cost).factorise(near)
        growth, probe_whirl = _least_stable_whirl(lin, probe, near, factorised)
    elapsed = time.perf_counter() - t0
    more = dict(probe_mass=probe, probe_growth_rate=growth, method=method,
                factorisations=cost.factorisations, solves=cost.solves)
    if growth > STABILITY_TOLERANCE:
        after = (f"; a crossing at M̄ = {first.mass:.4g} (γ = {first.whirl:.3f}) may bound a "
                 "stable range above it" if first else "")
        return LinearThreshold(0.0, probe_whirl, False, (
            f"unstable for every rotor mass: already at M̄ = {probe:.3g} a mode whirling at "
            f"γ = {probe_whirl:.3f} grows at {growth:.3g} per radian (the massless journal "
            f"is unstable){after}"), cost.evaluations, elapsed, **more)
    if first is None:
        return LinearThreshold(math.inf, math.nan, True,
                               f"no real threshold for whirl ratios in {(low, high)}: "
                               "stable for every rotor mass", cost.evaluations, elapsed, **more)
    return LinearThreshold(first.mass, first.whirl, False, "", cost.evaluations, elapsed,
                           **more)


def _check_whirl_range(whirl_range) -> tuple[float, float]:
    try:
        low, high = (float(v) for v in whirl_range)
    except (TypeError, ValueError):
        raise ParameterError("whirl_range", whirl_range, "must be two whirl ratios "
                             "(low, high)") from None
    if not (math.isfinite(low) and math.isfinite(high) and 0 < low < high):
        raise ParameterError("whirl_range", whirl_range, "must be finite with 0 < low < high")
    return low, high


def _check_samples(samples) -> int:
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 2:
        raise ParameterError("samples", samples, "must be an integer >= 2")
    return int(samples)


#: mass M̄ [-] at which stability is checked when no threshold crossing exists
PROBE_MASS = 1.0
#: growth rate per radian above which a mode counts as growing (eigenvalue accuracy ~1e-12)
STABILITY_TOLERANCE = 1e-9


def _least_stable_whirl(lin: Linearisation, mass: float, near: float,
                        factorised: Optional[tuple] = None) -> tuple:
    """(growth rate, whirl ratio) of the least-stable forward-whirling eigenvalue at M̄ among
    those nearest i·``near`` (shift-invert eigenvalues of the semi-discrete system), from an
    LU of the bordered system, or from ``factorised`` = (LU, X, Z) of A + i·near·B."""
    shift = 1j * near
    ev = (semi_discrete_eigenvalues(lin, mass, shift, count=8) if factorised is None
          else _bordered_eigenvalues(lin, mass, shift, *factorised, count=8))
    whirling = ev[(ev.imag > 0.02) & (ev.imag < 3.0)]
    if whirling.size == 0:
        return -math.inf, math.nan
    best = whirling[np.argmax(whirling.real)]
    return float(best.real), float(best.imag)


def _bordered_eigenvalues(lin: Linearisation, mass: float, shift: complex, lu, x: np.ndarray,
                          z: np.ndarray, count: int = 6) -> np.ndarray:
    """:func:`semi_discrete_eigenvalues` from the LU of A + shift·B (``lu``; X = its solve
    of C_ξ, Z = f X the impedance at the shift), with shift in the upper half plane.

    Shift-invert Arnoldi needs (J − σE)⁻¹ E v.  For J − σE = [[−(A+σB), −C_ξ, 0],
    [0, −σI, I], [f, 0, −σ M̄W̄0 I]] and a right-hand side (r1, r2, r3), eliminating the
    pressure and foil states leaves the 2 × 2 system (Z(σ) + σ² M̄W̄0 I) ξ = −(r3 + σ M̄W̄0 r2
    + f w) with w = (A+σB)⁻¹ r1; then y = −w − X ξ and u = r2 + σ ξ: one solve with the
    impedance's own LU per step instead of an LU of the bordered matrix.
    """
    m = _check_positive_mass(mass) * lin.load
    _, b = lin.system(shift)
    n = lin.size
    schur = np.linalg.inv(z + shift**2 * m * np.eye(2))

    def apply(v):
        v = np.ravel(v)
        r1, r2, r3 = b @ v[:n], v[n:n + 2], m * v[n + 2:]
        w = lu.solve(r1)
        xi = -schur @ (r3 + shift * m * r2 + lin.force @ w)
        return np.concatenate([-w - x @ xi, xi, r2 + shift * xi])

    op = spla.LinearOperator((n + 4, n + 4), matvec=apply, dtype=complex)
    mu = spla.eigs(op, k=count, which="LM", return_eigenvectors=False, tol=1e-12)
    return shift + 1.0 / mu


@single_threaded
def characteristic_root(lin: Linearisation, mass: float, guess: complex,
                        tol: float = 1e-10, max_iter: int = 40) -> complex:
    """A root s of det(M̄ W̄0 s² I + Z(s)) = 0 near ``guess`` (secant iteration in s).

    Re s is the growth rate per radian of shaft rotation, Im s the whirl ratio.
    """
    m = _check_positive_mass(mass) * lin.load

    def d(s):
        z = impedance(lin, s)
        return np.linalg.det(m * s * s * np.eye(2) + z)

    s0, s1 = guess, guess * (1 + 1e-3) + 1e-4j
    f0, f1 = d(s0), d(s1)
    for _ in range(max_iter):
        if f1 == f0:
            break
        s2 = s1 - f1 * (s1 - s0) / (f1 - f0)
        s0, f0, s1, f1 = s1, f1, s2, d(s2)
        if abs(s1 - s0) < tol * max(1.0, abs(s1)):
            return complex(s1)
    raise ConvergenceError("characteristic root did not converge", "max_iter", abs(f1))


def _check_positive_mass(mass: float) -> float:
    try:
        m = float(mass)
    except (TypeError, ValueError):
        raise ParameterError("mass", mass, "must be a number") from None
    if not math.isfinite(m) or m <= 0:
        raise ParameterError("mass", mass, "must be finite and > 0")
    return m


@single_threaded
def semi_discrete_eigenvalues(lin: Linearisation, mass: float, shift: complex,
                              count: int = 6) -> np.ndarray:
    """Eigenvalues nearest ``shift`` of the linearised semi-discrete system (pressure and
    foil states + rigid rotor), by shift-invert Arnoldi on the descriptor system s E v = J v.

    States v = (y, ξ, u = ξ'):  B y' = −A y − C_ξ ξ,  ξ' = u,  M̄W̄0 u' = f·y.
    An independent check of :func:`linear_threshold` (no impedance, no root finding).

    With structural damping (η > 0) the foundation of the half plane of the shift is used,
    k (1 + iη sign(Im shift)), and only eigenvalues in that half plane are returned (the
    others belong to the wrong foundation); a shift on the real axis is then refused.
    """
    m = _check_positive_mass(mass) * lin.load
    damped = lin.hysteretic
    if damped and complex(shift).imag == 0:
        raise ParameterError("shift", shift, "must have Im ≠ 0 with structural damping "
                             "(η > 0): the hysteretic foundation depends on the whirl "
                             "direction sign(Im s)")
    a, b = lin.system(shift)
    n = lin.size
    zero = sp.csc_matrix((n, 2))
    jac = sp.bmat([[-a, sp.csc_matrix(-lin.c_xi), zero],
                   [sp.csc_matrix((2, n)), None, sp.identity(2)],
                   [sp.csc_matrix(lin.force), sp.csc_matrix((2, 2)), None]], format="csc")
    e = sp.block_diag([b, sp.identity(2), m * sp.identity(2)], format="csc")
    lu = factor((jac - shift * e).astype(complex), lin.factoriser)
    op = spla.LinearOperator(jac.shape, matvec=lambda v: lu.solve(e @ v), dtype=complex)
    mu = spla.eigs(op, k=count, which="LM", return_eigenvectors=False, tol=1e-12)
    values = shift + 1.0 / mu
    if damped:
        values = values[np.sign(values.imag) == np.sign(complex(shift).imag)]
    return values
