"""The rigid rotor's four degrees of freedom: mass, gyroscopic and transformation matrices,
statics (load sharing) and the dynamic stiffness with frequency-dependent bearings.

Coordinates and signs (the frame of :mod:`gfbopt.inputs.rotor_system`)
----------------------------------------------------------------------
z along the rotor axis from the centre of gravity (CG); x, y in the bearing plane; the shaft
spins at ω > 0 from x towards y.  The rotor's state is

    q = (x, y, ψx, ψy)ᵀ,    x, y : CG translation [m];  ψx = dx/dz, ψy = dy/dz : tilts [rad],

so the axis point at axial position z moves by (x + z ψx, y + z ψy) (small motion).  With
M = diag(m, m, I_t, I_t) and the skew gyroscopic matrix G (G[2,3] = I_p, G[3,2] = −I_p),

    M q̈ + ω G q̇ = Q,       Q = Σ_k T_kᵀ F_k + (applied forces),

the angular-momentum balance H = I_p ω n + I_t n × ṅ of the axis n ≈ (ψx, ψy, 1).  Sign check
(also a test): for free forward conical whirl ψx + iψy ∝ e^{iΩt} on isotropic tilt stiffness
k, I_t Ω² − I_p ω Ω = k, so the forward conical frequency rises with speed (gyroscopic
stiffening) and the backward one falls.  A force (F_x, F_y) at z gives the generalised force
(F_x, F_y, z F_x, z F_y).

Bearing k sits at z_k and carries the static load W_k (the force the journal exerts on it,
the "load" of :mod:`gfbopt.static`), of direction α_k from +x in the direction of rotation.
Its own frame has X along W_k and Y ahead of it in the direction of rotation, the frame of
the bearing's impedance Z̄_k (:mod:`gfbopt.linear`).  Its journal displacement in that frame
is ξ_k = T_k q with

    T_k = R(α_k)ᵀ [[1, 0, z_k, 0], [0, 1, 0, z_k]],    R(α) = [[cos α, −sin α], [sin α, cos α]],

and the bearing's dynamic force on the rotor is −Z_k(iΩ) ξ_k, Z_k = (p_a R_k²/c_k) Z̄_k(iΩ/ω)
[N/m] (Z̄ per unit ξ/c and per p_a R²; the whirl ratio γ = Ω/ω).  The rotor whirls at a real
frequency Ω where the dynamic stiffness

    D(Ω) = −Ω² M + iΩ ω G + Σ_k T_kᵀ Z_k(iΩ) T_k                                      (1)

is singular (a generalisation of the one-bearing det(−M̄W̄0γ² I + Z̄) = 0).

Statics: the applied forces (weight m g at the CG along the gravity direction, side loads at
their positions) are shared by force and moment balance, W_A + W_B = F, z_A W_A + z_B W_B =
M_z (vector sums in the x–y plane).  A bearing can be pushed away from gravity (overhung CG):
its load direction α_k changes and T_k rotates with it.  The top foil's seam is fixed in the
housing, whose reference is the gravity direction: a seam stated at θ_s from gravity sits at
θ_s − (α_k − α_g) from that bearing's load (:func:`seam_from_load`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Sequence

import numpy as np

from ..errors import ParameterError
from ..inputs.options import MAX_FILM, ModelOptions
from ..inputs.rotor_system import BearingSupport, RotorBody, RotorSystem
from .structure import RigidStructure, imbalance_vector, is_rigid, structure_of

#: names of the rotor's degrees of freedom, in the order of q
DOF_NAMES = ("x", "y", "psi_x", "psi_y")
#: the bearing loads' relative magnitude below which a bearing counts as unloaded [-]
UNLOADED = 1e-9


def mass_matrix(body: RotorBody) -> np.ndarray:
    """M = diag(m, m, I_t, I_t) [kg, kg m²] (4 × 4)."""
    return np.diag([body.mass, body.mass, body.transverse_inertia, body.transverse_inertia])


def gyroscopic_matrix(body: RotorBody) -> np.ndarray:
    """G, skew: G[2,3] = I_p, G[3,2] = −I_p [kg m²] (4 × 4); the rotor's term is ω G q̇."""
    g = np.zeros((4, 4))
    g[2, 3], g[3, 2] = body.polar_inertia, -body.polar_inertia
    return g


def rotation(angle_rad: float) -> np.ndarray:
    """R(α) = [[cos α, −sin α], [sin α, cos α]]: a bearing frame's axes in x–y components."""
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    return np.array([[c, -s], [s, c]])


def station_matrix(position: float) -> np.ndarray:
    """[[1, 0, z, 0], [0, 1, 0, z]]: the x–y displacement of the axis at z [m] from q (2 × 4)."""
    return np.array([[1.0, 0.0, position, 0.0], [0.0, 1.0, 0.0, position]])


def transformation(position: float, load_angle_rad: float) -> np.ndarray:
    """T_k = R(α_k)ᵀ [[1, 0, z_k, 0], [0, 1, 0, z_k]]: ξ_k (bearing frame, X along the load)
    from q (2 × 4)."""
    return rotation(load_angle_rad).T @ station_matrix(position)


@dataclass(frozen=True)
class BearingLoad:
    """The static load on one bearing.

    name; position [m]; force_x, force_y : the load vector W_k [N] (the force the journal
    exerts on the bearing); magnitude [N]; direction_deg : α_k from +x in the direction of
    rotation [deg]; away_from_gravity_deg : α_k − α_g wrapped to (−180, 180] [deg] (0: the
    load is along gravity)."""

    name: str
    position: float
    force_x: float
    force_y: float
    magnitude: float
    direction_deg: float
    away_from_gravity_deg: float

    @property
    def direction_rad(self) -> float:
        return math.radians(self.direction_deg)

    def to_dict(self) -> dict:
        return {"bearing": self.name, "position_m": self.position,
                "load_newton": self.magnitude, "load_direction_deg": self.direction_deg,
                "load_from_gravity_deg": self.away_from_gravity_deg,
                "force_x_newton": self.force_x, "force_y_newton": self.force_y}


def applied_loads(system: RotorSystem, centre_of_gravity: float = 0.0
                  ) -> tuple[np.ndarray, np.ndarray]:
    """(F, M_z): the sum of the applied static forces (weight and side loads) [N] and of their
    moments z F about the origin of the axial positions [N m] (the CG of a rigid rotor, where
    the weight has no moment; a shaft's first end, the weight acting at
    ``centre_of_gravity`` [m] from it), each an x–y vector."""
    force = np.array(system.weight_vector, dtype=float)
    moment = np.zeros(2)
    if centre_of_gravity != 0.0:
        moment += centre_of_gravity * force
    for load in system.side_loads:
        f = np.array(load.vector)
        force += f
        moment += load.position * f
    return force, moment


def bearing_loads(system: RotorSystem) -> tuple[BearingLoad, BearingLoad]:
    """Each bearing's static load from force and moment balance (module docstring).

    A bearing whose load vanishes (e.g. the CG exactly over the other bearing with no side
    load) is refused with ParameterError: the linear film model needs a loaded journal
    (ε > 0).  The weight acts at the system's centre of gravity (0 for the rigid body, whose
    positions are measured from it; a shaft's from its first end)."""
    force, moment = applied_loads(system, float(getattr(system, "centre_of_gravity", 0.0)))
    (a, b) = system.bearings
    za, zb = a.position, b.position
    wa = (zb * force - moment) / (zb - za)
    wb = (moment - za * force) / (zb - za)
    scale = max(np.linalg.norm(force), np.linalg.norm(moment) / system.span, 1e-300)
    out = []
    for support, w in ((a, wa), (b, wb)):
        magnitude = float(np.hypot(*w))
        if magnitude <= UNLOADED * scale or magnitude == 0.0:
            raise ParameterError(f"bearing {support.name} load", magnitude,
                                 "the statics leave this bearing unloaded (its share of the "
                                 "weight and side loads is zero): the linear film model needs "
                                 "a loaded journal; move the centre of gravity or add a side "
                                 "load")
        direction = math.degrees(math.atan2(w[1], w[0]))
        away = (direction - system.gravity_direction_deg + 180.0) % 360.0 - 180.0
        away = 180.0 if away == -180.0 else away
        out.append(BearingLoad(support.name, support.position, float(w[0]), float(w[1]),
                               magnitude, direction, away))
    return out[0], out[1]


def seam_from_load(options: ModelOptions, away_from_gravity_deg: float) -> ModelOptions:
    """The options with a stated seam angle re-measured from the bearing's own load: the seam
    is fixed in the housing, stated from gravity; the load is α − α_g from gravity.  Every
    other option (film, foil, deflection law, loss factor, the bumps' friction and
    hardening) is kept as stated."""
    angle = options.seam_angle_deg
    if angle is None or angle == MAX_FILM or away_from_gravity_deg == 0.0:
        return options
    shifted = (angle - away_from_gravity_deg) % 360.0
    shifted = 0.0 if shifted >= 360.0 else shifted
    return replace(options, seam_angle_deg=shifted)      # every other option kept (friction)


def transformations(system: RotorSystem, loads: Sequence[BearingLoad], structure=None
                    ) -> tuple:
    """(T_A, T_B): each bearing's transformation T_k = R(α_k)ᵀ S(z_k) in its own load frame
    (2 × n; the rigid body's 2 × 4 when ``structure`` is None or rigid)."""
    if structure is None or is_rigid(structure):
        return tuple(transformation(s.position, l.direction_rad)
                     for s, l in zip(system.bearings, loads))
    return tuple(rotation(l.direction_rad).T @ structure.station(s.position)
                 for s, l in zip(system.bearings, loads))


def dynamic_stiffness(structure, omega: float, whirl: complex, transforms: Sequence,
                      impedances: Sequence, inertia_scale: float = 1.0) -> np.ndarray:
    """D = μ(s² M + s ω G) + s C + K + Σ T_kᵀ Z_k T_k at s = ``whirl`` [1/s] (s = iΩ on the
    axis: (1)), on any :class:`~gfbopt.rotor.structure.Structure` (a :class:`RotorBody` is
    the rigid body's).

    omega : shaft speed [rad/s]; impedances : Z_k(s) [N/m] (2 × 2, bearing frames);
    inertia_scale μ multiplies M and G only (μ = 1: the rotor itself; the shaft's own K and C
    are not scaled)."""
    st = RigidStructure(structure) if isinstance(structure, RotorBody) else structure
    d = inertia_scale * (whirl**2 * st.mass() + whirl * omega * st.gyroscopic())
    if not is_rigid(st):
        d = d + whirl * st.damping() + st.stiffness()
    for t, z in zip(transforms, impedances):
        d = d + t.T @ z @ t
    return d.astype(complex)


def imbalance_forces(system: RotorSystem, omega: float, structure=None) -> np.ndarray:
    """Complex amplitude Q̂ of the generalised imbalance force, Q(t) = Re(Q̂ e^{iωt}) [N, N m].

    A plane of amount U at phase φ and position z pulls with U ω² (cos(ωt + φ), sin(ωt + φ)):
    Q̂ = S(z)ᵀ (1, −i) U ω² e^{iφ} (:func:`~gfbopt.rotor.structure.imbalance_vector`; the
    rigid body's (1, −i, z, −i z) U ω² e^{iφ}).  ``structure``: the rotor's (default: the
    system's, :func:`~gfbopt.rotor.structure.structure_of`)."""
    st = structure if structure is not None else structure_of(system)
    if is_rigid(st):
        q = np.zeros(4, dtype=complex)
        for plane in system.imbalance:
            u = plane.amount_kg_m * omega**2 * np.exp(1j * math.radians(plane.phase_deg))
            q += u * np.array([1.0, -1j, plane.position, -1j * plane.position])
        return q
    q = np.zeros(st.size, dtype=complex)
    for plane in system.imbalance:
        u = plane.amount_kg_m * omega**2 * np.exp(1j * math.radians(plane.phase_deg))
        q += imbalance_vector(st, plane.position, u)
    return q


def support_names(system: RotorSystem) -> tuple[str, str]:
    return tuple(b.name for b in system.bearings)


def check_support(support: BearingSupport) -> BearingSupport:
    """ParameterError unless ``support`` is a :class:`BearingSupport`."""
    if not isinstance(support, BearingSupport):
        raise ParameterError("bearing", support, "must be a BearingSupport")
    return support
