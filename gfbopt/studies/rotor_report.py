"""What a bearing-pair design study reports (:mod:`.rotor_design`): the chosen design and why,
its robustness and its answer on the default grid, the verdict in words, tables, figures and
checks."""
from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
import pandas as pd

from ..design.decision import binding_limits, failed_count, limits_frame, limits_text
from ..design.pareto import feasible_rows
from ..design.rotor_objectives import design_conventions
from ..design.lever_runs import STORE_SCHEMA, answers_text
from ..plotting.design_front import variable_label
from .base import StudyResult
from .rotor_decision import answers_frame, answers_records, margin_of, margin_text, run_levers

#: the search methods (gfbopt.design.search.METHODS) in words
SEARCH_WORDS = {"nsga2": "pymoo NSGA-II",
                "nsga2_refine": "pymoo NSGA-II, then a constrained pattern search of its "
                                "best design (gfbopt.design.refine)",
                "bayes": "GP Bayesian optimisation, bayesian-optimization"}

#: largest relative difference between a design's stored objectives and the same design
#: evaluated again from scratch (a fresh solver cache): the evaluation is deterministic, so
#: only round-off may differ
REPRODUCE_TOLERANCE = 1e-6


def choose(table: pd.DataFrame, problem, top_speed: float):
    """(chosen row or None, why): stable to the top speed at the least power loss when some
    feasible design is; otherwise the highest first onset (then the least power)."""
    ok = feasible_rows(table, problem)
    if ok.empty:
        return None, "no evaluated design meets every limit"
    stable = ok[ok["first_onset_speed_rpm"] >= top_speed]
    if len(stable):
        row = stable.sort_values("total_power_loss_w").iloc[0]
        return row.to_dict(), (f"{len(stable)} of {len(ok)} feasible designs are stable to "
                               f"the top speed; the chosen one loses the least power")
    row = ok.sort_values(["first_onset_speed_rpm", "total_power_loss_w"],
                         ascending=[False, True]).iloc[0]
    return row.to_dict(), (f"none of the {len(ok)} feasible designs is stable to the top "
                           "speed; the chosen one has the highest first onset")


def describe(row: dict, names: list) -> str:
    """The design's values for people, e.g. 'radial clearance c 18.3 µm, pads 3'."""
    parts = []
    for n in names:
        label = variable_label(n)
        unit = label[label.rfind("[") + 1:-1] if label.endswith("]") else ""
        text = label[:label.rfind("[")].strip() if unit else label
        value = float(row[n])
        shown = f"{value:.0f}" if value == int(value) and unit in ("-", "") else f"{value:.3g}"
        parts.append(f"{text} {shown}{'' if unit in ('-', '') else ' ' + unit}")
    return ", ".join(parts)


def _onset_text(row: dict, search_high: float) -> str:
    if row["onset_status"] == "stable over the range":
        return f"above {search_high:,.0f} rpm (every mode stable to the end of the search)"
    if row["onset_status"] != "onset":
        return f"below {row['first_onset_speed_rpm']:,.0f} rpm (unstable at the lowest speed)"
    return f"{row['first_onset_speed_rpm']:,.0f} rpm ({row['first_mode']})"


def verdict(chosen, why: str, plan, check, whirl=None) -> str:
    """The answer in words, for the first line of the README."""
    s = plan.settings
    top, grid, default = s.top_speed_rpm, str(s.grid), str(plan.default_settings.grid)
    if chosen is None:
        return (f"No design in this space meets every limit ({why}); nothing is stable to "
                f"{top:,.0f} rpm here. Searched on the {grid} grid.")
    names = plan.problem.names
    honest = ""
    if check is not None and check.get("success"):
        honest = (f"; on the default {default} grid the first onset is "
                  f"{check['first_onset_speed_rpm_default_grid']:,.0f} rpm "
                  f"({check['first_onset_speed_rpm_relative_change']:+.1%}) and the power "
                  f"loss {check['total_power_loss_w_default_grid']:.0f} W")
        if not check.get("feasible_default_grid", True):
            honest += (f", but there the design breaks a limit (minimum film "
                       f"{check['min_film_lowest_speed_um_default_grid']:.2f} µm against "
                       f"{check['min_film_lowest_speed_um_search_grid']:.2f} µm on the search grid): the "
                       "search grid is too coarse for this limit")
            alt = check.get("feasible_alternative")
            honest += (f"; of the designs re-checked there, {describe(alt, names)} meets every "
                       f"limit (first onset {alt['first_onset_speed_rpm_default_grid']:,.0f} rpm, "
                       f"minimum film {alt['min_film_lowest_speed_um_default_grid']:.2f} µm)"
                       if alt else "; none of the designs re-checked there meets it")
    film = (f"minimum film {chosen['min_film_lowest_speed_um']:.2f} µm at {s.speed_low_rpm:,.0f} rpm under "
            f"{s.heaviest_load_factor:g}× the static load")
    heated = [b.name for b in plan.system.bearings if getattr(b, "running_tables", ())]
    if heated:          # the clearance at speed: say which model the answer comes from
        honest = (f", with bearing{'s' if len(heated) > 1 else ''} {' and '.join(heated)} at "
                  "the running clearance of its heat balance and growth at every speed"
                  + honest)
    if chosen["first_onset_speed_rpm"] >= top:
        return (f"Stable to {top:,.0f} rpm with {describe(chosen, names)}: first onset "
                f"{_onset_text(chosen, s.search_high_rpm)}, {chosen['total_power_loss_w']:.0f} W "
                f"lost in both bearings at {top:,.0f} rpm, {film} — answer from the {grid} "
                f"search grid{honest}.")
    return (f"No design in this space is stable to {top:,.0f} rpm; the best first onset is "
            f"{chosen['first_onset_speed_rpm']:,.0f} rpm (mode {chosen['first_mode']}) with "
            f"{describe(chosen, names)}, {film}; {whirl_text(whirl, top)} — answer from the "
            f"{grid} search grid{honest}.")


def whirl_text(whirl, top: float) -> str:
    """The whirl at the top speed in words (the rotor transient's orbit)."""
    if whirl is None:
        return f"the whirl at {top:,.0f} rpm was not computed (limit_cycle_revolutions = 0)"
    if whirl.get("running") and whirl["running"].get("failure"):
        return f"the orbit at {top:,.0f} rpm was not run: {whirl['running']['failure']}"
    if whirl.get("model"):          # the bumps rub: the transient with sliders
        return friction_whirl_text(whirl, top)
    frozen = (" (each bearing held at its running clearance and viscosity at that speed)"
              if whirl.get("running") else "")
    if whirl["contact"]:
        return (f"at {top:,.0f} rpm the whirl grows until the film closes at bearing "
                f"{whirl['contact_bearing']} after {whirl['contact_time_s'] * 1e3:.0f} ms "
                f"(no limit cycle within the film){frozen}")
    if not whirl["success"]:
        return (f"the orbit at {top:,.0f} rpm on the {whirl['grid']} grid failed "
                f"({whirl['message']}): no limit cycle to report")
    film = min(b["min_film_um"] for b in whirl["bearings"])
    run = f"{whirl['revolutions']:.4g} revolutions on the {whirl['grid']} grid"
    whirling = [b for b in whirl["bearings"] if b.get("limit_cycle_status", "none") != "none"]
    if not whirling:
        return (f"at {top:,.0f} rpm no subsynchronous whirl (minimum film {film:.2f} µm; "
                f"{run})")
    cycles = " and ".join(f"{b['limit_cycle_amplitude_um']:.2f} µm at bearing {b['bearing']}"
                          for b in whirling)
    quiet = [b["bearing"] for b in whirl["bearings"] if b not in whirling]
    cycles += "".join(f", none at bearing {q}" for q in quiet)
    state = ("settled" if all(b["limit_cycle_settled"] for b in whirling)
             else "not yet settled")
    return (f"at {top:,.0f} rpm the whirl limit cycle is {cycles} with minimum film "
            f"{film:.2f} µm ({run}, {state})")


def friction_whirl_text(whirl, top: float) -> str:
    """The top-speed whirl of a rotor whose bumps rub in words (the rotor transient with
    sliders, :func:`gfbopt.design.robustness.whirl_at_top_speed`): 'bounded whirl of A µm at
    B Hz, minimum film F µm' when every bearing's orbit settled, 'contact at bearing X after
    T ms', or how the run ended; the model named, the describing function's prediction
    beside it."""
    run = f"{whirl['revolutions']:.4g} revolutions on the {whirl['grid']} grid"
    second = (f"; the describing function of the bumps' friction says "
              f"{whirl.get('describing_function_verdict', 'nothing')}")
    by = f" (by the {whirl['model']}, {run}{second})"
    bearings = whirl["bearings"]
    if whirl["contact"]:
        return (f"at {top:,.0f} rpm contact at bearing {whirl['contact_bearing']} after "
                f"{whirl['contact_time_s'] * 1e3:.3g} ms{by}")
    if not whirl["success"]:
        return (f"the orbit at {top:,.0f} rpm on the {whirl['grid']} grid failed "
                f"({whirl['message']}): no limit cycle to report (by the {whirl['model']}"
                f"{second})")
    film = min(b["min_film_um"] for b in bearings)
    if all(b.get("friction_orbit_kind") == "settled limit cycle" for b in bearings):
        hz = [b["friction_orbit_whirl_frequency_hz"] for b in bearings]
        if max(hz) - min(hz) <= 1e-3 * max(hz):     # one whirl (to the figures shown)
            amps = " and ".join(f"{b['friction_orbit_amplitude_um']:.3g} µm at bearing "
                                f"{b['bearing']}" for b in bearings)
            whirling = f"{amps} at {hz[0]:.4g} Hz"
        else:
            whirling = " and ".join(f"{b['friction_orbit_amplitude_um']:.3g} µm at "
                                    f"{b['friction_orbit_whirl_frequency_hz']:.4g} Hz at "
                                    f"bearing {b['bearing']}" for b in bearings)
        return (f"at {top:,.0f} rpm bounded whirl of {whirling}, minimum film {film:.3g} µm"
                f"{by}")
    ends = "; ".join(f"bearing {b['bearing']} {b.get('friction_orbit_verdict', '')}"
                     for b in bearings)
    return (f"at {top:,.0f} rpm no settled whirl by the end of the run ({ends}), minimum "
            f"film {film:.3g} µm{by}")


def _reproduce(plan, chosen: dict) -> float:
    """Largest relative difference of the chosen design's objectives evaluated again from
    scratch (new solver cache) against the stored ones."""
    from ..design.rotor_objectives import evaluate_rotor_design

    row = evaluate_rotor_design(plan.system, plan.settings, None,
                                **{n: float(chosen[n]) for n in plan.problem.names})
    worst = 0.0
    for o in plan.problem.objectives:
        a, b = float(chosen[o.name]), float(row.get(o.name, math.nan))
        worst = max(worst, abs(b / a - 1.0) if a else abs(b))
    return worst if row.get("success") else math.inf


def report(study, plan, search, run_tasks, stages, started: float, store,
           resume: bool = False) -> StudyResult:
    """The StudyResult of a finished search (module docstring); ``stages``: the run's
    :class:`gfbopt.progress.Stages` (``"whirl at top speed"``, ``"default-grid check"``,
    ``"tolerances"``, ``"what it would take"`` when the study names levers,
    ``"reproduction"``); ``started``: the run's time.perf_counter() at its
    start (the wall time stated covers the whole study: search, default-grid check,
    robustness, the orbit at the top speed and the reproduction); ``store``: the search's
    :class:`gfbopt.doe.ResultStore` (the table of every evaluation has its columns, and the
    stored-once check counts the rows it holds); ``resume``: the what-it-would-take
    evaluations of an earlier run of the same study are answered from their store
    (:func:`gfbopt.studies.rotor_decision.lever_store`)."""
    from ..design.robustness import regrid, robustness
    from ..plotting.design_front import plot_design_front, plot_onset_against_variables

    s, problem = plan.settings, plan.problem
    stored = store.read()
    table = search.table.reindex(columns=list(store.schema))   # one schema: store and CSV
    front = search.front
    chosen, why = choose(table, problem, s.top_speed_rpm)
    checked = []
    if chosen is not None:
        checked = [chosen] + [r for r in front.to_dict(orient="records")
                              if r["point"] != chosen["point"]]
    whirl = None            # first: its length (it ends at contact) is the least known
    step = stages.stage("whirl at top speed")
    if (chosen is not None and chosen["first_onset_speed_rpm"] < s.top_speed_rpm
            and plan.limit_cycle_revolutions > 0):
        from ..design.robustness import whirl_at_top_speed

        whirl = whirl_at_top_speed(plan.system, {n: float(chosen[n]) for n in problem.names},
                                   dataclasses.replace(s, grid=plan.limit_cycle_grid),
                                   plan.limit_cycle_revolutions, step)
    step = stages.stage("default-grid check")
    default = regrid(plan.system, plan.default_settings, checked[:plan.regrid_designs], problem,
                     run_tasks, step) if checked else pd.DataFrame()
    robust = pd.DataFrame()
    r = plan.robustness
    step = stages.stage("tolerances")
    if checked and (r.tolerances or plan.loss_factor_band[1] > plan.loss_factor_band[0]):
        robust = robustness(plan.system, s, checked[:r.designs], r.tolerances,
                            plan.loss_factor_band, r.samples, r.seed, problem, run_tasks, step)
    check = default.iloc[0].to_dict() if len(default) else None
    if check is not None and not check.get("feasible_default_grid", True):
        ok = default.iloc[1:][default.iloc[1:]["feasible_default_grid"].astype(bool)]
        check["feasible_alternative"] = (ok.sort_values(
            "first_onset_speed_rpm_default_grid").iloc[-1].to_dict() if len(ok) else None)
    limits = binding_limits(table, problem, chosen)
    levers, lever_runs, margin = None, None, None
    named = bool(study.spec.get("what_it_would_take"))   # its stage exists (run_stages)
    step = stages.stage("what it would take") if named else None
    if chosen is not None and chosen["first_onset_speed_rpm"] < s.top_speed_rpm and named:
        levers, lever_runs = run_levers(study, plan, chosen, store, run_tasks, resume, step)
        levers = levers if lever_runs is not None else None
    elif chosen is not None:
        margin = margin_of(chosen, robust, s.top_speed_rpm)
    found = answer(chosen, why, table, plan, check, whirl, limits, levers, margin)
    text = found["verdict"]
    notes = [text, f"Why this design: {why}."]
    notes += limits_text(limits, len(table), failed_count(table))
    if levers:
        notes.append(answers_text(levers, s.top_speed_rpm, chosen["first_onset_speed_rpm"],
                                  lever_runs.evaluated, lever_runs.reused,
                                  lever_runs.seconds, str(s.grid)))
    if margin is not None:
        notes.append(margin_text(margin, s.search_high_rpm))
    mean = search.evaluation_time_s / search.evaluated if search.evaluated else math.nan
    method = SEARCH_WORDS.get(plan.search.method, plan.search.method)
    notes.append(
        f"Search: {plan.search.method} ({method}), budget {plan.search.budget}, seed "
        f"{plan.search.seed}, on the {s.grid} grid: {search.evaluated} designs evaluated, "
        f"{search.reused} answered from the store (resume), {search.repeated} repeats; "
        f"{len(feasible_rows(table, problem))} feasible, {len(front)} on the Pareto front; "
        + (f"{search.evaluated / search.wall_time_s:.3g} evaluations per second of wall "
           f"time (one evaluation {mean:.1f} s of its worker)" if search.evaluated else
           "no evaluation in this run")
        + f"; the optimiser's own time {search.driver_time_per_design_s * 1e3:.0f} ms per "
        "design (imports included).")
    if chosen is not None and len(default):
        rel = default["first_onset_speed_rpm_relative_change"].abs()
        notes.append(f"Grid honesty: {len(default)} designs re-evaluated on the default "
                     f"{plan.default_settings.grid} grid; first onset changes by at most "
                     f"{rel.max():.2%} (chosen design "
                     f"{check['first_onset_speed_rpm_relative_change']:+.2%}).")
    if len(robust):
        notes.append(robustness_text(robust.iloc[0], r, plan.loss_factor_band))
    tables = {"evaluations.csv": table, "pareto_front.csv": front}
    if limits:
        tables["binding_limits.csv"] = limits_frame(limits)
    if levers:
        tables["what_it_would_take.csv"] = answers_frame(levers)
        tables["what_it_would_take_evaluations.csv"] = pd.DataFrame(
            lever_runs.rows).drop_duplicates("point").reindex(columns=list(STORE_SCHEMA))
    if whirl is not None:
        # bumps that rub: the describing function's statement beside the transient's
        second = ({"friction_model": whirl["describing_function_model"],
                   "friction_verdict": whirl["describing_function_verdict"]}
                  if "describing_function_verdict" in whirl else {})
        tables["whirl_at_top_speed.csv"] = pd.DataFrame(
            [{**b, "speed_rpm": s.top_speed_rpm, "revolutions": whirl["revolutions"],
              "limit_cycle_revolutions": whirl.get("limit_cycle_revolutions", math.nan),
              "contact": whirl["contact"], "success": whirl["success"],
              "message": whirl["message"], "grid": whirl["grid"], **second}
             for b in whirl["bearings"]])
    if chosen is not None:
        tables["chosen.csv"] = pd.DataFrame([chosen])
    if len(default):
        tables["default_grid_check.csv"] = default
    if len(robust):
        tables["robustness.csv"] = robust
    title = study.spec["title"]
    figures = {"design_front.png": plot_design_front(
        table, front, chosen, s.top_speed_rpm, s.search_high_rpm, robust,
        title=f"{title}: every design evaluated ({s.grid} grid)",
        limits=", ".join(r.words.removesuffix(" limit") for r in limits)).figure}
    bounds = {v.name: ((v.low, v.high) if v.values is None else (min(v.values), max(v.values)))
              for v in problem.variables}
    axes = plot_onset_against_variables(
        table, problem.names, s.top_speed_rpm, chosen=chosen, bounds=bounds,
        title=(f"First onset against each design variable ({s.grid} search grid, top speed "
               f"{s.top_speed_rpm:,.0f} rpm)"))
    figures["onset_vs_variables.png"] = np.atleast_1d(axes).ravel()[0].figure
    asked = search.evaluated + search.reused
    rows = store.rows_written()
    checks = [{"what": "every design asked is stored exactly once (rows in the store)",
               "value": float(rows), "limit": float(asked),
               "passed": bool(rows == asked and stored["point"].is_unique
                              and set(stored["point"]) == set(table["point"]))}]
    step = stages.stage("reproduction")
    if chosen is not None:
        diff = _reproduce(plan, chosen)
        checks.append({"what": "chosen design evaluated again from scratch: largest "
                       "relative change of its objectives", "value": diff,
                       "limit": REPRODUCE_TOLERANCE, "passed": bool(diff <= REPRODUCE_TOLERANCE)})
        step(1.0)
    stages.finish()
    options = {"variants": {"design": {"goal": plan.goal, "loss_factor_search":
                                       plan.loss_factor_band[0],
                                       "loss_factor_band": list(plan.loss_factor_band)}},
               "grid": str(plan.default_settings.grid), "search_grid": str(s.grid),
               "method": plan.search.method, "budget": plan.search.budget,
               "seed": plan.search.seed, "top_speed_rpm": s.top_speed_rpm,
               "conventions": design_conventions(
                   plan.system, {n: float(chosen[n]) for n in problem.names}
                   if chosen is not None else {}, s)}
    return StudyResult(study, tables=tables, figures=figures, checks=checks, options=options,
                       notes=notes, wall_time_s=time.perf_counter() - started,
                       verdict=text, answer=found)


def answer(chosen, why: str, table: pd.DataFrame, plan, check=None, whirl=None,
           limits=None, levers=None, margin=None) -> dict:
    """The study's answer as ``summary.json`` keys, the verdict among them — the one place
    they are made (:func:`verdict` words it): ``verdict``;
    ``stable_to_top_speed`` (the chosen design's first onset ≥ the top speed);
    ``best_first_onset_rpm`` (the best feasible first onset, None: none feasible);
    ``answer_grid``; ``chosen_design`` (its variables and main outputs, None: none);
    ``limits`` (one :class:`gfbopt.design.decision.LimitReport` per limit) and
    ``active_limits`` (the names of the chosen design's active limits); ``what_it_would_take``
    (one :class:`gfbopt.design.what_it_takes.LeverAnswer` per lever; None when not searched)
    and ``margin`` (:func:`margin_of`; None unless the chosen design is stable)."""
    ok = feasible_rows(table, plan.problem)
    top = plan.settings.top_speed_rpm
    design = None
    if chosen is not None:
        keep = [*plan.problem.names, "first_onset_speed_rpm", "first_mode",
                "total_power_loss_w", "min_film_lowest_speed_um", "point"]
        design = {k: chosen[k] for k in keep if k in chosen}
    return {"verdict": verdict(chosen, why, plan, check, whirl),
            "stable_to_top_speed": bool(chosen is not None
                                        and chosen["first_onset_speed_rpm"] >= top),
            "best_first_onset_rpm": float(ok["first_onset_speed_rpm"].max()) if len(ok)
            else None,
            "answer_grid": str(plan.settings.grid), "chosen_design": design,
            "limits": [r.to_dict() for r in limits or []],
            "active_limits": [r.name for r in limits or [] if r.active],
            "what_it_would_take": None if levers is None else
            answers_records(levers),
            "margin": margin}


def robustness_text(c, r, band) -> str:
    """The tolerance check of the chosen design in words, each figure with what it is
    over (:func:`gfbopt.design.robustness.robustness`)."""
    tolerances = ", ".join(f"±{v:g} {variable_label(k).split('[')[-1].rstrip(']')} on {k}"
                           for k, v in r.tolerances.items()) or "no tolerances"
    text = (f"Robustness of the chosen design: first onset "
            f"{c['band_low_onset_speed_rpm']:,.0f} rpm at loss factor η = {band[0]:g}")
    if band[1] != band[0]:
        text += f" and {c['band_high_onset_speed_rpm']:,.0f} rpm at η = {band[1]:g}"
    text += (f"; at the band's worst end (η = {c['worst_loss_factor']:g}), over the design "
             f"and {int(c['samples']) - 1} samples of its tolerances ({tolerances}): "
             f"5th percentile {c['p05_onset_speed_rpm']:,.0f} rpm, worst "
             f"{c['worst_onset_speed_rpm']:,.0f} rpm; {c['stable_to_top_fraction']:.0%} "
             "of them stable to the top speed.")
    return text

