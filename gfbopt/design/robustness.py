"""What a chosen bearing-pair design is worth: its onset under manufacturing tolerances and
over the loss-factor band, and its answer on the default grid (grid honesty).

* :func:`tolerance_sample` — a seeded Latin hypercube (:mod:`gfbopt.doe.sampling`) of the
  ± tolerances of the design variables around one design; :func:`robustness` evaluates the
  design at both ends of the uncertain loss-factor band, takes the end where its onset is
  lower (the band's worst end) and evaluates the tolerance samples there: the worst case and
  the 5th percentile are over the design and its samples at that loss factor, beside the
  onset at each end of the band.
* :func:`regrid` — the same designs evaluated on another grid (the default grid after a
  search on a coarse one), with the differences of the objectives.

Every evaluation here refines its first onset from a known one (:func:`near`): the design's
stored onset (on the default grid, at the other end of the band) or its nominal's at that loss
factor (the samples), by secant steps on the evaluation's own grid and loss factor
(:func:`gfbopt.design.rotor_objectives.first_onset`, to 1e-5 on ln N, where the search's Brent
refinement stops at 1e-3: the figures move by that refinement's error, ≤ 4e-4 on the blower):
3 speeds instead of 11, the scan from the lowest speed when it does not converge.  The
tolerance samples and the band's other end are evaluated for their onset only
(``onset_only``: no film, no power).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Callable, Optional

import numpy as np
import pandas as pd

from ..doe.sampling import SamplePlan, Variable, sample
from ..transient.rotor_friction import MODEL_WORDS
from .optimiser import evaluate_points
from .problem import DesignProblem
from .rotor_objectives import evaluate_rotor_design

#: outputs compared between the search grid and the default grid
COMPARED = ("first_onset_speed_rpm", "total_power_loss_w", "min_film_lowest_speed_um")


def tolerance_sample(design: dict, tolerances: dict, n: int, seed: int) -> list:
    """``n`` perturbed designs (dicts): each toleranced variable uniform in value ±
    half-width (a preload depth kept ≥ 0), a seeded Latin hypercube; the design itself when
    nothing is toleranced."""
    if not tolerances:
        return []
    variables = [Variable(name, -half, half) for name, half in tolerances.items()]
    frame = sample(SamplePlan(tuple(variables), method="lhs", n=n, seed=seed))
    out = []
    for _, row in frame.iterrows():
        d = dict(design)
        for name in tolerances:
            value = design[name] + float(row[name])
            if name.endswith("preload_depth_um"):
                value = max(value, 0.0)
            d[name] = value
        out.append(d)
    return out


def near(row: dict) -> dict:
    """The keywords of an evaluation after the search that starts its onset scan at
    ``row``'s first onset (:func:`gfbopt.design.rotor_objectives.first_onset`): empty when
    ``row`` has no onset inside the range (the scan from the lowest speed)."""
    ok = row.get("success") and row.get("onset_status") == "onset"
    return {"near_onset_rpm": float(row["first_onset_speed_rpm"])} if ok else {}


def _onset(row: dict) -> float:
    return float(row.get("first_onset_speed_rpm", math.nan)) if row.get("success") \
        else math.nan


def robustness(system, settings, designs: list, tolerances: dict, band: tuple, n: int,
               seed: int, problem: DesignProblem, run_tasks: Optional[Callable] = None,
               progress: Optional[Callable[[float], None]] = None) -> pd.DataFrame:
    """For each design (a stored row, evaluated with ``settings``' loss factor): its first
    onset at both ends of the loss-factor ``band``, the end where it is lower (the band's
    worst end), and over the design and ``n`` tolerance samples evaluated at that end the
    worst case, the 5th percentile and the fraction stable to the top speed — every figure
    of the tolerance check is at one loss factor, so the worst case is never above the
    nominal there.  ``progress``: the fraction of the evaluations finished."""
    names = problem.names
    nominal = [{n_: float(row[n_]) for n_ in names} for row in designs]
    samples = [tolerance_sample(d, tolerances, n, seed + k) for k, d in enumerate(nominal)]
    others = [eta for eta in dict.fromkeys(band) if eta != settings.loss_factor]
    total = len(others) * len(designs) + sum(len(x) for x in samples)
    finished = [0]

    def evaluate(points: list) -> list:
        def step(fraction: float) -> None:
            if progress is not None:
                progress((finished[0] + fraction * len(points)) / total)
        rows = evaluate_points(evaluate_rotor_design, points, run_tasks, step)
        finished[0] += len(points)
        return rows

    # the design at each end of the band: the stored row at the search's loss factor
    at = [{settings.loss_factor: dict(r)} for r in designs]
    for eta in others:
        rows = evaluate([{"system": system, "settings": dataclasses.replace(
            settings, loss_factor=eta), "onset_only": True, **near(r), **d}
            for r, d in zip(designs, nominal)])
        for k, row in enumerate(rows):
            at[k][eta] = row
    worst = [min((eta for eta in band), key=lambda eta, a=a: _order(a[eta])) for a in at]
    points, owner = [], []
    for k, eta in enumerate(worst):
        for d in samples[k]:
            points.append({"system": system, "onset_only": True, **near(at[k][eta]),
                           "settings": dataclasses.replace(settings, loss_factor=eta), **d})
            owner.append(k)
    rows = evaluate(points) if points else []
    out = []
    for k, row in enumerate(designs):
        eta = worst[k]
        onset = np.array([_onset(at[k][eta])] + [_onset(r) for r, o in zip(rows, owner)
                                                  if o == k], float)
        ok = onset[np.isfinite(onset)]
        out.append({"point": row["point"], **{n_: row[n_] for n_ in names},
                    "nominal_onset_speed_rpm": row["first_onset_speed_rpm"],
                    "loss_factor_low": band[0], "loss_factor_high": band[1],
                    "band_low_onset_speed_rpm": _onset(at[k][band[0]]),
                    "band_high_onset_speed_rpm": _onset(at[k][band[1]]),
                    "worst_loss_factor": eta,
                    "worst_onset_speed_rpm": float(ok.min()) if ok.size else math.nan,
                    "p05_onset_speed_rpm": float(np.percentile(ok, 5)) if ok.size else math.nan,
                    "stable_to_top_fraction": float(np.mean(ok >= settings.top_speed_rpm))
                    if ok.size else math.nan,
                    "samples": len(onset), "failed_samples": int(len(onset) - ok.size)})
    return pd.DataFrame.from_records(out)


def _order(row: dict) -> float:
    """Sort key of a band end: its onset, a failed evaluation first (the worst)."""
    onset = _onset(row)
    return onset if math.isfinite(onset) else -math.inf


def regrid(system, settings, designs: list, problem: DesignProblem,
           run_tasks: Optional[Callable] = None,
           progress: Optional[Callable[[float], None]] = None) -> pd.DataFrame:
    """The designs evaluated with ``settings`` (another grid): the objectives on both grids
    and their relative differences (new/stored − 1)."""
    names = problem.names
    points = [{"system": system, "settings": settings, **near(r),
               **{n: float(r[n]) for n in names}} for r in designs]
    rows = evaluate_points(evaluate_rotor_design, points, run_tasks, progress)
    out = []
    for stored, new in zip(designs, rows):
        line = {"point": stored["point"], **{n: stored[n] for n in names},
                "success": bool(new.get("success", False)),
                "message": new.get("message", "")}
        for name in COMPARED:
            a, b = float(stored[name]), float(new.get(name, math.nan))
            line[f"{name}_search_grid"] = a
            line[f"{name}_default_grid"] = b
            line[f"{name}_relative_change"] = b / a - 1.0 if a else math.nan
        line["first_mode_default_grid"] = new.get("first_mode", "")
        line["onset_status_default_grid"] = new.get("onset_status", "")
        line["feasible_default_grid"] = bool(new.get("success")) and problem.feasible(new)
        out.append(line)
    return pd.DataFrame.from_records(out)


def whirl_at_top_speed(system, design: dict, settings, revolutions: float,
                       progress: Optional[Callable[[float], None]] = None) -> dict:
    """The rotor with ``design`` run at the top speed for ``revolutions`` from its
    equilibrium with a small cylindrical kick (:func:`gfbopt.transient.rotor_orbit`, the
    rotor transient, on the search grid, the loss factor of the search): per
    bearing the subsynchronous limit cycle [µm] (settled or not) and the smallest film
    [µm], and whether the film closed (contact) first; ``progress``: called with the fraction
    of the revolutions integrated.

    Bearings whose files state the bumps' Coulomb friction run the same transient, their
    sliders integrated with the rotor (:mod:`gfbopt.transient.rotor_friction`): the keys
    above plus ``model`` (:data:`FRICTION_MODEL`, the model the verdict uses), per bearing
    how the orbit ended (``friction_orbit_kind`` 'settled limit cycle' / 'contact' / 'end of
    run', ``friction_orbit_amplitude_um``, ``friction_orbit_whirl_frequency_hz``,
    ``friction_orbit_verdict``), and beside it the describing function's prediction, a second
    statement (:func:`describing_function_whirl`)."""
    from ..inputs.options import ModelOptions, merge_options
    from ..transient.rotor_analysis import rotor_orbit
    from .rotor_objectives import apply_design

    designed, _ = apply_design(system, design, settings)
    supports = tuple(dataclasses.replace(b, options=merge_options(
        ModelOptions(loss_factor=settings.loss_factor), b.options))
        for b in designed.bearings)
    designed = dataclasses.replace(designed, bearings=supports)
    rubbing = any((b.options.friction_coefficient or 0.0) > 0 for b in designed.bearings)
    running = None
    if any(b.running_tables for b in designed.bearings):     # the clearance at speed
        from ..rotor.supports import frozen_at_running_condition

        designed, running = frozen_at_running_condition(designed, settings.top_speed_rpm,
                                                        settings.grid)
        if running.get("failure"):
            return {"revolutions": 0.0, "limit_cycle_revolutions": revolutions,
                    "grid": str(settings.grid), "success": False,
                    "message": running["failure"], "contact": False, "contact_bearing": None,
                    "contact_time_s": math.nan, "bearings": [], "running": running}
    from ..progress import Fraction

    reporter = (Fraction(max(1, math.ceil(revolutions)), progress) if progress is not None
                else None)
    result = rotor_orbit(designed, settings.top_speed_rpm, revolutions, grid=settings.grid,
                         progress=reporter)
    d = result.to_dict()
    out = {"revolutions": float(d.get("revolutions_integrated") or 0.0),
           "limit_cycle_revolutions": revolutions, "grid": str(settings.grid),
           "success": bool(d["success"]),
           "message": d.get("message", ""), "contact": bool(d.get("contact")),
           "contact_bearing": d.get("contact_bearing"),
           "contact_time_s": d.get("contact_time_s", math.nan), "bearings": []}
    if running is not None:
        out["running"] = running
    for b in d["bearings"]:
        entry = {"bearing": b["bearing"], "min_film_um": _number(b.get("min_film_um")),
                 "limit_cycle_status": b.get("limit_cycle_status") or "none",
                 "limit_cycle_amplitude_um": _number(b.get("limit_cycle_amplitude_um")),
                 "limit_cycle_settled": bool(b.get("limit_cycle_settled")),
                 "limit_cycle_frequency_hz": _number(b.get("limit_cycle_frequency_hz"))}
        if rubbing:                              # how the orbit ended (the sliders')
            entry.update({
                "friction_orbit_kind": b.get("friction_orbit_kind", ""),
                "friction_orbit_amplitude_um": _number(b.get("friction_orbit_amplitude_um")),
                "friction_orbit_whirl_frequency_hz":
                    _number(b.get("friction_orbit_whirl_frequency_hz")),
                "friction_orbit_verdict": b.get("friction_orbit_verdict", "")})
        out["bearings"].append(entry)
    if rubbing:
        out["model"] = FRICTION_MODEL
        out.update(describing_function_whirl(designed, settings, out["bearings"]))
    return out


#: the model of the top-speed whirl of a rotor whose bumps rub (the verdict's)
FRICTION_MODEL = f"rotor transient with sliders ({MODEL_WORDS})"


def _number(value) -> float:                     # null in the orbit's JSON: not measured
    return math.nan if value is None else float(value)


def describing_function_whirl(designed, settings, bearings: list) -> dict:
    """The describing function's settled orbit of the rotor at the top speed
    (:func:`gfbopt.rotor.friction_onset.settled_whirl`, the search grid), the second
    statement beside the transient's: ``describing_function_model``,
    ``describing_function_verdict`` ('bounded whirl of …' or 'no bounded orbit inside the
    film', or why there is no answer), ``describing_function_bounded``; and in each entry of
    ``bearings`` (updated in place) its ``settled_orbit_um``, ``settled_whirl_hz`` and
    ``settled_min_film_um`` (glossary: gfbopt/terms/rotor_friction.py)."""
    from ..errors import ParameterError
    from ..rotor.friction_onset import MODEL, settled_whirl
    from ..rotor.supports import resolve_rotor

    out = {"describing_function_model": MODEL}
    try:
        orbit = settled_whirl(resolve_rotor(designed, settings.grid), settings.top_speed_rpm)
    except ParameterError as exc:
        for b in bearings:
            b.update(settled_orbit_um=math.nan, settled_whirl_hz=math.nan,
                     settled_min_film_um=math.nan)
        return {**out, "describing_function_verdict": f"no describing-function answer: {exc}",
                "describing_function_bounded": False}
    amplitude = dict(zip(orbit.bearings, orbit.amplitude_um))
    for b in bearings:                   # no settled orbit: nothing settled to state
        b.update(settled_orbit_um=float(amplitude.get(b["bearing"], math.nan))
                 if orbit.bounded else math.nan,
                 settled_whirl_hz=float(orbit.whirl_frequency_hz)
                 if orbit.bounded else math.nan,
                 settled_min_film_um=float(orbit.min_film_um) if orbit.bounded else math.nan)
    return {**out, "describing_function_verdict": orbit.verdict,
            "describing_function_bounded": bool(orbit.bounded)}
