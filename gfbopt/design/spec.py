"""Inputs and results of the bump-foil geometric program (SI units throughout).

:class:`BumpDesignSpec` holds the clearance, the material, the design pressure, the ranges of
the geometry and the limits; :class:`BumpDesign` is the answer with its binding constraints;
:class:`Relaxation` says how far a limit must move when the limits admit no geometry.
Validation happens here, before any solve (``ParameterError`` with one line naming the
parameter, its value and the rule).  The program itself is in
:mod:`gfbopt.design.geometry_program`.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from ..errors import ParameterError
from .materials import Material, get_material

#: Monomials that can be minimised.  Ties (several geometries with the same objective) are
#: broken by the least bump stress.
OBJECTIVES = ("stress", "pitch", "number_of_bumps", "thickness", "half_length",
              "top_foil_thickness", "top_foil_sag")


# ---------------------------------------------------------------------------- checks
def _positive(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be a real number") from None
    if not math.isfinite(v) or v <= 0.0:
        raise ParameterError(name, value, "must be finite and > 0")
    return v


def _optional_positive(name: str, value) -> float | None:
    return None if value is None else _positive(name, value)


def _range(name: str, value) -> tuple[float, float]:
    try:
        low, high = value
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be a pair (low, high)") from None
    low, high = _positive(f"{name} low", low), _positive(f"{name} high", high)
    if low >= high:
        raise ParameterError(name, value, "low must be < high")
    return low, high


def _mm(x: float) -> str:
    return f"{x * 1e3:.4g} mm"


def _um(x: float) -> str:
    return f"{x * 1e6:.4g} µm"


def _mpa(x: float) -> str:
    return f"{x * 1e-6:.4g} MPa"


# ------------------------------------------------------------------------------ spec
@dataclass(frozen=True)
class BumpDesignSpec:
    """What a bump foil must satisfy.  SI units throughout.

    Attributes
    ----------
    radial_clearance : radial clearance c [m]
    radius : bearing radius R [m]; when given the number of bumps 2πR/s is made whole
    ambient_pressure : ambient pressure p_a [Pa] (default 101325)
    material : registered material name or a :class:`Material` (default Inconel X-750 at
        20 °C); stored as a Material
    youngs_modulus, poisson_ratio, allowable_stress : override the material's E [Pa], ν [-]
        and σ_allow [Pa] (None: the material's value)
    design_pressure : film pressure above ambient the foil must carry, Δp [Pa] (default 1 bar)
    pitch_range : (low, high) bump pitch s [m] (default 2–6 mm)
    half_length_range : (low, high) half bump length l0 [m] (default 0.5–3 mm)
    thickness_range : (low, high) bump foil thickness t_b [m] (default 50–200 µm)
    gap : flat length between neighbouring bumps: 2 l0 + gap ≤ s [m] (default 0.2 mm)
    top_foil_thickness_range : (low, high) top-foil thickness t_top [m]; when given the top foil
        is designed too, its stress Δp s²/(2 t_top²) is limited and the thinnest top foil that
        meets its limits is returned (unless a top-foil objective is chosen)
    sag_limit : κ_c, top-foil sag ≤ κ_c c [-] (needs top_foil_thickness_range)
    top_foil_allowable_stress : top-foil stress limit [Pa] (default: the allowable stress)
    flattening_limit : κ in the no-flattening limit Δp α ≤ κ h_b, 0 < κ ≤ 1 [-]
    bump_height : free bump height h_b [m] (given with flattening_limit)
    objective : monomial to minimise, one of :data:`OBJECTIVES` (default 'stress')
    """

    radial_clearance: float
    radius: float | None = None
    ambient_pressure: float = 101325.0
    material: str | Material = "inconel-x750"
    youngs_modulus: float | None = None
    poisson_ratio: float | None = None
    allowable_stress: float | None = None
    design_pressure: float = 1e5
    pitch_range: tuple[float, float] = (2e-3, 6e-3)
    half_length_range: tuple[float, float] = (0.5e-3, 3e-3)
    thickness_range: tuple[float, float] = (50e-6, 200e-6)
    gap: float = 0.2e-3
    top_foil_thickness_range: tuple[float, float] | None = None
    sag_limit: float | None = None
    top_foil_allowable_stress: float | None = None
    flattening_limit: float | None = None
    bump_height: float | None = None
    objective: str = "stress"

    def __post_init__(self) -> None:
        def put(key, value):
            object.__setattr__(self, key, value)

        for key in ("radial_clearance", "ambient_pressure", "design_pressure"):
            put(key, _positive(key, getattr(self, key)))
        for key in ("radius", "youngs_modulus", "allowable_stress", "sag_limit",
                    "top_foil_allowable_stress", "flattening_limit", "bump_height"):
            put(key, _optional_positive(key, getattr(self, key)))
        gap = self.gap
        try:
            gap = float(gap)
        except (TypeError, ValueError):
            raise ParameterError("gap", self.gap, "must be a real number") from None
        if not math.isfinite(gap) or gap < 0.0:
            raise ParameterError("gap", self.gap, "must be finite and >= 0")
        put("gap", gap)
        if isinstance(self.material, str):
            put("material", get_material(self.material))
        elif not isinstance(self.material, Material):
            raise ParameterError("material", self.material,
                                 "must be a material name or a Material")
        if self.poisson_ratio is not None:
            nu = self.poisson_ratio
            if not (isinstance(nu, (int, float)) and -1.0 < nu < 0.5):
                raise ParameterError("poisson_ratio", nu, "must lie in (-1, 0.5)")
            put("poisson_ratio", float(nu))
        for key in ("pitch_range", "half_length_range", "thickness_range"):
            put(key, _range(key, getattr(self, key)))
        if self.top_foil_thickness_range is not None:
            put("top_foil_thickness_range",
                _range("top_foil_thickness_range", self.top_foil_thickness_range))
        else:
            for key in ("sag_limit", "top_foil_allowable_stress"):
                if getattr(self, key) is not None:
                    raise ParameterError(key, getattr(self, key),
                                         "needs top_foil_thickness_range (the top foil is "
                                         "not designed without it)")
        if (self.flattening_limit is None) != (self.bump_height is None):
            raise ParameterError("flattening_limit", self.flattening_limit,
                                 "needs bump_height too (Δp α <= κ h_b uses both)")
        if self.flattening_limit is not None and self.flattening_limit > 1.0:
            raise ParameterError("flattening_limit", self.flattening_limit,
                                 "must be <= 1 (a fraction of the bump height)")
        if self.objective not in OBJECTIVES:
            raise ParameterError("objective", self.objective,
                                 f"must be one of {', '.join(OBJECTIVES)}")
        if self.objective.startswith("top_foil") and self.top_foil_thickness_range is None:
            raise ParameterError("objective", self.objective, "needs top_foil_thickness_range")
        shortest = 2.0 * self.half_length_range[0] + self.gap
        if shortest > self.pitch_range[1]:
            raise ParameterError(
                "half_length_range", self.half_length_range,
                f"2 x shortest half length + gap = {_mm(shortest)} exceeds the largest pitch "
                f"{_mm(self.pitch_range[1])}: no bump closes within its pitch")
        if self.radius is not None:
            n_min, n_max = self.bump_count_range
            if n_min > n_max:
                raise ParameterError(
                    "radius", self.radius,
                    f"no whole number of bumps N gives a pitch 2πR/N within "
                    f"[{_mm(self.pitch_range[0])}, {_mm(self.pitch_range[1])}]")

    # Resolved values -----------------------------------------------------------
    @property
    def effective_youngs_modulus(self) -> float:
        """E [Pa]: the override, else the material's."""
        return (self.material.youngs_modulus if self.youngs_modulus is None
                else self.youngs_modulus)

    @property
    def effective_poisson_ratio(self) -> float:
        """ν [-]: the override, else the material's."""
        return self.material.poisson_ratio if self.poisson_ratio is None else self.poisson_ratio

    @property
    def effective_allowable_stress(self) -> float:
        """Bump allowable stress σ_allow [Pa]: the override, else the material's."""
        return (self.material.allowable_stress if self.allowable_stress is None
                else self.allowable_stress)

    @property
    def effective_top_foil_allowable_stress(self) -> float:
        """Top-foil allowable stress [Pa] (default: the bump allowable stress)."""
        return (self.effective_allowable_stress if self.top_foil_allowable_stress is None
                else self.top_foil_allowable_stress)

    @property
    def bump_count_range(self) -> tuple[int, int]:
        """(N_min, N_max): whole numbers of bumps whose pitch 2πR/N lies in pitch_range."""
        if self.radius is None:
            raise ParameterError("radius", None, "is needed for a number of bumps")
        circumference = 2.0 * math.pi * self.radius
        return (max(1, math.ceil(circumference / self.pitch_range[1] - 1e-9)),
                math.floor(circumference / self.pitch_range[0] + 1e-9))

    def to_dict(self) -> dict:
        """Inputs and resolved material values as a plain dict (SI units)."""
        out = asdict(self)
        out["material"] = self.material.to_dict()
        out.update(youngs_modulus=self.effective_youngs_modulus,
                   poisson_ratio=self.effective_poisson_ratio,
                   allowable_stress=self.effective_allowable_stress)
        if self.top_foil_thickness_range is not None:
            out["top_foil_allowable_stress"] = self.effective_top_foil_allowable_stress
        return out


# ---------------------------------------------------------------------------- result
@dataclass(frozen=True)
class Relaxation:
    """A limit that must move for the design to exist.

    Attributes
    ----------
    limit : what moves, e.g. 'allowable stress'
    factor : required / current value (> 1)
    current, required : the limit now and the least value that makes the design feasible,
        in ``unit``
    unit : unit of current and required ('MPa', 'µm' or '' for a ratio)
    """

    limit: str
    factor: float
    current: float
    required: float
    unit: str

    def describe(self) -> str:
        """E.g. 'allowable stress must rise by 23 % (to 295 MPa)'."""
        to = f"{self.required:.4g} {self.unit}".rstrip()
        return f"{self.limit} must rise by {100.0 * (self.factor - 1.0):.3g} % (to {to})"


@dataclass(frozen=True)
class BumpDesign:
    """A designed bump foil, or why there is none.  SI units.

    Attributes
    ----------
    status : solver status of the final GP ('optimal', 'optimal_inaccurate', 'infeasible', …)
    success : True when a geometry meeting every constraint was found
    message : one paragraph: the optimum, or which limits must move and by how much
    target_compliance : (low, high) target S [-] (low == high for a single value)
    objective : the monomial minimised
    pitch, half_length, thickness : bump pitch s, half length l0, thickness t_b [m]
        (NaN without success)
    top_foil_thickness : t_top [m], None when the top foil is not designed
    compliance : S = p_a α / c of the returned geometry [-]
    bump_compliance : α [m³/N]
    bump_stress : σ_b at the design pressure [Pa]
    bump_deflection : Δp α [m]
    top_foil_sag, top_foil_stress : [m], [Pa], None when the top foil is not designed
    number_of_bumps : whole N = 2πR/s, None without a radius
    binding_constraints : names of the constraints active at the optimum
    compliance_range : (min, max) S achievable under every constraint (NaN if none)
    geometric_compliance_range : (min, max) S under the geometry constraints alone
    relaxations : the limits that must move (empty on success)
    solver : the conic solver cvxpy used
    solves : number of GPs the design needs (the four of the compliance ranges included:
        they are solved once per spec in a process and kept)
    wall_time_s : wall time of the whole design [s]
    """

    status: str
    success: bool
    message: str
    target_compliance: tuple[float, float]
    objective: str
    pitch: float
    half_length: float
    thickness: float
    top_foil_thickness: float | None
    compliance: float
    bump_compliance: float
    bump_stress: float
    bump_deflection: float
    top_foil_sag: float | None
    top_foil_stress: float | None
    number_of_bumps: int | None
    binding_constraints: tuple[str, ...]
    compliance_range: tuple[float, float]
    geometric_compliance_range: tuple[float, float]
    relaxations: tuple[Relaxation, ...]
    solver: str
    solves: int
    wall_time_s: float

    def to_dict(self) -> dict:
        """The result as a plain dict (tuples as lists, relaxations as dicts)."""
        out = asdict(self)
        for key in ("target_compliance", "binding_constraints", "compliance_range",
                    "geometric_compliance_range"):
            out[key] = list(out[key])
        out["relaxations"] = [dict(asdict(r), description=r.describe())
                              for r in self.relaxations]
        return out
