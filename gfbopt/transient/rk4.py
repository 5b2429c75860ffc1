"""Classic fourth-order Runge–Kutta, batched over rotors: the reference integrator.

Explicit RK4 on the method-of-lines system is limited by the diffusion part of the Reynolds
operator: its stable step shrinks with the square of the grid spacing.  The step is taken
from a Gershgorin bound on the Φ-Jacobian (:func:`gfbopt.transient.system.stiffness_bound`),
re-checked during the run; a step above the limit is refused, never run silently (just past
the limit a run need not blow up: it can settle on a false equilibrium).
"""
from __future__ import annotations

import math
import time
from typing import Optional

import numpy as np

from ..errors import ParameterError
from ..threads import single_threaded
from .result import OrbitBatch, check_positive, finish_orbits
from .system import RightHandSide, State, TransientModel, equilibrium_state, stiffness_bound
from .system import pressure_and_film

#: RK4's stability boundary on the negative real axis is 2.785; on the imaginary axis 2.828.
RK4_STABILITY_RADIUS = 2.78
#: Fraction of the stability limit used by the automatic step.  The Gershgorin bound is within
#: 5 % of the true spectral radius here (its spectrum is real and negative: diffusion), see
#: the transient tests, so 0.9 keeps Δτ·λ_max ≤ 0.9 × 2.78.
STEP_SAFETY = 0.9


def _rk4_sum(a, b, c, d):
    out = b + c
    out *= 2.0
    out += a
    out += d
    return out


def _rk4_update(y: State, w, k1: State, k2: State, k3: State, k4: State) -> State:
    """y + w (k1 + 2 k2 + 2 k3 + k4) in one pass, ``w`` scalar or per rotor."""
    wp = w[:, None, None] if np.ndim(w) else w
    foil = None
    if y.w is not None:                 # the damped foil's state
        wf = w.reshape(w.shape + (1,) * (y.w.ndim - 1)) if np.ndim(w) else w
        foil = y.w + wf * _rk4_sum(k1.w, k2.w, k3.w, k4.w)
    return State(y.phi + wp * _rk4_sum(k1.phi, k2.phi, k3.phi, k4.phi),
                 y.x + w * _rk4_sum(k1.x, k2.x, k3.x, k4.x),
                 y.y + w * _rk4_sum(k1.y, k2.y, k3.y, k4.y),
                 y.u + w * _rk4_sum(k1.u, k2.u, k3.u, k4.u),
                 y.v + w * _rk4_sum(k1.v, k2.v, k3.v, k4.v), foil)


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
    if isinstance(y, State):          # one pass instead of four (speed)
        return _rk4_update(y, w, k1, k2, k3, k4)
    return y.axpy(w, k1).axpy(2 * w, k2).axpy(2 * w, k3).axpy(w, k4)


class _Rows:
    """Packed rows (a numpy array, leading axis the batch) with the ``axpy`` that
    :func:`rk4_step` needs."""

    __slots__ = ("z",)

    def __init__(self, z: np.ndarray):
        self.z = z

    def axpy(self, alpha, d: "_Rows") -> "_Rows":
        a = np.asarray(alpha, dtype=float)
        return _Rows(self.z + (a[:, None, None] if a.ndim else a) * d.z)


def rk4_array_step(f, z: np.ndarray, dt: float, stages=None) -> np.ndarray:
    """One RK4 step of a packed system dz/dτ = f(z) (a (B, ...) numpy array; ``alpha`` of
    a stage scalar or per run); ``stages`` is unused (the signature of every method's
    ``step`` in :data:`gfbopt.transient.orbit.METHODS`)."""
    return rk4_step(lambda r: _Rows(f(r.z)), _Rows(z), dt).z


def stable_time_step(tm: TransientModel, state: State, safety: float = STEP_SAFETY) -> float:
    """Largest RK4 step Δτ [rad] with Δτ·λ_max ≤ safety × 2.78 (Gershgorin bound)."""
    return safety * RK4_STABILITY_RADIUS / stiffness_bound(state, tm)


@single_threaded
def rk4_first_step(rho: float, time_step=None) -> float:
    """Δτ of an RK4 run whose right-hand side has the stiffness bound ``rho``: STEP_SAFETY
    times the stability limit RK4_STABILITY_RADIUS/ρ, or the ``time_step`` given — refused in
    one line above that limit (every RK4 driver: one bearing, its friction, the rotor)."""
    limit = RK4_STABILITY_RADIUS / rho
    if time_step is None:
        return STEP_SAFETY * limit
    dt = check_positive("time_step", time_step)
    if dt > limit:
        raise ParameterError("time_step", time_step, f"exceeds the RK4 stability limit "
                             f"{limit:.4g} of the discretised system (Gershgorin bound); use "
                             "a smaller step")
    return dt


def integrate_rk4(tm: TransientModel, mass: np.ndarray, revolutions: float, *,
                  kick: float, initial: Optional[State], sample_every: float,
                  contact_film: float, settle: float, time_step: Optional[float] = None,
                  check_every: int = 50, progress=None) -> OrbitBatch:
    """Advance a batch of rotors with classic RK4 (arguments as
    :func:`gfbopt.transient.orbit.integrate_orbits`, already validated)."""
    t0 = time.perf_counter()
    batch = mass.size
    state = initial if initial is not None else equilibrium_state(tm, batch)
    if initial is None:
        state.u[:] = kick / math.sqrt(2)
        state.v[:] = kick / math.sqrt(2)
    dt = rk4_first_step(stiffness_bound(state, tm), time_step)
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
        p, h = pressure_and_film(s.phi, s.x, s.y, tm, rhs.guess, deflection=s.w)
        hmin = h.min(axis=(1, 2))
        taus.append(tau)
        xs.append(s.x.copy())
        ys.append(s.y.copy())
        hs.append(hmin)
        return hmin

    record(state)
    failure = ""
    for step in range(1, n_steps + 1):
        rhs.min_film[:] = np.inf
        state = rk4_step(rhs, state, dt, active.astype(float))
        tau += dt
        if not np.all(np.isfinite(state.x[active])):
            failure = (f"the integration blew up (non-finite state) at τ = {tau:.4g} with "
                       f"Δτ = {dt:.4g}; the step is above the stability limit")
            break
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
            new_limit = RK4_STABILITY_RADIUS / stiffness_bound(state.take(active), tm)
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
    return finish_orbits(tm, tau_arr, x, y, hmin, ~active, contact_tau, mass, settle=settle,
                         kick=kick, time_step=dt, evaluations=rhs.evaluations, started=t0,
                         revolutions=tau / (2 * math.pi), method="rk4",
                         success=not failure, message=failure)
