"""The whole rotor and the films of both its bearings as one method-of-lines system.

Rotor (a structure of n degrees of freedom, :mod:`.rotor_model`)
----------------------------------------------------------------
Any :class:`gfbopt.rotor.structure.Structure`: M q̈ + (C + ω G) q̇ + K q = Σ_k S_kᵀ F_k + Q_s
+ Q_u(t), the bearings, imbalance planes and probes at stations S(z) (2 × n); a shaft is
condensed on its bearing stations (:mod:`gfbopt.rotor.condensed`) before it gets here.  The
rigid body (the rest of this section; gfbopt.rotor.rigid's convention) keeps the arithmetic
it always had, K = C = 0 adding no term.  Global frame: x along gravity (the static load line by default), y 90° ahead of x in the
direction of rotation, z along the shaft so that the spin ω is positive about +z.  The
generalised coordinates are q = (x, y, a_x, a_y): the centre-of-gravity displacement [m] and
the slopes of the shaft axis dx/dz, dy/dz [rad].  A station at axial position z (from the CG)
moves by r = T(z) q, T(z) = [[1, 0, z, 0], [0, 1, 0, z]].  With the axis n ≈ (a_x, a_y, 1),
the angular momentum about the CG is I_p ω n + I_t n × ṅ, and the moment of station forces
F_k is Σ z_k e_z × F_k, so

    M q̈ + ω G q̇ = Σ_k T_kᵀ F_k + Q_s + Q_u(t),
    M = diag(m, m, I_t, I_t),   G = I_p [[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 1], [0, 0, −1, 0]]

(forward whirl of the tilt, a_x + i a_y ∝ e^{iΩt} with Ω > 0, has −I_t Ω² + I_p ω Ω: the
gyroscopic term stiffens it).  Q_s is the static generalised force (gravity, side loads) and
Q_u the imbalance: a plane at z_j with amount u_j = m_j e_j [kg m] and phase φ_j sits at
shaft angle ϑ_j = ϑ(t) + φ_j, ϑ̇ = ω, and pushes the shaft with
u_j [ω² (cos ϑ_j, sin ϑ_j) + ω̇ (sin ϑ_j, −cos ϑ_j)] (the second term: angular acceleration
during a run-up).  Linearised, the rotor whirls where −Ω² M + iΩ ω G + Σ T_kᵀ Z_k(iΩ) T_k is
singular (gfbopt.rotor).

Bearings
--------
Each bearing k keeps the one-bearing transient model (:class:`.system.TransientModel`, its
film Φ = P H and, with a loss factor, its Kelvin–Voigt foil state W; :mod:`.foil_state`), in
its own load frame: X_k along the bearing's static load, at angle ψ_k from the global x in
the direction of rotation, positions over its clearance c_k, forces over p_a R_k².  Films
of one grid, film and axial-mean (or rigid) law are evaluated together in one fused pass
(:mod:`.rotor_films`, equal to the one-bearing functions to round-off); others call that
model's own functions (:func:`.system.pressure_and_film`, :func:`.system.flux_residual`,
:func:`.system.film_force`, the foil state's ``rate``).  A bearing whose bumps rub (μ_f > 0)
keeps its sliders Z beside the state (``sliders``, :mod:`.rotor_friction`): its films take
the fused rows with the friction elements (:mod:`.rotor_friction_films`) or the one-bearing
functions with ``slider=``.

Time and speed
--------------
τ = ω_ref t [rad of rotation at the reference speed ω_ref].  A bearing's model was built at a
speed ω_m (its Λ_m); at speed ω(t) its bearing number is Λ_m ω/ω_m, and since
dΦ/dt = (ω/(2Λ)) R(P, H; Λ) with ω/Λ fixed by the bearing, dΦ/dτ = R(P, H; Λ(τ)) ω_m/(2 Λ_m
ω_ref): the speed enters only through the Couette term of R, passed to the same kernel as an
argument — the film model is never rebuilt.  At constant speed ω_ref = ω_m = ω and these are
the one-bearing engine's equations, operation for operation.  The Kelvin–Voigt foil keeps
its time constant in seconds, t_f = τ_f/ω_m, through a run-up (a viscous element matched to
the hysteretic loss at the reference whirl frequency ν_ref ω_m/2π of the model speed).  Each
run of a batch has its own speed ω = ω_ref (r0 + a τ), shaft angle ϑ = r0 τ + a τ²/2.

State of a batch of B runs, one row each:  [Φ_1 … Φ_K | W_1 … W_K | q̃ (n) | q̃' (n) | τ],
q̃ = q/c_ref (c_ref the first bearing's clearance), primes d/dτ.  τ is carried as a state
(τ' = 1) so that every Runge–Kutta stage sees its own time (both methods integrate it exactly).
"""
from __future__ import annotations

import math
from dataclasses import replace
from typing import Optional

import numpy as np

from ..errors import ParameterError
from .foil_state import foil_bound
from .rotor_films import FusedFilms, AtSpeed, largest_deflection, fusable
from .rotor_running import speed_table
from .rotor_friction import rubbing, same_friction
from .rotor_friction_films import FrictionFusedFilms, fusable_with_friction
from .rotor_batch import Runs, runs  # noqa: F401  (re-exported: the batch of runs)
from .rotor_model import (DOF, BearingFilm, ImbalancePlane,  # noqa: F401  (re-exported)
                          RotorTransientModel, imbalance_shapes, rigid_rotor_matrices,
                          rigid_structure, rotation,
                          rotor_transient_model, station_matrix, structure_transient_model)
from .rotor_layout import Layout, empty_states, layout, stackable  # noqa: F401  (re-exported)
from .system import (State, film_force, flux_residual, pressure_and_film,
                     stiffness_bound)

# ------------------------------------------------------------------ the system
class RotorRightHandSide:
    """dz/dτ for a batch of runs (states (B, K, L), :class:`Layout`), and the films it saw.

    ``min_film`` (B, K): the smallest film H of each bearing over every evaluation since the
    last reset; with ``track_deflection``, ``max_deflection`` (B, K): the largest foil
    deflection W = H − H_r [clearances] (else −inf).
    """

    def __init__(self, model: RotorTransientModel, batch: Runs, stack: Optional[bool] = None,
                 track_deflection: bool = False, fuse: Optional[bool] = None,
                 sliders: Optional[tuple] = None):
        self.model = model
        self.runs = batch
        self.layout = layout(model)
        rub = rubbing(model)
        if rub and fuse and not fusable_with_friction(model):
            raise ParameterError("fuse", fuse, "the fused films with bump friction need every "
                                 "bearing fusable with its friction on θ rows (axial-mean law)")
        if rub and sliders is None:
            raise ParameterError("sliders", None, "a rotor with bump friction needs each "
                                 "bearing's sliders Z (rotor_friction.initial_sliders)")
        #: the bearings' running lines (a heated rotor's ramp, .rotor_running; None: today's)
        self.running = speed_table(model)
        self.stack = (stackable(model) and same_friction(model)) if stack is None else stack
        if self.running is not None:       # the running line's offset goes bearing by bearing
            self.stack = False
        self.track_deflection = track_deflection
        if fuse is None:                               # fuse=False: the one-bearing kernels
            fuse = fusable_with_friction(model) if rub else fusable(model)
        self.fuse = fuse
        k, n = len(model.bearings), model.dofs
        self.dofs = n
        self.to_local = np.vstack(list(model.to_local())).T.copy()        # (n, 2K)
        self.from_local = np.hstack(list(model.from_local())).T.copy()    # (2K, n)
        c, w = model.clearance_ref, model.reference_speed
        minv = np.linalg.inv(model.mass_matrix) / (c * w * w)
        scale = batch.inertia_scale
        self.uniform_mass = bool(np.all(scale == scale[0])) if scale.size else True
        self.accel = (minv / scale[0]).T.copy() if self.uniform_mass and scale.size else None
        self.accel_each = minv[None] / scale[:, None, None]                # (B, n, n)
        self.gyro = (np.linalg.inv(model.mass_matrix) @ model.gyroscopic).T.copy()
        self.static = model.static_force
        # the structure's own forces, −C q̇ − K q [N] from q̃', q̃ (none for the rigid body)
        self.elastic = not model.rigid and bool(np.any(model.stiffness) or
                                                np.any(model.damping))
        self.damp_force = -(model.damping.T * (c * w)) if self.elastic else None   # q̃' → N
        #: the structure's highest natural frequency [per rad of τ] (√ of M⁻¹K's largest)
        self.structure_rate = float(np.sqrt(max(0.0, np.linalg.eigvals(np.linalg.solve(
            model.mass_matrix, model.stiffness)).real.max())) / w) if self.elastic else 0.0
        self.stiff_force = -(model.stiffness.T * c) if self.elastic else None       # q̃ → N
        self.shape_u, self.shape_v = imbalance_shapes(model)         # Q_u = α U + β V
        self._planes = bool(model.imbalance)
        if self.accel is not None:   # q̃'' = [f | α β | r q̃' (| q̃' | q̃)] @ combined + M⁻¹Q_s
            blocks = [self.from_local @ self.accel, self.shape_u @ self.accel,
                      self.shape_v @ self.accel, -self.gyro]
            if self.elastic:
                blocks += [self.damp_force @ self.accel, self.stiff_force @ self.accel]
            self.combined = np.vstack(blocks)
            self.static_accel = self.static @ self.accel
            self._stack = np.zeros((batch.size, 2 * k + 2 + (3 if self.elastic else 1) * n))
        self.film_divisor = [2.0 * b.tm.bearing_number * (w / b.model_speed)
                             for b in model.bearings]
        self.foil_factor = [b.model_speed / w for b in model.bearings]
        self.base_lambda = [b.tm.bearing_number * (w / b.model_speed) for b in model.bearings]
        self.same_speed = bool(np.all(batch.speed == batch.speed[0])
                               and np.all(batch.ramp == batch.ramp[0])) if batch.size else True
        self._kernels = [AtSpeed(b.tm) for b in model.bearings]
        self.fused = (FrictionFusedFilms if rub else FusedFilms)(
            model, batch.size, self.film_divisor, self.foil_factor,
            self.base_lambda) if self.fuse else None
        self._sliders = None
        #: per bearing the sliders Z (B, ...) every stage of the current step sees (None
        #: for a bearing without friction; None for a rotor without friction)
        self.sliders = sliders if rub else None
        self.evaluations = 0
        self._rotor_start, self._filled = self.layout.rotor, self.layout.filled
        self.min_film = np.full((batch.size, k), np.inf)
        self.max_deflection = np.full((batch.size, k), -np.inf)

    def take(self, keep) -> "RotorRightHandSide":
        """The same system for the runs selected by ``keep`` (the counters restart)."""
        return RotorRightHandSide(self.model, self.runs.take(keep), self.stack,
                                  self.track_deflection, self.fuse, None if self.sliders is None
                                  else tuple(None if z is None else z[keep]
                                             for z in self.sliders))

    @property
    def sliders(self) -> Optional[tuple]:
        return self._sliders

    @sliders.setter
    def sliders(self, value: Optional[tuple]) -> None:
        self._sliders = None if value is None else tuple(value)
        if self.fused is not None and value is not None:       # (B·K, m), run-major
            self.fused.slider = self.slider(slice(None))

    def slider(self, k) -> Optional[np.ndarray]:
        """Bearing k's sliders Z (B, ...), or, with ``k`` a slice (stacked bearings), all of
        them as one (B·K, ...) array; None without friction."""
        if self.sliders is None:
            return None
        if isinstance(k, slice):
            z = np.stack(self.sliders, axis=1)
            return z.reshape((-1,) + z.shape[2:])
        return self.sliders[k]

    def reset(self) -> None:
        self.min_film[:] = np.inf
        self.max_deflection[:] = -np.inf

    # ---------------------------------------------------------------- pieces
    def journals(self, z: np.ndarray) -> np.ndarray:
        """(X_k, Y_k) of every run, (B, K, 2)."""
        return np.dot(self.layout.rotor_of(z)[:, :self.dofs], self.to_local).reshape(
            z.shape[0], -1, 2)

    def _speed(self, tau: np.ndarray):
        """ω/ω_ref: a float when every run turns at the same speed, else (B,)."""
        if self.same_speed:
            t = float(tau[0])
            return float(self.runs.speed[0] + self.runs.ramp[0] * t)
        return self.runs.speed_at(tau)

    def _films(self, z: np.ndarray, xy: np.ndarray):
        """[(bearings, tm, Φ, X, Y, W)] with a leading batch axis: once for all bearings
        (stacked, (B·K, …) views) or once per bearing."""
        lay, bearings = self.layout, self.model.bearings
        if self.stack:
            flat = z.reshape((-1, lay.width))
            tm = bearings[0].tm
            n = lay.phi_size[0]
            phi = flat[:, :n].reshape((flat.shape[0],) + lay.phi[0])
            w = None
            if lay.foil[0] is not None:
                w = flat[:, n:n + lay.foil_size[0]].reshape(
                    (flat.shape[0],) + lay.foil[0])
            return [(slice(None), tm, phi, xy[..., 0].ravel(), xy[..., 1].ravel(), w)]
        return [(k, b.tm, lay.phi_of(z, k), xy[:, k, 0], xy[:, k, 1], lay.foil_of(z, k))
                for k, b in enumerate(bearings)]

    def _at_running(self, tm, k: int, offset):
        """Bearing k's model with its running line's film offset δ_k (a float: one speed for
        the batch) folded into the bore: H_r = 1 + bore − δ − X cos θ − Y sin θ."""
        if offset is None:
            return tm
        return replace(tm, bore=tm.bore - float(np.max(np.atleast_1d(offset)[..., k])))

    def pressures(self, z: np.ndarray) -> list:
        """[(P, H)] per bearing, each (B, ...), at the states ``z``."""
        xy = self.journals(z)
        out = []
        offset = None
        if self.running is not None:
            offset = self.running.at(self._speed(self.layout.rotor_of(z)[:, 2 * self.dofs]))[0]
        for k, b in enumerate(self.model.bearings):
            p, h = pressure_and_film(self.layout.phi_of(z, k), xy[:, k, 0], xy[:, k, 1],
                                     self._at_running(b.tm, k, offset),
                                     deflection=self.layout.foil_of(z, k),
                                     slider=self.slider(k))
            out.append((p, h))
        return out

    # ---------------------------------------------------------------- RHS
    def __call__(self, z: np.ndarray) -> np.ndarray:
        self.evaluations += 1
        nb, start, n = z.shape[0], self._rotor_start, self.dofs
        rotor = z[:, 0, start:]                        # q̃, q̃', τ (Layout.rotor_of)
        tau = rotor[:, 2 * n]
        xy = np.dot(rotor[:, :n], self.to_local).reshape(nb, -1, 2)       # journals()
        speed = self._speed(tau)
        out = np.empty_like(z)
        out[:, :, self._filled:] = 0.0                 # padding (the rotor's tail is set below)
        if self.fused is not None:                     # every film at once (.rotor_films)
            forces = self.fused.evaluate(z, xy, speed, out, self.min_film,
                                         self.max_deflection if self.track_deflection else None)
        else:
            forces = self._films_one_by_one(z, xy, speed, out)
        velocity = rotor[:, n:2 * n]
        tail = out[:, 0, start:]
        tail[:, :n] = velocity
        tail[:, 2 * n] = 1.0
        if self.accel is not None and nb == self._stack.shape[0]:
            x, two_k = self._stack, forces.shape[1] * 2
            x[:, :two_k] = forces.reshape(nb, -1)
            if self._planes:
                self._phase_terms(tau, x[:, two_k:two_k + 2])
            np.multiply(velocity, speed if isinstance(speed, float) else speed[:, None],
                        out=x[:, two_k + 2:two_k + 2 + n])
            if self.elastic:
                x[:, two_k + 2 + n:two_k + 2 + 2 * n] = velocity
                x[:, two_k + 2 + 2 * n:] = rotor[:, :n]
            acc = np.dot(x, self.combined)
            acc += self.static_accel
            tail[:, n:2 * n] = acc
            return out
        load = np.dot(forces.reshape(nb, -1), self.from_local)
        load += self.static
        if self._planes:
            load += self._imbalance(tau)
        if self.elastic:
            load += np.dot(velocity, self.damp_force) + np.dot(rotor[:, :n], self.stiff_force)
        acc = (np.dot(load, self.accel) if self.accel is not None
               else np.einsum("bij,bj->bi", self.accel_each, load))
        turn = np.dot(velocity, self.gyro)
        turn *= speed if isinstance(speed, float) else speed[:, None]
        acc -= turn
        tail[:, n:2 * n] = acc
        return out

    def _films_one_by_one(self, z, xy, speed, out) -> np.ndarray:
        """The films through the one-bearing kernels (stacked or bearing by bearing): writes
        dΦ/dτ and dW/dτ into ``out``, returns the forces (B, K, 2)."""
        lay, nb, k = self.layout, z.shape[0], len(self.model.bearings)
        forces = np.empty((nb, k, 2))
        offset = inverse = None
        if self.running is not None:
            if not isinstance(speed, float):
                raise ParameterError("runs", "speeds", "the running line's films take one "
                                     "speed for the batch")
            offset, inverse = self.running.at(speed)
        for j, tm, phi, x, y, w in self._films(z, xy):
            jj = 0 if self.stack else j
            p, h = pressure_and_film(phi, x, y, self._at_running(tm, j, offset), deflection=w,
                                     slider=self.slider(j))
            lam = self.base_lambda[jj] * speed
            if not isinstance(speed, float):
                lam = (np.repeat(lam, k) if self.stack else lam)[:, None, None]
            kernel = self._kernels[jj]
            ratio = 1.0 if inverse is None else float(inverse[j])      # μ_ref/μ
            kernel.bearing_number = lam / ratio                        # Λ μ/μ_ref
            dphi = flux_residual(p, h, kernel)
            dphi *= ratio / self.film_divisor[jj]                      # over 2Λ μ/μ_ref
            fx, fy = film_force(p, tm)
            hmin = h.min(axis=(1, 2))
            n = lay.phi_size[jj]
            if self.stack:
                view = out.reshape((-1, lay.width))
                view[:, :n] = dphi.reshape(view.shape[0], n)
                forces[:, :, 0], forces[:, :, 1] = fx.reshape(nb, k), fy.reshape(nb, k)
                np.minimum(self.min_film, hmin.reshape(nb, k), out=self.min_film)
            else:
                view = out[:, j]
                view[:, :n] = dphi.reshape(nb, n)
                forces[:, j, 0], forces[:, j, 1] = fx, fy
                np.minimum(self.min_film[:, j], hmin, out=self.min_film[:, j])
            if tm.foil_state is not None:
                dw = tm.foil_state.rate(p, w, tm, self.slider(j))
                if self.foil_factor[jj] != 1.0:
                    dw *= self.foil_factor[jj]
                view[:, n:n + dw[0].size] = dw.reshape(view.shape[0], -1)
            if self.track_deflection:
                d = largest_deflection(h, x, y, tm)
                if self.stack:
                    np.maximum(self.max_deflection, d.reshape(nb, k), out=self.max_deflection)
                else:
                    np.maximum(self.max_deflection[:, j], d, out=self.max_deflection[:, j])
        return forces

    def _phase_terms(self, tau: np.ndarray, out: np.ndarray) -> np.ndarray:
        """(α, β) (B, 2) of every run at τ, into ``out``: Q_u = α U + β V
        (:func:`imbalance_shapes`), α = r² cos ϑ + a sin ϑ, β = r² sin ϑ − a cos ϑ with
        r = ω/ω_ref, a = dr/dτ, ϑ the shaft angle; times each run's imbalance scale."""
        if self.same_speed:          # one shaft angle for the batch: scalars
            t = float(tau[0])
            r0, a = float(self.runs.speed[0]), float(self.runs.ramp[0])
            r2 = (r0 + a * t) ** 2
            c, s = math.cos(r0 * t + 0.5 * a * t * t), math.sin(r0 * t + 0.5 * a * t * t)
            if out.shape[0] == 1:                    # one run: two scalar stores
                u = float(self.runs.imbalance_scale[0])
                out[0, 0], out[0, 1] = u * (r2 * c + a * s), u * (r2 * s - a * c)
                return out
            return np.multiply(self.runs.imbalance_scale[:, None],
                               (r2 * c + a * s, r2 * s - a * c), out=out)
        r2 = self.runs.speed_at(tau) ** 2
        angle = self.runs.angle_at(tau)
        c, s, a = np.cos(angle), np.sin(angle), self.runs.ramp
        out[:, 0] = r2 * c + a * s
        out[:, 1] = r2 * s - a * c
        out *= self.runs.imbalance_scale[:, None]
        return out

    def _imbalance(self, tau: np.ndarray) -> np.ndarray:
        """Q_u (B, n) [N] of every run at τ (module docstring)."""
        ab = self._phase_terms(tau, np.empty((tau.size, 2)))
        return np.outer(ab[:, 0], self.shape_u) + np.outer(ab[:, 1], self.shape_v)

    # ---------------------------------------------------------------- stiffness
    def stiffness(self, z: np.ndarray) -> float:
        """Gershgorin bound ρ [per rad of τ] of the films and foil states at ``z`` (the
        one-bearing bound, with each bearing's Λ at its current speed), at least the
        structure's highest natural frequency on rigid supports (:attr:`structure_rate`,
        0 for the rigid body): an explicit step within ρ is within that mode's too."""
        xy = self.journals(z)
        r = float(np.max(self.runs.speed_at(self.layout.rotor_of(z)[:, 2 * self.dofs])))
        rho = self.structure_rate
        offset = inverse = None
        if self.running is not None:
            offset, inverse = self.running.at(r)
        for k, b in enumerate(self.model.bearings):
            tm = self._at_running(b.tm, k, offset)
            lam = self.base_lambda[k] * r
            s = State(self.layout.phi_of(z, k), xy[:, k, 0], xy[:, k, 1], xy[:, k, 0] * 0,
                      xy[:, k, 0] * 0, self.layout.foil_of(z, k))
            film = stiffness_bound(s, replace(tm, bearing_number=lam, foil_state=None),
                                   self.slider(k))
            # the diffusion carries μ_ref/μ, the advection not: max(1, μ_ref/μ) bounds both
            rho = max(rho, film * 2.0 * lam / self.film_divisor[k]
                      * (1.0 if inverse is None else max(1.0, float(inverse[k]))))
            if tm.foil_state is not None:
                p, h = pressure_and_film(s.phi, s.x, s.y, tm, deflection=s.w)
                rho = max(rho, foil_bound(p, h, tm) * self.foil_factor[k])
        return rho
