"""Inputs: the dimensional bearing, the non-dimensional model and the conversions between them.

All conversions between SI quantities and the non-dimensional groups of the Reynolds
equation live in this module and nowhere else (see ``docs/ARCHITECTURE.md``).

Non-dimensional groups (PHYSICS.md):

=========  =====================================================  =========================
symbol     definition                                             here
=========  =====================================================  =========================
Λ          6 μ ω R² / (p_a c²)                                    ``bearing_number``
α          2 s l0³ (1 − ν²) / (E_b t_b³)   [m³/N] (Heshmat 1983)  ``bump_compliance``
S          p_a α / c                                              ``compliance``
C          E_t I_t c / (R⁴ L p_a),  I_t = L t_t³ / 12             ``top_foil_coefficient``
W̄          W / (p_a R²)                                           ``load``
=========  =====================================================  =========================
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Optional

from .errors import ParameterError

FOIL_MODELS = ("rigid", "simple", "beam")
FILM_MODELS = ("periodic", "seam")
DEFLECTION_LAWS = ("mean", "local")
SUBAMBIENT_TREATMENTS = ("full", "gumbel")


# ---------------------------------------------------------------------------- checks
def _finite(name: str, value: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be a real number") from None
    if not math.isfinite(v):
        raise ParameterError(name, value, "must be finite (not NaN or infinite)")
    return v


def check_positive(name: str, value: float) -> float:
    """Return ``value`` as float; raise ParameterError unless finite and > 0."""
    v = _finite(name, value)
    if v <= 0.0:
        raise ParameterError(name, value, "must be > 0")
    return v


def check_nonnegative(name: str, value: float) -> float:
    """Return ``value`` as float; raise ParameterError unless finite and ≥ 0."""
    v = _finite(name, value)
    if v < 0.0:
        raise ParameterError(name, value, "must be >= 0")
    return v


def check_choice(name: str, value: str, choices: tuple[str, ...]) -> str:
    if value not in choices:
        raise ParameterError(name, value, f"must be one of {', '.join(choices)}")
    return value


# ----------------------------------------------------------------------- conversions
def rpm_to_rad_per_s(speed_rpm: float) -> float:
    """Shaft speed [rpm] → angular speed ω [rad/s]."""
    return check_positive("speed_rpm", speed_rpm) * 2.0 * math.pi / 60.0


def bearing_number_from_speed(viscosity: float, omega: float, radius: float,
                              ambient_pressure: float, radial_clearance: float) -> float:
    """Bearing number Λ = 6 μ ω R² / (p_a c²) [-].

    viscosity μ [Pa s], omega ω [rad/s], radius R [m], ambient_pressure p_a [Pa],
    radial_clearance c [m].
    """
    return 6.0 * viscosity * omega * radius**2 / (ambient_pressure * radial_clearance**2)


def bump_compliance(bump_pitch: float, bump_half_length: float, bump_thickness: float,
                    bump_youngs_modulus: float, poisson_ratio: float) -> float:
    """Bump-foil compliance per unit area α = 2 s l0³ (1 − ν²) / (E_b t_b³) [m³/N].

    Heshmat, Walowit & Pinkus (1983), J. Lubr. Technol. 105(4):647, doi:10.1115/1.3254698.
    bump_pitch s [m], bump_half_length l0 [m], bump_thickness t_b [m], E_b [Pa], ν [-].
    """
    return (2.0 * bump_pitch * bump_half_length**3 * (1.0 - poisson_ratio**2)
            / (bump_youngs_modulus * bump_thickness**3))


def compliance_from_alpha(alpha: float, ambient_pressure: float, radial_clearance: float) -> float:
    """Compliance coefficient S = p_a α / c [-]; α [m³/N], p_a [Pa], c [m]."""
    return ambient_pressure * alpha / radial_clearance


def top_foil_coefficient_from_geometry(top_foil_youngs_modulus: float, top_foil_thickness: float,
                                       radius: float, length: float, ambient_pressure: float,
                                       radial_clearance: float) -> float:
    """Top-foil bending coefficient C = E_t I_t c / (R⁴ L p_a), I_t = L t_t³/12 [-].

    E_t [Pa], t_t [m], R [m], L [m], p_a [Pa], c [m].
    """
    second_moment = length * top_foil_thickness**3 / 12.0
    return (top_foil_youngs_modulus * second_moment * radial_clearance
            / (radius**4 * length * ambient_pressure))


def load_to_nondimensional(load_newton: float, ambient_pressure: float, radius: float) -> float:
    """Static load W [N] → W̄ = W / (p_a R²) [-]."""
    return load_newton / (ambient_pressure * radius**2)


def load_to_newton(load: float, ambient_pressure: float, radius: float) -> float:
    """W̄ = W / (p_a R²) [-] → W [N]."""
    return load * ambient_pressure * radius**2


# ------------------------------------------------------------------ dimensional input
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

    def __post_init__(self) -> None:
        for key in ("radius", "length", "radial_clearance", "bump_pitch", "bump_half_length",
                    "bump_thickness", "bump_youngs_modulus", "top_foil_youngs_modulus",
                    "top_foil_thickness", "viscosity", "ambient_pressure"):
            object.__setattr__(self, key, check_positive(key, getattr(self, key)))
        nu = _finite("poisson_ratio", self.poisson_ratio)
        if not -1.0 < nu < 0.5:
            raise ParameterError("poisson_ratio", self.poisson_ratio, "must lie in (-1, 0.5)")
        object.__setattr__(self, "poisson_ratio", nu)
        if self.radial_clearance > 0.01 * self.radius:
            raise ParameterError(
                "radial_clearance", self.radial_clearance,
                f"must be small against the radius (c/R <= 0.01; R = {self.radius!r} m) "
                "for the thin-film Reynolds equation to hold")

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
        return BearingModel(bearing_number=self.bearing_number(speed_rpm),
                            compliance=compliance,
                            length_ratio=self.length_ratio,
                            top_foil_coefficient=self.top_foil_coefficient,
                            foil=foil, **kwargs)


# -------------------------------------------------------------- non-dimensional input
@dataclass(frozen=True)
class BearingModel:
    """The non-dimensional bearing model solved by gfbopt.

    Attributes
    ----------
    bearing_number : Λ = 6 μ ω R²/(p_a c²) [-], > 0
    compliance : S = p_a α / c [-], ≥ 0 (0 = rigid plain gas bearing)
    length_ratio : L/D [-], > 0
    foil : 'rigid', 'simple' (W = S (P̄ − 1)) or 'beam' (1D FE top foil on the bumps)
    top_foil_coefficient : C [-], ≥ 0, used by the beam model only
    film : 'periodic' (no seam) or 'seam' (P = 1 at the top-foil ends)
    seam_angle : angle of the welded (fixed) end of the top foil measured from the load line
        in the direction of rotation [rad]; ``None`` puts the seam at the maximum-film line
        (the thesis's convention: θ measured from the line of centres, P = 1 at θ = 0, 2π).
        For a periodic film it only places the fixed end of the beam foil.
    compression_only : if True the bumps cannot pull the foil towards the journal (W ≥ 0
        for the simple model; the bump reaction acts only where W > 0 for the beam).
    deflection_law : 'mean' — the foil deflects with the axially averaged pressure,
        W = S (P̄ − 1) (thesis, Heshmat's strip model); 'local' — with the local pressure,
        W = S (P − 1) (simple model only).
    subambient : 'full' — the whole film pressure acts on the journal; 'gumbel' — gauge
        pressure below ambient is dropped from the force integral,
        F = −∬ max(P − 1, 0)(cos θ, sin θ) dθ dZ (the convention that reproduces the Λ = 1
        rows of thesis Table 3.2; docs/literature_table_3_2.md).  The pressure field itself
        is the full-film solution in both cases.
    """

    bearing_number: float
    compliance: float = 0.0
    length_ratio: float = 1.0
    foil: str = "simple"
    top_foil_coefficient: float = 0.0
    film: str = "periodic"
    seam_angle: Optional[float] = None
    compression_only: bool = False
    deflection_law: str = "mean"
    subambient: str = "full"

    def __post_init__(self) -> None:
        object.__setattr__(self, "bearing_number",
                           check_positive("bearing_number", self.bearing_number))
        object.__setattr__(self, "compliance", check_nonnegative("compliance", self.compliance))
        object.__setattr__(self, "length_ratio", check_positive("length_ratio", self.length_ratio))
        object.__setattr__(self, "top_foil_coefficient",
                           check_nonnegative("top_foil_coefficient", self.top_foil_coefficient))
        check_choice("foil", self.foil, FOIL_MODELS)
        check_choice("film", self.film, FILM_MODELS)
        check_choice("deflection_law", self.deflection_law, DEFLECTION_LAWS)
        check_choice("subambient", self.subambient, SUBAMBIENT_TREATMENTS)
        if self.deflection_law == "local" and self.foil == "beam":
            raise ParameterError("deflection_law", self.deflection_law,
                                 "'local' applies to the simple foil model only (the beam is "
                                 "loaded by the axially averaged pressure)")
        if not isinstance(self.compression_only, (bool, int)) or self.compression_only not in (0, 1):
            raise ParameterError("compression_only", self.compression_only, "must be true or false")
        object.__setattr__(self, "compression_only", bool(self.compression_only))
        if self.foil == "rigid" and self.compliance != 0.0:
            object.__setattr__(self, "compliance", 0.0)
        if self.seam_angle is not None:
            object.__setattr__(self, "seam_angle", _finite("seam_angle", self.seam_angle))
        if self.length_ratio > 10.0:
            raise ParameterError("length_ratio", self.length_ratio, "must be <= 10")

    @property
    def is_rigid(self) -> bool:
        return self.foil == "rigid" or self.compliance == 0.0

    def replace(self, **changes) -> "BearingModel":
        """A copy with ``changes`` applied (validated again)."""
        return replace(self, **changes)


@dataclass(frozen=True)
class Grid:
    """Finite-difference grid: ``n_theta`` intervals round the bearing, ``n_z`` axially.

    Periodic film: nodes θ_i = θ_0 + 2π i/n_theta, i = 0..n_theta−1.  Seam film: nodes
    i = 0..n_theta with P = 1 at both ends.  Axially Z_j = −L/D + j·2(L/D)/n_z,
    j = 0..n_z, with P = 1 at j = 0 and j = n_z.
    """

    n_theta: int = 72
    n_z: int = 20

    def __post_init__(self) -> None:
        for key, low in (("n_theta", 12), ("n_z", 4)):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, int):
                raise ParameterError(f"grid {key}", value, "must be an integer")
            if value < low:
                raise ParameterError(f"grid {key}", value, f"must be >= {low} (grid too coarse)")
            if value > 2000:
                raise ParameterError(f"grid {key}", value, "must be <= 2000")
        if self.n_z % 2:
            raise ParameterError("grid n_z", self.n_z,
                                 "must be even (a node on the mid-plane Z = 0)")

    @classmethod
    def parse(cls, text: str) -> "Grid":
        """Grid from 'NTHETAxNZ', e.g. '72x20'."""
        parts = str(text).lower().split("x")
        if len(parts) != 2 or not all(p.strip().isdigit() for p in parts):
            raise ParameterError("grid", text, "must be written NTHETAxNZ, e.g. 72x20")
        return cls(int(parts[0]), int(parts[1]))

    def __str__(self) -> str:
        return f"{self.n_theta}x{self.n_z}"


#: Default grid: its load error is <= 0.5 % of the grid-converged value over the validation
#: cases up to ε = 0.9 (results/grid_convergence).  72 × 20 is 4× cheaper and within 0.5 % up
#: to ε ≈ 0.6, 1.7 % at ε = 0.9.
DEFAULT_GRID = Grid(144, 36)
