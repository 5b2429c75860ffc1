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
