"""Pareto fronts of evaluated designs: non-dominated feasible rows, hypervolume, distance.

A design dominates another when it is no worse in every objective and better in at least one
(objectives in minimisation form).  The front of an optimisation is taken over *every*
evaluation stored, feasible and successful ones only — not over the last population — so a
good design found early is never lost.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from .problem import DesignProblem


def non_dominated(F: np.ndarray) -> np.ndarray:
    """Boolean mask of the rows of ``F`` (n × m, minimised) that no other row dominates.

    Rows with equal objective vectors do not dominate each other (both are kept)."""
    F = np.asarray(F, float)
    n = len(F)
    keep = np.ones(n, dtype=bool)
    for i in range(n):
        if not keep[i]:
            continue
        dominated_by = np.all(F <= F[i], axis=1) & np.any(F < F[i], axis=1)
        if dominated_by.any():
            keep[i] = False
            continue
        dominates = np.all(F[i] <= F, axis=1) & np.any(F[i] < F, axis=1)
        keep &= ~dominates
    return keep


def minimised_objectives(frame: pd.DataFrame, problem: DesignProblem) -> np.ndarray:
    """The objectives of every row of ``frame`` in minimisation form (n × m)."""
    return np.array([[o.minimised(float(v)) for o, v in zip(problem.objectives, row)]
                     for row in frame[[o.name for o in problem.objectives]].to_numpy(float)]
                    ).reshape(len(frame), len(problem.objectives))


def feasible_rows(frame: pd.DataFrame, problem: DesignProblem) -> pd.DataFrame:
    """The rows that succeeded and meet every constraint."""
    if frame.empty:
        return frame
    mask = [problem.feasible(row) for row in frame.to_dict(orient="records")]
    return frame[np.asarray(mask, dtype=bool)]


def pareto_front(frame: pd.DataFrame, problem: DesignProblem) -> pd.DataFrame:
    """The non-dominated feasible rows, sorted by the first objective (best first)."""
    ok = feasible_rows(frame, problem)
    if ok.empty:
        return ok.copy()
    F = minimised_objectives(ok, problem)
    front = ok[non_dominated(F)].copy()
    first = problem.objectives[0]
    return front.sort_values(first.name, ascending=first.sense == "min").reset_index(drop=True)


def hypervolume(F: np.ndarray, reference: np.ndarray) -> float:
    """Hypervolume dominated by the points ``F`` (minimised) up to ``reference``.

    Exact sweep for one and two objectives; pymoo's indicator above that."""
    F = np.asarray(F, float)
    ref = np.asarray(reference, float)
    F = F[np.all(F < ref, axis=1)] if len(F) else F.reshape(0, len(ref))
    if len(F) == 0:
        return 0.0
    if F.shape[1] == 1:
        return float(ref[0] - F[:, 0].min())
    if F.shape[1] == 2:
        F = F[non_dominated(F)]
        F = F[np.argsort(F[:, 0])]
        volume, f2_prev = 0.0, ref[1]
        for f1, f2 in F:
            volume += (ref[0] - f1) * (f2_prev - f2)
            f2_prev = f2
        return float(volume)
    from pymoo.indicators.hv import HV

    return float(HV(ref_point=ref)(F))


def distance_to_front(F: np.ndarray, true_front: np.ndarray) -> np.ndarray:
    """For every row of ``F``, the Euclidean distance to the nearest point of a densely
    sampled ``true_front`` (generational distance terms)."""
    F, T = np.asarray(F, float), np.asarray(true_front, float)
    return np.sqrt(((F[:, None, :] - T[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
