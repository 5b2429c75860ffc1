"""The explicit steps of the friction driver (:mod:`.friction_orbit`): RK4 or damped RKC2.

Both integrators' steps are used as they are (:func:`.rk4.rk4_step`, :func:`.rkc.rkc_step`);
this module holds only the choice of Δτ (and RKC's stage count) the two one-bearing drivers
make, written for a model whose right-hand side needs the sliders Z:

* rk4: Δτ = 0.9 × 2.78/ρ (ρ the Gershgorin bound with Z), re-checked every ``check_every``
  steps; a given Δτ above the limit is refused (as :mod:`.rk4`);
* rkc: Δτ from :func:`.rkc.accuracy_step` of the model with the sliders stuck (the stiffest
  foundation the sliders give: S/(1 + κ) on every row, so the shortest rotor period), the
  fewest stages with Δτ ρ ≤ 0.9 β(s), re-checked every ``check_every`` steps (as :mod:`.rkc`).

Rotors that reached contact are frozen: rk4 by its per-rotor weight 0, rkc by keeping their
state from before the step.
"""
from __future__ import annotations

import dataclasses
from typing import Optional

import numpy as np

from ..errors import ParameterError
from .result import check_positive
from .rk4 import RK4_STABILITY_RADIUS, STEP_SAFETY, rk4_first_step, rk4_step
from .rkc import (MAX_STAGES, STAGE_SAFETY, accuracy_step, rkc_stability_interval, rkc_step,
                  stages_for)
from .system import State, TransientModel, stiffness_bound

#: methods of the friction driver and their default ``check_every``
FRICTION_METHODS = {"rk4": 50, "rkc": 5}


def check_friction_method(method: str) -> int:
    """The default ``check_every`` of ``method``; ParameterError unless rk4 or rkc."""
    if method not in FRICTION_METHODS:
        raise ParameterError("method", method, f"must be one of {', '.join(FRICTION_METHODS)} "
                             "for the transient with bump friction (explicit steps; the "
                             "sliders move between steps)")
    return FRICTION_METHODS[method]


def _stuck_model(tm: TransientModel) -> TransientModel:
    """The model with every slider stuck, for the rotor-period part of RKC's step: the simple
    foundation with S/(1 + κ) (no sliders)."""
    if tm.friction is None:
        return tm
    return dataclasses.replace(tm, friction=None, compliance_rows=tm.compliance_rows
                               / (1.0 + tm.friction.stiffness_ratio))


def first_step(method: str, tm: TransientModel, state: State, slider, mass: np.ndarray,
               time_step: Optional[float]) -> tuple:
    """(Δτ, stages) at the start of a run (stages None for rk4)."""
    rho = stiffness_bound(state, tm, slider)
    if method == "rk4":
        return rk4_first_step(rho, time_step), None
    dt = (check_positive("time_step", time_step) if time_step is not None
          else accuracy_step(_stuck_model(tm), state, mass))
    stages = stages_for(dt * rho)
    if stages > MAX_STAGES:
        if time_step is not None:
            raise ParameterError("time_step", time_step, f"needs more than {MAX_STAGES} RKC "
                                 f"stages (Δτ·ρ = {dt * rho:.4g})")
        stages = MAX_STAGES
        dt = STAGE_SAFETY * rkc_stability_interval(stages) / rho
    return dt, stages


def take_step(method: str, rhs, state: State, dt: float, stages, active: np.ndarray) -> State:
    """One step of every active rotor (the others frozen)."""
    if method == "rk4":
        return rk4_step(rhs, state, dt, active.astype(float))
    new = rkc_step(rhs, state, dt, stages)
    if active.all():
        return new
    keep = lambda a, b: None if a is None else np.where(  # noqa: E731
        active.reshape((-1,) + (1,) * (a.ndim - 1)), a, b)
    return State(keep(new.phi, state.phi), keep(new.x, state.x), keep(new.y, state.y),
                 keep(new.u, state.u), keep(new.v, state.v), keep(new.w, state.w))


def recheck(method: str, tm: TransientModel, state: State, slider, active: np.ndarray,
            dt: float, stages, fixed_step: bool) -> tuple:
    """(Δτ, stages, changed) after re-checking the stiffness bound on the active rotors."""
    keep = np.flatnonzero(active)
    rho = stiffness_bound(state.take(keep), tm, None if slider is None else slider[keep])
    if method == "rk4":
        limit = RK4_STABILITY_RADIUS / rho
        if dt <= limit:
            return dt, stages, False
        if fixed_step:
            raise ParameterError("time_step", dt, f"exceeds the RK4 stability limit "
                                 f"{limit:.4g} reached during the run")
        return STEP_SAFETY * limit, stages, True
    if dt * rho <= STAGE_SAFETY * rkc_stability_interval(stages):
        return dt, stages, False
    more = stages_for(dt * rho)
    if more > MAX_STAGES:
        return STAGE_SAFETY * rkc_stability_interval(MAX_STAGES) / rho, MAX_STAGES, True
    return dt, more, False
