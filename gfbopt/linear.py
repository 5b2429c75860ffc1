"""Linearised dynamics: frequency-dependent stiffness and damping, and the linear threshold.

Small harmonic journal motion ξ = (δX, δY) e^{sτ} about a static equilibrium (s = iγ for a
whirl at γ times the shaft speed).  The semi-discrete equations of the static model
(:mod:`gfbopt.static`) with the squeeze term of the time-dependent Reynolds equation,

    E(y, ξ) − 2Λ ∂(P H)/∂τ = 0       at the unknown pressure nodes,
    the lifted algebraic equations    (film, axial integrals, beam, force sums),

are linearised about the static state y0: (A + s B) ŷ = −C_ξ ξ, where A = ∂E/∂y (IPOPT's own
Jacobian of the static problem), B = ∂(−2Λ ∂(PH)/∂τ)/∂ẏ and C_ξ = ∂E/∂ξ.  The foil enters
through the algebraic rows, so it responds quasi-statically through its compliance (simple,
local or beam law).  The film-force perturbation is ΔF = f·ŷ and the impedance

    Z(s) = −ΔF/ξ = f (A + s B)⁻¹ C_ξ,        Z(iγ) = K(γ) + iγ C(γ)

gives the non-dimensional stiffness K̄ = K c/(p_a R²) and damping C̄ = C c ω/(p_a R²) in the
load frame (X along the static load, Y ahead of it in the direction of rotation).

Rigid rotor (mass M per bearing, M̄ = M c ω²/W0): M̄ W̄0 ξ'' = ΔF, i.e.
det(M̄ W̄0 s² I + Z(s)) = 0.  At the threshold s = iγ: with u = M̄ W̄0 γ², u² − u tr Z + det Z = 0
must have a real positive root u; M̄_crit = u/(γ² W̄0).

A seam that follows the maximum-film line in the static solution (``seam_angle=None``) is frozen
at its static position for the perturbation: the top foil is fixed in the housing.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Iterable, Optional, Sequence

import numpy as np
import pandas as pd
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.optimize import brentq

from .errors import ConvergenceError, ParameterError
from .inputs.bearing import BearingGeometry
from .inputs.conversions import rpm_to_rad_per_s, stiffness_scale, whirl_frequency_hz
from .physics.foil_laws import foil_law
from .static import StaticSolution, StaticSolver, solver_for


@dataclass(frozen=True, eq=False)
class Linearisation:
    """The linearised semi-discrete bearing about one static equilibrium (all non-dimensional).

    a : ∂E/∂y (n × n, sparse);  b : ∂E/∂ẏ (squeeze term, sparse; zero rows are algebraic);
    c_xi : ∂E/∂(X, Y) (n × 2);  force : ∂(F_X, F_Y)/∂y (2 × n);  load : W̄0 [-];
    static : the equilibrium.
    """

    static: StaticSolution
    a: sp.csc_matrix
    b: sp.csc_matrix
    c_xi: np.ndarray
    force: np.ndarray
    load: float

    @property
    def size(self) -> int:
        return self.a.shape[0]


def linearise(solution: StaticSolution, solver: Optional[StaticSolver] = None) -> Linearisation:
    """Linearise the bearing about ``solution`` (a converged static equilibrium)."""
    if not solution.success:
        raise ParameterError("solution", f"status {solution.status}",
                             "the static equilibrium did not converge; nothing to linearise")
    if solution.eccentricity == 0.0 or not math.isfinite(solution.attitude_angle):
        raise ParameterError("solution.eccentricity", solution.eccentricity,
                             "must be > 0: a concentric journal carries no load (W0 = 0), so "
                             "M̄ = M c ω²/W0 is undefined")
    model = solution.model
    if solver is None:
        solver = solver_for(model, solution.grid)
    elif not solver.matches(model, solution.grid):
        raise ParameterError("solver", f"{solver.film} film, {solver.law.name} structure",
                             "was not built for this solution's grid and formulation")
    blocks = solver.perturbation_blocks(solution)
    n = blocks.a.shape[0]
    # Squeeze term −2Λ (H Ṗ + P Ḣ) at the unknown pressure nodes; Ḣ is the lifted film's
    # rate, plus (local law) the foil following the node's own pressure.
    lam = model.bearing_number
    st = solver.stencil
    pressure = solution.pressure.ravel()[st.unknown]
    film = solution.film.ravel()[st.unknown]
    n_u = blocks.n_pressure
    dp = -2 * lam * film
    slope = foil_law(model).squeeze_film_slope(pressure, model.compliance,
                                                model.compression_only)
    if slope is not None:
        dp = dp - 2 * lam * pressure * slope
    b = sp.csc_matrix((np.concatenate([dp, -2 * lam * pressure]),
                       (np.concatenate([np.arange(n_u), np.arange(n_u)]),
                        np.concatenate([np.arange(n_u), blocks.film_of_pressure]))),
                      shape=(n, n))
    return Linearisation(solution, blocks.a, b, blocks.c_xi, blocks.force, solution.load)


def impedance(lin: Linearisation, s: complex) -> np.ndarray:
    """Z(s) = f (A + sB)⁻¹ C_ξ, the 2 × 2 complex impedance at complex frequency s [-]."""
    lu = spla.splu((lin.a + s * lin.b).astype(complex).tocsc())
    return lin.force @ lu.solve(lin.c_xi.astype(complex))


@dataclass(frozen=True, eq=False)
class Coefficients:
    """Stiffness and damping at a list of whirl ratios (non-dimensional, load frame).

    whirl_ratio γ [-] (n,); stiffness K̄ (n, 2, 2) = K c/(p_a R²); damping C̄ (n, 2, 2) =
    C c ω/(p_a R²); index order [X, Y] with X along the load.
    """

    whirl_ratio: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    attitude_angle: float

    def in_line_of_centres_frame(self) -> "Coefficients":
        """The same coefficients with axes (r along the line of centres, t ahead of it)."""
        c, s = math.cos(self.attitude_angle), math.sin(self.attitude_angle)
        rot = np.array([[c, -s], [s, c]])       # columns: r and t in load-frame components
        tr = lambda m: np.einsum("ji,njk,kl->nil", rot, m, rot)  # noqa: E731  Rᵀ M R
        return Coefficients(self.whirl_ratio, tr(self.stiffness), tr(self.damping), 0.0)

    def to_frame(self) -> pd.DataFrame:
        """One row per whirl ratio: kxx, kxy, kyx, kyy, cxx, … (non-dimensional)."""
        rec = {"whirl_ratio": self.whirl_ratio}
        for i, a in enumerate("xy"):
            for j, b in enumerate("xy"):
                rec[f"k{a}{b}"] = self.stiffness[:, i, j]
                rec[f"c{a}{b}"] = self.damping[:, i, j]
        return pd.DataFrame(rec)


def _check_whirl(values: Iterable[float]) -> np.ndarray:
    g = np.atleast_1d(np.asarray(list(values) if not np.isscalar(values) else [values],
                                 dtype=float))
    for v in g:
        if not math.isfinite(v) or v < 0:
            raise ParameterError("whirl_ratio", float(v), "must be finite and >= 0")
    return g


def coefficients(lin: Linearisation, whirl_ratios: Sequence[float]) -> Coefficients:
    """K̄(γ) and C̄(γ) at each whirl ratio γ ≥ 0 in one call.

    One sparse complex LU of A + iγB per γ (the matrix changes with γ; reusing SuperLU's
    symbolic analysis across γ was measured to be slower, benchmarks/bench_linear.py).  At
    γ = 0 the stiffness is the static derivative f A⁻¹ C_ξ and the damping its exact limit
    dZ/ds = −f A⁻¹ B A⁻¹ C_ξ, from one real LU of A.
    """
    g = _check_whirl(whirl_ratios)
    k = np.empty((g.size, 2, 2))
    c = np.empty((g.size, 2, 2))
    for n, gamma in enumerate(g):
        if gamma == 0.0:
            lu = spla.splu(lin.a.tocsc())
            y0 = lu.solve(lin.c_xi)
            k[n] = lin.force @ y0
            c[n] = -(lin.force @ lu.solve(lin.b @ y0))
        else:
            z = impedance(lin, 1j * gamma)
            k[n], c[n] = z.real, z.imag / gamma
    return Coefficients(g, k, c, lin.static.attitude_angle)


# -------------------------------------------------------------------- stability
@dataclass(frozen=True)
class LinearThreshold:
    """Linear stability threshold of the rigid rotor.

    critical_mass : M̄_crit = M c ω²/W0 [-] (inf if stable for every mass)
    whirl_ratio : whirl frequency over shaft speed at the threshold [-] (nan if none)
    stable_for_all_masses : True when no real threshold exists on (0, γ_max)
    message, evaluations (impedance solves), wall_time_s
    """

    critical_mass: float
    whirl_ratio: float
    stable_for_all_masses: bool
    message: str
    evaluations: int
    wall_time_s: float

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
    (Im u = 0 with Re u > 0) and refines with Brent's method; the smallest such mass is the
    threshold (the rotor is stable below it).
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
    elapsed = time.perf_counter() - t0
    if not candidates:
        return LinearThreshold(math.inf, math.nan, True,
                               f"no real threshold for whirl ratios in {whirl_range}: "
                               "stable for every rotor mass", count[0], elapsed)
    mass, gamma = min(candidates)
    return LinearThreshold(mass, gamma, False, "", count[0], elapsed)


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

    States v = (y, ξ, η = ξ'):  B y' = −A y − C_ξ ξ,  ξ' = η,  M̄W̄0 η' = f·y.
    An independent check of :func:`linear_threshold` (no impedance, no root finding).
    """
    m = _check_positive_mass(mass) * lin.load
    n = lin.size
    zero = sp.csc_matrix((n, 2))
    jac = sp.bmat([[-lin.a, sp.csc_matrix(-lin.c_xi), zero],
                   [sp.csc_matrix((2, n)), None, sp.identity(2)],
                   [sp.csc_matrix(lin.force), sp.csc_matrix((2, 2)), None]], format="csc")
    e = sp.block_diag([lin.b, sp.identity(2), m * sp.identity(2)], format="csc")
    lu = spla.splu((jac - shift * e).astype(complex).tocsc())
    op = spla.LinearOperator(jac.shape, matvec=lambda v: lu.solve(e @ v), dtype=complex)
    mu = spla.eigs(op, k=count, which="LM", return_eigenvectors=False, tol=1e-12)
    return shift + 1.0 / mu


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


# ------------------------------------------------------------- dimensional output
def dimensional_coefficients(coeffs: Coefficients, geometry: BearingGeometry,
                             speed_rpm: float) -> pd.DataFrame:
    """K [N/m] and C [N s/m] against excitation frequency [Hz] (load frame).

    K = K̄ p_a R²/c, C = C̄ p_a R²/(c ω), f = γ ω/(2π).
    """
    omega = rpm_to_rad_per_s(speed_rpm)
    scale_k = stiffness_scale(geometry.ambient_pressure, geometry.radius,
                              geometry.radial_clearance)
    frame = {"speed_rpm": speed_rpm, "whirl_ratio": coeffs.whirl_ratio,
             "frequency_hz": whirl_frequency_hz(coeffs.whirl_ratio, omega)}
    for i, a in enumerate("xy"):
        for j, b in enumerate("xy"):
            frame[f"k{a}{b}_N_per_m"] = coeffs.stiffness[:, i, j] * scale_k
    for i, a in enumerate("xy"):
        for j, b in enumerate("xy"):
            frame[f"c{a}{b}_Ns_per_m"] = coeffs.damping[:, i, j] * scale_k / omega
    return pd.DataFrame(frame)
