"""Design of experiments from Python: your analysis function, your sample plan, the study
store and its resume (docs/doe.md has a worked example)::

    from gfbopt.doe import SamplePlan, Variable, run_doe

    def onset(radial_clearance, bump_pitch, cache=None):        # module level
        ...
        return {"onset_speed_rpm": result.onset_speed_rpm}

    if __name__ == "__main__":                                    # workers are spawned
        plan = SamplePlan((Variable("radial_clearance", 25e-6, 40e-6),
                           Variable("bump_pitch", 3e-3, 5e-3)), method="lhs", n=20, seed=1)
        frame = run_doe(onset, plan, "runs/my_doe", outputs={"onset_speed_rpm": "float64"},
                        workers=2)

:func:`run_doe` writes every finished point to a results store
(:class:`gfbopt.doe.ResultStore`) as it goes — in batches and at most 10 s after it
finished — and returns the whole table as a pandas DataFrame, one row per point (``point``,
the inputs, the outputs, ``success``, ``message``, ``wall_time_s``, ``worker``).  Run the same
script again after Ctrl-C, SIGTERM, ``kill -9`` or a crash and it computes only the points
not yet stored (``resume=True``, the default); a store that holds another plan, other fixed
inputs, other outputs or another version of the function is refused, naming what changed.
A point whose function raises is a row with ``success = False`` and the error (it is a
result); a point whose worker died is retried on a fresh pool and never stored as a
failure.  Same store, lock and rules as ``gfbopt run`` (:mod:`gfbopt.doe.engine`).
"""
from __future__ import annotations

import hashlib
import inspect
import json
import pickle
import time
from collections.abc import Callable
from pathlib import Path
from typing import Optional, Union

import pandas as pd

from ..errors import ParameterError
from .limits import MAX_POINTS, check_size
from .sampling import SamplePlan, sample
from .store import TYPES

#: columns every row carries besides the point, the inputs and the outputs
DIAGNOSTICS = {"success": "bool", "message": "string", "wall_time_s": "float64",
               "worker": "string"}


def _points_frame(plan) -> pd.DataFrame:
    if isinstance(plan, SamplePlan):
        return sample(plan)
    frame = pd.DataFrame(plan if isinstance(plan, pd.DataFrame) else list(plan)).copy()
    if frame.empty:
        raise ParameterError("plan", "empty", "must hold at least one point")
    if "point" not in frame.columns:
        frame.insert(0, "point", range(len(frame)))
    if not frame["point"].is_unique:
        raise ParameterError("plan.point", "duplicates", "point keys must be unique")
    return frame


def _kind(values: pd.Series) -> str:
    if pd.api.types.is_bool_dtype(values):
        return "bool"
    if pd.api.types.is_integer_dtype(values):
        return "int64"
    if pd.api.types.is_numeric_dtype(values):
        return "float64"
    return "string"


def _outputs(outputs) -> dict:
    if isinstance(outputs, (list, tuple)):
        outputs = {name: "float64" for name in outputs}
    if not isinstance(outputs, dict) or not outputs:
        raise ParameterError("outputs", outputs, "must name the function's outputs: a dict "
                             "name → type (float64, int64, bool, string) or a list of names")
    for name, kind in outputs.items():
        if kind not in TYPES:
            raise ParameterError(f"outputs.{name}", kind, f"must be one of {', '.join(TYPES)}")
    return dict(outputs)


def _function_version(function: Callable, version: Optional[str]) -> str:
    if version is not None:
        return str(version)
    try:
        return inspect.getsource(function)
    except (OSError, TypeError):
        return f"{getattr(function, '__module__', '?')}.{getattr(function, '__qualname__', '?')}"


def _digest(value) -> str:
    return hashlib.sha256(json.dumps(value, sort_keys=True, default=str).encode()
                          ).hexdigest()[:16]


def _call(function: Callable, takes_cache: bool, kwargs: dict) -> dict:
    if takes_cache:
        from ..parallel import worker_cache

        kwargs = {**kwargs, "cache": worker_cache()}
    out = function(**kwargs)
    if not isinstance(out, dict):
        raise TypeError(f"the function returned {type(out).__name__}, not a dict of outputs")
    return out


def iter_points(task: dict):
    """The rows of one chunk of a DOE task, one at a time (runs in a worker or here)."""
    from ..parallel import worker_name

    who = worker_name()
    outputs = task["outputs"]
    for point in task["points"]:
        inputs = {k: v for k, v in point.items() if k != "point"}
        t0 = time.perf_counter()
        try:
            out = _call(task["function"], task["takes_cache"], {**task["fixed"], **inputs})
            unknown = sorted(set(out) - set(outputs) - {"success", "message"})
            if unknown:
                raise KeyError(f"output {unknown[0]!r} is not declared in outputs= "
                               f"({', '.join(outputs)})")
            row = {**out, "success": bool(out.get("success", True)),
                   "message": str(out.get("message", ""))}
        except Exception as exc:  # noqa: BLE001 - a failed point is a row with its error
            row = {"success": False, "message": f"{type(exc).__name__}: {exc}"}
        row.update(task["fixed"])
        row.update(inputs)
        row.update(point=point["point"], wall_time_s=time.perf_counter() - t0, worker=who)
        yield row


def evaluate_points(task: dict) -> list:
    """The rows of one chunk of a DOE task (see :func:`iter_points`)."""
    return list(iter_points(task))


def _failed(task: dict, error: BaseException) -> list:
    return [{**task["fixed"], **point, "success": False,
             "message": f"{type(error).__name__}: {error}"} for point in task["points"]]


def run_doe(function: Callable, plan: Union[SamplePlan, pd.DataFrame, list], store,
            *, outputs, fixed: Optional[dict] = None, workers: int = 1, client=None,
            resume: bool = True, chunk_size: int = 4, batch_rows: int = 256,
            flush_s: Optional[float] = None, version: Optional[str] = None,
            max_points: int = MAX_POINTS, progress: bool = True,
            notify: Optional[Callable[[str], None]] = None) -> pd.DataFrame:
    """Run ``function(**inputs, **fixed)`` at every point of ``plan`` into the store
    ``store`` (a folder) and return the table (module docstring).

    Parameters
    ----------
    function : a module-level function (sent by reference to the workers) taking the
        inputs as keywords (and ``cache=``, the worker's solver cache, if it accepts it) and
        returning a dict of outputs (optionally ``success``/``message``)
    plan : a :class:`SamplePlan`, or a DataFrame / list of dicts of points (a ``point``
        column is added when absent)
    outputs : the output columns, name → type (float64, int64, bool, string), or a list of
        names (float64); inputs and outputs never share a column
    fixed : inputs held fixed, passed to every call and stored as columns
    workers : processes (1: this process; inside ``with WorkerPool(n)``: that pool)
    client : a ``distributed.Client``: the chunks run on its Dask cluster instead, several
        whole chunks a task, sized to 20 s of measured work (:mod:`gfbopt.cluster`)
    resume : keep the points already stored (default); False starts a new store, keeping
        the old one aside (``<store>.previous-N``)
    chunk_size : points per chunk (a task of the process pool; on Dask a task carries
        several whole chunks, the first ones one each); batch_rows : most rows per part; flush_s : seconds after
        which finished rows are written (default 10)
    version : a text standing for the function's version in the store's hash (default: its
        source code, so an edited function does not resume into old rows)
    max_points : bound on the job (refused beyond it, with the estimate)

    Returns
    -------
    pandas.DataFrame, one row per point, sorted by ``point``.  SIGTERM/Ctrl-C raise
    :class:`gfbopt.parallel.Interrupted` (a KeyboardInterrupt) after the finished rows are
    written; its ``report`` says what was kept.
    """
    import sys

    from ..parallel import Interrupted, _takes_cache
    from ..progress import progress as progress_bar
    from .engine import FLUSH_S, execute
    from .store import ResultStore, lock_store

    notify = notify or (lambda text: print(f"gfbopt: {text}", file=sys.stderr, flush=True))
    if not callable(function):
        raise ParameterError("function", function, "must be callable")
    fixed = dict(fixed or {})
    outputs = _outputs(outputs)
    for name, value in (("chunk_size", chunk_size), ("batch_rows", batch_rows),
                        ("workers", workers), ("max_points", max_points)):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise ParameterError(name, value, "must be an integer >= 1")
    points = plan if isinstance(plan, SamplePlan) else None
    if points is not None:
        from .limits import plan_size

        check_size(plan_size(points), columns=len(points.variables) + len(outputs),
                   analysis="function", cells=0, workers=workers, max_points=max_points,
                   name="plan")
    frame = _points_frame(plan)
    check_size(len(frame), columns=len(frame.columns) + len(outputs), analysis="function",
               cells=0, workers=workers, max_points=max_points, name="plan")
    inputs = [c for c in frame.columns if c != "point"]
    clash = sorted((set(inputs) | set(fixed)) & (set(outputs) | set(DIAGNOSTICS) | {"point"}))
    if clash:
        raise ParameterError("outputs", clash[0], "is also an input (or a reserved column: "
                             "point, success, message, wall_time_s, worker); inputs and "
                             "outputs never share a column")
    if set(inputs) & set(fixed):
        name = sorted(set(inputs) & set(fixed))[0]
        raise ParameterError(f"fixed.{name}", fixed[name], "is also sampled")
    if workers > 1 or client is not None:
        try:
            pickle.dumps(function)
        except Exception:  # noqa: BLE001 - any reason it cannot travel
            raise ParameterError("function", getattr(function, "__qualname__", function),
                                 "must be a module-level function to run on workers (it "
                                 "is sent to them by reference)") from None
    schema = {"point": "int64", **{c: _kind(frame[c]) for c in inputs},
              **{k: ("string" if isinstance(v, str) else "bool" if isinstance(v, bool)
                     else "float64") for k, v in fixed.items()},
              **outputs, **DIAGNOSTICS}
    name = getattr(function, "__qualname__", "doe")
    digests = {"function": _digest(_function_version(function, version)),
               "sample plan": _digest(frame.to_dict(orient="list")),
               "fixed inputs": _digest(fixed), "outputs": _digest(outputs)}
    study_hash = hashlib.sha256(json.dumps(digests, sort_keys=True).encode()).hexdigest()
    directory = Path(store)
    takes_cache = _takes_cache(function)
    with lock_store(directory):
        target = ResultStore.create(directory, study=name, study_hash=study_hash,
                                    schema=schema, resume=resume, inputs=digests,
                                    study_file=f"function {name}",
                                    metadata={"function": name})
        for text in target.notices:
            notify(text)
        done = target.done_points() if resume else set()
        todo = [k for k, p in enumerate(frame["point"]) if p not in done]
        records = frame.iloc[todo].to_dict(orient="records")
        tasks = [{"function": function, "takes_cache": takes_cache, "fixed": fixed,
                  "outputs": list(outputs), "points": records[i:i + chunk_size]}
                 for i in range(0, len(records), chunk_size)]
        bar = progress_bar(total=len(records), desc=name, unit="point",
                           enabled=progress and bool(records))
        try:
            outcome = execute(evaluate_points, tasks, target,
                              conform=lambda r: {k: r[k] for k in schema if k in r},
                              batch_rows=batch_rows, workers=workers, client=client,
                              iterate=iter_points,
                              failed_rows=_failed, progress=bar.update,
                              flush_s=FLUSH_S if flush_s is None else flush_s, status=notify)
        except Interrupted as exc:
            kept = len(target.read())
            raise Interrupted(exc.signum, f"{kept} of {len(frame)} points stored in "
                              f"{directory}; run again (resume=True) to compute the other "
                              f"{len(frame) - kept}") from None
        finally:
            bar.close()
        if outcome.lost:
            notify(f"{len(outcome.lost)} points not computed (their workers kept dying); "
                   "run again to compute them")
        return target.read()
