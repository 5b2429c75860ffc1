"""Nonlinear time-transient model of a rigid rotor on gas foil bearings (numpy, batched).

State of each rotor (a batch of B rotors advances together, one array per quantity):

* Φ = P H at every grid node, shape (B, m, n_z + 1) — the conserved quantity of the
  time-dependent Reynolds equation 2Λ ∂(PH)/∂τ = R(P, H) (docs/PHYSICS.md), so
  ∂Φ/∂τ = R(P, H)/(2Λ) with R the steady residual of :mod:`gfbopt.discretisation`;
* the journal centre (X, Y) and its velocity (U, V) = (X', Y'), τ = ω t;
* with structural damping (loss factor η > 0) the foil deflection W, one per θ row or per
  node, relaxing as τ_f W' + W = S q (:mod:`.foil_state`); then H = H_r + W and P = Φ/H.
* with Coulomb friction in the bumps (``transient_model(..., friction=True)``) the sliders Z
  per θ row (or node), not integrated but carried beside the state and moved by the play
  operator after each accepted step (:mod:`.friction_foil`, :mod:`.friction_orbit`); every
  stage sees the step's starting Z (``RightHandSide.slider``).

Without damping the foil is massless and follows the pressure at every instant (as in the
static model), so P and H are recovered from Φ and (X, Y) algebraically:

* rigid: H = H_r = 1 − X cos θ − Y sin θ, P = Φ/H;
* simple, axial-mean law: on each θ row H = a with a = H_r + S(P̄ − 1) and P = Φ/a, so
  a² − b a − S Φ̃ = 0 (b, Φ̃ from the row's axial sums) — closed form; with compression-only
  bumps a = max(that, H_r);
* simple, local law: S P² + (H_r − S) P − Φ = 0 per node — closed form;
* hardened (bumps k0/(1 − δ/δ_lim)^n): the row balance in the bump's reaction by a
  safeguarded Newton, to round-off (:mod:`.hardening_recovery`);
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

from ..discretisation import trapezoid_weights
from ..errors import ParameterError
from ..physics.film import force_gauge
from ..physics.film import rigid_film_tabulated
from ..physics.foil_laws import FoilLaw
from ..static import StaticSolution
from ..static.build import row_values, solution_stencil
from ..threads import single_threaded
from .foil_state import KelvinVoigtFoil, foil_bound, kelvin_voigt_foil
from .friction_foil import FrictionFoil, friction_foil, recover_with_slider
from .hardening_recovery import transient_foil_law



@dataclass(frozen=True, eq=False)
class TransientModel:
    """Everything the right-hand side needs, precomputed from a static equilibrium.

    Angles θ [rad] from the load line; all quantities non-dimensional (docs/PHYSICS.md).
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
    law: FoilLaw             # the foil law (gfbopt.physics.foil_laws): owns P/H recovery
    compression_only: bool
    gumbel: bool
    foil_data: Optional[np.ndarray]  # the law's precomputed data (beam: W per unit P̄ − 1)
    foil_state: Optional[KelvinVoigtFoil] = None   # the damped foil's state (η > 0), or None
    ambient: Optional[np.ndarray] = None     # (m,) rows at ambient pressure (seams, pad ends)
    bore: Optional[np.ndarray] = None        # (m,) the bore's clearance change Δc/c
    compliance_rows: Optional[np.ndarray] = None   # (m,) S per θ row (bump zones)
    friction: Optional[FrictionFoil] = None  # the bumps' sliders (μ_f > 0), or None

    @property
    def foil(self) -> str:
        """Name of the foil law: 'rigid', 'simple', 'local' or 'beam'."""
        return self.law.name

    @property
    def shape(self) -> tuple:
        return self.static.pressure.shape


@single_threaded
def transient_model(solution: StaticSolution, reference_whirl_ratio: Optional[float] = None,
                    solver=None, threshold=None, *, friction: bool = False) -> TransientModel:
    """The transient model around a converged static equilibrium ``solution``.

    A seam on the maximum-film line is frozen where the static solution put it (the top foil
    is fixed in the housing).  With structural damping (``solution.model.loss_factor`` η > 0)
    the foil is a Kelvin–Voigt state with τ_f = η/ν_ref (:mod:`.foil_state`):
    ``reference_whirl_ratio`` ν_ref [-] defaults to the linear threshold whirl ratio, taken
    from ``threshold`` (the :class:`gfbopt.linear.LinearThreshold` of ``solution``, when the
    caller has it) or computed (one linearisation, reusing ``solver``); it is refused
    without damping.

    ``friction``: a model with Coulomb friction in the bumps (μ_f > 0) is built with its
    slider state (:mod:`.friction_foil`; axial-mean, hardened or local law, with or without
    the loss factor's Kelvin–Voigt state), integrated by
    :func:`gfbopt.transient.friction_orbit.integrate_friction_orbits` (which
    :func:`gfbopt.transient.orbit.integrate_orbits` hands such a model to; the other drivers
    refuse it: they carry no slider).  Without friction it is today's model.
    """
    if not solution.success:
        raise ParameterError("solution", f"status {solution.status}",
                             "the static equilibrium did not converge; no transient from it")
    model = solution.model
    if solution.load <= 0 or not math.isfinite(solution.attitude_angle_rad):
        raise ParameterError("solution.load", solution.load,
                             "must be > 0 (the rotor mass parameter M̄ = M c ω²/W0 needs a load)")
    m, nzn = solution.pressure.shape
    periodic = model.film == "periodic"
    dtheta = 2 * math.pi / solution.grid.n_theta
    dz = 2 * model.length_ratio / solution.grid.n_z
    tw = dtheta * (np.ones(m) if periodic else trapezoid_weights(m))
    zw = dz * trapezoid_weights(nzn)
    rubbing = friction and model.has_friction
    law = transient_foil_law(model, engine="rk4" if rubbing else "transient")
    foil_data = law.transient_data(model, solution.grid, periodic, dtheta)
    cos, sin = np.cos(solution.theta), np.sin(solution.theta)
    x0 = solution.eccentricity * math.cos(solution.attitude_angle_rad)
    y0 = solution.eccentricity * math.sin(solution.attitude_angle_rad)
    st = solution_stencil(solution)
    bore, s_rows = row_values(model, st, solution.seam_angle_rad)   # the bearing as built
    foil_state = kelvin_voigt_foil(solution, law, 1.0 + bore - x0 * cos - y0 * sin,
                                   reference_whirl_ratio, solver, threshold)
    sliders = None
    if rubbing:
        from ..linear.friction_units import friction_rows

        sliders = friction_foil(solution, 1.0 + bore - x0 * cos - y0 * sin,
                                friction_rows(model, st, solution.seam_angle_rad),
                                "nodes" if law.name == "local" else "rows")
    return TransientModel(
        static=solution, bearing_number=model.bearing_number, compliance=model.compliance,
        load=solution.load, periodic=periodic, cos=cos, sin=sin, theta_weight=tw,
        z_weight=zw, dtheta=dtheta, dz=dz, law=law,
        compression_only=bool(model.compression_only), gumbel=model.subambient == "gumbel",
        foil_data=foil_data, foil_state=foil_state, ambient=st.ambient_rows, bore=bore,
        compliance_rows=s_rows, friction=sliders)


# ----------------------------------------------------------------------- kernel
def flux_residual(p: np.ndarray, h: np.ndarray, tm: TransientModel) -> np.ndarray:
    """Steady Reynolds residual R(P, H) at every node (zero on boundary nodes) [-].

    p : array (..., m, n_z + 1); h : the same shape, or (..., m, 1) when H is uniform along
    each θ row (then H³ is formed per row, and the axial face value is just H³).  The same
    stencil as :func:`gfbopt.discretisation.reynolds_residual`, written with slices: the
    face fluxes fe = 0.25 (H³ + H³_e)(P²_e − P²)/Δθ − 0.5 Λ (PH + PH_e) and
    fn = 0.25 (H³ + H³_n)(P²_n − P²)/ΔZ, R = (fe − fe_w)/Δθ + (fn − fn_s)/ΔZ, with the 1/Δθ
    and 1/ΔZ of the differences folded into the (small, per-row when H is) coefficients and
    every full-size step in place: it is the cost of every right-hand-side evaluation.
    """
    lam = tm.bearing_number
    dth, dz = tm.dtheta, tm.dz
    h3 = h * h * h
    p2 = p * p
    ph = p * h
    res = np.empty_like(p)
    res[..., 0] = 0.0
    res[..., -1] = 0.0
    inner = res[..., 1:-1]
    # axial: (fn − fn_s)/ΔZ on the interior columns
    fn = p2[..., 1:] - p2[..., :-1]
    if h.shape[-1] == 1:
        np.subtract(fn[..., 1:], fn[..., :-1], out=inner)
        inner *= h3 * (0.5 / (dz * dz))
    else:
        fn *= (0.25 / (dz * dz)) * (h3[..., :-1] + h3[..., 1:])
        np.subtract(fn[..., 1:], fn[..., :-1], out=inner)
    # circumferential: fe/Δθ through the face i+½ of every row (wrapping round when periodic)
    advect = 0.5 * lam / dth
    if tm.periodic:
        fe = _east(p2)
        fe -= p2
        fe *= (0.25 / (dth * dth)) * (h3 + _east(h3))
        flow = _east(ph)
        flow += ph
        flow *= advect
        fe -= flow
        inner += fe[..., 1:-1]
        inner -= _west(fe)[..., 1:-1]
    else:
        fe = p2[..., 1:, :] - p2[..., :-1, :]
        fe *= (0.25 / (dth * dth)) * (h3[..., :-1, :] + h3[..., 1:, :])
        flow = ph[..., 1:, :] + ph[..., :-1, :]
        flow *= advect
        fe -= flow
        mid = inner[..., 1:-1, :]
        mid += fe[..., 1:, 1:-1]
        mid -= fe[..., :-1, 1:-1]
    res[..., tm.ambient, :] = 0.0
    return res


def _east(a: np.ndarray) -> np.ndarray:
    """Periodic east neighbour along θ, np.roll(a, -1, axis=-2) (4× faster for small arrays)."""
    return np.concatenate([a[..., 1:, :], a[..., :1, :]], axis=-2)


def _west(a: np.ndarray) -> np.ndarray:
    """Periodic west neighbour along θ, np.roll(a, 1, axis=-2)."""
    return np.concatenate([a[..., -1:, :], a[..., :-1, :]], axis=-2)


def rigid_film(x: np.ndarray, y: np.ndarray, tm: TransientModel) -> np.ndarray:
    """H_r = 1 + B − X cos θ − Y sin θ per θ row, shape (B, m) (:mod:`gfbopt.physics.film`;
    B the bore's clearance change)."""
    return rigid_film_tabulated(x[:, None], y[:, None], tm.cos, tm.sin) + tm.bore


def pressure_and_film(phi: np.ndarray, x: np.ndarray, y: np.ndarray, tm: TransientModel,
                      guess: Optional[np.ndarray] = None, cache: Optional[dict] = None,
                      deflection: Optional[np.ndarray] = None,
                      slider: Optional[np.ndarray] = None) -> tuple[np.ndarray, np.ndarray]:
    """Recover P (B, m, n_z + 1) and H from Φ = P H and the journal position.

    The foil law does it (:meth:`gfbopt.physics.foil_laws.FoilLaw.recover`).  H has shape
    (B, m, n_z + 1) for the local law and (B, m, 1) — uniform along each θ row — otherwise.
    Boundary nodes carry P = 1.  ``guess`` (B, m) is a starting film for the beam's Newton.
    A damped model (``tm.foil_state``) needs the foil state W, ``deflection``: then
    H = H_r + W and P = Φ/H (:meth:`~gfbopt.physics.foil_laws.FoilLaw.recover_deflected`).
    A model with friction (``tm.friction``) needs the slider positions Z (B, m), ``slider``
    (:func:`.friction_foil.recover_with_slider`); with friction and damping both, P and H come
    from W alone (the sliders enter the foil's rate, :meth:`.foil_state.KelvinVoigtFoil.rate`).
    """
    if tm.friction is not None and tm.foil_state is None:
        if slider is None:
            raise ParameterError("slider", None, "the transient model with bump friction "
                                 "needs the slider positions Z: integrate it with "
                                 "gfbopt.transient.friction_orbit.integrate_friction_orbits")
        return recover_with_slider(phi, rigid_film(x, y, tm), slider, tm)
    if tm.foil_state is not None:
        if deflection is None:
            raise ParameterError("deflection", None, "the damped transient model (η > 0) "
                                 "needs the foil state W to recover P and H")
        return tm.law.recover_deflected(phi, rigid_film(x, y, tm), deflection, tm)
    return tm.law.recover(phi, rigid_film(x, y, tm), tm, guess, cache)


def film_force(p: np.ndarray, tm: TransientModel) -> tuple[np.ndarray, np.ndarray]:
    """F = −∬ (P − 1)(cos θ, sin θ) dθ dZ for each rotor (Gümbel: max(P − 1, 0)) [-]."""
    q = force_gauge(p - 1.0, tm.gumbel) @ tm.z_weight                       # (B, m)
    w = tm.theta_weight
    return -(q * tm.cos) @ w, -(q * tm.sin) @ w


@dataclass
class State:
    """A batch of rotor states: Φ (B, m, n_z+1), X, Y, U, V (B,), and the foil state W of a
    damped model ((B, m) per θ row or (B, m, n_z+1) per node; None without damping)."""

    phi: np.ndarray
    x: np.ndarray
    y: np.ndarray
    u: np.ndarray
    v: np.ndarray
    w: Optional[np.ndarray] = None

    def axpy(self, alpha, d: "State") -> "State":
        """self + alpha·d; ``alpha`` a scalar or one value per rotor (B,)."""
        a = np.asarray(alpha, dtype=float)
        ap = a[:, None, None] if a.ndim else a
        w = None if self.w is None else self.w + _per_rotor(a, self.w) * d.w
        return State(self.phi + ap * d.phi, self.x + a * d.x, self.y + a * d.y,
                     self.u + a * d.u, self.v + a * d.v, w)

    def take(self, rotors) -> "State":
        """The rotors selected by ``rotors`` (index or boolean mask), as a new batch."""
        return State(self.phi[rotors], self.x[rotors], self.y[rotors], self.u[rotors],
                     self.v[rotors], None if self.w is None else self.w[rotors])


def _per_rotor(a: np.ndarray, like: np.ndarray) -> np.ndarray:
    """A scalar, or one value per rotor shaped to broadcast against ``like`` (B, ...)."""
    return a.reshape(a.shape + (1,) * (like.ndim - 1)) if a.ndim else a



class RightHandSide:
    """dState/dτ for a batch of rotors with masses ``mass`` (M̄, shape (B,)).

    Keeps the last beam films as the Newton guess of the next evaluation (``guess``; the
    integrators thin it with the batch when rotors leave it).
    """

    def __init__(self, tm: TransientModel, mass: np.ndarray):
        self.tm = tm
        self.mass_load = np.asarray(mass, dtype=float) * tm.load
        self.guess = None
        self._cache: dict = {}
        self.evaluations = 0
        #: the sliders Z (B, m) every stage of the current step sees (friction model only)
        self.slider = None
        #: smallest film H seen per rotor since the last reset (contact detection) [-]
        self.min_film = np.full(self.mass_load.size, np.inf)

    def __call__(self, s: State) -> State:
        tm = self.tm
        self.evaluations += 1
        p, h = pressure_and_film(s.phi, s.x, s.y, tm, self.guess, self._cache, s.w,
                                 self.slider)
        np.minimum(self.min_film, h.min(axis=(1, 2)), out=self.min_film)
        if tm.law.name == "beam":
            self.guess = h[..., 0]
        dphi = flux_residual(p, h, tm)
        dphi /= 2 * tm.bearing_number
        fx, fy = film_force(p, tm)
        dw = None if tm.foil_state is None else tm.foil_state.rate(p, s.w, tm, self.slider)
        return State(dphi, s.u, s.v, (fx + tm.load) / self.mass_load, fy / self.mass_load, dw)


def equilibrium_state(tm: TransientModel, batch: int) -> State:
    """The static equilibrium replicated ``batch`` times (Φ = P H, journal at rest)."""
    sol = tm.static
    phi = np.broadcast_to(sol.pressure * sol.film, (batch,) + sol.pressure.shape).copy()
    x0 = sol.eccentricity * math.cos(sol.attitude_angle_rad)
    y0 = sol.eccentricity * math.sin(sol.attitude_angle_rad)
    full = lambda v: np.full(batch, v)  # noqa: E731
    w = None
    if tm.foil_state is not None:
        w0 = tm.foil_state.equilibrium
        w = np.broadcast_to(w0, (batch,) + w0.shape).copy()
    return State(phi, full(x0), full(y0), full(0.0), full(0.0), w)


# -------------------------------------------------------------- stability bound
def stiffness_bound(s: State, tm: TransientModel, slider: Optional[np.ndarray] = None) -> float:
    """Gershgorin bound on |λ| of ∂(dΦ/dτ)/∂Φ at state ``s`` [1/rad of shaft rotation].

    With P = Φ/H (foil coupling neglected: it is non-local and non-stiff), row sums of
    |∂R/∂P_k|/H_k over the five-point stencil, over 2Λ.  RK4 is stable for Δτ·λ ≤ 2.78.
    A damped model's foil rows (:func:`.foil_state.foil_bound`) are included: the bound is
    the larger of the two.  ``slider``: the sliders Z of a friction model.
    """
    p, h = pressure_and_film(s.phi, s.x, s.y, tm, deflection=s.w, slider=slider)
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
    bound = (diag + off)[..., :, 1:-1][..., ~tm.ambient, :]
    film = float(bound.max() / (2 * lam))
    return film if tm.foil_state is None else max(film, foil_bound(p, h, tm))


def _shift(a: np.ndarray, k: int) -> np.ndarray:
    """Non-periodic neighbour along θ (edge rows repeat; they are boundary rows anyway)."""
    if k == -1:
        return np.concatenate([a[..., 1:, :], a[..., -1:, :]], axis=-2)
    return np.concatenate([a[..., :1, :], a[..., :-1, :]], axis=-2)
