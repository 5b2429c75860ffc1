"""A gas foil journal bearing described in SI units, and its non-dimensional groups."""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Optional

from ..errors import ParameterError
from ..physics.bump import bump_compliance
from .bore_si import BearingBuild
from .checks import check_finite, check_positive
from .conversions import (bearing_number_from_speed, compliance_from_alpha,
                          load_to_newton, load_to_nondimensional, rpm_to_rad_per_s,
                          top_foil_coefficient_from_geometry)
from .model import BearingModel


@dataclass(frozen=True)
class BearingGeometry:
    """A bump-type gas foil journal bearing in SI units.

    Attributes
    ----------
    radius : bearing (journal) radius R [m]
    length : axial length L [m]
    radial_clearance : radial clearance c [m]
    bump_pitch : bump pitch s [m]
    bump_half_length : half bump length l0 [m]
    bump_thickness : bump foil thickness t_b [m]
    bump_youngs_modulus : bump foil Young's modulus E_b [Pa]
    top_foil_youngs_modulus : top foil Young's modulus E_t [Pa]
    poisson_ratio : bump foil Poisson's ratio ν [-]
    top_foil_thickness : top foil thickness t_t [m]
    viscosity : gas dynamic viscosity μ [Pa s]
    ambient_pressure : ambient pressure p_a [Pa]
    name : label used in reports
    build : the bearing as built (:class:`gfbopt.inputs.bore.BearingBuild`: bore profile,
        pads, bump zones, SI and degrees), or None for a round bore, one top foil and a
        uniform foundation
    """

    radius: float
    length: float
    radial_clearance: float
    bump_pitch: float
    bump_half_length: float
    bump_thickness: float
    bump_youngs_modulus: float
    top_foil_youngs_modulus: float
    poisson_ratio: float
    top_foil_thickness: float
    viscosity: float
    ambient_pressure: float = 101325.0
    name: str = "bearing"
    build: Optional[BearingBuild] = None

    def __post_init__(self) -> None:
        for key in ("radius", "length", "radial_clearance", "bump_pitch", "bump_half_length",
                    "bump_thickness", "bump_youngs_modulus", "top_foil_youngs_modulus",
                    "top_foil_thickness", "viscosity", "ambient_pressure"):
            object.__setattr__(self, key, check_positive(key, getattr(self, key)))
        nu = check_finite("poisson_ratio", self.poisson_ratio)
        if not -1.0 < nu < 0.5:
            raise ParameterError("poisson_ratio", self.poisson_ratio, "must lie in (-1, 0.5)")
        object.__setattr__(self, "poisson_ratio", nu)
        if self.radial_clearance > 0.01 * self.radius:
            raise ParameterError(
                "radial_clearance", self.radial_clearance,
                f"must be small against the radius (c/R <= 0.01; R = {self.radius!r} m) "
                "for the thin-film Reynolds equation to hold")
        if self.build is not None:
            self.build.nondimensional(self)       # bore, pads and zones checked here

    # Derived non-dimensional groups --------------------------------------------
    @property
    def length_ratio(self) -> float:
        """L/D [-]."""
        return self.length / (2.0 * self.radius)

    @property
    def bump_compliance(self) -> float:
        """α [m³/N] (Heshmat 1983)."""
        return bump_compliance(self.bump_pitch, self.bump_half_length, self.bump_thickness,
                               self.bump_youngs_modulus, self.poisson_ratio)

    @property
    def compliance(self) -> float:
        """S = p_a α / c [-]."""
        return compliance_from_alpha(self.bump_compliance, self.ambient_pressure,
                                     self.radial_clearance)

    @property
    def top_foil_coefficient(self) -> float:
        """C = E_t I_t c / (R⁴ L p_a) [-]."""
        return top_foil_coefficient_from_geometry(
            self.top_foil_youngs_modulus, self.top_foil_thickness, self.radius, self.length,
            self.ambient_pressure, self.radial_clearance)

    def bearing_number(self, speed_rpm: float) -> float:
        """Λ at shaft speed ``speed_rpm`` [rpm]."""
        return bearing_number_from_speed(self.viscosity, rpm_to_rad_per_s(speed_rpm),
                                         self.radius, self.ambient_pressure,
                                         self.radial_clearance)

    def nondimensional_load(self, load_newton: float) -> float:
        """W̄ = W/(p_a R²) for a static load ``load_newton`` [N]."""
        return load_to_nondimensional(check_positive("load_newton", load_newton),
                                      self.ambient_pressure, self.radius)

    def load_newton(self, load: float) -> float:
        """W [N] for a non-dimensional load W̄ [-]."""
        return load_to_newton(load, self.ambient_pressure, self.radius)

    def model(self, speed_rpm: float, foil: str = "simple", **kwargs) -> "BearingModel":
        """The non-dimensional :class:`BearingModel` of this bearing at ``speed_rpm`` [rpm].

        ``foil='rigid'`` sets S = 0; other keyword arguments go to BearingModel.
        """
        compliance = 0.0 if foil == "rigid" else self.compliance
        if self.build is not None and "as_built" not in kwargs:
            built = self.build.nondimensional(self)
            if foil == "rigid":       # a rigid comparison keeps the bore, not the foils
                built = replace(built, zones=(), pads=())
            elif built.zones:
                compliance = built.mean_compliance()
            kwargs["as_built"] = built
        return BearingModel(bearing_number=self.bearing_number(speed_rpm),
                            compliance=compliance,
                            length_ratio=self.length_ratio,
                            top_foil_coefficient=self.top_foil_coefficient,
                            foil=foil, **kwargs)
