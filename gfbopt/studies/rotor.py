"""The rotor study kind: a rigid rotor on two foil bearings.

* ``rotor_two_bearings`` — for a rotor file (``problems/rotors/*.toml``): the onset speed of
  every mode (matched whirl, :func:`gfbopt.rotor.system.rotor_onsets`), which whirls first, the
  Campbell diagram (full-system eigenvalues), the imbalance response, the same rotor without
  gyroscopic coupling (I_p = 0: how much I_p ω raises the forward conical onset) and the
  per-bearing half-mass approximation beside it (each bearing alone with its share of mass
  and load, :func:`gfbopt.rotor.onset_speed`), so that users see how far the rule of thumb is
  from the two-bearing answer.

Checks: the Campbell diagram (eigenvalues of the full system) and the matched-whirl onsets
must agree where they should — below the first onset every mode of the diagram has a positive
log decrement, above it at least one is negative — and each onset's mode is the diagram's
track (named by it) that loses its damping next to it.
"""
from __future__ import annotations

import math
import time

import numpy as np
import pandas as pd

from ..errors import ParameterError
from .base import Kind, RunContext, Study, StudyResult
from .spec import GRID, opt, req

SCHEMAS: dict[str, dict] = {
    "rotor_two_bearings": {**GRID,
        "rotor": req("string", "rotor file (SI), relative to the study file"),
        "speed_range_rpm": req("numbers", "[low, high] speeds searched and scanned [rpm]",
                               length=2),
        "top_speed_rpm": req("number", "the rotor's top running speed [rpm], marked on the "
                             "figures", positive=True),
        "campbell_speeds": opt("integer", 20, "speeds of the Campbell diagram", minimum=2),
        "imbalance_speeds": opt("integer", 40, "speeds of the imbalance response",
                                minimum=2)},
}


def plan_rotor(study: Study) -> dict:
    from ..inputs.rotor_system import load_rotor

    path = study.directory / study.spec["rotor"]
    try:
        system = load_rotor(path, running=True)    # [journal]/[thermal]: running clearance
    except ParameterError as exc:
        raise study.where("rotor").error(str(study.spec["rotor"]),
                                         f"{exc.name}: {exc.rule}") from None
    low, high = study.spec["speed_range_rpm"]
    if not 0 < low < high:
        raise study.where("speed_range_rpm").error([low, high], "must be [low, high] with "
                                                   "0 < low < high [rpm]")
    from ..rotor.analyse import check_speed_span

    try:
        check_speed_span((low, high), system)
    except ParameterError as exc:
        raise study.where("speed_range_rpm").error([low, high], exc.rule) from None
    if not system.imbalance:
        raise study.where("rotor").error(str(study.spec["rotor"]), "has no [[imbalance]] "
                                         "plane: the study shows the imbalance response")
    return {"system": system, "speed_range": (float(low), float(high))}


def run_rotor(study: Study, plan: dict, ctx: RunContext) -> StudyResult:
    from ..plotting.rotor import plot_campbell, plot_imbalance_response, plot_onsets
    from ..rotor.analyse import analyse_rotor
    from ..rotor.system import rotor_onsets, without_gyroscopics

    spec, system = study.spec, plan["system"]
    t0 = time.perf_counter()
    result = analyse_rotor(system, plan["speed_range"], campbell=True, imbalance=True,
                           half_mass=True, grid=study.grid,
                           campbell_speeds=spec["campbell_speeds"],
                           imbalance_speeds=spec["imbalance_speeds"])
    plain = rotor_onsets(without_gyroscopics(system), plan["speed_range"], grid=study.grid)
    out = result.to_dict()
    tables = {f"{k}.csv": v for k, v in result.tables().items()}
    rows = [{"label": m.label, "onset_speed_rpm": m.onset_speed_rpm,
             "whirl_frequency_hz": m.whirl_frequency_hz, "onset_status": m.status}
            for m in plain.modes]
    tables["modes_without_gyroscopics.csv"] = pd.DataFrame(rows)
    top = spec["top_speed_rpm"]
    onsets = {m.label: m.onset_speed_rpm for m in result.onsets.modes}
    name = system.body.name
    figs = {}
    ax, _ = plot_campbell(result.campbell.table, onsets, top,
                          title=f"Campbell diagram: {name} (grid {study.grid})")
    figs["campbell.png"] = ax.figure
    ax, _ = plot_imbalance_response(result.imbalance.table, result.imbalance.peaks, onsets, top,
                                    title=f"Imbalance response: {name}",
                                    unstable_from_rpm=result.imbalance.unstable_from_rpm)
    figs["imbalance_response.png"] = ax.figure
    ax = plot_onsets([m.to_dict() for m in result.onsets.modes], result.half_mass, top,
                     title=f"Onset of each mode against the half-mass rule: {name}")
    figs["onsets.png"] = ax.figure
    checks = [_campbell_check(result), _tracking_check(result)]
    notes = _notes(result, plain, out, top)
    notes.append(f"computed in {time.perf_counter() - t0:.1f} s, grid {study.grid}")
    options = {"grid": str(study.grid), "rotor_file": spec["rotor"],
               "speed_range_rpm": list(plan["speed_range"]),
               "conventions": result.onsets.conventions}
    return StudyResult(study, tables=tables, figures=figs, checks=checks, options=options,
                       notes=notes)


def _campbell_check(result) -> dict:
    """Campbell below/above the first onset against the matched-whirl onset (a count of
    speeds where they disagree, 0 expected); a rotor unstable at the lowest speed is unstable
    from there."""
    from ..rotor.analyse import unstable_from
    from . import checks

    table = result.campbell.table
    onset = unstable_from(result.onsets, result.onsets.speed_range_rpm[0])
    worst = table.groupby("speed_rpm")["log_decrement"].min()
    if math.isfinite(onset):
        # speeds within 1 % of the onset are left out (the onset's tolerance and the grid)
        wrong = sum(1 for s, d in worst.items() if abs(s / onset - 1) > 0.01
                    and (d < 0) != (s > onset))
    else:
        wrong = int((worst < 0).sum())
    return checks.check("Campbell diagram (full system) agrees with the matched-whirl onset: "
                        "speeds where the least log decrement has the wrong sign", wrong, 0)


def _tracking_check(result) -> dict:
    """Each matched-whirl onset inside the diagram has one Campbell track named by its mode
    whose log decrement falls through zero in the diagram interval holding the onset (a count
    of onsets without one, 0 expected)."""
    from . import checks

    table = result.campbell.table
    speeds = np.sort(table["speed_rpm"].unique())
    missing = 0
    for m in result.onsets.modes:
        s = m.onset_speed_rpm
        if not (math.isfinite(s) and speeds[0] < s < speeds[-1]):
            continue
        k = int(np.searchsorted(speeds, s))
        lo, hi = speeds[k - 1], speeds[k]
        named = table[(table["track_label"] == m.label) & (table["track_zero_rpm"] >= lo)
                      & (table["track_zero_rpm"] <= hi)]
        missing += int(named["mode"].nunique() != 1)
    return checks.check("Campbell tracks named by the onset's mode, losing damping in the "
                        "diagram interval of each matched-whirl onset: onsets without one",
                        missing, 0)


def _notes(result, plain, out: dict, top: float) -> list:
    from ..rotor.analyse import imbalance_note

    notes = []
    r = result.onsets
    loads = ", ".join(f"{l.name} {l.magnitude:.3g} N" for l in r.bearing_loads)
    notes.append(f"Bearing loads from the statics: {loads}.")
    notes += [f"{n[0].upper()}{n[1:]}." for n in out["bearing_notes"]]
    notes += [f"Warning: {w}." for w in out["warnings"]]
    if math.isfinite(r.onset_speed_rpm):
        notes.append(f"First to whirl: {r.first_mode} from {r.onset_speed_rpm:,.0f} rpm at "
                     f"{r.onset_whirl_frequency_hz:.4g} Hz; the top speed {top:,.0f} rpm is "
                     f"{top / r.onset_speed_rpm:.2f}× the onset.")
    else:
        notes.append(f"No onset in the range: {r.onset_reason}.")
    for m in r.modes:
        other = plain.mode(m.label)
        if other is not None and math.isfinite(m.onset_speed_rpm) and math.isfinite(
                other.onset_speed_rpm):
            notes.append(f"{m.label}: onset {m.onset_speed_rpm:,.0f} rpm with gyroscopic "
                         f"coupling, {other.onset_speed_rpm:,.0f} rpm without (I_p = 0): "
                         f"{m.onset_speed_rpm / other.onset_speed_rpm - 1:+.1%}.")
    h = out["half_mass_approximation"]
    notes.append("Per-bearing (half-mass) approximation: " + "; ".join(
        f"bearing {b['bearing']} alone ({b['mass_share_kg']:.3g} kg, {b['load_newton']:.3g} N)"
        f": {b['onset_speed_rpm']:,.0f} rpm" for b in h["bearings"]) +
        f"; its first onset is {h['error_of_approximation']:+.1%} against the two-bearing "
        "answer, and it cannot say which mode whirls (it has no conical mode).")
    for station, p in result.imbalance.peaks.items():
        notes.append(f"Imbalance response at {station}: peak {p['peak_amplitude_um']:.3g} µm at "
                     f"{p['peak_speed_rpm']:,.0f} rpm" + (
                         ", where the rotor is unstable: not physical" if p["above_first_onset"]
                         else "") + (
                         f" (largest below the onset {p['largest_below_onset_um']:.3g} µm at "
                         f"{p['largest_below_onset_rpm']:,.0f} rpm)"
                         if p["above_first_onset"] and math.isfinite(
                             p["largest_below_onset_um"]) else "") + ".")
    notes.append(f"The imbalance response: {imbalance_note(result.imbalance.unstable_from_rpm)}.")
    least = result.campbell.least_stable()
    notes.append(f"Campbell diagram: least log decrement {least['log_decrement']:.3g} "
                 f"({least['track_label']}, {least['speed_rpm']:,.0f} rpm); "
                 f"{int(np.isfinite(result.campbell.table['log_decrement']).sum())} eigenvalues.")
    for d in result.campbell.dropped:      # a root that continues no track: stated, not drawn
        notes.append(f"Campbell diagram: a root of {d['whirl_frequency_hz']:,.1f} Hz "
                     f"({d['shape_label']}, log decrement {d['log_decrement']:.3g}) at "
                     f"{d['speed_rpm']:,.0f} rpm is left out of the diagram: {d['reason']}.")
    return notes


KINDS = {"rotor_two_bearings": Kind(plan_rotor, run_rotor)}
