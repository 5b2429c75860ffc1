"""The rotor transient's step rules: the first step and stages, the rotor's own period, and
the speed-following step of a ramp (:func:`.rotor_run.integrate_rotor`; rules in its module
docstring).  Times are rad of τ = ω_ref t; ρ is the Gershgorin bound of the films and foil
states (:meth:`.rotor_system.RotorRightHandSide.stiffness`)."""
from __future__ import annotations

import math

import numpy as np

from ..errors import ParameterError
from ..inputs.checks import check_positive
from .rk4 import rk4_first_step
from .rkc import (MAX_STAGES, MAX_STEP, STAGE_SAFETY, STEPS_PER_FILM_TIME,
                  STEPS_PER_ROTOR_PERIOD, film_time, rkc_stability_interval, stages_for)
from .rotor_batch import Runs
from .rotor_system import RotorRightHandSide

#: the most an undamped structural mode may grow by RKC's own amplification over a run
GROWTH = 1.1
#: a ramp re-measures T_rotor every this many stage checks (8 evaluations each: ≈ 1 % of
#: the run's at 72 × 20)
PERIOD_CHECKS = 10


def rotor_frequency(rhs: RotorRightHandSide, z: np.ndarray, h: float = 1e-6) -> float:
    """Fastest rotor frequency [rad per rad of τ] on the films' instantaneous stiffness.

    ∂q̃''/∂q̃ at fixed films (central differences, every run at once), with the gyroscopic
    term: the largest |Im λ| of [[0, I], [∂q̃''/∂q̃, ∂q̃''/∂q̃']] over the runs.  It holds the
    structure's own frequencies (a shaft's stiffness K is in ∂q̃''/∂q̃), so the step cap
    T_rotor/30 respects the highest mode the structure keeps.  The rigid body's velocity
    block is −r (M⁻¹G)ᵀ, as this rule was measured with (the gyroscopic term of the
    opposite spin: the same frequencies for an isotropic support); a structure with
    stiffness or damping gets ∂q̃''/∂q̃' by central differences too (2n more evaluations).
    """
    lay, n = rhs.layout, rhs.dofs

    def columns(offset: int) -> np.ndarray:
        cols = []
        for j in range(n):
            plus, minus = z.copy(), z.copy()
            lay.rotor_of(plus)[:, offset + j] += h
            lay.rotor_of(minus)[:, offset + j] -= h
            cols.append((lay.rotor_of(rhs(plus))[:, n:2 * n]
                         - lay.rotor_of(rhs(minus))[:, n:2 * n]) / (2 * h))
        return np.stack(cols, axis=-1)                                # (B, n, n)

    stiff = columns(0)
    rate = rhs.runs.speed_at(lay.rotor_of(z)[:, 2 * n])
    turn = columns(n) if rhs.elastic else None
    fastest = 0.0
    for b in range(z.shape[0]):
        comp = np.zeros((2 * n, 2 * n))
        comp[:n, n:] = np.eye(n)
        comp[n:, :n] = stiff[b]
        comp[n:, n:] = -rate[b] * rhs.gyro if turn is None else turn[b]
        fastest = max(fastest, float(np.abs(np.linalg.eigvals(comp).imag).max()))
    return fastest


def rotor_period(rhs: RotorRightHandSide, z: np.ndarray, h: float = 1e-6) -> float:
    """Shortest period [rad of τ] of the rotor on the films' instantaneous stiffness
    (:func:`rotor_frequency`); at least one shaft revolution at the run's speed (as the
    one-bearing engine's rule)."""
    rate = rhs.runs.speed_at(rhs.layout.rotor_of(z)[:, 2 * rhs.dofs])
    return 2 * math.pi / max(rotor_frequency(rhs, z, h), float(np.max(rate)))


def growth_step(rhs: RotorRightHandSide, duration: float) -> float:
    """The longest RKC step Δτ [rad of τ] over which an undamped mode of the structure at its
    highest natural frequency ω_s (:attr:`~.rotor_system.RotorRightHandSide.structure_rate`)
    grows by at most :data:`GROWTH` over a run of ``duration`` rad: a second-order RKC step
    multiplies an undamped oscillation by 1 + (ω_s Δτ)⁴/8 at 2 stages (less with more; the
    held modes of a condensed shaft touch no film, so nothing damps them), so
    (duration/Δτ)(ω_s Δτ)⁴/8 ≤ ln GROWTH.  Infinite for the rigid body (its modes ride on
    the films).  RK4 needs no such cap: it damps the imaginary axis up to 2.83/Δτ."""
    rate = float(getattr(rhs, "structure_rate", 0.0))
    if not rate > 0 or not duration > 0:
        return math.inf
    return (8.0 * math.log(GROWTH) / (duration * rate ** 4)) ** (1.0 / 3.0)


def accuracy_step(rhs: RotorRightHandSide, z: np.ndarray, top_speed: float,
                  max_step: float = MAX_STEP, duration: float = 0.0) -> float:
    """The default RKC step Δτ (module docstring); ``top_speed`` = max ω/ω_ref of the run;
    ``max_step`` [rad of shaft rotation at the top speed]; ``duration`` [rad of τ], for the
    structure's growth cap (:func:`growth_step`)."""
    films = min(film_time(b.tm) * rhs.model.reference_speed / b.model_speed
                for b in rhs.model.bearings)
    return min(max_step / top_speed, rotor_period(rhs, z) / STEPS_PER_ROTOR_PERIOD,
               films / STEPS_PER_FILM_TIME, growth_step(rhs, duration))


class _SpeedStep:
    """Δτ(τ, runs) of a ramp: ``max_step`` rad of shaft rotation at the highest speed any
    live run reaches over the step, at most T_rotor/30 and T_film/4 (module docstring).
    T_rotor follows the rotor (:meth:`refresh`, from :func:`rotor_frequency` at the current
    state): the films soften from the stiff low-speed equilibrium within the first tenth of
    a run-up, so the start's period would hold the cap ≈ 20 % shorter than the rotor needs
    for the rest of the ramp (blower rotor on its preloaded bearings, 72 × 20)."""

    def __init__(self, rhs: RotorRightHandSide, z: np.ndarray, max_step: float,
                 duration: float = 0.0):
        self.max_step = max_step
        self.film_cap = min(min(film_time(b.tm) * rhs.model.reference_speed / b.model_speed
                                for b in rhs.model.bearings) / STEPS_PER_FILM_TIME,
                            growth_step(rhs, duration))
        self.refresh(rhs, z)

    def refresh(self, rhs: RotorRightHandSide, z: np.ndarray) -> None:
        """Re-measure the rotor's fastest frequency (8 right-hand-side evaluations)."""
        fastest = rotor_frequency(rhs, z)
        self.cap = self.film_cap if not fastest > 0 else min(
            self.film_cap, 2 * math.pi / fastest / STEPS_PER_ROTOR_PERIOD)

    def __call__(self, tau: float, batch: Runs) -> float:
        r = batch.speed_at(tau)
        r_hi = np.maximum(r, batch.speed_at(tau + self.max_step / np.max(r)))
        return min(self.max_step / float(np.max(r_hi)), self.cap)


def _stages_at(dt: float, rho: float, stages, fixed_stages: bool) -> tuple:
    """(Δτ, s) of a speed-following step: the fewest stages with Δτ·ρ ≤ 0.9 β(s) (ρ the
    largest bound met so far), or, with the stages given, Δτ shortened to their interval."""
    if fixed_stages:
        return min(dt, STAGE_SAFETY * rkc_stability_interval(stages) / rho), stages
    s = stages_for(dt * rho)
    if s > MAX_STAGES:
        s = MAX_STAGES
        dt = STAGE_SAFETY * rkc_stability_interval(s) / rho
    return dt, s


def _hermite(lay, before: np.ndarray, after: np.ndarray, tau0: float, h: float,
             at: float) -> np.ndarray:
    """q̃ (B, n) at τ = ``at`` inside the step [τ0, τ0 + h]: the cubic Hermite interpolant
    of q̃ and q̃' at both ends (fourth order, above the second-order step's own error)."""
    a, b, n = lay.rotor_of(before), lay.rotor_of(after), lay.dofs
    s = (at - tau0) / h
    s2, s3 = s * s, s * s * s
    return ((2 * s3 - 3 * s2 + 1) * a[:, :n] + (s3 - 2 * s2 + s) * h * a[:, n:2 * n]
            + (-2 * s3 + 3 * s2) * b[:, :n] + (s3 - s2) * h * b[:, n:2 * n])


def _check_stages(stages):
    """A given RKC stage count as an int in [2, MAX_STAGES] (None stays None)."""
    if stages is None:
        return None
    if isinstance(stages, bool) or not float(stages).is_integer() \
            or not 2 <= int(stages) <= MAX_STAGES:
        raise ParameterError("stages", stages, f"must be an integer in [2, {MAX_STAGES}]")
    return int(stages)


def _first_step(rhs: RotorRightHandSide, z: np.ndarray, rho: float, top: float, method: str,
                time_step, stages, max_step: float = MAX_STEP, duration: float = 0.0) -> tuple:
    """(Δτ, stages) at the start; a given step or stage count outside the stability region
    is refused with the bound it violates."""
    if method == "rk4":
        return rk4_first_step(rho, time_step), None
    stages = _check_stages(stages)
    dt = (check_positive("time_step", time_step) if time_step is not None
          else accuracy_step(rhs, z, top, max_step, duration))
    if stages is None:
        stages = stages_for(dt * rho)
        if stages > MAX_STAGES:
            if time_step is not None:
                raise ParameterError("time_step", time_step, f"Δτ·ρ = {dt * rho:.4g} needs "
                                     f"more than {MAX_STAGES} RKC stages")
            stages = MAX_STAGES
            dt = STAGE_SAFETY * rkc_stability_interval(stages) / rho
    elif dt * rho > rkc_stability_interval(stages):
        if time_step is None:
            dt = STAGE_SAFETY * rkc_stability_interval(stages) / rho
        else:
            raise ParameterError("time_step", time_step, f"Δτ·ρ = {dt * rho:.4g} exceeds the "
                                 f"RKC stability interval β({stages}) = "
                                 f"{rkc_stability_interval(stages):.4g}")
    return dt, stages
