"""The least-stable linear mode as the starting perturbation of a transient.

A generic kick excites the whirling mode together with many decaying film modes; the growth
rate can only be read once those have decayed or been fitted away (a few revolutions).
Started on the eigenvector of the linearised semi-discrete system, the orbit is the whirling
mode alone from τ = 0, so a clean growth-rate fit needs about one revolution.

The eigenvector comes from :mod:`gfbopt.linear` (read-only use of the
:class:`~gfbopt.linear.Linearisation`): for an eigenvalue s at mass M̄ the journal part ξ is
the null vector of M̄ W̄0 s² I + Z(s), the film part ŷ = −(A + sB)⁻¹ C_ξ ξ, and because the
squeeze rows of B are −2Λ ∂(PH)/∂ẏ, the perturbation of Φ = P H at the unknown pressure nodes
is δΦ = −(B ŷ)/(2Λ) (boundary nodes carry no unknown).  The journal velocity is s ξ.
At the linear threshold s = iγ_c exactly, so no eigenvalue solve is needed: one sparse LU.

Structural damping (η > 0).  (A, B) are the damped system at s, ``lin.system(s)``: the
foundation compliance S/(1 + iη sign γ) of the hysteretic model.  The damped transient
carries the foil deflection W as a state (:mod:`.foil_state`), so the mode carries its part
too: from δΦ = H δP + P δH at the unknown nodes, δW = δH − δH_r = (δΦ − H δP)/P + cos θ δX
+ sin θ δY (δP = ŷ at the unknown nodes, which come first in y).  At the threshold
(s = iν_ref) this is the Kelvin–Voigt state's own response, S q/(1 + iτ_f ν_ref)
= S q/(1 + iη), so the transient starts on its whirling mode there too.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np
import scipy.sparse.linalg as spla

from ..static.build import solution_stencil
from ..errors import ParameterError
from .foil_state import deflection_of_mode


@dataclass(frozen=True, eq=False)
class LinearMode:
    """A complex mode of the linearised rotor–bearing system (non-dimensional).

    eigenvalue : s = σ + iγ [1/rad] (growth rate per radian of shaft rotation, whirl ratio);
    mass : M̄ it was computed at; phi : δΦ (m, n_z + 1), complex; journal : (δX, δY, δU, δV),
    complex; deflection : the foil's δW (m, n_z + 1), complex, of a damped bearing (η > 0;
    0 where P is not unknown), else None.  Calling it with a mass returns the real
    perturbation (δΦ, (δX, δY, δU, δV)) scaled so that the journal speed √(δU² + δV²) is 1;
    the same shape serves nearby masses.  :meth:`foil` gives δW with the same scale.
    """

    eigenvalue: complex
    mass: float
    phi: np.ndarray
    journal: np.ndarray
    deflection: Optional[np.ndarray] = None

    @property
    def _speed(self) -> float:
        return math.hypot(self.journal.real[2], self.journal.real[3])

    def __call__(self, mass: Optional[float] = None) -> tuple:
        return self.phi.real / self._speed, self.journal.real / self._speed

    def foil(self, layout: str) -> Optional[np.ndarray]:
        """The real δW in the layout of the transient's foil state ('rows' or 'nodes'),
        scaled like :meth:`__call__`; None when the mode carries no foil part."""
        if self.deflection is None:
            return None
        return deflection_of_mode(self.deflection.real, layout) / self._speed


def linear_mode(lin, mass: float, eigenvalue: complex) -> LinearMode:
    """The mode of ``lin`` (a :class:`gfbopt.linear.Linearisation`) with eigenvalue s at M̄.

    ``eigenvalue`` is i·γ_c at the linear threshold (``linear_threshold``), or a root from
    :func:`gfbopt.linear.least_stable_mode` at another mass.
    """
    if not (math.isfinite(mass) and mass > 0):
        raise ParameterError("mass", mass, "must be finite and > 0")
    s = complex(eigenvalue)
    if not (math.isfinite(s.real) and math.isfinite(s.imag)) or s.imag == 0:
        raise ParameterError("eigenvalue", eigenvalue, "must be a finite whirling root "
                             "(Im s ≠ 0)")
    sol = lin.static
    # the system at s (gfbopt.linear makes a damped foundation complex there; else A, B)
    a, b = lin.system(s)
    lu = spla.splu((a + s * b).astype(complex).tocsc())
    basis = -lu.solve(lin.c_xi.astype(complex))             # ŷ per unit δX and δY
    dyn = mass * lin.load * s * s * np.eye(2) + lin.force @ (-basis)   # M̄W̄0 s² I + Z(s)
    _, _, vh = np.linalg.svd(dyn)
    xi = vh[-1].conj()                                      # null vector
    y_hat = basis @ xi
    st = solution_stencil(sol)
    n_u = st.unknown.size
    dphi = np.zeros(sol.pressure.size, dtype=complex)
    dphi[st.unknown] = -(b @ y_hat)[:n_u] / (2 * sol.model.bearing_number)
    journal = np.array([xi[0], xi[1], s * xi[0], s * xi[1]])
    deflection = None
    if lin.loss_factor > 0 and lin.compliance is not None:
        deflection = _mode_deflection(sol, st.unknown, dphi, y_hat[:n_u], xi)
    return LinearMode(s, float(mass), dphi.reshape(sol.pressure.shape), journal, deflection)


def _mode_deflection(sol, unknown: np.ndarray, dphi: np.ndarray, dp: np.ndarray,
                     xi: np.ndarray) -> np.ndarray:
    """δW = (δΦ − H δP)/P − δH_r at the unknown nodes (module docstring), 0 elsewhere;
    shape (m, n_z + 1), complex."""
    m, nzn = sol.pressure.shape
    theta = np.repeat(sol.theta, nzn)[unknown]
    p, h = sol.pressure.ravel()[unknown], sol.film.ravel()[unknown]
    rigid = -(np.cos(theta) * xi[0] + np.sin(theta) * xi[1])          # δH_r
    out = np.zeros(m * nzn, dtype=complex)
    out[unknown] = (dphi[unknown] - h * dp) / p - rigid
    return out.reshape(m, nzn)
