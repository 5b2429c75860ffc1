"""The IPOPT equilibrium problem for one grid, film type and foil structure.

:class:`StaticSolver` wraps the symbolic problem of :mod:`gfbopt.static.model` in a CasADi
``nlpsol`` (IPOPT, square system, zero objective, P > 0 and H > 0 by bounds); the operating
values are CasADi parameters, so one build serves a whole sweep.  :func:`solver_key` is the
one definition of which build serves a model; :class:`SolverCache` keeps one build per key.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Optional

import casadi as ca
import numpy as np
import scipy.sparse as sp

from .. import discretisation as disc
from ..errors import ParameterError
from ..inputs.bore import check_grid_resolves
from ..inputs.grid import DEFAULT_GRID, Grid, as_grid
from ..inputs.model import FILM_MODELS, BearingModel
from ..physics.foil_laws import FOIL_LAWS, static_structure
from ..sparse_lu import Factoriser
from ..threads import single_threaded
from .model import build_problem, n_parameters

if TYPE_CHECKING:  # pragma: no cover
    from .solution import StaticSolution


def default_ipopt_options() -> dict:
    """IPOPT options of every build (CasADi ``nlpsol`` keys); user options override them.

    ``no_nlp_grad``/``calc_lam_p``: CasADi would otherwise build the gradient of the
    Lagrangian (a reverse sweep of the whole model) to post-process multipliers that gfbopt
    never reads.  ``mumps_pivot_order`` 0 (AMD) instead of MUMPS's automatic choice: the same
    iterations and the same states (≤ 2.5e-12) for 1.3–4.3× less time per cold solve at
    144 × 36 and 1.1–1.5× at 36 × 10 (rigid periodic, seam simple, local law, beam;
    benchmarks/bench_onset.py, section ipopt_options, keeps the comparison).
    """
    return {
        "ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes",
        "ipopt.tol": 1e-10, "ipopt.constr_viol_tol": 1e-10, "ipopt.acceptable_iter": 0,
        "ipopt.hessian_approximation": "exact",
        "ipopt.max_iter": 60, "ipopt.bound_push": 1e-10, "ipopt.bound_frac": 1e-10,
        "ipopt.mu_init": 1e-6, "ipopt.nlp_scaling_method": "none",
        "ipopt.linear_solver": "mumps", "ipopt.mumps_pivot_order": 0,
        "no_nlp_grad": True, "calc_lam_p": False,
    }


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
    fixed_rows : θ rows held at ambient pressure besides the seam (several pads: their
        leading ends and gaps, :meth:`gfbopt.inputs.bore.AsBuilt.fixed_rows`)

    Attributes
    ----------
    layout, stencil, law, law_data : where the unknowns sit, the grid's stencil, the foil
        law and its grid data
    residual_function : (x, p) ↦ g, the discrete equations (CasADi Function)
    n_equations : number of equations (= unknowns)
    force_blocks : θ-row indices of each force partial sum
    build_time_s : wall time of the build [s]
    """

    def __init__(self, grid: Grid = DEFAULT_GRID, film: str = "periodic",
                 foil_law: str = "simple", ipopt_options: Optional[dict] = None,
                 fixed_rows: tuple = ()):
        t0 = time.perf_counter()
        grid = as_grid(grid)
        if film not in FILM_MODELS:
            raise ParameterError("film", film, f"must be one of {', '.join(FILM_MODELS)}")
        structures = sorted({law.static_structure for law in FOIL_LAWS.values()})
        if foil_law not in structures:
            raise ParameterError("foil_law", foil_law, "must be one of "
                                 f"{', '.join(structures)} (rigid models use 'simple')")
        if ipopt_options is not None and not isinstance(ipopt_options, dict):
            raise ParameterError("ipopt_options", ipopt_options, "must be a dict or None")
        self.grid = grid
        self.film = film
        self.law = FOIL_LAWS[foil_law]
        self.stencil = disc.make_stencil(grid, periodic=(film == "periodic"),
                                         fixed_rows=tuple(fixed_rows))
        self.law_data = self.law.prepare(grid, self.stencil.dpsi)
        problem = build_problem(self.stencil, self.law, self.law_data)
        self.layout = problem.layout
        self.force_blocks = problem.force_blocks
        x, p, g = problem.x, problem.p, problem.g
        self.n_equations = g.shape[0]
        #: g(x, p): the discrete equations as a CasADi Function (for checks and linearisation)
        self.residual_function = ca.Function("static_residual", [x, p], [g], ["x", "p"], ["g"])
        opts = default_ipopt_options()
        opts.update(ipopt_options or {})
        if "jac_g" not in opts:
            opts["jac_g"] = ca.Function("nlp_jac_g", [x, p], [g, problem.jacobian],
                                        ["x", "p"], ["g", "jac_g_x"])
        if opts.get("ipopt.hessian_approximation") == "exact" and "hess_lag" not in opts:
            # A square system needs no curvature: with J nonsingular the Newton step is fixed
            # by the constraints alone, so IPOPT gets an empty Hessian of the Lagrangian (this
            # avoids both the symbolic Hessian build and the L-BFGS extra solves).
            lam_f, lam_g = ca.MX.sym("lam_f"), ca.MX.sym("lam_g", self.n_equations)
            n = self.layout.size
            opts["hess_lag"] = ca.Function(
                "zero_hessian", [x, p, lam_f, lam_g], [ca.MX(ca.Sparsity(n, n))],
                ["x", "p", "lam_f", "lam_g"], ["triu_hess_gamma_x_x"])
        self._nlp = ca.nlpsol("gfbopt_static", "ipopt", {"x": x, "p": p, "f": 0, "g": g}, opts)
        lay = self.layout
        lbx = -np.inf * np.ones(lay.size)
        ubx = np.inf * np.ones(lay.size)
        lbx[lay.pressure] = 1e-6
        if self.law.lifted_film_is_total:
            lbx[lay.film] = 1e-6
        lbx[lay.eccentricity] = 0.0
        lbx[lay.attitude] = -0.5 * math.pi
        ubx[lay.attitude] = math.pi
        self._lbx, self._ubx = lbx, ubx
        self._newton = None
        #: functions derived from this build by other modules, built on first use and kept
        #: with it (e.g. the linearisation's film sensitivity, :mod:`gfbopt.linear.model`)
        self.derived: dict = {}
        #: the sparse LUs of this build's matrices (static Jacobians, perturbation matrices),
        #: each sparsity pattern's fill-reducing order kept (:mod:`gfbopt.sparse_lu`)
        self.factoriser = Factoriser()
        self.build_time_s = time.perf_counter() - t0

    @property
    def bounds(self) -> tuple:
        """(lower, upper): IPOPT's bounds on the unknowns (P > 0, a total film > 0, ε ≥ 0,
        −π/2 ≤ φ ≤ π; ±inf elsewhere)."""
        return self._lbx, self._ubx

    def newton_system(self):
        """The equations as numpy arrays for the Newton fast path (:mod:`.newton`), built on
        first use and kept with this build."""
        if self._newton is None:
            from .newton import NewtonSystem
            self._newton = NewtonSystem(self)
        return self._newton

    def jacobian_function(self) -> ca.Function:
        """(x, p) ↦ (g, dg/dx): IPOPT's own sparse constraint Jacobian (no rebuild)."""
        return self._nlp.get_function("nlp_jac_g")

    def parameters(self, model: BearingModel, load_mode: bool, target: float,
                   attitude: Optional[float] = None,
                   seam_angle: Optional[float] = None) -> np.ndarray:
        """The parameter vector of ``model`` for a given eccentricity or load.

        ``attitude`` [rad] fixes the journal position too (forces at a given position);
        ``seam_angle`` [rad] overrides the model's seam (used to freeze a following seam).
        The bore's clearance change and the foundation compliance per θ row follow
        (:func:`row_values`).
        """
        seam = fixed_origin(model) if seam_angle is None else seam_angle
        follows = seam is None
        bore, s_rows = row_values(model, self.stencil, seam)
        return np.concatenate([[model.bearing_number, model.compliance,
                                model.top_foil_coefficient, model.length_ratio,
                                float(load_mode), target, 0.0 if follows else seam,
                                float(follows), float(model.compression_only),
                                float(model.subambient == "gumbel"),
                                float(attitude is not None),
                                0.0 if attitude is None else float(attitude),
                                *hardening_values(model)], bore, s_rows])

    @property
    def n_parameters(self) -> int:
        """Length of the parameter vector."""
        return n_parameters(self.stencil)

    @property
    def key(self) -> tuple:
        """(grid, film, static structure, rows at ambient besides the seam): what this build
        can solve (:func:`solver_key`)."""
        return (self.grid, self.film, self.law.name, self.stencil.fixed_rows)

    def matches(self, model: BearingModel, grid: Grid) -> bool:
        """True if this build can solve ``model`` on ``grid``."""
        return self.key == solver_key(model, grid)

    def perturbation_blocks(self, solution: "StaticSolution") -> PerturbationBlocks:
        """What the linearisation needs from this build about ``solution`` (its own layout
        stays private): the Jacobian of the equations in y = every variable except ε and φ,
        with the seam frozen where the static solution put it (the top foil is fixed in the
        housing), how the journal position enters, and the film-force map.
        """
        lay, st = self.layout, self.stencil
        n = lay.eccentricity
        p = self.parameters(solution.model, False, solution.eccentricity,
                            solution.attitude_angle_rad, seam_angle=solution.seam_angle_rad)
        _, jac = self.newton_system().residual_and_jacobian(solution.state, p)
        a = jac[:n, :n].tocsc()
        # Only the lifted film rows depend on the journal: their equation is
        # H − H_r − W = 0 (or H − H_r for the local law), H_r = 1 − X cos θ − Y sin θ.
        film_rows = np.arange(lay.film.start, lay.film.stop)
        c_xi = np.zeros((n, 2))
        c_xi[film_rows, 0] = np.cos(solution.theta)
        c_xi[film_rows, 1] = np.sin(solution.theta)
        # F_X = cos θ_s ΣA_k − sin θ_s ΣB_k, F_Y = sin θ_s ΣA_k + cos θ_s ΣB_k (partial sums)
        sums = np.arange(lay.partial_sums.start, lay.partial_sums.stop)
        nb = sums.size // 2
        ts = solution.seam_angle_rad
        force = np.zeros((2, n))
        force[0, sums[:nb]], force[0, sums[nb:]] = math.cos(ts), -math.sin(ts)
        force[1, sums[:nb]], force[1, sums[nb:]] = math.sin(ts), math.cos(ts)
        return PerturbationBlocks(a, c_xi, force, st.n_unknown,
                                  lay.film.start + st.row)

    @single_threaded
    def run(self, x0: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, dict]:
        """One IPOPT solve from ``x0``; returns (x, stats)."""
        sol = self._nlp(x0=x0, p=p, lbx=self._lbx, ubx=self._ubx, lbg=0, ubg=0)
        return np.asarray(sol["x"]).ravel(), self._nlp.stats()


def solver_key(model: BearingModel, grid: Grid) -> tuple:
    """The one definition of which build serves ``model`` on ``grid``: (grid, film,
    structure, rows held at ambient besides the seam).

    Λ, S, C, L/D, the seam angle, the eccentricity or load, the compression-only and Gümbel
    switches, the bore profile (preload) and the foundation zones are parameters of a build,
    so they are not part of the key; several pads change which rows are unknown, so they are.
    A grid too coarse for the bearing as built is refused here
    (:func:`gfbopt.inputs.bore.check_grid_resolves`), for every build and every cached one.
    """
    ab = model.as_built
    check_grid_resolves(ab, grid.n_theta)        # lobes, shims or pads finer than the grid
    fixed = () if ab is None else ab.fixed_rows(model.seam_angle_rad or 0.0, grid.n_theta)
    return (grid, model.film, static_structure(model), fixed)


def solver_for(model: BearingModel, grid: Grid = DEFAULT_GRID, **kwargs) -> StaticSolver:
    """Build the :class:`StaticSolver` that fits ``model`` on ``grid``."""
    _, film, structure, fixed = solver_key(model, grid)
    return StaticSolver(grid, film=film, foil_law=structure, fixed_rows=fixed, **kwargs)


def solution_stencil(solution: "StaticSolution") -> disc.Stencil:
    """The stencil a solution was solved on (its grid, film and pads)."""
    return disc.make_stencil(solution.grid, periodic=solution.model.film == "periodic",
                             fixed_rows=solver_key(solution.model, solution.grid)[3])


def fixed_origin(model: BearingModel) -> Optional[float]:
    """The grid origin θ_s [rad] when it is fixed in the housing, or None when it follows
    the journal (θ_s = π + φ: the seam on the maximum-film line, or a periodic film).

    A periodic film whose bore or foundation varies round the housing is solved on a grid
    fixed in the housing, its origin on the load line (the bore does not move with the
    journal); a seam on the maximum-film line is refused with such a bearing
    (:func:`gfbopt.inputs.bore.check_as_built`).
    """
    if model.seam_angle_rad is not None:
        return model.seam_angle_rad
    if model.as_built is not None and model.as_built.housing_fixed:
        return 0.0
    return None


def hardening_values(model: BearingModel) -> tuple:
    """(n, W_lim) of the hardening bump, or (1, 1) when it is off (unused by the other
    structures; finite, so the parameter vector stays finite)."""
    if getattr(model, "hardening_exponent", 0.0) > 0.0:
        return float(model.hardening_exponent), float(model.hardening_limit)
    return 1.0, 1.0


def row_values(model: BearingModel, st: disc.Stencil, origin: Optional[float]) -> tuple:
    """(B_i, S_i): the bore's clearance change Δc/c and the foundation compliance per θ row
    of ``st`` with its origin at ``origin`` [rad] (None: following the journal, where only a
    round bore and a uniform foundation are allowed) [-]."""
    ab = model.as_built
    m = st.n_theta_nodes
    if ab is None or not ab.housing_fixed:
        return np.zeros(m), np.full(m, model.compliance)
    theta = (0.0 if origin is None else origin) + st.psi
    return ab.bore_rows(theta), ab.compliance_rows(theta, model.compliance)


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
