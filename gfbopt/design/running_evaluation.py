"""One trial S of the stability-driven bump design (:mod:`.stability_design`) at the running
condition: a bearing file stating ``[journal]``/``[thermal]`` gives the design's
:class:`~gfbopt.thermal.running.RunningSpec`, and each evaluated S (its bump thickness
changed, :func:`~gfbopt.design.stability_design.bearing_with_compliance`) is analysed with the
running clearance and viscosity at each speed, through the functions ``gfbopt stability``
and :mod:`gfbopt.api` call (:mod:`gfbopt.rotor.running_bearing`; no second heat balance):

* the merit: the onset of whirl of
  :func:`~gfbopt.rotor.running_bearing.running_onset` (searched from the geometric mean of
  the range, as ``gfbopt stability --bearing FILE --speed-range LOW HIGH`` does), the high
  end of the range when stable over it, the low end when unstable there, and the speed from
  which the bearing has no running state (thermal runaway, closure) when that comes first;
* the film check: :func:`~gfbopt.rotor.running_bearing.running_stability` at the film-check
  speed (``gfbopt stability --speed-rpm N``): h_min of that speed's own running clearance.

The heat balance sees the bump foil only through the film it carries (the drag of the warm
film), and the film sees the bump geometry only through S, so which geometry realises a
trial S still does not change its answer.
"""
from __future__ import annotations

import math

#: the running point's columns at the onset (glossary: gfbopt/terms/thermal.py)
RUNNING_POINT_COLUMNS = ("thermal_status", "running_clearance_um", "centrifugal_growth_um",
                         "thermal_growth_um", "film_temperature_c", "viscosity_pa_s")
#: the running onset search's own figures (glossary: gfbopt/terms/thermal.py)
SEARCH_COLUMNS = ("frozen_onset_speed_rpm", "thermal_evaluations", "thermal_static_solves",
                  "thermal_limit_rpm", "thermal_limit_kind")


def heated(running) -> bool:
    """The file states the running condition (a RunningSpec other than the isothermal one:
    the design route of today otherwise)."""
    from ..thermal.running import ISOTHERMAL

    return running is not None and running.model_name != ISOTHERMAL


def merit_speed(found: dict, speed_range) -> float:
    """The figure of merit of one running onset search [rpm] (module docstring), within the
    range."""
    low, high = speed_range
    onset = found.get("onset_speed_rpm", math.nan)
    if onset is not None and math.isfinite(onset):
        return onset
    if found.get("thermal_limit_kind"):            # no running state from this speed on
        limit = found.get("thermal_limit_rpm", math.nan)
        return min(high, max(low, limit)) if math.isfinite(limit) else low
    if found.get("stable_over_range"):
        return high
    if found.get("unstable_at_lower_end"):
        return low
    return math.nan


def evaluate_running(spec, bearing, options, cache) -> dict:
    """The onset and film-check columns of
    :func:`~gfbopt.design.stability_design.evaluate_compliance` for ``bearing`` (one trial S)
    at the running condition of ``spec.running``, with the running point at the onset and the
    search's figures (RUNNING_POINT_COLUMNS, SEARCH_COLUMNS, ``thermal_model``).  A
    ParameterError (a load beyond the capacity) propagates, as on the cold route."""
    from ..inputs.rotor import OperatingPoint
    from ..rotor.running_bearing import running_onset, running_stability

    found = running_onset(bearing, spec.running, spec.rotor, spec.load_newton,
                          tuple(spec.speed_range_rpm), options=options, grid=spec.grid,
                          cache=cache)
    film, point, _ = running_stability(bearing, spec.running, spec.rotor,
                                       OperatingPoint(spec.check_speed, spec.load_newton),
                                       options=options, grid=spec.grid, cache=cache)
    at_onset = found.get("running") or {}
    limited = bool(found.get("thermal_limit_kind"))
    messages = [found.get("message") or "", found["answer"] if limited else ""]
    if film is None:
        messages.append(f"no running state at the film-check speed {spec.check_speed:g} rpm"
                        f" ({point.message})")
    else:
        messages.append(film.message or "")
    return {"onset_speed_rpm": merit_speed(found, spec.speed_range_rpm),
            "stable_over_range": bool(found.get("stable_over_range", False)),
            "unstable_at_lower_end": bool(found.get("unstable_at_lower_end", False)),
            "onset_whirl_frequency_hz": found.get("whirl_frequency_hz", math.nan),
            "min_film_thickness_um": math.nan if film is None else film.min_film_thickness_um,
            "mass_margin_at_check_speed": math.nan if film is None else film.mass_margin,
            "success": bool(found.get("success", True)) and film is not None
            and bool(film.success),
            "message": "; ".join(m for m in messages if m),
            "thermal_model": spec.running.model_name,
            **{key: at_onset.get(key, math.nan) for key in RUNNING_POINT_COLUMNS},
            **{key: found.get(key, math.nan) for key in SEARCH_COLUMNS}}


def running_confirmation_case(spec, bearing, options, speed_rpm: float, cache):
    """(StabilityResult of the warm bearing, "") at the running condition of the
    confirmation speed (:func:`~gfbopt.rotor.running_bearing.running_stability`: its
    linearisation is the warm bearing's), or (None, why there is no running state)."""
    from ..inputs.rotor import OperatingPoint
    from ..rotor.running_bearing import running_stability

    result, point, _ = running_stability(bearing, spec.running, spec.rotor,
                                            OperatingPoint(speed_rpm, spec.load_newton),
                                            options=options, grid=spec.grid, cache=cache)
    if result is None:
        return None, f"no running state at {speed_rpm:g} rpm ({point.message})"
    return result, ""
