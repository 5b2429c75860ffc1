"""The least-stable mode of the rigid rotor on the linearised bearing: the least-damped root
over all its rigid-body roots (whirl ratios in :data:`MODE_BAND`).

Checked against a dense eigenvalue computation of the whole semi-discrete system in
tests/verification/test_least_stable_mode.py.
"""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

from ..errors import ConvergenceError
from .model import Linearisation
from .threshold import LinearThreshold, semi_discrete_eigenvalues


#: whirl ratios searched for the least-stable mode: every rigid-body root lies in (0, 3]
#: (the half-frequency whirl near 0.5, the rotor's translatory roots up to ~3 at low speed)
MODE_BAND = (0.02, 3.0)
#: shifts (whirl ratios) of the shift-invert eigenvalue searches covering :data:`MODE_BAND`
MODE_SHIFTS = (0.5, 1.5, 2.5)


def whirling_modes(lin: Linearisation, mass: float, count: int = 8,
                   shifts: tuple = MODE_SHIFTS) -> np.ndarray:
    """The eigenvalues s of the rotor–bearing system at mass M̄ [-] with whirl ratio |Im s|
    in :data:`MODE_BAND`: shift-invert eigenvalues of the semi-discrete system nearest
    i·γ for every γ of ``shifts`` (``count`` each; and −i·γ with structural damping, whose
    foundation depends on the whirl direction), duplicates removed.  Re s is the growth rate per radian of shaft
    rotation, Im s the whirl ratio.  Checked against a dense eigenvalue computation of the
    whole semi-discrete system in tests/verification/test_least_stable_mode.py."""
    signs = (1, -1) if lin.loss_factor > 0 and lin.compliance is not None else (1,)
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


def least_stable_mode(lin: Linearisation, mass: float,
                      threshold: Optional[LinearThreshold] = None) -> complex:
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
    """
    modes = whirling_modes(lin, mass)
    if modes.size == 0:
        raise ConvergenceError("no whirling mode in whirl ratios "
                               f"{MODE_BAND[0]}–{MODE_BAND[1]}", "eigs", math.nan)
    best = min(modes, key=damping_ratio)
    return complex(best.real, abs(best.imag))
