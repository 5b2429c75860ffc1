"""Nonlinear time-transient model of a rigid rotor on gas foil bearings (numpy, batched).

State of each rotor (a batch of B rotors advances together, one array per quantity):

* Φ = P H at every grid node, shape (B, m, n_z + 1) — the conserved quantity of the
  time-dependent Reynolds equation 2Λ ∂(PH)/∂τ = R(P, H) (PHYSICS.md), so
  ∂Φ/∂τ = R(P, H)/(2Λ) with R the steady residual of :mod:`gfbopt.discretisation`;
* the journal centre (X, Y) and its velocity (U, V) = (X', Y'), τ = ω t.

The foil is massless and follows the pressure at every instant (as in the static model), so P
and H are recovered from Φ and (X, Y) algebraically:

* rigid: H = H_r = 1 − X cos θ − Y sin θ, P = Φ/H;
* simple, axial-mean law: on each θ row H = a with a = H_r + S(P̄ − 1) and P = Φ/a, so
  a² − b a − S Φ̃ = 0 (b, Φ̃ from the row's axial sums) — closed form; with compression-only
  bumps a = max(that, H_r);
* simple, local law: S P² + (H_r − S) P − Φ = 0 per node — closed form;
* beam: W = 𝓛 (P̄ − 1) with 𝓛 the (dense, m × m) compliance of the Hermite beam on the bump
  foundation; a few Newton steps per evaluation solve a − H_r − 𝓛(P̄(a) − 1) = 0.

Rotor (per bearing, load W̄0 along X): M̄ W̄0 X'' = F_X + W̄0, M̄ W̄0 Y'' = F_Y.

The flux stencil here is a 2-D slicing version of :func:`gfbopt.discretisation.reynolds_residual`
for speed; ``tests/test_transient.py`` proves the two equal to round-off, and that a static
equilibrium is a fixed point of this right-hand side.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from .errors import ConvergenceError, ParameterError
from .foil import beam_deflection, beam_matrices
from .static import StaticSolution

#: RK4's stability boundary on the negative real axis is 2.785; on the imaginary axis 2.828.
RK4_STABILITY_RADIUS = 2.78
#: Fraction of the stability limit used by the automatic step.  The Gershgorin bound is within
#: 5 % of the true spectral radius here (its spectrum is real and negative: diffusion), see
#: tests/test_transient.py, so 0.9 keeps Δτ·λ_max ≤ 0.9 × 2.78.
STEP_SAFETY = 0.9


@dataclass(frozen=True, eq=False)
class TransientModel:
    """Everything the right-hand side needs, precomputed from a static equilibrium.

    Angles θ [rad] from the load line; all quantities non-dimensional (PHYSICS.md).
    """

    static: StaticSolution
    bearing_number: float
    compliance: float
    load: float
    periodic: bool
    cos: np.ndarray          # (m,)
    sin: np.ndarray          # (m,)
    theta_weight: np.ndarray  # (m,)
    z_weight: np.ndarray     # (n_z + 1,) trapezoid weights × ΔZ
    dtheta: float
    dz: float
    foil: str                # 'rigid', 'simple', 'local', 'beam'
    compression_only: bool
    gumbel: bool
    beam_map: Optional[np.ndarray]  # (m, m): W at film rows per unit P̄ − 1 at film rows

    @property
    def shape(self) -> tuple:
        return self.static.pressure.shape


def transient_model(solution: StaticSolution) -> TransientModel:
    """The transient model around a converged static equilibrium ``solution``.

    A seam on the maximum-film line is frozen where the static solution put it (the top foil
    is fixed in the housing).
    """
    if not solution.success:
        raise ParameterError("solution", f"status {solution.status}",
                             "the static equilibrium did not converge; no transient from it")
    model = solution.model
    if solution.load <= 0 or not math.isfinite(solution.attitude_angle):
        raise ParameterError("solution.load", solution.load,
                             "must be > 0 (the rotor mass parameter M̄ = M c ω²/W0 needs a load)")
    m, nzn = solution.pressure.shape
    periodic = model.film == "periodic"
    dtheta = 2 * math.pi / solution.grid.n_theta
    dz = 2 * model.length_ratio / solution.grid.n_z
    tw = np.full(m, dtheta)
    if not periodic:
        tw[[0, -1]] *= 0.5
    zw = np.full(nzn, dz)
    zw[[0, -1]] *= 0.5
    if model.is_rigid:
        foil = "rigid"
    elif model.foil == "beam":
        foil = "beam"
    elif model.deflection_law == "local":
        foil = "local"
    else:
        foil = "simple"
    beam_map = None
    if foil == "beam":
        if model.compression_only:
            raise ParameterError("compression_only", True, "is not available in the transient "
                                 "beam model (use the simple model for bumps that let go)")
        n = solution.grid.n_theta
        mats = beam_matrices(n, dtheta)
        # W at beam nodes 0..n per unit load at each node (columns): the static beam law
        w = beam_deflection(np.eye(n + 1), mats, model.compliance, model.top_foil_coefficient)
        if periodic:       # film rows 0..n−1; the free end (node n) sees row 0's load
            w = w[:n]
            w[:, 0] += w[:, n]
            beam_map = w[:, :n]
        else:
            beam_map = w
    return TransientModel(
        static=solution, bearing_number=model.bearing_number, compliance=model.compliance,
        load=solution.load, periodic=periodic, cos=np.cos(solution.theta),
        sin=np.sin(solution.theta), theta_weight=tw, z_weight=zw, dtheta=dtheta, dz=dz,
        foil=foil, compression_only=bool(model.compression_only),
        gumbel=model.subambient == "gumbel", beam_map=beam_map)


# ----------------------------------------------------------------------- kernel
def flux_residual(p: np.ndarray, h: np.ndarray, tm: TransientModel) -> np.ndarray:
    """Steady Reynolds residual R(P, H) at every node (zero on boundary nodes) [-].

    p : array (..., m, n_z + 1); h : the same shape, or (..., m, 1) when H is uniform along
    each θ row (then H³ is formed per row, and the axial face value is just H³).  The same
    stencil as :func:`gfbopt.discretisation.reynolds_residual`, written with slices.
    """
    lam = tm.bearing_number
    dth, dz = tm.dtheta, tm.dz
    h3 = h * h * h
    p2 = p * p
    ph = p * h
    if tm.periodic:
        h3e = np.roll(h3, -1, axis=-2)
        p2e = np.roll(p2, -1, axis=-2)
        phe = np.roll(ph, -1, axis=-2)
        # flux through the face i+½ for every row i (wraps round)
        fe = 0.25 * (h3 + h3e) * (p2e - p2) / dth - 0.5 * lam * (ph + phe)
        dflux = (fe - np.roll(fe, 1, axis=-2)) / dth
    else:
        fe = (0.25 * (h3[..., :-1, :] + h3[..., 1:, :]) * (p2[..., 1:, :] - p2[..., :-1, :]) / dth
              - 0.5 * lam * (ph[..., :-1, :] + ph[..., 1:, :]))
        dflux = np.zeros_like(p)
        dflux[..., 1:-1, :] = (fe[..., 1:, :] - fe[..., :-1, :]) / dth
    if h.shape[-1] == 1:
        fn = (0.5 / dz) * h3 * (p2[..., :, 1:] - p2[..., :, :-1])
    else:
        fn = 0.25 * (h3[..., :, :-1] + h3[..., :, 1:]) * (p2[..., :, 1:] - p2[..., :, :-1]) / dz
    res = np.zeros_like(p)
    res[..., :, 1:-1] = dflux[..., :, 1:-1] + (fn[..., :, 1:] - fn[..., :, :-1]) / dz
    if not tm.periodic:
        res[..., [0, -1], :] = 0.0
    return res


def rigid_film(x: np.ndarray, y: np.ndarray, tm: TransientModel) -> np.ndarray:
    """H_r = 1 − X cos θ − Y sin θ per θ row, shape (B, m)."""
    return 1.0 - x[:, None] * tm.cos - y[:, None] * tm.sin


def pressure_and_film(phi: np.ndarray, x: np.ndarray, y: np.ndarray, tm: TransientModel,
                      guess: Optional[np.ndarray] = None,
                      cache: Optional[dict] = None) -> tuple[np.ndarray, np.ndarray]:
    """Recover P (B, m, n_z + 1) and H from Φ = P H and the journal position.

    H has shape (B, m, n_z + 1) for the local law and (B, m, 1) — uniform along each θ row —
    otherwise.  Boundary nodes carry P = 1.  ``guess`` (B, m) is a starting film for the beam's Newton.
    """
    hr = rigid_film(x, y, tm)
    zw = tm.z_weight
    total = zw.sum()
    interior = np.ones(phi.shape[-1], dtype=bool)
    interior[[0, -1]] = False
    if tm.foil == "local":
        s = tm.compliance
        hr3 = hr[:, :, None]
        p = (-(hr3 - s) + np.sqrt((hr3 - s) ** 2 + 4 * s * phi)) / (2 * s)
        if tm.compression_only:   # W = S max(P − 1, 0): where P < 1 the film is rigid
            p = np.where(p < 1.0, phi / hr3, p)
        p = _set_boundary(p, tm)
        h = hr3 + s * (p - 1.0) if not tm.compression_only else hr3 + s * np.maximum(p - 1.0, 0)
        return p, h
    if tm.foil == "rigid":
        a = hr
    else:
        # P̄ = (Σ_interior w Φ/a + Σ_ends w·1)/Σw = Φ̃/a + c  on each row
        phit = (phi[..., interior] @ zw[interior]) / total
        c = (zw[~interior].sum()) / total
        if not tm.periodic:          # seam rows carry P = 1: P̄ − 1 = 0 there
            phit[:, [0, -1]] = (1.0 - c) * hr[:, [0, -1]]
        if tm.foil == "simple":
            s = tm.compliance
            b = hr + s * (c - 1.0)
            a = 0.5 * (b + np.sqrt(b * b + 4 * s * phit))
            if tm.compression_only:
                a = np.maximum(a, hr)
        else:
            a = _beam_film(hr, phit, c, tm, guess, cache)
    p = phi / a[:, :, None]
    p = _set_boundary(p, tm)
    return p, a[:, :, None]          # film uniform along each θ row: shape (B, m, 1)


def _set_boundary(p: np.ndarray, tm: TransientModel) -> np.ndarray:
    p[..., :, 0] = 1.0
    p[..., :, -1] = 1.0
    if not tm.periodic:
        p[..., 0, :] = 1.0
        p[..., -1, :] = 1.0
    return p


def _beam_film(hr, phit, c, tm: TransientModel, guess, cache: Optional[dict] = None):
    """Solve a = H_r + 𝓛 q, q = Φ̃/a + c − 1 (q = 0 on seam rows), for the row films a
    (B, m).

    Chord iterations a ← a − J⁻¹ f with the inverse Jacobian J = I + 𝓛 diag(Φ̃/a²) kept in
    ``cache`` between evaluations (it changes little from one RK stage to the next); it is
    recomputed when the iteration stalls.  Converged to |f| < 1e-13.
    """
    lmap = tm.beam_map
    live = np.ones(hr.shape[1])
    if not tm.periodic:
        live[[0, -1]] = 0.0
    a = hr.copy() if guess is None or guess.shape != hr.shape else guess.copy()
    cache = {} if cache is None else cache
    eye = np.eye(a.shape[1])
    previous = math.inf
    for _ in range(40):
        q = (phit / a + c - 1.0) * live
        f = a - hr - q @ lmap.T
        err = float(np.abs(f).max())
        if err < 1e-13:
            return a
        jinv = cache.get("jinv")
        if jinv is None or jinv.shape[0] != a.shape[0] or err > 0.1 * previous:
            jac = eye[None] + lmap[None] * (live * phit / (a * a))[:, None, :]
            jinv = np.linalg.inv(jac)
            cache["jinv"] = jinv
        previous = err
        a = a - np.einsum("bij,bj->bi", jinv, f)
    raise ConvergenceError("beam film did not converge in the transient model", "max_iter",
                           err)


def film_force(p: np.ndarray, tm: TransientModel) -> tuple[np.ndarray, np.ndarray]:
    """F = −∬ (P − 1)(cos θ, sin θ) dθ dZ for each rotor (Gümbel: max(P − 1, 0)) [-]."""
    gauge = p - 1.0
    if tm.gumbel:
        gauge = np.maximum(gauge, 0.0)
    q = gauge @ tm.z_weight                       # (B, m)
    w = tm.theta_weight
    return -(q * tm.cos) @ w, -(q * tm.sin) @ w


@dataclass
class State:
    """A batch of rotor states: Φ (B, m, n_z+1), X, Y, U, V (B,)."""

    phi: np.ndarray
    x: np.ndarray
    y: np.ndarray
    u: np.ndarray
    v: np.ndarray

    def axpy(self, alpha, d: "State") -> "State":
        """self + alpha·d; ``alpha`` a scalar or one value per rotor (B,)."""
        a = np.asarray(alpha, dtype=float)
        ap = a[:, None, None] if a.ndim else a
        return State(self.phi + ap * d.phi, self.x + a * d.x, self.y + a * d.y,
                     self.u + a * d.u, self.v + a * d.v)

    def rk4_update(self, w, k1, k2, k3, k4) -> "State":
        """self + w (k1 + 2 k2 + 2 k3 + k4), ``w`` scalar or per rotor."""
        wp = w[:, None, None] if np.ndim(w) else w
        return State(self.phi + wp * _rk4_sum(k1.phi, k2.phi, k3.phi, k4.phi),
                     self.x + w * _rk4_sum(k1.x, k2.x, k3.x, k4.x),
                     self.y + w * _rk4_sum(k1.y, k2.y, k3.y, k4.y),
                     self.u + w * _rk4_sum(k1.u, k2.u, k3.u, k4.u),
                     self.v + w * _rk4_sum(k1.v, k2.v, k3.v, k4.v))


def _rk4_sum(a, b, c, d):
    out = b + c
    out *= 2.0
    out += a
    out += d
    return out


def rk4_step(f, y, dt, weight=1.0):
    """One classic fourth-order Runge–Kutta step y ← y + dt/6 (k1 + 2k2 + 2k3 + k4).

    ``y`` supports ``axpy(alpha, d)`` (alpha scalar or per-rotor); ``weight`` (scalar or per
    rotor) multiplies the final update, so rotors with weight 0 stay frozen.
    """
    k1 = f(y)
    k2 = f(y.axpy(0.5 * dt, k1))
    k3 = f(y.axpy(0.5 * dt, k2))
    k4 = f(y.axpy(dt, k3))
    w = np.asarray(weight, dtype=float) * dt / 6.0
    if hasattr(y, "rk4_update"):          # one pass instead of four (speed)
        return y.rk4_update(w, k1, k2, k3, k4)
    return y.axpy(w, k1).axpy(2 * w, k2).axpy(2 * w, k3).axpy(w, k4)


class RightHandSide:
    """dState/dτ for a batch of rotors with masses ``mass`` (M̄, shape (B,)).

    Keeps the last beam films as the Newton guess of the next evaluation.
    """

    def __init__(self, tm: TransientModel, mass: np.ndarray):
        self.tm = tm
        self.mass_load = np.asarray(mass, dtype=float) * tm.load
        self._guess = None
        self._cache: dict = {}
        self.evaluations = 0
        #: smallest film H seen per rotor since the last reset (contact detection) [-]
        self.min_film = np.full(self.mass_load.size, np.inf)

    def __call__(self, s: State) -> State:
        tm = self.tm
        self.evaluations += 1
        p, h = pressure_and_film(s.phi, s.x, s.y, tm, self._guess, self._cache)
        np.minimum(self.min_film, h.min(axis=(1, 2)), out=self.min_film)
        if tm.foil == "beam":
            self._guess = h[..., 0]
        dphi = flux_residual(p, h, tm) / (2 * tm.bearing_number)
        fx, fy = film_force(p, tm)
        return State(dphi, s.u, s.v, (fx + tm.load) / self.mass_load, fy / self.mass_load)


def equilibrium_state(tm: TransientModel, batch: int) -> State:
    """The static equilibrium replicated ``batch`` times (Φ = P H, journal at rest)."""
    sol = tm.static
    phi = np.broadcast_to(sol.pressure * sol.film, (batch,) + sol.pressure.shape).copy()
    x0 = sol.eccentricity * math.cos(sol.attitude_angle)
    y0 = sol.eccentricity * math.sin(sol.attitude_angle)
    full = lambda v: np.full(batch, v)  # noqa: E731
    return State(phi, full(x0), full(y0), full(0.0), full(0.0))


# -------------------------------------------------------------- stability bound
def stiffness_bound(s: State, tm: TransientModel) -> float:
    """Gershgorin bound on |λ| of ∂(dΦ/dτ)/∂Φ at state ``s`` [1/rad of shaft rotation].

    With P = Φ/H (foil coupling neglected: it is non-local and non-stiff), row sums of
    |∂R/∂P_k|/H_k over the five-point stencil, over 2Λ.  RK4 is stable for Δτ·λ ≤ 2.78.
    """
    p, h = pressure_and_film(s.phi, s.x, s.y, tm)
    lam, dth, dz = tm.bearing_number, tm.dtheta, tm.dz
    h3 = h ** 3
    roll = (lambda a, k: np.roll(a, k, axis=-2)) if tm.periodic else _shift
    he3, hw3 = roll(h3, -1), roll(h3, 1)
    hn3 = np.concatenate([h3[..., 1:], h3[..., -1:]], axis=-1)
    hs3 = np.concatenate([h3[..., :1], h3[..., :-1]], axis=-1)
    pe, pw = roll(p, -1), roll(p, 1)
    hh_e, hh_w = roll(h, -1), roll(h, 1)
    ce = 0.25 * (h3 + he3) / dth
    cw = 0.25 * (h3 + hw3) / dth
    cn = 0.25 * (h3 + hn3) / dz
    cs = 0.25 * (h3 + hs3) / dz
    pn = np.concatenate([p[..., 1:], p[..., -1:]], axis=-1)
    ps = np.concatenate([p[..., :1], p[..., :-1]], axis=-1)
    diag = (2 * p * (ce + cw) / dth + 2 * p * (cn + cs) / dz) / h
    off = (np.abs(2 * ce * pe - 0.5 * lam * hh_e) / dth / hh_e
           + np.abs(2 * cw * pw + 0.5 * lam * hh_w) / dth / hh_w
           + 2 * cn * pn / dz / h + 2 * cs * ps / dz / h)
    bound = (diag + off)[..., :, 1:-1]
    if not tm.periodic:
        bound = bound[..., 1:-1, :]
    return float(bound.max() / (2 * lam))


def _shift(a: np.ndarray, k: int) -> np.ndarray:
    """Non-periodic neighbour along θ (edge rows repeat; they are boundary rows anyway)."""
    if k == -1:
        return np.concatenate([a[..., 1:, :], a[..., -1:, :]], axis=-2)
    return np.concatenate([a[..., :1, :], a[..., :-1, :]], axis=-2)


# ------------------------------------------------------------------ integration
VERDICTS = ("stable", "unstable", "limit cycle", "contact")


@dataclass(frozen=True, eq=False)
class OrbitBatch:
    """Journal-centre orbits of a batch of rotors (non-dimensional; τ = ω t [rad]).

    tau (n,), x, y, min_film (B, n): positions and the minimum film; equilibrium (X0, Y0);
    mass (B,); growth_rate (B,) [1/rad of shaft rotation] and whirl_ratio (B,) fitted to
    the orbit after ``settle`` revolutions; amplitude (B,) final orbit radius about the
    equilibrium; contact (B,) bool; contact_tau (B,); verdict (B,) strings; time_step Δτ;
    evaluations of the right-hand side; wall_time_s.
    """

    tau: np.ndarray
    x: np.ndarray
    y: np.ndarray
    min_film: np.ndarray
    equilibrium: tuple
    mass: np.ndarray
    growth_rate: np.ndarray
    whirl_ratio: np.ndarray
    amplitude: np.ndarray
    contact: np.ndarray
    contact_tau: np.ndarray
    verdict: tuple
    time_step: float
    evaluations: int
    wall_time_s: float
    revolutions: float

    def to_frame(self, rotor: int = 0):
        """The orbit of one rotor as a table: τ, X, Y, ε, φ [deg], minimum film."""
        import pandas as pd

        x, y = self.x[rotor], self.y[rotor]
        return pd.DataFrame({"tau": self.tau, "x": x, "y": y, "eccentricity": np.hypot(x, y),
                             "attitude_deg": np.degrees(np.arctan2(y, x)),
                             "min_film": self.min_film[rotor]})


def _check_positive(name: str, value, integer: bool = False) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be a number") from None
    if not math.isfinite(v) or v <= 0:
        raise ParameterError(name, value if isinstance(value, (int, str)) else v,
                             "must be finite and > 0")
    return v


def stable_time_step(tm: TransientModel, state: State, safety: float = STEP_SAFETY) -> float:
    """Largest RK4 step Δτ [rad] with Δτ·λ_max ≤ safety × 2.78 (Gershgorin bound)."""
    return safety * RK4_STABILITY_RADIUS / stiffness_bound(state, tm)


def integrate_orbits(tm: TransientModel, mass, revolutions: float = 10.0, *,
                     kick: float = 1e-3, initial: Optional[State] = None,
                     time_step: Optional[float] = None, sample_every: float = 0.2,
                     contact_film: float = 0.02, settle: float = 2.0,
                     check_every: int = 50, progress=None,
                     method: str = "rk4") -> OrbitBatch:
    """Advance a batch of rotors (one per entry of ``mass``, M̄ = M c ω²/W0) with classic RK4.

    Parameters
    ----------
    tm : the transient model (from :func:`transient_model`)
    mass : M̄ of each rotor [-], > 0
    revolutions : length of the run in shaft revolutions [-]
    kick : initial journal velocity dX/dτ = dY/dτ = kick/√2 from the equilibrium [-]
    initial : a batch state to start from instead of the kicked equilibrium
    time_step : Δτ [rad]; default from the stability bound.  A step above the RK4 stability
        limit of the discretised system is refused (ParameterError), never run silently.
    sample_every : Δτ between stored samples [rad]
    contact_film : minimum film H at which a rotor is in contact; its run stops there [-]
    settle : revolutions skipped before fitting the growth rate [-]
    check_every : steps between re-checks of the stability bound
    progress : optional callable(fraction) for progress display
    method : 'rk4' (this batched engine) or 'bdf' (scipy's implicit BDF with a sparse
        Jacobian, rotor by rotor: :mod:`gfbopt.implicit`; rigid and simple models; wins for
        the rigid bearing, see benchmarks/bench_transient.py)
    """
    import time as _time

    if method == "bdf":
        if time_step is not None:
            raise ParameterError("time_step", time_step, "applies to method='rk4' only (BDF "
                                 "chooses its own steps)")
        from .implicit import integrate_orbits_bdf

        return integrate_orbits_bdf(tm, mass, revolutions, kick=kick, initial=initial,
                                    sample_every=sample_every, contact_film=contact_film,
                                    settle=settle)
    if method != "rk4":
        raise ParameterError("method", method, "must be 'rk4' or 'bdf'")

    t0 = _time.perf_counter()
    mass = np.atleast_1d(np.asarray(mass, dtype=float))
    for mm in mass:
        _check_positive("mass", mm)
    revolutions = _check_positive("revolutions", revolutions)
    batch = mass.size
    state = initial if initial is not None else equilibrium_state(tm, batch)
    if initial is None:
        state.u[:] = kick / math.sqrt(2)
        state.v[:] = kick / math.sqrt(2)
    limit = RK4_STABILITY_RADIUS / stiffness_bound(state, tm)
    if time_step is None:
        dt = STEP_SAFETY * limit
    else:
        dt = _check_positive("time_step", time_step)
        if dt > limit:
            raise ParameterError("time_step", time_step,
                                 f"exceeds the RK4 stability limit {limit:.4g} of the "
                                 "discretised system (Gershgorin bound); use a smaller step")
    t_end = 2 * math.pi * revolutions
    per_sample = max(1, int(round(sample_every / dt)))
    n_steps = int(math.ceil(t_end / dt - 1e-9))
    rhs = RightHandSide(tm, mass)
    active = np.ones(batch, dtype=bool)
    contact_tau = np.full(batch, np.nan)
    contact_min = np.full(batch, np.nan)
    taus, xs, ys, hs = [], [], [], []
    tau = 0.0

    def record(s):
        p, h = pressure_and_film(s.phi, s.x, s.y, tm, rhs._guess)
        hmin = h.min(axis=(1, 2))
        taus.append(tau)
        xs.append(s.x.copy())
        ys.append(s.y.copy())
        hs.append(hmin)
        return hmin

    record(state)
    for step in range(1, n_steps + 1):
        rhs.min_film[:] = np.inf
        state = rk4_step(rhs, state, dt, active.astype(float))
        tau += dt
        if not np.all(np.isfinite(state.x[active])):
            raise ParameterError("time_step", dt, "the integration blew up (non-finite state); "
                                 "the step is above the stability limit")
        # contact: any RK stage of this step reached the threshold film (≤ one step late)
        touching = active & (rhs.min_film <= contact_film)
        if touching.any():
            contact_tau[touching] = tau
            contact_min[touching] = rhs.min_film[touching]
            active &= ~touching          # frozen from here on
        if step % per_sample == 0 or step == n_steps or not active.any():
            record(state)
            if not active.any():
                break
        if step % check_every == 0:
            live = State(state.phi[active], state.x[active], state.y[active],
                         state.u[active], state.v[active])
            new_limit = RK4_STABILITY_RADIUS / stiffness_bound(live, tm)
            if dt > new_limit:
                if time_step is not None:
                    raise ParameterError("time_step", time_step,
                                         f"exceeds the RK4 stability limit {new_limit:.4g} "
                                         f"reached at τ = {tau:.3g}")
                dt = STEP_SAFETY * new_limit   # automatic step: shrink and go on
                per_sample = max(1, int(round(sample_every / dt)))
                n_steps = step + int(math.ceil((t_end - tau) / dt - 1e-9))
        if progress is not None and step % 200 == 0:
            progress(min(tau / t_end, 1.0))
    tau_arr = np.array(taus)
    x = np.array(xs).T
    y = np.array(ys).T
    hmin = np.array(hs).T
    for b in np.flatnonzero(np.isfinite(contact_tau)):   # the orbit ends at contact
        after = tau_arr > contact_tau[b] + 1e-12
        x[b, after] = y[b, after] = hmin[b, after] = np.nan
        last = np.flatnonzero(~after)[-1]
        hmin[b, last] = min(hmin[b, last], contact_min[b])
    sol = tm.static
    x0 = sol.eccentricity * math.cos(sol.attitude_angle)
    y0 = sol.eccentricity * math.sin(sol.attitude_angle)
    growth, whirl, amp, verdicts = classify(tau_arr, x - x0, y - y0, ~active, settle, kick)
    return OrbitBatch(tau_arr, x, y, hmin, (x0, y0), mass, growth, whirl, amp, ~active,
                      contact_tau, tuple(verdicts), dt, rhs.evaluations,
                      _time.perf_counter() - t0, tau / (2 * math.pi))


def fit_growth_rate(tau: np.ndarray, dx: np.ndarray, dy: np.ndarray,
                    max_modes: int = 10, rank_tolerance: float = 1e-5,
                    whirl_band: tuple = (0.02, 3.0)) -> tuple[float, float]:
    """Growth rate σ [1/rad] and whirl ratio of the dominant whirling mode of an orbit.

    Matrix-pencil fit (Hua & Sarkar, IEEE Trans. ASSP 38 (1990) 814) of both coordinates of
    the deviation from equilibrium as one sum of damped exponentials e^{s τ}: the model order
    is the numerical rank of the stacked Hankel matrices, so the decaying pressure modes the
    kick excites are fitted rather than biasing the rotor mode, and no spurious roots appear.
    The rotor mode is the whirling mode (``whirl_band`` on |Im s|) with the largest amplitude
    at the end of the window; its σ is returned with its whirl ratio |Im s|.
    """
    n = tau.size
    if n < 12:
        return math.nan, math.nan
    d = tau[1] - tau[0]
    signals = []
    for sgl in (dx, dy):
        scale = np.abs(sgl).max()
        if np.isfinite(scale) and scale > 0:
            signals.append(sgl / scale)
    if not signals:
        return math.nan, math.nan
    pencil = n // 3
    hankel = np.vstack([np.lib.stride_tricks.sliding_window_view(sgl, pencil + 1)
                        for sgl in signals])
    _, sv, vh = np.linalg.svd(hankel, full_matrices=False)
    rank = int(min(max_modes, np.sum(sv > rank_tolerance * sv[0])))
    if rank == 0:
        return math.nan, math.nan
    v = vh[:rank].conj().T                       # (pencil + 1, rank)
    z = np.linalg.eigvals(np.linalg.pinv(v[:-1]) @ v[1:])
    z = z[np.abs(z) > 1e-12]
    modes = np.log(z.astype(complex)) / d
    # a physical mode neither grows by e^3 per radian nor sits near the Nyquist frequency
    modes = modes[(modes.real < 3.0) & (np.abs(modes.imag) < 0.5 * math.pi / d)]
    if modes.size == 0:
        return math.nan, math.nan
    # amplitudes of each mode in each signal (least squares on the Vandermonde basis)
    basis = np.exp(np.outer(tau - tau[0], modes))
    amps = np.zeros(modes.size)
    for sgl in signals:
        c, *_ = np.linalg.lstsq(basis, sgl.astype(complex), rcond=None)
        amps += np.abs(c * np.exp(modes * (tau[-1] - tau[0])))
    whirling = (np.abs(modes.imag) >= whirl_band[0]) & (np.abs(modes.imag) <= whirl_band[1])
    if not whirling.any():
        return math.nan, math.nan
    k = np.flatnonzero(whirling)[np.argmax(amps[whirling])]
    return float(modes[k].real), float(abs(modes[k].imag))


def classify(tau, dx, dy, contact, settle, kick, growth_tolerance: float = 2e-5,
             cycle_amplitude: float = 0.05):
    """Fit each orbit's growth rate and give its verdict (stable, unstable, limit cycle,
    contact).

    A growth rate within ±``growth_tolerance`` [1/rad] with a final orbit larger than
    ``cycle_amplitude`` (clearances) is a limit cycle: the envelope is flat at a finite size.
    A large orbit shrinking towards such a cycle from outside has a negative fitted rate but
    a final amplitude that stays large, so it is called a limit cycle too, not stable.
    """
    batch = dx.shape[0]
    growth = np.full(batch, np.nan)
    whirl = np.full(batch, np.nan)
    amp = np.full(batch, np.nan)
    verdicts = []
    start = 2 * math.pi * settle
    for b in range(batch):
        valid = np.isfinite(dx[b])
        # fit at most the last 10 revolutions: the dominant mode is settled by then, and the
        # matrix pencil's cost grows with the square of the window
        window = valid & (tau >= start)
        if window.any():
            window &= tau >= tau[window].max() - 20 * math.pi
        r = np.hypot(dx[b], dy[b])
        last = valid & (tau >= tau[valid].max() - 4 * math.pi)
        amp[b] = float(r[last].max()) if last.any() else math.nan
        if contact[b]:
            verdicts.append("contact")
            growth[b] = math.inf
            continue
        growth[b], whirl[b] = fit_growth_rate(tau[window], dx[b][window], dy[b][window])
        # envelope trend in the last part of the run: ratio of peak radii
        half = valid & (tau >= tau[valid].max() - 8 * math.pi) & (tau < tau[valid].max() - 4 * math.pi)
        earlier = float(r[half].max()) if half.any() else amp[b]
        flat = abs(math.log(max(amp[b], 1e-300) / max(earlier, 1e-300))) < 0.05
        if amp[b] > cycle_amplitude and (flat or growth[b] < 0):
            verdicts.append("limit cycle")
        elif growth[b] > growth_tolerance or (growth[b] > 0 and amp[b] > cycle_amplitude):
            verdicts.append("unstable")
        elif growth[b] < -growth_tolerance:
            verdicts.append("stable")
        else:
            verdicts.append("stable" if growth[b] <= 0 else "unstable")
    return growth, whirl, amp, verdicts


# ------------------------------------------------------------------ critical mass
@dataclass(frozen=True)
class CriticalMass:
    """Nonlinear (transient) critical mass M̄_crit = M c ω²/W0 of a rigid rotor.

    critical_mass : interpolated zero of the fitted growth rate between the bracket [-]
    bracket : (largest stable mass, smallest unstable mass) tested [-]
    whirl_ratio : whirl ratio at the threshold [-]
    linear_critical_mass : the linear threshold used to centre the search (nan if unused)
    history : one dict per transient (round, mass, growth_rate, whirl_ratio, verdict)
    transients, rotor_revolutions, evaluations : cost counters; wall_time_s
    success, message
    """

    critical_mass: float
    bracket: tuple
    whirl_ratio: float
    linear_critical_mass: float
    history: tuple
    transients: int
    rotor_revolutions: float
    evaluations: int
    wall_time_s: float
    success: bool
    message: str = ""

    def to_dict(self) -> dict:
        return {"critical_mass": self.critical_mass, "bracket": list(self.bracket),
                "whirl_ratio": self.whirl_ratio,
                "linear_critical_mass": self.linear_critical_mass,
                "transients": self.transients, "rotor_revolutions": self.rotor_revolutions,
                "wall_time_s": self.wall_time_s, "success": self.success,
                "message": self.message}


def _threshold_from_history(history: list) -> tuple:
    """(M̄_crit, whirl ratio, bracket low, bracket high) from all transients so far.

    The growth rate is linear in M̄ near the threshold: the zero of a least-squares line
    through the (up to) four finite growth rates nearest the sign change is the estimate, so
    a single noisy fit (growth rates ~1e-5 within 0.5 % of threshold) cannot break the
    search.  The bracket is the nearest tested masses on either side of that zero.
    """
    pts = sorted((h["mass"], h["growth_rate"], h["whirl_ratio"]) for h in history
                 if not math.isnan(h["growth_rate"]))
    stable = [p for p in pts if p[1] < 0]
    unstable = [p for p in pts if p[1] > 0]
    if not stable or not unstable:
        lo = max((p[0] for p in stable), default=0.0)
        hi = min((p[0] for p in unstable), default=math.inf)
        return math.nan, math.nan, lo, hi
    # the sign change: between the largest stable mass below the smallest unstable one
    first_unstable = min(p[0] for p in unstable)
    last_stable = max((p[0] for p in stable if p[0] < first_unstable), default=None)
    if last_stable is None:
        last_stable = max(p[0] for p in stable)
    centre = 0.5 * (last_stable + first_unstable)
    near = sorted((p for p in pts if math.isfinite(p[1])), key=lambda p: abs(p[0] - centre))[:4]
    m = np.array([p[0] for p in near])
    g = np.array([p[1] for p in near])
    if np.ptp(m) == 0:
        return math.nan, math.nan, last_stable, first_unstable
    slope, intercept = np.polyfit(m, g, 1)
    mc = -intercept / slope if slope > 0 else centre
    mc = min(max(mc, last_stable), first_unstable)     # never outside the verdicts' bracket
    lo = max((p[0] for p in pts if p[0] <= mc), default=0.0)
    hi = min((p[0] for p in pts if p[0] > mc), default=math.inf)
    whirls = [p[2] for p in near if math.isfinite(p[2])]
    whirl = float(np.interp(mc, [p[0] for p in near if math.isfinite(p[2])], whirls)) \
        if whirls else math.nan
    return float(mc), whirl, lo, hi


def find_critical_mass(tm: TransientModel, *, tolerance: float = 0.005,
                       linear_estimate: Optional[float] = None, batch: int = 8,
                       revolutions: float = 5.0, settle: float = 1.0, kick: float = 1e-3,
                       max_rounds: int = 8, progress=None,
                       method: str = "rk4") -> CriticalMass:
    """Find M̄_crit to a relative ``tolerance`` with batches of RK4 transients.

    Each round integrates ``batch`` rotors of different mass together and fits each orbit's
    growth rate (:func:`fit_growth_rate`).  Around a linear estimate the first batch spans
    ±(batch/2)·tolerance; otherwise a geometric batch over 0.25–64 brackets it first.  The
    threshold is the zero of a line fitted to the growth rates nearest the sign change
    (:func:`_threshold_from_history`); rounds go on until the tested masses on either side of
    it are at most 2·tolerance apart.  Contact and limit cycles count as unstable.
    """
    import time as _time

    tolerance = _check_positive("tolerance", tolerance)
    if tolerance >= 0.5:
        raise ParameterError("tolerance", tolerance, "must be < 0.5 (relative)")
    batch = int(_check_positive("batch", batch))
    revolutions = _check_positive("revolutions", revolutions)
    t0 = _time.perf_counter()
    history = []
    if linear_estimate is not None and math.isfinite(linear_estimate):
        half = batch // 2
        offsets = np.concatenate([np.arange(-half, 0) + 0.5, np.arange(0, batch - half) + 0.5])
        masses = linear_estimate * (1 + tolerance * offsets)
    else:
        masses = np.geomspace(0.25, 64.0, batch)
    evaluations = 0
    rotor_revs = 0.0
    message = ""
    mc, whirl, lo, hi = math.nan, math.nan, 0.0, math.inf
    for round_ in range(max_rounds):
        orbit = integrate_orbits(tm, masses, revolutions, kick=kick, settle=settle,
                                 method=method)
        evaluations += orbit.evaluations
        rotor_revs += orbit.revolutions * masses.size
        for k, mm in enumerate(masses):
            g = float(orbit.growth_rate[k])
            if orbit.verdict[k] in ("contact", "limit cycle"):
                g = math.inf if not math.isfinite(g) or g <= 0 else g
            history.append({"round": round_, "mass": float(mm), "growth_rate": g,
                            "whirl_ratio": float(orbit.whirl_ratio[k]),
                            "verdict": orbit.verdict[k]})
        if progress is not None:
            progress((round_ + 1) / max_rounds)
        mc, whirl, lo, hi = _threshold_from_history(history)
        if math.isnan(mc):
            if lo == 0.0 and hi == math.inf:
                message = "no finite growth rate was measured"
                break
            if hi == math.inf:            # everything stable: go heavier
                masses = lo * np.geomspace(1.1, 4.0, batch)
            else:                         # everything unstable: go lighter
                masses = hi / np.geomspace(4.0, 1.1, batch)
            continue
        if (hi - lo) <= 2 * tolerance * mc:
            break
        masses = np.linspace(lo, hi, batch + 2)[1:-1]
    wall = _time.perf_counter() - t0
    ok = math.isfinite(mc) and (hi - lo) <= 2 * tolerance * mc
    if not ok:
        message = message or (f"no bracket of relative width {2 * tolerance:g} after "
                              f"{max_rounds} rounds (bracket {lo:.4g}–{hi:.4g})")
        mc = mc if math.isfinite(mc) else math.nan
    return CriticalMass(mc if ok else math.nan, (lo, hi), whirl,
                        math.nan if linear_estimate is None else float(linear_estimate),
                        tuple(history), len(history), rotor_revs, evaluations, wall, ok,
                        message)


def limit_cycle_amplitudes(tm: TransientModel, masses, revolutions: float = 60.0,
                           kicks: tuple = (0.05, 0.6)):
    """Bifurcation diagram: the limit-cycle size against M̄ above the threshold.

    Each mass runs twice in one batch, from the journal displaced along X by ``kicks[0]``
    (inside the cycle) and by ``kicks[1]`` (outside) [clearances]; where both reach
    the same final amplitude the cycle is established.  Amplitude: largest distance of the
    journal centre from the equilibrium over the last two whirl periods [clearances].
    """
    import pandas as pd

    masses = np.asarray(masses, dtype=float)
    batch = 2 * masses.size
    state = equilibrium_state(tm, batch)
    n = masses.size
    state.x[:n] += kicks[0]
    state.x[n:] += kicks[1]
    orbit = integrate_orbits(tm, np.concatenate([masses, masses]), revolutions, initial=state,
                             settle=revolutions / 2)
    return pd.DataFrame({
        "mass": masses, "amplitude_from_inside": orbit.amplitude[:n],
        "amplitude_from_outside": orbit.amplitude[n:],
        "verdict_from_inside": orbit.verdict[:n], "verdict_from_outside": orbit.verdict[n:],
        "min_film": np.nanmin(orbit.min_film[:n], axis=1),
        "wall_time_s": orbit.wall_time_s})
