"""Study kinds on a dimensional bearing (a bearing file in SI units) swept over speed and load.

* ``load_sweep`` — minimum film [µm] and attitude angle against static load [N] at several
  speeds and foil models (Ruscitto bearing, thesis Figs 3.2–3.5, 4.2–4.5);
* ``linear_coefficients`` — stiffness [N/m] and damping [N s/m] against excitation frequency,
  with the linear threshold, per speed and load, and a table per operating point in the
  layout rotordynamics codes read.

The formulation of each variant is resolved as every route resolves it
(:func:`gfbopt.analyses.bearing_model`, :func:`~gfbopt.inputs.options.merge_options`): the
variant's keys, then the study's ``[model]``, then the bearing file's ``[model]`` table, then
gfbopt's defaults (a seam with the welded end 180° from the load).  A study that wants
another convention than its bearing file states it (e.g. ``seam_angle_deg = "max_film"``).
"""
from __future__ import annotations

from .. import analyses
from ..errors import ParameterError
from ..parallel import run_points
from ..static import SolverCache
from . import checks
from .base import (
    RunContext,
    Study,
    StudyResult,
    frame,
    load_running_geometry,
    merged,
    options_of,
    variant_titles,
)

#: trend name → (column, rising with load?)
LOAD_TRENDS = {"min_film_thickness_decreases_with_load": ("min_film_thickness_um", False),
               "eccentricity_increases_with_load": ("eccentricity", True)}


def _plan(study: Study) -> tuple:
    """(geometry, [(variant label, speed, model)]) — models of every variant and speed; on a
    file with ``[journal]``/``[thermal]`` a third item, the running condition
    (:func:`_running`); a file without them gives today's plan unchanged."""
    spec = study.spec
    geometry, running = load_running_geometry(study)      # [journal]/[thermal] read
    for key in ("speeds_rpm", "loads_newton"):
        for k, v in enumerate(spec[key]):
            if v <= 0:
                raise study.where(key, k).error(v, "must be > 0")
    models = []
    for k, variant in enumerate(spec["variants"]):
        opts = {key: v for key, v in merged(spec["model"], variant).items() if key != "label"}
        for speed in spec["speeds_rpm"]:
            try:        # variant, then study [model], then the bearing file's, then defaults
                model = analyses.bearing_model(geometry, speed, **opts)
            except ParameterError as exc:
                raise (study.where("variants", k) / exc.name).error(exc.value,
                                                                    exc.rule) from None
            models.append((variant["label"], speed, model))
    running = _running(study, geometry, running)
    return (geometry, models) if running is None else (geometry, models, running)


def _running(study: Study, geometry, running):
    """None without the tables; else {"spec": the RunningSpec, "formulations": the model
    keywords of each variant (:func:`.running_points.model_keywords`)}."""
    from ..thermal.running import ISOTHERMAL

    if running is None or running.model_name == ISOTHERMAL:
        return None
    from ..inputs.rotor_limits import check_surface_speed
    from .running_points import model_keywords

    check_surface_speed(geometry, list(study.spec["speeds_rpm"]), f"{study.file}: speeds_rpm")
    spec = study.spec
    return {"spec": running, "formulations": {
        variant["label"]: model_keywords(geometry, {key: v for key, v in merged(
            spec["model"], variant).items() if key != "label"})
        for variant in spec["variants"]}}


plan_load_sweep = _plan
plan_linear_coefficients = _plan


def _options(study: Study, models: list) -> dict:
    by_label: dict = {}
    for label, _, model in models:
        by_label.setdefault(label, []).append(model)
    return options_of(by_label, study.grid, bearing=study.spec["bearing"])


def run_load_sweep(study: Study, plan: tuple, ctx: RunContext) -> StudyResult:
    """Each (variant, speed) is a load curve warm-started from load to load."""
    from ..plotting import plot_load_sweep

    spec = study.spec
    geometry, models, *heated = plan
    running = heated[0] if heated else None
    if running is None:
        loads = [geometry.nondimensional_load(w) for w in spec["loads_newton"]]
        rows = run_points(analyses.load_curve,
                          [{"model": m, "loads": loads, "grid": study.grid,
                            "geometry": geometry} for _, _, m in models],
                          tags=[{"variant": label, "foil": m.foil, "speed_rpm": speed}
                                for label, speed, m in models], progress=ctx.progress)
    else:                 # each (speed, load) at its running condition (the heat balance)
        rows = _running_rows(study, geometry, models, running, ctx)
    table = frame(rows, ("variant", "foil", "speed_rpm", "load_newton"))
    found = [checks.all_converged(table)]
    for name in spec["trends"]:
        column, rising = LOAD_TRENDS[name]
        found += checks.monotone(table, column, "load_newton", rising, ["variant", "speed_rpm"],
                                 f"largest {'fall' if rising else 'rise'} of {column} between "
                                 "load steps")
    titles = variant_titles({label: m for label, _, m in models})
    figures = {}
    for quantity, name, what in (
            ("min_film_thickness_um", "min_film_vs_load.png", "Minimum film thickness"),
            ("attitude_angle_deg", "attitude_vs_load.png", "Attitude angle")):
        ax = plot_load_sweep(table, quantity, labels=titles,
                             title=f"{what} against static load: {geometry.name} bearing")
        figures[name] = ax.figure
    return StudyResult(study, tables={"table.csv": table}, figures=figures, checks=found,
                       **_named(study, models, running))


def _named(study: Study, models: list, running) -> dict:
    """The StudyResult's options, notes and answer: at the running condition they name the
    clearance model (``thermal_model`` in summary.json and the README)."""
    options = _options(study, models)
    if running is None:
        return {"options": options}
    from .running_points import running_static_notes

    name = options["thermal_model"] = running["spec"].model_name
    return {"options": options, "answer": {"thermal_model": name},
            "notes": running_static_notes(name, study.spec["bearing"], study.kind)}


def _running_rows(study: Study, geometry, models: list, running: dict, ctx) -> list:
    """Each (variant, speed, load) at its running condition (.running_points)."""
    from ..inputs import DEFAULT_GRID
    from .running_points import running_coefficient_rows, running_static_row

    points, tags = [], []
    coefficients = study.kind == "linear_coefficients"
    for label, speed, model in models:
        for load_newton in study.spec["loads_newton"]:
            point = {"bearing": geometry, "running": running["spec"],
                     "formulation": running["formulations"][label], "speed_rpm": speed,
                     "load_newton": load_newton, "grid": study.grid or DEFAULT_GRID}
            if coefficients:
                point["whirl_ratios"] = study.spec["whirl_ratios"]
            points.append(point)
            tags.append({"variant": label, "load_newton": load_newton} if coefficients else
                        {"variant": label, "foil": model.foil, "speed_rpm": speed})
    return run_points(running_coefficient_rows if coefficients else running_static_row,
                      points, tags=tags, progress=ctx.progress)


def run_linear_coefficients(study: Study, plan: tuple, ctx: RunContext) -> StudyResult:
    from ..plotting import new_axes, plot_coefficients

    spec = study.spec
    geometry, models, *heated = plan
    running = heated[0] if heated else None
    points, tags = [], []
    for label, speed, model in models:
        for load_newton in spec["loads_newton"]:
            points.append({"model": model, "load": geometry.nondimensional_load(load_newton),
                           "whirl_ratios": spec["whirl_ratios"], "grid": study.grid,
                           "geometry": geometry, "speed_rpm": speed})
            tags.append({"variant": label, "load_newton": load_newton})
    if running is None:
        rows = run_points(analyses.coefficients_point, points, tags=tags,
                          cache=SolverCache(), progress=ctx.progress)
    else:                 # each (speed, load) at its running condition (the heat balance)
        rows = _running_rows(study, geometry, models, running, ctx)
    table = frame(rows, ("variant", "load_newton", "speed_rpm", "whirl_ratio", "frequency_hz"))
    tables = {"coefficients.csv": table}
    figures = {}
    titles = variant_titles({label: m for label, _, m in models})
    ok = table[table["success"].astype(bool)]
    for (label, speed, load_newton), sub in ok.groupby(["variant", "speed_rpm", "load_newton"],
                                                       sort=False):
        stem = f"{label}_{int(speed)}rpm_{int(load_newton)}N"
        columns = ["frequency_hz"] + [c for c in sub.columns
                                      if c.endswith(("_N_per_m", "_Ns_per_m"))]
        tables[f"rotordynamics_{stem}.csv"] = sub[columns]
        left, right = new_axes(figsize=(10.0, 4.4), ncols=2)
        where = f"{titles[label]}, {speed:,.0f} rpm, {load_newton:g} N"
        plot_coefficients(sub, "stiffness", ax=left, title=f"Stiffness: {where}")
        plot_coefficients(sub, "damping", ax=right, title=f"Damping: {where}")
        figures[f"coefficients_{stem}.png"] = left.figure
    found = [checks.all_converged(table, "all static solves and thresholds converged")]
    return StudyResult(study, tables=tables, figures=figures, checks=found,
                       **_named(study, models, running))
