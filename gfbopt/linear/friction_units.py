"""The bumps' spring–slider (Jenkins) elements in the linearised bearing (non-dimensional).

One element beside the bump of each foil unit u (a θ row of the axial-mean law, an unknown node
of the local law; :class:`~gfbopt.physics.compliance.ComplianceTerms`).  In clearances and
ambient pressures, per unit area: the bump's stiffness is 1/S_u, the element's spring κ/S_u
(κ = k_f/k_b, ``BearingModel.friction_stiffness_ratio``) and its slip force μ_f q_u⁺ (the
local gauge pressure q_u = P̄ − 1 or P − 1 is the normal load; no load, no friction), so its
slip displacement is

    X_s,u = μ_f q_u⁺ S_u / κ        [clearances].

At a deflection amplitude |δW_u| the foundation stiffness over the bump's is

    k_u = 1 + iη sign γ + κ D(β_u),   β_u = X_s,u/|δW_u|,

with D the element's describing function over its spring (:func:`gfbopt.physics.friction.
describing_function` with k = 1): D = 1 when stuck (β ≥ 1; also for vanishing amplitude on a
loaded unit), (1/π)(ψ − ½ sin 2ψ) + i sign γ (4/π) β (1 − β) when slipping, 0 on unloaded
units.  With μ_f = 0 every X_s is 0, D = 0 and k_u = 1 + iη sign γ: today's foundation.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..physics.compliance import ComplianceTerms
from ..physics.friction import describing_function


@dataclass(frozen=True, eq=False)
class FrictionUnits:
    """The friction elements of the foil units of one linearisation [-].

    coefficient μ_f (one, or one per unit with friction zones); stiffness_ratio κ (the
    element's spring over the bump's stiffness in the linearisation: κ, or κ S_t,u/S_u per
    unit over a hardening bump's tangent); slip X_s,u per unit [clearances].
    """

    coefficient: object
    stiffness_ratio: object
    slip: np.ndarray

    @classmethod
    def of(cls, terms: ComplianceTerms, coefficient: float,
           stiffness_ratio: object) -> "FrictionUnits":
        """The elements of the units of ``terms`` (a law with foil units)."""
        if terms.unit_columns is None:
            raise ValueError("the foil law has no foil units to carry friction")
        gauge = np.maximum(np.asarray(terms.unit_gauge, dtype=float), 0.0)
        carried = np.asarray(terms.unit_gain) != 0          # compression-only bumps let go
        slip = np.where(carried, coefficient * gauge * terms.unit_compliance
                        / stiffness_ratio, 0.0)
        # the element's spring is κ times the bump's small-deflection stiffness; over a
        # hardening bump's tangent stiffness it is κ S_t/S0
        ratio = (float(stiffness_ratio) if terms.unit_softening is None
                 else stiffness_ratio * np.asarray(terms.unit_softening, dtype=float))
        mu = float(coefficient) if np.ndim(coefficient) == 0 else np.asarray(coefficient, float)
        return cls(mu, ratio, slip)

    def describing(self, amplitude: Optional[np.ndarray], sign: float = 1.0) -> np.ndarray:
        """D(β_u) per unit: the element's complex stiffness over its spring (module doc)."""
        if amplitude is None:
            return (self.slip > 0).astype(complex)          # small orbits: stuck where loaded
        amp = np.abs(np.asarray(amplitude, dtype=float))
        d = describing_function(1.0, self.slip, amp, sign if sign else 1.0)
        if not sign:                                         # s on the real axis: in phase
            d = d.real.astype(complex)
        return np.where(self.slip > 0, d, 0.0)

    def factor(self, amplitude: Optional[np.ndarray], sign: float) -> np.ndarray:
        """κ D(β_u): what the elements add to the foundation stiffness over the bump's."""
        return self.stiffness_ratio * self.describing(amplitude, sign)

    def stuck_fraction(self, amplitude: Optional[np.ndarray]) -> float:
        """Share of the loaded units whose slider stays stuck at these amplitudes [-]."""
        loaded = self.slip > 0
        if not loaded.any():
            return 0.0
        if amplitude is None:
            return 1.0
        amp = np.abs(np.asarray(amplitude, dtype=float))
        return float(np.mean(amp[loaded] <= self.slip[loaded]))


def friction_rows(model, st, origin) -> np.ndarray:
    """μ_f per θ row of the stencil ``st`` with its origin at ``origin`` [rad]: each bump
    zone's own coefficient where the bearing states one (``Zone.friction_coefficient``, None:
    the model's), else the model's ``friction_coefficient`` [-]."""
    m = st.n_theta_nodes
    ab = getattr(model, "as_built", None)
    rows = getattr(ab, "friction_rows", None)
    if rows is None or not ab.housing_fixed:
        return np.full(m, float(model.friction_coefficient))
    theta = (0.0 if origin is None else origin) + st.psi
    return np.asarray(rows(theta, model.friction_coefficient), dtype=float)
