"""Studies of the bearing as built: the levers foil-bearing designers use.

* ``onset_as_built`` — the onset speed of whirl [rpm] of a rotor (mass and load per bearing
  fixed) on a bearing file, against the mechanical preload depth of N shims (or lobes) and
  against the number of top-foil pads (``problems/ruscitto_preload.toml``);
* ``drag_power`` — drag torque [N m] and power loss [W] of a bearing file against speed (one
  line per load) and against load (one line per speed), Petroff's torque of the concentric
  journal drawn beside ours (``problems/ruscitto_drag.toml``).

Every point is independent and runs on the process pool (:func:`gfbopt.parallel.run_points`,
one solver cache per worker): a preload depth is a parameter of the static build, so one
build serves every depth; a pad count is a build of its own.
"""
from __future__ import annotations

import dataclasses
import math
import time

from ..inputs.bore_si import BearingBuild, BoreSpec, PadSpec
from ..parallel import run_points
from . import checks
from .base import (
    Kind,
    RunContext,
    Study,
    StudyResult,
    frame,
    load_running_geometry,
)
from .spec import GRID, opt, req
from .stability import FAILED, ONSET, onset_point

_ROTOR = {
    "bearing": req("string", "bearing file (SI), relative to the study file"),
    "rotor_mass_kg": req("number", "rotor mass per bearing [kg]", positive=True),
    "load_newton": req("number", "static load per bearing [N]", positive=True),
    "speed_range_rpm": req("numbers", "[low, high] speeds searched for the onset [rpm]",
                           length=2),
    "seam_angle_deg": opt("number", 180.0, "welded end of the (first) top foil from the load "
                          "line [deg]"),
}

SCHEMAS: dict[str, dict] = {
    "onset_as_built": {**GRID, **_ROTOR,
        "bore": opt("string", "shims", "preload profile: shims or lobes",
                    choices=("shims", "lobes")),
        "n_shims": opt("integer", 3, "number of shims (or lobes)"),
        "shim_width_deg": opt("number", 60.0, "angular width of each shim [deg]",
                              positive=True),
        "shim_offset_deg": opt("number", 0.0, "centre of the first shim from the load line "
                               "[deg]"),
        "preload_depths_um": req("numbers", "preload depths [µm] (0: the round bore)"),
        "n_pads": opt("numbers", [1.0, 2.0, 3.0, 4.0], "numbers of equal top-foil pads, the "
                      "first welded at seam_angle_deg (round bore)"),
        "min_gain": opt("number", 0.0, "smallest onset gain of the deepest preload over the "
                        "round bore [-] checked (0: report only)")},
    "drag_power": {**GRID,
        "bearing": req("string", "bearing file (SI), relative to the study file"),
        "speeds_rpm": req("numbers", "shaft speeds [rpm]"),
        "loads_newton": req("numbers", "static loads per bearing [N]")},
}


# ------------------------------------------------------------------ points
_DRAG_COLUMNS = ("torque_ratio", "drag_torque_nm", "power_loss_w", "min_film_thickness_um",
                 "eccentricity", "attitude_angle_deg", "bearing_number", "success", "message")


def drag_point(bearing, speed_rpm: float, load_newton: float, grid, options,
               cache=None, running=None) -> dict:
    """Static equilibrium of ``bearing`` under ``load_newton`` at ``speed_rpm`` with the
    formulation ``options`` (complete ModelOptions): drag torque, power loss, torque ratio,
    film (one row, :func:`gfbopt.analyses.static_row`).  With ``running`` (the file's
    RunningSpec with ``[journal]``/``[thermal]``): at the running condition of (speed, load),
    as ``gfbopt static`` (:func:`.running_points.running_static_row`), with the running
    point's columns."""
    if running is not None:
        from ..inputs import DEFAULT_GRID
        from ..rotor.running_bearing import Formulation
        from .running_points import RUNNING_COLUMNS, running_static_row

        row = running_static_row(bearing, running, Formulation(tuple(sorted(
            options.model_kwargs().items()))), speed_rpm, load_newton,
            grid=grid or DEFAULT_GRID, cache=cache)
        return {k: row[k] for k in (*_DRAG_COLUMNS, *RUNNING_COLUMNS,
                                    "thermal_static_solves")}
    from ..analyses import static_point

    model = bearing.model(speed_rpm, **options.model_kwargs())
    row = static_point(model, load=bearing.nondimensional_load(load_newton), grid=grid,
                       cache=cache, geometry=bearing)
    return {k: row[k] for k in _DRAG_COLUMNS}


# ------------------------------------------------------------------ onset_as_built
def _pads(count: int, first_deg: float) -> tuple:
    step = 360.0 / count
    return tuple(PadSpec((first_deg + k * step) % 360.0, step) for k in range(count))


def plan_onset_as_built(study: Study) -> dict:
    spec = study.spec
    bearing, running = load_running_geometry(study)       # [journal]/[thermal] read
    low, high = spec["speed_range_rpm"]
    if not 0 < low < high:
        raise study.where("speed_range_rpm").error([low, high], "must be [low, high] with 0 < "
                                                   "low < high [rpm]")
    if spec["n_shims"] < 1:
        raise study.where("n_shims").error(spec["n_shims"], "must be >= 1")
    seam = spec["seam_angle_deg"]
    if not 0.0 <= seam < 360.0:
        raise study.where("seam_angle_deg").error(seam, "must lie in [0, 360) degrees")
    common = {"rotor_mass_kg": spec["rotor_mass_kg"], "load_newton": spec["load_newton"],
              "speed_range": (float(low), float(high)), "film": "seam",
              "seam_angle_deg": seam, "foil": "simple", "deflection_law": "mean",
              "loss_factor": 0.0, "grid": study.grid}
    points, tags = [], []
    c_um = bearing.radial_clearance * 1e6
    for k, depth in enumerate(spec["preload_depths_um"]):
        if not 0.0 <= depth < c_um:
            raise study.where("preload_depths_um", k).error(depth, f"must lie in [0, "
                                                           f"{c_um:.4g}) µm (the clearance)")
        bore = BoreSpec(spec["bore"], spec["n_shims"], preload_depth=depth * 1e-6,
                        width_deg=spec["shim_width_deg"], offset_deg=spec["shim_offset_deg"])
        built = dataclasses.replace(bearing, build=BearingBuild(bore))   # checked here
        points.append({**common, "bearing": built})
        tags.append({"variant": "preload", "preload_depth_um": float(depth),
                     "preload_ratio": depth / c_um, "n_pads": 1})
    for k, count in enumerate(spec["n_pads"]):
        if count != int(count) or not 1 <= count <= 12:
            raise study.where("n_pads", k).error(count, "must be a whole number in 1..12")
        built = dataclasses.replace(bearing, build=BearingBuild(pads=_pads(int(count), seam)))
        points.append({**common, "bearing": built})
        tags.append({"variant": "pads", "preload_depth_um": 0.0, "preload_ratio": 0.0,
                     "n_pads": int(count)})
    return {"points": points, "tags": tags, "bearing": bearing,
            **_at_running_condition(study, bearing, running, points)}


def _at_running_condition(study: Study, bearing, running, points: list) -> dict:
    """With ``[journal]``/``[thermal]``: each onset at the running condition of each speed
    (``running`` added to every point, :func:`.running_points.running_onset_row`) and the
    model named ({"thermal_model": …}); else {} (today's points)."""
    from ..thermal.running import ISOTHERMAL

    if running.model_name == ISOTHERMAL:
        return {}
    from ..inputs.rotor_limits import check_surface_speed

    check_surface_speed(bearing, list(study.spec["speed_range_rpm"]),
                        f"{study.file}: speed_range_rpm")
    for point in points:
        point["running"] = running
    return {"thermal_model": running.model_name}


def run_onset_as_built(study: Study, plan: dict, ctx: RunContext) -> StudyResult:
    from ..plotting.bearing import plot_against_lever

    spec = study.spec
    t0 = time.perf_counter()
    rows = run_points(onset_point, plan["points"], workers=ctx.workers, tags=plan["tags"],
                      progress=ctx.progress)
    elapsed = time.perf_counter() - t0
    table = frame(rows, ("variant", "preload_depth_um", "preload_ratio", "n_pads",
                         "onset_speed_rpm", "onset_status"), ("onset_speed_rpm",))
    preload = table[table["variant"] == "preload"]
    pads = table[table["variant"] == "pads"]
    name = plan["bearing"].name
    rotor = f"{spec['rotor_mass_kg']:g} kg, {spec['load_newton']:g} N per bearing"
    round_rows = preload[preload["preload_depth_um"] == 0.0]
    reference = float(round_rows["onset_speed_rpm"].iloc[0]) if len(round_rows) else math.nan
    figures = {}
    ax = plot_against_lever(
        preload, "preload_depth_um", "onset_speed_rpm", reference=reference,
        reference_label="round bore (no preload)", xlabel="preload depth [µm]",
        ylabel="onset speed of whirl [rpm]",
        title=f"Onset speed of whirl against the preload of {spec['n_shims']} "
              f"{spec['bore']} ({spec['shim_width_deg']:g}° wide): {rotor}, {name}")
    figures["onset_preload.png"] = ax.figure
    if len(pads):
        ax = plot_against_lever(
            pads, "n_pads", "onset_speed_rpm", reference=reference,
            reference_label="one top foil", xlabel="number of top-foil pads",
            ylabel="onset speed of whirl [rpm]",
            title=f"Onset speed of whirl against the number of equal pads (first welded "
                  f"{spec['seam_angle_deg']:g}° from the load): {rotor}, {name}")
        figures["onset_pads.png"] = ax.figure
    found = [checks.check("every onset search converged (failed rows)",
                          float((table["onset_status"] == FAILED).sum()), 0)]
    deepest = preload.loc[preload["preload_depth_um"].idxmax()] if len(preload) else None
    if deepest is not None and spec["min_gain"] > 0:
        gain = deepest["onset_speed_rpm"] / reference - 1.0
        found.append(checks.check(f"onset gain of the deepest preload ({deepest['preload_depth_um']:g}"
                                  f" µm) over the round bore, shortfall below {spec['min_gain']:g}",
                                  max(0.0, spec["min_gain"] - gain), 0.0))
    notes = [_describe(preload, "preload_depth_um", "µm preload", reference),
             _describe(pads, "n_pads", "pads", reference),
             f"{len(rows)} onset searches in {elapsed:.1f} s on {ctx.workers} worker "
             f"process{'es' if ctx.workers > 1 else ''}, grid {study.grid}"]
    options = {"grid": str(study.grid), "rotor_mass_kg": spec["rotor_mass_kg"],
               "load_newton": spec["load_newton"], "speed_range_rpm": spec["speed_range_rpm"],
               "film": "seam", "seam_angle_deg": spec["seam_angle_deg"], "foil": "simple",
               "deflection_law": "mean", "loss_factor": 0.0, "bore": spec["bore"],
               "n_shims": spec["n_shims"], "shim_width_deg": spec["shim_width_deg"],
               "shim_offset_deg": spec["shim_offset_deg"]}
    answer = {}
    if plan.get("thermal_model"):                # the clearance at speed, named
        from .running_points import running_notes

        options["thermal_model"] = answer["thermal_model"] = plan["thermal_model"]
        notes += running_notes(plan["thermal_model"], spec["bearing"])
    return StudyResult(study, tables={"onset.csv": table}, figures=figures, checks=found,
                       options=options, notes=notes, answer=answer)


def _describe(table, x: str, unit: str, reference: float) -> str:
    parts = []
    for _, r in table.sort_values(x).iterrows():
        if r["onset_status"] == ONSET and math.isfinite(reference):
            parts.append(f"{r[x]:g} {unit}: {r['onset_speed_rpm']:,.0f} rpm "
                         f"({r['onset_speed_rpm'] / reference - 1:+.1%})")
        else:
            parts.append(f"{r[x]:g} {unit}: {r['onset_status']}")
    return "Onset speed, " + "; ".join(parts) + "."


# ------------------------------------------------------------------ drag_power
def plan_drag_power(study: Study) -> dict:
    from ..inputs.options import ModelOptions, merge_options

    spec = study.spec
    bearing, running = load_running_geometry(study)       # [journal]/[thermal] read
    options = merge_options(ModelOptions(), bearing.options)   # the file's [model]
    for key in ("speeds_rpm", "loads_newton"):
        for k, v in enumerate(spec[key]):
            if not v > 0:
                raise study.where(key, k).error(v, "must be > 0")
    points, tags = [], []
    for speed in spec["speeds_rpm"]:
        for load in spec["loads_newton"]:
            points.append({"bearing": bearing, "speed_rpm": float(speed),
                           "load_newton": float(load), "grid": study.grid,
                           "options": options})
            tags.append({"speed_rpm": float(speed), "load_newton": float(load)})
    from ..thermal.running import ISOTHERMAL

    thermal = None
    if running.model_name != ISOTHERMAL:         # each point at its running condition
        from ..inputs.rotor_limits import check_surface_speed

        check_surface_speed(bearing, list(spec["speeds_rpm"]), f"{study.file}: speeds_rpm")
        points = [{**p, "running": running} for p in points]
        thermal = running.model_name
    return {"points": points, "tags": tags, "bearing": bearing, "options": options,
            "thermal_model": thermal}


def run_drag_power(study: Study, plan: dict, ctx: RunContext) -> StudyResult:
    from ..physics.torque import petroff_torque
    from ..plotting.bearing import plot_against_lever

    bearing = plan["bearing"]
    rows = run_points(drag_point, plan["points"], workers=ctx.workers, tags=plan["tags"],
                      progress=ctx.progress)
    table = frame(rows, ("speed_rpm", "load_newton", "drag_torque_nm", "power_loss_w",
                         "torque_ratio"), ("drag_torque_nm", "power_loss_w"))
    omega = table["speed_rpm"] * math.pi / 30.0
    if plan.get("thermal_model"):               # Petroff's at each row's running condition
        table["petroff_power_w"] = [
            petroff_torque(mu, w, bearing.radius, bearing.length, c_um * 1e-6) * w
            for w, mu, c_um in zip(omega, table["viscosity_pa_s"],
                                   table["running_clearance_um"])]
    else:
        table["petroff_power_w"] = [petroff_torque(bearing.viscosity, w, bearing.radius,
                                                   bearing.length,
                                                   bearing.radial_clearance) * w
                                    for w in omega]
    name = bearing.name
    ax = plot_against_lever(table, "speed_rpm", "power_loss_w", group="load_newton",
                            xlabel="shaft speed [rpm]", ylabel="power loss per bearing [W]", group_label="W = {:g} N",
                            title=f"Power loss against speed, one line per static load [N]: "
                                  f"{name}")
    petroff = table.drop_duplicates("speed_rpm").sort_values("speed_rpm")
    ax.plot(petroff["speed_rpm"], petroff["petroff_power_w"], "k--", lw=1.0,
            label="Petroff (concentric journal, 2π μ ω² R³ L / c)")
    ax.legend(fontsize=8)
    figures = {"power_against_speed.png": ax.figure}
    ax = plot_against_lever(table, "load_newton", "drag_torque_nm", group="speed_rpm",
                            xlabel="static load per bearing [N]", ylabel="drag torque [N m]",
                            group_label="{:,.0f} rpm",
                            title=f"Drag torque against load, one line per speed [rpm]: {name}")
    figures["torque_against_load.png"] = ax.figure
    ok = table[table["success"].astype(bool)]
    found = [checks.all_converged(table)]
    notes = [f"Torque over Petroff's ranges {ok['torque_ratio'].min():.3f}–"
             f"{ok['torque_ratio'].max():.3f}; power loss {ok['power_loss_w'].min():.3g}–"
             f"{ok['power_loss_w'].max():.3g} W per bearing." if len(ok) else
             "No point converged.",
             "Drag torque from the film shear on the journal, Couette and pressure-gradient "
             "parts (docs/PHYSICS.md §5b); isothermal film at the bearing file's viscosity."]
    options = {"grid": str(study.grid), **plan["options"].to_dict(),
               **({} if bearing.build is None else bearing.build.describe())}
    answer = {}
    if plan.get("thermal_model"):                # the clearance at speed, named
        from .running_points import running_static_notes

        options["thermal_model"] = answer["thermal_model"] = plan["thermal_model"]
        notes[-1] = ("Drag torque from the film shear on the journal, Couette and "
                     "pressure-gradient parts (docs/PHYSICS.md §5b); Petroff's power at each "
                     "row's running clearance and viscosity (the line drawn: the first "
                     "load's).")
        notes += running_static_notes(plan["thermal_model"], study.spec["bearing"],
                                      study.kind)
    return StudyResult(study, tables={"drag.csv": table}, figures=figures, checks=found,
                       options=options, notes=notes, answer=answer)


KINDS = {"onset_as_built": Kind(plan_onset_as_built, run_onset_as_built, parallel=True),
         "drag_power": Kind(plan_drag_power, run_drag_power, parallel=True)}
