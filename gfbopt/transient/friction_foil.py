"""The bumps' Coulomb friction in the one-bearing transient: the slider state of each foil unit.

Each foil unit (θ row of the axial-mean law) carries a spring–slider (Jenkins) element beside
its bump (:mod:`gfbopt.physics.friction`, docs/PHYSICS.md §7a), non-dimensional: bump reaction
W/S, element reaction (κ/S)(W − Z) clipped at μ_f q⁺, q = P̄ − 1 the row's gauge pressure, so
the slip displacement is X_s = μ_f q⁺ S/κ.  The slider positions Z (B, m) are the state.

Recovery of P and H from Φ = P H, the journal position and Z (massless foil, no regularisation).
On each row H = a = H_r + W, P = Φ/a, P̄ = Φ̃/a + c (:func:`~gfbopt.physics.foil_recovery.
row_mean_phi`).  The foil's balance W/S + r = q with r the element's reaction has three closed
forms, each the simple law's quadratic a² − b a − S_e Φ̃ = 0, b = H_r + W_off + S_e (c − 1):

* stuck:           S_e = S/(1 + κ), W_off = κ Z/(1 + κ)   (r = (κ/S)(W − Z), |W − Z| ≤ X_s);
* slipping out:    S_e = S (1 − μ_f), W_off = 0           (W − Z > X_s, r = +μ_f q);
* slipping in:     S_e = S (1 + μ_f), W_off = 0           (W − Z < −X_s, r = −μ_f q);
* unloaded rows (q ≤ 0, the sign of q is that of Φ̃/H_r + c − 1 for every S_e when H_r > 0;
  a row with H_r ≤ 0 is loaded, its film needs W > 0): W = S q, or 0 for compression-only
  bumps.

Hardening bumps (the 'hardened' law) have no closed form: their rows solve the same balance
with the hardened reaction by a safeguarded Newton (:func:`.hardening_recovery.
hardened_friction_rows`), the same branches picked the same way.

The local law (one unit per node, q = P − 1) has the same branches on its per-node quadratic
S_e P² + (H_r + W_off − S_e) P − Φ = 0 (:func:`friction_nodes`); boundary nodes carry none.

The balance F(W) = W/S + clip((κ/S)(W − Z), ±μ_f q⁺(W)) − q(W) rises monotonically in W (q
falls as W rises; μ_f < 1 keeps the slipping branches rising), so the root is unique, and
when the stuck candidate stretches the element beyond X_s in one sense the root slips in that
sense: the stuck candidate, checked, picks the branch (exact, two square roots per row).

With μ_f = 0 every X_s is 0 and the slipping branch is the simple law's own formula (the same
floating-point operations): the elastic foundation bit for bit.

The slider after a step (operator splitting).  Z has no rate: between two accepted steps it
follows the play operator Z ← clip(Z, W − X_s, W + X_s), exact for a deflection monotone over
the step.  Every stage of an integrator step sees the element by the play operator from the
step's starting Z (the recovery above with that Z *is* the play operator at the stage's W), and
after the accepted step Z is updated once from the step's final W and q
(:func:`slider_after_step`).  Inside a step whose W reverses, the stages use the starting Z
where the true path has a slider that has just stopped: the error is confined to the steps
containing a reversal (two per whirl period), so the scheme converges at first order in Δτ at
worst — tests/verification/test_friction_transient.py halves the step and shows the settled
amplitude unchanged to well below 1 %.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..physics.foil_recovery import row_mean_phi, set_boundary
from .hardening_recovery import hardened_friction_rows


@dataclass(frozen=True, eq=False)
class FrictionFoil:
    """The friction elements of a transient model's θ rows [-].

    coefficient : μ_f per θ row (m,) (bump zones may differ); stiffness_ratio : κ = k_f/k_b;
    equilibrium : the slider positions of the static equilibrium, Z = W0 per row (m,) or per
    node (m, n_z + 1) (friction holds no static deflection: the element is relaxed there);
    layout : 'rows' (axial-mean law) or 'nodes' (local law).
    """

    coefficient: np.ndarray
    stiffness_ratio: float
    equilibrium: np.ndarray
    layout: str = "rows"

    def describe(self) -> dict:
        """μ_f (largest over the rows) and κ, for results."""
        return {"friction_coefficient": float(np.max(self.coefficient)),
                "friction_stiffness_ratio": float(self.stiffness_ratio),
                "friction_state": "spring–slider per θ row, slider by the play operator "
                                  "after each accepted step"}


def friction_foil(solution, rigid_film: np.ndarray, mu_rows: np.ndarray,
                  layout: str = "rows") -> FrictionFoil:
    """The friction state of a transient model about ``solution``.

    rigid_film : H_r (m,) at the equilibrium; mu_rows : μ_f per θ row; layout : 'rows'
    (axial-mean law) or 'nodes' (local law).
    """
    model = solution.model
    mu = np.asarray(mu_rows, dtype=float)
    if np.any(mu >= 1.0):
        raise ParameterError("friction_coefficient", float(mu.max()), "must be < 1 in the "
                             "transient (the slipping foil's balance W = S(1 − μ_f) q needs it)")
    w0 = solution.film - rigid_film[:, None]
    w0 = w0[:, 0].copy() if layout == "rows" else w0.copy()
    return FrictionFoil(mu, float(model.friction_stiffness_ratio), w0, layout)


def _root(hr, off, s_e, phit, c):
    """a = ½ (b + √(b² + 4 S_e Φ̃)), b = H_r + W_off + S_e (c − 1) (the simple law's form)."""
    b = hr + off + s_e * (c - 1.0) if off is not None else hr + s_e * (c - 1.0)
    return 0.5 * (b + np.sqrt(b * b + 4 * s_e * phit))


def friction_rows(phi: np.ndarray, hr: np.ndarray, slider: np.ndarray, tm) -> tuple:
    """(a, q, stuck): the row films a = H_r + W (B, m), gauge q = P̄ − 1 and the stuck mask,
    from Φ (B, m, n_z + 1), H_r (B, m) and the slider positions Z (B, m) (module doc)."""
    if tm.law.name == "hardened":
        return hardened_friction_rows(phi, hr, slider, tm)
    fr = tm.friction
    phit, c = row_mean_phi(phi, hr, tm)
    s = tm.compliance_rows
    mu, kappa = fr.coefficient, fr.stiffness_ratio
    a_stuck = _root(hr, kappa * slider / (1.0 + kappa), s / (1.0 + kappa), phit, c)
    q_stuck = phit / a_stuck + c - 1.0
    stretch = a_stuck - hr - slider
    xs = mu * np.maximum(q_stuck, 0.0) * s / kappa
    stuck = (np.abs(stretch) <= xs) & (xs > 0.0)     # X_s = 0 carries nothing: slipping
    sense = np.where(stretch > 0, 1.0, -1.0)
    loaded = (hr <= 0.0) | (phit / np.where(hr > 0.0, hr, 1.0) + c - 1.0 > 0.0)  # H_r ≤ 0: W > 0
    s_slip = np.where(loaded, s * (1.0 - sense * mu), s)
    a = np.where(stuck, a_stuck, _root(hr, None, s_slip, phit, c))
    if tm.compression_only:
        a = np.maximum(a, hr)
    return a, phit / a + c - 1.0, stuck


def friction_nodes(phi: np.ndarray, hr: np.ndarray, slider: np.ndarray, tm) -> tuple:
    """(P, H, q, stuck) of the local law (B, m, n_z + 1) from Φ, H_r (B, m) and the sliders
    Z (B, m, n_z + 1): per node S_e P² + (H_r + W_off − S_e) P − Φ = 0 with the branches of
    the module docstring (q = P − 1; a node is loaded when Φ > H_r; boundary nodes, P = 1,
    carry no friction)."""
    fr = tm.friction
    s = tm.compliance_rows[:, None]
    mu, kappa = fr.coefficient[:, None], fr.stiffness_ratio
    hr3 = hr[:, :, None]
    s_st = s / (1.0 + kappa)
    h_st = hr3 + kappa * slider / (1.0 + kappa)
    p_st = (-(h_st - s_st) + np.sqrt((h_st - s_st) ** 2 + 4 * s_st * phi)) / (2 * s_st)
    q_st = p_st - 1.0
    stretch = h_st + s_st * q_st - hr3 - slider
    xs = mu * np.maximum(q_st, 0.0) * s / kappa
    stuck = (np.abs(stretch) <= xs) & (xs > 0.0)
    stuck[..., :, 0] = stuck[..., :, -1] = False
    stuck[..., tm.ambient, :] = False
    sense = np.where(stretch > 0, 1.0, -1.0)
    s_sl = np.where(phi > hr3, s * (1.0 - sense * mu), s)
    p_sl = (-(hr3 - s_sl) + np.sqrt((hr3 - s_sl) ** 2 + 4 * s_sl * phi)) / (2 * s_sl)
    if tm.compression_only:   # W = S max(P − 1, 0): where P < 1 the film is rigid
        p_sl = np.where(p_sl < 1.0, phi / hr3, p_sl)
    p = set_boundary(np.where(stuck, p_st, p_sl), tm)
    q = p - 1.0
    w_sl = s_sl * (q if not tm.compression_only else np.maximum(q, 0.0))
    h = hr3 + np.where(stuck, h_st - hr3 + s_st * q, w_sl)
    return p, h, q, stuck


def recover_with_slider(phi: np.ndarray, hr: np.ndarray, slider: np.ndarray, tm) -> tuple:
    """(P (B, m, n_z + 1), H (B, m, 1) rows or (B, m, n_z + 1) nodes) of the friction model
    from Φ, H_r and Z."""
    if tm.friction.layout == "nodes":
        return friction_nodes(phi, hr, slider, tm)[:2]
    a = friction_rows(phi, hr, slider, tm)[0]
    return set_boundary(phi / a[:, :, None], tm), a[:, :, None]


def _deflection(phi, hr, slider, tm, deflection=None) -> tuple:
    """(W, q, stuck) in the layout of the sliders; with the Kelvin–Voigt state W is
    ``deflection`` and q that of P = Φ/(H_r + W) (:func:`damped_gauge`)."""
    if tm.foil_state is not None:
        q = damped_gauge(phi, hr, deflection, tm)
        xs = slip(q, tm)
        return deflection, q, (np.abs(deflection - slider) <= xs) & (xs > 0.0)
    if tm.friction.layout == "nodes":
        p, h, q, stuck = friction_nodes(phi, hr, slider, tm)
        return h - hr[:, :, None], q, stuck
    a, q, stuck = friction_rows(phi, hr, slider, tm)
    return a - hr, q, stuck


def slip(q: np.ndarray, tm) -> np.ndarray:
    """X_s = μ_f q⁺ S/κ in the sliders' layout [clearances] (q in that layout)."""
    fr = tm.friction
    s = tm.compliance_rows if fr.layout == "rows" else tm.compliance_rows[:, None]
    mu = fr.coefficient if fr.layout == "rows" else fr.coefficient[:, None]
    return mu * np.maximum(q, 0.0) * s / fr.stiffness_ratio


def damped_gauge(phi: np.ndarray, hr: np.ndarray, w: np.ndarray, tm) -> np.ndarray:
    """q in the foil state's layout from Φ, H_r and the Kelvin–Voigt W: P̄ − 1 per row (0 on
    rows at ambient) or P − 1 per node, P = Φ/(H_r + W) (as the foil's rate sees it)."""
    p = tm.law.recover_deflected(phi, hr, w, tm)[0]
    return element_gauge(p, tm)


def element_gauge(p: np.ndarray, tm) -> np.ndarray:
    """The gauge pressure of each foil unit from P (B, m, n_z + 1): P̄ − 1 per θ row (0 on
    rows at ambient), as :meth:`~gfbopt.physics.foil_laws.SimpleLaw.deflection_target` forms
    it, or P − 1 per node (layout of ``tm.foil_state``, else of ``tm.friction``)."""
    layout = (tm.foil_state or tm.friction).layout
    if layout == "nodes":
        return p - 1.0
    q = (p @ tm.z_weight) / tm.z_weight.sum() - 1.0
    q[:, tm.ambient] = 0.0
    return q


def element_reaction(q: np.ndarray, w: np.ndarray, slider: np.ndarray, tm) -> np.ndarray:
    """The friction element's reaction r = clip((κ/S)(W − Z), −μ_f q⁺, μ_f q⁺) per unit
    [ambient pressures], in the sliders' layout: the play operator at W from Z."""
    fr = tm.friction
    rows = fr.layout == "rows"
    s = tm.compliance_rows if rows else tm.compliance_rows[:, None]
    mu = fr.coefficient if rows else fr.coefficient[:, None]
    kb = np.where(s > 0.0, fr.stiffness_ratio / np.where(s > 0.0, s, 1.0), 0.0)
    bound = mu * np.maximum(q, 0.0)
    return np.minimum(np.maximum(kb * (w - slider), -bound), bound)


def slider_after_step(phi: np.ndarray, hr: np.ndarray, slider: np.ndarray, tm,
                      deflection=None) -> np.ndarray:
    """Z after an accepted step ending at Φ, H_r, from the step's starting Z: the play
    operator clip(Z, W − X_s, W + X_s) at the step's final W and q (in the sliders' layout);
    ``deflection``: the Kelvin–Voigt W of a damped model (its state at the step's end)."""
    w, q, _ = _deflection(phi, hr, slider, tm, deflection)
    xs = slip(q, tm)
    return np.minimum(np.maximum(slider, w - xs), w + xs)


def stuck_share(phi: np.ndarray, hr: np.ndarray, slider: np.ndarray, tm,
                deflection=None) -> np.ndarray:
    """Share of the loaded units (rows or nodes) whose slider is stuck, per rotor (B,) [-]."""
    _, q, stuck = _deflection(phi, hr, slider, tm, deflection)
    loaded = (q > 0).reshape(q.shape[0], -1)
    count = loaded.sum(axis=1)
    both = (stuck.reshape(q.shape[0], -1) & loaded).sum(axis=1)
    return np.where(count > 0, both / np.maximum(count, 1), 0.0)
