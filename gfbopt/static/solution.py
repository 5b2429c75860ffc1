"""The result of a static solve: :class:`StaticSolution` (frozen, with diagnostics).

Its residual and force balance are recomputed from IPOPT's raw solution with numpy
(:func:`gfbopt.static.solve.postprocess`), not taken from IPOPT.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import discretisation as disc
from ..inputs.grid import Grid
from ..inputs.model import BearingModel, renamed_radian_attribute
from ..physics.foil_laws import FoilParameters

#: |ε| below this is a journal at the centre (IPOPT's round-off of a fixed ε = 0) [-]
CONCENTRIC_TOLERANCE = 1e-12
#: a film force below this has no direction (the round bore's concentric P ≡ 1) [-]
FORCE_TOLERANCE = 1e-12


@dataclass(frozen=True, eq=False)
class StaticSolution:
    """A static equilibrium and its diagnostics.

    Scalars are non-dimensional (load W̄ = W/(p_a R²), film H = h/c).  Angles (from the load
    line, direction of rotation) are degrees at the public edge: :attr:`attitude_angle_deg`,
    :attr:`min_film_angle_deg`, :attr:`seam_angle_deg`, :attr:`min_film_angle_from_seam_deg`;
    the numerics keep radians only in the fields named ``*_rad`` (the old unit-less names
    ``attitude_angle``, ``seam_angle``, ``min_film_angle`` raise an AttributeError naming the
    replacement).
    Arrays: ``theta`` [rad, from the load line, direction of rotation] at the θ nodes,
    ``z`` [-] at the axial nodes, ``pressure`` P of shape (n_theta_nodes, n_z + 1),
    ``film`` H and ``deflection`` W of the same shape, ``mean_pressure`` P̄ per θ node.
    Drag torque on the journal over Petroff's 2π μ ω R³ L / c: ``couette_torque_ratio``
    (shear of the journal's motion) and ``pressure_torque_ratio`` (the pressure-gradient
    part), their sum :attr:`torque_ratio` (docs/PHYSICS.md §5b).
    """

    model: BearingModel
    grid: Grid
    eccentricity: float
    attitude_angle_rad: float
    load: float
    force: tuple
    min_film: float
    min_film_angle_rad: float
    seam_angle_rad: float
    theta: np.ndarray
    z: np.ndarray
    pressure: np.ndarray
    film: np.ndarray
    deflection: np.ndarray
    success: bool
    status: str
    iterations: int
    residual: float
    force_residual: float
    solve_time_s: float
    state: np.ndarray = field(repr=False)
    message: str = ""
    couette_torque_ratio: float = math.nan
    pressure_torque_ratio: float = math.nan
    #: which method solved it: "ipopt", or "newton" (the warm fast path, gfbopt.static.newton)
    solver: str = "ipopt"

    def __post_init__(self) -> None:
        # IPOPT returns a journal held at the centre as ε ≈ ±1e-48: a round-off, reported as
        # the concentric journal it is (never a negative eccentricity)
        if abs(self.eccentricity) < CONCENTRIC_TOLERANCE:
            object.__setattr__(self, "eccentricity", 0.0)
        if abs(self.attitude_angle_rad) < CONCENTRIC_TOLERANCE:      # (−0.000 deg printed)
            object.__setattr__(self, "attitude_angle_rad", 0.0)
        if self.eccentricity == 0.0:
            # concentric: no line of centres (φ undefined), and the film force of a preloaded
            # bore need not lie on the load line, so the load carried is its magnitude |F|
            # (its direction is :attr:`film_force_angle_deg`), not the component −F_X
            object.__setattr__(self, "attitude_angle_rad", math.nan)
            object.__setattr__(self, "load", self.film_force)

    def __getattr__(self, name: str):
        raise renamed_radian_attribute(type(self).__name__, name)

    @property
    def attitude_angle_deg(self) -> float:
        """Attitude angle φ: the journal centre from the load line in the direction of
        rotation [deg] (NaN for a concentric journal)."""
        return math.degrees(self.attitude_angle_rad)

    @property
    def film_force(self) -> float:
        """Magnitude of the film force on the journal, |F| = √(F_X² + F_Y²) [-] (W̄ units).
        At an equilibrium it is the load; at a stated position (``attitude_angle_deg`` given,
        or a concentric journal in a preloaded bore) F_Y need not vanish."""
        return float(math.hypot(*self.force))

    @property
    def film_force_angle_deg(self) -> float:
        """Direction of the film force on the journal from the load line (+X) in the direction
        of rotation, in [0, 360) [deg]: 180 when it opposes the load exactly (NaN for no
        force)."""
        if not self.film_force > FORCE_TOLERANCE:
            return math.nan
        return math.degrees(math.atan2(self.force[1], self.force[0])) % 360.0

    @property
    def min_film_angle_deg(self) -> float:
        """Angle of the minimum film from the load line, in [0, 360) [deg]."""
        return math.degrees(self.min_film_angle_rad) % 360.0

    @property
    def seam_angle_deg(self) -> float:
        """Angle of the welded end of the top foil (the grid origin) from the load line [deg]
        (for the seam on the maximum-film line: 180° + φ; for a periodic film the grid's
        origin)."""
        return math.degrees(self.seam_angle_rad)

    @property
    def torque_ratio(self) -> float:
        """Drag torque on the journal over Petroff's, T / (2π μ ω R³ L / c) [-] (1 for a
        concentric journal in a round bore)."""
        return self.couette_torque_ratio + self.pressure_torque_ratio

    @property
    def mean_pressure(self) -> np.ndarray:
        """Axially averaged pressure P̄ at each θ node [-]."""
        w = disc.trapezoid_weights(self.z.size)
        return self.pressure @ w / w.sum()

    @property
    def theta_from_seam(self) -> np.ndarray:
        """θ-node angles measured from the welded end of the top foil, in [0, 2π] [rad].

        With a seam film the first node is the welded end (0) and the last the free end (2π).
        """
        return self.theta - self.seam_angle_rad

    @property
    def min_film_angle_from_seam_deg(self) -> float:
        """Angle of the minimum film from the welded end, in [0, 360) [deg]."""
        return math.degrees(float(np.mod(self.min_film_angle_rad - self.seam_angle_rad,
                                         2 * math.pi)))

    def to_dict(self) -> dict:
        """Scalar results as a flat dict (angles in degrees) for JSON and DataFrames."""
        return {
            "eccentricity": self.eccentricity,
            "attitude_angle_deg": self.attitude_angle_deg,
            "load": self.load,
            "force_x": self.force[0], "force_y": self.force[1],
            "film_force": self.film_force, "film_force_angle_deg": self.film_force_angle_deg,
            "min_film": self.min_film,
            "min_film_angle_deg": self.min_film_angle_deg,
            "min_film_angle_from_seam_deg": self.min_film_angle_from_seam_deg,
            "max_mean_pressure": float(self.mean_pressure.max()),
            "max_deflection": float(self.deflection.max()),
            "torque_ratio": self.torque_ratio,
            "couette_torque_ratio": self.couette_torque_ratio,
            "success": self.success, "status": self.status, "iterations": self.iterations,
            "residual": self.residual, "force_residual": self.force_residual,
            "solve_time_s": self.solve_time_s,
        }


def foil_parameters(model: BearingModel, row_compliance=None) -> FoilParameters:
    """The foil groups of ``model`` as numbers (the numpy side of the foil law); with
    ``row_compliance`` (S per θ row) the simple and local laws see the foundation zones."""
    s = model.compliance if row_compliance is None or model.foil == "beam" else row_compliance
    hardening = ((model.hardening_exponent, model.hardening_limit)
                 if getattr(model, "hardening_exponent", 0.0) > 0.0 else None)
    return FoilParameters(s, model.top_foil_coefficient, float(model.compression_only),
                          hardening)
