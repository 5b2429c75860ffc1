"""Design optimisation driven by ask/tell, every evaluation streamed into the results store.

    from gfbopt.design.optimiser import optimise
    from gfbopt.design.problem import Constraint, DesignProblem, Objective, Variable
    from gfbopt.design.search import SearchSettings
    problem = DesignProblem((Variable("x", 0, 1), Variable("y", 0, 1)),
                            (Objective("f1"), Objective("f2")), (Constraint("g", upper=0),))
    result = optimise(problem, my_module.evaluate, SearchSettings("nsga2", budget=200),
                      store=store)          # a gfbopt.doe.ResultStore (resume: reopen it)
    result.front                            # non-dominated feasible designs

How a run goes:

1. the search method (:mod:`.search`: pymoo NSGA-II, or GP Bayesian optimisation for one
   objective) *asks* a batch of designs in the unit cube; they are decoded to values
   (:class:`~gfbopt.design.problem.DesignProblem`);
2. a design already in the store (an earlier, killed run; or the same design asked again,
   e.g. after rounding a discrete variable) is answered from it; the others are evaluated by
   ``evaluate(**fixed, **design)`` (a module-level function returning one row: a dict with
   the objective and constraint columns), through an executor — serial, a process pool
   or a Dask cluster (:func:`executor`, over :func:`gfbopt.parallel.stream_tasks`; inside
   ``with gfbopt.parallel.WorkerPool(n):`` every batch of the run reuses one pool and its
   workers' solvers, and a task whose worker died is retried on a fresh pool); each task runs
   :func:`gfbopt.parallel.run_points` on its point with the worker's solver cache, so a failed
   evaluation is a row with ``success = False`` and its message, never a crash;
3. finished rows are appended to the store in Parquet parts: at the end of every batch, when
   ``flush_rows`` rows are waiting, and at least every ``flush_seconds`` (checked as rows
   arrive and on the executor's ticks); a part is written atomically, so ``kill -9`` loses at
   most the rows of the last few seconds and those in flight, and an exception or Ctrl-C
   writes the waiting rows first (one Parquet append costs ~40 ms: one per row would be
   3-4 % of a one-second evaluation);
4. the batch's objectives and constraint violations are *told* to the method.

**A lost design is not an evaluation.**  A task the executor could not run (its worker died
on every pool it was retried on, a lost cluster: :class:`gfbopt.runtime.InfrastructureFailure`)
is never stored and never told to the method as a failed design — that would steer the search
away from a design nobody evaluated.  The batch's other designs finish and are stored, then
:func:`optimise` raises :class:`gfbopt.runtime.InfrastructureError`: nothing of the lost
designs, and nothing asked after them, is kept, so a resume asks the same batch again and
evaluates only the lost designs.

The proposals depend only on the seed and on the values told, and the values of a stored
design are read back bit for bit, so a resumed run asks the same designs, answers the stored
ones from the store and evaluates only the rest: every design is evaluated once, and the
resumed result equals an uninterrupted run's.  Row order is the order of first asking
(``evaluation``), whatever the executor's completion order.

The Pareto front is taken over every evaluation (:func:`gfbopt.design.pareto.pareto_front`).
"""
from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Optional

import numpy as np
import pandas as pd

from ..errors import ParameterError
from .pareto import feasible_rows, pareto_front
from .problem import DesignProblem
from .search import SearchSettings, proposer

#: columns every optimisation table has besides the variables and the outputs
BOOK_KEEPING = {"point": "string", "evaluation": "int64", "batch": "int64",
                "success": "bool", "feasible": "bool", "message": "string",
                "wall_time_s": "float64", "worker": "string"}
#: book-keeping columns a store must have to be searched into (``feasible`` is derived from
#: the row and the problem: an older store without it is still read)
REQUIRED = tuple(k for k in BOOK_KEEPING if k != "feasible")


def store_schema(problem: DesignProblem, outputs: dict) -> dict:
    """The fixed column schema of an optimisation's store: book-keeping, one float64 column
    per design variable, then ``outputs`` (name → type; objectives and constraints must be
    among them)."""
    missing = [n for n in [o.name for o in problem.objectives]
               + [c.name for c in problem.constraints] if n not in outputs]
    if missing:
        raise ParameterError("outputs", missing[0], "is an objective or constraint but not "
                             "an output column of the evaluation")
    return {**BOOK_KEEPING, **{n: "float64" for n in problem.names}, **outputs}


@dataclass(frozen=True)
class OptimisationResult:
    """An optimisation run.

    table : every design asked, in the order of first asking (variables, outputs,
        ``evaluation``, ``batch``, ``success``, ``message``, ``wall_time_s``)
    front : the non-dominated feasible designs (one objective: the best feasible)
    best : the best feasible row for one objective (None for several, or none feasible)
    evaluated : designs evaluated in this run; reused : designs answered from the store
        (an earlier run's); repeated : designs asked again in this run (answered once)
    evaluation_time_s : sum of the wall times of the evaluations of this run
    driver_time_s : time in the method's ask/tell, decoding and the store writes
    wall_time_s : the whole run
    convergence : why the search stopped — ``"converged: ..."`` (nsga2_refine's rule,
        :mod:`.refine`), ``"not converged: budget N reached"``, or for a fixed-budget
        method ``"fixed budget N (no convergence test)"``
    stages : designs asked per stage (``search``, ``refinement``), in the order of asking
    stage_time_s : sum of the evaluation wall times per stage (this run's evaluations)
    """

    problem: DesignProblem
    settings: SearchSettings
    table: pd.DataFrame
    front: pd.DataFrame
    best: Optional[dict]
    evaluated: int
    reused: int
    repeated: int
    evaluation_time_s: float
    driver_time_s: float
    wall_time_s: float
    convergence: str = ""
    stages: tuple = ()
    stage_time_s: tuple = ()

    @property
    def converged(self) -> bool:
        """True when the search stopped on its convergence rule."""
        return self.convergence.startswith("converged")

    @property
    def stage_counts(self) -> dict:
        """Designs asked per stage."""
        return dict(self.stages)

    @property
    def asked(self) -> int:
        return self.evaluated + self.reused + self.repeated

    @property
    def driver_time_per_design_s(self) -> float:
        return self.driver_time_s / self.asked if self.asked else math.nan

    @property
    def feasible_count(self) -> int:
        return len(feasible_rows(self.table, self.problem))

    @property
    def success(self) -> bool:
        return self.feasible_count > 0

    @property
    def message(self) -> str:
        if self.success:
            return ""
        failed = int((~self.table["success"].fillna(False).astype(bool)).sum())
        return (f"no feasible design among {len(self.table)} evaluated ({failed} failed, "
                "the others broke a constraint)")


def _task(argument: dict) -> dict:
    """One evaluation in a worker (or here): ``run_points`` on the point with this process's
    solver cache; a failure is a row with ``success = False``."""
    from ..parallel import run_points, worker_cache, worker_name

    row = run_points(argument["function"], [argument["point"]], workers=1,
                     cache=worker_cache())[0]
    row["worker"] = worker_name()
    return row


def executor(workers: int = 1, client=None) -> Callable:
    """The ``run_tasks`` of :func:`optimise`: this process (``workers <= 1``), a pool of
    ``workers`` worker processes (forked where safe, :func:`gfbopt.parallel.start_method`;
    the run's :class:`gfbopt.parallel.WorkerPool` when one is open) or a Dask cluster
    (``client``), through :func:`gfbopt.parallel.stream_tasks`."""
    from functools import partial

    from ..parallel import stream_tasks

    return partial(stream_tasks, workers=workers, client=client)


def lost_designs(lost: list, of: int, what: str) -> str:
    """The sentence of an InfrastructureError for ``lost`` (exceptions) of ``of`` tasks."""
    first = lost[0]
    return (f"{len(lost)} of {of} {what} could not be evaluated "
            f"({type(first).__name__}: {first})")


def evaluate_points(function: Callable, points: list, run_tasks: Optional[Callable] = None,
                    progress: Optional[Callable[[float], None]] = None) -> list:
    """``function(**point)`` for every point through an executor (``run_tasks``, default
    this process), the rows in the order of ``points``; ``progress`` is called with the
    fraction finished.  A task the executor lost (a worker that kept dying) is not a result:
    when every other task has finished, :class:`gfbopt.runtime.InfrastructureError`."""
    from ..runtime import InfrastructureError

    run_tasks = run_tasks or _serial
    rows: list = [None] * len(points)
    lost, done = [], 0
    for k, result in run_tasks(_task, [{"function": function, "point": p} for p in points]):
        if k is None:
            continue
        if isinstance(result, BaseException):
            lost.append(result)
        else:
            rows[k] = result
        done += 1
        if progress is not None:
            progress(done / len(points))
    if lost:
        raise InfrastructureError(lost_designs(lost, len(points), "evaluations"))
    return rows


def _serial(function, arguments):
    return executor(1)(function, arguments)


def _number(value) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def _stored(store) -> dict:
    """key → row of the designs already in the store."""
    if store is None:
        return {}
    frame = store.read()
    frame = frame.astype(object).where(frame.notna(), None)
    return {str(r["point"]): r for r in frame.to_dict(orient="records")}


def _columns(schema: dict, row: dict) -> dict:
    """The row's columns of the store's schema (the row buffer's ``conform``)."""
    return {k: row[k] for k in schema if k in row}


def _writer(store, schema: dict, flush_rows: int, flush_seconds: float):
    """The row buffer of the run (:class:`gfbopt.doe.engine.RowBuffer`, the sampled
    studies' too): parts of ``flush_rows`` rows, none older than ``flush_seconds``."""
    from functools import partial

    from ..doe.engine import RowBuffer

    return RowBuffer(store, partial(_columns, schema), flush_rows, flush_seconds)


def optimise(problem: DesignProblem, evaluate: Callable, settings: SearchSettings, *,
             fixed: Optional[dict] = None, store=None, run_tasks: Optional[Callable] = None,
             initial: Optional[list] = None, flush_rows: int = 64,
             flush_seconds: float = 5.0,
             progress: Optional[Callable[[float], None]] = None) -> OptimisationResult:
    """Search the design space of ``problem`` (module docstring).

    Parameters
    ----------
    evaluate : module-level function ``evaluate(**fixed, **design) -> dict`` (picklable for
        the workers; it may take ``cache=``, the worker's solver cache)
    settings : method, budget, population/batch, seed (:class:`~.search.SearchSettings`)
    fixed : keyword arguments passed to every evaluation unchanged
    store : a :class:`gfbopt.doe.ResultStore` whose schema is :func:`store_schema` (None:
        nothing is written); reopened with ``resume=True`` it answers the designs it holds
    run_tasks : executor ``run_tasks(function, arguments)`` yielding ``(k, result)`` as each
        task finishes (default: this process; :func:`executor` for a pool or Dask)
    initial : designs (dicts) put first in the initial sample (e.g. the baseline)
    flush_rows, flush_seconds : most rows per Parquet part / longest time rows wait (step 3)
    progress : called with the fraction of the budget done (designs evaluated or answered
        from the store), after every finished evaluation

    Raises :class:`gfbopt.runtime.InfrastructureError` when the executor lost designs of a
    batch (module docstring): the batch's finished designs are stored, nothing is told.
    """
    from ..runtime import InfrastructureError

    t_start = time.perf_counter()
    fixed = dict(fixed or {})
    run_tasks = run_tasks or _serial
    clash = sorted(set(fixed) & set(problem.names))
    if clash:
        raise ParameterError("fixed", clash[0], "is also a design variable")
    schema = store.schema if store is not None else None
    if store is not None:
        missing = [n for n in [*REQUIRED, *problem.names] if n not in schema]
        if missing:
            raise ParameterError("store", missing[0], "is not a column of the store's schema "
                                 "(make it with store_schema)")
    known = _stored(store)
    writer = _writer(store, schema or {}, flush_rows, flush_seconds)
    init = (np.array([problem.encode(d) for d in initial]) if initial else None)
    method = proposer(problem, settings, init)
    order: list = []            # keys in the order of first asking
    seen: set = set()
    evaluated = reused = repeated = batch = 0
    evaluation_time = 0.0
    stage_of: dict = {}         # stage -> designs asked; stage -> evaluation seconds
    stage_time: dict = {}
    driver = time.perf_counter() - t_start
    try:
        while True:
            t0 = time.perf_counter()
            X = method.ask()
            if X is None:
                driver += time.perf_counter() - t0
                break
            designs = [problem.decode(x) for x in X]
            keys = [problem.key(d) for d in designs]
            stage = getattr(method, "stage", "search")
            stage_of[stage] = stage_of.get(stage, 0) + len(keys)
            stage_time.setdefault(stage, 0.0)
            todo = []
            for key, design in zip(keys, designs):
                if key in seen:
                    repeated += 1
                    continue
                seen.add(key)
                order.append(key)
                if key in known:
                    reused += 1
                else:
                    todo.append((key, design, len(order) - 1))
            driver += time.perf_counter() - t0
            lost: list = []
            if todo:
                arguments = [{"function": evaluate, "point": {**fixed, **d}}
                             for _, d, _ in todo]
                waiting = len(todo)
                for k, result in run_tasks(_task, arguments):
                    if k is None:                   # an executor's tick: nothing finished
                        writer.tick()
                        continue
                    t1 = time.perf_counter()
                    waiting -= 1
                    key, design, index = todo[k]
                    if isinstance(result, BaseException):   # lost by the executor: neither
                        lost.append(result)                  # stored nor told (docstring)
                        continue
                    row = {**{n: v for n, v in result.items() if n not in fixed}, **design,
                           "point": key, "evaluation": index, "batch": batch}
                    row["feasible"] = problem.feasible(row)
                    spent = _number(row.get("wall_time_s"))
                    evaluation_time += spent if math.isfinite(spent) else 0.0
                    stage_time[stage] += spent if math.isfinite(spent) else 0.0
                    known[key] = row
                    writer.add([row])
                    evaluated += 1
                    if progress is not None:
                        progress(min(1.0, (len(order) - waiting) / settings.budget))
                    driver += time.perf_counter() - t1
            t2 = time.perf_counter()
            writer.flush()
            if lost:
                raise InfrastructureError(
                    lost_designs(lost, len(todo), f"designs of batch {batch}") + ": the "
                    "search stopped without telling the optimiser anything of them")
            rows = [known[key] for key in keys]
            F = np.array([problem.objective_vector(r) for r in rows])
            G = np.array([problem.violation_vector(r) for r in rows])
            method.tell(F, G)
            batch += 1
            if progress is not None:
                progress(min(1.0, len(order) / settings.budget))
            driver += time.perf_counter() - t2
    finally:                    # an exception or Ctrl-C keeps the finished rows
        writer.flush()
    table = pd.DataFrame.from_records([known[k] for k in order])
    for column in [*problem.names, *(o.name for o in problem.objectives),
                   *(c.name for c in problem.constraints), "success", "message"]:
        if column not in table:
            table[column] = math.nan
    table["success"] = table["success"].map(lambda v: bool(v) if v is not None and
                                            v == v else False)
    table["feasible"] = [problem.feasible(r) for r in table.to_dict(orient="records")]
    front = pareto_front(table, problem)
    best = front.iloc[0].to_dict() if len(problem.objectives) == 1 and len(front) else None
    status = getattr(method, "status", None) or (
        f"fixed budget {settings.budget} (no convergence test)")
    return OptimisationResult(problem, settings, table, front, best, evaluated, reused,
                              repeated, evaluation_time, driver, time.perf_counter() - t_start,
                              status, tuple(stage_of.items()), tuple(stage_time.items()))
