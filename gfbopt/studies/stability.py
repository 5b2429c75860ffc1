"""Stability in engineering terms: the onset speed of whirl against the film convention (this
module), and the structural loss factor η against the compliance S (:mod:`.damping`, which
shares the point functions and helpers here).

* ``onset_conventions`` — the onset speed of whirl [rpm] of a rotor (mass and load per
  bearing fixed) on a bearing file, against the top foil's welded-end angle (seam at a fixed
  housing angle), beside the periodic film and the seam on the maximum-film line
  (``problems/ruscitto_conventions.toml``; docs/PHYSICS.md §4);
* ``loss_factor_map`` — the linear critical mass M̄c against S per η at fixed Λ and W̄, both
  deflection laws, with the rigid bearing (S = 0) beside them; the onset speed of a rotor on
  a bearing file against S (bump thickness) per η; the transient (Kelvin–Voigt foil state)
  critical mass against the linear one at a few points (``problems/loss_factor.toml``).

Every point is independent and runs on the process pool (:func:`gfbopt.parallel.run_points`,
one solver cache per worker).  An onset search that finds no onset is an answer, stated in
``onset_status``: "unstable at every mass" (the massless journal already whirls: M̄c = 0 at
the lowest speed, e.g. a welded end inside the loaded arc), "unstable at the lowest speed",
"stable over the range", or "load exceeds capacity".
"""
from __future__ import annotations

import math
import time


from ..errors import ParameterError
from ..inputs import DEFLECTION_LAWS, BearingModel, Grid
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
from .onset_status import FAILED, ONSET, OVERLOAD, STABLE, UNSTABLE_ALL, UNSTABLE_LOW
from .spec import GRID, UNSET, opt, req

_FILM_KEYS = {
    "film": opt("string", "seam", "film: periodic or seam", choices=("periodic", "seam")),
    "seam_angle_deg": opt("seam_angle", 180.0, "welded end from the load line [deg], or "
                          "'max_film'"),
    "subambient": opt("string", UNSET, "force from sub-ambient pressure (default full)",
                      choices=("full", "gumbel")),
}
_ROTOR = {
    "bearing": req("string", "bearing file (SI), relative to the study file"),
    "rotor_mass_kg": req("number", "rotor mass per bearing [kg]", positive=True),
    "load_newton": req("number", "static load per bearing [N]", positive=True),
    "speed_range_rpm": req("numbers", "[low, high] speeds searched for the onset [rpm]",
                           length=2),
}

SCHEMAS: dict[str, dict] = {
    "onset_conventions": {**GRID, **_ROTOR,
        "seam_angles_deg": req("numbers", "welded-end angles from the load line [deg], in "
                               "[0, 360)"),
        "model": opt("table", {}, "foil formulation (film and seam are swept); what it does "
                     "not state comes from the bearing file's [model], else the defaults",
                     keys={
            "foil": opt("string", UNSET, "foil model (default simple)",
                        choices=("simple", "beam")),
            "deflection_law": opt("string", UNSET, "foil deflection law (default mean)",
                                  choices=DEFLECTION_LAWS),
            "loss_factor": opt("number", UNSET, "structural loss factor η [-] (default 0)",
                               minimum=0.0)}),
        "fine_grid": opt("grid", "144x36", "grid of the reference onsets"),
        "fine_grid_onset_rpm": opt("mapping", {}, "onset speeds [rpm] at fine_grid per "
                                   "convention: periodic, max_film, seam_<deg> (e.g. "
                                   "seam_180)", values=req("number", "onset speed [rpm]")),
        "fine_grid_tolerance": opt("number", 0.02, "largest |onset / fine-grid onset − 1|",
                                   minimum=0.0)}
}


# ------------------------------------------------------------------ points (module level:
# they are pickled to the workers)
def onset_point(bearing, rotor_mass_kg: float, load_newton: float, speed_range, *,
                film: str, seam_angle_deg, foil: str, deflection_law: str, loss_factor: float,
                grid: Grid, cache=None, running=None) -> dict:
    """The onset speed of one rotor on one formulation, as a row with ``onset_status``;
    with ``running`` (the bearing file's RunningSpec with ``[journal]``/``[thermal]``) at
    the running condition of each speed (:func:`.running_points.running_onset_row`)."""
    from ..inputs.rotor import Rotor
    from ..rotor import onset_speed

    if running is not None:
        from .running_points import running_onset_row

        return running_onset_row(bearing, running, rotor_mass_kg, load_newton, speed_range,
                                 film=film, seam_angle_deg=seam_angle_deg, foil=foil,
                                 deflection_law=deflection_law, loss_factor=loss_factor,
                                 grid=grid, cache=cache)

    t0 = time.perf_counter()
    row = {"onset_speed_rpm": math.nan, "whirl_frequency_hz": math.nan,
           "whirl_ratio": math.nan, "onset_status": FAILED, "smallest_margin": math.nan,
           "critical_mass_kg_at_low_speed": math.nan}
    try:
        res = onset_speed(bearing, Rotor(rotor_mass_kg), load_newton, speed_range, film=film,
                          seam_angle_deg=seam_angle_deg, foil=foil,
                          deflection_law=deflection_law,
                          loss_factor=loss_factor, grid=grid, cache=cache)
    except ParameterError as exc:
        overload = "load capacity" in str(exc)
        return {**row, "onset_status": OVERLOAD if overload else FAILED, "success": overload,
                "message": str(exc), "wall_time_s": time.perf_counter() - t0}
    first = res.scan[0]
    if res.unstable_at_lower_end:
        status = UNSTABLE_ALL if first["critical_mass"] == 0 else UNSTABLE_LOW
    elif res.stable_over_range:
        status = STABLE
    else:
        status = ONSET
    row.update(onset_speed_rpm=res.onset_speed_rpm, whirl_frequency_hz=res.whirl_frequency_hz,
               whirl_ratio=res.whirl_ratio, onset_status=status,
               smallest_margin=res.smallest_margin,
               critical_mass_kg_at_low_speed=rotor_mass_kg * (1 + first["mass_margin"]),
               evaluations=res.evaluations, success=True, message=res.message,
               wall_time_s=time.perf_counter() - t0)
    return row


def reference_load(model: BearingModel, eccentricity: float, grid: Grid, cache=None) -> dict:
    """The load W̄ [-] of ``model`` at ``eccentricity`` (one static solve)."""
    from ..analyses import static_point

    row = static_point(model, eccentricity=eccentricity, grid=grid, cache=cache)
    return {"load": row["load"], "success": row["success"], "message": row.get("message", "")}


def threshold_point(model: BearingModel, load: float, grid: Grid, cache=None) -> dict:
    """Linear critical mass M̄c and whirl ratio at load W̄ (one row)."""
    from ..analyses import linear_threshold_point

    row = linear_threshold_point(model, load=load, grid=grid, cache=cache)
    out = {k: row[k] for k in ("eccentricity", "attitude_angle_deg", "min_film",
                               "critical_mass", "whirl_ratio", "stable_for_all_masses",
                               "success", "message") if k in row}
    # the static continuation in load stopped short of W̄ with the film closing: the load
    # exceeds what this foil can carry (not a solver failure)
    out["load_exceeds_capacity"] = bool(not row["success"] and "continuation stopped"
                                        in str(row.get("message", "")))
    return out


def confirmation_point(model: BearingModel, load: float, grid: Grid, method: str,
                       tolerance: float, cache=None) -> dict:
    """Transient critical mass (Kelvin–Voigt foil state, τ_f = η/ν_ref with ν_ref the
    threshold whirl ratio; transients started on the least-stable linear mode) against the
    linear hysteretic one at load W̄."""
    from ..analyses import _solver
    from ..linear import linear_threshold, linearise
    from ..static import solve_static
    from ..transient import find_critical_mass, transient_model
    from ..transient.mode import linear_mode

    t0 = time.perf_counter()
    solver = _solver(model, grid, cache)
    sol = solve_static(model, load=load, solver=solver)
    row = {"eccentricity": sol.eccentricity, "linear_critical_mass": math.nan,
           "linear_whirl_ratio": math.nan, "critical_mass": math.nan,
           "nonlinear_over_linear": math.nan, "transients": 0, "success": False,
           "message": sol.message}
    if not sol.success:
        return row
    lin = linearise(sol, solver)
    thr = linear_threshold(lin)
    row.update(linear_critical_mass=thr.critical_mass, linear_whirl_ratio=thr.whirl_ratio)
    if not (math.isfinite(thr.critical_mass) and thr.critical_mass > 0):
        return {**row, "message": f"no finite linear threshold ({thr.critical_mass})"}
    mode = linear_mode(lin, thr.critical_mass, 1j * thr.whirl_ratio)
    crit = find_critical_mass(transient_model(sol, threshold=thr), tolerance=tolerance,
                              linear_estimate=thr.critical_mass, initial_mode=mode,
                              method=method)
    row.update(critical_mass=crit.critical_mass,
               nonlinear_over_linear=crit.critical_mass / thr.critical_mass,
               transients=crit.transients, success=bool(crit.success), message=crit.message,
               wall_time_s=time.perf_counter() - t0)
    return row


# ------------------------------------------------------------------ helpers
def _seam(value):
    """seam_angle_deg of a study file → the rotor API's seam_angle_deg (deg or 'max_film')."""
    return "max_film" if value == "max_film" else float(value)


def _convention_label(film: str, seam) -> str:
    if film == "periodic":
        return "periodic"
    return "max_film" if seam == "max_film" else f"seam_{float(seam):g}"


def _speed_range(study: Study, where=("speed_range_rpm",), value=None):
    low, high = value if value is not None else study.spec["speed_range_rpm"]
    if not 0 < low < high:
        raise study.where(*where).error([low, high], "must be [low, high] with 0 < low < high "
                                        "[rpm]")
    return float(low), float(high)


def _status_text(row) -> str:
    if row["onset_status"] == ONSET:
        return f"{row['onset_speed_rpm']:,.0f} rpm"
    return row["onset_status"]


# ------------------------------------------------------------------ onset_conventions
def plan_onset_conventions(study: Study) -> dict:
    spec = study.spec
    bearing, running = load_running_geometry(study)     # [journal]/[thermal] read
    speed_range = _speed_range(study)
    for k, angle in enumerate(spec["seam_angles_deg"]):
        if not 0.0 <= angle < 360.0:
            raise study.where("seam_angles_deg", k).error(angle, "must lie in [0, 360) degrees")
    # the study's [model], then the bearing file's, then the defaults (the one resolution of
    # gfbopt.inputs.options.merge_options; film and seam are swept, so not taken from the file)
    from ..inputs.options import BUMP_OPTION_NAMES, ModelOptions, merge_options

    file_options = bearing.options
    try:                      # a study foil the file's bumps cannot keep: name the study key
        resolved = merge_options(
            ModelOptions(foil=spec["model"].get("foil"),
                         deflection_law=spec["model"].get("deflection_law"),
                         loss_factor=spec["model"].get("loss_factor")),
            ModelOptions(foil=file_options.foil, deflection_law=file_options.deflection_law,
                         loss_factor=file_options.loss_factor,
                         **{key: getattr(file_options, key) for key in BUMP_OPTION_NAMES}))
    except ParameterError as exc:
        raise study.where("model", exc.name).error(exc.value, exc.rule) from None
    model = {"foil": resolved.foil, "deflection_law": resolved.deflection_law,
             "loss_factor": resolved.loss_factor}
    # the bearing file's bumps (friction, hardening): each onset point resolves them from
    # bearing.options too; stated here so that the outputs name them
    bump = {key: getattr(resolved, key) for key in BUMP_OPTION_NAMES
            if getattr(resolved, key) is not None}
    if model["foil"] == "beam" and model["loss_factor"] > 0:
        raise study.where("model", "loss_factor").error(model["loss_factor"],
                                                        "is not supported with the beam foil")
    try:                # the bumps' options with this foil (e.g. friction with the beam)
        bearing.model(1000.0, **resolved.model_kwargs())
    except ParameterError as exc:
        raise study.where("bearing").error(spec["bearing"], f"{exc.name} = {exc.value}: "
                                           f"{exc.rule}") from None
    conventions = [("periodic", None), ("seam", "max_film")] + [
        ("seam", float(a)) for a in spec["seam_angles_deg"]]
    known = {_convention_label(f, s) for f, s in conventions}
    for name in spec["fine_grid_onset_rpm"]:
        if name not in known:
            raise study.where("fine_grid_onset_rpm", name).error(
                spec["fine_grid_onset_rpm"][name], "is not a convention of the study "
                "(periodic, max_film or seam_<deg> of seam_angles_deg)")
    common = {"bearing": bearing, "rotor_mass_kg": spec["rotor_mass_kg"],
                  "load_newton": spec["load_newton"], "speed_range": speed_range,
                  "foil": model["foil"], "deflection_law": model["deflection_law"],
                  "loss_factor": model["loss_factor"], "grid": study.grid}
    from ..thermal.running import ISOTHERMAL

    if running.model_name != ISOTHERMAL:        # each onset at the running condition
        from ..inputs.rotor_limits import check_surface_speed

        check_surface_speed(bearing, list(speed_range), f"{study.file}: speed_range_rpm")
        common["running"] = running
    points = [{**common, "film": f, "seam_angle_deg": None if s is None else _seam(s)}
              for f, s in conventions]
    tags = [{"convention": _convention_label(f, s), "film": f,
             "seam_angle_deg": s if s is not None else "none"} for f, s in conventions]
    return {"points": points, "tags": tags, "bearing": bearing, "bump": bump,
            "thermal_model": common.get("running") and running.model_name}


_CONVENTION_TITLES = {"periodic": "periodic film (no seam)",
                      "max_film": "seam on the maximum-film line (thesis)"}


def run_onset_conventions(study: Study, plan: dict, ctx: RunContext) -> StudyResult:
    from ..plotting.stability import plot_onset_against_seam

    spec = study.spec
    t0 = time.perf_counter()
    rows = run_points(onset_point, plan["points"], workers=ctx.workers, tags=plan["tags"],
                      progress=ctx.progress)
    elapsed = time.perf_counter() - t0
    table = frame(rows, ("convention", "film", "seam_angle_deg", "onset_speed_rpm",
                         "onset_status"), ("onset_speed_rpm",))
    low, high = _speed_range(study)
    by = {r["convention"]: r for r in rows}
    title = (f"Onset speed of whirl against the top foil's welded-end angle: "
             f"{spec['rotor_mass_kg']:g} kg, {spec['load_newton']:g} N per bearing, "
             f"{plan['bearing'].name}")
    ax = plot_onset_against_seam(table, speed_range=(low, high), title=title,
                                 conventions=_CONVENTION_TITLES)
    found = [checks.check("every onset search converged (failed rows)",
                          float((table["onset_status"] == FAILED).sum()), 0)]
    for name, reference in spec["fine_grid_onset_rpm"].items():
        value = by[name]["onset_speed_rpm"] if name in by else math.nan
        found.append(checks.check(f"{name}: onset at {study.grid} against {spec['fine_grid']}"
                                  f" ({reference:g} rpm), |relative difference|",
                                  abs(value / reference - 1.0) if math.isfinite(value)
                                  else math.nan, spec["fine_grid_tolerance"]))
    notes = _convention_notes(table, by)
    notes.append(f"{len(rows)} onset searches in {elapsed:.1f} s on {ctx.workers} worker "
                 f"process{'es' if ctx.workers > 1 else ''}, grid {study.grid}")
    model = plan["points"][0]
    options = {"variants": {"all": {"foil": model["foil"],
                                    "deflection_law": model["deflection_law"],
                                    "loss_factor": model["loss_factor"],
                                    **plan.get("bump", {})}},
               "grid": str(study.grid), "rotor_mass_kg": spec["rotor_mass_kg"],
               "load_newton": spec["load_newton"], "speed_range_rpm": [low, high]}
    if plan.get("thermal_model"):                # the clearance at speed, named
        from .running_points import running_notes

        options["thermal_model"] = plan["thermal_model"]
        notes += running_notes(plan["thermal_model"], study.spec["bearing"])
    return StudyResult(study, tables={"onset.csv": table},
                       figures={"onset_speed.png": ax.figure}, checks=found, options=options,
                       notes=notes, answer=({"thermal_model": plan["thermal_model"]}
                                            if plan.get("thermal_model") else {}))


def _convention_notes(table, by: dict) -> list:
    seams = table[table["convention"].str.startswith("seam_")]
    onset = seams[seams["onset_status"] == ONSET]
    notes = []
    per = "; ".join(f"{r['seam_angle_deg']:g}°: {_status_text(r)}" for _, r in seams.iterrows())
    p, m = by.get("periodic"), by.get("max_film")
    if p is not None and m is not None:
        notes.append(f"Periodic film: {_status_text(p)}; seam on the maximum-film line: "
                     f"{_status_text(m)}.")
    if len(onset):
        best = onset.loc[onset["onset_speed_rpm"].idxmax()]
        worst = onset.loc[onset["onset_speed_rpm"].idxmin()]
        notes.append(f"Welded end at a fixed housing angle: onset from "
                     f"{worst['onset_speed_rpm']:,.0f} rpm (at {worst['seam_angle_deg']:g}°) "
                     f"to {best['onset_speed_rpm']:,.0f} rpm (at {best['seam_angle_deg']:g}°),"
                     f" a factor {best['onset_speed_rpm'] / worst['onset_speed_rpm']:.2f}.")
        if p is not None and p["onset_status"] == ONSET:
            notes.append(f"How much the convention matters: the fixed-seam onset ranges from "
                         f"{worst['onset_speed_rpm'] / p['onset_speed_rpm']:.2f}× to "
                         f"{best['onset_speed_rpm'] / p['onset_speed_rpm']:.2f}× the periodic "
                         "film's" + (f", the max-film seam's is "
                                     f"{m['onset_speed_rpm'] / p['onset_speed_rpm']:.2f}×"
                                     if m is not None and m["onset_status"] == ONSET else "")
                         + ".")
    other = seams[seams["onset_status"] != ONSET]
    if len(other):
        notes.append("Welded-end angles without an onset in the range: " + "; ".join(
            f"{r['seam_angle_deg']:g}° ({r['onset_status']})" for _, r in other.iterrows())
            + ".")
    notes.append("Per welded-end angle: " + per + ".")
    return notes


def _dispatch(which: str, call: dict, cache=None) -> dict:
    function = {"confirm": confirmation_point, "onset": onset_point,
                "map": threshold_point}[which]
    return function(**call, cache=cache)


def _film_text(base: dict) -> str:
    if base.get("film") == "periodic":
        return "periodic film"
    seam = base.get("seam_angle_deg", 180.0)
    return ("seam on the max-film line" if seam == "max_film"
            else f"welded end {seam:g}° from the load")


KINDS = {"onset_conventions": Kind(plan_onset_conventions, run_onset_conventions,
                                   parallel=True)}
