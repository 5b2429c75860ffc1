"""The linearised bearing: perturbation matrices, impedance and frequency-dependent K and C.

See the package docstring (:mod:`gfbopt.linear`) for the equations, the frame and the treatment
of structural damping.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Iterable, Optional, Sequence

import casadi as ca
import numpy as np
import pandas as pd
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .. import discretisation as disc
from ..errors import ParameterError
from ..inputs.bearing import BearingGeometry
from ..inputs.model import renamed_radian_attribute
from ..inputs.conversions import rpm_to_rad_per_s, stiffness_scale, whirl_frequency_hz
from ..physics.compliance import ComplianceTerms, PerturbationContext
from ..physics.foil_laws import foil_law
from .friction_units import FrictionUnits, friction_rows
from ..static import StaticSolution, StaticSolver, solver_for
from ..static.build import row_values
from ..sparse_lu import Factoriser, factor
from ..threads import single_threaded


@dataclass(frozen=True, eq=False)
class Linearisation:
    """The linearised semi-discrete bearing about one static equilibrium (all non-dimensional).

    a : ∂E/∂y (n × n, sparse);  b : ∂E/∂ẏ (squeeze term, sparse; zero rows are algebraic);
    c_xi : ∂E/∂(X, Y) (n × 2);  force : ∂(F_X, F_Y)/∂y (2 × n);  load : W̄0 [-];
    static : the equilibrium;  compliance : the entries of (a, b) the bump foundation carries
    (None for a rigid bearing);  loss_factor : the foundation's structural loss factor η [-];
    friction : the bumps' spring–slider elements (:class:`~.friction_units.FrictionUnits`,
    None without friction);  deflection_amplitude : |δW| per foil unit at which their
    describing function is taken (None: small orbits, stuck where loaded);
    factoriser : the build's sparse LUs, each pattern's order kept (:mod:`gfbopt.sparse_lu`;
    None: a fresh order for every LU).
    """

    static: StaticSolution
    a: sp.csc_matrix
    b: sp.csc_matrix
    c_xi: np.ndarray
    force: np.ndarray
    load: float
    compliance: Optional[ComplianceTerms] = None
    loss_factor: float = 0.0
    factoriser: Optional[Factoriser] = None
    friction: Optional[FrictionUnits] = None
    deflection_amplitude: Optional[np.ndarray] = None

    @property
    def size(self) -> int:
        return self.a.shape[0]

    @property
    def hysteretic(self) -> bool:
        """True when the foundation's damping is rate independent (η > 0, or friction
        slipping at the stated amplitude): it then depends on sign(Im s)."""
        if self.compliance is None:
            return False
        return self.loss_factor > 0 or (self.friction is not None
                                        and self.deflection_amplitude is not None)

    def stiffness_factor(self, s: complex):
        """k = 1 + iη sign(Im s): the foundation stiffness over its static value at s [-].

        With Coulomb friction (``friction``) one factor per foil unit, the bump's plus the
        friction element's describing function at the unit's deflection amplitude
        (``deflection_amplitude``; None: small orbits, every loaded unit stuck)."""
        sign = float(np.sign(complex(s).imag))
        bump = 1.0 + 1j * self.loss_factor * sign
        if self.friction is None:
            return bump
        return bump + self.friction.factor(self.deflection_amplitude, sign)

    def at_amplitude(self, deflection_amplitude: Optional[np.ndarray]) -> "Linearisation":
        """The same linearisation with the friction elements' describing function evaluated
        at these deflection amplitudes |δW| per foil unit [-] (None: small orbits)."""
        if self.friction is None:
            raise ParameterError("friction_coefficient", 0.0, "must be > 0 for an "
                                 "amplitude-dependent foundation (the bumps have no friction)")
        amp = None if deflection_amplitude is None else np.asarray(deflection_amplitude, float)
        return replace(self, deflection_amplitude=amp)

    def system(self, s: complex, stiffness_factor: Optional[complex] = None) -> tuple:
        """(A, B) at complex frequency s: the foundation stiffness is multiplied by
        ``stiffness_factor`` (default :meth:`stiffness_factor` of s; 1 gives (a, b) itself)."""
        k = self.stiffness_factor(s) if stiffness_factor is None else stiffness_factor
        if self.compliance is None or (np.ndim(k) == 0 and k == 1.0):
            return self.a, self.b
        return self.compliance.apply(self.a, self.b, k)


@single_threaded
def linearise(solution: StaticSolution, solver: Optional[StaticSolver] = None) -> Linearisation:
    """Linearise the bearing about ``solution`` (a converged static equilibrium).

    The model's loss factor η (``solution.model.loss_factor``) is carried along; the foil
    law's compliance terms (:class:`~gfbopt.physics.compliance.ComplianceTerms`) are found
    here once, whatever η, so that any foundation stiffness can be applied later.
    """
    if not solution.success:
        raise ParameterError("solution", f"status {solution.status}",
                             "the static equilibrium did not converge; nothing to linearise")
    if solution.eccentricity == 0.0 or not math.isfinite(solution.attitude_angle_rad):
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
    law = foil_law(model, engine="linear")
    s_rows = row_values(model, st, solution.seam_angle_rad)[1]    # S per θ row (bump zones)
    slope = law.squeeze_film_slope(pressure, s_rows[st.row], model.compression_only)
    if slope is not None:
        dp = dp - 2 * lam * pressure * slope
    b = sp.csc_matrix((np.concatenate([dp, -2 * lam * pressure]),
                       (np.concatenate([np.arange(n_u), np.arange(n_u)]),
                        np.concatenate([np.arange(n_u), blocks.film_of_pressure]))),
                      shape=(n, n))
    terms = law.compliance_terms(_perturbation_context(solution, solver, n))
    friction = None
    if getattr(model, "has_friction", False) and terms is not None:
        mu_rows = friction_rows(model, st, solution.seam_angle_rad)
        mu = mu_rows if law.name != "local" else mu_rows[st.row]     # rows, or nodes
        friction = FrictionUnits.of(terms, mu, model.friction_stiffness_ratio)
    return Linearisation(solution, blocks.a, b, blocks.c_xi, blocks.force, solution.load,
                         terms, model.loss_factor, solver.factoriser, friction)


def _perturbation_context(solution: StaticSolution, solver: StaticSolver,
                          n: int) -> PerturbationContext:
    """Where the foil's variables sit in y (the static build's layout) and their values."""
    model, st, lay = solution.model, solver.stencil, solver.layout
    rows = np.arange(st.n_theta_nodes)
    dz = st.axial_spacing(model.length_ratio)
    p_full = solution.pressure.ravel()
    return PerturbationContext(
        compliance=model.compliance, length_ratio=model.length_ratio,
        bearing_number=model.bearing_number, compression_only=bool(model.compression_only),
        size=n, pressure=p_full[st.unknown],
        mean_gauge=disc.axial_integral(p_full, st, dz) / (2 * model.length_ratio),
        film_rows=lay.film.start + rows, axial_cols=lay.axial.start + rows,
        beam=np.arange(lay.beam.start, lay.beam.stop),
        beam_dofs=solution.state[lay.beam], law_data=solver.law_data,
        film_sensitivity=lambda: film_sensitivity(
            st, p_full, solution.film.ravel(), model.bearing_number, dz,
            function=_kept_sensitivity(solver)),
        row_compliance=row_values(model, st, solution.seam_angle_rad)[1], pressure_rows=st.row,
        hardening=((model.hardening_exponent, model.hardening_limit)
                   if getattr(model, "hardening_exponent", 0.0) > 0.0 else None))


def _kept_sensitivity(solver: StaticSolver) -> ca.Function:
    """The :func:`sensitivity_function` of the build's stencil, kept with the build."""
    function = solver.derived.get("film_sensitivity")
    if function is None:
        function = solver.derived["film_sensitivity"] = sensitivity_function(solver.stencil)
    return function


def sensitivity_function(st: disc.Stencil) -> ca.Function:
    """(P, H at the five nodes, Λ, ΔZ) ↦ ∂R/∂H at the centre node, mapped over the
    unknown nodes of ``st``: :func:`gfbopt.discretisation.reynolds_residual` on a one-node
    stencil (centre, east, west, north, south), differentiated by CasADi."""
    one = replace(st, unknown=np.array([0]), east=np.array([1]), west=np.array([2]),
                  north=np.array([3]), south=np.array([4]))
    p5, h5, lam, d = ca.SX.sym("p", 5), ca.SX.sym("h", 5), ca.SX.sym("lam"), ca.SX.sym("dz")
    jac = ca.jacobian(disc.reynolds_residual(p5, h5, one, lam, d), h5)
    return ca.Function("dR_dH", [p5, h5, lam, d], [jac]).map(st.n_unknown)


def film_sensitivity(st: disc.Stencil, p_full: np.ndarray, h_full: np.ndarray,
                     bearing_number: float, dz: float,
                     function: Optional[ca.Function] = None) -> sp.csr_matrix:
    """∂R/∂H of the steady discrete Reynolds residual, unknown nodes × unknown nodes [-].

    R is :func:`gfbopt.discretisation.reynolds_residual` itself, differentiated by CasADi on a
    one-node stencil (centre, east, west, north, south) and evaluated at every unknown node,
    so the derivative comes from the one definition of the film physics.  Columns of nodes
    with a fixed pressure (seam, axial edges) are dropped: the local law's foil moves only
    where P is unknown.  p_full, h_full : P and H at every node (flat) [-]; dz : ΔZ [-];
    function : :func:`sensitivity_function` of ``st`` when kept (the linearisation keeps it
    with the static build; building it costs more than evaluating it).
    """
    n_u = st.n_unknown
    nodes = np.vstack([st.unknown, st.east, st.west, st.north, st.south])   # (5, n_u)
    f = sensitivity_function(st) if function is None else function
    values = np.asarray(f(p_full[nodes], h_full[nodes], bearing_number, dz)).reshape(n_u, 5)
    position = np.full(st.n_nodes, -1)
    position[st.unknown] = np.arange(n_u)
    cols = position[nodes.T]                                                 # (n_u, 5)
    keep = cols >= 0
    rows = np.repeat(np.arange(n_u), 5).reshape(n_u, 5)
    return sp.csr_matrix((values[keep], (rows[keep], cols[keep])), shape=(n_u, n_u))


@single_threaded
def impedance(lin: Linearisation, s: complex,
              stiffness_factor: Optional[complex] = None) -> np.ndarray:
    """Z(s) = f (A + sB)⁻¹ C_ξ, the 2 × 2 complex impedance at complex frequency s [-].

    The foundation stiffness is hysteretic, k (1 + iη sign(Im s)) (module docstring), unless
    ``stiffness_factor`` (a complex number multiplying the foundation stiffness) is given.
    """
    a, b = lin.system(s, stiffness_factor)
    lu = factor((a + s * b).astype(complex), lin.factoriser)
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
    #: attitude angle of the static solution [rad] (the numerics' unit; see attitude_angle_deg)
    attitude_angle_rad: float

    def __getattr__(self, name: str):
        raise renamed_radian_attribute(type(self).__name__, name)

    @property
    def attitude_angle_deg(self) -> float:
        """Attitude angle of the static solution, from the load line [deg]."""
        return math.degrees(self.attitude_angle_rad)

    def in_line_of_centres_frame(self) -> "Coefficients":
        """The same coefficients with axes (r along the line of centres, t ahead of it)."""
        c, s = math.cos(self.attitude_angle_rad), math.sin(self.attitude_angle_rad)
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


@single_threaded
def coefficients(lin: Linearisation, whirl_ratios: Sequence[float]) -> Coefficients:
    """K̄(γ) and C̄(γ) at each whirl ratio γ ≥ 0 in one call.

    One sparse complex LU of A + iγB per γ (the matrix changes with γ; reusing SuperLU's
    symbolic analysis across γ was measured to be slower, benchmarks/bench_linear.py).  At
    γ = 0 the stiffness is the static derivative f A⁻¹ C_ξ and the damping its exact limit
    dZ/ds = −f A⁻¹ B A⁻¹ C_ξ, from one real LU of A.  With structural damping (η > 0) the
    damping at γ = 0 is NaN: the hysteretic foundation's damping η k/γ is unbounded as
    γ → 0 (its stiffness there is the undamped static one).
    """
    g = _check_whirl(whirl_ratios)
    k = np.empty((g.size, 2, 2))
    c = np.empty((g.size, 2, 2))
    for n, gamma in enumerate(g):
        if gamma == 0.0:
            # the zero-frequency foundation: the bump's, plus the friction elements' in-phase
            # stiffness (real at sign 0) when the bumps rub
            a0, b0 = ((lin.a, lin.b) if lin.friction is None else
                      (_real_part(m) for m in lin.system(0.0)))
            lu = spla.splu(a0.tocsc())
            y0 = lu.solve(lin.c_xi)
            k[n] = lin.force @ y0
            c[n] = math.nan if lin.hysteretic else -(lin.force @ lu.solve(b0 @ y0))
        else:
            z = impedance(lin, 1j * gamma)
            k[n], c[n] = z.real, z.imag / gamma
    return Coefficients(g, k, c, lin.static.attitude_angle_rad)


def _real_part(m: sp.spmatrix) -> sp.csc_matrix:
    """The real part of a sparse matrix as its own contiguous csc matrix (SuperLU refuses the
    strided view that ``m.real`` holds)."""
    m = sp.csc_matrix(m)
    return sp.csc_matrix((np.ascontiguousarray(m.data.real), m.indices.copy(), m.indptr.copy()),
                         shape=m.shape)


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
