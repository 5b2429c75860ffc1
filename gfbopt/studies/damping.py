"""Study kind ``loss_factor_map``: the structural loss factor η of the bump foundation against
the compliance S (``problems/loss_factor.toml``; docs/PHYSICS.md §7).

The linear critical mass M̄c against S per η at fixed Λ and W̄, both deflection laws, with the
rigid bearing (S = 0) beside them; the onset speed of a rotor on a bearing file against S
(bump thickness) per η; the transient (Kelvin–Voigt foil state) critical mass against the
linear one at a few points.  The point functions and helpers are those of :mod:`.stability`.
"""
from __future__ import annotations

import math
import time

import numpy as np

from ..inputs import DEFLECTION_LAWS, BearingModel
from ..parallel import run_points
from . import checks
from .base import (
    Kind,
    RunContext,
    Study,
    StudyResult,
    build_model,
    frame,
    load_running_geometry,
)
from .spec import GRID, opt, req
from .stability import (confirmation_point, onset_point, reference_load, threshold_point,
                        _FILM_KEYS, _ROTOR, FAILED, OVERLOAD, STABLE, UNSTABLE_ALL,
                        UNSTABLE_LOW, _dispatch, _film_text, _seam,
                        _speed_range)

SCHEMAS: dict[str, dict] = {
    "loss_factor_map": {**GRID,
        "loss_factors": req("numbers", "structural loss factors η [-]"),
        "compliances": req("numbers", "compliances S > 0 of the foil bearings [-] (the rigid "
                           "bearing S = 0 is added)"),
        "deflection_laws": opt("strings", list(DEFLECTION_LAWS), "foil deflection laws",
                               choices=DEFLECTION_LAWS),
        "model": opt("table", {}, "film convention of every point", keys=_FILM_KEYS),
        "cases": req("tables", "non-dimensional operating points (fixed Λ and W̄)", keys={
            "label": req("string", "label of the case"),
            "bearing_number": req("number", "Λ [-]", positive=True),
            "length_ratio": opt("number", 1.0, "L/D [-]", positive=True),
            "eccentricity": opt("number", None, "ε [-] of the reference bearing that fixes "
                                "the load W̄ (or give `load`)", positive=True),
            "load": opt("number", None, "load W̄ [-] (or give `eccentricity`)", positive=True),
            "reference_compliance": opt("number", 1.0, "S of the reference bearing (axial-"
                                        "mean law, η = 0)", minimum=0.0)}),
        "onset": opt("table", None, "onset speed against S on a bearing file (S by the bump "
                     "thickness)", keys=_ROTOR),
        "onset_compliances": opt("numbers", None, "compliances of the onset part (default: "
                                 "`compliances`)"),
        "confirmations": opt("tables", [], "points confirmed by the transient critical mass "
                             "(Kelvin–Voigt foil state)", keys={
            "case": req("string", "label of the case"),
            "deflection_law": req("string", "foil deflection law", choices=DEFLECTION_LAWS),
            "compliance": req("number", "S [-]", positive=True),
            "loss_factor": req("number", "η [-]", minimum=0.0)}),
        "critical_mass_tolerance": opt("number", 0.002, "relative bracket of the transient "
                                       "critical-mass search", positive=True),
        "nonlinear_linear_tolerance": opt("number", 0.01, "largest |nonlinear/linear − 1| "
                                          "of the critical mass", minimum=0.0),
        "method": opt("string", "rkc", "transient integration method",
                      choices=("rkc", "rk4", "bdf"))},
}


# ------------------------------------------------------------------ loss_factor_map
def _foil_model(base: dict, case: dict, law: str, compliance: float, eta: float,
                where) -> BearingModel:
    opts = {**base, "bearing_number": case["bearing_number"],
            "length_ratio": case["length_ratio"], "compliance": compliance}
    if compliance == 0:
        opts["foil"] = "rigid"
    else:
        opts.update(foil="simple", deflection_law=law, loss_factor=eta)
    return build_model(opts, where)


def plan_loss_factor_map(study: Study) -> dict:
    spec = study.spec
    base = {"film": "seam", "seam_angle_deg": 180.0, **spec["model"]}
    if base.get("film") == "periodic":
        base.pop("seam_angle_deg", None)
    labels = [c["label"] for c in spec["cases"]]
    if len(set(labels)) != len(labels):
        raise study.where("cases").error(labels, "labels must be distinct")
    for k, eta in enumerate(spec["loss_factors"]):
        if not 0 <= eta <= 1:
            raise study.where("loss_factors", k).error(eta, "must lie in [0, 1]")
    for k, s in enumerate(spec["compliances"]):
        if not s > 0:
            raise study.where("compliances", k).error(s, "must be > 0 (the rigid bearing is "
                                                      "added)")
    cases = []
    for k, case in enumerate(spec["cases"]):
        where = study.where("cases", k)
        if (case["eccentricity"] is None) == (case["load"] is None):
            raise where.error(case, "give one of eccentricity (of the reference bearing) or "
                              "load")
        reference = _foil_model(base, case, "mean", case["reference_compliance"], 0.0, where)
        points = [{"law": "rigid", "compliance": 0.0, "loss_factor": 0.0,
                   "model": _foil_model(base, case, "mean", 0.0, 0.0, where)}]
        for law in spec["deflection_laws"]:
            for eta in spec["loss_factors"]:
                for s in spec["compliances"]:
                    points.append({"law": law, "compliance": float(s), "loss_factor": float(eta),
                                   "model": _foil_model(base, case, law, float(s), float(eta),
                                                        where)})
        cases.append({"case": case, "reference": reference, "points": points})
    by_label = {c["case"]["label"]: c for c in cases}
    confirmations = []
    for k, c in enumerate(spec["confirmations"]):
        if c["case"] not in by_label:
            raise study.where("confirmations", k, "case").error(
                c["case"], f"is not a case ({', '.join(labels)})")
        case = by_label[c["case"]]["case"]
        confirmations.append({**c, "model": _foil_model(base, case, c["deflection_law"],
                                                        c["compliance"], c["loss_factor"],
                                                        study.where("confirmations", k))})
    onset = None
    if spec["onset"] is not None:
        o = spec["onset"]
        from ..design.stability_design import bearing_with_compliance

        # [journal]/[thermal] read: each onset at the running condition of each speed
        geometry, running = load_running_geometry(Study(study.file, study.name, study.kind,
                                                        o, study.directory))
        speed_range = _speed_range(study, ("onset", "speed_range_rpm"), o["speed_range_rpm"])
        svalues = spec["onset_compliances"] or spec["compliances"]
        film = base.get("film", "seam")
        seam = _seam(base.get("seam_angle_deg", 180.0)) if film == "seam" else None
        common = {"rotor_mass_kg": o["rotor_mass_kg"], "load_newton": o["load_newton"],
                      "speed_range": speed_range, "film": film, "seam_angle_deg": seam, "grid": study.grid}
        points = [({"deflection_law": "rigid", "compliance": 0.0, "loss_factor": 0.0},
                   {**common, "bearing": geometry, "foil": "rigid", "deflection_law": "mean",
                    "loss_factor": 0.0})]
        for law in spec["deflection_laws"]:
            for eta in spec["loss_factors"]:
                for s in svalues:
                    if not s > 0:
                        raise study.where("onset_compliances").error(s, "must be > 0")
                    points.append(({"deflection_law": law, "compliance": float(s),
                                    "loss_factor": float(eta)},
                                   {**common, "bearing": bearing_with_compliance(geometry, s),
                                    "foil": "simple", "deflection_law": law,
                                    "loss_factor": float(eta)}))
        onset = {"geometry": geometry, "points": points, "speed_range": speed_range,
                 **_at_running_condition(study, geometry, running, points, speed_range)}
    return {"cases": cases, "confirmations": confirmations, "onset": onset, "base": base}


def _at_running_condition(study: Study, geometry, running, points: list,
                          speed_range) -> dict:
    """With ``[journal]``/``[thermal]`` in the onset's bearing file: ``running`` added to
    every onset point (:func:`.running_points.running_onset_row`) and the model named
    ({"thermal_model": …}); else {} (today's points).  The critical-mass map is
    non-dimensional: no clearance at speed enters it."""
    from ..thermal.running import ISOTHERMAL

    if running.model_name == ISOTHERMAL:
        return {}
    from ..inputs.rotor_limits import check_surface_speed

    check_surface_speed(geometry, list(speed_range), f"{study.file}: onset.speed_range_rpm")
    for _, point in points:
        point["running"] = running
    return {"thermal_model": running.model_name}


def _beats_rigid(table, value: str, group: str) -> list:
    """Per (group, law, η): the best S, its value, the rigid value and the S where the foil
    beats the rigid bearing."""
    out = []
    for key, sub in table.groupby(group, sort=False):
        rigid = sub[sub["deflection_law"] == "rigid"][value]
        rigid = float(rigid.iloc[0]) if len(rigid) else math.nan
        for (law, eta), g in sub[sub["deflection_law"] != "rigid"].groupby(
                ["deflection_law", "loss_factor"], sort=False):
            g = g.sort_values("compliance")
            vals = g[value].to_numpy(dtype=float)
            if not np.isfinite(vals).any():
                out.append({"group": key, "law": law, "eta": eta, "best_s": math.nan,
                            "best": math.nan, "rigid": rigid, "wins": []})
                continue
            k = int(np.nanargmax(vals))
            wins = [float(s) for s, v in zip(g["compliance"], vals)
                    if not math.isnan(v) and v > rigid]
            out.append({"group": key, "law": law, "eta": eta,
                        "best_s": float(g["compliance"].iloc[k]), "best": float(vals[k]),
                        "rigid": rigid, "wins": wins})
    return out


_LAW = {"mean": "axial-mean law", "local": "local law"}


def _s_text(values: list) -> str:
    return ", ".join(f"{v:g}" for v in values)


def _beat_notes(found: list, what: str, fmt: str) -> list:
    """One plain sentence per group: where the compliant (damped) foil beats the rigid
    bearing, by how much at best, and where it never does."""
    notes = []
    for group in dict.fromkeys(f["group"] for f in found):
        rows = [f for f in found if f["group"] == group]
        rigid = rows[0]["rigid"]
        parts = []
        for law in dict.fromkeys(f["law"] for f in rows):
            wins, never = [], []
            for f in (f for f in rows if f["law"] == law):
                if math.isnan(f["best"]):
                    never.append(f"{f['eta']:g} (no converged point)")
                elif f["wins"]:
                    gain = ("stable for every mass" if math.isinf(f["best"]) else
                            f"{f['best'] / rigid - 1:+.1%}")
                    wins.append(f"η = {f['eta']:g} at S = {_s_text(f['wins'])} (best "
                                f"{fmt.format(f['best'])} at S = {f['best_s']:g}, {gain})")
                else:
                    never.append(f"{f['eta']:g} (best {fmt.format(f['best'])} at "
                                 f"S = {f['best_s']:g})")
            text = f"{_LAW[law]}: "
            text += ("beats it with " + "; ".join(wins)) if wins else "never beats it"
            if never:
                text += ("; not with η = " if wins else ": η = ") + ", ".join(never)
            parts.append(text)
        notes.append(f"{what}{', ' + group if group else ''}, rigid bearing "
                     f"{fmt.format(rigid)}. "
                     + ". ".join(parts) + ".")
    return notes


def run_loss_factor_map(study: Study, plan: dict, ctx: RunContext) -> StudyResult:
    from ..plotting.stability import (
        plot_critical_mass_against_compliance,
        plot_onset_against_compliance,
    )

    spec = study.spec
    grid = study.grid
    t0 = time.perf_counter()
    # 1. the load W̄ of each case (the reference foil at its ε)
    refs = run_points(reference_load, [{"model": c["reference"], "eccentricity":
                                        c["case"]["eccentricity"], "grid": grid}
                                       for c in plan["cases"]
                                       if c["case"]["load"] is None], workers=1)
    given = iter(refs)
    refs = [{"load": c["case"]["load"]} if c["case"]["load"] is not None else next(given)
            for c in plan["cases"]]
    calls, tags = [], []
    for c, ref in zip(plan["cases"], refs):
        case = c["case"]
        for p in c["points"]:
            calls.append({"model": p["model"], "load": ref["load"], "grid": grid})
            tags.append({"case": case["label"], "bearing_number": case["bearing_number"],
                         "load": ref["load"], "deflection_law": p["law"],
                         "compliance": p["compliance"], "loss_factor": p["loss_factor"]})
    conf_calls, conf_tags = [], []
    loads = {c["case"]["label"]: r["load"] for c, r in zip(plan["cases"], refs)}
    case_of = {c["case"]["label"]: c["case"] for c in plan["cases"]}
    for c in plan["confirmations"]:
        conf_calls.append({"model": c["model"], "load": loads[c["case"]], "grid": grid,
                           "method": spec["method"],
                           "tolerance": spec["critical_mass_tolerance"]})
        conf_tags.append({"case": c["case"], "bearing_number":
                          case_of[c["case"]]["bearing_number"], "load": loads[c["case"]],
                          "deflection_law": c["deflection_law"],
                          "compliance": c["compliance"], "loss_factor": c["loss_factor"]})
    onset_calls = [p for _, p in plan["onset"]["points"]] if plan["onset"] else []
    onset_tags = [t for t, _ in plan["onset"]["points"]] if plan["onset"] else []
    # one pool for everything: the slow points (transients, onsets) first
    functions = ([("confirm", confirmation_point, c, t) for c, t in zip(conf_calls, conf_tags)]
                 + [("onset", onset_point, c, t) for c, t in zip(onset_calls, onset_tags)]
                 + [("map", threshold_point, c, t) for c, t in zip(calls, tags)])
    rows = run_points(_dispatch, [{"which": w, "call": c} for w, _, c, _ in functions],
                      workers=ctx.workers, tags=[t for *_, t in functions],
                      progress=ctx.progress)
    elapsed = time.perf_counter() - t0
    part = {"confirm": [], "onset": [], "map": []}
    for (w, *_), r in zip(functions, rows):
        part[w].append(r)
    first = ("case", "bearing_number", "load", "deflection_law", "compliance", "loss_factor")
    table = frame(part["map"], first, ("critical_mass", "whirl_ratio"))
    tables = {"critical_mass.csv": table}
    figures = {}
    ax = plot_critical_mass_against_compliance(
        table, title="Linear critical mass against compliance S per loss factor η, rigid "
        "bearing (S = 0) dashed; " + _film_text(plan["base"]))
    figures["critical_mass.png"] = np.asarray(ax).flat[0].figure
    over = table["load_exceeds_capacity"].fillna(False).astype(bool)
    found = [checks.check("every point of the critical-mass map converged or exceeds the "
                          "load capacity (failed rows)",
                          float((~table["success"].astype(bool) & ~over).sum()), 0)]
    if over.any():
        notes_over = ["Load W̄ exceeds the capacity of the foil (static continuation stopped "
                      "with the film closing; no critical mass) at: " + "; ".join(
                          f"{c}, {_LAW[law]}, S = {s:g}" for (c, law, s) in dict.fromkeys(
                              zip(table.loc[over, "case"], table.loc[over, "deflection_law"],
                                  table.loc[over, "compliance"]))) + " (every η)."]
    else:
        notes_over = []
    notes = _beat_notes(_beats_rigid(table.assign(group=[
        f"Λ = {b:g}, W̄ = {w:.3g}" for b, w in zip(table["bearing_number"], table["load"])]),
        "critical_mass", "group"), "Linear critical mass M̄c", "{:.3g}") + notes_over
    if plan["onset"]:
        o = spec["onset"]
        otable = frame(part["onset"], ("deflection_law", "compliance", "loss_factor",
                                       "onset_speed_rpm", "onset_status"),
                       ("onset_speed_rpm",))
        tables["onset.csv"] = otable
        low, high = plan["onset"]["speed_range"]
        ax = plot_onset_against_compliance(
            otable, speed_range=(low, high),
            title=(f"Onset speed of whirl against compliance S (bump thickness) per loss "
                   f"factor η: {o['rotor_mass_kg']:g} kg, {o['load_newton']:g} N per bearing, "
                   f"{plan['onset']['geometry'].name}, " + _film_text(plan["base"])))
        figures["onset_speed.png"] = np.asarray(ax).flat[0].figure
        found.append(checks.check("every onset search ended with an answer (failed rows)",
                                  float((otable["onset_status"] == FAILED).sum()), 0))
        ranked = otable.assign(group="", value=np.where(
            otable["onset_status"] == STABLE, high, np.where(
                otable["onset_status"].isin([UNSTABLE_LOW, UNSTABLE_ALL]), low,
                otable["onset_speed_rpm"])))
        notes += _beat_notes(_beats_rigid(ranked, "value", "group"),
                             f"Onset speed [rpm] of {o['rotor_mass_kg']:g} kg at "
                             f"{o['load_newton']:g} N on {plan['onset']['geometry'].name}",
                             "{:,.0f} rpm")
        nover = otable[otable["onset_status"] == OVERLOAD]
        if len(nover):
            notes.append("Load exceeds the capacity (no onset computed) at: " + "; ".join(
                f"{r['deflection_law']}, η = {r['loss_factor']:g}, S = {r['compliance']:g}"
                for _, r in nover.iterrows()) + ".")
    if part["confirm"]:
        ctable = frame(part["confirm"], first, ("nonlinear_over_linear",))
        tables["confirmation.csv"] = ctable
        for _, r in ctable.iterrows():
            found.append(checks.check(
                f"{r['case']}, {_LAW[r['deflection_law']]}, S = {r['compliance']:g}, η = "
                f"{r['loss_factor']:g}: |transient / linear critical mass − 1|",
                abs(r["nonlinear_over_linear"] - 1) if np.isfinite(r["nonlinear_over_linear"])
                else math.nan, spec["nonlinear_linear_tolerance"]))
    notes.append(f"{len(rows)} points in {elapsed:.1f} s on {ctx.workers} worker "
                 f"process{'es' if ctx.workers > 1 else ''}, grid {grid}")
    options = {"variants": {"all": {**plan["base"], "foil": "simple (rigid at S = 0)"}},
               "grid": str(grid), "loss_factors": spec["loss_factors"],
               "compliances": spec["compliances"], "method": spec["method"],
               "critical_mass_tolerance": spec["critical_mass_tolerance"]}
    answer = {}
    if plan["onset"] and plan["onset"].get("thermal_model"):    # the onset's model named
        from .running_points import running_notes

        name = options["thermal_model"] = answer["thermal_model"] = \
            plan["onset"]["thermal_model"]
        notes += running_notes(name, spec["onset"]["bearing"])
        notes.append("The critical-mass map is non-dimensional (Λ, S, W̄ given): only the "
                     "onset part (onset.csv) is at the running condition.")
    return StudyResult(study, tables=tables, figures=figures, checks=found, options=options,
                       notes=notes, answer=answer)


KINDS = {"loss_factor_map": Kind(plan_loss_factor_map, run_loss_factor_map, parallel=True)}
