"""The rotor transient's model: a rotor structure of any size on its bearing films (SI).

The rotor is a :class:`gfbopt.rotor.structure.Structure` (mass M, gyroscopic G per rad/s of
spin, stiffness K, damping C, n × n, and the station S(z), 2 × n): today's rigid body
(:class:`~gfbopt.rotor.structure.RigidStructure`, q = (x, y, ψx, ψy) at the CG, S(z) =
[[1, 0, z, 0], [0, 1, 0, z]]), or a flexible shaft (condensed on its bearing stations,
:mod:`gfbopt.rotor.condensed`), whose axial positions run from the shaft's first end.

    M q̈ + (C + ω G) q̇ + K q = Σ_k S(z_k)ᵀ F_k + Q_s + Q_u(t)

(:mod:`.rotor_system` gives the films' forces F_k and the time scaling).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import ParameterError
from ..inputs.bearing import BearingGeometry
from ..inputs.rotor_system import RotorBody
from ..rotor.rigid import gyroscopic_matrix, mass_matrix, rotation, station_matrix  # noqa: F401
from ..rotor.structure import RigidStructure, is_rigid
from .system import TransientModel


#: names of the rigid body's generalised coordinates, in order (gfbopt.rotor.rigid's
#: q = (x, y, ψx, ψy)); a structure names its own (``structure.dof_names``)
DOF = ("x", "y", "psi_x", "psi_y")


def rigid_rotor_matrices(mass: float, transverse_inertia: float,
                         polar_inertia: float) -> tuple[np.ndarray, np.ndarray]:
    """(M, G) of a rigid rotor [kg, kg m²] in the coordinates :data:`DOF` (gfbopt.rotor.rigid's
    :func:`~gfbopt.rotor.rigid.mass_matrix` and :func:`~gfbopt.rotor.rigid.gyroscopic_matrix`;
    the inputs are checked by :class:`~gfbopt.inputs.rotor_system.RotorBody`)."""
    body = RotorBody(mass, transverse_inertia, polar_inertia)
    return mass_matrix(body), gyroscopic_matrix(body)


@dataclass(frozen=True, eq=False)
class BearingFilm:
    """One bearing of the rotor: its transient film model and where it sits.

    tm : the one-bearing model (about the bearing's equilibrium at ``model_speed``);
    geometry : the bearing in SI (R, c, p_a); position : z [m] in the structure's axial
    coordinate (from the CG of a rigid body, from a shaft's first end);
    frame_angle : ψ [rad], the bearing's load line (its X axis) from the global x, in the
    direction of rotation; model_speed : ω_m [rad/s] at which ``tm`` was built;
    label : for outputs.  running : the bearing's running line over a ramp of a heated
    rotor (:class:`.rotor_running.RunningSchedule`: running clearance and viscosity against
    speed, quasi-steady in temperature), None for today's bearing at its cold clearance and
    constant viscosity; ``tm`` and ``geometry`` stay the cold ones (the reference c), and
    only the fused films (:class:`.rotor_films.FusedFilms`) apply it (the run refuses others).
    """

    tm: TransientModel
    geometry: BearingGeometry
    position: float
    frame_angle: float
    model_speed: float
    label: str = ""
    running: Optional[object] = None

    @property
    def force_scale(self) -> float:
        """p_a R² [N per unit non-dimensional force]."""
        return self.geometry.ambient_pressure * self.geometry.radius ** 2

    @property
    def clearance(self) -> float:
        return self.geometry.radial_clearance


@dataclass(frozen=True)
class ImbalancePlane:
    """amount u = m e [kg m], > 0; phase φ [rad] from the shaft's reference mark in the
    direction of rotation; position z [m] in the structure's axial coordinate."""

    amount: float
    phase: float
    position: float


@dataclass(frozen=True, eq=False)
class RotorTransientModel:
    """The rotor structure and its bearing films (module docstring); everything in SI.

    structure : the rotor (:class:`~gfbopt.rotor.structure.Structure`, n degrees of
    freedom); bearings : BearingFilm per bearing; static_force Q_s (n,) [N, N m]: the
    generalised static force (gravity, side loads); imbalance : ImbalancePlane per plane;
    reference_speed ω_ref [rad/s] (the time unit τ = ω_ref t).  ``mass_matrix``,
    ``gyroscopic``, ``stiffness`` and ``damping`` are the structure's matrices.
    """

    structure: object
    bearings: tuple
    static_force: np.ndarray
    imbalance: tuple
    reference_speed: float

    @property
    def dofs(self) -> int:
        return int(self.structure.size)

    @property
    def rigid(self) -> bool:
        return is_rigid(self.structure)

    @property
    def mass_matrix(self) -> np.ndarray:
        return np.asarray(self.structure.mass(), dtype=float)

    @property
    def gyroscopic(self) -> np.ndarray:
        return np.asarray(self.structure.gyroscopic(), dtype=float)

    @property
    def stiffness(self) -> np.ndarray:
        return np.asarray(self.structure.stiffness(), dtype=float)

    @property
    def damping(self) -> np.ndarray:
        return np.asarray(self.structure.damping(), dtype=float)

    def station(self, position: float) -> np.ndarray:
        """S(z) (2, n) [m of axis per unit q]."""
        return np.asarray(self.structure.station(position), dtype=float)

    @property
    def clearance_ref(self) -> float:
        return self.bearings[0].clearance

    @property
    def stations(self) -> np.ndarray:
        """S_k of each bearing, (K, 2, n)."""
        return np.array([self.station(b.position) for b in self.bearings])

    def to_local(self) -> np.ndarray:
        """A_k (K, 2, n): q̃ → (X_k, Y_k), the journal in bearing k's frame over c_k."""
        c = self.clearance_ref
        return np.array([rotation(-b.frame_angle) @ self.station(b.position) * (c / b.clearance)
                         for b in self.bearings])

    def from_local(self) -> np.ndarray:
        """B_k (K, n, 2): bearing k's non-dimensional film force → generalised force [N]."""
        return np.array([self.station(b.position).T @ rotation(b.frame_angle) * b.force_scale
                         for b in self.bearings])


def rigid_structure(mass_matrix, gyroscopic) -> RigidStructure:
    """The rigid body whose M = diag(m, m, I_t, I_t) and G (G[2, 3] = I_p = −G[3, 2]) these
    are (the matrices of :func:`rigid_rotor_matrices`); anything else is refused."""
    m = np.asarray(mass_matrix, dtype=float)
    g = np.asarray(gyroscopic, dtype=float)
    if m.shape != (4, 4) or g.shape != (4, 4) or not np.all(np.isfinite(m)) \
            or not np.all(np.isfinite(g)):
        raise ParameterError("mass_matrix", m.shape, "M and G must be finite 4 × 4 matrices")
    if np.any(np.linalg.eigvalsh(0.5 * (m + m.T)) <= 0):
        raise ParameterError("mass_matrix", np.diag(m).tolist(), "must be positive definite")
    body = RotorBody(float(m[0, 0]), float(m[2, 2]), float(g[2, 3]))
    rigid = RigidStructure(body)
    if not (np.array_equal(rigid.mass(), m) and np.array_equal(rigid.gyroscopic(), g)):
        raise ParameterError("mass_matrix", np.diag(m).tolist(), "M and G must be a rigid "
                             "body's diag(m, m, I_t, I_t) and I_p (rigid_rotor_matrices); "
                             "another rotor is a Structure (structure_transient_model)")
    return rigid


def rotor_transient_model(mass_matrix, gyroscopic, bearings, static_force, imbalance=(),
                          reference_speed: Optional[float] = None) -> RotorTransientModel:
    """:func:`structure_transient_model` of the rigid body with these M and G
    (:func:`rigid_structure`)."""
    return structure_transient_model(rigid_structure(mass_matrix, gyroscopic), bearings,
                                     static_force, imbalance, reference_speed)


def structure_transient_model(structure, bearings, static_force, imbalance=(),
                              reference_speed: Optional[float] = None) -> RotorTransientModel:
    """Check and assemble a :class:`RotorTransientModel` (two bearings at distinct positions;
    ``reference_speed`` defaults to the first bearing's model speed)."""
    n = int(structure.size)
    m = np.asarray(structure.mass(), dtype=float)
    mats = [m] + [np.asarray(f(), dtype=float) for f in (structure.gyroscopic,
                                                       structure.stiffness, structure.damping)]
    if any(a.shape != (n, n) or not np.all(np.isfinite(a)) for a in mats):
        raise ParameterError("structure", n, "M, G, K and C must be finite n × n matrices")
    if np.any(np.linalg.eigvalsh(0.5 * (m + m.T)) <= 0):
        raise ParameterError("mass_matrix", np.diag(m).tolist(), "must be positive definite")
    bearings = tuple(bearings)
    if len(bearings) != 2:
        raise ParameterError("bearings", len(bearings), "a rotor on exactly two bearings is "
                             "supported")
    if bearings[0].position == bearings[1].position:
        raise ParameterError("bearings.position", bearings[0].position,
                             "the two bearings must sit at different axial positions")
    q = np.asarray(static_force, dtype=float).ravel()
    if q.shape != (n,) or not np.all(np.isfinite(q)):
        raise ParameterError("static_force", static_force, f"must be {n} finite numbers (the "
                             f"generalised force of the coordinates "
                             f"{', '.join(map(str, structure.dof_names))})")
    for k, plane in enumerate(imbalance):
        if not (math.isfinite(plane.amount) and plane.amount > 0):
            raise ParameterError(f"imbalance[{k}].amount", plane.amount, "must be > 0 [kg m]")
    omega = bearings[0].model_speed if reference_speed is None else float(reference_speed)
    if not (math.isfinite(omega) and omega > 0):
        raise ParameterError("reference_speed", reference_speed, "must be > 0 [rad/s]")
    return RotorTransientModel(structure, bearings, q, tuple(imbalance), omega)


def imbalance_shapes(model: RotorTransientModel) -> tuple[np.ndarray, np.ndarray]:
    """(U, V) [N at ω_ref], the generalised force of every imbalance plane at once.

    A plane j (amount u_j, phase φ_j, station S_j with rows S_j0, S_j1) at shaft angle
    ϑ_j = ϑ + φ_j pushes with u_j ω_ref² [r² (cos ϑ_j, sin ϑ_j) + a (sin ϑ_j, −cos ϑ_j)]; with
    cos ϑ_j, sin ϑ_j expanded in cos ϑ, sin ϑ this is Q_u = α U + β V (α = r² cos ϑ + a sin ϑ,
    β = r² sin ϑ − a cos ϑ) with U = Σ u_j ω_ref² (cos φ_j S_j0 + sin φ_j S_j1) and
    V = Σ u_j ω_ref² (cos φ_j S_j1 − sin φ_j S_j0): two shapes, whatever the planes."""
    w2 = model.reference_speed ** 2
    u = np.zeros(model.dofs)
    v = np.zeros(model.dofs)
    for p in model.imbalance:
        t = model.station(p.position)
        c, s = math.cos(p.phase), math.sin(p.phase)
        u += p.amount * w2 * (c * t[0] + s * t[1])
        v += p.amount * w2 * (c * t[1] - s * t[0])
    return u, v
