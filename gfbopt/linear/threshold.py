"""Stability of the rigid rotor from the linearised bearing: the threshold (critical mass and
whirl ratio), characteristic roots, semi-discrete eigenvalues and the least-stable mode.

See the package docstring (:mod:`gfbopt.linear`) for the characteristic equation and the
treatment of structural damping (sign(Im s)).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Optional

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.optimize import brentq

from ..errors import ConvergenceError, ParameterError
from .model import Linearisation, factor, impedance


@dataclass(frozen=True)
class LinearThreshold:
    """Linear stability threshold of the rigid rotor.

    critical_mass : M̄_crit = M c ω²/W0 [-]: rotors with M̄ < M̄_crit are stable (inf if
        stable for every mass; 0 if unstable already for the lightest rotor)
    whirl_ratio : whirl frequency over shaft speed at the threshold [-] (nan if none)
    stable_for_all_masses : True when no real threshold exists on (0, γ_max) and the
        rotor is stable
    message, evaluations (impedance solves), wall_time_s
    probe_mass : the mass M̄ [-] below every crossing at which stability was checked
    probe_growth_rate : growth rate per radian of the least-stable whirling mode there
        (< 0 means the rotor is stable below the threshold)
    """

    critical_mass: float
    whirl_ratio: float
    stable_for_all_masses: bool
    message: str
    evaluations: int
    wall_time_s: float
    probe_mass: float = math.nan
    probe_growth_rate: float = math.nan

    @property
    def success(self) -> bool:
        return math.isfinite(self.critical_mass) or self.stable_for_all_masses


def _mass_roots(z: np.ndarray) -> np.ndarray:
    """Roots u = M̄ W̄0 γ² of u² − u tr Z + det Z = 0."""
    tr = z[0, 0] + z[1, 1]
    det = z[0, 0] * z[1, 1] - z[0, 1] * z[1, 0]
    disc = np.sqrt(tr * tr - 4 * det + 0j)
    return np.array([(tr + disc) / 2, (tr - disc) / 2])


def linear_threshold(lin: Linearisation, whirl_range: tuple = (0.02, 1.2),
                     samples: int = 24) -> LinearThreshold:
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
    """
    t0 = time.perf_counter()
    count = [0]

    def roots(gamma: float) -> np.ndarray:
        count[0] += 1
        return _mass_roots(impedance(lin, 1j * gamma))

    gammas = np.linspace(*whirl_range, samples)
    values = np.array([roots(g) for g in gammas])          # (samples, 2)
    candidates = []
    for branch in range(2):
        # follow each root branch by continuity (sort by nearest to the previous point)
        branch_vals = [values[0, branch]]
        for k in range(1, samples):
            prev = branch_vals[-1]
            branch_vals.append(values[k, np.argmin(np.abs(values[k] - prev))])
        im = np.array([v.imag for v in branch_vals])
        for k in range(samples - 1):
            if im[k] == 0 or im[k] * im[k + 1] < 0:
                def f(g, ref=branch_vals[k]):
                    r = roots(g)
                    return r[np.argmin(np.abs(r - ref))].imag
                try:
                    g_star = brentq(f, gammas[k], gammas[k + 1], xtol=1e-10)
                except ValueError:
                    continue
                r = roots(g_star)
                u = r[np.argmin(np.abs(r.imag))]
                if u.real > 0:
                    candidates.append((u.real / (g_star**2 * lin.load), g_star))
    first = min(candidates) if candidates else None
    probe = 0.5 * first[0] if first else PROBE_MASS
    growth, probe_whirl = _least_stable_whirl(lin, probe, first[1] if first else 0.5)
    elapsed = time.perf_counter() - t0
    more = dict(probe_mass=probe, probe_growth_rate=growth)
    if growth > STABILITY_TOLERANCE:
        after = (f"; a crossing at M̄ = {first[0]:.4g} (γ = {first[1]:.3f}) may bound a "
                 "stable range above it" if first else "")
        return LinearThreshold(0.0, probe_whirl, False, (
            f"unstable for every rotor mass: already at M̄ = {probe:.3g} a mode whirling at "
            f"γ = {probe_whirl:.3f} grows at {growth:.3g} per radian (the massless journal "
            f"is unstable){after}"), count[0], elapsed, **more)
    if first is None:
        return LinearThreshold(math.inf, math.nan, True,
                               f"no real threshold for whirl ratios in {whirl_range}: "
                               "stable for every rotor mass", count[0], elapsed, **more)
    return LinearThreshold(first[0], first[1], False, "", count[0], elapsed, **more)


#: mass M̄ [-] at which stability is checked when no threshold crossing exists
PROBE_MASS = 1.0
#: growth rate per radian above which a mode counts as growing (eigenvalue accuracy ~1e-12)
STABILITY_TOLERANCE = 1e-9


def _least_stable_whirl(lin: Linearisation, mass: float, near: float) -> tuple:
    """(growth rate, whirl ratio) of the least-stable forward-whirling eigenvalue at M̄ among
    those nearest i·``near`` (shift-invert eigenvalues of the semi-discrete system)."""
    ev = semi_discrete_eigenvalues(lin, mass, 1j * near, count=8)
    whirling = ev[(ev.imag > 0.02) & (ev.imag < 3.0)]
    if whirling.size == 0:
        return -math.inf, math.nan
    best = whirling[np.argmax(whirling.real)]
    return float(best.real), float(best.imag)


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
    damped = lin.loss_factor > 0 and lin.compliance is not None
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
    lu = factor((jac - shift * e).astype(complex))
    op = spla.LinearOperator(jac.shape, matvec=lambda v: lu.solve(e @ v), dtype=complex)
    mu = spla.eigs(op, k=count, which="LM", return_eigenvectors=False, tol=1e-12)
    values = shift + 1.0 / mu
    if damped:
        values = values[np.sign(values.imag) == np.sign(complex(shift).imag)]
    return values


def least_stable_mode(lin: Linearisation, mass: float,
                      threshold: Optional[LinearThreshold] = None) -> complex:
    """The least stable whirling eigenvalue s of the rotor–bearing system at mass M̄ [-].

    Re s is the growth rate per radian of shaft rotation (> 0: unstable), Im s the whirl
    ratio.  Shift-invert eigenvalues of the semi-discrete system near the threshold whirl
    (or 0.5), refined on the characteristic equation det(M̄W̄0 s² I + Z(s)) = 0.
    """
    threshold = threshold or linear_threshold(lin)
    gamma = threshold.whirl_ratio if math.isfinite(threshold.whirl_ratio) else 0.5
    ev = semi_discrete_eigenvalues(lin, mass, 1j * gamma, count=8)
    whirling = ev[(np.abs(ev.imag) > 0.02) & (np.abs(ev.imag) < 3.0)]
    if whirling.size == 0:
        raise ConvergenceError("no whirling mode near the threshold frequency", "eigs",
                               math.nan)
    best = whirling[np.argmax(whirling.real)]
    best = complex(best.real, abs(best.imag))
    return characteristic_root(lin, mass, best)
