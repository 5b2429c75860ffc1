"""Study kinds that tabulate static and small-motion results at given operating points.

* ``static_table`` — rows of operating points × model variants beside published columns
  (thesis Tables 3.1 and 3.2);
* ``profile`` — pressure, foil deflection and film profiles at one point (thesis Figs
  3.6–3.8), peaks beside the published ones;
* ``grid_convergence`` — load and attitude on grids refined by two: observed order and the
  error of the default grid;
* ``concentric_impedance`` — the impedance near ε = 0 against Ausman's closed form.

Each kind has ``plan_*`` (the models and points, built while the file is validated, so an
inconsistent model is reported before any solve) and ``run_*`` (the computation).
"""
from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .. import analyses
from ..inputs import Grid
from ..parallel import run_points
from ..static import SolverCache
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


def _variant_models(points: list) -> dict:
    """variant label → its models, in the order met."""
    out: dict = {}
    for p in points:
        out.setdefault(p["variant"], []).append(p["model"])
    return out


# ------------------------------------------------------------------- static_table
def plan_static_table(study: Study) -> list:
    """One point per row × variant (rows with S = 0 are solved as the rigid bearing)."""
    spec = study.spec
    labels = [v["label"] for v in spec["variants"]]
    for k, c in enumerate(spec["comparisons"]):
        if c["variant"] not in labels:
            raise study.where("comparisons", k, "variant").error(
                c["variant"], f"must be one of the variants: {', '.join(labels)}")
        if c["reference"] not in spec["references"]:
            raise study.where("comparisons", k, "reference").error(
                c["reference"], f"must be one of references: {', '.join(spec['references'])}")
    points = []
    for k, row in enumerate(spec["rows"]):
        for ref, values in row["published"].items():
            if ref not in spec["references"]:
                raise study.where("rows", k, "published", ref).error(
                    values, f"is not one of references: {', '.join(spec['references'])}")
        for variant in spec["variants"]:
            opts = merged(spec["model"], variant,
                          {key: v for key, v in row.items() if key not in ("eccentricity",
                                                                           "published")})
            model = build_model(opts, study.where("rows", k), rigid_when_no_compliance=True)
            points.append({"variant": variant["label"], "model": model,
                           "eccentricity": row["eccentricity"], "published": row["published"]})
    for k, c in enumerate(spec["comparisons"]):
        for quantity in c["tolerance"]:
            if not any(quantity in r["published"].get(c["reference"], {})
                       for r in spec["rows"]):
                raise study.where("comparisons", k, "tolerance", quantity).error(
                    c["tolerance"][quantity], f"no row publishes {quantity} for "
                    f"{c['reference']}")
    return points


def run_static_table(study: Study, points: list, ctx: RunContext) -> StudyResult:
    spec = study.spec
    rows = run_points(analyses.static_point,
                      [{"model": p["model"], "eccentricity": p["eccentricity"],
                        "grid": study.grid} for p in points],
                      tags=[{"variant": p["variant"]} for p in points], progress=ctx.progress)
    table = checks.add_published_columns(frame(rows, ("variant",)),
                                         [p["published"] for p in points],
                                         tuple(spec["references"]))
    return StudyResult(
        study, tables={"table.csv": table},
        checks=[checks.all_converged(table)],
        comparisons=checks.published_comparisons(table, spec["comparisons"]),
        options=options_of(_variant_models(points), study.grid))


# ------------------------------------------------------------------------ profile
def plan_profile(study: Study) -> list:
    spec = study.spec
    labels = [v["label"] for v in spec["variants"]]
    for k, c in enumerate(spec["comparisons"]):
        if c["variant"] not in labels:
            raise study.where("comparisons", k, "variant").error(
                c["variant"], f"must be one of the variants: {', '.join(labels)}")
        missing = [q for q in c["tolerance"] if q not in spec["published"].get(c["reference"],
                                                                             {})]
        if missing:
            raise study.where("comparisons", k, "tolerance", missing[0]).error(
                c["tolerance"][missing[0]], f"[published.{c['reference']}] has no "
                f"{missing[0]}")
    point = {k: v for k, v in spec["point"].items() if k != "eccentricity"}
    return [{"variant": v["label"],
             "model": build_model(merged(spec["model"], v, point), study.where("variants", k)),
             "eccentricity": spec["point"]["eccentricity"]}
            for k, v in enumerate(spec["variants"])]


def _profile_table(sol) -> pd.DataFrame:
    angles = np.degrees(sol.theta_from_seam)
    table = pd.DataFrame({"angle_from_seam_deg": angles,
                          "theta_deg": np.degrees(sol.theta) % 360,
                          "mean_pressure": sol.mean_pressure,
                          "deflection": sol.deflection[:, 0],
                          "film_thickness": sol.film.min(axis=1),
                          "midplane_pressure": sol.pressure[:, sol.z.size // 2]})
    return table.sort_values("angle_from_seam_deg", kind="stable").reset_index(drop=True)


def _peaks(sol) -> dict:
    angles = np.degrees(sol.theta_from_seam)
    pbar = sol.mean_pressure
    k = int(np.argmax(pbar))
    return {"max_mean_pressure": float(pbar[k]),
            "max_mean_pressure_angle_from_seam_deg": float(angles[k]),
            "max_deflection": float(sol.deflection[:, 0].max()),
            "max_deflection_angle_from_seam_deg":
                float(angles[int(np.argmax(sol.deflection[:, 0]))]),
            "min_film_angle_from_seam_deg": sol.min_film_angle_from_seam_deg}


def run_profile(study: Study, points: list, ctx: RunContext) -> StudyResult:
    from ..plotting import new_axes, plot_pressure_field, plot_profiles

    spec = study.spec
    cache = SolverCache()
    rows, profiles, tables, figures, fields = [], {}, {}, {}, {}
    for p in points:
        sol = analyses.equilibrium(p["model"], eccentricity=p["eccentricity"],
                                   grid=study.grid, cache=cache)
        rows.append({"variant": p["variant"], **_peaks(sol),
                     **analyses.static_row(p["model"], sol)})
        profiles[p["variant"]] = _profile_table(sol)
        tables[f"profile_{p['variant']}.csv"] = profiles[p["variant"]]
        fields[p["variant"]] = (np.degrees(sol.theta_from_seam), sol.z, sol.pressure)
    references = tuple(spec["published"])
    table = checks.add_published_columns(frame(rows, ("variant",)),
                                         [spec["published"]] * len(rows), references)
    titles = variant_titles({p["variant"]: p["model"] for p in points})
    axes = plot_profiles(profiles, published=spec["published"], labels=titles,
                         title=study.spec["title"])
    figures["profiles.png"] = axes[0].figure
    for label, (angle, z, pressure) in fields.items():
        ax = plot_pressure_field(angle, z, pressure, ax=new_axes(figsize=(7.0, 3.6)),
                                 title=f"Film pressure: {titles[label]}")
        figures[f"pressure_field_{label}.png"] = ax.figure
    return StudyResult(
        study, tables={"table.csv": table, **tables}, figures=figures,
        checks=[checks.all_converged(table)],
        comparisons=checks.published_comparisons(table, spec["comparisons"]),
        options=options_of(_variant_models(points), study.grid))


# --------------------------------------------------------------- grid_convergence
def plan_grid_convergence(study: Study) -> list:
    spec = study.spec
    if len(spec["grids"]) < 3:
        raise study.where("grids").error(spec["grids"], "needs at least three grids (the "
                                         "observed order uses the three finest)")
    grids = {Grid.parse(g) for g in [*spec["grids"], spec["default_grid"],
                                     *spec["also_report"]]}
    points = []
    for k, case in enumerate(spec["cases"]):
        opts = {key: v for key, v in case.items() if key not in ("label", "eccentricity")}
        model = build_model(opts, study.where("cases", k))
        for grid in sorted(grids, key=lambda g: g.n_theta * g.n_z):
            points.append({"variant": case["label"], "model": model, "grid": grid,
                           "eccentricity": case["eccentricity"]})
    return points


def _order(values: np.ndarray) -> float:
    return math.log2(abs(values[-3] - values[-2]) / abs(values[-2] - values[-1]))


def run_grid_convergence(study: Study, points: list, ctx: RunContext) -> StudyResult:
    from ..plotting import plot_grid_convergence

    spec = study.spec
    rows = run_points(analyses.static_point,
                      [{"model": p["model"], "eccentricity": p["eccentricity"],
                        "grid": p["grid"]} for p in points],
                      tags=[{"case": p["variant"], "grid": str(p["grid"]),
                             "n_theta": p["grid"].n_theta, "n_z": p["grid"].n_z,
                             "grid_spacing": 1.0 / p["grid"].n_theta} for p in points],
                      progress=ctx.progress)
    table = frame(rows)
    base = [str(Grid.parse(g)) for g in spec["grids"]]
    default = str(Grid.parse(spec["default_grid"]))
    orders, found = [], []
    for label, sub in table.groupby("case", sort=False):
        seq = sub[sub["grid"].isin(base)].sort_values("grid_spacing", ascending=False)
        loads, att = seq["load"].to_numpy(), seq["attitude_angle_deg"].to_numpy()
        load_inf = loads[-1] + (loads[-1] - loads[-2]) / 3.0     # Richardson, formal order 2
        att_inf = att[-1] + (att[-1] - att[-2]) / 3.0
        at = sub.set_index("grid")
        row = {"case": label, "observed_order_load": _order(loads),
               "observed_order_attitude": _order(att), "load_extrapolated": load_inf,
               "attitude_angle_deg_extrapolated": att_inf, "default_grid": default,
               "default_grid_load_error": at.loc[default, "load"] / load_inf - 1.0,
               "default_grid_attitude_error_deg": at.loc[default, "attitude_angle_deg"]
               - att_inf}
        for g in spec["also_report"]:
            g = str(Grid.parse(g))
            row[f"load_error_grid_{g}"] = at.loc[g, "load"] / load_inf - 1.0
        orders.append(row)
        found.append(checks.check(f"{label}: observed order of the load − 2",
                                  row["observed_order_load"] - 2.0, spec["order_tolerance"]))
        found.append(checks.check(f"{label}: load error of the default grid {default} "
                                  "(relative)", row["default_grid_load_error"],
                                  spec["default_grid_load_tolerance"]))
    ax = plot_grid_convergence(table, title=spec["title"])
    models = {p["variant"]: [p["model"]] for p in points}
    return StudyResult(study, tables={"table.csv": table, "orders.csv": frame(orders)},
                       figures={"grid_convergence.png": ax.figure},
                       checks=[checks.all_converged(table), *found],
                       options=options_of(models, None, grids=sorted(set(table["grid"]))))


# ----------------------------------------------------------- concentric_impedance
def plan_concentric_impedance(study: Study) -> list:
    return [{"variant": f"case {k}", "model": build_model(
        {"foil": "rigid", **case}, study.where("cases", k))}
        for k, case in enumerate(study.spec["cases"])]


def run_concentric_impedance(study: Study, points: list, ctx: RunContext) -> StudyResult:
    from ..physics.closed_forms import concentric_impedance

    spec = study.spec
    rows = run_points(analyses.impedance_point,
                      [{"model": p["model"], "eccentricity": spec["eccentricity"],
                        "whirl_ratios": spec["whirl_ratios"], "grid": study.grid}
                       for p in points], progress=ctx.progress)
    for row in rows:
        if not row["success"]:
            continue
        z = analyses.impedance_matrix(row)
        za = concentric_impedance(row["bearing_number"], row["length_ratio"],
                                  row["whirl_ratio"])
        row["impedance_error"] = float(np.abs(z - za).max() / np.abs(za).max())
        for i, a in enumerate("xy"):
            for j, b in enumerate("xy"):
                row[f"z{a}{b}_ausman_re"] = float(za[i, j].real)
                row[f"z{a}{b}_ausman_im"] = float(za[i, j].imag)
    table = frame(rows, ("bearing_number", "length_ratio", "whirl_ratio", "impedance_error"))
    worst = float(table["impedance_error"].max()) if table["success"].all() else math.nan
    return StudyResult(
        study, tables={"table.csv": table}, checks=[checks.all_converged(table)],
        comparisons=[checks.comparison("impedance against Ausman's closed form: "
                                       "max|Z − Z_Ausman| / max|Z_Ausman| over all points",
                                       "ausman", worst, spec["impedance_tolerance"])],
        options=options_of({"rigid": [p["model"] for p in points]}, study.grid))

