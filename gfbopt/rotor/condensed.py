"""A flexible structure condensed onto its bearings and a few of its modes (Craig–Bampton),
the structure that every two-bearing analysis of a shaft works on.

A shaft of beam elements has n = 4 (nodes) degrees of freedom, most of them in modes far above
any whirl frequency of interest.  Its bearings touch it at two stations only, so the rotor on
its bearings is represented exactly at zero frequency, and to a few parts in a million at the
whirl frequencies of its lower modes, by the basis

    q = Ψ u + Φ η,    u = (S(z_A) q, S(z_B) q) : the axis's displacement at both bearings,

Ψ (n × 4) the constraint modes, K Ψ = S_bᵀ λ with S_b Ψ = I (the static shape of the shaft for
a unit displacement of one bearing's station, the other held), and Φ (n × k) the lowest k
modes of the shaft with both bearing stations held (S_b Φ = 0; K Φ = M Φ Ω², ignoring the
gyroscopic and damping terms, which the reduced matrices keep: M_r = Tᵀ M T, G_r = Tᵀ G T,
K_r = Tᵀ K T, C_r = Tᵀ C T, S_r(z) = S(z) T with T = [Ψ Φ]).  :data:`MODES` = 16 held
modes (eight per plane) by default: on problems/rotors/flexible_rotor.toml on 2 MN/m supports
the first three bending pairs (812, 2,089, 3,245 Hz) are within 3.3e-4 of the full shaft's
(8 modes: 4.9e-3; 24: 7.4e-5; tests/verification/test_rotor_condensed.py); each mode is scaled so that its largest translation is
1 m, so that η is in metres like u.  The bearing stations are exact (S_r(z_k) = [I 0]);
another station (an imbalance plane, a probe) sees the shaft through the basis.

The rigid body (four degrees of freedom) is never condensed: it is its own exact basis.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla

from ..errors import ParameterError

#: modes of the shaft with both bearing stations held that the basis keeps
MODES = 16


@dataclass(frozen=True, eq=False)
class CondensedStructure:
    """The Craig–Bampton basis of ``parent`` on the stations ``positions`` [m] (module
    docstring); the :class:`~gfbopt.rotor.structure.Structure` contract."""

    parent: object
    positions: tuple
    basis: np.ndarray = field(repr=False)
    matrices: tuple = field(repr=False)
    modes_kept: int = 0

    @property
    def kind(self) -> str:
        return self.parent.kind

    @property
    def size(self) -> int:
        return self.basis.shape[1]

    @property
    def dof_names(self) -> tuple:
        stations = tuple(f"{a}_{k}" for k in range(1, len(self.positions) + 1)
                         for a in ("x", "y"))
        return stations + tuple(f"eta_{j}" for j in range(1, self.modes_kept + 1))

    @property
    def total_mass(self) -> float:
        return self.parent.total_mass

    @property
    def centre_of_gravity(self) -> float:
        return self.parent.centre_of_gravity

    def mass(self) -> np.ndarray:
        return self.matrices[0]

    def gyroscopic(self) -> np.ndarray:
        return self.matrices[1]

    def stiffness(self) -> np.ndarray:
        return self.matrices[2]

    def damping(self) -> np.ndarray:
        return self.matrices[3]

    def station(self, position: float) -> np.ndarray:
        return self.parent.station(position) @ self.basis

    def expand(self, q: np.ndarray) -> np.ndarray:
        """The parent's degrees of freedom T q of a reduced amplitude q."""
        return self.basis @ q

    #: where the shape of a mode is read (the parent's, when it states them)
    @property
    def shape_positions(self) -> tuple:
        return (tuple(getattr(self.parent, "shape_positions", ()) or ())
                or tuple(getattr(self.parent, "nodes", ()) or ()))


def condensed(structure, positions, modes: int = MODES) -> CondensedStructure:
    """The Craig–Bampton condensation of ``structure`` on the stations at ``positions`` [m]
    with ``modes`` held modes (module docstring).  ParameterError when the stations do not
    hold the structure (its stiffness with them held is not positive definite)."""
    s_b = np.vstack([structure.station(z) for z in positions])
    m, g = structure.mass(), structure.gyroscopic()
    k, c = structure.stiffness(), structure.damping()
    n, r = k.shape[0], s_b.shape[0]
    aug = np.block([[k, s_b.T], [s_b, np.zeros((r, r))]])
    try:
        psi = np.linalg.solve(aug, np.vstack([np.zeros((n, r)), np.eye(r)]))[:n]
    except np.linalg.LinAlgError:
        raise ParameterError("bearings", tuple(positions), "do not hold the shaft (its "
                             "stiffness with both bearing stations held is singular)") from None
    null = sla.null_space(s_b)
    kept = min(int(modes), null.shape[1])
    if kept:
        kn, mn = null.T @ k @ null, null.T @ m @ null
        try:
            _, vec = sla.eigh(kn, mn, subset_by_index=(0, kept - 1))
        except np.linalg.LinAlgError:
            raise ParameterError("bearings", tuple(positions), "do not hold the shaft (its "
                                 "stiffness with both bearing stations held is not positive "
                                 "definite)") from None
        phi = null @ vec
        moving = np.array([not str(nm).startswith("psi") for nm in structure.dof_names])
        size = np.abs(phi[moving] if moving.any() else phi).max(axis=0)
        phi = phi / np.where(size > 0, size, 1.0)
    else:
        phi = np.zeros((n, 0))
    t = np.hstack([psi, phi])
    mats = tuple(t.T @ a @ t for a in (m, g, k, c))
    return CondensedStructure(structure, tuple(float(z) for z in positions), t, mats, kept)
