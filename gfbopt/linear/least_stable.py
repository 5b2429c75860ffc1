"""The least-stable mode of the rigid rotor on the linearised bearing: the least-damped root
over all its rigid-body roots (whirl ratios in :data:`MODE_BAND`).

Method (default ``"krylov"``).  One sparse LU of M0 = A + s0 B at the shift of
:class:`~gfbopt.linear.krylov.ShiftedImpedance` over the whole band builds one block Krylov
space; its Galerkin (FOM) model of the film, (I + (s − s0) H_m) y = E_1 R ξ, Z̄ ≈ (F V_m) y,
closed with the rotor, M̄W̄0 s² ξ + Z̄ ξ = 0, is the small descriptor system

    s [H 0 0; 0 I 0; 0 0 m I] (y, ξ, u) = [−(I − s0 H)  E_1R  0;  0 0 I;  −F V  0  0] (y, ξ, u),

of order 2k + 4 (k block steps): all its eigenvalues by dense QZ, a few milliseconds.  The
space grows until the answer can be trusted: (i) the least-damped root in the band has
not moved (relative change ≤ :data:`ROOT_TOLERANCE`) over the last block step and the film
solve at that root is converged (FOM residual ≤ :data:`RESIDUAL_TOLERANCE`: the exact
preconditioned residual ‖M0⁻¹(C_ξ − (A + sB) V y)‖/‖X0‖ at s); (ii) the impedance is
converged on the whole region where a less damped root could still hide: the rectangle of
whirl ratios :data:`MODE_BAND` and growth rates from +:data:`GROWTH_MARGIN` down to −x, where
x = 3 ζ*/√(1 − ζ*²) (a root with Re s < −x and |Im s| ≤ 3 has ζ > ζ*, the damping ratio
found), checked on its boundary (Z̄ is analytic inside, away from the film's own poles,
whose coupled roots the QZ sees).  A space that stops growing (its ``max_blocks`` or a
breakdown) hands over to the reference search.  The reference (``method="eigs"``) is
:func:`whirling_modes`: three shift-invert Arnoldi searches of the full semi-discrete system,
one LU of the bordered matrix each.

With structural damping (η > 0) the foundation is k(1 + iη sign Im s); the system matrices
are otherwise real, so the roots with Im s < 0 (foundation k(1 − iη)) are the conjugates of
those with Im s > 0 (foundation k(1 + iη)): the upper half plane, which the Krylov space is
built for, holds every mode once.

Checked against a dense eigenvalue computation of the whole semi-discrete system (QZ of
the full pencil) in tests/verification/test_least_stable_mode.py, and against the reference
search there; speed in benchmarks/bench_stability.py (results/benchmarks/stability_speed.json).
"""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

import scipy.linalg as sla

from ..errors import ConvergenceError, ParameterError
from ..threads import single_threaded
from .krylov import ShiftedImpedance
from .model import Linearisation
from .threshold import LinearThreshold, semi_discrete_eigenvalues


#: whirl ratios searched for the least-stable mode: every rigid-body root lies in (0, 3]
#: (the half-frequency whirl near 0.5, the rotor's translatory roots up to ~3 at low speed)
MODE_BAND = (0.02, 3.0)
#: shifts (whirl ratios) of the shift-invert eigenvalue searches covering :data:`MODE_BAND`
MODE_SHIFTS = (0.5, 1.5, 2.5)
#: ways to find the least-stable mode (module docstring)
MODE_METHODS = ("krylov", "eigs")
#: largest relative change of the least-damped root over the last block step
ROOT_TOLERANCE = 1e-10
#: largest relative FOM residual of the film solve at the root and on the search region
RESIDUAL_TOLERANCE = 1e-10
#: growth rate per radian above the axis up to which the region is checked [-]
GROWTH_MARGIN = 0.1
#: points per side of the region's boundary on which the impedance is checked
BOUNDARY_POINTS = 24
#: block steps before the first QZ (the space is too small to hold the band before)
FIRST_BLOCKS = 4


@single_threaded
def whirling_modes(lin: Linearisation, mass: float, count: int = 8,
                   shifts: tuple = MODE_SHIFTS) -> np.ndarray:
    """The eigenvalues s of the rotor–bearing system at mass M̄ [-] with whirl ratio |Im s|
    in :data:`MODE_BAND`: shift-invert eigenvalues of the semi-discrete system nearest
    i·γ for every γ of ``shifts`` (``count`` each; and −i·γ with structural damping, whose
    foundation depends on the whirl direction), duplicates removed.  Re s is the growth rate
    per radian of shaft rotation, Im s the whirl ratio.  Checked against a dense eigenvalue computation of the
    whole semi-discrete system in tests/verification/test_least_stable_mode.py."""
    signs = (1, -1) if lin.hysteretic else (1,)
    found: list = []
    for sign in signs:
        for gamma in shifts:
            ev = semi_discrete_eigenvalues(lin, mass, sign * 1j * gamma, count=count)
            ev = ev[np.sign(ev.imag) == sign]      # η = 0: the conjugates are the same modes
            for v in ev[(np.abs(ev.imag) > MODE_BAND[0]) & (np.abs(ev.imag) <= MODE_BAND[1])]:
                if all(abs(v - w) > 1e-8 * max(1.0, abs(v)) for w in found):
                    found.append(complex(v))
    return np.array(found, dtype=complex)


def damping_ratio(s: complex) -> float:
    """ζ = −Re s/|s| of a root s [-]: < 0 growing; the log decrement is 2π ζ/√(1 − ζ²)."""
    return -s.real / abs(s)


def _reduced_roots(model: ShiftedImpedance, mass_load: float) -> np.ndarray:
    """The eigenvalues s of the reduced descriptor system on the whole space (module
    docstring); infinite ones dropped."""
    m = 2 * model.blocks
    h = model.hessenberg[:m, :m]
    r, fv = model.start_factor, model.force_basis[:, :m]
    s0 = model.shift
    er = np.zeros((m, 2), dtype=complex)
    er[:2] = r
    jac = np.zeros((m + 4, m + 4), dtype=complex)
    jac[:m, :m] = -(np.eye(m) - s0 * h)
    jac[:m, m:m + 2] = er
    jac[m:m + 2, m + 2:] = np.eye(2)
    jac[m + 2:, :m] = -fv
    e = np.zeros_like(jac)
    e[:m, :m] = h
    e[m:m + 2, m:m + 2] = np.eye(2)
    e[m + 2:, m + 2:] = mass_load * np.eye(2)
    w = sla.eig(jac, e, right=False, overwrite_a=True, overwrite_b=True)
    return w[np.isfinite(w) & (np.abs(w) < 1e6)]


def _residual(model: ShiftedImpedance, s: complex) -> float:
    """Relative FOM residual of the film solve at s (exact preconditioned residual, module
    docstring of :mod:`gfbopt.rotor.reduced`)."""
    m = 2 * model.blocks
    h = model.hessenberg
    rhs = np.zeros((m, 2), dtype=complex)
    rhs[:2] = model.start_factor
    sigma = complex(s) - model.shift
    try:
        y = np.linalg.solve(np.eye(m) + sigma * h[:m, :m], rhs)
    except np.linalg.LinAlgError:
        return math.inf
    return float(abs(sigma) * np.linalg.norm(h[m:m + 2, :m] @ y)
                 / np.linalg.norm(model.start_factor))


def _in_band(w: np.ndarray) -> np.ndarray:
    return (w.imag > MODE_BAND[0]) & (w.imag <= MODE_BAND[1])


def _region_converged(model: ShiftedImpedance, zeta: float) -> bool:
    """Z̄ converged on the boundary of the region where a root less damped than ζ* could
    lie (module docstring), checked from the farthest point from the shift inwards."""
    z = min(max(zeta, 0.0), 0.999)
    depth = 3.0 * z / math.sqrt(1.0 - z * z) * 1.05 + 1e-3
    low, high = MODE_BAND
    gammas = np.linspace(low, high, BOUNDARY_POINTS)
    growth = np.linspace(-depth, GROWTH_MARGIN, BOUNDARY_POINTS)
    points = np.concatenate([-depth + 1j * gammas, GROWTH_MARGIN + 1j * gammas,
                             growth + 1j * low, growth + 1j * high])
    order = np.argsort(-np.abs(points - model.shift))
    return all(_residual(model, points[j]) <= RESIDUAL_TOLERANCE for j in order)


def _krylov_mode(lin: Linearisation, mass: float) -> Optional[complex]:
    """The least-damped root in the band from the Krylov model (module docstring); None
    when the space stops growing before the tests pass."""
    mass_load = mass * lin.load
    model = ShiftedImpedance(lin, MODE_BAND)
    previous = None
    while True:
        if not model.extend():
            return None
        if model.blocks < FIRST_BLOCKS:
            continue
        w = _reduced_roots(model, mass_load)
        w = w[_in_band(w)]
        if w.size == 0:
            previous = None
            continue
        best = complex(min(w, key=damping_ratio))
        settled = (previous is not None
                   and abs(best - previous) <= ROOT_TOLERANCE * max(1.0, abs(best)))
        previous = best
        if (settled and _residual(model, best) <= RESIDUAL_TOLERANCE
                and _region_converged(model, damping_ratio(best))):
            return best


@single_threaded
def least_stable_mode(lin: Linearisation, mass: float,
                      threshold: Optional[LinearThreshold] = None,
                      method: str = "krylov") -> complex:
    """The least-damped whirling root s of the rotor–bearing system at mass M̄ [-], over all
    its rigid-body roots (whirl ratios in :data:`MODE_BAND`, :func:`whirling_modes`).

    Least damped = the smallest damping ratio ζ = −Re s/|s|, i.e. the smallest logarithmic
    decrement δ = −2π Re s/Im s per whirl cycle; a growing root (Re s > 0) always wins over
    the decaying ones, so the verdict and this mode agree.  Re s is the growth rate per radian
    of shaft rotation (> 0: unstable), Im s (returned ≥ 0) the whirl ratio; it is a root of
    the characteristic equation det(M̄W̄0 s² I + Z(s)) = 0 to Arnoldi's tolerance (the secant
    polish of :func:`characteristic_root` changes it by ~1e-14, so it is not applied).
    (Before 0.3 only the
    roots near the threshold whirl were searched, which missed a less damped root at 2.5x
    shaft speed at low speeds.)  ``threshold`` is not needed and kept for compatibility.

    method : "krylov" (default: one LU and one Krylov space, the roots of its reduced model by
        dense QZ, module docstring) or "eigs" (the reference: :func:`whirling_modes`, three
        shift-invert searches of the full system); they agree to ~1e-10.
    """
    if method not in MODE_METHODS:
        raise ParameterError("method", method, f"must be one of: {', '.join(MODE_METHODS)}")
    if method == "krylov":
        if not (math.isfinite(mass) and mass > 0):
            raise ParameterError("mass", mass, "must be finite and > 0")
        best = _krylov_mode(lin, float(mass))
        if best is not None:
            return complex(best.real, abs(best.imag))
    modes = whirling_modes(lin, mass)
    if modes.size == 0:
        raise ConvergenceError("no whirling mode in whirl ratios "
                               f"{MODE_BAND[0]}–{MODE_BAND[1]}", "eigs", math.nan)
    best = min(modes, key=damping_ratio)
    return complex(best.real, abs(best.imag))
