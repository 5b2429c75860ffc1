"""Where a root u(γ) of u² − u tr Z(iγ) + det Z(iγ) = 0 becomes real: the candidate
thresholds of :func:`gfbopt.linear.linear_threshold`.

Both searches scan γ, follow the two root branches by continuity (nearest root to the
previous scan point), and refine every sign change of Im u with Brent's method
(xtol = :data:`WHIRL_TOLERANCE`); a crossing with Re u > 0 is a mass M̄ = u/(γ² W̄0) at which a
mode sits on the imaginary axis.  They differ only in where Z(iγ) comes from:

* :func:`scan_crossings`, the reference: a sparse LU of A + iγB per evaluation;
* :func:`krylov_crossings`: Z from the Krylov space of one LU
  (:class:`~gfbopt.linear.krylov.ShiftedImpedance`), converged at every scan point.  Scan
  points where it has not converged are solved directly, and a bracket with such an end is
  refined on the exact impedance.  A crossing found on the model is trusted as a candidate
  when the model's residual at its γ is within tolerance: then one with u < 0 is dropped (as
  the reference drops it) and one whose mass exceeds the smallest checked one by more than
  :data:`MASS_MARGIN` cannot be the threshold.  Every other crossing is checked on the exact
  impedance at its γ (one LU): accepted when the Newton correction −Im u/(d Im u/dγ) from the
  exact Im u (slope from the model) is within :data:`WHIRL_TOLERANCE`, the reference's own
  tolerance, or else when the exact branch function changes sign within that tolerance (two
  more LUs); otherwise up to :data:`POLISH_STEPS` Newton steps on the exact impedance, and
  then Brent's method on it, as the reference.  Its mass comes from the exact roots, and its
  LU is returned with it (the stability probe reuses it).

The branch function (Im of the root nearest the branch's value at the bracket's left end)
can jump where the two roots swap places as the nearer one, and Brent's method then reports
the jump as a crossing although neither root is real there (seen at Λ ≥ 10 with periodic
films, near γ = 1/2: Im u = 0.048 against |u| = 1.5).  The reference does so, and so does the
fast search, to the same tolerance: the sign test above accepts such a point with 3 LUs
where Brent's method on the exact impedance spends ~45 (it bisects a jump).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np
from scipy.optimize import brentq

from .krylov import TOLERANCE, ShiftedImpedance
from ..sparse_lu import factor
from ..threads import single_threaded
from .model import Linearisation

#: tolerance of a crossing's whirl ratio (absolute, Brent's xtol) [-]
WHIRL_TOLERANCE = 1e-10
#: Newton steps on the exact impedance before falling back to Brent's method on it
POLISH_STEPS = 3
#: a crossing found on the Krylov model is checked on the exact impedance unless its mass
#: exceeds the smallest one checked by more than this (relative) [-]
MASS_MARGIN = 1e-6
#: step of the central difference for d Im u/dγ on the Krylov model [-]
SLOPE_STEP = 1e-6


@dataclass
class Cost:
    """What a threshold search spent: direct impedance evaluations (a sparse LU each), all
    sparse LUs (the Krylov model's included), triangular solves (two right-hand sides)."""

    evaluations: int = 0
    factorisations: int = 0
    solves: int = 0


@dataclass(frozen=True)
class Crossing:
    """A real root u > 0 at whirl ratio γ: mass M̄ = u/(γ² W̄0) [-], whirl γ [-], and
    ``factorised`` = (LU of A + iγB, X = (A + iγB)⁻¹ C_ξ, Z(iγ)) when kept (Krylov search)."""

    mass: float
    whirl: float
    factorised: Optional[tuple] = None


def mass_roots(z: np.ndarray) -> np.ndarray:
    """Roots u = M̄ W̄0 γ² of u² − u tr Z + det Z = 0."""
    tr = z[0, 0] + z[1, 1]
    det = z[0, 0] * z[1, 1] - z[0, 1] * z[1, 0]
    disc = np.sqrt(tr * tr - 4 * det + 0j)
    return np.array([(tr + disc) / 2, (tr - disc) / 2])


class DirectImpedance:
    """Z(iγ) from its own sparse LU each time, as :func:`gfbopt.linear.impedance` does (the
    same operations, so the same numbers); the last factorisation is kept."""

    def __init__(self, lin: Linearisation, cost: Cost):
        self.lin, self.cost = lin, cost
        self.last: Optional[tuple] = None          # (γ, LU, X, Z)

    def factorise(self, gamma: float) -> tuple:
        """(LU of A + iγB, X = its solve of C_ξ, Z(iγ) = f X)."""
        s = 1j * gamma
        a, b = self.lin.system(s)
        lu = factor((a + s * b).astype(complex), self.lin.factoriser)
        x = lu.solve(self.lin.c_xi.astype(complex))
        self.cost.factorisations += 1
        self.cost.solves += 1
        self.last = (gamma, lu, x, self.lin.force @ x)
        return self.last[1:]

    def roots(self, gamma: float) -> np.ndarray:
        self.cost.evaluations += 1
        return mass_roots(self.factorise(gamma)[2])


def brackets(values: np.ndarray) -> list:
    """(k, u_k) for every scan interval [γ_k, γ_k+1] where a root branch's Im u changes sign,
    branch after branch; each branch is followed by continuity (nearest root to its value at
    the previous point) and u_k is its root at γ_k.  values : (samples, 2) roots."""
    out = []
    for branch in range(2):
        branch_vals = [values[0, branch]]
        for k in range(1, len(values)):
            prev = branch_vals[-1]
            branch_vals.append(values[k, np.argmin(np.abs(values[k] - prev))])
        im = np.array([v.imag for v in branch_vals])
        for k in range(len(values) - 1):
            if im[k] == 0 or im[k] * im[k + 1] < 0:
                out.append((k, branch_vals[k]))
    return out


def _branch_imag(roots: Callable, ref: complex) -> Callable:
    """γ ↦ Im of the root u(γ) nearest ``ref`` (the branch being refined)."""
    def f(gamma):
        r = roots(gamma)
        return r[np.argmin(np.abs(r - ref))].imag
    return f


def _refine(roots: Callable, low: float, high: float, ref: complex) -> Optional[float]:
    """γ in [low, high] where the branch through ``ref`` is real (Brent), or None when Im u
    of the root nearest ``ref`` does not change sign there."""
    try:
        return brentq(_branch_imag(roots, ref), low, high, xtol=WHIRL_TOLERANCE)
    except ValueError:
        return None


def _real_root(r: np.ndarray) -> complex:
    """The root with the smallest |Im u| (the real one at a crossing)."""
    return r[np.argmin(np.abs(r.imag))]


@single_threaded
def scan_crossings(lin: Linearisation, gammas: np.ndarray, cost: Cost) -> list:
    """The reference search: every Z(iγ) from its own LU.  Crossings with u > 0."""
    direct = DirectImpedance(lin, cost)
    values = np.array([direct.roots(g) for g in gammas])
    found = []
    for k, ref in brackets(values):
        g = _refine(direct.roots, gammas[k], gammas[k + 1], ref)
        if g is None:
            continue
        u = _real_root(direct.roots(g))
        if u.real > 0:
            found.append(Crossing(u.real / (g**2 * lin.load), g))
    return found


@single_threaded
def krylov_crossings(lin: Linearisation, gammas: np.ndarray, cost: Cost) -> list:
    """The search on the Krylov model, crossings checked on the exact impedance (module
    docstring).  Crossings with u > 0 that can be the threshold, with their LU."""
    direct = DirectImpedance(lin, cost)
    try:
        model = ShiftedImpedance(lin, (gammas[0], gammas[-1]))
    except RuntimeError:                     # A + s0 B exactly singular: all direct
        model = None
    if model is not None:
        converged = model.converge(gammas)
        cost.factorisations += model.factorisations
        cost.solves += model.solves
    else:
        converged = np.zeros(gammas.size, dtype=bool)

    def reduced(gamma):
        return mass_roots(model.evaluate(gamma)[0])

    values = np.array([reduced(g) if ok else direct.roots(g)
                       for g, ok in zip(gammas, converged)])
    found, pending = [], []
    for k, ref in brackets(values):
        low, high = gammas[k], gammas[k + 1]
        if not (converged[k] and converged[k + 1]):
            crossing = _exact_crossing(lin, direct, low, high, ref)
            if crossing is not None:
                found.append(crossing)
            continue
        g = _refine(reduced, low, high, ref)
        if g is None:
            continue
        z, residual = model.evaluate(g)
        u = _real_root(mass_roots(z))
        trusted = residual <= TOLERANCE
        if u.real > -1e-9 * abs(u) or not trusted:   # else u < 0: no mass crosses here
            pending.append((u.real / (g**2 * lin.load), g, k, ref, trusted))
    for mass, g, k, ref, trusted in sorted(pending, key=lambda p: p[:2]):
        best = min((c.mass for c in found), default=math.inf)
        if trusted and mass > best * (1 + MASS_MARGIN):
            continue                          # cannot be the threshold
        branch = _branch_imag(reduced, ref)
        slope = (branch(g + SLOPE_STEP) - branch(g - SLOPE_STEP)) / (2 * SLOPE_STEP)
        crossing = _checked_crossing(lin, direct, g, slope, gammas[k], gammas[k + 1], ref)
        if crossing is not None:
            found.append(crossing)
    return found


def _checked_crossing(lin: Linearisation, direct: DirectImpedance, g: float, slope: float,
                      low: float, high: float, ref: complex) -> Optional[Crossing]:
    """The crossing found on the model near ``g``, checked on the exact impedance: accepted
    when the exact branch function changes sign within :data:`WHIRL_TOLERANCE` of ``g`` (what
    Brent's method guarantees) — shown by the Newton correction from the exact Im u at ``g``,
    or else by its signs at g ± the tolerance (where it jumps, see the module docstring).
    Otherwise Newton steps on the exact impedance, and then Brent's method on it."""
    tol = WHIRL_TOLERANCE
    branch = _branch_imag(direct.roots, ref)
    newton = math.isfinite(slope) and slope != 0
    value = branch(g)
    if value == 0 or (newton and abs(value / slope) <= tol):
        return _crossing_here(lin, direct)
    if branch(g - tol) * branch(g + tol) <= 0:
        return _crossing_here(lin, direct)            # at g + tol
    for _ in range(POLISH_STEPS if newton else 0):
        g -= value / slope
        if not (math.isfinite(g) and low <= g <= high):
            break
        value = branch(g)
        if abs(value / slope) <= tol:
            return _crossing_here(lin, direct)
    return _exact_crossing(lin, direct, low, high, ref)


def _exact_crossing(lin: Linearisation, direct: DirectImpedance, low: float, high: float,
                    ref: complex) -> Optional[Crossing]:
    """The reference refinement of one bracket, on the exact impedance."""
    g = _refine(direct.roots, low, high, ref)
    if g is None:
        return None
    direct.roots(g)
    return _crossing_here(lin, direct)


def _crossing_here(lin: Linearisation, direct: DirectImpedance) -> Optional[Crossing]:
    """The crossing at the last direct evaluation, with its LU, if its real root is > 0."""
    g, lu, x, z = direct.last
    u = _real_root(mass_roots(z))
    if not u.real > 0:
        return None
    return Crossing(u.real / (g**2 * lin.load), g, (lu, x, z))


#: a Newton step on the whirl ratio below this ends the direct local search (one sparse LU
#: per step): γ and u corrected by it are exact to its square times the curvature (~1e-8) [-]
LOCAL_STEP = 1e-4
#: Newton steps (one sparse LU each) the direct local search may take
LOCAL_STEPS = 6
#: half-width of the whirl-ratio window of the local search's Krylov space (its shift sits
#: over the start, a quarter of the window's width into the right half plane) [-]
LOCAL_WINDOW = 0.05
#: Newton steps on the Krylov model (no LU each) before the local search gives up
MODEL_STEPS = 12


@dataclass(frozen=True)
class LocalCrossing:
    """A crossing found by Newton's method on the whirl ratio from a nearby one: mass M̄ [-],
    whirl γ [-], the real root u = M̄ W̄0 γ² [-] (to follow the branch at the next call) and
    ``factorisations`` (sparse LUs spent)."""

    mass: float
    whirl: float
    root: complex
    factorisations: int


@single_threaded
def local_crossing(lin: Linearisation, whirl: float, root: complex,
                   whirl_range: tuple = (0.02, 1.2),
                   max_steps: int = LOCAL_STEPS) -> Optional[LocalCrossing]:
    """The crossing Im u(γ) = 0 of the root branch through ``root`` near ``whirl``, by
    Newton's method on γ, or None.

    For a neighbour of an operating point whose threshold is known (the onset search's
    speed line): the branch is the root u of u² − u tr Z + det Z = 0 nearest ``root`` (the
    real root there), followed from step to step by continuity.  Z(iγ) comes from a Krylov
    space on one LU of A + s0 B with s0 over ``whirl``
    (:class:`~gfbopt.linear.krylov.ShiftedImpedance` on ±:data:`LOCAL_WINDOW`, converged at
    every γ evaluated to its tolerance, 1e-11), d Im u/dγ from a central difference on it;
    Newton's method runs on that model until its step is below :data:`WHIRL_TOLERANCE` (the
    full threshold's own tolerance on γ), so the crossing equals the full threshold's on the
    same branch to ~1e-10 for one LU (a new space when a step leaves the window).  Where the
    model does not converge, the direct search (:func:`direct_local_crossing`: an LU per
    step) takes over.  None when it does not converge in :data:`MODEL_STEPS` steps, leaves
    ``whirl_range``, or ends on a root with u ≤ 0: the caller then computes the full
    threshold (:func:`gfbopt.linear.linear_threshold`), which also decides between branches
    — this search follows one.  ``max_steps`` bounds the direct search's steps.
    """
    low, high = whirl_range
    gamma, ref = float(whirl), complex(root)
    model, centre, lus = None, math.nan, 0
    for _ in range(MODEL_STEPS):
        if not low <= gamma <= high:
            return None
        if model is None or abs(gamma - centre) > 0.5 * LOCAL_WINDOW:
            try:
                model = ShiftedImpedance(lin, (max(gamma - LOCAL_WINDOW, 0.5 * gamma),
                                               gamma + LOCAL_WINDOW))
            except RuntimeError:                 # A + s0 B exactly singular
                return direct_local_crossing(lin, gamma, ref, whirl_range, max_steps, lus)
            centre, lus = gamma, lus + 1
        points = np.array([gamma - SLOPE_STEP, gamma, gamma + SLOPE_STEP])
        if not model.converge(points[1:2]).all():   # ±1e-6 converge with it
            return direct_local_crossing(lin, gamma, ref, whirl_range, max_steps, lus)
        roots = [mass_roots(model.evaluate(g)[0]) for g in points]
        u = roots[1][np.argmin(np.abs(roots[1] - ref))]
        left, right = (r[np.argmin(np.abs(r - u))] for r in (roots[0], roots[2]))
        du = (right - left) / (2 * SLOPE_STEP)
        if not (math.isfinite(du.imag) and du.imag != 0):
            return None
        step = -u.imag / du.imag
        gamma, ref = gamma + step, u
        if abs(step) <= WHIRL_TOLERANCE:
            u_star = (u + du * step).real
            if not (u_star > 0 and low <= gamma <= high):
                return None
            return LocalCrossing(u_star / (gamma**2 * lin.load), gamma, complex(u_star), lus)
    return None


@single_threaded
def direct_local_crossing(lin: Linearisation, whirl: float, root: complex,
                          whirl_range: tuple = (0.02, 1.2), max_steps: int = LOCAL_STEPS,
                          spent: int = 0) -> Optional[LocalCrossing]:
    """:func:`local_crossing` with Z(iγ) from its own LU of A + iγB at every step, as
    :class:`DirectImpedance`, and with the same LU dZ/dγ = −i F (A+iγB)⁻¹ B X (one more
    solve); then du/dγ = (u tr Z′ − (det Z)′)/(2u − tr Z).  The search ends when the Newton
    step falls below :data:`LOCAL_STEP`; γ and u are then corrected by that step (their error
    is its square).  ``spent`` : LUs already spent (counted in the result)."""
    low, high = whirl_range
    gamma, ref = float(whirl), complex(root)
    for k in range(1, max_steps + 1):
        s = 1j * gamma
        a, b = lin.system(s)
        lu = factor((a + s * b).astype(complex), lin.factoriser)
        x = lu.solve(lin.c_xi.astype(complex))
        z = lin.force @ x
        dz = -1j * (lin.force @ lu.solve((b @ x).astype(complex)))
        roots = mass_roots(z)
        u = roots[np.argmin(np.abs(roots - ref))]
        tr, dtr = z[0, 0] + z[1, 1], dz[0, 0] + dz[1, 1]
        ddet = dz[0, 0] * z[1, 1] + z[0, 0] * dz[1, 1] - dz[0, 1] * z[1, 0] - z[0, 1] * dz[1, 0]
        du = (u * dtr - ddet) / (2 * u - tr)
        if not (math.isfinite(du.imag) and du.imag != 0):
            return None
        step = -u.imag / du.imag
        gamma, ref = gamma + step, u
        if not low <= gamma <= high:
            return None
        if abs(step) <= LOCAL_STEP:
            u_star = (u + du * step).real
            if not u_star > 0:
                return None
            return LocalCrossing(u_star / (gamma**2 * lin.load), gamma, complex(u_star),
                                 spent + k)
    return None
