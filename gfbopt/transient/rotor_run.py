"""Integrating the rotor on both bearing films: RKC (default) or RK4 (the reference), batched.

The system is :class:`.rotor_system.RotorRightHandSide`; the steps are those of the
one-bearing engine (:func:`.rkc.rkc_step`, :func:`.rk4.rk4_step`), with the same rules:

* rkc — Δτ from accuracy, min(0.1 rad of shaft rotation at the run's top speed, T_rotor/30,
  T_film/4, and for a flexible structure the growth cap of its undamped modes,
  :func:`.rotor_steps.growth_step`), T_rotor the shortest period of the rotor on the films'
  instantaneous stiffness with its gyroscopic coupling and the structure's own stiffness (a
  shaft's highest kept mode: :func:`.rotor_steps.rotor_frequency`, :func:`rotor_period`),
  T_film the slowest film relaxation (:func:`.rkc.film_time`); stages the fewest with Δτ·ρ ≤ 0.9 β(s), ρ the Gershgorin bound
  of every bearing's film and foil state at its current speed, re-checked every
  ``check_every`` steps (stages raised when it grew);
* rkc on a ramp (a run-up or coast-down, no step given) — the step follows the speed:
  Δτ(τ) = min(max_step rad of shaft rotation at the highest speed over the step, T_rotor/30,
  T_film/4), re-set with the stages every ``check_every`` steps from the largest ρ met so
  far, T_rotor re-measured at the current state every ``10 check_every`` steps (it is the
  rotor's own period that needs 30 steps, not the one at the start).  The accuracy rule is the constant-speed one, per rad of shaft rotation (the
  one-bearing accuracy study, :mod:`.rkc`), so at 5,000 rpm of a ramp to 60,000 rpm the step
  may be up to 12× the top speed's with ≈ √12× the stages, where T_rotor/30 does not bind
  (a heavy rotor: the study rotor's run-up to contact took 2.2× fewer evaluations).
  The record stays uniform in time: samples every ``sample_every`` are interpolated inside
  the step (cubic Hermite in q̃ and q̃', fourth order, below the step's own error);
* rk4 — Δτ = 0.9 × 2.78/ρ, re-checked likewise; a given step above the limit is refused
  (ρ is at least the structure's highest natural frequency on rigid supports).

Memory.  A run keeps, per stored sample (every ``sample_every`` rad of τ), τ, the four rotor
coordinates and each bearing's smallest film since the previous sample — 4 + K floats per
run per sample, never the films themselves — plus, per bearing, the smallest film of the
whole run with the time it occurred.  Contact (film H ≤ ``contact_film``, or a foil
deflection beyond ``foil_travel`` when that is given) ends that run at the step it happens;
its record up to there is kept and the other runs go on.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..errors import ConvergenceError, ParameterError
from ..inputs.checks import check_positive
from .orbit import check_method
from .rk4 import RK4_STABILITY_RADIUS, STEP_SAFETY
from .rkc import MAX_STAGES, MAX_STEP, STAGE_SAFETY, rkc_stability_interval, stages_for
from .rotor_steps import (  # noqa: F401  (the step rules; rotor_frequency re-exported)
    PERIOD_CHECKS, _SpeedStep, _check_stages, _first_step, _hermite, _stages_at, accuracy_step,
    rotor_frequency, rotor_period)
from .rotor_friction import check_method as check_friction_method
from .rotor_friction import initial_sliders, last_state_words, move_sliders
from .rotor_system import RotorRightHandSide, RotorTransientModel, Runs, layout

#: film H at which a bearing is in contact (the one-bearing engine's default: the film
#: model — no asperities, no slip — says nothing closer than 2 % of the clearance)
CONTACT_FILM = 0.02


@dataclass(frozen=True, eq=False)
class RotorRun:
    """What a rotor transient kept (module docstring), for a batch of B runs, K bearings.

    tau (n,) [rad of τ = ω_ref t]; q (B, n, d): the structure's d coordinates (the rigid
    body's x, y [m] and slopes [rad]; ``model.structure.dof_names``) (NaN after a run's
    contact); min_film (B, K, n): smallest film H of each bearing since
    the previous sample [-]; run_min_film (B, K) and run_min_film_tau (B, K): the smallest
    film of the whole run and when; max_deflection (B, K): largest foil deflection W [-];
    contact (B,) bool, contact_tau (B,), contact_bearing (B,) (index, −1 none),
    contact_kind (B,) ('film', 'foil travel' or ''); time_step Δτ (last); stages (the
    counts used, rkc); evaluations; wall_time_s; method; success, message.
    """

    model: RotorTransientModel
    runs: Runs
    tau: np.ndarray
    q: np.ndarray
    min_film: np.ndarray
    run_min_film: np.ndarray
    run_min_film_tau: np.ndarray
    max_deflection: np.ndarray
    contact: np.ndarray
    contact_tau: np.ndarray
    contact_bearing: np.ndarray
    contact_kind: tuple
    time_step: float
    stages: tuple
    evaluations: int
    wall_time_s: float
    method: str
    success: bool = True
    message: str = ""
    options: dict = field(default_factory=dict)
    #: per bearing the sliders Z at the end (B, ...) of a rotor whose bumps rub (rows of the
    #: runs that reached contact: at their contact step), else None
    sliders: Optional[tuple] = None

    @property
    def time_s(self) -> np.ndarray:
        return self.tau / self.model.reference_speed

    def speed_rpm(self, run: int = 0, tau=None) -> np.ndarray:
        """Shaft speed [rpm] of ``run`` at the samples (or at ``tau``)."""
        t = self.tau if tau is None else np.asarray(tau)
        r = self.runs.speed[run] + self.runs.ramp[run] * t
        return r * self.model.reference_speed * 30.0 / math.pi

    def shaft_angle(self, run: int = 0) -> np.ndarray:
        """ϑ [rad] of ``run`` at the samples (0 at the start: the imbalance phase origin)."""
        return self.runs.speed[run] * self.tau + 0.5 * self.runs.ramp[run] * self.tau ** 2

    def journal(self, run: int = 0, bearing: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """(x, y) of the journal at ``bearing`` [m], global frame, from the bearing centre
        (S(z_k) q of the structure; the rigid body's x + z ψx, y + z ψy)."""
        z = self.model.bearings[bearing].position
        q = self.q[run]
        if self.model.rigid:
            return q[:, 0] + z * q[:, 2], q[:, 1] + z * q[:, 3]
        s = self.model.station(z)
        return q @ s[0], q @ s[1]

    @property
    def revolutions(self) -> float:
        """Shaft revolutions of run 0 over the stored record."""
        return float(self.shaft_angle(0)[-1] / (2 * math.pi)) if self.tau.size else 0.0


def integrate_rotor(model: RotorTransientModel, batch: Runs, duration: float,
                    initial: np.ndarray, *, method: str = "rkc",
                    time_step: Optional[float] = None, stages: Optional[int] = None,
                    sample_every: float = 0.2, contact_film: float = CONTACT_FILM,
                    foil_travel: Optional[float] = None, check_every: int = 5,
                    max_step: float = MAX_STEP, progress=None,
                    progress_total: int = 100, exact_end: bool = False,
                    sliders: Optional[tuple] = None) -> RotorRun:
    """Advance a batch of rotor runs over ``duration`` rad of τ from the packed ``initial``
    rows (:func:`.rotor_setup.equilibrium_states`).

    method : 'rkc' (default) or 'rk4', an explicit method of the one table
    :data:`gfbopt.transient.orbit.METHODS` (advanced by its packed step; 'bdf' is refused);
    time_step Δτ [rad] and stages (rkc) : default from accuracy and the stiffness bound
    (module docstring), refused when outside the stability
    region; sample_every : Δτ between stored samples; contact_film : H at contact [-];
    foil_travel : largest foil deflection W [clearances] before the bumps are exhausted
    (None: not checked); max_step : rkc's accuracy limit [rad of shaft rotation at the top
    speed] (default 0.1, the one-bearing engine's); progress : a
    :func:`gfbopt.progress.progress` reporter, advanced in proportion to τ up to
    ``progress_total`` (its total: revolutions of an orbit, milliseconds of a ramp);
    exact_end : shorten the last step to end at ``duration`` exactly (a ramp ends at its end
    speed); otherwise whole steps, the last one past the end by less than a step, as the
    one-bearing engine does.  A bearing whose bumps rub (its model built with friction,
    :func:`.rotor_setup.build_model`) carries its sliders Z beside the state, moved by the
    play operator after every accepted step (:mod:`.rotor_friction`); ``sliders``: per
    bearing the Z to start from (default: relaxed at the equilibrium, Z = W0).
    """
    t0 = time.perf_counter()
    check_friction_method(model, method)
    advance = check_method(method, {"time_step": time_step, "stages": stages},
                           explicit=True).step          # the one METHODS table (.orbit)
    duration = check_positive("duration", duration)
    sample_every = check_positive("sample_every", sample_every)
    contact_film = float(contact_film)
    travel = math.inf if foil_travel is None else check_positive("foil_travel", foil_travel)
    lay = layout(model)
    z = np.array(initial, dtype=float)
    shape = (batch.size, len(model.bearings), lay.width)
    if z.shape != shape:
        raise ParameterError("initial", z.shape, f"must be {shape}, the packed states of "
                             "the batch (rotor_setup.equilibrium_states)")
    for b in model.bearings:
        b.tm.law.check_engine(method, damped=b.tm.foil_state is not None)
    dofs = lay.dofs
    lay.rotor_of(z)[:, 2 * dofs] = 0.0
    slide = initial_sliders(model, batch.size, sliders)
    rhs = RotorRightHandSide(model, batch, track_deflection=foil_travel is not None,
                             sliders=slide)
    final_sliders = None if slide is None else [z_k.copy() if z_k is not None else None
                                                 for z_k in slide]
    top = float(np.max(np.maximum(batch.speed, batch.speed_at(duration))))
    rho = rhs.stiffness(z)
    fixed, fixed_stages = time_step is not None, stages is not None
    # a ramp's rkc step follows the speed (module docstring); everything else is constant
    follow = method == "rkc" and not fixed and bool(np.any(batch.ramp != 0.0))
    if follow:
        stages, rho_top = _check_stages(stages), rho
        step_of = _SpeedStep(rhs, z, max_step, duration)
        dt = step_of(0.0, batch)
        dt, stages = _stages_at(dt, rho_top, stages, fixed_stages)
    else:
        dt, stages = _first_step(rhs, z, rho, top, method, time_step, stages, max_step,
                                 duration)
    n_steps = int(math.ceil(duration / dt - 1e-9))
    per_sample = max(1, int(round(sample_every / dt)))
    nb, k = batch.size, len(model.bearings)
    live = np.arange(nb)
    q_now = np.full((nb, dofs), np.nan)
    h_low = np.full((nb, k), np.inf)                 # since the last sample
    run_min = np.full((nb, k), np.inf)
    run_min_tau = np.full((nb, k), np.nan)
    max_defl = np.full((nb, k), -np.inf)
    contact_tau = np.full(nb, np.nan)
    contact_bearing = np.full(nb, -1)
    kinds = [""] * nb
    taus, qs, hs = [], [], []
    c_ref = model.clearance_ref
    evaluations, tau, step, failure, used = 0, 0.0, 0, "", {stages}
    films0 = rhs.pressures(z)
    for j, (_, h) in enumerate(films0):
        run_min[:, j] = h.min(axis=tuple(range(1, h.ndim)))
        run_min_tau[:, j] = 0.0
    h_low[:] = run_min

    def record(at: float, q: np.ndarray) -> None:
        q_now[:] = np.nan
        q_now[live] = q * c_ref
        taus.append(at)
        qs.append(q_now.copy())
        hs.append(h_low.copy())
        h_low[live] = np.inf

    record(tau, lay.rotor_of(z)[:, :dofs])
    h_low[:] = run_min
    next_sample = sample_every                        # follow: the uniform sample grid
    done_revs = 0
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        while (tau < duration - 1e-9 * dt) if follow else (step < n_steps):
            step += 1
            rhs.reset()
            if follow:
                h = min(dt, duration - tau) if exact_end else dt
                if exact_end and duration - tau - h < 1e-9 * dt:
                    h = duration - tau
            else:
                h = min(dt, duration - tau) if exact_end and step == n_steps else dt
            before = z
            try:
                z = advance(rhs, z, h, stages)
            except ConvergenceError as err:
                failure = f"the foil recovery failed at τ = {tau:.4g}: {err}"
                break
            tau += h
            if not np.all(np.isfinite(lay.rotor_of(z)[:, :2 * dofs])):
                failure = (f"the integration blew up (non-finite state) at τ = {tau:.4g} "
                           f"with Δτ = {dt:.4g}" + (f" and {stages} stages"
                                                    if method == "rkc" else "")
                           + last_state_words(rhs, before))
                break
            if rhs.sliders is not None:       # the play operator after the accepted step
                rhs.sliders = move_sliders(rhs, z)
                for j, z_k in enumerate(rhs.sliders):
                    if z_k is not None:
                        final_sliders[j][live] = z_k
            low = rhs.min_film
            better = low < run_min[live]
            sub_min, sub_tau = run_min[live], run_min_tau[live]
            sub_min[better], sub_tau[better] = low[better], tau
            run_min[live], run_min_tau[live] = sub_min, sub_tau
            h_low[live] = np.minimum(h_low[live], low)
            max_defl[live] = np.maximum(max_defl[live], rhs.max_deflection)
            film_hit = low <= contact_film
            foil_hit = rhs.max_deflection >= travel
            touching = film_hit.any(axis=1) | foil_hit.any(axis=1)
            if touching.any():
                for i in np.flatnonzero(touching):
                    run = live[i]
                    contact_tau[run] = tau
                    if film_hit[i].any():
                        contact_bearing[run] = int(np.argmin(low[i]))
                        kinds[run] = "film"
                    else:
                        contact_bearing[run] = int(np.argmax(rhs.max_deflection[i]))
                        kinds[run] = "foil travel"
            if follow:
                while next_sample <= tau + 1e-9 * h:
                    record(next_sample, _hermite(lay, before, z, tau - h, h, next_sample))
                    next_sample += sample_every
                ended = tau >= duration - 1e-9 * dt
                if (touching.any() or ended) and abs(taus[-1] - tau) > 1e-9 * h:
                    record(tau, lay.rotor_of(z)[:, :dofs])
            elif step % per_sample == 0 or step == n_steps or touching.any():
                record(tau, lay.rotor_of(z)[:, :dofs])
            if touching.any():
                if touching.all():
                    break
                keep = ~touching
                evaluations += rhs.evaluations
                live, z = live[keep], z[keep]
                rhs = rhs.take(keep)
            if step % check_every == 0:
                rho = rhs.stiffness(z)
                if follow:
                    rho_top = max(rho_top, rho)
                    if step % (check_every * PERIOD_CHECKS) == 0:
                        step_of.refresh(rhs, z)
                    dt, stages = _stages_at(step_of(tau, rhs.runs), rho_top, stages,
                                            fixed_stages)
                    if stages > MAX_STAGES:
                        failure = (f"Δτ·ρ = {dt * rho_top:.4g} needs more than {MAX_STAGES} "
                                   f"RKC stages at τ = {tau:.3g}")
                        break
                    used.add(stages)
                elif method == "rk4":
                    limit = RK4_STABILITY_RADIUS / rho
                    if dt > limit:
                        if fixed:
                            failure = (f"time_step = {dt:.4g} exceeds the RK4 stability "
                                       f"limit {limit:.4g} reached at τ = {tau:.3g}")
                            break
                        dt = STEP_SAFETY * limit
                        per_sample = max(1, int(round(sample_every / dt)))
                        n_steps = step + int(math.ceil((duration - tau) / dt - 1e-9))
                elif dt * rho > STAGE_SAFETY * rkc_stability_interval(stages):
                    stages = stages_for(dt * rho)
                    if stages > MAX_STAGES:
                        failure = (f"Δτ·ρ = {dt * rho:.4g} needs more than {MAX_STAGES} "
                                   f"RKC stages at τ = {tau:.3g}")
                        break
                    used.add(stages)
            if progress is not None:
                revs = int(progress_total * min(tau / duration, 1.0))
                if revs > done_revs:
                    progress.update(revs - done_revs)
                    done_revs = revs
                    speed = batch.speed_at(tau)[0] * model.reference_speed * 30 / math.pi
                    progress.set_postfix_str(f"{speed:,.0f} rpm, min film "
                                             f"{np.nanmin(run_min) * c_ref * 1e6:.2f} µm")
    evaluations += rhs.evaluations
    q = np.transpose(np.array(qs), (1, 0, 2))
    hmin = np.transpose(np.array(hs), (1, 2, 0))
    hmin[~np.isfinite(hmin)] = np.nan
    contact = np.isfinite(contact_tau)
    options = {"method": method, "contact_film": contact_film,
               "foil_travel": None if foil_travel is None else travel,
               "sample_every": sample_every, "check_every": check_every,
               "step_rule": ("follows the speed: Δτ = min(max_step/r(τ), T_rotor/30, "
                             "T_film/4), T_rotor re-measured along the run, samples "
                             "interpolated (cubic Hermite) onto a uniform grid")
               if follow else "constant"}
    return RotorRun(model, batch, np.array(taus), q, hmin, run_min, run_min_tau, max_defl,
                    contact, contact_tau, contact_bearing, tuple(kinds), dt,
                    tuple(sorted(used)) if method == "rkc" else (), evaluations,
                    time.perf_counter() - t0, method, not failure, failure, options,
                    None if final_sliders is None else tuple(final_sliders))
