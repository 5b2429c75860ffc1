"""The structure contract: what every rotor analysis asks of the rotor, whatever its size.

A rotor structure is linear and spins at ω:

    M q̈ + (C + ω G) q̇ + K q = Q,        Q = Σ_k S(z_k)ᵀ F_k + (applied forces),

with n degrees of freedom q.  The analyses (statics, matched-whirl onset, Campbell diagram,
imbalance response, transients, design) see only this contract:

- ``mass()``, ``gyroscopic()``, ``stiffness()``, ``damping()``: the n × n matrices M, G (per
  rad/s of spin; skew), K, C, in SI (kg, kg m², N/m, N s/m, ...);
- ``station(z)``: the 2 × n matrix S(z) giving the axis's displacement (x, y) [m] at the axial
  position z [m] from q — bearings, imbalance planes and probes are all stations; the
  generalised force of a force (F_x, F_y) at z is S(z)ᵀ (F_x, F_y);
- ``total_mass`` [kg] and ``centre_of_gravity`` [m]: what the statics of two supports needs
  (two bearings carry the weight by force and moment balance, whatever the shaft's stiffness);
- ``dof_names``: one name per degree of freedom (a tilt's name starts with "psi", a
  translation's does not: the full system's scaling reads it); ``kind``: "rigid" or "shaft".

Axial positions are in the rotor's own coordinate: from the centre of gravity for a rigid
body (today's rotor file), from the shaft's first end for a shaft of beam elements.

Two implementations: :class:`RigidStructure` here (the four degrees of freedom of
:mod:`gfbopt.rotor.rigid`), and the flexible shaft of Timoshenko beam elements with disks in
:mod:`gfbopt.rotor.shaft`.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from ..inputs.rotor_system import RotorBody

#: names of the rigid body's degrees of freedom, in the order of q
RIGID_DOFS = ("x", "y", "psi_x", "psi_y")


@runtime_checkable
class Structure(Protocol):
    """The contract (see the module's docstring)."""

    kind: str

    @property
    def size(self) -> int: ...

    @property
    def dof_names(self) -> tuple: ...

    @property
    def total_mass(self) -> float: ...

    @property
    def centre_of_gravity(self) -> float: ...

    def mass(self) -> np.ndarray: ...

    def gyroscopic(self) -> np.ndarray: ...

    def stiffness(self) -> np.ndarray: ...

    def damping(self) -> np.ndarray: ...

    def station(self, position: float) -> np.ndarray: ...


@dataclass(frozen=True)
class RigidStructure:
    """The rigid body: q = (x, y, ψx, ψy) at the centre of gravity (z = 0);
    M = diag(m, m, I_t, I_t), G[2,3] = I_p = −G[3,2], K = C = 0;
    S(z) = [[1, 0, z, 0], [0, 1, 0, z]] (small tilts)."""

    body: RotorBody
    kind: str = "rigid"

    @property
    def size(self) -> int:
        return 4

    @property
    def dof_names(self) -> tuple:
        return RIGID_DOFS

    @property
    def total_mass(self) -> float:
        return self.body.mass

    @property
    def centre_of_gravity(self) -> float:
        return 0.0

    def mass(self) -> np.ndarray:
        b = self.body
        return np.diag([b.mass, b.mass, b.transverse_inertia, b.transverse_inertia])

    def gyroscopic(self) -> np.ndarray:
        g = np.zeros((4, 4))
        g[2, 3], g[3, 2] = self.body.polar_inertia, -self.body.polar_inertia
        return g

    def stiffness(self) -> np.ndarray:
        return np.zeros((4, 4))

    def damping(self) -> np.ndarray:
        return np.zeros((4, 4))

    def station(self, position: float) -> np.ndarray:
        z = float(position)
        return np.array([[1.0, 0.0, z, 0.0], [0.0, 1.0, 0.0, z]])


def structure_of(system) -> Structure:
    """The structure of a :class:`~gfbopt.inputs.rotor_system.RotorSystem`: the rigid body
    (:class:`RigidStructure`) when it has no shaft (``system.shaft`` is None or absent),
    else its shaft of beam elements (:func:`gfbopt.rotor.shaft.shaft_structure`)."""
    if getattr(system, "shaft", None) is None:
        return RigidStructure(system.body)
    from .shaft import shaft_structure
    return shaft_structure(system)


def is_rigid(structure: Structure) -> bool:
    """True for the four degrees of freedom of the rigid body (every analysis keeps its
    original arithmetic there, bit for bit)."""
    return isinstance(structure, RigidStructure)


def dof_scales(structure: Structure, length: float) -> np.ndarray:
    """Λ's diagonal: 1 for a translation, 1/``length`` [1/m] for a tilt (a name starting
    with "psi"): q = c Λ q̃ puts every degree of freedom in units of a clearance."""
    return np.array([1.0 / length if str(n).startswith("psi") else 1.0
                     for n in structure.dof_names])


def imbalance_vector(structure: Structure, position: float, amount: complex) -> np.ndarray:
    """Generalised force amplitude of a rotating force of complex amplitude ``amount``
    (U ω² e^{iφ}) at ``position``: S(z)ᵀ (1, −i) amount, Q(t) = Re(Q̂ e^{iωt})."""
    return structure.station(position).T @ np.array([1.0, -1j]) * amount
