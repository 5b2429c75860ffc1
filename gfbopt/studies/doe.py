"""Sampled studies (design of experiments): one analysis over a sample of inputs, streamed into
a resumable Parquet store.

A ``kind = "sweep"`` study names ONE analysis (:data:`gfbopt.doe.points.ANALYSES`: ``static``,
``linear_threshold``, ``onset_speed``), its fixed inputs (``[fixed]``, glossary names) and a
``[sampling]`` table (method factorial | lhs | sobol | list | saltelli, ``n`` or ``levels``,
``seed``, ``[[sampling.variables]]`` with ``low``/``high``/``scale`` or ``values``).  Everything
is checked before any solve; the sample is reproducible from the file.

Running it (``gfbopt run problems/NAME.toml [--workers N] [--scheduler ADDRESS] [--resume]``):

* the points are ordered so that neighbours follow each other
  (:func:`gfbopt.doe.points.neighbour_order`) and cut into chunks of ``chunk_size``
  points; a chunk's points warm-start each other in the worker, with the worker's cached
  solver, so the rows depend on ``chunk_size`` alone.  A chunk is one task of this process
  or of the local pool; on a Dask cluster a task carries several whole chunks, one at
  first and then as many as take 20 s of measured work (:func:`gfbopt.cluster.task_size`);
* rows are appended to ``results/NAME/store/`` (:class:`gfbopt.doe.ResultStore`: Parquet
  parts written atomically, fixed schema) in batches as the chunks finish; a failed point
  is a row with its error;
* ``--resume`` reuses the store (refused when it belongs to another study file) and computes
  only the points it does not hold, so every point ends up stored exactly once;
* at the end the table is read back (``NAME.csv`` too when ≤ 10 000 rows), with a
  summary/README through :mod:`.report` and a throughput line (points/s, workers);
  with a Saltelli design and ``sensitivity_outputs``, the Sobol indices table and bar chart.

Python API::

    from gfbopt.studies import load_study
    from gfbopt.studies.doe import run_sampled
    result = run_sampled(load_study("problems/sweep_static_lhs.toml"), "results", workers=2)
    frame = result.tables  # or gfbopt.doe.read_results("results/sweep_static_lhs/store")
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ..doe import METHODS, ResultStore, SamplePlan, Variable, sample
from ..doe.limits import MAX_POINTS, check_fixed, check_size, plan_size
from ..doe.points import (
    ANALYSES,
    FORMULATION,
    chunks,
    evaluate_chunk,
    failed_rows,
    neighbour_order,
    unit_coordinates,
)
from ..doe.points import schema as table_schema
from ..errors import ParameterError
from ..inputs import Grid
from .base import Kind, LoadedStudy, RunContext, Study, StudyResult
from .spec import FORMULATION as MODEL_FORMULATION
from .spec import GRID, opt, req

#: largest table also written as CSV
CSV_ROWS = 10_000

VARIABLE = {
    "name": req("string", "input sampled (a glossary name accepted by the analysis)"),
    "low": opt("number", None, "low end of the range"),
    "high": opt("number", None, "high end of the range"),
    "scale": opt("string", "linear", "linear or log", choices=("linear", "log")),
    "values": opt("numbers", None, "explicit values (method list or factorial)"),
}
SAMPLING = {
    "method": req("string", "sampling method", choices=METHODS),
    "n": opt("integer", 0, "number of points (lhs, sobol) or base samples (saltelli)",
             minimum=1),
    "levels": opt("integer", 0, "levels per range variable (factorial)", minimum=2),
    "seed": opt("integer", 0, "seed of the random methods (lhs, sobol, saltelli)",
                minimum=0, maximum=2**32 - 1),
    "variables": req("tables", "sampled inputs", keys=VARIABLE),
}
SCHEMAS = {
    "sweep": {**GRID,
              "analysis": req("string", "analysis run at every point", choices=tuple(ANALYSES)),
              "bearing": opt("string", None, "bearing file (SI), relative to the study file "
                             "(analysis onset_speed)"),
              "fixed": opt("mapping", {}, "numeric inputs held fixed (glossary names)",
                           values=req("number", "value of the fixed input")),
              "model": opt("table", {}, "formulation of the non-dimensional model "
                           "(static, linear_threshold)", keys=MODEL_FORMULATION),
              "sampling": req("table", "the sample plan", keys=SAMPLING),
              "chunk_size": opt("integer", 8, "neighbouring points per task (warm starts)",
                                minimum=1, maximum=10_000),
              "batch_rows": opt("integer", 256, "rows per Parquet part written (at most; "
                                "rows are also written 10 s after they finish)", minimum=1,
                                maximum=100_000),
              "max_points": opt("integer", MAX_POINTS, "largest number of points accepted "
                                "(a bound on the job; gfbopt run --max-points sets it)",
                                minimum=1),
              "min_success_fraction": opt("number", 0.9, "smallest fraction of points "
                                          "that must succeed (check)", minimum=0.0,
                                          maximum=1.0),
              "sensitivity_outputs": opt("strings", [], "outputs whose Sobol indices are "
                                         "computed (saltelli design)")},
}


@dataclass(frozen=True)
class SweepPlan:
    """The validated sample: the plan, its table (``point`` + inputs), the analysis, the
    fixed inputs, the bearing (onset_speed), the table schema and the study hash."""

    plan: SamplePlan
    frame: pd.DataFrame
    analysis: str
    fixed: dict
    grid: Grid
    bearing: object
    options: object
    schema: dict
    study_hash: str
    inputs: dict
    estimate: str


def _fixed_values(spec: dict, where) -> dict:
    if spec["model"] and spec["analysis"] == "onset_speed":
        raise (where / "model").error(spec["model"], "is not used by analysis 'onset_speed' "
                                      "(the bearing file's [model] table is)")
    return {**spec["model"], **{k: float(v) for k, v in spec["fixed"].items()}}


#: what the numbers of a sweep depend on (hashed); everything else in the file (name,
#: title, source, notes, chunk_size, batch_rows, max_points, min_success_fraction,
#: sensitivity_outputs) may change between a run and its resume
HASHED_KEYS = {"analysis": "analysis", "grid": "grid", "model": "model options",
               "fixed": "fixed inputs", "sampling": "sample plan"}


def code_version() -> str:
    """The code-version part of the study hash: gfbopt's major.minor version.  A resume
    with another minor release is refused (a release may change the numbers); patch releases
    and uncommitted edits are not hashed (each part's provenance records the commit)."""
    from ..version import __version__

    return ".".join(__version__.split(".")[:2])


def _digest(value) -> str:
    return hashlib.sha256(json.dumps(value, sort_keys=True, default=str).encode()
                          ).hexdigest()[:16]


def study_inputs(spec: dict, bearing=None, options=None) -> dict:
    """Digest of each input the numbers depend on (the bearing file by its parsed
    content — every value of [bearing] and [model] — not its path)."""
    out = {label: _digest(spec[key]) for key, label in HASHED_KEYS.items()}
    if bearing is not None:
        out["bearing file content"] = _digest([dataclasses.asdict(bearing),
                                               dataclasses.asdict(options)])
    out["gfbopt version"] = code_version()
    return out


def study_hash(inputs: dict) -> str:
    """sha256 over the digests of :func:`study_inputs`."""
    return hashlib.sha256(json.dumps(inputs, sort_keys=True).encode()).hexdigest()


def plan_sweep(study: Study) -> SweepPlan:
    """Validate the sample, the analysis's inputs and the bearing; build the sample (no
    solving).  Every mistake is one ParameterError naming the file and the key."""
    spec = study.spec
    analysis = ANALYSES[spec["analysis"]]
    s = spec["sampling"]
    where = study.where("sampling")
    method = s["method"]
    if method in ("lhs", "sobol", "saltelli") and s["n"] < 1:
        raise (where / "n").error(s["n"], f"is required (>= 1) for method '{method}'")
    variables = []
    for k, v in enumerate(s["variables"]):
        w = where / "variables" / k
        if v["name"] not in analysis.inputs:
            raise (w / "name").error(v["name"], f"is not an input of analysis "
                                     f"'{analysis.name}' (inputs: {', '.join(analysis.inputs)})")
        if FORMULATION.get(v["name"], "float64") != "float64":
            raise (w / "name").error(v["name"], "is a formulation option: fix it in [fixed]")
        try:
            variables.append(Variable(v["name"], low=v["low"], high=v["high"],
                                      scale=v["scale"],
                                      values=None if v["values"] is None else tuple(v["values"])))
        except ParameterError as exc:
            raise w.error(exc.value, exc.rule) from None
    fixed = _fixed_values(spec, study.where())
    check_fixed(fixed, study.where("fixed"))
    for name in fixed:
        if name not in analysis.inputs:
            raise study.where("fixed", name).error(fixed[name], f"is not an input of analysis "
                                                   f"'{analysis.name}' (inputs: "
                                                   f"{', '.join(analysis.inputs)})")
    try:
        plan = SamplePlan(tuple(variables), method=method, n=s["n"], levels=s["levels"],
                          seed=s["seed"])
    except ParameterError as exc:
        raise study.where(*exc.name.split(".")).error(exc.value, exc.rule) from None
    names = set(plan.names) | set(fixed)
    clash = sorted(set(plan.names) & set(fixed))
    if clash:
        raise study.where("fixed", clash[0]).error(fixed[clash[0]], "is also sampled")
    if analysis.one_of and len(names & set(analysis.one_of)) != 1:
        raise study.where("fixed").error(sorted(names & set(analysis.one_of)),
                                         f"give exactly one of {' or '.join(analysis.one_of)} "
                                         "(fixed or sampled)")
    bearing = options = None
    if analysis.needs_bearing:
        if spec["bearing"] is None:
            raise study.where("bearing").error(None, f"is required by analysis "
                                               f"'{analysis.name}'")
        from .base import load_geometry

        # the file checked as every study kind checks it: [journal]/[thermal] refused in one
        # line naming this kind and the kinds and commands that read them
        bearing = load_geometry(study)
        options = bearing.options
        for need in ("rotor_mass_kg", "speed_low_rpm", "speed_high_rpm"):
            if need not in names:
                raise study.where("fixed", need).error(None, f"is required by analysis "
                                                       f"'{analysis.name}'")
    for out in spec["sensitivity_outputs"]:
        if out not in analysis.outputs:
            raise study.where("sensitivity_outputs").error(out, f"is not an output of "
                                                           f"'{analysis.name}'")
    if spec["sensitivity_outputs"] and method != "saltelli":
        raise study.where("sensitivity_outputs").error(spec["sensitivity_outputs"],
                                                       "need sampling.method = 'saltelli'")
    estimate = check_size(plan_size(plan), columns=len(analysis.inputs) + len(analysis.outputs),
                          analysis=analysis.name, cells=study.grid.n_theta * study.grid.n_z,
                          workers=1, max_points=spec["max_points"],
                          name=f"{study.file}: sampling")
    try:
        frame = sample(plan)
    except ParameterError as exc:
        raise study.where(*exc.name.split(".")).error(exc.value, exc.rule) from None
    inputs = {name: None for name in [*plan.names, *fixed]}
    columns = table_schema(analysis.name, inputs)
    for name, value in fixed.items():           # a fixed string/flag keeps its own type
        if isinstance(value, bool):
            columns[name] = "bool"
        elif isinstance(value, str):
            columns[name] = "string"
    digests = study_inputs(spec, bearing, options)
    return SweepPlan(plan, frame, analysis.name, fixed, study.grid, bearing, options, columns,
                     study_hash(digests), digests, estimate)


# ------------------------------------------------------------------ running
def _tasks(sp: SweepPlan, todo: np.ndarray, chunk_size: int) -> list[dict]:
    sub = sp.frame.iloc[todo]
    order = todo[neighbour_order(unit_coordinates(sub, sp.plan))] if len(todo) else todo
    tasks = []
    for chunk in chunks(order, chunk_size):
        points = [{"point": int(sp.frame["point"].iloc[k]),
                   **{n: _plain(sp.frame[n].iloc[k]) for n in sp.plan.names}} for k in chunk]
        tasks.append({"analysis": sp.analysis, "grid": sp.grid, "fixed": sp.fixed,
                      "points": points, "bearing": sp.bearing, "options": sp.options})
    return tasks


def _plain(value):
    return value.item() if isinstance(value, np.generic) else value


def _conform(row: dict, schema: dict) -> dict:
    return {k: row[k] for k in schema if k in row}


def _stored(store) -> int:
    try:
        return len(store.read())
    except ParameterError:
        return 0


def run_sampled(loaded, results_root="runs", *, workers: int = 1,
                scheduler: str | None = None, client=None, resume: bool = False,
                progress: Callable[[float], None] | None = None,
                write: bool = True, force: bool = False,
                notify: Callable[[str], None] | None = None,
                flush_s: float | None = None) -> StudyResult:
    """Run a loaded sampled study into ``results_root/NAME/store/`` (module docstring).

    workers : local processes (1: this process; inside ``with WorkerPool(n)`` the run's
    pool); scheduler : address of a Dask scheduler (``client``: an existing
    ``distributed.Client`` instead); resume : keep the stored points; force : overwrite
    files in ``results_root/NAME/`` that gfbopt did not write; notify : where notices go
    (parts moved aside, waiting for workers; default stderr); flush_s : seconds after which
    finished rows are written (default 10).  An unreachable scheduler, an unwritable or
    foreign results folder, or a store in use by another run raise ParameterError before
    anything is computed.  SIGTERM/SIGINT raise :class:`gfbopt.parallel.Interrupted` whose
    ``report`` says what was kept and how to resume, after the finished rows are written.
    """
    import sys

    from ..doe.engine import FLUSH_S, execute
    from ..doe.points import iter_chunk
    from ..doe.store import lock_store
    from ..parallel import InfrastructureError, Interrupted
    from .report import prepare_output

    study, sp = loaded.study, loaded.plan
    spec = study.spec
    notify = notify or (lambda text: print(f"gfbopt: {text}", file=sys.stderr, flush=True))
    out = (prepare_output(Path(results_root), study.name, force=force) if write
           else Path(results_root) / study.name)
    own_client = None
    if client is None and scheduler is not None:
        from ..parallel import connect_scheduler

        client = own_client = connect_scheduler(scheduler)       # before anything is written
    try:
        with lock_store(out / "store"):
            from ..provenance import provenance

            store = ResultStore.create(out / "store", study=study.name,
                                       study_hash=sp.study_hash, schema=sp.schema,
                                       resume=resume, inputs=sp.inputs, study_file=study.file,
                                       metadata={"study_file": study.file,
                                                 "provenance": provenance(grid=str(sp.grid))})
            for text in store.notices:
                notify(text)
            done = store.done_points() if resume else set()
            todo = np.array([k for k, p in enumerate(sp.frame["point"]) if int(p) not in done],
                            dtype=int)
            tasks = _tasks(sp, todo, spec["chunk_size"])
            executor = ("dask " + (scheduler or "client") if client is not None else
                        "process pool" if workers > 1 and len(tasks) > 1 else "serial")
            finished = [0]

            def advance(n: int) -> None:
                finished[0] += n
                if progress is not None and len(todo):
                    progress(finished[0] / len(todo))

            t0 = time.perf_counter()
            try:
                outcome = execute(evaluate_chunk, tasks, store,
                                  conform=lambda r: _conform(r, sp.schema),
                                  batch_rows=spec["batch_rows"], workers=workers,
                                  client=client, iterate=iter_chunk, failed_rows=failed_rows,
                                  progress=advance, status=notify,
                                  flush_s=FLUSH_S if flush_s is None else flush_s)
            except (Interrupted, InfrastructureError) as exc:
                kept = _stored(store)
                why = signal_name(exc.signum) if isinstance(exc, Interrupted) else str(exc)
                report = (f"{why}: {kept} of {len(sp.frame)} points of {study.name} are "
                          f"stored in {out / 'store'}; `{study.command} --resume` "
                          f"computes the other {len(sp.frame) - kept}")
                if isinstance(exc, Interrupted):
                    raise Interrupted(exc.signum, report) from None
                raise InfrastructureError(report) from None
            elapsed = time.perf_counter() - t0
            n_workers = _workers_used(client, workers, len(tasks))
            frame = store.read()
    finally:
        if own_client is not None:
            own_client.close()
    result = _result(study, sp, frame, finished[0], elapsed, n_workers, executor, len(done),
                     outcome.lost)
    if write:
        from .report import write_result

        write_result(result, Path(results_root), force=force, notify=notify)
    return result


def signal_name(signum: int) -> str:
    import signal

    return signal.Signals(signum).name


def _workers_used(client, workers: int, n_tasks: int) -> int:
    if client is not None:
        from ..cluster import worker_count

        return worker_count(client)
    return min(workers, n_tasks) if workers > 1 and n_tasks > 1 else 1


def _result(study, sp, frame, n_done, elapsed, n_workers, executor, resumed,
            lost=()) -> StudyResult:
    n = len(sp.frame)
    ok = int(frame["success"].fillna(False).sum()) if len(frame) else 0
    once = len(frame) == n and set(frame["point"]) == set(sp.frame["point"])
    rate = n_done / elapsed if elapsed > 0 else math.nan
    checks = [
        {"what": "every planned point stored exactly once", "value": float(len(frame)),
         "limit": float(n), "passed": bool(once)},
        {"what": f"fraction of points that succeeded (>= {study.spec['min_success_fraction']:g})",
         "value": ok / n if n else math.nan, "limit": study.spec["min_success_fraction"],
         "passed": bool(n and ok / n >= study.spec["min_success_fraction"])}]
    fixed = ", ".join(f"{k} = {v}" for k, v in sp.fixed.items()) or "none"
    notes = [(f"analysis {sp.analysis} on grid {sp.grid}; sampling {sp.plan.method} with "
             f"{n} points over {', '.join(sp.plan.names)}; fixed: {fixed}"),
             (f"throughput: {n_done} points in {elapsed:.1f} s = {rate:.2f} points/s on "
             f"{n_workers} worker(s) ({executor}); {resumed} points already stored (resume)"),
             f"{n - ok} of {n} points failed (rows with success = false and their message)",
             f"bound on the job: {sp.estimate} (limit: max_points = "
             f"{study.spec['max_points']:,})",
             "full table: store/ (Parquet parts; gfbopt.doe.read_results('store'))"]
    tables = {}
    if len(frame) <= CSV_ROWS:
        tables[f"{study.name}.csv"] = frame
    figures = {}
    for output in study.spec["sensitivity_outputs"]:
        from ..doe.sensitivity import sobol_indices

        s = sobol_indices(sp.plan, frame, output)
        notes.append(f"Sobol indices of {output}: {s.base_samples} base samples used"
                     + (f"; {s.message}" if s.message else ""))
        if s.success:
            tables[f"sobol_{output}.csv"] = s.table.assign(output=output)[
                ["output", "input", "S1", "S1_conf", "ST", "ST_conf"]]
            from ..plotting.doe import plot_sobol_indices

            ax = plot_sobol_indices(s.table, output=output)
            figures[f"sobol_{output}.png"] = ax.figure
        checks.append({"what": f"Sobol indices of {output} computed", "value":
                       float(s.base_samples), "limit": 2.0, "passed": bool(s.success)})
    if lost:
        notes.append(f"{len(lost)} points were not computed because their workers kept dying "
                     "(not stored as failures): `gfbopt run ... --resume` computes them")
    options = {"variants": {}, "grid": str(sp.grid), "analysis": sp.analysis,
               "sampling": sp.plan.method, "points": n, "workers": n_workers,
               "executor": executor, "points_per_second": rate}
    return StudyResult(study=study, tables=tables, figures=figures, checks=checks,
                       options=options, notes=notes, wall_time_s=elapsed)


def _run_default(study: Study, plan: SweepPlan, context: RunContext) -> StudyResult:
    """``compute``/``run_study``: RESULTS/NAME/store/ (the context's results folder), no
    resume, the local executor."""
    return run_sampled(LoadedStudy(study, plan), context.results_root, workers=context.workers,
                       progress=context.progress, write=False)


KINDS = {"sweep": Kind(plan_sweep, _run_default, parallel=True)}
