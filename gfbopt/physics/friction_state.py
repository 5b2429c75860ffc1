"""The bumps' friction as a transient state: pure functions for the slider of each foil unit.

The spring–slider (Jenkins) element of :mod:`gfbopt.physics.friction` beside each bump, written
for an integrator that carries the slider position Z_u of every foil unit (θ row of the
axial-mean law, or node of the local law) as a state, non-dimensional (clearances, ambient
pressures, per unit area):

* bump reaction W/S, element reaction (κ/S)(W − Z), with |(κ/S)(W − Z)| ≤ μ_f q⁺;
* slip displacement X_s = μ_f q⁺ S/κ (:func:`slip_displacement`), q the local gauge pressure;
* the massless foil balances the film: W/S + (κ/S)(W − Z) = q while stuck, and
  W/S ± μ_f q⁺ = q while slipping (:func:`foil_deflection`, exact, no regularisation);
* after an accepted step the slider follows the play operator Z ← clip(Z, W − X_s, W + X_s)
  (:func:`slider_after_step`), the exact update for a deflection monotone over the step.

The slider has no rate: it is not an ODE state but a discrete map applied once per accepted
step; each stage of the step sees the element at the stage's deflection through the play
operator from the step's starting Z (for the massless foil that is :func:`foil_deflection`
with the starting Z).  No regularisation; the stick/slip switch falls inside one step, and
halving the step checks it (tests/unit/test_friction_state.py: the settled amplitude of the
self-excited oscillator moves by ~3e-6 relative when the step is halved).

How the one-bearing transient uses it: :mod:`gfbopt.transient.friction_foil` carries Z
(B, m) beside the journal state and recovers P and H with the closed forms of
:func:`foil_deflection` (axial-mean law: the stuck branch is the simple law's quadratic with
compliance S/(1 + κ) and the offset κZ/(1 + κ), the slipping branch the simple law with
S(1 ∓ μ_f) on q > 0); :mod:`gfbopt.transient.friction_orbit` applies the play operator after
each accepted RK4 step (tests/verification/test_friction_transient.py checks the recovery
against :func:`foil_deflection` to 1e-12).  The rotor transient does not carry Z yet.
"""
from __future__ import annotations

import numpy as np

__all__ = ["element_reaction", "foil_deflection", "slider_after_step", "slip_displacement"]


def slip_displacement(gauge, compliance, coefficient, stiffness_ratio):
    """X_s = μ_f q⁺ S/κ [clearances]: the element's stretch when its slider slips (arrays).

    gauge q (P̄ − 1 or P − 1); compliance S (bump); coefficient μ_f; stiffness_ratio κ.
    """
    return coefficient * np.maximum(np.asarray(gauge, dtype=float), 0.0) * compliance \
        / stiffness_ratio


def element_reaction(deflection, slider, compliance, stiffness_ratio):
    """(κ/S)(W − Z): the friction element's reaction on the foil [ambient pressures]."""
    return stiffness_ratio / compliance * (np.asarray(deflection) - np.asarray(slider))


def foil_deflection(gauge, slider, compliance, coefficient, stiffness_ratio):
    """(W, stuck) of the massless foil under gauge q with the slider at Z (arrays).

    Stuck when the stuck balance W = (S q + κ Z)/(1 + κ) stretches the element by at most X_s;
    otherwise slipping in the direction of the stretch: W = S (q − sign·μ_f q⁺).  Exact: the
    returned W satisfies the foil's balance with the element's reaction clipped at μ_f q⁺.
    """
    q = np.asarray(gauge, dtype=float)
    z = np.asarray(slider, dtype=float)
    xs = slip_displacement(q, compliance, coefficient, stiffness_ratio)
    w_stuck = (compliance * q + stiffness_ratio * z) / (1.0 + stiffness_ratio)
    stretch = w_stuck - z
    stuck = np.abs(stretch) <= xs
    w_slip = compliance * (q - np.sign(stretch) * coefficient * np.maximum(q, 0.0))
    return np.where(stuck, w_stuck, w_slip), stuck


def slider_after_step(slider, deflection, gauge, compliance, coefficient, stiffness_ratio):
    """Z after an accepted step that ended at deflection W under gauge q (the play operator)."""
    xs = slip_displacement(gauge, compliance, coefficient, stiffness_ratio)
    w = np.asarray(deflection, dtype=float)
    return np.minimum(np.maximum(np.asarray(slider, dtype=float), w - xs), w + xs)
