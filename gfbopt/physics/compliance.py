"""The foil's dynamic compliance in the linearisation: which entries of the linearised
equations the bump foundation carries (``docs/PHYSICS.md`` §7, "Structural damping").

Each foil law (:mod:`gfbopt.physics.foil_laws`) returns its :class:`ComplianceTerms` from a
:class:`PerturbationContext`; the linear analysis (:mod:`gfbopt.linear`) then makes the
foundation stiffness complex, k → k (1 + iη sign γ), in exactly those entries.  A hysteretic
loss factor η (Peng & Carpino 1993; Kim & San Andrés 2008) has no effect on the static
equilibrium, so only the perturbation changes.

References: J.-P. Peng, M. Carpino, "Calculation of stiffness and damping coefficients for
elastically supported gas foil bearings", J. Tribol. 115(1) (1993) 20–27; T. H. Kim,
L. San Andrés, "Heavily loaded gas foil bearings: a model anchored to test data", ASME J. Eng.
Gas Turbines Power (January 2008).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np
import scipy.sparse as sp


@dataclass(frozen=True, eq=False)
class PerturbationContext:
    """What a foil law reads to find its compliance terms in the linearised equations [-].

    The perturbation vector y and the equation rows share the static model's layout (the
    equation that defines a lifted variable sits at that variable's index).

    compliance S, length_ratio L/D, bearing_number Λ, compression_only (bool);
    size : n, the length of y; pressure : P at the unknown nodes, which are y[:n_p];
    mean_gauge : P̄ − 1 per θ row; film_rows : index of each θ row's lifted film (variable
    and equation); axial_cols : index of each row's Q = ∫(P − 1) dZ; beam : indices of the
    beam's free Hermite dofs (variables and equations; empty for the other laws);
    beam_dofs : their values; law_data : the law's :meth:`FoilLaw.prepare` data;
    film_sensitivity : a callable returning ∂R/∂H (n_p × n_p, sparse), how the steady
    Reynolds residual at each unknown node moves with the film at each unknown node (built
    on demand: only the local law needs it).
    row_compliance : S per θ row (bump zones; None: the uniform ``compliance``);
    pressure_rows : the θ row of each unknown pressure node.
    hardening : (n, W_lim) of the hardening bump ('hardened' law), None otherwise.
    """

    compliance: float
    length_ratio: float
    bearing_number: float
    compression_only: bool
    size: int
    pressure: np.ndarray
    mean_gauge: np.ndarray
    film_rows: np.ndarray
    axial_cols: np.ndarray
    beam: np.ndarray
    beam_dofs: np.ndarray
    law_data: object
    film_sensitivity: Callable[[], sp.spmatrix]
    row_compliance: Optional[np.ndarray] = None
    pressure_rows: Optional[np.ndarray] = None
    hardening: Optional[tuple] = None

    def rows(self):
        """S per θ row (or the uniform S)."""
        return self.compliance if self.row_compliance is None else self.row_compliance

    def nodes(self):
        """S at each unknown pressure node (or the uniform S)."""
        return (self.compliance if self.row_compliance is None
                else self.row_compliance[self.pressure_rows])


@dataclass(frozen=True, eq=False)
class ComplianceTerms:
    """The entries of the linearised equations that the bump foundation's compliance carries.

    With the real foundation the perturbation matrices are (A, B) (:mod:`gfbopt.linear`).  With
    a complex foundation stiffness k·K_f (k = 1 + iη sign γ for a hysteretic loss factor η) they
    become A + (m − 1) a and B + (m − 1) b, where m = 1/k when the entries are proportional to
    the compliance S (``scales_with='compliance'``: the foil deflection follows the pressure,
    δW = S_eff δq) and m = k when they are proportional to the foundation stiffness 1/S
    ('stiffness': the beam's foundation term).  k = 1 gives (A, B) exactly.

    a : n × n sparse; b : n × n sparse, or None when the squeeze term carries no compliance.

    Foil units (for a foundation stiffness that differs from unit to unit, e.g. the friction
    element's describing function, :mod:`gfbopt.physics.friction`): each unit is one θ row
    (axial-mean law) or one unknown pressure node (local law) with its own bump.  The entries
    of unit u sit in column ``unit_columns[u]`` of a and b only, so a factor k_u per unit
    scales those columns (:meth:`apply` with an array); its deflection perturbation is
    δW_u = ``unit_gain[u]`` ŷ[unit_columns[u]] / k_u, under the gauge pressure
    ``unit_gauge[u]`` (P̄ − 1 or P − 1) on a bump of compliance ``unit_compliance[u]`` [-]
    (small deflections); ``unit_softening[u]`` = tangent/small-deflection compliance of a
    hardening bump (None: 1).  None for a law without units (the beam).
    """

    a: sp.csc_matrix
    b: Optional[sp.csc_matrix]
    scales_with: str
    unit_columns: Optional[np.ndarray] = None
    unit_gain: Optional[np.ndarray] = None
    unit_gauge: Optional[np.ndarray] = None
    unit_compliance: Optional[np.ndarray] = None
    unit_softening: Optional[np.ndarray] = None

    def multiplier(self, stiffness_factor):
        """m: the factor on these entries for a foundation stiffness k·K_f [-] (k a number,
        or an array over the units)."""
        if self.scales_with == "compliance":
            return 1.0 / np.asarray(stiffness_factor) if np.ndim(stiffness_factor) else \
                1.0 / stiffness_factor
        return stiffness_factor

    def apply(self, a: sp.spmatrix, b: sp.spmatrix, stiffness_factor) -> tuple:
        """(A, B) with the foundation stiffness multiplied by ``stiffness_factor`` k [-]: one
        number for every unit, or an array with one factor per foil unit."""
        if np.ndim(stiffness_factor):
            if self.unit_columns is None:
                raise ValueError("this foil law has no foil units: one stiffness factor only")
            scale = np.zeros(a.shape[1], dtype=complex)
            scale[self.unit_columns] = self.multiplier(stiffness_factor) - 1.0
            d = sp.diags(scale)
            return (a + self.a @ d, b if self.b is None else b + self.b @ d)
        m = self.multiplier(stiffness_factor) - 1.0
        if m == 0:
            return a, b
        return a + m * self.a, (b if self.b is None else b + m * self.b)

    def deflection(self, y: np.ndarray, stiffness_factor=1.0) -> np.ndarray:
        """δW per foil unit from a perturbation ŷ (complex) and the units' factors k_u."""
        return self.unit_gain * y[self.unit_columns] / stiffness_factor


def embed(block: sp.spmatrix, rows: np.ndarray, cols: np.ndarray, n: int) -> sp.csc_matrix:
    """An n × n sparse matrix holding ``block`` at the given rows and columns of y."""
    coo = sp.coo_matrix(block)
    return sp.csc_matrix((coo.data, (np.asarray(rows)[coo.row], np.asarray(cols)[coo.col])),
                         shape=(n, n))


def active(values: np.ndarray, compression_only: bool) -> np.ndarray:
    """∂ max(v, 0)/∂v where the bumps act only in compression, else 1 (per entry)."""
    return (values > 0).astype(float) if compression_only else np.ones(values.size)
