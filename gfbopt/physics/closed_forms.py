"""Closed forms the numerical models are checked against (small eccentricity, ε → 0).

Ausman's first-order perturbation of the compressible Reynolds equation: J. S. Ausman, "An
improved analytical solution for self-acting, gas-lubricated journal bearings of finite
length", J. Basic Eng. 83(2) (1961) 188–194.  Used as the cold start of the static
solve, as an exact check in the tests, and for the concentric impedance of the linear model.
``docs/PHYSICS.md``, section "Exact checks".
"""
from __future__ import annotations

import math

import numpy as np

from ..inputs.model import BearingModel


def small_eccentricity_coefficient(bearing_number: float, length_ratio: float,
                                   compliance: float = 0.0, law: str = "mean") -> complex:
    """Axial mean f̄ of Ausman's first-order pressure P = 1 + ε Re{f(Z) e^{iψ}} [-].

    ψ from the maximum-film line.  Rigid: f'' − k² f = iΛ, k² = 1 + iΛ, f(±L/D) = 0, so
    f̄ = −iΛ/(1 + iΛ)·[1 − tanh(k L/D)/(k L/D)].  Local law W = S(P − 1): k² = 1 + iΛ(1 + S)
    and the factor −iΛ/(1 + iΛ(1 + S)); axial-mean law: f̄_S = g/(1 − S g), g the rigid f̄.
    (docs/PHYSICS.md; Ausman, J. Basic Eng. 1961.)  As ε → 0, W/(p_a L D)/ε = (π/2)|f̄| and
    tan φ = Im f̄/Re f̄.
    """
    lam, ld, s = bearing_number, length_ratio, compliance
    if law == "local":
        k = np.sqrt(1 + 1j * lam * (1 + s))
        return complex(-1j * lam / (1 + 1j * lam * (1 + s)) * (1 - np.tanh(k * ld) / (k * ld)))
    k = np.sqrt(1 + 1j * lam)
    g = -1j * lam / (1 + 1j * lam) * (1 - np.tanh(k * ld) / (k * ld))
    return complex(g / (1 - s * g))


def small_eccentricity_limit(model: BearingModel) -> tuple[float, float]:
    """(load per unit ε, attitude angle [rad]) of the rigid/simple bearing as ε → 0.

    Load is W/(p_a R²) per unit ε = 4 (L/D)·(π/2)|f̄|; exact for the periodic film.
    """
    s = 0.0 if model.is_rigid else model.compliance
    fbar = small_eccentricity_coefficient(model.bearing_number, model.length_ratio, s,
                                          model.deflection_law)
    # tan φ = Im f̄/Re f̄ with φ in (0, π): both parts of f̄ are negative for a rigid bearing
    return (4 * model.length_ratio * 0.5 * math.pi * abs(fbar),
            math.atan2(fbar.imag, fbar.real) % math.pi)


def first_order_pressure(model: BearingModel, z: np.ndarray, psi: np.ndarray,
                         eccentricity: float) -> np.ndarray:
    """Ausman's first-order pressure 1 + ε Re{f(Z) e^{iψ}} of the rigid bearing [-].

    f(Z) = (iΛ/k²)(cosh kZ / cosh k(L/D) − 1), k² = 1 + iΛ; ψ from the maximum-film line
    [rad], Z ∈ [−L/D, L/D].  Returns an array of shape (psi.size, z.size).  Used as the cold
    start of the nonlinear solve (and as an exact small-ε check in the tests).
    """
    lam, ld = model.bearing_number, model.length_ratio
    k = np.sqrt(1 + 1j * lam)
    f = 1j * lam / k**2 * (np.cosh(k * z) / np.cosh(k * ld) - 1)
    return 1 + eccentricity * np.real(np.outer(np.exp(1j * psi), f))


def concentric_impedance(bearing_number: float, length_ratio: float,
                         whirl_ratio: float) -> np.ndarray:
    """Impedance Z(iγ) of a rigid, concentric (ε → 0) bearing from Ausman's first-order
    theory (Ausman, J. Basic Eng. 83 (1961) 188; docs/PHYSICS.md) [-], load-frame convention.

    A forward circular whirl at γ sees the steady film of Λ(1 − 2γ), a backward one that of
    Λ(1 + 2γ); with the static small-ε response u(Λ) = −2π (L/D) conj f̄(Λ) = k e^{−iφ} (f̄ the
    axial mean of Ausman's first-order pressure, k the load per unit ε, φ the attitude) the
    isotropic impedance [[a, b], [−b, a]] has a − i b = u(Λ(1 − 2γ)) (forward whirl) and
    a + i b = conj u(Λ(1 + 2γ)) (backward whirl).
    """
    def u(lam):
        if lam == 0.0:
            return 0.0j
        return -2 * math.pi * length_ratio * np.conj(
            small_eccentricity_coefficient(lam, length_ratio))

    uf = u(bearing_number * (1 - 2 * whirl_ratio))
    ub = u(bearing_number * (1 + 2 * whirl_ratio))
    a, b = (uf + np.conj(ub)) / 2, (np.conj(ub) - uf) / 2j
    return np.array([[a, b], [-b, a]])
