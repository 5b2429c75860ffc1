"""The pressure a bore profile raises with the journal concentric, to first order.

For a film H = 1 + δ(θ) with a small clearance change δ = Σ_k a_k e^{ikθ} (a rigid bore,
steady, isothermal), the linearised Reynolds equation ∂²p/∂θ² + ∂²p/∂Z² = Λ ∂(p + δ)/∂θ
with p = 0 at Z = ±L/D gives, harmonic by harmonic (the same algebra as Ausman's first-order
solution for the eccentricity, which is the harmonic k = 1; docs/PHYSICS.md §9),

    p_k(Z) = −iΛk a_k / (k² + iΛk) · [1 − cosh(κ_k Z) / cosh(κ_k L/D)],   κ_k² = k² + iΛk.

The static solver uses it (added to Ausman's eccentricity term) as the cold start of a
preloaded bearing (:mod:`gfbopt.static.solve`): it is a starting point, not a result.
"""
from __future__ import annotations

import numpy as np


def first_order_bore_pressure(bore_rows: np.ndarray, z: np.ndarray, bearing_number: float,
                              length_ratio: float, periodic: bool) -> np.ndarray:
    """P − 1 (θ rows × axial nodes) raised by the clearance change ``bore_rows`` (B per θ
    row on a uniform grid round the bearing; a seamed grid repeats its first row last) [-]."""
    b = np.asarray(bore_rows, float)
    rows = b if periodic else b[:-1]
    n = rows.size
    coeff = np.fft.rfft(rows) / n
    k = np.arange(coeff.size)
    lam = bearing_number
    kappa = np.sqrt(k * k + 1j * lam * k + 0j)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        amplitude = np.where(k > 0, -1j * lam * k / (k * k + 1j * lam * k + (k == 0)), 0.0)
        shape = 1.0 - np.cosh(np.outer(kappa, z)) / np.cosh(kappa * length_ratio)[:, None]
    shape = np.nan_to_num(shape)                # very high harmonics: the bore's own edges
    spectrum = (amplitude * coeff)[:, None] * shape
    spectrum[1:-1 if n % 2 == 0 else None] *= 2.0   # one-sided spectrum of a real signal
    theta = 2 * np.pi * np.arange(n) / n
    p = np.real(np.exp(1j * np.outer(theta, k)) @ spectrum)
    return p if periodic else np.vstack([p, p[:1]])


def step_film(film: np.ndarray, deflection: np.ndarray, bore_rows: np.ndarray) -> float:
    """The smallest film [-] at the steps of a sharp-edged bore (shims), bounded from below
    with the pressure continuous across each step.

    At a shim's edge the clearance jumps by the preload while the pressure (hence the
    deflection W of a local foil law) is continuous.  On the grid the edge row carries the
    shim's clearance with a pressure between the two sides', and which value it takes
    depends on the row spacing: when the journal's rigid film on the shim side
    H_r = 1 + B − X cos θ − Y sin θ is small or negative there, the nodal film at the edge
    runs to zero as the grid is refined (measured on a shimmed Ruscitto bearing under twice
    its load: 2.79, 1.53, 0.09 µm at 36×10, 72×20, 144×36).  This returns, over every step
    between rows k and k + 1, the shim side's rigid film plus the smaller deflection of the
    two rows, min(W_k, W_k+1) — a bound the edge's continuous pressure cannot fall below
    while it lies between its neighbours', nearly the same on every grid — or inf without a
    step.  ``film``, ``deflection``: H and W (θ rows × axial nodes); ``bore_rows``: B per θ
    row (a step is a jump of more than 1e-12)."""
    b = np.asarray(bore_rows, float)
    steps = np.flatnonzero(np.abs(np.diff(b)) > 1e-12)
    best = np.inf
    for k in steps:
        low = k if b[k] < b[k + 1] else k + 1
        rigid = film[low] - deflection[low]
        best = min(best, float((rigid + np.minimum(deflection[k], deflection[k + 1])).min()))
    return best
