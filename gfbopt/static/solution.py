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
from ..inputs.model import BearingModel
from ..physics.foil_laws import FoilParameters


@dataclass(frozen=True, eq=False)
class StaticSolution:
    """A static equilibrium and its diagnostics.

    Scalars are non-dimensional (load W̄ = W/(p_a R²), film H = h/c), angles in radians.
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
    attitude_angle: float
    load: float
    force: tuple
    min_film: float
    min_film_angle: float
    seam_angle: float
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
        return self.theta - self.seam_angle

    @property
    def min_film_angle_from_seam(self) -> float:
        """Angle of the minimum film from the welded end, in [0, 2π) [rad]."""
        return float(np.mod(self.min_film_angle - self.seam_angle, 2 * math.pi))

    def to_dict(self) -> dict:
        """Scalar results as a flat dict (angles in degrees) for JSON and DataFrames."""
        return {
            "eccentricity": self.eccentricity,
            "attitude_angle_deg": math.degrees(self.attitude_angle),
            "load": self.load,
            "force_x": self.force[0], "force_y": self.force[1],
            "min_film": self.min_film,
            "min_film_angle_deg": math.degrees(self.min_film_angle) % 360.0,
            "min_film_angle_from_seam_deg": math.degrees(self.min_film_angle_from_seam),
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
    return FoilParameters(s, model.top_foil_coefficient, float(model.compression_only))
