"""The decision of a bearing-pair design study (:mod:`.rotor_design`) beyond its verdict
(one function, :func:`gfbopt.studies.rotor_report.answer`, makes the verdict and every
``summary.json`` key of the answer from these parts, so the console's last line, the
README's first line and ``summary.json`` say the same thing): which limit binds
(:mod:`gfbopt.design.decision`), what it would take (:mod:`gfbopt.design.what_it_takes`) or,
for a design stable to the top speed, its margin.
"""
from __future__ import annotations

import hashlib
import json
import math
import time

import pandas as pd


#: the what-it-would-take evaluations' store, beside the search's in the result folder
LEVER_STORE = "what_it_takes_store"

#: LeverAnswer fields → columns of what_it_would_take.csv
ANSWER_COLUMNS = {"lever": "lever", "unit": "lever_unit", "words": "lever_words",
                  "start": "lever_start", "low": "lever_low", "high": "lever_high",
                  "found": "threshold_found", "value": "threshold_value",
                  "change": "threshold_change", "onset_rpm": "threshold_onset_speed_rpm",
                  "meets_limits": "threshold_meets_limits",
                  "min_film_lowest_speed_um": "min_film_lowest_speed_um",
                  "limit_value": "at_bound_value",
                  "limit_onset_rpm": "at_bound_onset_speed_rpm",
                  "evaluations": "lever_evaluations", "message": "message"}


def margin_of(chosen: dict, robust: pd.DataFrame, top: float) -> dict:
    """The margin of a design stable to the top speed: its first onset [rpm], the margin
    over the top speed [rpm] and relative, and the worst case under the tolerances at the
    loss-factor band's worst end (:func:`gfbopt.design.robustness.robustness`; NaN when not
    checked) with its relative margin."""
    onset = float(chosen["first_onset_speed_rpm"])
    worst = math.nan
    if len(robust):
        first = robust[robust["point"] == chosen["point"]]
        if len(first):
            worst = float(first.iloc[0]["worst_onset_speed_rpm"])
    return {"first_onset_rpm": onset, "top_speed_rpm": top, "margin_rpm": onset - top,
            "relative_margin": onset / top - 1.0, "worst_onset_under_tolerances_rpm": worst,
            "worst_relative_margin": worst / top - 1.0 if math.isfinite(worst) else math.nan,
            "onset_status": chosen.get("onset_status", "")}


def margin_text(m: dict, search_high: float) -> str:
    """The margin in one sentence."""
    capped = m["onset_status"] == "stable over the range"
    onset = (f"above {search_high:,.0f} rpm (the end of the onset search)" if capped
             else f"{m['first_onset_rpm']:,.0f} rpm")
    text = (f"Margin: the chosen design's first onset is {onset}, "
            f"{'at least ' if capped else ''}{m['relative_margin']:+.1%} over the top speed "
            f"{m['top_speed_rpm']:,.0f} rpm")
    if math.isfinite(m["worst_onset_under_tolerances_rpm"]):
        text += (f"; under the tolerances at the loss-factor band's worst end the worst case "
                 f"is {m['worst_onset_under_tolerances_rpm']:,.0f} rpm "
                 f"({m['worst_relative_margin']:+.1%})")
    else:
        text += "; the tolerances were not checked"
    return text + "."


def lever_store(out, plan, chosen: dict, levers: tuple, resume: bool):
    """The what-it-would-take store in ``out``/:data:`LEVER_STORE`: resumed when it holds
    the same search (study hash), design and levers, else started afresh (an older store is
    kept aside, :class:`gfbopt.doe.ResultStore`)."""
    from ..design.lever_runs import STORE_SCHEMA
    from ..doe.store import ResultStore
    from ..errors import ParameterError

    text = json.dumps({"study": plan.study_hash, "design": chosen["point"],
                       "levers": [repr(v) for v in levers],
                       "top": plan.settings.top_speed_rpm}, sort_keys=True)
    digest = hashlib.sha256(text.encode()).hexdigest()
    where = out / LEVER_STORE
    try:
        return ResultStore.create(where, study=f"{out.name} what it would take",
                                  study_hash=digest, schema=STORE_SCHEMA, resume=resume)
    except ParameterError:
        if not resume:
            raise
        return ResultStore.create(where, study=f"{out.name} what it would take",
                                  study_hash=digest, schema=STORE_SCHEMA, resume=False)


def run_levers(study, plan, chosen: dict, store, run_tasks, resume: bool, step):
    """(answers, evaluations) of the study's levers on the chosen design (empty, None
    when the study names none)."""
    from ..design import rotor_objectives
    from ..design.lever_runs import LeverEvaluations, what_it_would_take
    from ..design.what_it_takes import parse_levers

    levers = parse_levers(study.spec.get("what_it_would_take") or None, study.file,
                          tuple(b.name for b in plan.system.bearings), tuple(plan.problem.names))
    if not levers:
        return [], None
    lstore = lever_store(store.directory.parent, plan, chosen, levers, resume)
    design = {n: float(chosen[n]) for n in plan.problem.names}
    ev = LeverEvaluations(rotor_objectives.evaluate_rotor_design, plan.system, design,
                          plan.settings, plan.problem, lstore, run_tasks)
    t0 = time.perf_counter()
    answers = what_it_would_take(levers, ev, float(chosen["first_onset_speed_rpm"]), step)
    ev.seconds = time.perf_counter() - t0
    return answers, ev


def answers_records(answers: list) -> list:
    """One dict per lever in the columns of ``what_it_would_take.csv`` (summary.json's
    ``what_it_would_take``: one name per quantity in both)."""
    return [{ANSWER_COLUMNS[k]: v for k, v in a.to_dict().items()} for a in answers]


def answers_frame(answers: list) -> pd.DataFrame:
    """``what_it_would_take.csv``: one row per lever."""
    return pd.DataFrame(answers_records(answers), columns=list(ANSWER_COLUMNS.values()))
