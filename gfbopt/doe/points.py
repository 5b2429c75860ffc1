"""The analyses a sampled study can name, evaluated on a *chunk* of neighbouring points.

A chunk is what one task of an executor carries (:func:`gfbopt.parallel.stream_tasks`):
the analysis name, the grid, the fixed inputs and a list of points (``point`` key plus the
sampled inputs).  :func:`evaluate_chunk` runs them one after the other in the worker, with
the worker's solver cache (:func:`gfbopt.parallel.worker_cache`: one build per grid and
formulation for the life of the process), and warm-starts each static solve from the last
converged one of the chunk — the points of a chunk are neighbours in the sample
(:func:`neighbour_order`), so the previous equilibrium is a good first guess.  A point that
fails (a bad value, no convergence, any exception) is a row with ``success = False`` and its
error in ``message``; the chunk goes on.

=====================  ======================================================================
analysis               what one point computes
=====================  ======================================================================
``static``             static equilibrium at ε or W̄ (non-dimensional model)
``linear_threshold``   linear critical mass M̄c and whirl ratio (non-dimensional model)
``onset_speed``        onset speed of whirl of a rotor on a bearing in SI
                       (:func:`gfbopt.rotor.onset_speed`), bump geometry and clearance sampled
=====================  ======================================================================
"""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

#: inputs of the non-dimensional model (floats) and its formulation (strings / flags)
MODEL_NUMBERS = ("bearing_number", "compliance", "length_ratio", "top_foil_coefficient")
FORMULATION = {"foil": "string", "film": "string", "seam_angle_deg": "float64",
               "deflection_law": "string", "subambient": "string",
               "compression_only": "bool"}
STATIC_OUT = {"eccentricity": "float64", "load": "float64", "attitude_angle_deg": "float64",
              "min_film": "float64", "status": "string", "residual": "float64"}
STATIC_OUT["torque_ratio"] = "float64"        # drag torque over Petroff's
#: geometry of a bearing file that an ``onset_speed`` study may sample [m]
GEOMETRY = ("bump_pitch", "bump_thickness", "bump_half_length", "radial_clearance",
            "bump_youngs_modulus", "top_foil_thickness", "length", "radius")
DIAGNOSTICS = {"success": "bool", "message": "string", "iterations": "int64",
               "wall_time_s": "float64", "worker": "string"}


@dataclass(frozen=True)
class Analysis:
    """One analysis of a sampled study: its inputs (name → column type), the inputs of
    which exactly one is needed (the operating point), and its output columns."""

    name: str
    inputs: dict
    outputs: dict
    one_of: tuple = ()
    needs_bearing: bool = False
    doc: str = ""


_MODEL_INPUTS = {**{k: "float64" for k in MODEL_NUMBERS}, **FORMULATION}
ANALYSES = {
    "static": Analysis("static", {**_MODEL_INPUTS, "eccentricity": "float64",
                                  "load": "float64"}, STATIC_OUT,
                       one_of=("eccentricity", "load"),
                       doc="static equilibrium (gfbopt.analyses.static_row)"),
    "linear_threshold": Analysis(
        "linear_threshold", {**_MODEL_INPUTS, "eccentricity": "float64", "load": "float64"},
        {**STATIC_OUT, "static_success": "bool", "critical_mass": "float64",
         "whirl_ratio": "float64", "stable_for_all_masses": "bool"},
        one_of=("eccentricity", "load"),
        doc="linear critical mass (gfbopt.analyses.linear_threshold_point)"),
    "onset_speed": Analysis(
        "onset_speed", {**{k: "float64" for k in GEOMETRY}, "loss_factor": "float64",
                        "rotor_mass_kg": "float64", "load_newton": "float64",
                        "speed_low_rpm": "float64", "speed_high_rpm": "float64"},
        {"compliance": "float64", "onset_speed_rpm": "float64",
         "whirl_frequency_hz": "float64", "whirl_ratio": "float64",
         "stable_over_range": "bool", "unstable_at_lower_end": "bool",
         "smallest_margin": "float64", "evaluations": "int64"},
        needs_bearing=True,
        doc="onset speed of whirl of a rigid rotor (gfbopt.rotor.onset_speed)"),
}


def schema(analysis: str, inputs: dict) -> dict:
    """The fixed column schema of a study table: point key, the inputs given (sampled or
    fixed, in ``inputs`` order), the analysis's outputs, the diagnostics."""
    a = ANALYSES[analysis]
    out = {"point": "int64"}
    for name in inputs:
        out[name] = a.inputs.get(name, "float64")
    for name, kind in a.outputs.items():
        out.setdefault(name, kind)
    out.update(DIAGNOSTICS)
    return out


# ------------------------------------------------------------------ ordering
def neighbour_order(unit: np.ndarray) -> np.ndarray:
    """An order of the rows of ``unit`` (points scaled to [0, 1]^d) in which each point is
    followed by its nearest not-yet-visited neighbour (greedy path from the first point),
    so consecutive points of a chunk warm-start each other.  O(n²) work in numpy; beyond
    20 000 points a sort along the first coordinate is used instead."""
    n = len(unit)
    if n <= 2:
        return np.arange(n)
    if n > 20000:
        return np.lexsort(unit.T[::-1])
    left = np.ones(n, dtype=bool)
    order = np.empty(n, dtype=int)
    current = int(np.argmin(unit.sum(axis=1)))
    for k in range(n):
        order[k] = current
        left[current] = False
        if k == n - 1:
            break
        d = np.sum((unit - unit[current]) ** 2, axis=1)
        d[~left] = np.inf
        current = int(np.argmin(d))
    return order


# ------------------------------------------------------------------ evaluation
def _model(inputs: dict):
    from ..inputs import BearingModel

    kwargs = {k: inputs[k] for k in (*MODEL_NUMBERS, *FORMULATION) if k in inputs}
    if float(kwargs.get("compliance", 0.0)) == 0.0 and "foil" not in kwargs:
        kwargs["foil"] = "rigid"
    return BearingModel(**kwargs)


def _target(inputs: dict) -> dict:
    return ({"eccentricity": inputs["eccentricity"]} if "eccentricity" in inputs
            else {"load": inputs["load"]})


def _static(inputs: dict, grid, cache, state: dict) -> dict:
    from ..analyses import static_row
    from ..static import solve_static

    model = _model(inputs)
    solver = cache(model, grid)
    initial = state.get("previous") if state.get("solver") is solver else None
    sol = solve_static(model, initial=initial, solver=solver, **_target(inputs))
    if not sol.success and initial is not None:          # a bad warm start: retry cold
        sol = solve_static(model, solver=solver, **_target(inputs))
    if sol.success:
        state.update(previous=sol, solver=solver)
    row = static_row(model, sol)
    return {k: row[k] for k in (*STATIC_OUT, "success", "message", "iterations")}


def _linear_threshold(inputs: dict, grid, cache, state: dict) -> dict:
    from ..analyses import linear_threshold_point

    row = linear_threshold_point(_model(inputs), grid=grid, cache=cache, **_target(inputs))
    row.pop("wall_time_s", None)
    return row


def _onset_speed(inputs: dict, grid, cache, state: dict, bearing=None, options=None) -> dict:
    from ..inputs import Rotor
    from ..rotor import onset_speed

    geometry = dataclasses.replace(bearing, **{k: inputs[k] for k in GEOMETRY if k in inputs})
    result = onset_speed(geometry, Rotor(inputs["rotor_mass_kg"]), inputs.get("load_newton"),
                         (inputs["speed_low_rpm"], inputs["speed_high_rpm"]),
                         loss_factor=inputs.get("loss_factor"), options=options, grid=grid,
                         cache=cache)
    return {"compliance": geometry.compliance, "onset_speed_rpm": result.onset_speed_rpm,
            "whirl_frequency_hz": result.whirl_frequency_hz, "whirl_ratio": result.whirl_ratio,
            "stable_over_range": result.stable_over_range,
            "unstable_at_lower_end": result.unstable_at_lower_end,
            "smallest_margin": result.smallest_margin, "evaluations": result.evaluations,
            "success": bool(result.success), "message": result.message}


_FUNCTIONS = {"static": _static, "linear_threshold": _linear_threshold,
              "onset_speed": _onset_speed}


def evaluate_chunk(task: dict) -> list[dict]:
    """Rows of one chunk of points (see :func:`iter_chunk`)."""
    return list(iter_chunk(task))


def iter_chunk(task: dict):
    """The rows of one chunk of points, one at a time (see the module docstring).

    ``task``: ``analysis``, ``grid`` (a Grid), ``fixed`` (inputs shared by every point),
    ``points`` (dicts with ``point`` and the sampled inputs), and for ``onset_speed`` the
    ``bearing`` (BearingGeometry) and ``options`` (ModelOptions) of the bearing file.

    A column is an input or an output, never both: the inputs of the point (sampled or
    fixed) are written as given, and an output of the same name (the target a static solve
    was given, returned as NaN by a failed point) is not written over them.
    """
    from ..parallel import worker_cache, worker_name

    cache = worker_cache()
    who = worker_name()
    function = _FUNCTIONS[task["analysis"]]
    extra = ({"bearing": task.get("bearing"), "options": task.get("options")}
             if ANALYSES[task["analysis"]].needs_bearing else {})
    state: dict = {}
    for point in task["points"]:
        inputs = {**task["fixed"], **{k: v for k, v in point.items() if k != "point"}}
        t0 = time.perf_counter()
        try:
            out = function(inputs, task["grid"], cache, state, **extra)
        except Exception as exc:  # noqa: BLE001 - a failed point is a row with its error
            out = {"success": False, "message": f"{type(exc).__name__}: {exc}"}
        row = {**{k: v for k, v in out.items() if k not in inputs}, **inputs}
        row.update(point=point["point"], wall_time_s=time.perf_counter() - t0, worker=who)
        row.setdefault("message", "")
        yield row


def failed_rows(task: dict, error: BaseException) -> list[dict]:
    """Rows for a chunk whose task died as a whole (a worker crash): each point failed."""
    text = f"{type(error).__name__}: {error}"
    return [{**task["fixed"], **point, "success": False, "message": text}
            for point in task["points"]]


def unit_coordinates(frame, plan) -> np.ndarray:
    """The sampled range variables of ``frame`` scaled to [0, 1] (log scale in its log)."""
    cols = []
    for v in plan.variables:
        x = frame[v.name].to_numpy(dtype=float) if v.is_range else None
        if x is None:
            values = list(v.values)
            x = np.array([values.index(e) for e in frame[v.name]], dtype=float)
            cols.append(x / max(1, len(values) - 1))
        elif v.scale == "log":
            cols.append((np.log(x) - np.log(v.low)) / (np.log(v.high) - np.log(v.low)))
        else:
            cols.append((x - v.low) / (v.high - v.low))
    return np.column_stack(cols) if cols else np.zeros((len(frame), 0))


def chunks(order: np.ndarray, size: int) -> list[np.ndarray]:
    """``order`` cut into consecutive chunks of at most ``size``."""
    return [order[i:i + size] for i in range(0, len(order), max(1, size))]


def row_inputs(plan_frame, names, k) -> dict:
    return {name: _plain(plan_frame[name].iloc[k]) for name in names}


def _plain(value) -> object | None:
    if isinstance(value, np.generic):
        return value.item()
    return value
