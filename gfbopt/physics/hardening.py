"""A bump that stiffens as it flattens: the hardening foundation law, with a hard limit.

Law (chosen here; a phenomenological form, stated so that it can be checked):

    k(δ) = k0 / (1 − δ/δ_lim)^n        for 0 ≤ δ < δ_lim (compression),  k0 for δ < 0,

per unit area [N/m³]; δ the bump's compression [m] (the foil deflection away from the journal),
k0 = 1/α the small-deflection (Heshmat) stiffness, δ_lim ≤ h_b the deflection at which the
bump is flat (the bump height h_b is the hard limit: the stiffness is unbounded there), and the
exponent n > 0 how early the stiffening sets in.  The reaction (pressure over ambient that the
bump carries) is the integral of k:

    Δp(δ) = k0 δ_lim/(n − 1) [(1 − δ/δ_lim)^(1−n) − 1]     (n ≠ 1)
    Δp(δ) = −k0 δ_lim ln(1 − δ/δ_lim)                      (n = 1)

and its inverse is closed too (so a foil law can keep its explicit W(q)):

    δ(Δp) = δ_lim [1 − (1 + (n − 1) Δp/(k0 δ_lim))^(−1/(n−1))]      (n ≠ 1)
    δ(Δp) = δ_lim [1 − exp(−Δp/(k0 δ_lim))]                          (n = 1)

Both reduce to δ = Δp/k0 as δ_lim → ∞, and δ < δ_lim for every finite load when n ≥ 1 (for
0 < n < 1 the bump flattens at the finite load k0 δ_lim/(1 − n), beyond which the law refuses).
In tension (δ < 0, a bump pulled off its seat) the law stays linear: the force and its slope are
continuous at δ = 0.  Non-dimensional form (W = δ/c, q = Δp/p_a, S = p_a/(c k0), W_lim = δ_lim/c):
replace k0 δ_lim by W_lim/S and Δp/k0 by S q.

Why: the bump foil's measured load–deflection curves stiffen as the bumps are compressed
(geometric nonlinearity and contact with the top foil), e.g. J. S. Larsen, A. C. Varela,
I. F. Santos, "Numerical and experimental investigation of bump foil mechanical behaviour",
Tribol. Int. 74 (2014) 46–56; T. H. Kim, L. San Andrés, "Heavily loaded gas foil bearings: a
model anchored to test data", ASME J. Eng. Gas Turbines Power 130 (2008) 012504, whose
structure stiffens with the deflection.  The form k0/(1 − δ/δ_lim)^n is a choice made here
(not fitted to those data): the simplest law with a rising stiffness and a hard limit at the
bump height and closed forms both ways.
"""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from ..errors import ParameterError
from .algebra import is_symbolic, positive_part
from ..inputs.checks import check_positive

__all__ = ["HardeningLaw", "check_hardening_limit", "describe", "hardened_deflection",
           "hardened_foil_deflection", "hardened_reaction", "hardened_stiffness",
           "hardened_deflection_and_slope", "hardened_reaction_nd",
           "hardened_tangent_compliance"]


@dataclass(frozen=True)
class HardeningLaw:
    """k(δ) = k0/(1 − δ/δ_lim)^n (module docstring).

    stiffness k0 [N/m³] (> 0); limit δ_lim [m] (> 0, ≤ the bump height, checked by the
    input that knows it); exponent n [-] (> 0).
    """

    stiffness: float
    limit: float
    exponent: float

    def __post_init__(self):
        for key in ("stiffness", "limit", "exponent"):
            object.__setattr__(self, key, check_positive(key, getattr(self, key)))

    def tangent(self, deflection):
        """k(δ) [N/m³] (arrays); ParameterError at or beyond the limit."""
        return hardened_stiffness(deflection, self.stiffness, self.limit, self.exponent)

    def reaction(self, deflection):
        """Δp(δ) = ∫₀^δ k [Pa] (arrays)."""
        return hardened_reaction(deflection, self.stiffness, self.limit, self.exponent)

    def deflection(self, reaction):
        """δ(Δp), the inverse of :meth:`reaction` [m] (arrays)."""
        return hardened_deflection(reaction, self.stiffness, self.limit, self.exponent)


def _below_limit(d, limit):
    if np.any(d >= limit):
        raise ParameterError("deflection", float(np.max(d)), f"must be < the hardening limit "
                             f"{limit:g} (the bump is flat there: the hard limit)")


def hardened_stiffness(deflection, stiffness, limit, exponent):
    """k(δ) = k0/(1 − δ/δ_lim)^n for δ ≥ 0, k0 for δ < 0 (per unit area, or non-dim)."""
    d = np.asarray(deflection, dtype=float)
    _below_limit(d, limit)
    return stiffness / (1.0 - np.maximum(d, 0.0) / limit) ** exponent


def hardened_reaction(deflection, stiffness, limit, exponent):
    """Δp(δ) in closed form (module docstring); linear k0 δ for δ < 0."""
    d = np.asarray(deflection, dtype=float)
    _below_limit(d, limit)
    u = 1.0 - np.maximum(d, 0.0) / limit
    n = float(exponent)
    if n == 1.0:
        hard = -stiffness * limit * np.log(u)
    else:
        hard = stiffness * limit / (n - 1.0) * (u ** (1.0 - n) - 1.0)
    return np.where(d >= 0.0, hard, stiffness * d)


def hardened_deflection(reaction, stiffness, limit, exponent):
    """δ(Δp), the closed-form inverse of :func:`hardened_reaction`; Δp/k0 for Δp < 0."""
    p = np.asarray(reaction, dtype=float)
    n = float(exponent)
    pp = np.maximum(p, 0.0)
    scale = stiffness * limit
    if n == 1.0:
        hard = limit * (1.0 - np.exp(-pp / scale))
    else:
        base = 1.0 + (n - 1.0) * pp / scale
        if np.any(base <= 0.0):           # 0 < n < 1: flat at the load k0 δ_lim/(1 − n)
            raise ParameterError("reaction", float(np.max(p)), "flattens the bump: the "
                                 f"hardening law with n = {n:g} < 1 reaches its limit at "
                                 f"{scale / (1.0 - n):g}")
        hard = limit * (1.0 - base ** (-1.0 / (n - 1.0)))
    return np.where(p >= 0.0, hard, p / stiffness)


def check_hardening_limit(limit: float, bump_height: float, where: str = "hardening_limit"):
    """δ_lim checked against the bump height h_b [m]: 0 < δ_lim ≤ h_b (the hard limit)."""
    lim = check_positive(where, limit)
    h = check_positive("bump_height", bump_height)
    if lim > h * (1.0 + 1e-12):
        raise ParameterError(where, limit, f"must be <= the bump height {h:g} m (a bump "
                             "cannot deflect further than it is high: the height is the hard "
                             "limit)")
    return lim


def describe(law: HardeningLaw) -> str:
    """One line naming the law and its parameters (SI)."""
    return (f"hardening bump k = k0/(1 − δ/δ_lim)^n, k0 = {law.stiffness:.4g} N/m³, "
            f"δ_lim = {law.limit * 1e6:.4g} µm, n = {law.exponent:.4g}")



# ------------------------------------------------------- the foil law's form (non-dimensional)
#: |n − 1| below which the n → 1 series of log(1 + (n − 1) x)/(n − 1) is used
_SERIES_BELOW = 1e-6


def _exponent_term(x, e):
    """g = log(1 + e x)/e (→ x as e → 0), e = n − 1 ≥ 0, on numbers or CasADi symbols."""
    series = x - 0.5 * e * x * x + e * e * x * x * x / 3.0
    if is_symbolic(x, e):
        return ca.if_else(ca.fabs(e) < _SERIES_BELOW, series, ca.log1p(e * x) / e)
    if abs(float(e)) < _SERIES_BELOW:
        return series
    return np.log1p(e * x) / e


def hardened_foil_deflection(q, compliance, exponent, limit, compression_only):
    """W(q) of the hardening foundation in clearances (numbers or CasADi symbols).

    W = W_lim [1 − (1 + (n − 1) S q⁺/W_lim)^(−1/(n − 1))] (n = 1: W_lim [1 − exp(−S q⁺/W_lim)])
    in compression, plus the linear S min(q, 0) in tension unless ``compression_only``; S the
    small-deflection compliance, n ≥ 1 the exponent, W_lim = δ_lim/c the limit.  The closed
    inverse of the module docstring's reaction, so the foil law keeps an explicit W(q).
    """
    qp = positive_part(q)
    x = compliance * qp / limit
    w = -limit * _expm1(-_exponent_term(x, exponent - 1.0))     # W_lim (1 − e^(−g)), exact
    return w + (1 - compression_only) * compliance * (q - qp)


def hardened_tangent_compliance(q, compliance, exponent, limit, compression_only):
    """dW/dq of :func:`hardened_foil_deflection` (numpy): S (1 + (n − 1) x)^(−n/(n − 1)),
    x = S q⁺/W_lim, in compression; S in tension (0 when ``compression_only``)."""
    q = np.asarray(q, dtype=float)
    x = compliance * np.maximum(q, 0.0) / limit
    e = exponent - 1.0
    g = _exponent_term(x, e)
    slope = compliance * np.exp(-g) / (1.0 + e * x)
    tension = 0.0 if compression_only else compliance
    return np.where(q > 0, slope, tension * np.ones_like(q))


def _expm1(x):
    return ca.expm1(x) if is_symbolic(x) else np.expm1(x)


def hardened_reaction_nd(w, compliance, exponent, limit):
    """q_b(W), the bump's reaction in ambient pressures at the deflection W [clearances]
    (numpy): (W_lim/S)/(n − 1) [(1 − W/W_lim)^(1−n) − 1] (n = 1: −(W_lim/S) ln(1 − W/W_lim))
    for 0 ≤ W < W_lim, W/S in tension; the inverse of :func:`hardened_foil_deflection`."""
    w = np.asarray(w, dtype=float)
    u = 1.0 - np.maximum(w, 0.0) / limit
    e = exponent - 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        hard = (-np.log(u) if abs(e) < _SERIES_BELOW else np.expm1(-e * np.log(u)) / e)
        return np.where(w >= 0.0, limit * hard, w) / compliance


def hardened_deflection_and_slope(q, compliance, exponent, limit, compression_only):
    """(W_h(q), dW_h/dq) of :func:`hardened_foil_deflection` together (numpy, one exp and one
    log for both): W_lim (1 − e^(−g)) and S e^(−g)/(1 + (n − 1) x) with x = S q⁺/W_lim,
    g = log(1 + (n − 1) x)/(n − 1); S q and S in tension (0 and 0 when ``compression_only``)."""
    x = compliance * np.maximum(q, 0.0) / limit
    e = exponent - 1.0
    g = (x - 0.5 * e * x * x + e * e * x * x * x / 3.0 if abs(e) < _SERIES_BELOW
         else np.log1p(e * x) / e)                        # _exponent_term's, numpy only
    decay = np.exp(-g)
    w = -limit * np.expm1(-g)
    slope = compliance * decay / (1.0 + e * x)
    if compression_only:
        return w, np.where(q > 0, slope, 0.0)
    tension = q < 0
    return np.where(tension, compliance * q, w), np.where(tension, compliance, slope)
