"""Named, runnable studies: ``gfbopt run problems/NAME.toml``.

A study file gives its source (citation, table or figure), its inputs, the published values
where there are any, and a tolerance per compared column with its justification.  Running it
writes ``results/NAME/`` (CSV tables, ``summary.json`` with metadata and pass/fail, figures)
and refreshes ``results/index.md``.

Study kinds (``kind = ...`` in the file):

* ``static_table`` — rows of operating points × model variants, compared with published
  columns (thesis Tables 3.1 and 3.2);
* ``load_sweep`` — a dimensional bearing from a file, ε and attitude against load in newtons
  at several speeds and foil models (Ruscitto bearing, thesis Figs 3.2–3.5, 4.2–4.5);
* ``profile`` — pressure, foil deflection and film profiles at one point (Figs 3.6–3.8);
* ``grid_convergence`` — load and attitude on refined grids, observed order, error of the
  default grid.
"""
from __future__ import annotations

import datetime as _dt
import json
import math
import platform
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np
import pandas as pd

from .version import __version__
from .errors import ParameterError
from .inputs import DEFAULT_GRID, BearingModel, Grid, bearing_from_dict, load_bearing, read_toml
from .static import SolverCache, StaticSolver, solve_static, solver_for


@dataclass
class StudySummary:
    """What a study run produced: name, checks (each a dict with ``passed``), files."""

    name: str
    title: str
    checks: list = field(default_factory=list)
    files: list = field(default_factory=list)
    wall_time_s: float = 0.0
    notes: list = field(default_factory=list)

    @property
    def passed(self) -> bool:
        return all(c["passed"] for c in self.checks)

    def report(self) -> str:
        lines = [f"{self.name}: {self.title}",
                 f"  {len(self.checks)} checks, {sum(c['passed'] for c in self.checks)} passed; "
                 f"{self.wall_time_s:.1f} s; results in {Path(self.files[0]).parent if self.files else '-'}"]
        for c in self.checks:
            if not c["passed"]:
                lines.append(f"  FAILED: {c['what']}: {c['value']:.4g} vs limit {c['limit']:.4g}")
        for n in self.notes:
            lines.append(f"  note: {n}")
        return "\n".join(lines)


# ------------------------------------------------------------------------ helpers
def model_from_table(table: dict, **overrides) -> BearingModel:
    """A BearingModel from a study's table of options (names as in BearingModel)."""
    values = dict(table)
    values.update(overrides)
    if "seam_angle_deg" in values:
        angle = values.pop("seam_angle_deg")
        values["seam_angle"] = None if angle in (None, "max_film") else math.radians(angle)
    values.pop("grid", None)
    values.pop("label", None)
    try:
        return BearingModel(**values)
    except TypeError as exc:
        raise ParameterError("model", values, f"is not a valid model description ({exc})") from None


def _metadata(study: dict, grid: Grid) -> dict:
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, timeout=5, check=False).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        commit = ""
    import casadi

    return {"gfbopt_version": __version__, "git_commit": commit or "unknown",
            "date": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
            "grid": str(grid), "python": platform.python_version(),
            "casadi": casadi.__version__, "numpy": np.__version__,
            "source": study.get("source", ""), "title": study.get("title", "")}


def _check(what: str, value: float, limit: float) -> dict:
    return {"what": what, "value": float(value), "limit": float(limit),
            "passed": bool(np.isfinite(value) and abs(value) <= limit)}


def _grid_of(study: dict) -> Grid:
    return Grid.parse(study["grid"]) if "grid" in study else DEFAULT_GRID


# --------------------------------------------------------------------- study kinds
def static_table(study: dict, out: Path, summary: StudySummary) -> None:
    """Rows of (Λ, ε, S, L/D) × variants, beside the published columns."""
    grid = _grid_of(study)
    cache = SolverCache(grid)
    variants = study.get("variants", [{"label": "default"}])
    base = study.get("model", {})
    records = []
    for row in study["rows"]:
        for variant in variants:
            opts = dict(base)
            opts.update(variant)
            s = float(row.get("S", 0.0))
            if s == 0.0:
                opts["foil"] = "rigid"
            model = model_from_table(opts, bearing_number=row["Lambda"], compliance=s,
                                     length_ratio=row.get("L_over_D", 1.0))
            sol = solve_static(model, eccentricity=row["eps"], solver=cache(model))
            rec = {"variant": variant.get("label", "default"), **row,
                   "load": sol.load, "attitude_deg": math.degrees(sol.attitude_angle),
                   "min_film": sol.min_film, "success": sol.success, "status": sol.status,
                   "iterations": sol.iterations, "residual": sol.residual}
            for ref in study.get("references", []):
                if f"load_{ref}" in row:
                    rec[f"load_err_{ref}"] = sol.load / row[f"load_{ref}"] - 1.0
                    rec[f"attitude_err_{ref}"] = rec["attitude_deg"] - row[f"attitude_deg_{ref}"]
            records.append(rec)
    frame = pd.DataFrame.from_records(records)
    path = out / "table.csv"
    frame.to_csv(path, index=False, float_format="%.6g")
    summary.files.append(str(path))
    for c in study.get("checks", []):
        sub = frame[frame["variant"] == c["variant"]]
        ref = c["reference"]
        summary.checks.append(_check(f"{c['variant']} vs {ref}: max |load error| (relative)",
                                     sub[f"load_err_{ref}"].abs().max(), c["load_rel"]))
        summary.checks.append(_check(f"{c['variant']} vs {ref}: max |attitude error| (deg)",
                                     sub[f"attitude_err_{ref}"].abs().max(), c["attitude_deg"]))
    summary.checks.append(_check("all solves converged (count of failures)",
                                 float((~frame["success"]).sum()), 0))


def load_sweep(study: dict, out: Path, summary: StudySummary) -> None:
    """Minimum film [µm] and attitude angle [deg] against static load [N]."""
    from .plotting import plot_load_sweep

    grid = _grid_of(study)
    cache = SolverCache(grid)
    geometry = (bearing_from_dict(study["bearing"]) if isinstance(study.get("bearing"), dict)
                else load_bearing(Path(study["_dir"]) / study["bearing"]))
    loads = np.asarray(study["loads_newton"], dtype=float)
    records = []
    for variant in study["variants"]:
        for speed in study["speeds_rpm"]:
            opts = dict(study.get("model", {}))
            opts.update(variant)
            foil = opts.pop("foil")
            opts.pop("label", None)
            if "seam_angle_deg" in opts:
                a = opts.pop("seam_angle_deg")
                opts["seam_angle"] = None if a == "max_film" else math.radians(a)
            model = geometry.model(speed, foil=foil, **opts)
            previous = None
            for load_n in loads:
                sol = solve_static(model, load=geometry.nondimensional_load(load_n),
                                   solver=cache(model), initial=previous)
                if not sol.success:  # retry cold before giving up on the point
                    sol = solve_static(model, load=geometry.nondimensional_load(load_n),
                                       solver=cache(model))
                previous = sol if sol.success else previous
                records.append({
                    "variant": variant.get("label", foil), "foil": foil, "speed_rpm": speed,
                    "load_newton": load_n, "bearing_number": model.bearing_number,
                    "compliance": model.compliance,
                    "top_foil_coefficient": model.top_foil_coefficient,
                    "eccentricity": sol.eccentricity,
                    "attitude_deg": math.degrees(sol.attitude_angle),
                    "min_film_um": sol.min_film * geometry.radial_clearance * 1e6,
                    "success": sol.success, "status": sol.status,
                    "iterations": sol.iterations, "residual": sol.residual})
    frame = pd.DataFrame.from_records(records)
    path = out / "table.csv"
    frame.to_csv(path, index=False, float_format="%.6g")
    summary.files.append(str(path))
    summary.files += plot_load_sweep(frame, out, title=study.get("title", ""))
    summary.checks.append(_check("all solves converged (count of failures)",
                                 float((~frame["success"]).sum()), 0))
    for c in study.get("checks", []):  # monotone trends the physics requires
        for (variant, speed), sub in frame.groupby(["variant", "speed_rpm"]):
            sub = sub.sort_values("load_newton")
            if c == "min_film_decreases_with_load":
                worst = float(np.max(np.diff(sub["min_film_um"].to_numpy())))
                summary.checks.append(_check(f"{variant} {speed:.0f} rpm: max increase of "
                                             "h_min between load steps (µm)", max(worst, 0), 0))
            if c == "eccentricity_increases_with_load":
                worst = float(np.min(np.diff(sub["eccentricity"].to_numpy())))
                summary.checks.append(_check(f"{variant} {speed:.0f} rpm: max decrease of ε "
                                             "between load steps", max(-worst, 0), 0))


def profile(study: dict, out: Path, summary: StudySummary) -> None:
    """Profiles of P̄, W and H against the angle from the welded end, per variant."""
    from .plotting import plot_profiles

    grid = _grid_of(study)
    cache = SolverCache(grid)
    point = study["point"]
    published = study.get("published", {})
    records, solutions = [], {}
    for variant in study["variants"]:
        opts = dict(study.get("model", {}))
        opts.update(variant)
        model = model_from_table(opts, bearing_number=point["Lambda"], compliance=point["S"],
                                 length_ratio=point["L_over_D"])
        sol = solve_static(model, eccentricity=point["eps"], solver=cache(model))
        label = variant.get("label", "default")
        solutions[label] = sol
        pbar = sol.mean_pressure
        k = int(np.argmax(pbar))
        angles = np.degrees(sol.theta_from_seam)
        records.append({"variant": label, "max_mean_pressure": pbar[k],
                        "max_mean_pressure_at_deg": angles[k],
                        "max_deflection": float(sol.deflection[:, 0].max()),
                        "max_deflection_at_deg": angles[int(np.argmax(sol.deflection[:, 0]))],
                        "min_film": sol.min_film,
                        "min_film_at_deg": math.degrees(sol.min_film_angle_from_seam),
                        "load": sol.load, "attitude_deg": math.degrees(sol.attitude_angle),
                        "success": sol.success})
        prof = pd.DataFrame({"angle_from_welded_end_deg": angles,
                             "theta_from_load_deg": np.degrees(sol.theta) % 360,
                             "mean_pressure": pbar, "deflection": sol.deflection[:, 0],
                             "film": sol.film.min(axis=1),
                             "midplane_pressure": sol.pressure[:, sol.z.size // 2]})
        p = out / f"profile_{label}.csv"
        prof.sort_values("angle_from_welded_end_deg").to_csv(p, index=False, float_format="%.6g")
        summary.files.append(str(p))
    frame = pd.DataFrame.from_records(records)
    for key, value in published.items():
        frame[f"{key}_published"] = value
    path = out / "table.csv"
    frame.to_csv(path, index=False, float_format="%.6g")
    summary.files.insert(0, str(path))
    summary.files += plot_profiles(solutions, out, published)
    for c in study.get("checks", []):
        row = frame[frame["variant"] == c["variant"]].iloc[0]
        value = row[c["quantity"]] - published[c["quantity"]]
        if c.get("relative", False):
            value = value / published[c["quantity"]]
        summary.checks.append(_check(f"{c['variant']}: {c['quantity']} vs thesis", value,
                                     c["tolerance"]))
    summary.checks.append(_check("all solves converged (count of failures)",
                                 float((~frame["success"]).sum()), 0))


def grid_convergence(study: dict, out: Path, summary: StudySummary) -> None:
    """Refine the grid by factors of two; observed order and error of the default grid."""
    from .plotting import plot_grid_convergence

    base_grids = [Grid.parse(g) for g in study["grids"]]
    default = Grid.parse(study.get("default_grid", str(DEFAULT_GRID)))
    extra = [Grid.parse(g) for g in study.get("also_report", [])]
    records = []
    for case in study["cases"]:
        opts = dict(case)
        label = opts.pop("label")
        eps = opts.pop("eps")
        model = model_from_table(opts)
        for grid in sorted(set(base_grids + [default] + extra), key=lambda g: g.n_theta * g.n_z):
            sol = solve_static(model, eccentricity=eps, grid=grid)
            records.append({"case": label, "grid": str(grid), "n_theta": grid.n_theta,
                            "n_z": grid.n_z, "h": 1.0 / grid.n_theta, "load": sol.load,
                            "attitude_deg": math.degrees(sol.attitude_angle),
                            "success": sol.success, "solve_time_s": sol.solve_time_s})
    frame = pd.DataFrame.from_records(records)
    rows = []
    for label, sub in frame.groupby("case", sort=False):
        seq = sub[sub["grid"].isin([str(g) for g in base_grids])].sort_values("h", ascending=False)
        loads = seq["load"].to_numpy()
        att = seq["attitude_deg"].to_numpy()
        order_load = math.log2(abs(loads[-3] - loads[-2]) / abs(loads[-2] - loads[-1]))
        order_att = math.log2(abs(att[-3] - att[-2]) / abs(att[-2] - att[-1]))
        p = 2.0  # formal order of the scheme, for the Richardson extrapolation
        load_inf = loads[-1] + (loads[-1] - loads[-2]) / (2**p - 1)
        att_inf = att[-1] + (att[-1] - att[-2]) / (2**p - 1)
        d = sub[sub["grid"] == str(default)].iloc[0]
        rows.append({"case": label, "observed_order_load": order_load,
                     "observed_order_attitude": order_att, "load_extrapolated": load_inf,
                     "attitude_extrapolated_deg": att_inf, "default_grid": str(default),
                     "default_load_error_rel": d["load"] / load_inf - 1.0,
                     "default_attitude_error_deg": d["attitude_deg"] - att_inf,
                     **{f"load_error_rel_{g}": sub[sub["grid"] == str(g)].iloc[0]["load"]
                        / load_inf - 1.0 for g in extra}})
        tol = study["tolerance"]
        summary.checks.append(_check(f"{label}: observed order (load) − 2", order_load - 2.0,
                                     tol["order"]))
        summary.checks.append(_check(f"{label}: default-grid load error (relative)",
                                     d["load"] / load_inf - 1.0, tol["default_load_rel"]))
    conv = pd.DataFrame.from_records(rows)
    for name, fr in (("table.csv", frame), ("orders.csv", conv)):
        fr.to_csv(out / name, index=False, float_format="%.8g")
        summary.files.append(str(out / name))
    summary.files += plot_grid_convergence(frame, out)


def _threshold_row(model: BearingModel, eps: float, solver: StaticSolver) -> dict:
    """Static solve + linear threshold at one point, as a table row (failures recorded)."""
    from .linear import linear_threshold, linearise

    t0 = time.perf_counter()
    sol = solve_static(model, eccentricity=eps, solver=solver)
    row = {"load": sol.load, "attitude_deg": math.degrees(sol.attitude_angle),
           "static_success": sol.success, "critical_mass": math.nan, "whirl_ratio": math.nan,
           "stable_for_all_masses": False, "message": sol.message}
    if sol.success:
        thr = linear_threshold(linearise(sol, solver))
        row.update(critical_mass=thr.critical_mass, whirl_ratio=thr.whirl_ratio,
                   stable_for_all_masses=thr.stable_for_all_masses, message=thr.message)
    row["success"] = bool(sol.success and (math.isfinite(row["critical_mass"])
                                           or row["stable_for_all_masses"]))
    row["wall_time_s"] = time.perf_counter() - t0
    return row


def _crossing(x: np.ndarray, a: np.ndarray, b: np.ndarray) -> list:
    """x where curves a and b cross (linear interpolation of a − b)."""
    d = a - b
    out = []
    for k in range(len(x) - 1):
        if np.isfinite(d[k]) and np.isfinite(d[k + 1]) and d[k] * d[k + 1] < 0:
            out.append(float(x[k] - d[k] * (x[k + 1] - x[k]) / (d[k + 1] - d[k])))
    return out


def _crossover_table(frame: pd.DataFrame, study: dict, axis: str) -> pd.DataFrame:
    """Where each pair of curves (``crossover_pairs``) cross in M̄_crit, beside the thesis's
    published crossovers (``published_crossovers``); NaN where they do not cross."""
    cross = []
    for label, ref in study.get("crossover_pairs", []):
        base = frame[frame["variant"] == ref].sort_values(axis)
        sub = frame[frame["variant"] == label].sort_values(axis)
        found = _crossing(sub[axis].to_numpy(), sub["critical_mass"].to_numpy(),
                          base["critical_mass"].to_numpy())
        for xc in found or [math.nan]:
            cross.append({"variant": label, "against": ref, "variable": axis, "crossover": xc})
    table = pd.DataFrame.from_records(cross, columns=["variant", "against", "variable",
                                                      "crossover"])
    published = pd.DataFrame.from_records(study.get("published_crossovers", []))
    if len(published):
        table = table.merge(published, on=["variant", "against"], how="outer")
    return table


def _map_points(study: dict):
    """(label, model options, ε, Λ, L/D) for every variant × swept value of a map study."""
    axis = study["sweep"]["variable"]            # "eps" or "Lambda"
    fixed = study["fixed"]
    for variant in study["variants"]:
        opts = dict(study.get("model", {}))
        opts.update(variant)
        label = opts.pop("label")
        for v in study["sweep"]["values"]:
            yield (label, opts, float(v) if axis == "eps" else fixed["eps"],
                   float(v) if axis == "Lambda" else fixed["Lambda"],
                   fixed.get("L_over_D", 1.0))


def linear_map(study: dict, out: Path, summary: StudySummary) -> None:
    """Linear critical mass against ε or Λ per foil variant; crossovers with the rigid curve."""
    from .plotting import plot_stability_map

    grid = _grid_of(study)
    cache = SolverCache(grid)
    axis = study["sweep"]["variable"]
    records = []
    for label, opts, eps, lam, ld in _map_points(study):
        model = model_from_table(opts, bearing_number=lam, length_ratio=ld)
        row = _threshold_row(model, eps, cache(model))
        records.append({"variant": label, "eps": eps, "Lambda": lam,
                        "compliance": model.compliance,
                        "top_foil_coefficient": model.top_foil_coefficient, **row})
    frame = pd.DataFrame.from_records(records)
    frame.to_csv(out / "map.csv", index=False, float_format="%.6g")
    summary.files.append(str(out / "map.csv"))
    cross_frame = _crossover_table(frame, study, axis)
    cross_frame.to_csv(out / "crossovers.csv", index=False, float_format="%.6g")
    summary.files.append(str(out / "crossovers.csv"))
    points = []
    for p in study.get("thesis_points", []):          # the thesis's reported thresholds
        opts = dict(study.get("model", {}))
        opts.update(p["model"])
        model = model_from_table(opts, bearing_number=p["Lambda"],
                                 length_ratio=p.get("L_over_D", 1.0))
        row = _threshold_row(model, p["eps"], cache(model))
        points.append({"case": p["case"], "eps": p["eps"], "Lambda": p["Lambda"],
                       "thesis_Mbar": p["Mbar"], "linear_Mbar": row["critical_mass"],
                       "ratio_thesis_over_ours": p["Mbar"] / row["critical_mass"],
                       "whirl_ratio": row["whirl_ratio"], "where": p.get("where", "")})
    if points:
        pd.DataFrame.from_records(points).to_csv(out / "thesis_points.csv", index=False,
                                                 float_format="%.6g")
        summary.files.append(str(out / "thesis_points.csv"))
    summary.files += plot_stability_map(frame, axis, out, study.get("title", ""),
                                        cross_frame if len(cross_frame) else None)
    summary.checks.append(_check("all points converged (count of failures)",
                                 float((~frame["success"]).sum()), 0))
    for c in study.get("checks", []):
        if c["kind"] == "whirl_ratio_range":
            w = frame["whirl_ratio"]
            summary.checks.append(_check("whirl ratio at threshold within [0.3, 0.6]: worst "
                                         "distance outside", float(max(0.3 - w.min(),
                                                                       w.max() - 0.6, 0)), 0))
        if c["kind"] == "increases_with_eps":
            for label, sub in frame.groupby("variant", sort=False):
                d = np.diff(sub.sort_values("eps")["critical_mass"].to_numpy())
                summary.checks.append(_check(f"{label}: M̄c rises with ε (largest fall)",
                                             float(max(-d.min(), 0)), 0))


def linear_coefficients(study: dict, out: Path, summary: StudySummary) -> None:
    """Dimensional K [N/m] and C [N s/m] against excitation frequency for a bearing file."""
    from .linear import coefficients, dimensional_coefficients, linear_threshold, linearise
    from .plotting import plot_coefficients

    grid = _grid_of(study)
    cache = SolverCache(grid)
    geometry = load_bearing(Path(study["_dir"]) / study["bearing"])
    ratios = np.asarray(study["whirl_ratios"], dtype=float)
    tables = []
    for variant in study["variants"]:
        opts = dict(study.get("model", {}))
        opts.update(variant)
        label = opts.pop("label")
        foil = opts.pop("foil")
        if "seam_angle_deg" in opts:
            a = opts.pop("seam_angle_deg")
            opts["seam_angle"] = None if a == "max_film" else math.radians(a)
        for speed in study["speeds_rpm"]:
            model = geometry.model(speed, foil=foil, **opts)
            for load_n in study["loads_newton"]:
                sol = solve_static(model, load=geometry.nondimensional_load(load_n),
                                   solver=cache(model))
                if not sol.success:
                    summary.checks.append(_check(f"{label} {speed} rpm {load_n} N converged",
                                                 1.0, 0.0))
                    continue
                lin = linearise(sol, cache(model))
                thr = linear_threshold(lin)
                table = dimensional_coefficients(coefficients(lin, ratios), geometry, speed)
                table.insert(0, "load_newton", load_n)
                table.insert(0, "variant", label)
                table["eccentricity"] = sol.eccentricity
                table["attitude_deg"] = math.degrees(sol.attitude_angle)
                table["critical_mass"] = thr.critical_mass
                table["threshold_whirl_ratio"] = thr.whirl_ratio
                omega = speed * math.pi / 30
                table["critical_rotor_mass_kg"] = (thr.critical_mass * load_n
                                                   / (geometry.radial_clearance * omega**2))
                tables.append(table)
    frame = pd.concat(tables, ignore_index=True)
    frame.to_csv(out / "coefficients.csv", index=False, float_format="%.6g")
    summary.files.append(str(out / "coefficients.csv"))
    # a plain table per operating point in the layout rotordynamics codes read
    for (label, speed, load_n), sub in frame.groupby(["variant", "speed_rpm", "load_newton"]):
        name = f"rotordynamics_{label}_{int(speed)}rpm_{int(load_n)}N.csv"
        cols = ["frequency_hz"] + [c for c in sub.columns if c.endswith(("_N_per_m", "_Ns_per_m"))]
        sub[cols].to_csv(out / name, index=False, float_format="%.8g")
        summary.files.append(str(out / name))
    summary.files += plot_coefficients(frame, out, study.get("title", ""))
    summary.checks.append(_check("all static solves and thresholds converged (count of "
                                 "failures)", float((~np.isfinite(frame["critical_mass"])).sum()),
                                 0))


def concentric_impedance_study(study: dict, out: Path, summary: StudySummary) -> None:
    """The perturbation impedance at ε → 0 against Ausman's closed form."""
    from .linear import impedance, linearise
    from .physics.closed_forms import concentric_impedance

    grid = _grid_of(study)
    cache = SolverCache(grid)
    records = []
    for case in study["cases"]:
        model = BearingModel(bearing_number=case["Lambda"], foil="rigid",
                             length_ratio=case["L_over_D"])
        sol = solve_static(model, eccentricity=study["eps0"], solver=cache(model))
        lin = linearise(sol, cache(model))
        for gamma in study["whirl_ratios"]:
            z = impedance(lin, 1j * gamma)
            za = concentric_impedance(case["Lambda"], case["L_over_D"], gamma)
            rec = {"Lambda": case["Lambda"], "L_over_D": case["L_over_D"],
                   "whirl_ratio": gamma,
                   "error_rel": float(np.abs(z - za).max() / np.abs(za).max())}
            for i, a in enumerate("xy"):
                for j, b in enumerate("xy"):
                    rec[f"z{a}{b}_re"], rec[f"z{a}{b}_im"] = z[i, j].real, z[i, j].imag
                    rec[f"z{a}{b}_ausman_re"] = za[i, j].real
                    rec[f"z{a}{b}_ausman_im"] = za[i, j].imag
            records.append(rec)
    frame = pd.DataFrame.from_records(records)
    frame.to_csv(out / "table.csv", index=False, float_format="%.6g")
    summary.files.append(str(out / "table.csv"))
    summary.checks.append(_check("max |Z − Z_Ausman| / max|Z_Ausman| over all points",
                                 frame["error_rel"].max(), study["tolerance_rel"]))


def stability_point(model: dict, eps: float, grid: str, tolerance: float = 0.005,
                    revolutions: float = 5.0) -> dict:
    """One point of a transient stability map: static solve, linear threshold, and the
    nonlinear critical mass centred on it.  Plain arguments, so it runs in a worker process."""
    from .linear import linear_threshold, linearise
    from .transient import find_critical_mass, transient_model

    m = model_from_table(model)
    solver = solver_for(m, Grid.parse(grid))
    sol = solve_static(m, eccentricity=eps, solver=solver)
    row = {"load": sol.load, "attitude_deg": math.degrees(sol.attitude_angle),
           "static_success": sol.success}
    if not sol.success:
        return {**row, "success": False, "message": sol.message}
    lin = linear_threshold(linearise(sol, solver))
    result = find_critical_mass(transient_model(sol), tolerance=tolerance,
                                linear_estimate=lin.critical_mass, revolutions=revolutions)
    return {**row, "critical_mass": result.critical_mass, "whirl_ratio": result.whirl_ratio,
            "bracket_low": result.bracket[0], "bracket_high": result.bracket[1],
            "linear_critical_mass": lin.critical_mass, "linear_whirl_ratio": lin.whirl_ratio,
            "transients": result.transients, "rotor_revolutions": result.rotor_revolutions,
            "success": result.success, "message": result.message}


def transient_map(study: dict, out: Path, summary: StudySummary) -> None:
    """Nonlinear critical mass against ε or Λ per variant (thesis Figs 3.12, 3.13, 4.9,
    4.10), with the linear threshold beside it and the crossovers against the thesis's."""
    from .plotting import plot_stability_map
    from .sweep import run_points

    grid = str(_grid_of(study))
    axis = study["sweep"]["variable"]
    points, labels = [], []
    for label, opts, eps, lam, ld in _map_points(study):
        points.append({"model": {**opts, "bearing_number": lam, "length_ratio": ld},
                       "eps": eps, "grid": grid, "tolerance": study.get("tolerance", 0.005),
                       "revolutions": study.get("revolutions", 5.0)})
        labels.append((label, eps, lam))
    t0 = time.perf_counter()
    rows = run_points(stability_point, points, workers=study.get("workers", 2))
    elapsed = time.perf_counter() - t0
    frame = pd.DataFrame.from_records(
        [{"variant": lab, "eps": e, "Lambda": lam, **{k: v for k, v in r.items()
                                                     if k != "traceback"}}
         for (lab, e, lam), r in zip(labels, rows)])
    frame["nonlinear_over_linear"] = frame["critical_mass"] / frame["linear_critical_mass"]
    frame.to_csv(out / "map.csv", index=False, float_format="%.6g")
    summary.files.append(str(out / "map.csv"))
    cross_frame = _crossover_table(frame, study, axis)
    cross_frame.to_csv(out / "crossovers.csv", index=False, float_format="%.6g")
    summary.files.append(str(out / "crossovers.csv"))
    summary.files += plot_stability_map(frame, axis, out, study.get("title", ""),
                                        cross_frame if len(cross_frame) else None)
    summary.notes.append(f"{len(points)} points in {elapsed:.1f} s on "
                         f"{study.get('workers', 2)} worker processes")
    summary.checks.append(_check("all points converged (count of failures)",
                                 float((~frame["success"].astype(bool)).sum()), 0))
    summary.checks.append(_check("max |nonlinear/linear − 1| over the map",
                                 float((frame["nonlinear_over_linear"] - 1).abs().max()),
                                 study.get("nonlinear_linear_tolerance", 0.01)))


def transient_points(study: dict, out: Path, summary: StudySummary) -> None:
    """Nonlinear against linear critical mass at a list of operating points."""
    from .sweep import run_points

    grid = str(_grid_of(study))
    points = [{"model": {**study.get("model", {}), **p["model"], "bearing_number": p["Lambda"]},
               "eps": p["eps"], "grid": grid, "tolerance": study.get("tolerance", 0.005)}
              for p in study["points"]]
    rows = run_points(stability_point, points, workers=study.get("workers", 2))
    frame = pd.DataFrame.from_records(
        [{"label": p["label"], "eps": p["eps"], "Lambda": p["Lambda"],
          **{k: v for k, v in r.items() if k != "traceback"}}
         for p, r in zip(study["points"], rows)])
    frame["nonlinear_over_linear"] = frame["critical_mass"] / frame["linear_critical_mass"]
    frame.to_csv(out / "table.csv", index=False, float_format="%.7g")
    summary.files.append(str(out / "table.csv"))
    for _, r in frame.iterrows():
        summary.checks.append(_check(f"{r['label']}: |M̄c nonlinear / linear − 1|",
                                     abs(r["nonlinear_over_linear"] - 1),
                                     study["tolerance_nonlinear_linear"]))


def thesis_orbits(study: dict, out: Path, summary: StudySummary) -> None:
    """The thesis's example orbits at its masses and at masses rescaled by our threshold."""
    from .linear import linear_threshold, linearise
    from .plotting import plot_orbits, save_figure
    from .transient import integrate_orbits, transient_model

    grid = _grid_of(study)
    cache = SolverCache(grid)
    records = []
    for case in study["cases"]:
        opts = dict(study.get("model", {}))
        opts.update(case["model"])
        model = model_from_table(opts, bearing_number=case["Lambda"])
        sol = solve_static(model, eccentricity=case["eps"], solver=cache(model))
        ours = linear_threshold(linearise(sol, cache(model))).critical_mass
        scale = ours / case["thesis_critical_mass"]
        masses = [(f"thesis {m:g}", m, "thesis") for m in case["masses"]]
        masses += [(f"scaled {m * scale:.3g}", m * scale, "scaled") for m in case["masses"]]
        tm = transient_model(sol)
        orbit = integrate_orbits(tm, [m for _, m, _ in masses], study.get("revolutions", 30),
                                 kick=study.get("kick", 0.02))
        tables = {}
        for k, (label, mass, kind) in enumerate(masses):
            table = orbit.to_frame(k)
            tables[f"{label}: {orbit.verdict[k]}"] = table
            name = f"orbit_{case['label']}_{kind}_{k % len(case['masses'])}.csv"
            table.to_csv(out / name, index=False, float_format="%.6g")
            summary.files.append(str(out / name))
            thesis_verdict = case["verdicts"][k % len(case["masses"])]
            records.append({"case": case["label"], "which": kind, "mass": mass,
                            "thesis_mass": case["masses"][k % len(case["masses"])],
                            "thesis_verdict": thesis_verdict, "verdict": orbit.verdict[k],
                            "growth_rate": orbit.growth_rate[k],
                            "whirl_ratio": orbit.whirl_ratio[k],
                            "final_amplitude": orbit.amplitude[k],
                            "min_film": float(np.nanmin(orbit.min_film[k])),
                            "contact_tau": orbit.contact_tau[k],
                            "our_linear_critical_mass": ours,
                            "thesis_critical_mass": case["thesis_critical_mass"]})
        for kind in ("thesis", "scaled"):
            ax = plot_orbits({k: v for k, v in tables.items() if k.startswith(kind)},
                             title=f"{case['label']}: {kind} masses (ε0 = {case['eps']}, "
                             f"Λ = {case['Lambda']})")
            summary.files.append(save_figure(ax.figure, out / f"orbits_{case['label']}_{kind}.png"))
    frame = pd.DataFrame.from_records(records)
    frame.to_csv(out / "verdicts.csv", index=False, float_format="%.6g")
    summary.files.insert(0, str(out / "verdicts.csv"))
    scaled = frame[frame["which"] == "scaled"]
    expected = scaled["thesis_verdict"].map({"stable": "stable", "critical": "critical",
                                             "unstable": "unstable"})
    mismatch = sum(1 for v, e in zip(scaled["verdict"], expected)
                   if e != "critical" and not (e == v or (e == "unstable" and v in
                                                          ("contact", "limit cycle"))))
    summary.checks.append(_check("scaled masses: verdicts that contradict the thesis's "
                                 "(stable/unstable; 'critical' not checked)", mismatch, 0))


def bifurcation(study: dict, out: Path, summary: StudySummary) -> None:
    """Limit-cycle amplitude against M̄/M̄_crit (supercritical Hopf: amplitude ∝ √(M̄ − M̄c))."""
    from .linear import linear_threshold, linearise
    from .plotting import plot_bifurcation
    from .transient import limit_cycle_amplitudes, transient_model

    grid = _grid_of(study)
    model = model_from_table(study["model"])
    solver = solver_for(model, grid)
    sol = solve_static(model, eccentricity=study["eps"], solver=solver)
    mc = linear_threshold(linearise(sol, solver)).critical_mass
    ratios = np.asarray(study["mass_ratios"], dtype=float)
    frame = limit_cycle_amplitudes(transient_model(sol), ratios * mc,
                                   study.get("revolutions", 60.0),
                                   tuple(study.get("kicks", (0.05, 0.6))))
    frame.insert(0, "mass_ratio", ratios)
    frame["linear_critical_mass"] = mc
    frame.to_csv(out / "bifurcation.csv", index=False, float_format="%.6g")
    summary.files.append(str(out / "bifurcation.csv"))
    summary.files += plot_bifurcation(frame, out, study.get("title", ""))
    both = frame[(frame["verdict_from_inside"] == "limit cycle")
                 & (frame["verdict_from_outside"] == "limit cycle")]
    if len(both):
        gap = float(((both["amplitude_from_inside"] - both["amplitude_from_outside"]).abs()
                     / both["amplitude_from_outside"]).max())
        summary.checks.append(_check("limit cycles reached from inside and outside agree "
                                     "(max relative difference)", gap,
                                     study.get("cycle_tolerance", 0.05)))
    touched = (frame["verdict_from_inside"] == "contact") & (frame["verdict_from_outside"]
                                                             == "contact")
    summary.checks.append(_check("masses with neither an established cycle nor contact from "
                                 "both sides (count)", float(len(frame) - len(both)
                                                             - touched.sum()),
                                 float(study.get("allowed_without_cycle", 0))))


KINDS: dict[str, Callable] = {"static_table": static_table, "load_sweep": load_sweep,
                              "profile": profile, "grid_convergence": grid_convergence,
                              "linear_map": linear_map,
                              "linear_coefficients": linear_coefficients,
                              "concentric_impedance": concentric_impedance_study,
                              "transient_map": transient_map,
                              "thesis_orbits": thesis_orbits,
                              "transient_points": transient_points,
                              "bifurcation": bifurcation}


def run_study(path: str | Path, results_root: str | Path = "results") -> StudySummary:
    """Run the study in ``path`` and write ``results_root/NAME/``; returns its summary."""
    path = Path(path)
    study = read_toml(path)
    study["_dir"] = str(path.parent)
    kind = study.get("kind")
    if kind not in KINDS:
        raise ParameterError(f"{path.name}: kind", kind, f"must be one of {', '.join(KINDS)}")
    name = study.get("name", path.stem)
    out = Path(results_root) / name
    out.mkdir(parents=True, exist_ok=True)
    summary = StudySummary(name=name, title=study.get("title", ""))
    t0 = time.perf_counter()
    KINDS[kind](study, out, summary)
    summary.wall_time_s = time.perf_counter() - t0
    summary.notes += study.get("notes", [])
    meta = _metadata(study, _grid_of(study))
    meta.update({"name": name, "kind": kind, "passed": summary.passed,
                 "checks": summary.checks, "files": [Path(f).name for f in summary.files],
                 "wall_time_s": summary.wall_time_s, "problem_file": str(path)})
    (out / "summary.json").write_text(json.dumps(meta, indent=2))
    (out / "README.md").write_text(_study_readme(meta, study, summary))
    write_index(Path(results_root))
    return summary


def _study_readme(meta: dict, study: dict, summary: StudySummary) -> str:
    """A generated page per study: what, source, conventions, checks and files."""
    lines = [f"# {meta['name']} (generated by `gfbopt run {meta['problem_file']}`; do not edit)",
             "", f"**{meta['title']}**", "", f"Source: {meta['source']}", "",
             f"gfbopt {meta['gfbopt_version']}, commit {meta['git_commit']}, {meta['date']}, "
             f"grid {meta['grid']}, {summary.wall_time_s:.1f} s.", "", "## Notes", ""]
    lines += [f"- {n}" for n in study.get("notes", [])] or ["- none"]
    lines += ["", "## Checks", "", "| check | value | limit | passed |", "|---|---|---|---|"]
    lines += [f"| {c['what']} | {c['value']:.4g} | {c['limit']:.4g} | "
              f"{'yes' if c['passed'] else '**NO**'} |" for c in summary.checks]
    lines += ["", "## Files", ""] + [f"- [{Path(f).name}]({Path(f).name})" for f in summary.files]
    return "\n".join(lines) + "\n"


def write_index(results_root: Path) -> None:
    """Regenerate ``results/index.md`` from the studies' summary files (bookkeeping only)."""
    lines = ["# Results index (generated by `gfbopt run`; do not edit)", "",
             "| study | title | checks | passed | date | commit |", "|---|---|---|---|---|---|"]
    for f in sorted(results_root.glob("*/summary.json")):
        s = json.loads(f.read_text())
        n = len(s.get("checks", []))
        ok = sum(c["passed"] for c in s.get("checks", []))
        lines.append(f"| [{s['name']}]({f.parent.name}/) | {s.get('title', '')} | {n} | "
                     f"{ok}/{n} | {s.get('date', '')[:10]} | {s.get('git_commit', '')} |")
    (results_root / "index.md").write_text("\n".join(lines) + "\n")
