"""The hardening bump in the transients: the recovery of P and H from Φ = P H (axial-mean law).

The bump of each θ row carries the reaction q_b(W) of the hardening law (stiffness
k0/(1 − δ/δ_lim)^n, :mod:`gfbopt.physics.hardening`; non-dimensional W = δ/c, S = p_a/(c k0),
W_lim = δ_lim/c), so the simple law's closed-form quadratic is gone.  On a row whose film is
a = H_r + W, P = Φ/a and P̄ = Φ̃/a + c (:func:`~gfbopt.physics.foil_recovery.row_mean_phi`),
the foil's balance is solved in the bump's reaction ρ = q_b(W), W = W_h(ρ) the law's closed
inverse (smooth, bounded by W_lim, no singularity at the flat bump)::

    f(ρ) = ρ + κ_b (W_h(ρ) − Z) − s_b q(W_h(ρ)) = 0,    q(W) = Φ̃/(H_r + W) + c − 1,

with (κ_b, Z, s_b) = (0, 0, 1) without friction; with the bumps' spring–slider element
(:mod:`.friction_foil`) (κ/S, Z, 1) when it is stuck (element reaction (κ/S)(W − Z)) and
(0, 0, 1 ∓ μ_f) when it slips outwards / inwards (reaction ±μ_f q).  f rises strictly in ρ
(f' = 1 + (κ_b + s_b Φ̃/a²) W_h' ≥ 1, W_h' ≥ 0), so the root is unique.  It is bracketed in
closed form — below by min(0, κ_b Z + s_b (c − 1)) (q > c − 1) or the reaction at which the
film closes, a = 0 (there f → −∞); above by max(ρ*, s_b Q* − κ_b (W* − Z)) with W* halfway
between max(0, −H_r) and W_lim, ρ* = q_b(W*), Q* = q(W*) — and found by Newton's method
safeguarded by bisection (a step leaving the bracket, or one after an iterate that did not
halve |f|, is replaced by the bracket's midpoint), vectorised over rows and runs, until every
Newton step is below 1e-14 (1 + |ρ|): that last step taken, with Newton's quadratic
convergence the root is at round-off.  From the previous evaluation's roots (kept in the
right-hand side's cache) plain Newton is tried first and kept when every row converges in a
few steps with |f| halving; else the safeguarded iteration runs (one root: the same answer).  A row
whose rigid film is so negative that even the flat bump cannot open it (H_r + W_lim ≤ 0, the
journal through the bump's height) has no root: its rigid film is raised to
1e-9 − W_lim, a film ≤ 1e-9, which the integrators' contact test stops.

:class:`HardenedTransientLaw` is the registry's hardened law with this recovery, engines
rk4 and rkc (the one-bearing and rotor drivers; not bdf, whose sparsity pattern knows the
rigid and simple films only), the Kelvin–Voigt state (η > 0: τ_f W' + W = W_h(q), the
relaxation of :mod:`.foil_state` towards the hardened law's deflection; linearised,
(1 + iτ_f γ) δW = S_t δq, the tangent compliance S_t with the loss factor η at γ = ν_ref, as
the linear analysis has it) and the friction elements (:func:`hardened_friction_rows`).
:func:`transient_foil_law` hands it to :func:`gfbopt.transient.system.transient_model`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConvergenceError
from ..physics.foil_laws import HardenedLaw, foil_law
from ..physics.foil_recovery import row_mean_phi, set_boundary
from ..physics.hardening import hardened_deflection_and_slope, hardened_reaction_nd

#: Newton iterations at most (bisection alone halves the bracket: 1e-16 in ~60)
MAX_ITERATIONS = 100
#: plain Newton steps tried from a warm start before the safeguarded iteration
WARM_ITERATIONS = 6
#: converged when the Newton step is below this × (1 + |ρ|)
STEP_TOLERANCE = 1e-14
#: the film a row is given when the flat bump cannot open it (contact) [-]
FLAT_FILM = 1e-9


@dataclass(frozen=True)
class HardeningData:
    """The hardening bump of a transient model: exponent n [-] (≥ 1), limit W_lim = δ_lim/c
    [clearances] (``TransientModel.foil_data`` of the hardened law)."""

    exponent: float
    limit: float


def row_balance(phit, c, hr, s, hard: HardeningData, compression_only: bool, kb=0.0, z=0.0,
                sb=1.0, guess=None) -> tuple:
    """(ρ, W, a) on every row (B, m): the root of f(ρ) of the module docstring.

    phit, c : Φ̃ (B, m) and c of :func:`row_mean_phi`; hr : H_r (B, m); s : S per row (m,);
    kb, z, sb : the branch's κ_b [-], slider Z [-] and gauge factor s_b (scalars or (B, m));
    guess : a starting ρ (B, m), or None (the linear foundation's root).
    """
    n, lim = hard.exponent, hard.limit
    hr = np.maximum(hr, FLAT_FILM - lim)                  # no root below: contact (docstring)
    if guess is not None and np.shape(guess) == hr.shape:
        warm = _warm_newton(phit, c, hr, s, n, lim, compression_only, kb, z, sb, guess)
        if warm is not None:
            return warm
    kb = np.broadcast_to(kb, hr.shape)
    z = np.broadcast_to(z, hr.shape)
    sb = np.broadcast_to(sb, hr.shape)
    s = np.broadcast_to(s, hr.shape)
    live = s > 0.0
    safe_s = np.where(live, s, 1.0)
    # where the film closes (a = 0): tension W = −H_r, or the hardened reaction of −H_r
    closes = np.where(hr > 0.0, -np.inf if compression_only else -hr / safe_s,
                      hardened_reaction_nd(np.maximum(-hr, 0.0), safe_s, n, lim))
    lo = np.maximum(np.minimum(0.0, kb * z + sb * (c - 1.0)), closes)
    w_star = 0.5 * (np.maximum(0.0, -hr) + lim)
    rho_star = hardened_reaction_nd(w_star, safe_s, n, lim)
    q_star = phit / (hr + w_star) + c - 1.0
    hi = np.maximum(rho_star, sb * q_star - kb * (w_star - z))
    if guess is None or np.shape(guess) != hr.shape:
        s_e = sb * s / (1.0 + kb * s)                     # the linear bump's branch root
        b = hr + s_e * kb * z + s_e * (c - 1.0)
        a_lin = 0.5 * (b + np.sqrt(b * b + 4 * s_e * phit))
        guess = (a_lin - hr) / safe_s
    x = np.where((guess > lo) & (guess < hi), guess, _mid(lo, hi))
    previous = np.full(hr.shape, np.inf)
    for _ in range(MAX_ITERATIONS):
        w, dw = hardened_deflection_and_slope(x, s, n, lim, compression_only)
        a = hr + w
        f = x + kb * (w - z) - sb * (phit / a + c - 1.0)
        lo = np.where(f < 0.0, x, lo)
        hi = np.where(f > 0.0, x, hi)
        step = f / (1.0 + (kb + sb * phit / (a * a)) * dw)
        newton = x - step
        done = np.abs(step) <= STEP_TOLERANCE * (1.0 + np.abs(x))
        bisect = ~done & (~((newton > lo) & (newton < hi)) | (np.abs(f) > 0.5 * previous))
        x = np.where(bisect, _mid(lo, hi), newton) if bisect.any() else newton
        previous = np.abs(f)
        if done.all():
            w = hardened_deflection_and_slope(x, s, n, lim, compression_only)[0]
            w = np.where(live, w, 0.0)
            return x, w, hr + w
    raise ConvergenceError("hardened bump's row balance did not converge in the transient "
                           "model", "max_iter", float(np.abs(f).max()))


def _mid(lo, hi):
    """The bracket's midpoint (both ends finite: the lower is at most 0)."""
    return 0.5 * (lo + hi)


def _warm_newton(phit, c, hr, s, n, lim, compression_only, kb, z, sb, x):
    """Plain Newton from a close start (the previous evaluation's roots): (ρ, W, a) when every
    row converges within :data:`WARM_ITERATIONS` steps with a > 0 and |f| at least halving,
    else None (then the safeguarded iteration runs; the root is unique, so both give it)."""
    previous = np.inf
    for _ in range(WARM_ITERATIONS):
        w, dw = hardened_deflection_and_slope(x, s, n, lim, compression_only)
        a = hr + w
        if not (a > 0.0).all():
            return None
        f = x + kb * (w - z) - sb * (phit / a + c - 1.0)
        size = np.abs(f)
        if (size > 0.5 * previous).any():
            return None
        step = f / (1.0 + (kb + sb * phit / (a * a)) * dw)
        x = x - step
        if (np.abs(step) <= STEP_TOLERANCE * (1.0 + np.abs(x))).all():
            w = hardened_deflection_and_slope(x, s, n, lim, compression_only)[0]
            return x, w, hr + w
        previous = size
    return None


def hardened_film(phi: np.ndarray, hr: np.ndarray, tm, cache=None) -> tuple:
    """(a, ρ): the row films a = H_r + W_h(ρ) (B, m) and the bump reactions, from Φ
    (B, m, n_z + 1) and H_r (B, m), without friction; ``cache`` (a dict) keeps ρ as the next
    evaluation's Newton start."""
    phit, c = row_mean_phi(phi, hr, tm)
    guess = None if cache is None else cache.get("hardened_rho")
    rho, _, a = row_balance(phit, c, hr, tm.compliance_rows, tm.foil_data,
                            tm.compression_only, guess=guess)
    if cache is not None:
        cache["hardened_rho"] = rho
    return a, rho


def hardened_friction_rows(phi: np.ndarray, hr: np.ndarray, slider: np.ndarray, tm) -> tuple:
    """(a, q, stuck) of the hardened rows with the friction elements (as
    :func:`gfbopt.transient.friction_foil.friction_rows`): the stuck branch's root, kept where
    the element's stretch |W − Z| stays within its slip X_s = μ_f q⁺ S/κ, else the slipping
    branch in the stretch's sense (module docstring)."""
    fr = tm.friction
    phit, c = row_mean_phi(phi, hr, tm)
    s = tm.compliance_rows
    mu, kappa = fr.coefficient, fr.stiffness_ratio
    kb = np.where(s > 0.0, kappa / np.where(s > 0.0, s, 1.0), 0.0)
    hard, comp = tm.foil_data, tm.compression_only
    _, w_st, a_st = row_balance(phit, c, hr, s, hard, comp, kb=kb, z=slider)
    q_st = phit / a_st + c - 1.0
    stretch = w_st - slider
    xs = mu * np.maximum(q_st, 0.0) * s / kappa
    stuck = (np.abs(stretch) <= xs) & (xs > 0.0)
    sense = np.where(stretch > 0, 1.0, -1.0)
    loaded = (hr <= 0.0) | (phit / np.where(hr > 0.0, hr, 1.0) + c - 1.0 > 0.0)
    s_b = np.where(loaded, 1.0 - sense * mu, 1.0)
    a = np.where(stuck, a_st, row_balance(phit, c, hr, s, hard, comp, sb=s_b)[2])
    return a, phit / a + c - 1.0, stuck


def gauge_target(q: np.ndarray, tm) -> np.ndarray:
    """W_h(q) per row (B, m) of the hardened law (the Kelvin–Voigt state's target)."""
    hard = tm.foil_data
    return hardened_deflection_and_slope(q, tm.compliance_rows, hard.exponent, hard.limit,
                                         tm.compression_only)[0]


class HardenedTransientLaw(HardenedLaw):
    """The hardened law with the transient recovery of this module (module docstring)."""

    engines = ("static", "linear", "rk4", "rkc")
    loss_factor_engines = ("linear", "rk4", "rkc")
    friction_engines = ("static", "linear", "rk4", "rkc")
    damped_state = "rows"
    damped_transient_refusal = ""

    def transient_data(self, model, grid, periodic, dtheta):
        return HardeningData(float(model.hardening_exponent), float(model.hardening_limit))

    def recover(self, phi, hr, tm, guess=None, cache=None):
        a = hardened_film(phi, hr, tm, cache)[0]
        return set_boundary(phi / a[:, :, None], tm), a[:, :, None]

    def deflection_target(self, p, tm):
        q = (p @ tm.z_weight) / tm.z_weight.sum() - 1.0   # P̄ − 1 per row (B, m)
        q[:, tm.ambient] = 0.0
        return gauge_target(q, tm)

    def gauge_target(self, q, tm):
        return gauge_target(q, tm)


HARDENED_TRANSIENT = HardenedTransientLaw()


def transient_foil_law(model, engine):
    """The foil law of a transient model: the registry's (:func:`foil_law`), except the
    hardened law, which comes with its transient recovery (:class:`HardenedTransientLaw`)
    after the checks the simple foundation's law makes of friction and damping (the same
    engines carry both)."""
    if model.foil_law != "hardened":
        return foil_law(model, engine)
    foil_law(model.replace(hardening_exponent=0.0), engine)
    return HARDENED_TRANSIENT
