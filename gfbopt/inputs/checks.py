"""Input checks shared by every input class: each raises ParameterError naming the value."""
from __future__ import annotations

import math

from ..errors import ParameterError


def check_finite(name: str, value: float) -> float:
    """Return ``value`` as float; raise ParameterError unless it is a finite real number."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be a real number") from None
    if not math.isfinite(v):
        raise ParameterError(name, value, "must be finite (not NaN or infinite)")
    return v


def check_positive(name: str, value: float) -> float:
    """Return ``value`` as float; raise ParameterError unless finite and > 0."""
    v = check_finite(name, value)
    if v <= 0.0:
        raise ParameterError(name, value, "must be > 0")
    return v


def check_nonnegative(name: str, value: float) -> float:
    """Return ``value`` as float; raise ParameterError unless finite and ≥ 0."""
    v = check_finite(name, value)
    if v < 0.0:
        raise ParameterError(name, value, "must be >= 0")
    return v


#: friction coefficients μ_f [-] accepted are 0 <= μ_f < this bound, by every route (file
#: schema, zones, BearingModel; the transients' slipping balance needs it)
FRICTION_COEFFICIENT_BELOW = 1.0
WHY_FRICTION = ("the slipping foil's balance W = S(1 − μ_f) q needs it: at μ_f >= 1 friction "
                "alone would carry the pressure; dry metal contacts lie near 0.1–1")


#: largest magnitude of a stated direction or phase [deg]: a turn either way (1e300° has no
#: direction left once wrapped)
MAX_ANGLE_DEG = 360.0


def check_angle_deg(name: str, value: float) -> float:
    """Return a direction or phase [deg] as float; ParameterError unless finite and within
    ±:data:`MAX_ANGLE_DEG`."""
    v = check_finite(name, value)
    if abs(v) > MAX_ANGLE_DEG:
        raise ParameterError(name, value, f"must lie in [-{MAX_ANGLE_DEG:g}, "
                             f"{MAX_ANGLE_DEG:g}] degrees (a direction, a turn either way)")
    return v


def check_choice(name: str, value: str, choices: tuple[str, ...]) -> str:
    """Return ``value`` unless it is not one of ``choices`` (ParameterError)."""
    if value not in choices:
        raise ParameterError(name, value, f"must be one of {', '.join(choices)}")
    return value


def check_flag(name: str, value) -> bool:
    """Return ``value`` as bool; only true/false (or 1/0) are accepted."""
    if not isinstance(value, (bool, int)) or value not in (0, 1):
        raise ParameterError(name, value, "must be true or false")
    return bool(value)


def check_loss_factor(value) -> float:
    """Return a structural loss factor η [-] as float; ParameterError unless 0 ≤ η ≤ 1.

    η is a fraction: the energy dissipated per cycle is 2π η times the peak elastic energy
    (phase lag arctan η between force and deflection); bump foils are usually quoted at
    0.1–0.5.  Values above 1 are refused as a likely percentage given by mistake.
    """
    eta = check_finite("loss_factor", value)
    if eta < 0.0:
        raise ParameterError("loss_factor", value, "must be >= 0 (a negative loss factor "
                             "would feed energy into the rotor)")
    if eta > 1.0:
        raise ParameterError("loss_factor", value, "must be <= 1 (a fraction: 0.2 means "
                             "20 %; bump foils are usually quoted at 0.1–0.5)")
    return eta


def check_seam_angle_deg(name: str, value, allow_max_film: bool = True):
    """A welded-end angle in degrees from the load line, in [0, 360), returned as float; or
    ``'max_film'`` (the seam on the maximum-film line) when ``allow_max_film``."""
    if allow_max_film and value == "max_film":
        return value
    if isinstance(value, bool):
        raise ParameterError(name, value, 'must be a number of degrees or "max_film"')
    angle = check_finite(name, value)
    if not 0.0 <= angle < 360.0:
        raise ParameterError(name, value, "must lie in [0, 360) degrees from the load line in "
                             "the direction of rotation")
    return angle


_ABSENT = object()


def refuse_radian_seam_angle(cls):
    """Class decorator: the keyword ``seam_angle`` (radians before gfbopt 0.3) is refused
    with the migration, so ``seam_angle=3.0`` can never silently mean 171.9°; the angle is
    ``seam_angle_deg`` (degrees) at every public edge."""
    init = cls.__init__

    def __init__(self, *args, seam_angle=_ABSENT, **kwargs):
        if seam_angle is not _ABSENT:
            raise ParameterError("seam_angle", seam_angle, seam_angle_migration(seam_angle))
        init(self, *args, **kwargs)

    __init__.__doc__ = init.__doc__
    __init__.__wrapped__ = init
    cls.__init__ = __init__
    return cls


def seam_angle_migration(value) -> str:
    """The rule shown for the old radian keyword ``seam_angle``.  Kept until gfbopt 0.4.0
    (CHANGELOG, Deprecated); from then the keyword is refused as unknown."""
    text = ("is no longer accepted: the welded-end angle is given in degrees as "
            "seam_angle_deg (from the load line in the direction of rotation, [0, 360), or "
            "'max_film'), as on the command line and in files")
    if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
        text += (f"; if {value!r} was meant in radians (gfbopt <= 0.2), write "
                 f"seam_angle_deg={math.degrees(value):.6g}")
    elif value is None or value == "max_film":
        text += "; for the seam on the maximum-film line write seam_angle_deg='max_film'"
    return text
