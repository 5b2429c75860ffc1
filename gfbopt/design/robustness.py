"""What a chosen bearing-pair design is worth: its onset under manufacturing tolerances and
over the loss-factor band, and its answer on the default grid (grid honesty).

* :func:`tolerance_sample` — a seeded Latin hypercube (:mod:`gfbopt.doe.sampling`) of the
  ± tolerances of the design variables and of the loss factor over its band, around one
  design; :func:`robustness` evaluates the samples (through the executors) and reports the
  nominal first onset next to the worst case and the 5th percentile.
* :func:`regrid` — the same designs evaluated on another grid (the default grid after a
  search on a coarse one), with the differences of the objectives.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Callable, Optional

import numpy as np
import pandas as pd

from ..doe.sampling import SamplePlan, Variable, sample
from .optimiser import evaluate_points
from .problem import DesignProblem
from .rotor_objectives import evaluate_rotor_design

#: outputs compared between the search grid and the default grid
COMPARED = ("first_onset_speed_rpm", "total_power_loss_w", "min_film_lowest_speed_um")


def tolerance_sample(design: dict, tolerances: dict, band: tuple, n: int, seed: int,
                     problem: DesignProblem) -> list:
    """``n`` perturbed designs: each toleranced variable uniform in value ± half-width
    (a preload depth kept ≥ 0), the loss factor uniform in ``band`` (fixed when the band is
    one value); each sample is (design dict, loss factor)."""
    variables = [Variable(name, -half, half) for name, half in tolerances.items()]
    if band[1] > band[0]:
        variables.append(Variable("loss_factor", band[0], band[1]))
    if not variables:
        return [(dict(design), band[0])]
    frame = sample(SamplePlan(tuple(variables), method="lhs", n=n, seed=seed))
    out = []
    for _, row in frame.iterrows():
        d = dict(design)
        for name in tolerances:
            value = design[name] + float(row[name])
            if name.endswith("preload_depth_um"):
                value = max(value, 0.0)
            d[name] = value
        out.append((d, float(row["loss_factor"]) if "loss_factor" in row else band[0]))
    return out


def robustness(system, settings, designs: list, tolerances: dict, band: tuple, n: int,
               seed: int, problem: DesignProblem, run_tasks: Optional[Callable] = None
               ) -> pd.DataFrame:
    """For each design (a stored row): nominal first onset, worst case and 5th percentile
    over the tolerance sample, the fraction of samples stable to the top speed."""
    names = problem.names
    points, owner = [], []
    for k, row in enumerate(designs):
        design = {n_: float(row[n_]) for n_ in names}
        for d, eta in tolerance_sample(design, tolerances, band, n, seed + k, problem):
            points.append({"system": system,
                           "settings": dataclasses.replace(settings, loss_factor=eta), **d})
            owner.append(k)
    rows = evaluate_points(evaluate_rotor_design, points, run_tasks)
    out = []
    for k, row in enumerate(designs):
        mine = [r for r, o in zip(rows, owner) if o == k]
        onset = np.array([r.get("first_onset_speed_rpm", math.nan) if r.get("success")
                          else math.nan for r in mine], float)
        ok = onset[np.isfinite(onset)]
        out.append({"point": row["point"], **{n_: row[n_] for n_ in names},
                    "nominal_onset_speed_rpm": row["first_onset_speed_rpm"],
                    "worst_onset_speed_rpm": float(ok.min()) if ok.size else math.nan,
                    "p05_onset_speed_rpm": float(np.percentile(ok, 5)) if ok.size else math.nan,
                    "stable_to_top_fraction": float(np.mean(ok >= settings.top_speed_rpm))
                    if ok.size else math.nan,
                    "samples": len(mine), "failed_samples": int(len(mine) - ok.size)})
    return pd.DataFrame.from_records(out)


def regrid(system, settings, designs: list, problem: DesignProblem,
           run_tasks: Optional[Callable] = None) -> pd.DataFrame:
    """The designs evaluated with ``settings`` (another grid): the objectives on both grids
    and their relative differences (new/stored − 1)."""
    names = problem.names
    points = [{"system": system, "settings": settings, **{n: float(r[n]) for n in names}}
              for r in designs]
    rows = evaluate_points(evaluate_rotor_design, points, run_tasks)
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


def whirl_at_top_speed(system, design: dict, settings, revolutions: float) -> dict:
    """The rotor with ``design`` run at the top speed for ``revolutions`` from its
    equilibrium with a small cylindrical kick (:func:`gfbopt.transient.rotor_orbit`, the
    rotor transient, on the search grid, the loss factor of the search): per
    bearing the subsynchronous limit cycle [µm] (settled or not) and the smallest film
    [µm], and whether the film closed (contact) first."""
    from ..inputs.options import ModelOptions, merge_options
    from ..transient.rotor_analysis import rotor_orbit
    from .rotor_objectives import apply_design

    designed, _ = apply_design(system, design, settings)
    supports = tuple(dataclasses.replace(b, options=merge_options(
        ModelOptions(loss_factor=settings.loss_factor), b.options))
        for b in designed.bearings)
    designed = dataclasses.replace(designed, bearings=supports)
    result = rotor_orbit(designed, settings.top_speed_rpm, revolutions, grid=settings.grid)
    d = result.to_dict()
    out = {"revolutions": revolutions, "grid": str(settings.grid), "success": bool(d["success"]),
           "message": d.get("message", ""), "contact": bool(d.get("contact")),
           "contact_bearing": d.get("contact_bearing"),
           "contact_time_s": d.get("contact_time_s", math.nan), "bearings": []}
    for b in d["bearings"]:
        out["bearings"].append({
            "bearing": b["bearing"], "min_film_um": b.get("min_film_um", math.nan),
            "limit_cycle_um": b.get("limit_cycle_amplitude_um", math.nan),
            "settled": bool(b.get("limit_cycle_settled", False)),
            "whirl_frequency_hz": b.get("limit_cycle_frequency_hz", math.nan)})
    return out
