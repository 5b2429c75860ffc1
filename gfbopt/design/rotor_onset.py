"""The first onset over all modes of a design along its rotor's speed line (the part of
:mod:`gfbopt.design.rotor_objectives` that finds it; SI, speeds in rpm): the scan upwards
to the first bracket and Brent's method there, or, from a nearby problem's onset, the
rotor's one onset secant (:func:`gfbopt.rotor.speed_line.secant_root`)."""
from __future__ import annotations

import math
from typing import Optional

from ..errors import ParameterError


#: relative tolerance of the first onset speed in a design search [-]: 1e-3 of the speed
#: (≈ 15 rpm at 15 krpm), far below what separates designs worth comparing
ONSET_TOLERANCE = 1e-3


def _lowest(line, speed: float):
    """The crossing with the least inertia scale μ_c over every mode at ``speed`` (None: no
    crossing; the string 'capacity' when a bearing cannot carry its load there)."""
    found = line.crossings(speed)
    if found is None:
        return "capacity"
    return min(found, key=lambda c: c.inertia_scale, default=None)


def first_onset(line, settings, near: Optional[float] = None) -> dict:
    """The first onset over all modes along the speed line (an adapter over the rotor's
    :class:`~gfbopt.rotor.system.SpeedLine`, cheaper than ``rotor_onsets`` for a search):
    the speeds of ``rotor_onsets``'s scan are visited upwards only until some mode's μ_c
    falls through 1, and that bracket is refined by Brent's method on the least μ_c over
    all modes, m(ω) = min_k (μ_k − 1)/(μ_k + 1) (continuous whichever mode is least, so no
    mode need be followed), to :data:`ONSET_TOLERANCE`.  The modes above the first onset,
    which ``rotor_onsets`` refines too, do not change a design's merit.

    ``near``: the first onset [rpm] of a nearby problem whose scan was stable below it (the
    same design on the search grid or at another loss factor, or a toleranced design's
    nominal): the secant refinement starts there instead (:func:`_secant_near`, to 1e-5;
    the scan from the lowest speed when it does not converge).  The assumption: μ_c
    changes less between the two problems than between neighbouring scan speeds (≥ 1.25²
    ≈ 1.56×), so the speeds below stay stable (on the blower grid and η change μ_c by
    3–8 %, ±1 µm of clearance or preload by ≤ 10 %)."""
    from scipy.optimize import brentq

    from ..rotor.system import scan_speeds

    def margin(speed: float) -> float:
        c = _lowest(line, speed)
        if c == "capacity":
            raise ParameterError("load", speed, "exceeds a bearing's capacity at this speed")
        return 1.0 if c is None else (c.inertia_scale - 1.0) / (c.inertia_scale + 1.0)

    low, high = settings.speed_low_rpm, settings.search_high_rpm
    speeds = scan_speeds(low, high)
    root = _secant_near(line, speeds, near) if near is not None else None
    if root is not None:
        return _onset_row(line, settings, root, None)
    previous = bracket = None
    for speed in speeds:
        c = _lowest(line, speed)
        if c == "capacity":
            continue
        if c is None or c.inertia_scale > 1.0:
            previous = speed
            continue
        if previous is None:
            return {"first_onset_speed_rpm": low, "onset_status": "unstable at the lowest "
                    "speed", "first_mode": c.label, "onset_whirl_frequency_hz": math.nan,
                    "stable_to_top_speed": False}
        bracket = previous, speed, c
        break
    if bracket is not None:
        previous, speed, c = bracket
        root = brentq(margin, previous, speed, xtol=ONSET_TOLERANCE * previous,
                      rtol=ONSET_TOLERANCE)
        return _onset_row(line, settings, root, c)
    if previous is None:
        raise ParameterError("speed range", (low, high), "no speed where both bearings "
                             "carry their loads")
    return {"first_onset_speed_rpm": high, "onset_status": "stable over the range",
            "first_mode": "", "onset_whirl_frequency_hz": math.nan,
            "stable_to_top_speed": True}


def _onset_row(line, settings, root: float, unstable) -> dict:
    """The onset columns at ``root`` [rpm]: the mode and whirl frequency of its least
    crossing (``unstable``'s mode when it has none)."""
    at = _lowest(line, root)
    found = at not in (None, "capacity")
    return {"first_onset_speed_rpm": root, "onset_status": "onset",
            "first_mode": at.label if found else getattr(unstable, "label", ""),
            "onset_whirl_frequency_hz": at.whirl_frequency_hz if found else math.nan,
            "stable_to_top_speed": bool(root >= settings.top_speed_rpm)}


#: the refinement from a nearby onset stops when the secant step from its latest speed (that
#: speed's error, superlinear convergence) is at most this on ln N [-], a hundredth of the
#: search's :data:`ONSET_TOLERANCE` (it gives up after secant_root's ``SECANT_STEPS``)
NEAR_TOLERANCE = ONSET_TOLERANCE / 100


class _LeastMargin:
    """The speed line as :func:`gfbopt.rotor.speed_line.secant_root` reads it: g = ln μ_c,
    least over every mode, at a speed [rpm] (``full`` and ``local`` alike: the rotor's
    crossings have one threshold); LookupError where a bearing is over capacity, a mode has
    no crossing or μ_c ≤ 0."""

    def __init__(self, line):
        self.line = line

    def full(self, speed: float) -> dict:
        c = _lowest(self.line, speed)
        if c in (None, "capacity") or c.inertia_scale <= 0.0:
            raise LookupError
        return {"g": math.log(c.inertia_scale)}

    local = full


def _secant_near(line, speeds: list, near: float) -> Optional[float]:
    """The first onset [rpm] by secant steps on g = ln μ_c (least over every mode) against
    ln N from ``near`` with the slope of μ_c ∝ N⁻² (as the rotor's refinement,
    :mod:`gfbopt.rotor.mode_search`), inside the scan intervals next to ``near`` — the
    rotor's one onset secant, :func:`gfbopt.rotor.speed_line.secant_root`, to
    :data:`NEAR_TOLERANCE` on ln N: typically 3 speeds.  None (then the scan from the lowest
    speed) when a step leaves those intervals without a bracket, a bearing is over
    capacity, a mode has no crossing, μ_c does not fall with speed or the secant does not
    converge."""
    from ..rotor.mode_search import NOMINAL_SLOPE
    from ..rotor.speed_line import secant_root

    k = next((j for j, s in enumerate(speeds) if s >= near), 0)
    if k == 0 or near > speeds[-1]:
        return None
    low, high = speeds[max(k - 2, 0)], speeds[min(k + 1, len(speeds) - 1)]
    margin = _LeastMargin(line)
    try:
        u0 = math.log(near)
        g0 = margin.full(near)["g"]
        found = secant_root(margin, low, high, NEAR_TOLERANCE, start=[(u0, g0)],
                            first=u0 - g0 / NOMINAL_SLOPE)
    except LookupError:                 # a bearing over capacity or a mode without crossing
        return None
    if found is None:
        return None
    at_start = abs(found[0] - u0) <= NEAR_TOLERANCE     # no step taken: no slope measured
    if not (found[1] < 0.0 or (at_start and math.isnan(found[1]))):
        return None                                      # μ_c does not fall with speed
    return math.exp(found[0])
