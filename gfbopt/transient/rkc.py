"""Damped second-order Runge–Kutta–Chebyshev (RKC2), batched over rotors.

Why a stabilised explicit method.  The method-of-lines system is stiff only through the
diffusion part of the Reynolds operator: its spectrum is essentially real and negative, and
its radius ρ grows with the square of the grid spacing (ρ ≈ 1570 per radian at 144 × 36,
ε = 0.4, Λ = 2, S = 1).  RK4 must keep Δτ·ρ ≤ 2.78, i.e. Δτ ≈ 0.0016 there, although the
physics (the whirl, period ≈ 13 rad, and the film's relaxation, ≈ 1.4 rad) is resolved to
1e-5 by steps sixty times longer.  An s-stage RKC method has a real stability interval
β(s) ≈ 0.653 s² that grows with the *square* of the number of stages, so the cost per unit
of time grows only with √ρ: one RKC step of Δτ = 0.1 needs ≈ 17 right-hand-side evaluations
at 144 × 36 where RK4 needs ≈ 250.

The method (Sommeijer, Shampine & Verwer 1998; Verwer 1996), with s stages, step Δτ,
F = the right-hand side, T_j the Chebyshev polynomials of the first kind, damping ε = 2/13,
w0 = 1 + ε/s², w1 = T_s'(w0)/T_s''(w0), b_j = T_j''(w0)/T_j'(w0)² (b0 = b1 = b2),
a_j = 1 − b_j T_j(w0)::

    Y0 = y_n,   Y1 = Y0 + μ̃1 Δτ F(Y0),                       μ̃1 = b1 w1
    Yj = (1 − μj − νj) Y0 + μj Y(j−1) + νj Y(j−2) + μ̃j Δτ F(Y(j−1)) + γ̃j Δτ F(Y0)
    μj = 2 b_j w0 / b(j−1),  νj = −b_j / b(j−2),  μ̃j = 2 b_j w1 / b(j−1),  γ̃j = −a(j−1) μ̃j
    y_(n+1) = Ys

It is second order for every s ≥ 2 and its stability polynomial is
R_s(z) = a_s + b_s T_s(w0 + w1 z), so |R_s| ≤ 1 on the real interval [−β(s), 0] with
β(s) = (1 + w0)/w1 (:func:`rkc_stability_interval`); the damping ε keeps |R_s| ≤ 1 − ε/3
away from the ends and gives the region a strip of finite width round the real axis.
ROCK2 (Abdulle & Medovikov 2001) has a ≈ 25 % longer interval (≈ 0.81 s², i.e. ≈ 10 %
fewer stages) but needs tabulated orthogonal-polynomial coefficients; RKC's are closed
forms, so RKC was chosen.

Stages and step.  The step is chosen for accuracy, not stability (:func:`accuracy_step`):
Δτ = min(0.1, T_rotor/30, T_film/4), with T_rotor the period of the fastest rotor
oscillation the film allows and T_film the relaxation time of the slowest film mode.  The
stage count is then the smallest s with Δτ·ρ ≤ 0.9 β(s), ρ the Gershgorin bound of
:func:`gfbopt.transient.system.stiffness_bound` (1–12 % above the true spectral radius).
With structural damping the bound includes the Kelvin–Voigt foil rows
(:mod:`.foil_state`): real relaxation rates ≈ (1 + S P/H)/τ_f, a few per radian at η = 0.3,
so the stage count is the undamped one; only a very small η makes them the stiffest part
(the bound then stays within 2× the true radius: tests/verification/test_kelvin_voigt.py).
The bound is re-checked every ``check_every`` steps on the rotors still running; when it has
grown, automatic stages are raised (or, with a stage count given, the automatic step shrunk).
A step or stage count given by the user outside the stability region is refused with the
bound it violates (ParameterError); a violation that appears during the run when both were
given ends the run with ``success=False`` and the bound in the message.

Accuracy study behind the default step (benchmarks/bench_integrators.py; 72 × 20, ε = 0.4,
S = 1, periodic film, one rotor at M̄ = 1.04 M̄_crit kicked as usual, 5 revolutions, growth
rate σ and whirl ratio γ fitted after the first; error Δσ, Δγ against RK4 at 0.9 × its
stability limit):

=================  =======================  =======================  =======================
Δτ [rad]           Λ = 2, L/D = 1           Λ = 0.5, L/D = 1         Λ = 2, L/D = 0.5
                   (T_film = 1.44)          (T_film = 0.37)          (T_film = 0.37)
=================  =======================  =======================  =======================
0.4                Δσ 1.4e-4, Δγ 1.2e-3     1.2e-4, 1.1e-3           6.3e-5, 1.1e-3
0.2                2.2e-5, 3.0e-4           1.3e-5, 2.7e-4           −5.2e-5, 2.3e-4
0.1                3.4e-6, 7.8e-5           3.6e-6, 7.0e-5           3.0e-6, 6.9e-5
0.05               6.5e-7, 2.0e-5           7.5e-7, 1.8e-5           −1.0e-6, 1.5e-5
default            0.1: as above            0.0875: 4.2e-6, 5.8e-5   0.093: −2.5e-6, 4.6e-5
RHS evaluations    2835 at 0.1 (RK4 21392)  5670 (RK4 90464)         4410 (RK4 51920)
=================  =======================  =======================  =======================

(results/benchmarks/integrators.json.)  At the same grid the critical-mass search takes
0.56 s with rkc, 4.5 s with rk4 and 2.8 s with bdf for the simple foil; for the rigid
bearing, whose five-point Jacobian suits BDF, 1.1 s, 3.5 s and 0.9 s.

The error is second order and set by the whirl (γ ≈ 0.48), not by the film: at Δτ = 0.1 it is
the same whether the step is 1/14 or 1/4 of T_film.  Δσ = 3e-6 moves the critical mass by
≈ 0.005 % (dσ/dM̄ ≈ 0.034 per unit M̄ near M̄_crit ≈ 2), a hundred times below the default
search tolerance of 0.5 %, so Δτ = 0.1 is the default.  T_rotor/30 and T_film/4 guard light
rotors (fast oscillation) and very short film times; where they bind in the study (0.0875,
0.093) the error stays at the Δτ = 0.1 level.

References
----------
B. P. Sommeijer, L. F. Shampine, J. G. Verwer, "RKC: an explicit solver for parabolic
PDEs", J. Comput. Appl. Math. 88(2) (1998) 315–326, doi:10.1016/S0377-0427(97)00219-7.
J. G. Verwer, "Explicit Runge–Kutta methods for parabolic partial differential equations",
Appl. Numer. Math. 22(1–3) (1996) 359–379, doi:10.1016/S0168-9274(96)00022-0.
A. Abdulle, A. A. Medovikov, "Second order Chebyshev methods based on orthogonal
polynomials", Numer. Math. 90(1) (2001) 1–18, doi:10.1007/s002110100292.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import lru_cache
from typing import Optional

import numpy as np

from ..errors import ConvergenceError, ParameterError
from ..threads import single_threaded
from .result import OrbitBatch, check_positive, finish_orbits
from .system import (RightHandSide, State, TransientModel, equilibrium_state,
                     pressure_and_film, stiffness_bound)

#: Damping parameter ε of damped RKC2 (Sommeijer et al. 1998).
DAMPING = 2.0 / 13.0
#: Fraction of the stability interval the automatic stage count uses: Δτ·ρ ≤ 0.9 β(s).
STAGE_SAFETY = 0.9
#: Fewest and most stages (s ≥ 2 for second order; many stages cost round-off).
MIN_STAGES, MAX_STAGES = 2, 250
#: Default step limits (module docstring): Δτ ≤ 0.1 rad, ≤ T_rotor/30, ≤ T_film/4.
MAX_STEP = 0.1
STEPS_PER_ROTOR_PERIOD = 30.0
STEPS_PER_FILM_TIME = 4.0


@dataclass(frozen=True)
class RKCCoefficients:
    """Coefficients of the s-stage damped RKC2 method (module docstring).

    mu, nu, mu_tilde, gamma_tilde : arrays indexed by stage j = 0..s (entries 0 unused; for
    j = 1 only mu_tilde is used); stability_interval β(s) on the negative real axis.
    """

    stages: int
    mu: np.ndarray
    nu: np.ndarray
    mu_tilde: np.ndarray
    gamma_tilde: np.ndarray
    stability_interval: float


@lru_cache(maxsize=None)
def rkc_coefficients(stages: int, damping: float = DAMPING) -> RKCCoefficients:
    """The damped RKC2 coefficients for ``stages`` ≥ 2 (recurrences of Sommeijer et al. 1998)."""
    s = int(stages)
    if s < MIN_STAGES:
        raise ParameterError("stages", stages, f"must be an integer >= {MIN_STAGES} (RKC2)")
    w0 = 1.0 + damping / s**2
    # T_j(w0), T_j'(w0), T_j''(w0) by the three-term recurrence
    t = np.zeros(s + 1)
    d1t = np.zeros(s + 1)
    d2t = np.zeros(s + 1)
    t[0], t[1], d1t[1] = 1.0, w0, 1.0
    for j in range(2, s + 1):
        t[j] = 2 * w0 * t[j - 1] - t[j - 2]
        d1t[j] = 2 * w0 * d1t[j - 1] - d1t[j - 2] + 2 * t[j - 1]
        d2t[j] = 2 * w0 * d2t[j - 1] - d2t[j - 2] + 4 * d1t[j - 1]
    w1 = d1t[s] / d2t[s]
    b = np.zeros(s + 1)
    b[2:] = d2t[2:] / d1t[2:] ** 2
    b[0] = b[1] = b[2]
    a = 1.0 - b * t
    mu = np.zeros(s + 1)
    nu = np.zeros(s + 1)
    mu_t = np.zeros(s + 1)
    gam = np.zeros(s + 1)
    mu_t[1] = b[1] * w1
    for j in range(2, s + 1):
        mu[j] = 2 * b[j] * w0 / b[j - 1]
        nu[j] = -b[j] / b[j - 2]
        mu_t[j] = 2 * b[j] * w1 / b[j - 1]
        gam[j] = -a[j - 1] * mu_t[j]
    return RKCCoefficients(s, mu, nu, mu_t, gam, (1.0 + w0) / w1)


def rkc_stability_interval(stages: int) -> float:
    """β(s): the s-stage damped RKC2 method is stable for Δτ·λ ∈ [−β(s), 0] (≈ 0.653 s²)."""
    return rkc_coefficients(stages).stability_interval


def stages_for(product: float, safety: float = STAGE_SAFETY) -> int:
    """Smallest stage count s with Δτ·ρ = ``product`` ≤ safety·β(s) (at least 2)."""
    s = max(MIN_STAGES, int(math.ceil(math.sqrt(max(product, 0.0) / (0.653 * safety)))) - 1)
    while rkc_stability_interval(s) * safety < product:
        s += 1
    return s


def _combine(terms):
    """Σ c·v over (c, v) pairs of arrays (or of States, field by field)."""
    (c0, v0), rest = terms[0], terms[1:]
    if isinstance(v0, State):
        names = ("phi", "x", "y", "u", "v") + (("w",) if v0.w is not None else ())
        return State(*(_combine([(c, getattr(v, name)) for c, v in terms]) for name in names))
    out = np.multiply(v0, c0)
    tmp = np.empty_like(out)
    for c, v in rest:
        np.multiply(v, c, out=tmp)
        out += tmp
    return out


def rkc_step(f, y, dt: float, stages: int):
    """One damped RKC2 step of ``stages`` stages: y_n → y_(n+1) (module docstring).

    ``y`` is a numpy array or a :class:`State`; ``f(y)`` returns the same kind.  Costs
    ``stages`` evaluations of ``f``.
    """
    co = rkc_coefficients(stages)
    f0 = f(y)
    y_prev2 = y
    y_prev = _combine([(1.0, y), (co.mu_tilde[1] * dt, f0)])
    for j in range(2, co.stages + 1):
        fj = f(y_prev)
        mu, nu = co.mu[j], co.nu[j]
        y_new = _combine([(1.0 - mu - nu, y), (mu, y_prev), (nu, y_prev2),
                          (co.mu_tilde[j] * dt, fj), (co.gamma_tilde[j] * dt, f0)])
        y_prev2, y_prev = y_prev, y_new
    return y_prev


def pack(s: State) -> np.ndarray:
    """A batch state as one array (B, m (n_z + 1) [+ foil] + 4): Φ, the damped foil's W
    when there is one, then X, Y, U, V (always last)."""
    foil = [] if s.w is None else [s.w.reshape(s.w.shape[0], -1)]
    return np.concatenate([s.phi.reshape(s.phi.shape[0], -1)] + foil +
                          [s.x[:, None], s.y[:, None], s.u[:, None], s.v[:, None]], axis=1)


def unpack(z: np.ndarray, shape: tuple, foil_shape: Optional[tuple] = None) -> State:
    """The :class:`State` (views) of a packed batch ``z``; ``shape`` = (m, n_z + 1);
    ``foil_shape`` the shape of one rotor's foil state W (None without damping)."""
    n = shape[0] * shape[1]
    w = None
    if foil_shape is not None:
        size = int(np.prod(foil_shape))
        w = z[:, n:n + size].reshape((z.shape[0],) + tuple(foil_shape))
        n += size
    return State(z[:, :shape[0] * shape[1]].reshape((z.shape[0],) + tuple(shape)), z[:, n],
                 z[:, n + 1], z[:, n + 2], z[:, n + 3], w)


def _unpack(z: np.ndarray, tm: TransientModel) -> State:
    """:func:`unpack` with the shapes of ``tm``."""
    foil = None if tm.foil_state is None else tm.foil_state.equilibrium.shape
    return unpack(z, tm.shape, foil)


# ------------------------------------------------------------------ default step
def film_time(tm: TransientModel) -> float:
    """Relaxation time [rad] of the slowest film mode, 1/κ1 (order of magnitude).

    Linearised about the equilibrium, Φ' ≈ (P H²/(2Λ)) ∂²Φ/∂Z² + …; the lowest axial mode of
    a film open at Z = ±L/D has wavenumber π/(2 L/D), so κ1 ≈ P̄ H̄² (π/(2 L/D))²/(2Λ) with
    the mean P and H of the equilibrium.  At ε = 0.4, Λ = 2, S = 1, L/D = 1: ≈ 1.4 rad.
    """
    sol = tm.static
    half_length = tm.dz * sol.grid.n_z / 2.0          # L/D
    k1 = math.pi / (2.0 * half_length)
    kappa = float(np.mean(sol.pressure) * np.mean(sol.film ** 2)) * k1 ** 2 / (
        2.0 * tm.bearing_number)
    return 1.0 / kappa


def rotor_period(tm: TransientModel, state: State, mass: np.ndarray) -> float:
    """Shortest period [rad] of a rotor oscillating on the film's instantaneous stiffness.

    K∞ = ‖∂F/∂(X, Y)‖ at fixed Φ (the film cannot flow in an instant: the stiffest response
    it has), by central differences; the period 2π √(M̄ W̄0/K∞) of the lightest rotor, or
    the synchronous period 2π when the rotor's is longer (a heavy rotor still whirls).
    """
    one = state.take(slice(0, 1))
    rhs = RightHandSide(tm, np.ones(1))
    h = 1e-6
    cols = []
    for dx, dy in ((h, 0.0), (0.0, h)):
        plus = rhs(State(one.phi, one.x + dx, one.y + dy, one.u, one.v, one.w))
        minus = rhs(State(one.phi, one.x - dx, one.y - dy, one.u, one.v, one.w))
        cols.append([(plus.u[0] - minus.u[0]) / (2 * h), (plus.v[0] - minus.v[0]) / (2 * h)])
    k_inf = float(np.linalg.norm(np.array(cols), 2)) * tm.load      # (per M̄ = 1) × W̄0
    omega = math.sqrt(k_inf / (float(np.min(mass)) * tm.load)) if k_inf > 0 else 0.0
    return 2 * math.pi / max(omega, 1.0)


def accuracy_step(tm: TransientModel, state: State, mass: np.ndarray) -> float:
    """The default RKC step Δτ [rad]: min(0.1, T_rotor/30, T_film/4) (module docstring)."""
    return min(MAX_STEP, rotor_period(tm, state, mass) / STEPS_PER_ROTOR_PERIOD,
               film_time(tm) / STEPS_PER_FILM_TIME)


def _stages_option(stages) -> int:
    if isinstance(stages, bool) or not float(stages).is_integer():
        raise ParameterError("stages", stages, f"must be an integer >= {MIN_STAGES}")
    s = int(stages)
    if not MIN_STAGES <= s <= MAX_STAGES:
        raise ParameterError("stages", stages,
                             f"must be an integer in [{MIN_STAGES}, {MAX_STAGES}]")
    return s


def _violation(dt: float, stages: int, rho: float) -> str:
    """The stability rule Δτ·ρ ≤ β(s), stated with its numbers."""
    beta = rkc_stability_interval(stages)
    need = stages_for(dt * rho, safety=1.0)
    return (f"Δτ·ρ = {dt:.4g} × {rho:.4g} = {dt * rho:.4g} exceeds the RKC stability "
            f"interval β({stages}) = {beta:.4g} (ρ: Gershgorin bound of the discretised "
            f"system); use ≥ {need} stages or Δτ ≤ {beta / rho:.4g}")


def _step_and_stages(tm: TransientModel, state: State, mass: np.ndarray, rho: float,
                     time_step: Optional[float], stages: Optional[int]) -> tuple:
    """(Δτ, s) at the start of a run; a given step or stage count outside the stability
    region is refused with the bound it violates."""
    if stages is not None:
        stages = _stages_option(stages)
    if time_step is not None:
        dt = check_positive("time_step", time_step)
    elif stages is not None:
        dt = min(accuracy_step(tm, state, mass),
                 STAGE_SAFETY * rkc_stability_interval(stages) / rho)
    else:
        dt = accuracy_step(tm, state, mass)
    if stages is not None:
        if dt * rho > rkc_stability_interval(stages):
            name, value = ("time_step", time_step) if time_step is not None else \
                ("stages", stages)
            raise ParameterError(name, value, _violation(dt, stages, rho))
        return dt, stages
    stages = stages_for(dt * rho)
    if stages > MAX_STAGES:
        if time_step is not None:
            raise ParameterError("time_step", time_step, _violation(dt, MAX_STAGES, rho)
                                 + f" (at most {MAX_STAGES} stages)")
        stages = MAX_STAGES
        dt = STAGE_SAFETY * rkc_stability_interval(stages) / rho
    return dt, stages


class _Packed:
    """The right-hand side on packed batch states (see :func:`pack`)."""

    def __init__(self, tm: TransientModel, mass: np.ndarray):
        self.rhs = RightHandSide(tm, mass)
        self.tm = tm

    def __call__(self, z: np.ndarray) -> np.ndarray:
        return pack(self.rhs(_unpack(z, self.tm)))


@single_threaded
def integrate_rkc(tm: TransientModel, mass: np.ndarray, revolutions: float, *,
                  kick: float, initial: Optional[State], sample_every: float,
                  contact_film: float, settle: float, progress=None,
                  time_step: Optional[float] = None, stages: Optional[int] = None,
                  check_every: int = 5) -> OrbitBatch:
    """Advance a batch of rotors with damped RKC2 (arguments as
    :func:`gfbopt.transient.orbit.integrate_orbits`, already validated).

    time_step : Δτ [rad]; default :func:`accuracy_step` (limited by the stability
        interval of ``stages`` when those are given).
    stages : s ≥ 2; default the fewest with Δτ·ρ ≤ 0.9 β(s).
    check_every : steps between re-checks of the stiffness bound.

    Rotors that reach contact leave the batch (their orbit ends there); the others go on.
    """
    t0 = time.perf_counter()
    batch = mass.size
    state = initial if initial is not None else equilibrium_state(tm, batch)
    if initial is None:
        state.u[:] = kick / math.sqrt(2)
        state.v[:] = kick / math.sqrt(2)
    fixed_stages, fixed_step = stages is not None, time_step is not None
    rho = stiffness_bound(state, tm)
    dt, stages = _step_and_stages(tm, state, mass, rho, time_step, stages)
    t_end = 2 * math.pi * revolutions
    per_sample = max(1, int(round(sample_every / dt)))
    n_steps = int(math.ceil(t_end / dt - 1e-9))

    z = pack(state)
    live = np.arange(batch)                     # rotors still running
    f = _Packed(tm, mass)
    evaluations = 0
    contact_tau = np.full(batch, np.nan)
    contact_min = np.full(batch, np.nan)
    x_now, y_now = state.x.copy(), state.y.copy()
    h_now = np.full(batch, np.nan)
    taus, xs, ys, hs = [], [], [], []
    tau = 0.0
    stage_counts = {stages}

    def record() -> None:
        s = _unpack(z, tm)
        x_now[live], y_now[live] = s.x, s.y
        _, h = pressure_and_film(s.phi, s.x, s.y, tm, f.rhs.guess, deflection=s.w)
        h_now[live] = h.min(axis=(1, 2))
        taus.append(tau)
        xs.append(x_now.copy())
        ys.append(y_now.copy())
        hs.append(h_now.copy())

    record()
    failure = ""
    shown = 0.0
    step = 0
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        while step < n_steps:
            step += 1
            f.rhs.min_film[:] = np.inf
            try:
                z = rkc_step(f, z, dt, stages)
            except ConvergenceError as err:
                failure = f"the foil recovery failed at τ = {tau:.4g}: {err}"
                break
            tau += dt
            if not np.all(np.isfinite(z[:, -4:])):
                failure = (f"the integration blew up (non-finite state) at τ = {tau:.4g} "
                           f"with Δτ = {dt:.4g} and {stages} stages")
                break
            # contact: any stage of this step reached the threshold film
            touching = f.rhs.min_film <= contact_film
            if touching.any():
                contact_tau[live[touching]] = tau
                contact_min[live[touching]] = f.rhs.min_film[touching]
            if step % per_sample == 0 or step == n_steps or touching.all():
                record()
            if touching.any():                   # those rotors leave the batch
                if touching.all():
                    break
                keep = ~touching
                guess = None if f.rhs.guess is None else f.rhs.guess[keep]
                evaluations += f.rhs.evaluations
                live, z = live[keep], z[keep]
                f = _Packed(tm, mass[live])
                f.rhs.guess = guess
            if step % check_every == 0:          # re-check the stiffness bound
                rho = stiffness_bound(_unpack(z, tm), tm)
                if dt * rho > STAGE_SAFETY * rkc_stability_interval(stages):
                    if not fixed_stages:
                        stages = stages_for(dt * rho)
                        if stages > MAX_STAGES:
                            failure = _violation(dt, MAX_STAGES, rho) + f" at τ = {tau:.3g}"
                            break
                        stage_counts.add(stages)
                    elif not fixed_step:
                        dt = STAGE_SAFETY * rkc_stability_interval(stages) / rho
                        per_sample = max(1, int(round(sample_every / dt)))
                        n_steps = step + int(math.ceil((t_end - tau) / dt - 1e-9))
                    elif dt * rho > rkc_stability_interval(stages):
                        failure = _violation(dt, stages, rho) + f" (reached at τ = {tau:.3g})"
                        break
            if progress is not None and tau >= (shown + 0.01) * t_end:
                shown = min(tau / t_end, 1.0)
                progress(shown)
    evaluations += f.rhs.evaluations
    if progress is not None and not failure:
        progress(1.0)
    tau_arr = np.array(taus)
    x, y, hmin = np.array(xs).T, np.array(ys).T, np.array(hs).T
    contact = np.isfinite(contact_tau)
    for b in np.flatnonzero(contact):            # the orbit ends at contact
        after = tau_arr > contact_tau[b] + 1e-12
        x[b, after] = y[b, after] = hmin[b, after] = np.nan
        last = np.flatnonzero(~after)[-1]
        hmin[b, last] = min(hmin[b, last], contact_min[b])
    if failure:
        failure += f" (stage counts used: {sorted(stage_counts)})"
    return finish_orbits(tm, tau_arr, x, y, hmin, contact, contact_tau, mass, settle=settle,
                         kick=kick, time_step=dt, evaluations=evaluations, started=t0,
                         revolutions=tau / (2 * math.pi), method="rkc",
                         success=not failure, message=failure)
