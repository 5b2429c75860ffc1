"""A gas foil journal bearing described in SI units, and its non-dimensional groups."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional

from ..errors import ParameterError
from ..physics.bump import bump_compliance
from .bore_si import BearingBuild
from .checks import check_positive
from .file_schema import BEARING, check_value
from .conversions import (bearing_number_from_speed, compliance_from_alpha,
                          load_to_newton, load_to_nondimensional, rpm_to_rad_per_s,
                          top_foil_coefficient_from_geometry)
from .model import BearingModel
from .options import ModelOptions


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
    options : the formulation the bearing is analysed with (a bearing file's ``[model]``
        table; nothing stated by default), used by :func:`gfbopt.rotor.stability` and
        :func:`gfbopt.rotor.onset_speed` unless told otherwise
    build : the bearing as built (:class:`gfbopt.inputs.bore.BearingBuild`: bore profile,
        pads, bump zones, SI and degrees), or None for a round bore, one top foil and a
        uniform foundation

    Every value is checked against the bearing file's schema
    (:data:`gfbopt.inputs.file_schema.BEARING`: bounds and the rules between dimensions), so
    a geometry that cannot be built is refused with the rule, whatever the route.
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
    options: ModelOptions = field(default_factory=ModelOptions)
    build: Optional[BearingBuild] = None

    def __post_init__(self) -> None:
        for f in BEARING.fields:
            object.__setattr__(self, f.name, check_value(f, getattr(self, f.name), f.name))
        if not isinstance(self.options, ModelOptions):
            raise ParameterError("options", self.options, "must be ModelOptions")
        self._check_rules()
        if self.build is not None:
            self.build.nondimensional(self)       # bore, pads and zones checked here

    def _check_rules(self) -> None:
        """The rules between dimensions (:data:`gfbopt.inputs.file_schema.BEARING` rules)."""
        r, s, l0, tb = self.radius, self.bump_pitch, self.bump_half_length, self.bump_thickness
        rules = (
            ("radial_clearance", self.radial_clearance, self.radial_clearance <= 0.01 * r,
             f"must be small against the radius (c/R <= 0.01; R = {r!r} m) for the "
             "thin-film Reynolds equation to hold"),
            ("length", self.length, 0.05 <= self.length / (2 * r) <= 10.0,
             f"must give 0.05 <= L/D <= 10 (D = {2 * r!r} m)"),
            ("bump_half_length", l0, 2 * l0 <= s, f"must satisfy 2 l0 <= s (a bump spans 2 l0 "
             f"and must fit in its pitch s = {s!r} m)"),
            ("bump_thickness", tb, tb < l0, f"must be < the half bump length l0 = {l0!r} m "
             "(each half bump is a slender beam in Heshmat's compliance formula)"),
            ("bump_pitch", s, s <= math.pi * r, f"must be <= π R = {math.pi * r:.6g} m (at "
             "least two bumps round the bearing)"),
            ("top_foil_thickness", self.top_foil_thickness, self.top_foil_thickness <= 0.1 * r,
             f"must be <= R/10 = {0.1 * r:.6g} m (a thin top foil)"))
        for name, value, holds, rule in rules:
            if not holds:
                raise ParameterError(name, value, rule)
        from .model import MAX_COMPLIANCE, MAX_TOP_FOIL_COEFFICIENT

        if not self.compliance <= MAX_COMPLIANCE:
            raise ParameterError("bump_thickness", tb, f"gives a bump compliance S = "
                                 f"{self.compliance:.3g} above {MAX_COMPLIANCE:g} (a foundation "
                                 "1000 times softer than the thesis's S = 1): a thicker or "
                                 "shorter bump")
        if not self.top_foil_coefficient <= MAX_TOP_FOIL_COEFFICIENT:
            raise ParameterError("top_foil_thickness", self.top_foil_thickness, f"gives a "
                                 f"top-foil coefficient C = {self.top_foil_coefficient:.3g} "
                                 f"above {MAX_TOP_FOIL_COEFFICIENT:g}")

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
        """W̄ = W/(p_a R²) for a static load ``load_newton`` [N], at least
        :data:`~gfbopt.inputs.rotor_limits.MIN_LOAD_RATIO` p_a R² (below it the bearing is
        unloaded) and at most :data:`~gfbopt.inputs.rotor_limits.MAX_SPECIFIC_LOAD_RATIO`
        p_a L D (100 bar on the projected area at 1 bar ambient: no gas bearing carries it)."""
        from .rotor_limits import MAX_SPECIFIC_LOAD_RATIO, MIN_LOAD_RATIO

        load = check_positive("load_newton", load_newton)
        floor = MIN_LOAD_RATIO * self.ambient_pressure * self.radius ** 2
        if load < floor:
            raise ParameterError("load_newton", load_newton, f"must be >= {MIN_LOAD_RATIO:g} "
                                 f"p_a R² = {floor:.3g} N: below it the bearing is unloaded "
                                 "(a foil bearing's film needs a load to find its equilibrium)")
        ceiling = MAX_SPECIFIC_LOAD_RATIO * self.ambient_pressure * self.length * 2 * self.radius
        if load > ceiling:
            raise ParameterError("load_newton", load_newton, f"must be <= "
                                 f"{MAX_SPECIFIC_LOAD_RATIO:g} p_a L D = {ceiling:.4g} N (100 "
                                 "bar on the projected area at 1 bar ambient; gas foil "
                                 "bearings carry at most about a tenth of it)")
        return load_to_nondimensional(load, self.ambient_pressure, self.radius)

    def load_newton(self, load: float) -> float:
        """W [N] for a non-dimensional load W̄ [-]."""
        return load_to_newton(load, self.ambient_pressure, self.radius)

    def model(self, speed_rpm: float, foil: str = "simple", **kwargs) -> "BearingModel":
        """The non-dimensional :class:`BearingModel` of this bearing at ``speed_rpm`` [rpm].

        ``foil='rigid'`` sets S = 0; other keyword arguments go to BearingModel.
        """
        compliance = 0.0 if foil == "rigid" else self.compliance
        if "hardening_limit_m" in kwargs:         # the hardening bump's limit δ_lim [m] → δ_lim/c
            kwargs["hardening_limit"] = kwargs.pop("hardening_limit_m") / self.radial_clearance
        if self.build is not None and "as_built" not in kwargs:
            built = self.build.nondimensional(self)
            if foil == "rigid" and (built.zones or built.pads):
                raise ParameterError("foil", foil, "a rigid bearing has no top foil or bumps: "
                                     "the bearing's [[zones]] and [[pads]] would be ignored "
                                     "(remove them, or choose foil 'simple' or 'beam')")
            if built.zones:
                compliance = built.mean_compliance()
            kwargs["as_built"] = built
        return BearingModel(bearing_number=self.bearing_number(speed_rpm),
                            compliance=compliance,
                            length_ratio=self.length_ratio,
                            top_foil_coefficient=self.top_foil_coefficient,
                            foil=foil, **kwargs)
