"""The rotor and its operating point in SI units (the engineer's inputs to a stability check)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

from ..errors import ParameterError
from .checks import check_positive
from .conversions import rotor_weight_newton


@dataclass(frozen=True)
class Rotor:
    """A rigid rotor, described per bearing.

    Attributes
    ----------
    mass_kg : rotor mass carried by one bearing M [kg], > 0.  A symmetric rotor of total
        mass 2M on two identical bearings has ``mass_kg = M`` (docs/PHYSICS.md §2).
    """

    mass_kg: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass_kg", check_positive("mass_kg", self.mass_kg))
        if not math.isfinite(rotor_weight_newton(self.mass_kg)):
            raise ParameterError("mass_kg", self.mass_kg, "must weigh a finite M g [N] (a "
                                 "rotor mass per bearing)")


@dataclass(frozen=True)
class OperatingPoint:
    """Shaft speed and static load on one bearing.

    Attributes
    ----------
    speed_rpm : shaft speed N [rpm], > 0
    load_newton : static load on the bearing W0 [N], > 0; ``None`` means the rotor's own
        weight, W0 = M g (a horizontal rigid rotor loaded by gravity only, g = 9.80665 m/s²)
    """

    speed_rpm: float
    load_newton: Optional[float] = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "speed_rpm", check_positive("speed_rpm", self.speed_rpm))
        if self.load_newton is not None:
            object.__setattr__(self, "load_newton",
                               check_positive("load_newton", self.load_newton))

    def load_on(self, rotor: Rotor) -> float:
        """W0 [N]: the stated load, or the rotor's weight M g when none is stated."""
        return self.load_newton if self.load_newton is not None else rotor_weight_newton(
            rotor.mass_kg)

    def load_source(self) -> str:
        """How W0 was obtained, for outputs."""
        return ("stated" if self.load_newton is not None
                else "rotor weight M g (horizontal rigid rotor, g = 9.80665 m/s²)")
