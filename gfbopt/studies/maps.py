"""Stability study kinds: critical mass against an operating variable, or at given points.

* ``linear_map`` — the linear critical mass against ε or Λ per foil variant, where the
  curves cross, beside published crossovers and critical masses;
* ``transient_map`` — the nonlinear critical mass from transients against ε or Λ, with the
  linear threshold beside it (thesis Figs 3.12, 3.13, 4.9, 4.10);
* ``transient_points`` — nonlinear against linear critical mass at a list of points.

Points are independent, so these kinds run on the process pool (``workers``); each worker
builds one static solver per formulation (:mod:`gfbopt.parallel`).
"""
from __future__ import annotations

import math
import time

import numpy as np

from .. import analyses
from ..parallel import run_points
from . import checks
from .base import (
    RunContext,
    Study,
    StudyResult,
    build_model,
    frame,
    merged,
    options_of,
    variant_titles,
)
from .published import crossovers_for, curve_model, load_published

_MAP_COLUMNS = ("variant", "eccentricity", "bearing_number")
#: outputs a map needs even when every point failed
_OUTPUTS = ("critical_mass", "whirl_ratio", "linear_critical_mass", "nonlinear_over_linear")


def plan_map(study: Study) -> dict:
    """Models and points of a map study; cross-references of the file checked."""
    spec = study.spec
    variable = spec["sweep"]["variable"]
    other = "bearing_number" if variable == "eccentricity" else "eccentricity"
    fixed = spec["fixed"]
    if other not in fixed:
        raise study.where("fixed", other).error(None, f"is required when sweeping {variable}")
    if variable in fixed:
        raise study.where("fixed", variable).error(fixed[variable], "is swept ([sweep]); do "
                                                   "not also fix it")
    labels = [v["label"] for v in spec["variants"]]
    for k, pair in enumerate(spec["crossover_pairs"]):
        for label in pair:
            if label not in labels:
                raise study.where("crossover_pairs", k).error(
                    pair, f"'{label}' is not a variant ({', '.join(labels)})")
    points, models = [], {}
    for k, variant in enumerate(spec["variants"]):
        for key in ("bearing_number", "length_ratio"):
            if key in variant:
                raise study.where("variants", k, key).error(
                    variant[key], "is set by [sweep] or [fixed] in a map study")
        for value in spec["sweep"]["values"]:
            at = {**fixed, variable: float(value)}
            opts = merged(spec["model"], variant, {"bearing_number": at["bearing_number"],
                                                   "length_ratio": at["length_ratio"]})
            model = build_model(opts, study.where("variants", k))
            models.setdefault(variant["label"], []).append(model)
            points.append({"variant": variant["label"], "model": model,
                           "eccentricity": at["eccentricity"]})
    crossovers, published = [], []
    if spec["published"] is not None:
        data = load_published(study)
        crossovers = crossovers_for(study, data, models)
        if study.kind == "linear_map":       # thresholds at the published critical masses
            published = [{**p, "reference": data["reference"],
                          "model": curve_model(data, p["curve"], spec["model"],
                                               {"bearing_number": p["bearing_number"]},
                                               study.where("published"))}
                         for p in data["critical_masses"]]
    return {"points": points, "published": published, "models": models,
            "crossovers": crossovers}


def _map_figure(study: Study, table, crossovers, titles, linear: bool):
    from ..plotting import plot_stability_map

    ax = plot_stability_map(table, study.spec["sweep"]["variable"], title=study.spec["title"],
                            crossovers=crossovers, labels=titles, linear=linear)
    return ax.figure


def _crossovers(study: Study, plan: dict, table, titles) -> tuple:
    spec = study.spec
    crossovers = checks.crossover_table(table, spec["sweep"]["variable"],
                                        spec["crossover_pairs"], plan["crossovers"])
    compared = checks.crossover_comparisons(crossovers, plan["crossovers"], titles)
    return crossovers, compared


def _tags(points: list) -> list:
    return [{"variant": p["variant"], "eccentricity": p["eccentricity"],
             "bearing_number": p["model"].bearing_number} for p in points]


def run_linear_map(study: Study, plan: dict, ctx: RunContext) -> StudyResult:
    spec = study.spec
    points, published = plan["points"], plan["published"]
    calls = [{"model": p["model"], "eccentricity": p["eccentricity"], "grid": study.grid}
             for p in points + published]
    rows = run_points(analyses.linear_threshold_point, calls, workers=ctx.workers,
                      tags=_tags(points) + [{"label": p["label"]} for p in published],
                      progress=ctx.progress)
    table = frame(rows[:len(points)], _MAP_COLUMNS, _OUTPUTS[:2])
    titles = variant_titles({label: ms[0] for label, ms in plan["models"].items()})
    crossovers, compared = _crossovers(study, plan, table, titles)
    tables = {"map.csv": table, "crossovers.csv": crossovers}
    if published:
        ours = rows[len(points):]
        pub = frame([{"label": p["label"], "eccentricity": p["eccentricity"],
                      "bearing_number": p["model"].bearing_number,
                      f"critical_mass_{p['reference']}": p["critical_mass"],
                      "critical_mass": r.get("critical_mass", math.nan),
                      "critical_mass_published_over_ours":
                          p["critical_mass"] / r.get("critical_mass", math.nan),
                      "whirl_ratio": r.get("whirl_ratio", math.nan), "where": p["where"]}
                     for p, r in zip(published, ours)])
        tables["published_points.csv"] = pub
        for p, r in zip(published, ours):
            compared.append(checks.comparison(
                f"{titles.get(p['curve'], p['curve'])} at ε = {p['eccentricity']:g}, "
                f"Λ = {p['bearing_number']:g}: our linear critical mass against the "
                f"published one ({p['where']}), relative", p["reference"],
                r.get("critical_mass", math.nan) / p["critical_mass"] - 1.0, p["tolerance"]))
    found = [checks.all_converged(table, "all points converged")]
    if spec["whirl_ratio_range"] is not None:
        low, high = spec["whirl_ratio_range"]
        w = table["whirl_ratio"]
        found.append(checks.check(f"whirl ratio at the threshold within [{low:g}, {high:g}]: "
                                  "largest distance outside",
                                  float(max(low - w.min(), w.max() - high, 0)), 0))
    if "critical_mass_increases_with_eccentricity" in spec["trends"]:
        found += checks.monotone(table, "critical_mass", "eccentricity", True, ["variant"],
                                 "M̄c rises with ε (largest fall)")
    return StudyResult(study, tables=tables,
                       figures={"critical_mass.png": _map_figure(study, table, crossovers,
                                                                 titles, False)},
                       checks=found, comparisons=compared,
                       options=options_of(plan["models"], study.grid))


def _search(spec: dict) -> dict:
    """Arguments of :func:`gfbopt.analyses.critical_mass_point` from the study's keys."""
    return {"tolerance": spec["critical_mass_tolerance"], "revolutions": spec["revolutions"],
            "method": spec["method"], "start": spec["start"]}


def _search_options(spec: dict) -> dict:
    """The transient-search settings as the study file names them (for the provenance)."""
    return {k: spec[k] for k in ("critical_mass_tolerance", "revolutions", "method",
                                 "start")}


def run_transient_map(study: Study, plan: dict, ctx: RunContext) -> StudyResult:
    spec = study.spec
    points = plan["points"]
    t0 = time.perf_counter()
    rows = run_points(analyses.critical_mass_point,
                      [{"model": p["model"], "eccentricity": p["eccentricity"],
                        "grid": study.grid, **_search(spec)} for p in points],
                      workers=ctx.workers, tags=_tags(points), progress=ctx.progress)
    elapsed = time.perf_counter() - t0
    table = frame(rows, _MAP_COLUMNS, _OUTPUTS)
    titles = variant_titles({label: ms[0] for label, ms in plan["models"].items()})
    crossovers, compared = _crossovers(study, plan, table, titles)
    deviation = float((table["nonlinear_over_linear"] - 1).abs().max())
    found = [checks.all_converged(table, "all points converged"),
             checks.check("largest |nonlinear / linear critical mass − 1| over the map",
                          deviation, spec["nonlinear_linear_tolerance"])]
    return StudyResult(study, tables={"map.csv": table, "crossovers.csv": crossovers},
                       figures={"critical_mass.png": _map_figure(study, table, crossovers,
                                                                 titles, True)},
                       checks=found, comparisons=compared,
                       options=options_of(plan["models"], study.grid, **_search_options(spec)),
                       notes=[f"{len(points)} points in {elapsed:.1f} s on {ctx.workers} "
                              f"worker process{'es' if ctx.workers > 1 else ''}"])


def plan_transient_points(study: Study) -> list:
    spec = study.spec
    out = []
    for k, p in enumerate(spec["points"]):
        opts = {key: v for key, v in p.items() if key not in ("label", "eccentricity")}
        out.append({"variant": p["label"], "eccentricity": p["eccentricity"],
                    "model": build_model(merged(spec["model"], opts),
                                         study.where("points", k))})
    return out


def run_transient_points(study: Study, points: list, ctx: RunContext) -> StudyResult:
    spec = study.spec
    rows = run_points(analyses.critical_mass_point,
                      [{"model": p["model"], "eccentricity": p["eccentricity"],
                        "grid": study.grid, **_search(spec)} for p in points],
                      workers=ctx.workers, progress=ctx.progress,
                      tags=[{"label": p["variant"], "eccentricity": p["eccentricity"],
                             "bearing_number": p["model"].bearing_number} for p in points])
    table = frame(rows, ("label", "eccentricity", "bearing_number"), _OUTPUTS)
    found = [checks.check(f"{r['label']}: |nonlinear / linear critical mass − 1|",
                          abs(r["nonlinear_over_linear"] - 1)
                          if np.isfinite(r["nonlinear_over_linear"]) else math.nan,
                          spec["nonlinear_linear_tolerance"])
             for _, r in table.iterrows()]
    return StudyResult(study, tables={"table.csv": table}, checks=found,
                       options=options_of({p["variant"]: [p["model"]] for p in points},
                                          study.grid, **_search_options(spec)))
