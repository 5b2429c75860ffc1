"""Study points at the running condition: a study whose bearing file states ``[journal]``/
``[thermal]`` (the kinds of :data:`gfbopt.inputs.bearing_file.RUNNING_STUDY_KINDS`) evaluates
each point through the functions ``gfbopt stability`` and :mod:`gfbopt.api` call
(:mod:`gfbopt.rotor.running_bearing`: the growths, Sutherland's μ(T) and the lumped heat
balance of :mod:`gfbopt.thermal`), so that a study row and the command give one answer for
the same inputs.  A file with neither table never comes here: the kind's points are today's.

* :func:`running_onset_row` — ``onset_conventions``: the onset of whirl with the running
  clearance and viscosity at each speed (:func:`~gfbopt.rotor.running_bearing.running_onset`,
  as ``gfbopt stability --bearing FILE --speed-range LOW HIGH``), with the running point at
  the onset;
* :func:`running_static_row` — ``load_sweep``: the static equilibrium of each (speed, load)
  at its running condition (the heat balance under that load), as ``gfbopt static --bearing
  FILE --speed-rpm N --load-newton F`` (:mod:`gfbopt.cli.running_point`): the fixed point of
  :func:`gfbopt.thermal.running.running_point` with :class:`~gfbopt.thermal.bearing.FilmDrag`
  started by :func:`~gfbopt.rotor.running_bearing.coarse_start`, then one cold static solve
  of :func:`~gfbopt.thermal.bearing.warm_bearing`;
* :func:`running_coefficient_rows` — ``linear_coefficients``: K and C at the running
  condition of each (speed, load), as ``gfbopt linear`` gives them.
"""
from __future__ import annotations

import math
import time
from ..errors import ParameterError

#: the clearance at speed's columns of a row (glossary: gfbopt/terms/thermal.py), from the
#: running point at the answer
RUNNING_COLUMNS = ("thermal_model", "thermal_status", "running_clearance_um",
                   "centrifugal_growth_um", "thermal_growth_um", "film_temperature_c",
                   "viscosity_pa_s")
#: the search's own figures of the running onset (glossary: gfbopt/terms/thermal.py)
SEARCH_COLUMNS = ("frozen_onset_speed_rpm", "frozen_at_rpm", "thermal_evaluations",
                  "thermal_static_solves", "thermal_limit_rpm", "thermal_limit_kind")


def stated_options(bearing, *, film, seam_angle_deg, foil, deflection_law, loss_factor):
    """The point's formulation over the bearing file's ``[model]``, then the defaults: the
    resolution of ``gfbopt stability``'s flags (:func:`~gfbopt.inputs.options.merge_options`
    of the stated options over ``bearing.options``)."""
    from ..inputs.options import ModelOptions, merge_options

    return merge_options(ModelOptions(film=film, seam_angle_deg=seam_angle_deg, foil=foil,
                                      deflection_law=deflection_law,
                                      loss_factor=loss_factor), bearing.options)


def running_onset_row(bearing, running, rotor_mass_kg: float, load_newton: float,
                      speed_range, *, film: str, seam_angle_deg, foil: str,
                      deflection_law: str, loss_factor: float, grid, cache=None) -> dict:
    """The onset row of :func:`gfbopt.studies.stability.onset_point` at the running
    condition (``running``: the file's RunningSpec): ``onset_speed_rpm`` of
    :func:`~gfbopt.rotor.running_bearing.running_onset` (searched from the geometric mean of
    the range, as the command does without ``--speed-rpm``), the running point at the onset
    (RUNNING_COLUMNS) and the search's figures (SEARCH_COLUMNS).  The frozen search's
    margins are not the running answer: ``smallest_margin`` and
    ``critical_mass_kg_at_low_speed`` are NaN."""
    from ..inputs.rotor import Rotor
    from ..rotor.running_bearing import running_onset
    from ..static import SolverCache
    from .onset_status import (
        CLOSURE,
        FAILED,
        ONSET,
        OVERLOAD,
        STABLE,
        THERMAL_RUNAWAY,
        UNSTABLE_ALL,
        UNSTABLE_LOW,
    )

    t0 = time.perf_counter()
    row = {"onset_speed_rpm": math.nan, "whirl_frequency_hz": math.nan,
           "whirl_ratio": math.nan, "onset_status": FAILED, "smallest_margin": math.nan,
           "critical_mass_kg_at_low_speed": math.nan, "thermal_model": running.model_name}
    options = stated_options(bearing, film=film, seam_angle_deg=seam_angle_deg, foil=foil,
                             deflection_law=deflection_law, loss_factor=loss_factor)
    try:
        found = running_onset(bearing, running, Rotor(rotor_mass_kg), load_newton,
                              tuple(speed_range), options=options, grid=grid,
                              cache=cache or SolverCache(grid))
    except ParameterError as exc:
        overload = "load capacity" in str(exc)
        return {**row, "onset_status": OVERLOAD if overload else FAILED, "success": overload,
                "message": str(exc), "wall_time_s": time.perf_counter() - t0}
    onset = found.get("onset_speed_rpm", math.nan)
    if math.isfinite(onset):
        status = ONSET
    elif found.get("thermal_limit_kind"):
        status = CLOSURE if found["thermal_limit_kind"] == "closure" else THERMAL_RUNAWAY
    elif found.get("unstable_at_lower_end"):
        first = found["scan"][0]
        status = UNSTABLE_ALL if first["critical_mass"] == 0 else UNSTABLE_LOW
    elif found.get("stable_over_range"):
        status = STABLE
    else:
        status = FAILED
    point = found.get("running") or {}
    row.update({key: point.get(key, math.nan) for key in RUNNING_COLUMNS[1:]})
    row.update({key: found.get(key, math.nan) for key in SEARCH_COLUMNS})
    row.update(onset_speed_rpm=onset, whirl_frequency_hz=found.get("whirl_frequency_hz"),
               whirl_ratio=found.get("whirl_ratio", math.nan), onset_status=status,
               evaluations=found.get("evaluations", 0),
               success=bool(found.get("success", True)) and status != FAILED,
               message=found.get("answer") or found.get("message", ""),
               wall_time_s=time.perf_counter() - t0)
    return row


def running_notes(thermal_model: str, bearing_file: str) -> list:
    """The README/summary notes of a study at the running condition (its model named)."""
    return [(f"Clearance at speed: the bearing file {bearing_file} states the running "
             f"condition ({thermal_model}); each point is evaluated at its running clearance "
            "and viscosity, through the functions `gfbopt stability` and gfbopt.api call "
            "(gfbopt.rotor.running_bearing), so a row equals the command's answer for the same "
            "inputs. The columns thermal_model … viscosity_pa_s give the running point at the "
            "answer; smallest_margin and critical_mass_kg_at_low_speed are empty (the "
            "frozen search's figures are not the running answer).")]


def model_keywords(bearing, opts: dict):
    """The keywords of :meth:`BearingGeometry.model` that
    :func:`gfbopt.analyses.bearing_model` resolves from a study point's ``opts`` (the
    variant's and the study's keys over the bearing file's ``[model]``, then the defaults;
    ``subambient`` and ``compression_only`` as stated)."""
    named = ("film", "seam_angle_deg", "foil", "deflection_law", "loss_factor")
    resolved = stated_options(bearing, **{key: opts.get(key) for key in named})
    from ..rotor.running_bearing import Formulation

    extra = {key: value for key, value in opts.items() if key not in named}
    return Formulation(tuple(sorted({**resolved.model_kwargs(), **extra}.items())))


def warm_at(bearing, running, formulation, speed_rpm: float,
            load_newton: float, *, grid, cache):
    """(the warm bearing or None, the running point's columns, why there is none): the fixed
    point under ``load_newton`` at ``speed_rpm`` as ``gfbopt static/linear`` solve it
    (:func:`gfbopt.thermal.running.running_point`, :class:`~gfbopt.thermal.bearing.FilmDrag`
    started by :func:`~gfbopt.rotor.running_bearing.coarse_start`), the centrifugal growth
    alone without ``[thermal]``."""
    from ..rotor.running_bearing import warm_under_load
    from ..thermal.bearing import FilmCase

    found = warm_under_load(running, FilmCase(bearing, formulation, grid, cache, load_newton),
                            speed_rpm)
    d = found.point.to_dict()
    columns = {"thermal_model": running.model_name,
               **{key: d[key] for key in RUNNING_COLUMNS[1:]},
               "thermal_static_solves": found.solves}
    if found.warm is None:
        return None, columns, found.point.message or "no running state"
    return found.warm, columns, ""


def running_static_row(bearing, running, formulation, speed_rpm: float,
                       load_newton: float, *, grid, cache=None) -> dict:
    """One row of ``load_sweep`` at the running condition of (speed, load): the static row
    of the warm bearing (:func:`gfbopt.analyses.static_row` with the geometry: h_min in µm
    of the running clearance, drag, power) and the running point (RUNNING_COLUMNS,
    ``thermal_static_solves``).  No running state (thermal runaway, closure): NaN figures,
    ``thermal_status`` and the message say why, ``success`` False."""
    from ..analyses import STATIC_OUTPUTS, static_row
    from ..static import SolverCache, solve_static

    t0 = time.perf_counter()
    cache = cache or SolverCache(grid)
    kwargs = formulation.model_kwargs()
    warm, found, message = warm_at(bearing, running, formulation, speed_rpm, load_newton,
                                   grid=grid, cache=cache)
    if warm is not None:
        model = warm.model(speed_rpm, **kwargs)
        sol = solve_static(model, load=warm.nondimensional_load(load_newton),
                           solver=cache(model, grid))
        row = static_row(model, sol, warm)
        row["load_newton"] = load_newton
        return {**row, **found, "wall_time_s": time.perf_counter() - t0}
    model = bearing.model(speed_rpm, **kwargs)             # the cold groups, for the row
    nan = math.nan
    return {**model.groups(), **dict.fromkeys(STATIC_OUTPUTS, nan), "load_newton": load_newton,
            "min_film_thickness_um": nan, "drag_torque_nm": nan, "power_loss_w": nan,
            **found, "success": False, "message": message,
            "wall_time_s": time.perf_counter() - t0}


def running_coefficient_rows(bearing, running, formulation, speed_rpm: float,
                             load_newton: float, *, whirl_ratios, grid,
                             cache=None) -> list:
    """The rows of ``linear_coefficients`` at the running condition of (speed, load): K and
    C of the warm bearing (:func:`gfbopt.analyses.coefficients_point`, the equilibrium and
    linearisation of ``gfbopt linear``) with the running point's columns on each row.  No
    running state: one row saying why, ``success`` False."""
    from ..analyses import coefficients_point
    from ..static import SolverCache

    t0 = time.perf_counter()
    cache = cache or SolverCache(grid)
    warm, found, message = warm_at(bearing, running, formulation, speed_rpm, load_newton,
                                   grid=grid, cache=cache)
    if warm is None:
        return [{"load_newton": load_newton, "speed_rpm": speed_rpm, **found,
                 "success": False, "message": message,
                 "wall_time_s": time.perf_counter() - t0}]
    model = warm.model(speed_rpm, **formulation.model_kwargs())
    rows = coefficients_point(model, whirl_ratios=whirl_ratios,
                              load=warm.nondimensional_load(load_newton), grid=grid,
                              cache=cache, geometry=warm, speed_rpm=speed_rpm)
    return [{**row, **found, "wall_time_s": time.perf_counter() - t0} for row in rows]


def running_static_notes(thermal_model: str, bearing_file: str,
                         kind: str = "load_sweep") -> list:
    """The README/summary notes of a load sweep, coefficient or drag study at the running
    condition."""
    command, what = {"linear_coefficients": ("linear", "K and C are"),
                     "drag_power": ("static", "the drag and power loss are")}.get(
        kind, ("static", "min_film_thickness_um is"))
    return [(f"Clearance at speed: the bearing file {bearing_file} states the running "
             f"condition ({thermal_model}); each (speed, load) is analysed at its own "
             "running clearance and viscosity (the heat balance under that load), as "
             f"`gfbopt {command} --bearing FILE --speed-rpm N --load-newton F` does; {what} "
             "of the running clearance, and the columns thermal_model … viscosity_pa_s give "
             "the running point of each row.")]
