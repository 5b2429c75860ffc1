"""Static equilibrium of a journal in a gas foil bearing: CasADi model, IPOPT solve.

The discrete Reynolds equation (:mod:`gfbopt.discretisation`), the foil law
(:mod:`gfbopt.foil`) and the force balance are assembled once per grid and formulation as
CasADi SX expressions; the operating values (Λ, S, C, L/D, the eccentricity or load, the seam
angle and the model switches) are CasADi *parameters*, so one build serves a whole sweep.

Frame and conventions
---------------------
X lies along the static load (the direction the load pushes the journal), θ is measured from
+X in the direction of rotation.  The journal centre sits at (X, Y) = ε (cos φ, sin φ), φ the
attitude angle, so the film is H = 1 − ε cos(θ − φ) + W, thickest at θ = π + φ.  The film
force on the journal is F = −∬ (P − 1)(cos θ, sin θ) dθ dZ (per p_a R²); equilibrium is
F_X + W̄ = 0, F_Y = 0.  The grid starts at the seam (the welded end of the top foil) at
θ = θ_s: either an input angle from the load line, or θ_s = π + φ (the thesis's convention,
seam on the maximum-film line).

Unknowns (``x``): P at interior nodes; lifted per-θ-row H (or its rigid part for the local
law), Q_i = ∫(P − 1) dZ and the force integrand Q^F_i; the beam's free Hermite dofs; ε and φ.
Lifting the axial integrals and the film geometry keeps the Jacobian sparse, which is what
makes the symbolic build take well under a second (PHYSICS.md).  Equations (``g``): Reynolds at
the unknown nodes, the lifting definitions, the beam equations, and two closing equations:
``mode·(F_X + W̄) + (1 − mode)(ε − ε_given) = 0`` and ``F_Y = 0``.  IPOPT solves this square
system (zero objective) keeping P > 0 and H > 0 by bounds.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Optional

import casadi as ca
import numpy as np
import scipy.sparse as sp

from . import discretisation as disc
from .errors import ConvergenceError, ParameterError
from .inputs.checks import check_finite, check_positive
from .inputs.grid import DEFAULT_GRID, Grid
from .inputs.model import FILM_MODELS, BearingModel
from .physics.closed_forms import first_order_pressure, small_eccentricity_limit
from .physics.film import force_gauge, rigid_film_polar
from .physics.foil_laws import FOIL_LAWS, FoilParameters, static_structure

PARAMETERS = ("bearing_number", "compliance", "top_foil_coefficient", "length_ratio",
              "load_mode", "target", "seam_angle", "seam_follows", "compression_only", "gumbel",
              "position_mode", "attitude_target")

#: residual tolerance on the Reynolds and force equations accepted as converged [-]
RESIDUAL_TOLERANCE = 1e-7


def _default_ipopt_options() -> dict:
    return {
        "ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
        "ipopt.tol": 1e-10, "ipopt.constr_viol_tol": 1e-10, "ipopt.acceptable_iter": 0,
        "ipopt.hessian_approximation": "exact",
        "ipopt.max_iter": 60, "ipopt.bound_push": 1e-10, "ipopt.bound_frac": 1e-10,
        "ipopt.mu_init": 1e-6, "ipopt.nlp_scaling_method": "none",
        "ipopt.linear_solver": "mumps",
    }


@dataclass(frozen=True)
class Layout:
    """Where each block of unknowns sits in the solver's vector ``x`` (slices)."""

    pressure: slice
    film: slice
    axial: slice
    force: slice
    beam: slice
    partial_sums: slice
    eccentricity: int
    attitude: int
    size: int


@dataclass(frozen=True, eq=False)
class PerturbationBlocks:
    """The static model's equations g(y, ξ) = 0 seen from the linearisation (all [-]).

    a : ∂g/∂y (sparse); c_xi : ∂g/∂(X, Y) (n × 2); force : ∂(F_X, F_Y)/∂y (2 × n);
    n_pressure : the unknown pressures are y[:n_pressure] (in the stencil's order);
    film_of_pressure : index in y of the lifted film of each unknown pressure node's row.
    """

    a: sp.csc_matrix
    c_xi: np.ndarray
    force: np.ndarray
    n_pressure: int
    film_of_pressure: np.ndarray


class StaticSolver:
    """The CasADi/IPOPT equilibrium problem for one grid, film type and foil structure.

    Build it once and reuse it for every operating point of a sweep: Λ, S, C, L/D, the seam
    angle, the eccentricity or load and the compression-only and Gümbel switches are
    parameters.  Not thread-safe (IPOPT/MUMPS): use one per process.

    Parameters
    ----------
    grid : the finite-difference grid
    film : 'periodic' or 'seam'
    foil_law : the static structure, a law of :mod:`gfbopt.physics.foil_laws` with its own
        model: 'simple' (also serves rigid models, S = 0), 'local' or 'beam'
    ipopt_options : overrides of the IPOPT options (CasADi ``nlpsol`` keys)
    """

    def __init__(self, grid: Grid = DEFAULT_GRID, film: str = "periodic",
                 foil_law: str = "simple", ipopt_options: Optional[dict] = None):
        t0 = time.perf_counter()
        if film not in FILM_MODELS:
            raise ParameterError("film", film, f"must be one of {', '.join(FILM_MODELS)}")
        structures = sorted({law.static_structure for law in FOIL_LAWS.values()})
        if foil_law not in structures:
            raise ParameterError("foil_law", foil_law, "must be one of "
                                 f"{', '.join(structures)} (rigid models use 'simple')")
        self.grid = grid
        self.film = film
        self.law = FOIL_LAWS[foil_law]
        st = disc.make_stencil(grid, periodic=(film == "periodic"))
        self.stencil = st
        m = st.n_theta_nodes
        self.law_data = self.law.prepare(grid, st.dpsi)
        n_beam = self.law.extra_unknowns(grid)

        par = ca.SX.sym("p", len(PARAMETERS))
        (lam, s, c, ld, mode, target, seam_angle, follows, comp, gumbel,
         position, attitude_target) = ca.vertsplit(par)
        pu = ca.SX.sym("P", st.n_unknown)
        hr = ca.SX.sym("H", m)
        q = ca.SX.sym("Q", m)
        qf = ca.SX.sym("QF", m)
        u = ca.SX.sym("U", n_beam)
        # Force integrals in the grid's own frame, lifted into block partial sums so that no
        # Jacobian row is dense (dense rows defeat CasADi's colouring: PHYSICS.md).
        blocks = np.array_split(np.arange(m), max(1, int(round(math.sqrt(m)))))
        self._blocks = blocks
        sums = ca.SX.sym("FS", 2 * len(blocks))
        ecc = ca.SX.sym("eps")
        phi = ca.SX.sym("phi")
        x = ca.vertcat(pu, hr, q, qf, u, sums, ecc, phi)
        o = 0
        sl = []
        for size in (st.n_unknown, m, m, m, n_beam, 2 * len(blocks)):
            sl.append(slice(o, o + size))
            o += size
        self.layout = Layout(*sl, eccentricity=o, attitude=o + 1, size=o + 2)

        dz = st.axial_spacing(ld)
        p_full = ca.SX.ones(st.n_nodes)
        p_full[st.unknown.tolist()] = pu
        theta_seam = follows * (math.pi + phi) + (1 - follows) * seam_angle
        theta = theta_seam + ca.DM(st.psi)
        h_rigid = rigid_film_polar(ecc, phi, theta)
        mean_gauge = q / (2 * ld)
        h_nodes, film_eq, foil_eq = self.law.static_film(
            h_rigid, hr, mean_gauge, p_full, u, FoilParameters(s, c, comp), st, self.law_data)
        reynolds = disc.reynolds_residual(p_full, h_nodes, st, lam, dz)
        force_p = 1 + force_gauge(p_full - 1, gumbel)
        equations = [reynolds, film_eq, q - disc.axial_integral(p_full, st, dz),
                     qf - disc.axial_integral(force_p, st, dz)]
        if foil_eq is not None:
            equations.append(foil_eq)
        # F = −Σ w (cos θ, sin θ) Q^F with θ = θ_s + ψ: partial sums of the ψ-frame force
        # components A = −Σ w cos ψ Q^F and B = −Σ w sin ψ Q^F, then a rotation by θ_s.
        w = st.theta_weight
        nb = len(blocks)
        part = [disc.film_forces(qf[b.tolist()], st.psi[b], w[b]) for b in blocks]
        part = [sums[k] - f[0] for k, f in enumerate(part)] + [
            sums[nb + k] - f[1] for k, f in enumerate(part)]
        equations.append(ca.vertcat(*part))
        fa, fb = ca.sum1(sums[:nb]), ca.sum1(sums[nb:])
        fx = ca.cos(theta_seam) * fa - ca.sin(theta_seam) * fb
        fy = ca.sin(theta_seam) * fa + ca.cos(theta_seam) * fb
        equations += [mode * (fx + target) + (1 - mode) * (ecc - target),
                      position * (phi - attitude_target) + (1 - position) * fy]
        g = ca.vertcat(*equations)
        opts = _default_ipopt_options()
        opts.update(ipopt_options or {})
        if opts.get("ipopt.hessian_approximation") == "exact" and "hess_lag" not in opts:
            # A square system needs no curvature: with J nonsingular the Newton step is fixed
            # by the constraints alone, so IPOPT gets an empty Hessian of the Lagrangian (this
            # avoids both the symbolic Hessian build and the L-BFGS extra solves).
            lam_f, lam_g = ca.SX.sym("lam_f"), ca.SX.sym("lam_g", g.shape[0])
            opts["hess_lag"] = ca.Function(
                "zero_hessian", [x, par, lam_f, lam_g],
                [ca.SX(ca.Sparsity(x.shape[0], x.shape[0]))],
                ["x", "p", "lam_f", "lam_g"], ["triu_hess_gamma_x_x"])
        self._nlp = ca.nlpsol("gfbopt_static", "ipopt", {"x": x, "p": par, "f": 0, "g": g}, opts)
        self.n_equations = g.shape[0]
        self._symbols = (x, par, g)
        #: g(x, p): the discrete equations as a CasADi Function (for checks and linearisation)
        self.residual_function = ca.Function("static_residual", [x, par], [g], ["x", "p"], ["g"])
        lbx = -np.inf * np.ones(self.layout.size)
        ubx = np.inf * np.ones(self.layout.size)
        lbx[self.layout.pressure] = 1e-6
        if self.law.lifted_film_is_total:
            lbx[self.layout.film] = 1e-6
        lbx[self.layout.eccentricity] = 0.0
        lbx[self.layout.attitude] = -0.5 * math.pi
        ubx[self.layout.attitude] = math.pi
        self._lbx, self._ubx = lbx, ubx
        self.build_time_s = time.perf_counter() - t0

    def jacobian_function(self) -> ca.Function:
        """(x, p) ↦ (g, dg/dx): IPOPT's own sparse constraint Jacobian (no rebuild)."""
        return self._nlp.get_function("nlp_jac_g")

    def parameters(self, model: BearingModel, load_mode: bool, target: float,
                   attitude: Optional[float] = None,
                   seam_angle: Optional[float] = None) -> np.ndarray:
        """The parameter vector of ``model`` for a given eccentricity or load.

        ``attitude`` [rad] fixes the journal position too (forces at a given position);
        ``seam_angle`` [rad] overrides the model's seam (used to freeze a following seam).
        """
        seam = model.seam_angle if seam_angle is None else seam_angle
        follows = seam is None
        return np.array([model.bearing_number, model.compliance, model.top_foil_coefficient,
                         model.length_ratio, float(load_mode), target,
                         0.0 if follows else seam, float(follows),
                         float(model.compression_only), float(model.subambient == "gumbel"),
                         float(attitude is not None),
                         0.0 if attitude is None else float(attitude)])

    @property
    def key(self) -> tuple:
        """(grid, film, static structure): what this build can solve (:func:`solver_key`)."""
        return (self.grid, self.film, self.law.name)

    def matches(self, model: BearingModel, grid: Grid) -> bool:
        """True if this build can solve ``model`` on ``grid``."""
        return self.key == solver_key(model, grid)

    def perturbation_blocks(self, solution: "StaticSolution") -> "PerturbationBlocks":
        """What the linearisation needs from this build about ``solution`` (its own layout
        stays private): the Jacobian of the equations in y = every variable except ε and φ,
        with the seam frozen where the static solution put it (the top foil is fixed in the
        housing), how the journal position enters, and the film-force map.
        """
        lay, st = self.layout, self.stencil
        n = lay.eccentricity
        p = self.parameters(solution.model, False, solution.eccentricity,
                            solution.attitude_angle, seam_angle=solution.seam_angle)
        _, jac = self.jacobian_function()(solution.state, p)
        a = sp.csc_matrix(jac.sparse())[:n, :n].tocsc()
        # Only the lifted film rows depend on the journal: their equation is
        # H − H_r − W = 0 (or H − H_r for the local law), H_r = 1 − X cos θ − Y sin θ.
        film_rows = np.arange(lay.film.start, lay.film.stop)
        c_xi = np.zeros((n, 2))
        c_xi[film_rows, 0] = np.cos(solution.theta)
        c_xi[film_rows, 1] = np.sin(solution.theta)
        # F_X = cos θ_s ΣA_k − sin θ_s ΣB_k, F_Y = sin θ_s ΣA_k + cos θ_s ΣB_k (partial sums)
        sums = np.arange(lay.partial_sums.start, lay.partial_sums.stop)
        nb = sums.size // 2
        ts = solution.seam_angle
        force = np.zeros((2, n))
        force[0, sums[:nb]], force[0, sums[nb:]] = math.cos(ts), -math.sin(ts)
        force[1, sums[:nb]], force[1, sums[nb:]] = math.sin(ts), math.cos(ts)
        return PerturbationBlocks(a, c_xi, force, st.n_unknown,
                                  lay.film.start + st.row)

    def run(self, x0: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, dict]:
        """One IPOPT solve from ``x0``; returns (x, stats)."""
        sol = self._nlp(x0=x0, p=p, lbx=self._lbx, ubx=self._ubx, lbg=0, ubg=0)
        return np.asarray(sol["x"]).ravel(), self._nlp.stats()


def solver_key(model: BearingModel, grid: Grid) -> tuple:
    """The one definition of which build serves ``model`` on ``grid``: (grid, film, structure).

    Λ, S, C, L/D, the seam angle, the eccentricity or load and the compression-only and
    Gümbel switches are parameters of a build, so they are not part of the key.
    """
    return (grid, model.film, static_structure(model))


def solver_for(model: BearingModel, grid: Grid = DEFAULT_GRID, **kwargs) -> StaticSolver:
    """Build the :class:`StaticSolver` that fits ``model`` on ``grid``."""
    _, film, structure = solver_key(model, grid)
    return StaticSolver(grid, film=film, foil_law=structure, **kwargs)


class SolverCache:
    """One :class:`StaticSolver` per (grid, film, structure), built on first use.

    Use one per process (IPOPT is not thread-safe; builds cannot be pickled): a sweep, a
    study or a worker process keeps one and calls ``cache(model, grid)`` for every point.
    """

    def __init__(self, grid: Grid = DEFAULT_GRID):
        self.grid = grid
        self._solvers: dict = {}

    def __call__(self, model: BearingModel, grid: Optional[Grid] = None) -> StaticSolver:
        key = solver_key(model, grid or self.grid)
        if key not in self._solvers:
            self._solvers[key] = solver_for(model, key[0])
        return self._solvers[key]

    def __len__(self) -> int:
        return len(self._solvers)


# ------------------------------------------------------------------------ results
@dataclass(frozen=True, eq=False)
class StaticSolution:
    """A static equilibrium and its diagnostics.

    Scalars are non-dimensional (load W̄ = W/(p_a R²), film H = h/c), angles in radians.
    Arrays: ``theta`` [rad, from the load line, direction of rotation] at the θ nodes,
    ``z`` [-] at the axial nodes, ``pressure`` P of shape (n_theta_nodes, n_z + 1),
    ``film`` H and ``deflection`` W of the same shape, ``mean_pressure`` P̄ per θ node.
    """

    model: BearingModel
    grid: Grid
    eccentricity: float
    attitude_angle: float
    load: float
    force: tuple
    min_film: float
    min_film_angle: float
    seam_angle: float
    theta: np.ndarray
    z: np.ndarray
    pressure: np.ndarray
    film: np.ndarray
    deflection: np.ndarray
    success: bool
    status: str
    iterations: int
    residual: float
    force_residual: float
    solve_time_s: float
    state: np.ndarray = field(repr=False)
    message: str = ""

    @property
    def mean_pressure(self) -> np.ndarray:
        """Axially averaged pressure P̄ at each θ node [-]."""
        w = disc.trapezoid_weights(self.z.size)
        return self.pressure @ w / w.sum()

    @property
    def theta_from_seam(self) -> np.ndarray:
        """θ-node angles measured from the welded end of the top foil, in [0, 2π] [rad].

        With a seam film the first node is the welded end (0) and the last the free end (2π).
        """
        return self.theta - self.seam_angle

    @property
    def min_film_angle_from_seam(self) -> float:
        """Angle of the minimum film from the welded end, in [0, 2π) [rad]."""
        return float(np.mod(self.min_film_angle - self.seam_angle, 2 * math.pi))

    def to_dict(self) -> dict:
        """Scalar results as a flat dict (angles in degrees) for JSON and DataFrames."""
        return {
            "eccentricity": self.eccentricity,
            "attitude_angle_deg": math.degrees(self.attitude_angle),
            "load": self.load,
            "force_x": self.force[0], "force_y": self.force[1],
            "min_film": self.min_film,
            "min_film_angle_deg": math.degrees(self.min_film_angle) % 360.0,
            "min_film_angle_from_seam_deg": math.degrees(self.min_film_angle_from_seam),
            "max_mean_pressure": float(self.mean_pressure.max()),
            "max_deflection": float(self.deflection.max()),
            "success": self.success, "status": self.status, "iterations": self.iterations,
            "residual": self.residual, "force_residual": self.force_residual,
            "solve_time_s": self.solve_time_s,
        }


# ------------------------------------------------------------------- initial guess
def _cold_guess(solver: StaticSolver, model: BearingModel, eccentricity: float,
                attitude: Optional[float] = None) -> np.ndarray:
    """A starting point: Ausman's first-order pressure and every lifted variable consistent."""
    st = solver.stencil
    _, phi0 = small_eccentricity_limit(model)
    # The attitude angle falls roughly like (1 − ε²) as the film closes (cf. the short-bearing
    # law tan φ = π √(1 − ε²)/(4ε)); compliance delays the closing.
    closing = min(eccentricity / (1.0 + model.compliance), 0.95)
    phi0 = min(max(phi0 * (1.0 - closing**2), 0.05), 1.5) if attitude is None else attitude
    seam = math.pi + phi0 if model.seam_angle is None else model.seam_angle
    theta = seam + st.psi
    shrink = 1.0 / (1.0 + model.compliance)       # a compliant film carries less pressure
    p = first_order_pressure(model, st.z_nodes(model.length_ratio), theta - phi0 - math.pi,
                             min(eccentricity, 0.8) * shrink).ravel()
    p_full = np.ones(st.n_nodes)
    p_full[st.unknown] = np.maximum(p[st.unknown], 0.05)
    return consistent_state(solver, model, p_full, eccentricity, phi0)


def consistent_state(solver: StaticSolver, model: BearingModel, p_full: np.ndarray,
                     eccentricity: float, attitude: float) -> np.ndarray:
    """The solver vector x for a pressure field, ε and φ [rad], with every lifted variable
    (film, axial integrals, beam dofs, force partial sums) computed to match."""
    st, lay = solver.stencil, solver.layout
    seam = math.pi + attitude if model.seam_angle is None else model.seam_angle
    theta = seam + st.psi
    dz = st.axial_spacing(model.length_ratio)
    q = disc.axial_integral(p_full, st, dz)
    qf = disc.axial_integral(1 + force_gauge(p_full - 1, model.subambient == "gumbel"), st, dz)
    mean_gauge = q / (2 * model.length_ratio)
    x = np.zeros(lay.size)
    x[lay.pressure] = p_full[st.unknown]
    h_rigid = rigid_film_polar(eccentricity, attitude, theta)
    x[lay.film], x[lay.beam] = solver.law.start(h_rigid, mean_gauge, _foil_parameters(model),
                                                st, solver.law_data)
    x[lay.axial] = q
    x[lay.force] = qf
    parts = [disc.film_forces(qf[b], st.psi[b], st.theta_weight[b]) for b in solver._blocks]
    nb = len(parts)
    sums = x[lay.partial_sums]
    sums[:nb] = [f[0] for f in parts]
    sums[nb:] = [f[1] for f in parts]
    x[lay.partial_sums] = sums
    x[lay.eccentricity] = eccentricity
    x[lay.attitude] = attitude
    return x


# ------------------------------------------------------------------------ solving
def _foil_parameters(model: BearingModel) -> FoilParameters:
    """The foil groups of ``model`` as numbers (the numpy side of the foil law)."""
    return FoilParameters(model.compliance, model.top_foil_coefficient,
                          float(model.compression_only))


def _check_target(model: BearingModel, eccentricity, load):
    if (eccentricity is None) == (load is None):
        raise ParameterError("eccentricity/load", (eccentricity, load),
                             "give exactly one of eccentricity or load")
    if eccentricity is not None:
        e = check_finite("eccentricity", eccentricity)
        if e < 0:
            raise ParameterError("eccentricity", eccentricity, "must be >= 0")
        if model.is_rigid and e >= 1.0:
            raise ParameterError("eccentricity", eccentricity,
                                 "must be < 1 for a rigid bearing (the journal would touch)")
        if e > 5.0:
            raise ParameterError("eccentricity", eccentricity, "must be <= 5")
        return False, e
    return True, check_positive("load", load)


def _postprocess(solver: StaticSolver, model: BearingModel, x: np.ndarray, stats: dict,
                 load_mode: bool, target: float, elapsed: float,
                 position_mode: bool = False) -> StaticSolution:
    """Recompute everything from the raw solution with numpy: residual, forces, profiles."""
    st, lay = solver.stencil, solver.layout
    ecc = float(x[lay.eccentricity])
    phi = float(x[lay.attitude])
    seam = (math.pi + phi) if model.seam_angle is None else float(model.seam_angle)
    theta = seam + st.psi
    p = np.ones(st.n_nodes)
    p[st.unknown] = x[lay.pressure]
    dz = st.axial_spacing(model.length_ratio)
    q = disc.axial_integral(p, st, dz)
    mean_gauge = q / (2 * model.length_ratio)
    h_rigid = rigid_film_polar(ecc, phi, theta)
    nzn = st.n_z_nodes
    w_nodes, foil_res = solver.law.deflection(p, mean_gauge, x[lay.beam],
                                              _foil_parameters(model), st, solver.law_data)
    h = np.repeat(h_rigid, nzn) + w_nodes
    reynolds = disc.reynolds_residual(p, h, st, model.bearing_number, dz)
    force_p = 1 + force_gauge(p - 1, model.subambient == "gumbel")
    fx, fy = disc.film_forces(disc.axial_integral(force_p, st, dz), theta,
                              st.theta_weight)
    if position_mode:
        force_res = 0.0
    elif load_mode:
        force_res = math.hypot(fx + target, fy)
    else:
        force_res = abs(fy)
    residual = max(float(np.abs(reynolds).max()) if reynolds.size else 0.0, foil_res)
    status = str(stats.get("return_status", "unknown"))
    hmat = h.reshape(st.n_theta_nodes, nzn)
    ok = bool(bool(stats.get("success", False)) and residual < RESIDUAL_TOLERANCE
          and force_res < RESIDUAL_TOLERANCE * max(1.0, abs(target)) and hmat.min() > 0
          and p.min() > 0)
    hmin, angle = _minimum_film(hmat, theta, st.periodic)
    message = "" if ok else (f"IPOPT status {status}; Reynolds residual {residual:.2e}; "
                             f"force residual {force_res:.2e}; min H {hmat.min():.3g}")
    return StaticSolution(
        model=model, grid=solver.grid, eccentricity=ecc, attitude_angle=phi,
        load=-float(fx), force=(float(fx), float(fy)), min_film=hmin, min_film_angle=angle, seam_angle=seam,
        theta=theta, z=st.z_nodes(model.length_ratio),
        pressure=p.reshape(st.n_theta_nodes, nzn), film=hmat,
        deflection=w_nodes.reshape(st.n_theta_nodes, nzn), success=ok, status=status,
        iterations=int(stats.get("iter_count", -1)), residual=residual,
        force_residual=float(force_res), solve_time_s=elapsed, state=x, message=message)


def _minimum_film(hmat: np.ndarray, theta: np.ndarray, periodic: bool) -> tuple[float, float]:
    """Minimum film and its angle, refined by a parabola through the three nearest nodes."""
    hrow = hmat.min(axis=1)
    k = int(np.argmin(hrow))
    n = hrow.size
    if periodic or 0 < k < n - 1:
        a, b, c = hrow[(k - 1) % n], hrow[k], hrow[(k + 1) % n]
        denom = a - 2 * b + c
        if denom > 0:
            shift = 0.5 * (a - c) / denom
            dth = theta[1] - theta[0]
            return float(b - 0.25 * (a - c) * shift), float(theta[k] + shift * dth)
    return float(hrow[k]), float(theta[k])


def solve_static(model: BearingModel, *, eccentricity: Optional[float] = None,
                 load: Optional[float] = None, attitude_angle: Optional[float] = None,
                 grid: Grid = DEFAULT_GRID,
                 solver: Optional[StaticSolver] = None,
                 initial: Optional[StaticSolution] = None,
                 continuation: bool = True, raise_on_failure: bool = False) -> StaticSolution:
    """Static equilibrium at a given eccentricity ratio or a given load.

    Parameters
    ----------
    model : the non-dimensional bearing
    eccentricity : ε = e/c [-] (then the load and attitude angle are found), or
    load : W̄ = W/(p_a R²) [-] (then ε and the attitude angle are found)
    attitude_angle : with ``eccentricity``, fixes the journal position too [rad]: the film
        force at that position is returned (``load`` = −F_X, ``force``) without equilibrium
    grid : finite-difference grid (ignored when ``solver`` is given)
    solver : a prebuilt :class:`StaticSolver` (reuse it across a sweep)
    initial : a previous solution to warm-start from (same solver)
    continuation : on failure from a cold start, step the eccentricity/load up from a small
        value, warm-starting each step
    raise_on_failure : raise :class:`ConvergenceError` instead of returning success=False

    Returns
    -------
    StaticSolution, with ``success``, IPOPT's ``status`` and the ``residual`` recomputed.
    """
    load_mode, target = _check_target(model, eccentricity, load)
    if attitude_angle is not None:
        if load_mode:
            raise ParameterError("attitude_angle", attitude_angle,
                                 "fixes the position together with eccentricity, not with load")
        attitude_angle = check_finite("attitude_angle", attitude_angle)
    if solver is None:
        solver = solver_for(model, grid)
    elif not solver.matches(model, solver.grid):
        raise ParameterError("solver", f"{solver.film} film, {solver.law.name} structure",
                             f"was built for another formulation than film={model.film}, "
                             f"foil={model.foil}, deflection_law={model.deflection_law}")
    t0 = time.perf_counter()
    if not load_mode and target == 0.0:
        sol = _concentric(solver, model, t0)
    else:
        sol = _solve_with_continuation(solver, model, load_mode, target, initial,
                                       continuation, t0, attitude_angle)
    if raise_on_failure and not sol.success:
        raise ConvergenceError("static equilibrium did not converge", sol.status,
                               max(sol.residual, sol.force_residual))
    return sol


def _concentric(solver: StaticSolver, model: BearingModel, t0: float) -> StaticSolution:
    """ε = 0: P ≡ 1, W ≡ 0 solves the discrete equations exactly (checked, not assumed)."""
    x = _cold_guess(solver, model, 0.0)
    sol = _postprocess(solver, model, x, {"success": True, "return_status": "Concentric",
                                          "iter_count": 0}, False, 0.0,
                       time.perf_counter() - t0)
    return replace(sol, attitude_angle=float("nan"))


def _solve_with_continuation(solver, model, load_mode, target, initial, continuation, t0,
                             attitude=None):
    p = solver.parameters(model, load_mode, target, attitude)
    if initial is not None and initial.state.size == solver.layout.size:
        x0 = initial.state
    else:
        x0 = _cold_guess(solver, model, target if not load_mode else
                         min(0.5, target / max(small_eccentricity_limit(model)[0], 1e-9)),
                         attitude)
    x, stats = solver.run(x0, p)
    sol = _postprocess(solver, model, x, stats, load_mode, target, time.perf_counter() - t0,
                       attitude is not None)
    if sol.success or not continuation:
        return sol
    # Continuation: march the target up from a small value, warm-starting each step.
    iterations = sol.iterations
    start = 0.1 * target
    x_prev = _cold_guess(solver, model, start if not load_mode else
                         min(0.5, start / max(small_eccentricity_limit(model)[0], 1e-9)),
                         attitude)
    value, step = start, (target - start) / 4
    last = None
    while True:
        x, stats = solver.run(x_prev, solver.parameters(model, load_mode, value, attitude))
        iterations += int(stats.get("iter_count", 0))
        trial = _postprocess(solver, model, x, stats, load_mode, value, 0.0,
                             attitude is not None)
        if trial.success:
            x_prev, last = x, value
            if value >= target:
                break
            value = min(target, value + step)
        else:
            if last is None:
                value *= 0.5
                if value < 1e-3 * target:
                    break
                continue
            step *= 0.5
            if step < 1e-3 * target:
                break
            value = min(target, last + step)
    final = _postprocess(solver, model, x if last == target else x_prev, stats, load_mode,
                         target, time.perf_counter() - t0, attitude is not None)
    final = replace(final, iterations=iterations)
    if last != target:
        final = replace(final, success=False,
                         message=f"continuation stopped at {last!r} of {target!r}; "
                                 + final.message)
    return final
