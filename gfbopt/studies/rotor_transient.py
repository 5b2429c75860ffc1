"""Study kind ``rotor_run_up``: a run-up of a rotor on two foil bearings with a stated
imbalance (problems/rotor_run_up.toml).

A run-up from ``start_rpm`` to ``end_rpm`` at ``rate_rpm_per_s`` (gfbopt.transient
.rotor_analysis.rotor_ramp) gives the waterfall at each bearing, the 1× and subsynchronous
components against speed and the speed where the subsynchronous line appears, set beside
the rotor's linear onset (gfbopt.rotor.system, when this build has it); then an orbit at the
top speed from a small kick gives the limit-cycle amplitude and whirl frequency there, with
its settledness (or contact).  Imbalance: ``balance_grade_mm_per_s`` (ISO 21940-11,
U = m G/ω_max, split over two planes at the bearings by their static load shares, phase 0),
or the rotor file's planes.
"""
from __future__ import annotations

import math
from dataclasses import replace

import pandas as pd

from ..errors import ParameterError
from . import checks
from .base import Kind, RunContext, Study, StudyResult
from .spec import GRID, opt, req

SCHEMAS: dict = {
    "rotor_run_up": {**GRID,
        "rotor": req("string", "rotor file (TOML), relative to the study file"),
        "start_rpm": req("number", "speed at the start of the run-up [rpm]", positive=True),
        "end_rpm": req("number", "speed at its end [rpm]", positive=True),
        "rate_rpm_per_s": req("number", "run-up rate [rpm/s]", positive=True),
        "balance_grade_mm_per_s": opt("number", None, "ISO balance grade G [mm/s] replacing "
                                      "the rotor file's imbalance", positive=True),
        "method": opt("string", "rkc", "integration method", choices=("rkc", "rk4")),
        "time_step": opt("number", None, "Δτ [rad of rotation at the top speed]",
                         positive=True),
        "top_speed_revolutions": opt("number", 300.0, "revolutions of the orbit at the top "
                                     "speed (limit cycle)", positive=True),
        "kick": opt("number", 1e-3, "journal speed of the top-speed orbit's kick [-]",
                    positive=True),
        "window_revolutions": opt("number", 20.0, "waterfall window [revolutions at the "
                                  "mean speed]", positive=True),
        "subsync_threshold_um": opt("number", None, "amplitude from which the "
                                    "subsynchronous line counts as present [µm]",
                                    positive=True),
        "settle_tolerance": opt("number", 0.01, "largest relative change of the limit cycle "
                                "between its last two windows to call it settled",
                                positive=True),
        "cycle_speed_ratios": opt("numbers", [1.02, 1.05], "orbits just above the linear "
                                  "onset, at these multiples of it (the limit cycle past "
                                  "the onset)"),
        "cycle_revolutions": opt("number", 300.0, "revolutions of each of those orbits",
                                 positive=True),
        "force": opt("flag", False, "allow more than the revolution limit"),
    },
}


def _system(study: Study):
    from ..inputs.rotor_system import ImbalancePlane, load_rotor
    from ..rotor.rigid import bearing_loads
    from ..transient.rotor_setup import iso_g_imbalance

    spec = study.spec
    try:
        system = load_rotor(study.directory / spec["rotor"])
    except ParameterError as exc:
        raise study.where("rotor").error(spec["rotor"], f"{exc.name}: {exc.rule}") from None
    grade = spec["balance_grade_mm_per_s"]
    if grade is not None:
        total = iso_g_imbalance(grade, system.body.mass, max(spec["start_rpm"],
                                                              spec["end_rpm"]))
        shares = [w.magnitude for w in bearing_loads(system)]
        planes = tuple(ImbalancePlane(total * s / sum(shares), b.position, 0.0,
                                      f"G{grade:g} at {b.name}")
                       for s, b in zip(shares, system.bearings))
        system = replace(system, imbalance=planes)
    if not system.imbalance:
        raise study.where("balance_grade_mm_per_s").error(None, "the rotor file has no "
                                                          "imbalance plane: state a grade")
    return system


def plan_rotor_run_up(study: Study) -> dict:
    from ..transient.rotor_analysis import orbit_profile, ramp_profile

    spec = study.spec
    system = _system(study)
    try:
        ramp = ramp_profile(spec["start_rpm"], spec["end_rpm"], spec["rate_rpm_per_s"],
                            "run-up", spec["force"])
        top = orbit_profile(spec["end_rpm"], spec["top_speed_revolutions"], spec["force"])
    except ParameterError as exc:
        raise study.where(exc.name).error(exc.value, exc.rule) from None
    return {"system": system, "ramp": ramp, "top": top}


def run_rotor_run_up(study: Study, plan: dict, ctx: RunContext) -> StudyResult:
    from ..inputs import Grid
    from ..plotting.waterfall import plot_components, plot_journal_orbits, plot_waterfall
    from ..progress import progress
    from ..transient.rotor_analysis import progress_units, run_profile
    from ..transient.rotor_result import whirl_words

    spec, system = study.spec, plan["system"]
    grid = Grid.parse(spec["grid"])
    common = dict(grid=grid, method=spec["method"], time_step=spec["time_step"],
                  system=system)
    ramp = plan["ramp"]
    total, unit = progress_units(ramp)
    with progress(total=total, desc="rotor run-up", unit=unit) as bar:
        up = run_profile(system, ramp, perturbation="none", progress=bar,
                         window_revolutions=spec["window_revolutions"],
                         subsync_threshold_um=spec["subsync_threshold_um"], **common)
    top = plan["top"]
    total, unit = progress_units(top)
    with progress(total=total, desc="orbit at the top speed", unit=unit) as bar:
        orbit = run_profile(system, top, perturbation="cylindrical", kick=spec["kick"],
                            progress=bar, settle_tolerance=spec["settle_tolerance"], **common)
    names = up.names
    cycles = _cycles_past_onset(system, spec, up.onset.get("linear_onset_speed_rpm",
                                                           math.nan), common)
    tables, figures, found, notes = {}, {}, [], list(up.notes)
    if cycles is not None:
        tables["limit_cycles_past_onset.csv"] = cycles
        for _, r in cycles.iterrows():
            notes.append(f"{r['speed_rpm']:,.0f} rpm ({r['speed_over_linear_onset']:.3g} × the "
                         f"linear onset), bearing {r['bearing']}: " + (
                             f"contact after {r['contact_time_s']:.4g} s" if r["contact"] else
                             whirl_words(r)))
    what = (f"run-up {ramp.start_rpm:,.0f} → {ramp.end_rpm:,.0f} rpm at "
            f"{ramp.rate_rpm_per_s:,.0f} rpm/s, {grid}")
    lin = up.onset.get("linear_onset_speed_rpm", math.nan)
    comp = {}
    for k, name in enumerate(names):
        w = up.waterfalls[0][k]
        comp[name] = w.table()
        tables[f"components_{name}.csv"] = comp[name]
        ax = plot_waterfall(w, bearing=name, linear_onset_rpm=lin,
                            appearance_rpm=up.onset.get(f"subsync_appearance_{name}_rpm",
                                                        math.nan),
                            title=f"Waterfall at bearing {name}: {what}")
        figures[f"waterfall_{name}.png"] = ax.figure
    axes = plot_components(comp, linear_onset_rpm=lin,
                           threshold_um=up.onset["subsync_threshold_um"],
                           title=f"1× and subsynchronous components: {what}")
    figures["components.png"] = axes[0].figure
    frame = orbit.orbit_frame()
    tables["orbit_top_speed.csv"] = frame
    c_um = orbit.run.model.bearings[0].clearance * 1e6
    figures["orbits_top_speed.png"] = plot_journal_orbits(
        frame, names, clearance_um=c_um, title=f"Journal orbits at {top.start_rpm:,.0f} rpm "
        f"from a small kick ({top.revolutions:g} revolutions)").figure
    up_d, top_d = up.to_dict(), orbit.to_dict()
    rows = [("subsync_appearance_rpm", up.onset["subsync_appearance_rpm"]),
            ("linear_onset_speed_rpm", lin),
            ("appearance_over_linear_onset", up.onset["appearance_over_linear_onset"]),
            ("run_up_contact", float(up_d["contact"])),
            ("run_up_contact_speed_rpm", up_d["contact_speed_rpm"]),
            ("run_up_contact_time_s", up_d["contact_time_s"]),
            ("run_up_revolutions", up.run.revolutions), ("run_up_wall_time_s",
                                                        up.run.wall_time_s)]
    for b in up_d["bearings"]:
        rows.append((f"run_up_min_film_{b['bearing']}_um", b["min_film_um"]))
    for b in top_d["bearings"]:
        for key in ("limit_cycle_amplitude_um", "limit_cycle_frequency_hz",
                    "limit_cycle_change", "sync_amplitude_um", "min_film_um"):
            if key in b:
                rows.append((f"top_speed_{key}_{b['bearing']}", b[key]))
    rows.append(("top_speed_contact", float(top_d["contact"])))
    tables["summary.csv"] = pd.DataFrame(rows, columns=["quantity", "value"])
    found.append(checks.check("run-up integrated to its end or to a reported contact "
                              "(failed runs)", float(not up.success), 0))
    found.append(checks.check("top-speed orbit integrated (failed runs)",
                              float(not orbit.success), 0))
    if up_d["contact"]:
        notes.append(f"The run-up ends in contact ({up_d['contact_kind']}) at bearing "
                     f"{up_d['contact_bearing']}, {up_d['contact_speed_rpm']:,.0f} rpm, "
                     f"t = {up_d['contact_time_s']:.4g} s; the record up to there is kept.")
    if top_d["contact"]:
        notes.append(f"At the top speed the whirl grows into contact at bearing "
                     f"{top_d['contact_bearing']} after {top_d['contact_time_s']:.4g} s: no "
                     "limit cycle with a film (the design is not acceptable there).")
    else:
        for b in top_d["bearings"]:
            notes.append(f"Top speed, bearing {b['bearing']}: {whirl_words(b)}")
    notes.append(f"Linear onset: {up.onset.get('linear_onset_source')}.")
    notes += orbit.notes[:1]
    options = {"grid": str(grid), "method": spec["method"], "rotor": spec["rotor"],
               "imbalance": up.description.get("imbalance"),
               "bearings": up.description.get("bearings")}
    return StudyResult(study, tables=tables, figures=figures, checks=found, options=options,
                       notes=notes)


def _cycles_past_onset(system, spec, onset: float, common: dict):
    """Orbits at multiples of the linear onset from a small kick: the limit cycle (or
    contact) past the onset, per bearing; None without a linear onset."""
    from ..progress import progress
    from ..transient.rotor_analysis import orbit_profile, progress_units, run_profile

    if not (math.isfinite(onset) and spec["cycle_speed_ratios"]):
        return None
    rows = []
    for ratio in spec["cycle_speed_ratios"]:
        profile = orbit_profile(ratio * onset, spec["cycle_revolutions"], spec["force"])
        total, unit = progress_units(profile)
        with progress(total=total, desc=f"orbit at {ratio:g} × onset", unit=unit) as bar:
            result = run_profile(system, profile, perturbation="cylindrical",
                                 kick=spec["kick"], progress=bar,
                                 settle_tolerance=spec["settle_tolerance"], **common)
        d = result.to_dict()
        for b in d["bearings"]:
            rows.append({"speed_rpm": profile.start_rpm, "speed_over_linear_onset": ratio,
                         "bearing": b["bearing"], "contact": d["contact"],
                         "contact_time_s": d["contact_time_s"],
                         "limit_cycle_status": b.get("limit_cycle_status", "none"),
                         **{key: _number(b.get(key)) for key in (
                             "limit_cycle_amplitude_um", "limit_cycle_frequency_hz",
                             "limit_cycle_whirl_ratio", "limit_cycle_change",
                             "sync_amplitude_um")},
                         "limit_cycle_settled": b.get("limit_cycle_settled"),
                         "min_film_um": b["min_film_um"],
                         "revolutions": result.run.revolutions})
    return pd.DataFrame(rows)


def _number(value) -> float:
    """A JSON number of a result (None: not there) as a table's float (NaN: empty)."""
    return math.nan if value is None else float(value)


KINDS: dict = {"rotor_run_up": Kind(plan_rotor_run_up, run_rotor_run_up)}
