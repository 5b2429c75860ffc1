"""The fused film evaluation of the rotor transient (:class:`.rotor_films.FusedFilms`) for
bearings whose bumps rub: the axial-mean law's row film with each row's spring–slider
element, all bearings of all runs in one (B·K, m) pass.

Only the row film a changes (:meth:`FrictionFusedFilms._film`); the flux, the force and the
smallest film are :class:`~.rotor_films.FusedFilms`' own.  The row film is
:func:`.friction_foil.friction_rows`' closed form, branch by branch, with the per-bearing
numbers as per-row coefficients: on each row Φ̃ = Φ̄ (live rows) or (1 − c) H_r (rows at
ambient), c the axial ends' weight share, and

* stuck:    a² − b a − S_e Φ̃ = 0, S_e = S/(1 + κ), b = H_r + κZ/(1 + κ) + S_e (c − 1);
* slipping: the same with S_e = S (1 ∓ μ_f) (sense of the element's stretch) on loaded rows
  (Φ̃/H_r + c − 1 > 0, or H_r ≤ 0: that row's film needs W > 0), S on the others, and no
  offset;

stuck where the stuck candidate's stretch |a − H_r − Z| is within the slip displacement
X_s = μ_f q⁺ S/κ (X_s > 0).  The sliders after an accepted step (:meth:`after_step`) are
:func:`.friction_foil.slider_after_step`'s play operator on the same rows.  Both equal the
one-bearing functions to round-off (tests/unit/test_rotor_friction_transient.py).

With a loss factor η > 0 (the Kelvin–Voigt row state W, :mod:`.foil_state` "With
friction") the row film is :class:`~.rotor_films.FusedFilms`' own, a = H_r + W, and the
element enters the foil's rate only: :meth:`FrictionFusedFilms.evaluate` takes the damped
fused evaluation and adds to each row's dW/dτ the element's share,
−S r (the bump's S (q − r) for S q; S max(q − r, 0) − S max(q, 0) for compression-only bumps)
over τ_f, r = clip((κ/S)(W − Z), ±μ_f q⁺) at the state's W from the step's Z and q = P̄ − 1
of P = Φ/(H_r + W) — :meth:`.foil_state.KelvinVoigtFoil.rate` with the sliders; with μ_f = 0
the share is exactly 0, so the rates are the damped fused films' bit for bit.  The sliders
move after a step from the state's W (:func:`.friction_foil.slider_after_step` with
``deflection``).

It serves a rotor whose every bearing is fusable (:func:`.rotor_films.fusable`) and carries
friction on θ rows (the axial-mean law); others take the one-bearing kernels.
"""
from __future__ import annotations

import numpy as np

from .rotor_films import FusedFilms, fusable


def fusable_with_friction(model) -> bool:
    """True when :class:`FrictionFusedFilms` serves every bearing of ``model``."""
    return fusable(model) and all(b.tm.friction is not None and b.tm.friction.layout == "rows"
                                  for b in model.bearings)


class FrictionFusedFilms(FusedFilms):
    """:class:`~.rotor_films.FusedFilms` with each row's friction element; ``slider`` is the
    sliders Z of every film, (B·K, m), set by the right-hand side before an evaluation."""

    def __init__(self, model, size: int, film_divisor, foil_factor, base_lambda):
        super().__init__(model, size, film_divisor, foil_factor, base_lambda)
        tms = [b.tm for b in model.bearings]
        tile = lambda per: np.tile(np.asarray(per, dtype=float), (size, 1))  # noqa: E731
        kappa = tile([[t.friction.stiffness_ratio] for t in tms])                 # (N, 1)
        mu = tile([t.friction.coefficient for t in tms])                           # (N, m)
        ends = float(self.zw[[0, -1]].sum() / self.zw_sum)
        self.ends_m1 = ends - 1.0
        self.fill = (1.0 - ends) * self.ambient                                    # (m,)
        self.offset = kappa / (1.0 + kappa)
        stuck_s = self.s / (1.0 + kappa)
        self.stuck_b, self.stuck_s4 = stuck_s * self.ends_m1, 4.0 * stuck_s
        self.mu_s = mu * self.s
        self.slip_gain = self.mu_s / kappa                                         # X_s / q⁺
        self.slider = None
        if self.damped:           # the element's reaction r = clip(κ/S (W − Z), ±μ_f q⁺)
            self.mu = mu
            self.spring = np.where(self.s > 0.0, kappa / np.where(self.s > 0.0, self.s, 1.0),
                                   0.0)                                            # κ/S
            self._w = self._a = None       # the rows' W and a of the last evaluation

    def _friction_rows(self, hr: np.ndarray, mean: np.ndarray, slider: np.ndarray) -> tuple:
        """(a, q) of every row (module docstring) from H_r, Φ̄ and Z, (B·K, m) each."""
        phit = mean * self.live
        phit += self.fill * hr
        b = hr + self.stuck_b
        b += self.offset * slider
        a_st = np.sqrt(b * b + self.stuck_s4 * phit)
        a_st += b
        a_st *= 0.5
        q_st = phit / a_st
        q_st += self.ends_m1
        stretch = a_st - hr
        stretch -= slider
        xs = np.maximum(q_st, 0.0)
        xs *= self.slip_gain
        stuck = (np.abs(stretch) <= xs) & (xs > 0.0)
        loaded = (hr <= 0.0) | (phit / np.where(hr > 0.0, hr, 1.0) + self.ends_m1 > 0.0)
        s_slip = np.where(loaded, self.s - np.where(stretch > 0, self.mu_s, -self.mu_s),
                          self.s)
        b = s_slip * self.ends_m1
        b += hr
        a = np.sqrt(b * b + 4.0 * s_slip * phit)
        a += b
        a *= 0.5
        a = np.where(stuck, a_st, a)
        if self.compression_only:
            np.maximum(a, hr, out=a)
        return a, phit / a + self.ends_m1

    def _film(self, hr: np.ndarray, mean: np.ndarray, flat: np.ndarray) -> np.ndarray:
        if self.damped:                    # a = H_r + W: the element is in the foil's rate
            a = super()._film(hr, mean, flat)
            self._w, self._a = flat[:, self.n:self.n + self.shape[0]], a
            return a
        return self._friction_rows(hr, mean, self.slider)[0]

    def evaluate(self, z: np.ndarray, xy: np.ndarray, speed, out: np.ndarray,
                 min_film: np.ndarray, max_deflection) -> np.ndarray:
        """:meth:`.rotor_films.FusedFilms.evaluate`; with η > 0 each row's dW/dτ then gets
        the friction element's share (module docstring)."""
        forces = super().evaluate(z, xy, speed, out, min_film, max_deflection)
        if not self.damped:
            return forces
        big, n, m = z.shape[0] * self.k, self.n, self.shape[0]
        phi = z.reshape(big, -1)[:, :n].reshape(big, m, self.shape[1])
        w, a = self._w, self._a
        q = self._gauge(phi, a)
        r = self._reaction(q, w, self.slider)
        if self.compression_only:
            share = np.maximum(q - r, 0.0)
            share -= np.maximum(q, 0.0)
        else:
            share = -r
        share *= self.live_s
        share *= self.foil_scale
        out.reshape(big, -1)[:, n:n + m] += share
        return forces

    def _gauge(self, phi: np.ndarray, a: np.ndarray) -> np.ndarray:
        """q = P̄ − 1 of P = Φ/a on the live rows (P = 1 on the axial ends), 0 at ambient."""
        q = np.matmul(phi, self.zw_inner) / a
        q += self.ends_m1
        q *= self.live
        return q

    def _reaction(self, q: np.ndarray, w: np.ndarray, slider: np.ndarray) -> np.ndarray:
        """r = clip((κ/S)(W − Z), −μ_f q⁺, μ_f q⁺) (:func:`.friction_foil.element_reaction`)."""
        bound = np.maximum(q, 0.0)
        bound *= self.mu
        return np.minimum(np.maximum(self.spring * (w - slider), -bound), bound)

    def after_step(self, z: np.ndarray, xy: np.ndarray, slider: np.ndarray) -> np.ndarray:
        """Z (B·K, m) after an accepted step ending at ``z`` (B, K, L) with journals ``xy``
        (B, K, 2), from the step's starting Z: clip(Z, W − X_s, W + X_s) at the final W, q
        (with η > 0 the state's W and q of P = Φ/(H_r + W))."""
        big, (m, w) = z.shape[0] * self.k, self.shape
        phi = z.reshape(big, -1)[:, :self.n].reshape(big, m, w)
        hr = (np.dot(xy.reshape(big, 2), self.trig) if self.same_angles
              else np.einsum("ni,nim->nm", xy.reshape(big, 2), self.trig))
        hr += self.base
        if self.damped:                    # W is the state's; q from P = Φ/(H_r + W)
            deflection = z.reshape(big, -1)[:, self.n:self.n + m]
            q = self._gauge(phi, hr + deflection)
        else:
            a, q = self._friction_rows(hr, np.matmul(phi, self.zw_inner), slider)
            deflection = a - hr
        xs = np.maximum(q, 0.0)
        xs *= self.slip_gain
        return np.minimum(np.maximum(slider, deflection - xs), deflection + xs)
