"""Foil materials: elastic constants and an allowable bending stress, each with its source.

The registry is a read-only mapping from a name to a frozen :class:`Material`; look a
material up with :func:`get_material`.  Values are SI.

Sources
-------
* Elastic modulus of INCONEL alloy X-750: 31.0 × 10⁶ psi = 214 GPa at 20 °C and
  26.7 × 10⁶ psi = 184 GPa at 538 °C (1000 °F), as tabulated from the Special Metals
  datasheet (INCONEL alloy X-750, Publication SMC-067, 2004) by the wire supplier Tokkin
  (tokkinwire.com, "Alloy X-750 (INCONEL X-750)").  Another distributor's table
  (jainsteels.in) gives 213.7 GPa at 27 °C and 172.4 GPa at 538 °C: the hot value differs by
  about 7 % between sources.  The 20 °C value is the one of the Ruscitto bearing
  (Ruscitto, McCormick & Gray 1978, NASA CR-135368, as listed in the thesis (Mohan, IIT Guwahati, 2010), Table 3.3).
* Poisson's ratio 0.29: the value of the Ruscitto bearing (same source); it is also the usual
  handbook value for nickel–chromium alloys.  Taken as temperature independent.
* Allowable stress: a design choice, half the minimum 0.2 % yield strength of UNS N07750
  heat-treated Type 1 (ASTM B637: 90 ksi = 620 MPa; as summarised on metalspiping.com,
  "Inconel X-750 Bars & Forgings (ASTM B637 UNS N07750)").  ASTM B637 covers bars and
  forgings; precipitation-hardened strip (AMS 5542/5598) is at least as strong, so the bar
  minimum is a conservative basis for foil.  The factor 1/2 covers the crude two-cantilever
  stress model and fatigue of a foil loaded once per revolution; it is not from a code.
  No sourced yield strength at 538 °C was found, so the hot entry keeps the room-temperature
  allowable: pass an explicit allowable stress for hot service.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from ..errors import ParameterError

__all__ = ["MATERIALS", "Material", "get_material", "material_names"]


@dataclass(frozen=True)
class Material:
    """An elastic foil material.

    Attributes
    ----------
    name : registry name
    youngs_modulus : Young's modulus E [Pa]
    poisson_ratio : Poisson's ratio ν [-]
    allowable_stress : allowable bending stress σ_allow [Pa]
    source : where the values come from, and which of them are design choices
    """

    name: str
    youngs_modulus: float
    poisson_ratio: float
    allowable_stress: float
    source: str

    def __post_init__(self) -> None:
        for key in ("youngs_modulus", "allowable_stress"):
            value = getattr(self, key)
            if not (isinstance(value, (int, float)) and value > 0.0):
                raise ParameterError(f"material {key}", value, "must be a number > 0")
        if not -1.0 < self.poisson_ratio < 0.5:
            raise ParameterError("material poisson_ratio", self.poisson_ratio,
                                 "must lie in (-1, 0.5)")

    def to_dict(self) -> dict:
        """The material as a plain dict (SI units)."""
        return {"name": self.name, "youngs_modulus_pa": self.youngs_modulus,
                "poisson_ratio": self.poisson_ratio,
                "allowable_stress_pa": self.allowable_stress, "source": self.source}


_X750_YIELD_MIN = 620e6  # Pa, ASTM B637 UNS N07750 Type 1, minimum 0.2 % yield strength
_X750_ALLOWABLE = 0.5 * _X750_YIELD_MIN
_X750_ALLOWABLE_BASIS = (
    "allowable stress 310 MPa = 0.5 x the 620 MPa (90 ksi) minimum 0.2 % yield strength of "
    "ASTM B637 UNS N07750 Type 1 (design choice)")

MATERIALS: Mapping[str, Material] = MappingProxyType({
    "inconel-x750": Material(
        name="inconel-x750", youngs_modulus=214e9, poisson_ratio=0.29,
        allowable_stress=_X750_ALLOWABLE,
        source=("INCONEL alloy X-750 at 20 C: E = 214 GPa (Special Metals SMC-067 via the "
                "Tokkin datasheet; Ruscitto et al. 1978, NASA CR-135368), nu = 0.29 (Ruscitto "
                f"et al. 1978); {_X750_ALLOWABLE_BASIS}")),
    "inconel-x750-538c": Material(
        name="inconel-x750-538c", youngs_modulus=184e9, poisson_ratio=0.29,
        allowable_stress=_X750_ALLOWABLE,
        source=("INCONEL alloy X-750 at 538 C (1000 F): E = 184 GPa (Special Metals SMC-067 "
                "via the Tokkin datasheet; another table gives 172 GPa), nu = 0.29 assumed "
                f"as at 20 C; {_X750_ALLOWABLE_BASIS}, NOT derated for temperature (no sourced "
                "hot yield strength): give an allowable stress for hot service")),
})


def material_names() -> tuple[str, ...]:
    """Names of the registered materials."""
    return tuple(MATERIALS)


def get_material(name: str) -> Material:
    """The registered material ``name``; ParameterError naming the known ones otherwise."""
    try:
        return MATERIALS[name]
    except (KeyError, TypeError):
        raise ParameterError("material", name,
                             f"unknown material; known: {', '.join(MATERIALS)}") from None
