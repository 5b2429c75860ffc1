"""The numbers the README and the docs quote from shipped results are those results.

A sentence that quotes a shipped result ends with a marker naming what it quotes::

    ... the best first onset is 17,027 rpm ...<!-- checked: design_first_onset_rpm -->

Each name is an entry of :data:`QUOTED` below: the shipped file it is read from (a
``summary.json``, a ``*.csv`` of ``results/``, a benchmark JSON, or the problem file for the
inputs a sentence restates) and how the text formats it.  The tests read every value from its
file, format it, and require it in the text between the marker and the previous marker (or the
start of the paragraph).  So a regenerated result that moves a number fails here until the text
is rewritten from it, and a stale number cannot hide behind a marker.

A number with a unit (rpm, Hz, %, µm, °, s, ms, W) in a paragraph that cites ``results/`` must
be one that the paragraph's markers check: a new or stale figure next to a result (the README's
old "best first onset 25,131 rpm at 36 × 10") fails until it is marked and matches.
"""
from __future__ import annotations

import csv
import json
import re
import statistics
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Callable

import pytest

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[2]
PAGES = ["README.md", *sorted(p.relative_to(ROOT).as_posix()
                              for p in (ROOT / "docs").glob("*.md"))]
MARKER = re.compile(r"<!--\s*checked:\s*(.*?)\s*-->", re.S)
NUMBER = r"[+−-]?\d[\d,]*(?:\.\d+)?"
WITH_UNIT = re.compile(rf"(?<![\w.,×/^]){NUMBER}(?:\s?[–-]\s?{NUMBER})?\s?(?:rpm|Hz|%|µm|°|ms\b|W\b|s\b)")


# ---------------------------------------------------------------- reading shipped files

@lru_cache(maxsize=None)
def _rows(path: str) -> tuple[dict, ...]:
    with open(ROOT / path, newline="", encoding="utf-8") as fh:
        return tuple(csv.DictReader(fh))


@lru_cache(maxsize=None)
def _json(path: str):
    return json.loads((ROOT / path).read_text(encoding="utf-8"))


@lru_cache(maxsize=None)
def _toml(path: str):
    return tomllib.loads((ROOT / path).read_text(encoding="utf-8"))


def rows(path: str, **where) -> list[dict]:
    return [r for r in _rows(path) if all(r[k] == str(v) for k, v in where.items())]


def cell(path: str, column: str, **where) -> float | str:
    """The one row of ``path`` matching ``where``: its ``column`` (a float when it is one)."""
    found = rows(path, **where)
    assert len(found) == 1, f"{path}: {len(found)} rows match {where}, expected one"
    value = found[0][column]
    try:
        return float(value)
    except ValueError:
        return value


def floats(path: str, column: str, keep: Callable[[dict], bool] = lambda r: True) -> list[float]:
    return [float(r[column]) for r in _rows(path) if r[column] != "" and keep(r)]


def key(path: str, dotted: str):
    """``a.b.0.c`` in a JSON (or TOML) file."""
    value = _toml(path) if path.endswith(".toml") else _json(path)
    for part in dotted.split("."):
        value = value[int(part)] if isinstance(value, list) else value[part]
    return value


def pct(new: float, reference: float) -> float:
    return 100.0 * (new / reference - 1.0)


# ---------------------------------------------------------------- what the text quotes

#: the rotor transient with bump friction (results/rotor_friction_transient)
RFT = "results/rotor_friction_transient/cases.csv"
RFT_ROW = {"case": "blower_friction", "grid": "72x20", "speed_rpm": 13500}


@dataclass(frozen=True)
class Quoted:
    source: str                      # the shipped file the value is read from
    read: Callable[[], float | str]
    fmt: str = "{:,.0f}"

    def text(self) -> str:
        value = self.read()
        return value if isinstance(value, str) else self.fmt.format(value)


DESIGN = "results/rotor_bearing_design"
DESIGN_TOML = "problems/rotor_bearing_design.toml"
BLOWER = "results/rotor_blower"
ROSS = "results/rotor_ross_comparison.json"
RUN_UP = "results/rotor_run_up"
CONVENTIONS = "results/ruscitto_conventions/onset.csv"
PRELOAD = "results/ruscitto_preload/onset.csv"
LOSS = "results/loss_factor/onset.csv"
BENCH = "results/benchmarks"


def _design_variable(name: str, bound: str) -> Quoted:
    return Quoted(DESIGN_TOML, lambda: next(v[bound] for v in key(DESIGN_TOML, "variables")
                                            if v["name"] == name))


def _chosen(column: str, fmt: str = "{:,.0f}") -> Quoted:
    return Quoted(f"{DESIGN}/chosen.csv", lambda: cell(f"{DESIGN}/chosen.csv", column), fmt)


def _lever(lever: str, column: str, fmt: str = "{:,.0f}") -> Quoted:
    path = f"{DESIGN}/what_it_would_take.csv"
    return Quoted(path, lambda: cell(path, column, lever=lever), fmt)


def _chosen_point() -> str:
    return rows(f"{DESIGN}/chosen.csv")[0]["point"]


def _default_grid(column: str, fmt: str = "{:,.0f}") -> Quoted:
    path = f"{DESIGN}/default_grid_check.csv"
    return Quoted(path, lambda: cell(path, column, point=_chosen_point()), fmt)


def _first_mode() -> dict:
    onsets = [r for r in _rows(f"{BLOWER}/modes.csv") if r["onset_speed_rpm"]]
    return min(onsets, key=lambda r: float(r["onset_speed_rpm"]))


def _gyroscopic_gain() -> float:
    first = _first_mode()
    without = cell(f"{BLOWER}/modes_without_gyroscopics.csv", "onset_speed_rpm",
                   label=first["label"])
    return pct(float(first["onset_speed_rpm"]), without)


def _convention(name: str) -> Quoted:
    return Quoted(CONVENTIONS, lambda: cell(CONVENTIONS, "onset_speed_rpm", convention=name))


def _fixed_seams() -> list[dict]:
    return [r for r in _rows(CONVENTIONS) if r["film"] == "seam" and r["seam_angle_deg"] != "max_film"]


def _loaded_arc_onsets() -> list[float]:
    """Onsets with the welded end in the loaded arc: 0°–90° from the load line."""
    return [float(r["onset_speed_rpm"]) for r in _fixed_seams()
            if float(r["seam_angle_deg"]) <= 90.0 and r["onset_speed_rpm"]]


def _unstable_angles() -> list[float]:
    return [float(r["seam_angle_deg"]) for r in _fixed_seams()
            if r["onset_status"] == "unstable at every mass"]


def _fixed_seam_onsets() -> list[float]:
    return [float(r["onset_speed_rpm"]) for r in _fixed_seams() if r["onset_speed_rpm"]]


def _loss_gain(law: str) -> float:
    etas = floats(LOSS, "loss_factor", lambda r: r["deflection_law"] == law)
    at = lambda eta: cell(LOSS, "onset_speed_rpm", deflection_law=law, compliance=1,  # noqa: E731
                          loss_factor=_same(LOSS, "loss_factor", eta))
    return pct(at(max(etas)), at(0.0))


def _same(path: str, column: str, value: float) -> str:
    """The spelling of ``value`` in ``column`` of ``path`` (e.g. 0.5 as it is written)."""
    return next(r[column] for r in _rows(path) if r[column] and float(r[column]) == value)


def _preload(column: str, pick: Callable[[list[float]], float], fmt: str = "{:,.0f}") -> Quoted:
    nonzero = lambda r: r["variant"] == "preload" and float(r["preload_depth_um"]) > 0  # noqa: E731
    return Quoted(PRELOAD, lambda: pick(floats(PRELOAD, column, nonzero)), fmt)


def _pads(n: int) -> Quoted:
    return Quoted(PRELOAD, lambda: cell(PRELOAD, "onset_speed_rpm", variant="pads", n_pads=n))


def _comparison(study: str, what: str, scale: float, fmt: str) -> Quoted:
    path = f"results/{study}/summary.json"
    return Quoted(path, lambda: scale * next(c["value"] for c in key(path, "comparisons")
                                             if c["what"].startswith(what)), fmt)


def _critical_mass(method: str) -> dict:
    return next(r for r in key(f"{BENCH}/critical_mass.json", "critical_mass")
                if r["method"] == method and r["start"] == "linear mode")


def _static_build(grid: str, which: str) -> Quoted:
    path = f"{BENCH}/static_speed.json"
    return Quoted(path, lambda: next(f[which]["median_s"] for f in key(path, "formulations")
                                     if f["grid"] == grid), "{:.1f}")


def _rt(dotted: str, fmt: str, loaded: bool = False) -> Quoted:
    """A rotor-transient benchmark figure: the latest run, or the one under load."""
    path = f"{BENCH}/rotor_transient{'_preloaded' if loaded else ''}.json"
    return Quoted(path, lambda: key(path, dotted), fmt)


def _run_up(quantity: str) -> float:
    return cell(f"{RUN_UP}/summary.csv", "value", quantity=quantity)


def _limit_cycle(bearing: str, column: str) -> float:
    first = min(floats(f"{RUN_UP}/limit_cycles_past_onset.csv", "speed_over_linear_onset"))
    return cell(f"{RUN_UP}/limit_cycles_past_onset.csv", column, bearing=bearing,
                speed_over_linear_onset=_same(f"{RUN_UP}/limit_cycles_past_onset.csv",
                                              "speed_over_linear_onset", first))


def _dask(dotted: str, fmt: str, scale: float = 1.0) -> Quoted:
    """A figure of the Dask benchmark (results/benchmarks/dask.json)."""
    path = f"{BENCH}/dask.json"
    return Quoted(path, lambda: scale * key(path, dotted), fmt)


def _dask_ratio(over: str) -> Quoted:
    path = f"{BENCH}/dask.json"
    return Quoted(path, lambda: key(path, "summary.dask_points_per_s")
                  / key(path, f"summary.{over}_points_per_s"), "{:.2f}")


QUOTED: dict[str, Quoted] = {
    # the Dask route at 10^5 points (docs/doe.md)
    "dask_point_cpu_ms": _dask("summary.analysis_cpu_s_per_point", "{:.2f}", 1e3),
    "dask_old_tasks": _dask("medians.dask-old.dask_tasks", "{:,.0f}"),
    "dask_old_driver_share": _dask("summary.old_dask_driver_cpu_share", "{:.1f}", 100.0),
    "dask_tasks": _dask("medians.dask.dask_tasks", "{:,.0f}"),
    "dask_driver_share": _dask("summary.dask_driver_cpu_share", "{:.1f}", 100.0),
    "dask_over_old": _dask_ratio("old_dask"),
    "dask_over_pool": _dask_ratio("pool"),
    # the main job: inputs restated from its problem file, then its answer
    "design_top_speed_rpm": Quoted(DESIGN_TOML, lambda: key(DESIGN_TOML, "speed_range_rpm.1")),
    "design_lowest_speed_rpm": Quoted(DESIGN_TOML, lambda: key(DESIGN_TOML, "speed_range_rpm.0")),
    "design_clearance_low_um": _design_variable("A:radial_clearance_um", "low"),
    "design_clearance_high_um": _design_variable("A:radial_clearance_um", "high"),
    "design_preload_low_um": _design_variable("A:preload_depth_um", "low"),
    "design_preload_high_um": _design_variable("A:preload_depth_um", "high"),
    "design_clearance_b_low_um": _design_variable("B:radial_clearance_um", "low"),
    "design_clearance_b_high_um": _design_variable("B:radial_clearance_um", "high"),
    "design_preload_b_low_um": _design_variable("B:preload_depth_um", "low"),
    "design_preload_b_high_um": _design_variable("B:preload_depth_um", "high"),
    "design_min_film_limit_um": Quoted(DESIGN_TOML, lambda: key(DESIGN_TOML, "min_film_um"), "{:g}"),
    "design_first_onset_rpm": _chosen("first_onset_speed_rpm"),
    "design_first_mode": _chosen("first_mode"),
    "design_clearance_a_um": _chosen("A:radial_clearance_um", "{:.1f}"),
    "design_clearance_b_um": _chosen("B:radial_clearance_um", "{:.1f}"),
    "design_preload_a_um": _chosen("A:preload_depth_um", "{:.2f}"),
    "design_preload_b_um": _chosen("B:preload_depth_um", "{:.2f}"),
    "design_min_film_default_grid_um": _default_grid("min_film_lowest_speed_um_default_grid",
                                                     "{:.2f}"),
    "design_evaluations": Quoted(f"{DESIGN}/evaluations.csv", lambda: len(
        _rows(f"{DESIGN}/evaluations.csv")), "{:,.0f}"),
    "design_wiwt_loss_factor_rpm": _lever("loss_factor", "at_bound_onset_speed_rpm"),
    "design_wiwt_loss_factor_bound": _lever("loss_factor", "lever_high", "{:g}"),
    "design_wiwt_side_load_rpm": _lever("side_load_n", "at_bound_onset_speed_rpm"),
    "design_wiwt_side_load_n": _lever("side_load_n", "lever_high", "{:g}"),
    "design_wiwt_preload_a_rpm": _lever("A:preload_depth_um", "at_bound_onset_speed_rpm"),
    "design_wiwt_preload_a_um": _lever("A:preload_depth_um", "at_bound_value", "{:.1f}"),
    "design_min_film_um": _chosen("min_film_lowest_speed_um", "{:.2f}"),
    "design_first_onset_default_grid_rpm": _default_grid("first_onset_speed_rpm_default_grid"),
    "design_power_loss_default_grid_w": _default_grid("total_power_loss_w_default_grid"),
    "main_job_wall_fast_s": Quoted(f"{BENCH}/main_job.json", lambda: min(
        r["wall_s"] for r in key(f"{BENCH}/main_job.json", "runs"))),
    "main_job_wall_slow_s": Quoted(f"{BENCH}/main_job.json", lambda: max(
        r["wall_s"] for r in key(f"{BENCH}/main_job.json", "runs"))),
    "main_job_load_low": Quoted(f"{BENCH}/main_job.json", lambda: min(
        r["load_before"][0] for r in key(f"{BENCH}/main_job.json", "runs")), "{:.1f}"),
    "main_job_load_high": Quoted(f"{BENCH}/main_job.json", lambda: max(
        r["load_before"][0] for r in key(f"{BENCH}/main_job.json", "runs")), "{:.1f}"),
    "main_job_wiwt_share_pct": Quoted(f"{BENCH}/main_job.json", lambda: 100 * max(
        r["stage_shares_of_wall"]["what it would take"]
        for r in key(f"{BENCH}/main_job.json", "runs"))),
    "all_studies_minutes": Quoted("results/*/summary.json", lambda: sum(
        json.loads(f.read_text(encoding="utf-8")).get("wall_time_s") or 0.0
        for f in (ROOT / "results").glob("*/summary.json")) / 60.0, "{:.0f}"),
    # the blower rotor on two bearings, ROSS beside it, its run-up
    "blower_first_mode": Quoted(f"{BLOWER}/modes.csv", lambda: _first_mode()["label"]),
    "blower_first_onset_rpm": Quoted(f"{BLOWER}/modes.csv",
                                     lambda: float(_first_mode()["onset_speed_rpm"])),
    "blower_first_whirl_hz": Quoted(f"{BLOWER}/modes.csv",
                                    lambda: float(_first_mode()["whirl_frequency_hz"])),
    "blower_gyroscopic_gain_pct": Quoted(f"{BLOWER}/modes_without_gyroscopics.csv",
                                         _gyroscopic_gain, "{:.1f}"),
    "blower_onset_without_gyroscopics_rpm": Quoted(
        f"{BLOWER}/modes_without_gyroscopics.csv",
        lambda: cell(f"{BLOWER}/modes_without_gyroscopics.csv", "onset_speed_rpm",
                     label=_first_mode()["label"])),
    "half_mass_error_pct": Quoted(f"{BLOWER}/half_mass.csv", lambda: pct(
        min(floats(f"{BLOWER}/half_mass.csv", "onset_speed_rpm")),
        float(_first_mode()["onset_speed_rpm"])), "{:.1f}"),
    "ross_onset_rpm": Quoted(ROSS, lambda: key(ROSS, "ross_rigid.onset_speed_rpm")),
    "ross_difference_pct": Quoted(ROSS, lambda: abs(pct(key(ROSS, "ross_rigid.onset_speed_rpm"),
                                                        key(ROSS, "gfbopt.onset_speed_rpm"))),
                                  "{:.2f}"),
    "blower_veering_whirl_hz": Quoted(ROSS, lambda: key(ROSS, "gfbopt.onset_whirl_frequency_hz"),
                                      "{:.0f}"),
    "run_up_top_speed_rpm": Quoted("problems/rotor_run_up.toml", lambda: key(
        "problems/rotor_run_up.toml", "end_rpm")),
    "run_up_subsync_rpm": Quoted(f"{RUN_UP}/summary.csv", lambda: _run_up("subsync_appearance_rpm")),
    "run_up_contact_rpm": Quoted(f"{RUN_UP}/summary.csv", lambda: _run_up("run_up_contact_speed_rpm")),
    "run_up_past_onset_pct": Quoted(f"{RUN_UP}/limit_cycles_past_onset.csv", lambda: 100 * (
        min(floats(f"{RUN_UP}/limit_cycles_past_onset.csv", "speed_over_linear_onset")) - 1),
        "{:.0f}"),
    "run_up_limit_cycle_b_um": Quoted(f"{RUN_UP}/limit_cycles_past_onset.csv",
                                      lambda: _limit_cycle("B", "limit_cycle_amplitude_um"), "{:.1f}"),
    # one bearing: film conventions, damping, preload and pads
    "conventions_periodic_rpm": _convention("periodic"),
    "conventions_max_film_rpm": _convention("max_film"),
    "conventions_seam_180_rpm": _convention("seam_180"),
    "conventions_best_angle_deg": Quoted(CONVENTIONS, lambda: float(max(
        (r for r in _fixed_seams() if r["onset_speed_rpm"]),
        key=lambda r: float(r["onset_speed_rpm"]))["seam_angle_deg"])),
    "conventions_angle_count": Quoted(CONVENTIONS, lambda: float(len(_fixed_seams()))),
    "conventions_loaded_arc_low_rpm": Quoted(CONVENTIONS, lambda: min(_loaded_arc_onsets())),
    "conventions_loaded_arc_high_rpm": Quoted(CONVENTIONS, lambda: max(_loaded_arc_onsets())),
    "conventions_unstable_low_deg": Quoted(CONVENTIONS, lambda: min(_unstable_angles())),
    "conventions_unstable_high_deg": Quoted(CONVENTIONS, lambda: max(_unstable_angles())),
    "conventions_range_factor": Quoted(CONVENTIONS, lambda: max(_fixed_seam_onsets())
                                       / min(_fixed_seam_onsets()), "{:.2f}"),
    "loss_factor_eta_max": Quoted(LOSS, lambda: max(floats(LOSS, "loss_factor")), "{:g}"),
    "loss_factor_mean_s1_gain_pct": Quoted(LOSS, lambda: _loss_gain("mean"), "{:.1f}"),
    "loss_factor_local_s1_gain_pct": Quoted(LOSS, lambda: _loss_gain("local"), "{:.1f}"),
    "preload_shim_width_deg": Quoted("results/ruscitto_preload/summary.json", lambda: key(
        "results/ruscitto_preload/summary.json", "provenance.options.shim_width_deg")),
    "preload_low_um": _preload("preload_depth_um", min, "{:g}"),
    "preload_high_um": _preload("preload_depth_um", max, "{:g}"),
    "preload_none_rpm": Quoted(PRELOAD, lambda: cell(PRELOAD, "onset_speed_rpm",
                                                     variant="preload", preload_depth_um=0)),
    "preload_low_rpm": _preload("onset_speed_rpm", min),
    "preload_high_rpm": _preload("onset_speed_rpm", max),
    "pads_2_rpm": _pads(2),
    "pads_3_rpm": _pads(3),
    # published tables and closed forms
    "table_3_1_load_pct": _comparison("thesis_table_3_1", "default: load vs yang", 100, "{:.1f}"),
    "table_3_1_angle_deg": _comparison("thesis_table_3_1", "default: attitude_angle_deg vs yang",
                                       1, "{:.2f}"),
    "table_3_2_thesis_load_pct": _comparison("thesis_table_3_2", "gumbel_mean_co: load", 100,
                                             "{:.1f}"),
    "table_3_2_thesis_angle_deg": _comparison("thesis_table_3_2",
                                              "gumbel_mean_co: attitude_angle_deg", 1, "{:.1f}"),
    "table_3_2_peng_load_pct": _comparison("thesis_table_3_2", "gumbel_local_co: load", 100,
                                           "{:.1f}"),
    "table_3_2_peng_angle_deg": _comparison("thesis_table_3_2",
                                            "gumbel_local_co: attitude_angle_deg", 1, "{:.1f}"),
    "profile_pressure_pct": _comparison("thesis_profile", "thesis_seam: max_mean_pressure", 100,
                                        "{:.0f}"),
    "profile_min_film_pct": _comparison("thesis_profile", "thesis_seam: min_film", 100, "{:.1f}"),
    "nonlinear_vs_linear_pct": Quoted("results/nonlinear_vs_linear/summary.json", lambda: 100 * max(
        c["value"] for c in key("results/nonlinear_vs_linear/summary.json", "checks")), "{:.3f}"),
    "ausman_pct": _comparison("ausman_concentric_impedance", "impedance against Ausman", 100,
                              "{:.2f}"),
    # the clearance at speed (docs/thermal.md)
    "thermal_onset_heat_cpu_s": Quoted(f"{BENCH}/thermal.json", lambda: statistics.median(
        key(f"{BENCH}/thermal.json", "onset.heat_cpu_s")), "{:.2f}"),
    "thermal_onset_isothermal_cpu_s": Quoted(f"{BENCH}/thermal.json", lambda: statistics.median(
        key(f"{BENCH}/thermal.json", "onset.isothermal_cpu_s")), "{:.2f}"),
    "rotor_friction_speed_rpm": Quoted(RFT, lambda: cell(RFT, "speed_rpm", **RFT_ROW, bearing="A")),
    "rotor_friction_a_um": Quoted(RFT, lambda: cell(RFT, "amplitude_um", **RFT_ROW, bearing="A"),
                                  "{:.2f}"),
    "rotor_friction_b_um": Quoted(RFT, lambda: cell(RFT, "amplitude_um", **RFT_ROW, bearing="B"),
                                  "{:.1f}"),
    "thermal_onset_ratio": Quoted(f"{BENCH}/thermal.json", lambda: key(
        f"{BENCH}/thermal.json", "onset.onset_ratio"), "{:.2f}"),
    "thermal_heat_onset_rpm": Quoted(f"{BENCH}/thermal.json", lambda: key(
        f"{BENCH}/thermal.json", "onset.heat_onset_rpm"), "{:,.1f}"),
    "thermal_isothermal_onset_rpm": Quoted(f"{BENCH}/thermal.json", lambda: key(
        f"{BENCH}/thermal.json", "onset.isothermal_onset_rpm"), "{:,.1f}"),
    "thermal_frozen_onset_rpm": Quoted(f"{BENCH}/thermal.json", lambda: key(
        f"{BENCH}/thermal.json", "onset.heat_frozen_onset_rpm"), "{:,.1f}"),
    "thermal_frozen_at_rpm": Quoted(f"{BENCH}/thermal.json", lambda: key(
        f"{BENCH}/thermal.json", "onset.heat_frozen_at_rpm"), "{:,.0f}"),
    # timings and counts of the benchmarks
    "critical_mass_rkc_s": Quoted(f"{BENCH}/critical_mass.json",
                                  lambda: _critical_mass("rkc")["wall_s"], "{:.1f}"),
    "critical_mass_rk4_s": Quoted(f"{BENCH}/critical_mass.json",
                                  lambda: _critical_mass("rk4")["wall_s"], "{:.1f}"),
    "critical_mass_worst_rel_pct": Quoted(f"{BENCH}/critical_mass.json", lambda: 100 * max(
        _critical_mass(m)["rel_to_linear"] for m in ("rkc", "rk4")), "{:.3f}"),
    "rkc_evaluation_ratio": Quoted(f"{BENCH}/critical_mass.json", lambda: key(
        f"{BENCH}/critical_mass.json", "orbit_example.evaluation_ratio_rk4_over_rkc"), "{:.1f}"),
    "static_build_72_s": _static_build("72x20", "build"),
    "static_build_144_s": _static_build("144x36", "build"),
    "static_flat_build_72_s": _static_build("72x20", "flat_reference_build"),
    "static_flat_build_144_s": _static_build("144x36", "flat_reference_build"),
    # the rotor transient's cost (docs/rotor_transient.md)
    "rt_rotor_cpu_per_rev_s": _rt("per_revolution.rotor_cpu_s_per_revolution", "{:.3f}"),
    "rt_one_bearing_cpu_per_rev_s": _rt("per_revolution.one_bearing_cpu_s_per_revolution",
                                        "{:.3f}"),
    "rt_ratio": _rt("per_revolution.ratio", "{:.2f}"),
    "rt_ratio_loaded": _rt("per_revolution.ratio", "{:.2f}", loaded=True),
    "rt_revolutions": _rt("run_up_preloaded.revolutions", "{:.0f}"),
    "rt_preloaded_film_a_um": _rt("run_up_preloaded.min_film_um.0", "{:.2f}"),
    "rt_preloaded_film_b_um": _rt("run_up_preloaded.min_film_um.1", "{:.2f}"),
    "rt_preloaded_sync_a_um": _rt("run_up_preloaded.peak_amplitude_um.0", "{:.2f}"),
    "rt_preloaded_sync_b_um": _rt("run_up_preloaded.peak_amplitude_um.1", "{:.2f}"),
    "rt_preloaded_peak_rpm": _rt("run_up_preloaded.peak_speed_rpm.0", "{:,.0f}"),
    "rt_preloaded_subsync_rpm": _rt("run_up_preloaded.subsync_appearance_rpm", "{:,.0f}"),
    "rt_preloaded_evaluations": _rt("run_up_preloaded.evaluations", "{:,.0f}"),
    "rt_study_evaluations": _rt("run_up_study.evaluations", "{:,.0f}"),
    "rt_preloaded_cpu_s": _rt("run_up_preloaded.cpu_time_s", "{:.0f}"),
    "rt_preloaded_wall_s": _rt("run_up_preloaded.wall_time_s", "{:.0f}"),
    "rt_preloaded_cpu_loaded_s": _rt("run_up_preloaded.cpu_time_s", "{:.0f}", loaded=True),
    "rt_preloaded_wall_loaded_s": _rt("run_up_preloaded.wall_time_s", "{:.0f}", loaded=True),
    "rt_study_contact_rpm": _rt("run_up_study.contact_speed_rpm", "{:,.0f}"),
    "rt_study_subsync_rpm": _rt("run_up_study.subsync_appearance_rpm", "{:,.0f}"),
    "rt_study_cpu_s": _rt("run_up_study.cpu_time_s", "{:.1f}"),
    "rt_study_cpu_loaded_s": _rt("run_up_study.cpu_time_s", "{:.1f}", loaded=True),
    "rt_rhs_undamped_ratio": _rt("rhs_evaluation.study.ratio", "{:.2f}"),
    "rt_rhs_damped_ratio": _rt("rhs_evaluation.preloaded.ratio", "{:.2f}"),
}


# ---------------------------------------------------------------- reading the pages

def _prose(text: str) -> str:
    """The text without fenced code blocks (commands are not quotations) and without inline
    code that shows a marker (documentation of the marker, not one)."""
    text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
    return re.sub(r"`[^`\n]*<!--[^`\n]*`", "", text)


def _normalised(text: str) -> str:
    return text.replace("−", "-").replace("\u2009", " ").replace("\u00a0", " ")


def markers(text: str) -> list[tuple[list[str], str, str]]:
    """(names, the text each marker checks, its paragraph) for every marker of a page."""
    text = _prose(text)
    found, previous = [], 0
    for m in MARKER.finditer(text):
        paragraph_start = max(text.rfind("\n\n", 0, m.start()), 0)
        segment = text[max(previous, paragraph_start):m.start()]
        paragraph_end = text.find("\n\n", m.end())
        paragraph = text[paragraph_start:paragraph_end if paragraph_end >= 0 else len(text)]
        names = [n.strip() for n in m.group(1).split(",") if n.strip()]
        found.append((names, MARKER.sub(" ", segment), paragraph))
        previous = m.end()
    return found


def quoted_in(value: str, segment: str) -> bool:
    pattern = rf"(?<![\d,.]){re.escape(_normalised(value))}(?![\d]|[.,]\d)"
    return re.search(pattern, _normalised(segment)) is not None


def uncovered(text: str) -> list[str]:
    """Numbers with a unit in paragraphs citing ``results/`` that no marker there checks."""
    problems = []
    for paragraph in re.split(r"\n\s*\n", _prose(text)):
        if "results/" not in paragraph:
            continue
        checked = set()
        for m in MARKER.finditer(paragraph):
            checked |= {_normalised(QUOTED[n].text()) for n in
                        (n.strip() for n in m.group(1).split(",")) if n in QUOTED}
        prose = re.sub(r"`[^`]*`", " ", MARKER.sub(" ", paragraph))
        for hit in WITH_UNIT.finditer(prose):
            for number in re.findall(NUMBER, hit.group()):
                plain = _normalised(number).lstrip("+")
                if plain not in checked and plain.lstrip("-") not in checked:
                    problems.append(f"{number} (in {hit.group()!r}) in: "
                                    f"{' '.join(paragraph.split())[:120]}")
    return problems


def page(name: str) -> str:
    return (ROOT / name).read_text(encoding="utf-8")


# ---------------------------------------------------------------- tests

@pytest.mark.parametrize("name", PAGES)
def test_every_checked_number_matches_its_shipped_result(name):
    wrong = []
    for names, segment, _ in markers(page(name)):
        for n in names:
            assert n in QUOTED, f"{name}: marker names {n!r}, which is not in QUOTED"
            value = QUOTED[n].text()
            if not quoted_in(value, segment):
                wrong.append(f"{n} = {value!r} (from {QUOTED[n].source}) is not in: "
                             f"{' '.join(segment.split())[-200:]}")
    assert not wrong, f"{name}: quoted numbers differ from the shipped results:\n" + "\n".join(wrong)


@pytest.mark.parametrize("name", PAGES)
def test_no_unchecked_number_beside_a_result(name):
    problems = uncovered(page(name))
    assert not problems, (f"{name}: numbers next to a shipped result that no marker checks "
                          "(mark them with <!-- checked: NAME --> and an entry of QUOTED):\n"
                          + "\n".join(problems))


def test_every_quoted_value_is_quoted_somewhere():
    used = {n for name in PAGES for names, _, _ in markers(page(name)) for n in names}
    assert set(QUOTED) <= used, f"entries of QUOTED no page quotes: {sorted(set(QUOTED) - used)}"


def test_the_main_jobs_answer_is_checked_on_the_first_screen():
    """The README's first screen quotes the main job's first onset, and nothing else in the
    README contradicts it: every rpm figure next to results/rotor_bearing_design is checked."""
    text = page("README.md")
    first_screen = "\n".join(text.splitlines()[:40])
    names = {n for names, _, _ in markers(first_screen) for n in names}
    assert {"design_first_onset_rpm", "design_first_onset_default_grid_rpm"} <= names
    assert QUOTED["design_first_onset_rpm"].text() in first_screen


def test_a_stale_number_fails(tmp_path):
    """The checks catch the README of before: a stale onset beside its result, marked or not."""
    text = page("README.md")
    value = QUOTED["design_first_onset_rpm"].text()
    stale = text.replace(value, "25,131")
    assert any(not quoted_in(QUOTED[n].text(), seg)
               for names, seg, _ in markers(stale) for n in names if n == "design_first_onset_rpm")
    unmarked = text + ("\n\nThe design study finds no pair stable (best first onset 25,131 rpm at "
                       "36 × 10) — `results/rotor_bearing_design`.\n")
    assert any("25,131 rpm" in p for p in uncovered(unmarked))
