"""Study kind ``pitch_design``: choose a bump foil for rotor stability
(:mod:`gfbopt.design.stability_design`) and report it for people.

The study file names the bearing (housing, clearance, baseline bump foil), the rotor and its
load per bearing, the speed range, the film-thickness limit, the manufacturing ranges and
stress limits of the bump foil, and the foundation laws and loss factors to search.  The
results are the recommendation (a plain-language summary at the top of the README), the
optimum of every (law, η) as a band of S with the baseline beside it, the trade-off table of
every evaluated S (geometry, stress, onset speed, minimum film, binding limits), the nonlinear
confirmation and a figure of onset speed against S and against pitch with the limits drawn.
A bearing file stating ``[journal]``/``[thermal]`` has every S evaluated at the running
condition of each speed (:mod:`gfbopt.design.running_evaluation`, the functions of ``gfbopt
stability``); summary.json and the README name the thermal model.
"""
from __future__ import annotations

import functools
import time

from ..design.spec import BumpDesignSpec
from ..design.stability_design import StabilityDesignSpec, design_for_stability
from ..inputs import Grid
from ..inputs.options import ModelOptions, merge_options
from ..inputs.rotor import Rotor
from ..parallel import run_points
from .base import Kind, RunContext, Study, StudyResult, load_running_geometry
from .checks import check
from .spec import GRID, UNSET, opt, req

SCHEMAS = {
    "pitch_design": {**GRID,
        "bearing": req("string", "bearing file (SI): housing, clearance, baseline bump foil"),
        "rotor_mass_kg": req("number", "rotor mass carried by one bearing [kg]",
                             positive=True),
        "load_newton": opt("number", None, "static load on one bearing [N] (default: the "
                           "rotor's weight)", positive=True),
        "speed_range_rpm": req("numbers", "speeds searched for the onset of whirl [rpm]",
                               length=2),
        "min_film_thickness_um": req("number", "smallest admissible minimum film at the "
                                     "design load [µm]", positive=True),
        "film_check_speed_rpm": opt("number", None, "speed of the film check [rpm] "
                                    "(default: the low end of the range)", positive=True),
        "loss_factors": opt("numbers", [0.0, 0.1, 0.2, 0.3], "structural loss factors η "
                            "searched [-]"),
        "deflection_laws": opt("strings", ["mean", "local"], "foundation laws searched",
                               choices=("mean", "local")),
        "film": opt("string", UNSET, "film convention (default: the bearing file's [model], "
                    "else a seam)", choices=("periodic", "seam")),
        "seam_angle_deg": opt("number", UNSET, "top-foil welded end from the load [deg] "
                              "(default: the bearing file's [model], else 180)", minimum=0.0),
        "scan_points": opt("integer", 7, "scan points of S per (law, η)", minimum=3),
        "pitch_range_mm": req("numbers", "bump pitch range [mm]", length=2),
        "half_length_range_mm": req("numbers", "half bump length range [mm]", length=2),
        "thickness_range_um": req("numbers", "bump foil thickness range [µm]", length=2),
        "gap_mm": opt("number", 0.2, "gap between bumps: 2 l0 + gap ≤ pitch [mm]",
                      minimum=0.0),
        "allowable_stress_mpa": opt("number", None, "allowable bump bending stress [MPa] "
                                    "(default: the material's)", positive=True),
        "design_pressure_bar": opt("number", 1.0, "gauge pressure of the stress check [bar]",
                                   positive=True),
        "material": opt("string", "inconel-x750", "bump foil material"),
        "confirmation_tolerance": opt("number", 0.01, "largest |nonlinear/linear − 1| of the "
                                      "critical mass in the confirmation", minimum=0.0)},
}


def plan_pitch_design(study: Study) -> StabilityDesignSpec:
    """The design specification, validated before any solve (errors name the file).  A
    bearing file stating ``[journal]``/``[thermal]`` gives the running condition every trial
    S is evaluated at (:mod:`gfbopt.design.running_evaluation`)."""
    from ..design.running_evaluation import heated

    s = study.spec
    bearing, running = load_running_geometry(study)     # [journal]/[thermal] read
    if heated(running):
        from ..inputs.rotor_limits import check_surface_speed

        check_surface_speed(bearing, list(s["speed_range_rpm"]),
                            f"{study.file}: speed_range_rpm")
    try:
        geometry = BumpDesignSpec(
            radial_clearance=bearing.radial_clearance, radius=bearing.radius,
            ambient_pressure=bearing.ambient_pressure, material=s["material"],
            youngs_modulus=bearing.bump_youngs_modulus, poisson_ratio=bearing.poisson_ratio,
            allowable_stress=(None if s["allowable_stress_mpa"] is None
                              else s["allowable_stress_mpa"] * 1e6),
            design_pressure=s["design_pressure_bar"] * 1e5,
            pitch_range=tuple(v * 1e-3 for v in s["pitch_range_mm"]),
            half_length_range=tuple(v * 1e-3 for v in s["half_length_range_mm"]),
            thickness_range=tuple(v * 1e-6 for v in s["thickness_range_um"]),
            gap=s["gap_mm"] * 1e-3)
        # what the study states, then the bearing file's [model] table, then the defaults:
        # the resolution every route uses (gfbopt.inputs.options.merge_options)
        film = s.get("film")
        stated = ModelOptions(film=film, foil="simple", seam_angle_deg=None
                              if film == "periodic" else s.get("seam_angle_deg"))
        return StabilityDesignSpec(
            bearing=bearing, rotor=Rotor(s["rotor_mass_kg"]), load_newton=s["load_newton"],
            speed_range_rpm=tuple(s["speed_range_rpm"]),
            min_film_thickness_m=s["min_film_thickness_um"] * 1e-6, geometry=geometry,
            film_check_speed_rpm=s["film_check_speed_rpm"],
            loss_factors=tuple(s["loss_factors"]),
            deflection_laws=tuple(s["deflection_laws"]),
            options=merge_options(stated, bearing.options),
            grid=Grid.parse(s["grid"]), n_scan=s["scan_points"],
            running=running if heated(running) else None)
    except Exception as exc:          # ParameterError from any input: name the file
        name = getattr(exc, "name", "design")
        raise study.where(name).error(getattr(exc, "value", None),
                                      getattr(exc, "rule", str(exc))) from None


def load_in_g(mass_kg: float, load_newton: float) -> str:
    """The static load per bearing as a multiple of the rotor's weight (computed, so that a
    note cannot misstate it): 20 N on 2 kg is 1.02 g."""
    from ..inputs.conversions import STANDARD_GRAVITY, rotor_weight_newton

    weight = rotor_weight_newton(mass_kg)
    return (f"Load: W0 = {load_newton:g} N per bearing on {mass_kg:g} kg per bearing, i.e. "
            f"{load_newton / weight:.2f} g (the rotor's weight is {weight:.3g} N at g = "
            f"{STANDARD_GRAVITY} m/s²).")


def _summary(spec: StabilityDesignSpec, result) -> list:
    """Plain-language recommendation, for the top of the README."""
    rec = result.recommended
    geo = rec.get("geometry", {})
    opt = result.optima.iloc[0]
    low, high = spec.speed_range_rpm
    base_s = spec.bearing.compliance
    lines = []
    if not result.success:
        return [f"No recommendation: {result.message}"]
    law = "axial-mean" if rec["deflection_law"] == "mean" else "local"
    onset = rec["onset_speed_rpm"]
    onset_text = (f"stable over the whole range up to {high:,.0f} rpm" if onset >= high
                  else f"onset of whirl at {onset:,.0f} rpm")
    lines.append(
        f"Recommended bump foil (for the {law} foundation law, loss factor η = "
        f"{rec['loss_factor']:g}, no credit for more damping): pitch "
        f"{geo['pitch'] * 1e3:.3f} mm ({geo['number_of_bumps']} bumps), half bump length "
        f"{geo['half_length'] * 1e3:.3f} mm, bump thickness {geo['thickness'] * 1e6:.1f} µm, "
        f"giving S = {geo['compliance']:.3g} and a bump stress of "
        f"{geo['bump_stress'] / 1e6:.0f} MPa at {spec.geometry.design_pressure / 1e5:g} bar: "
        f"{onset_text} for the {spec.rotor.mass_kg:g} kg rotor, against "
        f"{opt['baseline_onset_speed_rpm']:,.0f} rpm with the original foil "
        f"(S = {base_s:.3g}).")
    bound = opt["decided_by_bound"]
    if bound:
        lines.append(
            f"Why: under this law the best S sits on the {'lower' if bound == 'low' else 'upper'}"
            f" end of what the bump foil can reach ({result.compliance_range[0]:.3g}–"
            f"{result.compliance_range[1]:.3g}) — the limit decides, not an optimum of the "
            "physics: the stiffer the bumps, the later the whirl. The binding geometric "
            f"limits are: {', '.join(geo.get('binding_constraints', [])) or 'none'}.")
    else:
        lines.append(f"Why: an interior optimum of the onset speed at S = "
                     f"{opt['best_compliance']:.3g}; every S in {opt['band_low']:.3g}–"
                     f"{opt['band_high']:.3g} is within 2 % of it.")
    for _, row in result.optima.iloc[1:].iterrows():
        if not row["success"]:
            continue
        lines.append(
            f"Under the {'axial-mean' if row['deflection_law'] == 'mean' else 'local'} law "
            f"with η = {row['loss_factor']:g} the best S is {row['best_compliance']:.3g} "
            f"(band {row['band_low']:.3g}–{row['band_high']:.3g}, onset "
            f"{row['best_onset_speed_rpm']:,.0f} rpm; original foil "
            f"{row['baseline_onset_speed_rpm']:,.0f} rpm)"
            + (f", decided by the {row['decided_by_bound']} bound" if row["decided_by_bound"]
               else "") + ".")
    inside = rec.get("inside_bands_of", [])
    lines.append("The recommended S lies inside the near-best band of "
                 + (", ".join(inside) if inside else "none of the other cases")
                 + ": the honest answer to 'which pitch is best' depends on the foundation "
                 "law and the damping one believes in, as the table shows.")
    lines.append(load_in_g(spec.rotor.mass_kg, spec.load_newton))
    conf = result.confirmation
    if conf.get("success"):
        lines.append(f"Nonlinear check at {conf['speed_rpm']:,.0f} rpm: transient critical "
                     f"mass {conf['nonlinear_critical_mass_kg']:.4g} kg against the linear "
                     f"{conf['linear_critical_mass_kg']:.4g} kg "
                     f"(ratio {conf['nonlinear_over_linear']:.5f}).")
    return lines


def run_pitch_design(study: Study, spec: StabilityDesignSpec,
                     context: RunContext) -> StudyResult:
    from ..plotting.design import plot_design_against_compliance, plot_design_against_pitch

    t0 = time.perf_counter()
    runner = functools.partial(run_points, workers=context.workers)
    result = design_for_stability(spec, runner, progress=context.progress)
    tables = {"optima.csv": result.optima, "tradeoff.csv": result.tradeoff,
              "baseline.csv": result.baseline}
    rec = result.recommended
    if "geometry" in rec:
        import pandas as pd

        geo = {k: v for k, v in rec["geometry"].items()
               if not isinstance(v, (list, tuple, dict))}
        tables["recommended.csv"] = pd.DataFrame([{**geo, **{
            k: rec[k] for k in ("deflection_law", "loss_factor", "onset_speed_rpm")}}])
    limits = {"compliance_range": result.compliance_range,
              "baseline_compliance": spec.bearing.compliance,
              "min_film_thickness_um": spec.min_film_thickness_m * 1e6}
    title = study.spec["title"]
    figures = {
        "onset_vs_compliance.png": plot_design_against_compliance(
            result.tradeoff, limits, title=title).figure,
        "onset_vs_pitch.png": plot_design_against_pitch(
            result.tradeoff, limits, title=title).figure}
    checks = [check("recommendation found and realised by a bump foil (0 = yes)",
                    0.0 if result.success else 1.0, 0.0)]
    conf = result.confirmation
    if conf.get("success"):
        checks.append(check("nonlinear transient confirms the recommended design: "
                            "|nonlinear/linear critical mass − 1|",
                            abs(conf["nonlinear_over_linear"] - 1.0),
                            study.spec["confirmation_tolerance"]))
    else:
        checks.append(check(f"nonlinear confirmation ran ({conf.get('message', '')})", 1.0,
                            0.0))
    options = {"variants": {"design": {"foil": "simple", "film": spec.options.film,
                                       "seam_angle_deg": study.spec["seam_angle_deg"],
                                       "deflection_laws": list(spec.deflection_laws),
                                       "loss_factors": list(spec.loss_factors)}},
               "grid": str(spec.grid), "method": "linear onset search; rkc confirmation"}
    notes, answer = _summary(spec, result), {}
    if spec.running is not None:                 # the clearance at speed, named
        options["thermal_model"] = answer["thermal_model"] = spec.running.model_name
        notes.append(running_design_note(spec.running.model_name, study.spec["bearing"]))
    return StudyResult(study, tables=tables, figures=figures, checks=checks, options=options,
                       notes=notes, answer=answer, wall_time_s=time.perf_counter() - t0)


def running_design_note(thermal_model: str, bearing_file: str) -> str:
    """The README/summary note of a design at the running condition (its model named)."""
    return (f"Clearance at speed: the bearing file {bearing_file} states the running "
            f"condition ({thermal_model}); every trial S, the original foil and the nonlinear "
            "check are evaluated at the running clearance and viscosity of each speed, "
            "through the functions `gfbopt stability` calls (gfbopt.rotor.running_bearing), "
            "so an onset of the trade-off table equals `gfbopt stability --bearing FILE "
            "--speed-range LOW HIGH` on a file with that row's S (its bump foil); the minimum "
            "film is that of the film-check speed's own running clearance, and the columns "
            "thermal_model … viscosity_pa_s give the running point at the onset.")


KINDS = {"pitch_design": Kind(plan_pitch_design, run_pitch_design, parallel=True)}
