"""Study kinds built on whole transients (orbits) rather than thresholds.

* ``orbits`` — journal-centre orbits at published rotor masses and at the same fractions of
  our linear threshold, verdicts against the published ones (thesis Figs 3.9–3.11, 4.6–4.8);
* ``bifurcation`` — limit-cycle amplitude against rotor mass above the threshold, reached
  from inside and from outside the cycle.
"""
from __future__ import annotations

import math

import numpy as np

from .. import analyses
from ..linear import linear_threshold, linearise
from ..static import SolverCache
from . import checks
from .published import curve_model, load_published
from .base import (
    RunContext,
    Study,
    StudyResult,
    build_model,
    frame,
    options_of,
    variant_titles,
)


def plan_orbits(study: Study) -> list:
    """One case per published critical mass that has example orbits (masses, verdicts)."""
    spec = study.spec
    data = load_published(study)
    out = []
    for p in data["critical_masses"]:
        if not p["masses"]:
            continue
        model = curve_model(data, p["curve"], spec["model"],
                            {"bearing_number": p["bearing_number"]}, study.where("published"))
        out.append({"label": p["label"], "eccentricity": p["eccentricity"], "model": model,
                    "masses": p["masses"], "published": {data["reference"]: {
                        "critical_mass": p["critical_mass"], "verdicts": p["verdicts"]}}})
    if not out:
        raise study.where("published").error(spec["published"], "has no critical_masses "
                                             "with masses and verdicts (no orbits to run)")
    return out


def _consistent(published: str, ours: str) -> bool:
    """Our verdict does not contradict the published one ('critical' is not judged: at the
    threshold either verdict is right to the fit's precision)."""
    return (published == "critical" or published == ours
            or (published == "unstable" and ours in ("contact", "limit cycle")))


def run_orbits(study: Study, cases: list, ctx: RunContext) -> StudyResult:
    from ..plotting import plot_orbits
    from ..transient import integrate_orbits, transient_model

    spec = study.spec
    cache = SolverCache()
    records, tables, figures, compared = [], {}, {}, []
    titles = variant_titles({c["label"]: c["model"] for c in cases})
    for case in cases:
        model = case["model"]
        sol = analyses.equilibrium(model, eccentricity=case["eccentricity"], grid=study.grid,
                                   cache=cache)
        ours = linear_threshold(linearise(sol, cache(model, study.grid))).critical_mass
        for ref, published in case["published"].items():
            scale = ours / published["critical_mass"]
            runs = [("thesis", m, m) for m in case["masses"]]
            runs += [("scaled", m * scale, m) for m in case["masses"]]
            orbit = integrate_orbits(transient_model(sol), [m for _, m, _ in runs],
                                     spec["revolutions"], kick=spec["kick"],
                                     method=spec["method"])
            drawn: dict = {"thesis": {}, "scaled": {}}
            contradictions = 0
            n = len(case["masses"])
            for k, (which, mass, mass_ref) in enumerate(runs):
                table = orbit.to_frame(k)
                tables[f"orbit_{case['label']}_{which}_{k % n}.csv"] = table
                drawn[which][f"M̄ = {mass:.3g}: {orbit.verdict[k]}"] = table
                verdict_ref = published["verdicts"][k % n]
                if which == "scaled" and not _consistent(verdict_ref, orbit.verdict[k]):
                    contradictions += 1
                records.append({
                    "label": case["label"], "masses": which, "mass": mass,
                    "mass_thesis": mass_ref, f"verdict_{ref}": verdict_ref,
                    "verdict": orbit.verdict[k], "growth_rate": orbit.growth_rate[k],
                    "whirl_ratio": orbit.whirl_ratio[k], "final_amplitude": orbit.amplitude[k],
                    "min_film": float(np.nanmin(orbit.min_film[k])),
                    "contact_tau": orbit.contact_tau[k], "linear_critical_mass": ours,
                    f"critical_mass_{ref}": published["critical_mass"],
                    "success": orbit.success, "message": orbit.message})
            compared.append(checks.comparison(
                f"{titles[case['label']]}: orbits at the published masses rescaled to our "
                "threshold whose verdict contradicts the published one (count; the "
                "'critical' orbit is not judged)", ref, contradictions, 0))
            for which, words in (("thesis", "the thesis's rotor masses"),
                                 ("scaled", "the same fractions of our linear threshold")):
                ax = plot_orbits(drawn[which], title=(
                    f"Orbits, {titles[case['label']]}, ε0 = {case['eccentricity']:g}, "
                    f"Λ = {model.bearing_number:g}: {words}"))
                figures[f"orbits_{case['label']}_{which}.png"] = ax.figure
    table = frame(records)
    return StudyResult(
        study, tables={"verdicts.csv": table, **tables}, figures=figures,
        checks=[checks.all_converged(table, "all orbits integrated")], comparisons=compared,
        options=options_of({c["label"]: [c["model"]] for c in cases}, study.grid,
                           method=spec["method"], kick=spec["kick"],
                           revolutions=spec["revolutions"]))


# -------------------------------------------------------------------- bifurcation
def plan_bifurcation(study: Study):
    opts = {k: v for k, v in study.spec["model"].items() if k != "eccentricity"}
    if "eccentricity" in study.spec["model"]:
        raise study.where("model", "eccentricity").error(
            study.spec["model"]["eccentricity"], "belongs at the top level of the file")
    return build_model(opts, study.where("model"))


def run_bifurcation(study: Study, model, ctx: RunContext) -> StudyResult:
    from ..plotting import plot_bifurcation
    from ..transient import limit_cycle_amplitudes, transient_model

    spec = study.spec
    cache = SolverCache()
    sol = analyses.equilibrium(model, eccentricity=spec["eccentricity"], grid=study.grid,
                               cache=cache)
    mc = linear_threshold(linearise(sol, cache(model, study.grid))).critical_mass
    ratios = np.asarray(spec["mass_ratios"], dtype=float)
    table = limit_cycle_amplitudes(transient_model(sol), ratios * mc, spec["revolutions"],
                                   tuple(spec["kicks"]))
    table.insert(0, "mass_ratio", ratios)
    table["linear_critical_mass"] = mc
    both = table[(table["verdict_from_inside"] == "limit cycle")
                 & (table["verdict_from_outside"] == "limit cycle")]
    found = []
    if len(both):
        gap = float(((both["amplitude_from_inside"] - both["amplitude_from_outside"]).abs()
                     / both["amplitude_from_outside"]).max())
        found.append(checks.check("limit cycles reached from inside and outside agree "
                                  "(largest relative difference)", gap,
                                  spec["cycle_tolerance"]))
    touched = ((table["verdict_from_inside"] == "contact")
               & (table["verdict_from_outside"] == "contact"))
    found.append(checks.check("masses with neither an established cycle nor contact from "
                              "both sides (count)", float(len(table) - len(both)
                                                          - touched.sum()),
                              float(spec["allowed_without_cycle"])))
    if not math.isfinite(mc):
        found.append(checks.check("linear threshold found", math.nan, 0))
    ax = plot_bifurcation(table, title=spec["title"])
    return StudyResult(study, tables={"bifurcation.csv": table},
                       figures={"bifurcation.png": ax.figure}, checks=found,
                       options=options_of({"model": [model]}, study.grid,
                                          kicks=spec["kicks"], revolutions=spec["revolutions"],
                                          method="rk4"))
