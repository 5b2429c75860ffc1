"""One-bearing orbits with the bumps' Coulomb friction: RK4 or RKC with the sliders split off.

The slider positions Z (B, m) of :mod:`.friction_foil` are not an ODE state (they have no
rate): they are carried beside the integrated state (Φ, X, Y, U, V) and updated once after
every accepted step by the play operator (operator splitting, :mod:`.friction_foil`'s
docstring says why it is consistent).  Every stage of a step recovers P and H with the step's
starting Z.  This driver is the one-bearing loop of :mod:`.rk4` with that update between
steps (the integrators' own loops have no post-step hook), stepping with RK4 or RKC
(:mod:`.friction_steps`); with ``tm.friction`` None and rk4 it is rk4's loop exactly.
With a loss factor η > 0 the Kelvin–Voigt foil state W is integrated with the rest and the
sliders enter its rate (:mod:`.foil_state`, "With friction"); they move after each step
from the state's W.

:func:`friction_outcome` states how a run ended: "settled limit cycle" (the orbit's
semi-major axis steady over the last whirl periods), "contact" (the film closed), or "end of
run" (still growing or decaying), with the amplitude and the whirl ratio.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import ParameterError
from ..threads import single_threaded
from .friction_foil import slider_after_step, stuck_share
from .result import OrbitBatch, check_masses, check_positive, finish_orbits
from .friction_steps import check_friction_method, first_step, recheck, take_step
from .system import (RightHandSide, State, TransientModel, equilibrium_state,
                     pressure_and_film, rigid_film)


@dataclass(frozen=True, eq=False)
class FrictionRun:
    """An orbit batch with the sliders: ``orbit`` (:class:`~.result.OrbitBatch`), the final
    state and sliders Z (B, m), and the share of loaded rows stuck at each sample (B, n)."""

    orbit: OrbitBatch
    state: State
    slider: Optional[np.ndarray]
    stuck: Optional[np.ndarray]


@single_threaded
def integrate_friction_orbits(tm: TransientModel, mass, revolutions: float = 10.0, *,
                              kick: float = 1e-3, initial: Optional[State] = None,
                              slider: Optional[np.ndarray] = None,
                              sample_every: float = 0.2, contact_film: float = 0.02,
                              settle: float = 2.0, time_step: Optional[float] = None,
                              check_every: Optional[int] = None,
                              method: str = "rk4") -> FrictionRun:
    """Advance a batch of rotors on one bearing whose bumps rub (RK4, sliders split off).

    Arguments as :func:`gfbopt.transient.orbit.integrate_orbits`; ``method`` 'rk4' (the
    reference, Δτ from the stability bound) or 'rkc' (Δτ for accuracy, stages from the bound;
    ≈ 2.5× fewer evaluations at 24 × 8, ≈ 9× at 72 × 20), :mod:`.friction_steps`;
    ``slider`` : the sliders Z (B, m) or (B, m, n_z + 1) to start from (default: relaxed at
    the equilibrium, Z = W0; with ``initial`` it must be given for a friction model).  A model
    without friction runs the rk4 loop exactly (its answers equal :func:`integrate_orbits`').
    A damped model (η > 0) carries its Kelvin–Voigt state W with the sliders in its rate;
    with μ_f = 0 its answers equal :func:`integrate_orbits`' to 1e-12.
    """
    t0 = time.perf_counter()
    default_check = check_friction_method(method)
    check_every = default_check if check_every is None else int(check_every)
    tm.law.check_engine(method)
    mass = check_masses(mass)
    revolutions = check_positive("revolutions", revolutions)
    batch = mass.size
    state = initial if initial is not None else equilibrium_state(tm, batch)
    if initial is None:
        state.u[:] = kick / math.sqrt(2)
        state.v[:] = kick / math.sqrt(2)
    z = None
    if tm.friction is not None:
        if slider is None:
            if initial is not None:
                raise ParameterError("slider", None, "must be given with ``initial`` for a "
                                     "model with bump friction")
            slider = np.broadcast_to(tm.friction.equilibrium,
                                     (batch,) + tm.friction.equilibrium.shape)
        z = np.array(slider, dtype=float)
    dt, stages = first_step(method, tm, state, z, mass, time_step)
    t_end = 2 * math.pi * revolutions
    per_sample = max(1, int(round(sample_every / dt)))
    n_steps = int(math.ceil(t_end / dt - 1e-9))
    rhs = RightHandSide(tm, mass)
    active = np.ones(batch, dtype=bool)
    contact_tau = np.full(batch, np.nan)
    contact_min = np.full(batch, np.nan)
    taus, xs, ys, hs, stuck = [], [], [], [], []
    tau = 0.0

    def record(s):
        h = pressure_and_film(s.phi, s.x, s.y, tm, rhs.guess, deflection=s.w, slider=z)[1]
        taus.append(tau)
        xs.append(s.x.copy())
        ys.append(s.y.copy())
        hs.append(h.min(axis=(1, 2)))
        if z is not None:
            stuck.append(stuck_share(s.phi, rigid_film(s.x, s.y, tm), z, tm, s.w))

    record(state)
    failure = ""
    step = 0
    while step < n_steps:                    # n_steps grows when the step shrinks
        step += 1
        rhs.min_film[:] = np.inf
        rhs.slider = z                       # every stage: the step's starting sliders
        state = take_step(method, rhs, state, dt, stages, active)
        tau += dt
        if not np.all(np.isfinite(state.x[active])):
            failure = (f"the integration blew up (non-finite state) at τ = {tau:.4g} with "
                       f"Δτ = {dt:.4g}; the step is above the stability limit")
            break
        if z is not None:                    # the play operator after the accepted step
            moved = slider_after_step(state.phi, rigid_film(state.x, state.y, tm), z, tm,
                                      state.w)
            z = np.where(active.reshape((-1,) + (1,) * (z.ndim - 1)), moved, z)
        touching = active & (rhs.min_film <= contact_film)
        if touching.any():
            contact_tau[touching] = tau
            contact_min[touching] = rhs.min_film[touching]
            active &= ~touching
        if step % per_sample == 0 or step == n_steps or not active.any():
            record(state)
            if not active.any():
                break
        if step % check_every == 0:
            dt, stages, changed = recheck(method, tm, state, z, active, dt, stages,
                                          time_step is not None)
            if changed:
                per_sample = max(1, int(round(sample_every / dt)))
                n_steps = step + int(math.ceil((t_end - tau) / dt - 1e-9))
    tau_arr = np.array(taus)
    x, y, hmin = np.array(xs).T, np.array(ys).T, np.array(hs).T
    for b in np.flatnonzero(np.isfinite(contact_tau)):
        after = tau_arr > contact_tau[b] + 1e-12
        x[b, after] = y[b, after] = hmin[b, after] = np.nan
        last = np.flatnonzero(~after)[-1]
        hmin[b, last] = min(hmin[b, last], contact_min[b])
    orbit = finish_orbits(tm, tau_arr, x, y, hmin, ~active, contact_tau, mass, settle=settle,
                          kick=kick, time_step=dt, evaluations=rhs.evaluations, started=t0,
                          revolutions=tau / (2 * math.pi), method=method,
                          success=not failure, message=failure)
    return FrictionRun(orbit, state, z, np.array(stuck).T if stuck else None)


@dataclass(frozen=True)
class FrictionOutcome:
    """How one rotor's run ended (non-dimensional).

    kind : 'settled limit cycle', 'contact' or 'end of run'; amplitude : the orbit's
    semi-major axis over the last window [clearances]; previous : the same over the window
    before it; whirl_ratio γ over the last window [-]; min_film [-]; contact_tau [rad];
    verdict : one line.
    """

    kind: str
    amplitude: float
    previous: float
    whirl_ratio: float
    min_film: float
    contact_tau: float
    verdict: str


def orbit_axes(tau: np.ndarray, dx: np.ndarray, dy: np.ndarray) -> tuple:
    """(semi-major axis, whirl ratio) of the first harmonic of an orbit segment.

    γ = 2π/(mean period) between the first and last upward zero crossings of X − mean
    (linearly interpolated); then the least-squares fit X, Y = c + a cos γτ + b sin γτ over
    the segment, and the semi-major axis of that ellipse, the larger singular value of
    [[a_X, b_X], [a_Y, b_Y]] [clearances] — the describing function's orbit amplitude
    (the semi-major axis of Re(ξ e^{iγτ}), :mod:`gfbopt.linear.friction_onset`).
    """
    ex = dx - dx.mean()
    up = np.flatnonzero((ex[:-1] < 0) & (ex[1:] >= 0))
    if up.size < 2:
        return math.nan, math.nan
    t_up = tau[up] - ex[up] * (tau[up + 1] - tau[up]) / (ex[up + 1] - ex[up])
    gamma = 2 * math.pi * (up.size - 1) / (t_up[-1] - t_up[0])
    basis = np.column_stack([np.ones_like(tau), np.cos(gamma * tau), np.sin(gamma * tau)])
    coef = np.linalg.lstsq(basis, np.column_stack([dx, dy]), rcond=None)[0]
    a = float(np.linalg.svd(coef[1:].T, compute_uv=False)[0])
    return a, gamma


def friction_outcome(orbit: OrbitBatch, rotor: int = 0, periods: int = 6,
                     tolerance: float = 1e-3) -> FrictionOutcome:
    """The end of one rotor's run: contact, a settled limit cycle (the semi-major axis over
    the last ``periods`` whirl periods within ``tolerance`` relative of the window before),
    or the end of the run.

    The default 1e-3 per 6 whirl periods: a settled friction cycle measured 3e-5; an orbit
    drifting at σ ≈ 4e-5 per radian (1 % per 6 periods at γ ≈ 0.5) is "end of run".
    """
    x0, y0 = orbit.equilibrium
    ok = np.isfinite(orbit.x[rotor])
    tau, dx, dy = orbit.tau[ok], orbit.x[rotor][ok] - x0, orbit.y[rotor][ok] - y0
    hmin = float(np.nanmin(orbit.min_film[rotor]))
    whirl = orbit_axes(tau[tau >= 0.75 * tau[-1]], dx[tau >= 0.75 * tau[-1]],
                       dy[tau >= 0.75 * tau[-1]])[1] if tau.size > 8 else math.nan
    span = 2 * math.pi / whirl * periods if math.isfinite(whirl) and whirl > 0 else math.nan
    amp = prev = gamma = math.nan
    if math.isfinite(span) and tau[-1] - tau[0] >= 2 * span:
        last = tau >= tau[-1] - span
        before = (tau >= tau[-1] - 2 * span) & ~last
        amp, gamma = orbit_axes(tau[last], dx[last], dy[last])
        prev = orbit_axes(tau[before], dx[before], dy[before])[0]
    if orbit.contact[rotor]:
        t = float(orbit.contact_tau[rotor])
        return FrictionOutcome("contact", amp, prev, gamma, hmin, t,
                               f"contact (H ≤ contact film) at τ = {t:.4g} rad")
    if math.isfinite(amp) and abs(amp / prev - 1.0) <= tolerance:
        return FrictionOutcome("settled limit cycle", amp, prev, gamma, hmin, math.nan,
                               f"settled limit cycle: semi-major axis {amp:.4g} c at γ = "
                               f"{gamma:.4f}, minimum film {hmin:.4g} c")
    return FrictionOutcome("end of run", amp, prev, gamma, hmin, math.nan,
                           f"end of run: semi-major axis {amp:.4g} c (was {prev:.4g} c "
                           f"{periods} whirl periods before) at γ = {gamma:.4f}")
