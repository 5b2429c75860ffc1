"""Executors: evaluate many independent points, serially or on a pool of processes.

``run_points(function, points, workers=...)`` calls ``function(**point)`` for every point
and returns the rows in the order of ``points``, whichever executor ran them:

* ``workers <= 1`` (or a single point): in this process, with one :class:`SolverCache`
  (the ``cache`` given, the run's serial cache inside :class:`WorkerPool`, or a new one);
* ``workers > 1``: a pool of processes (:func:`start_method`).  IPOPT/MUMPS is not thread-safe and a CasADi
  solver cannot be pickled, so only the points travel; every worker builds its solvers
  itself, once per (grid, film, structure), in its **per-worker solver cache** — created by
  the worker initialiser (:func:`_start_worker`) and living as long as the worker process.
  The initialiser also pins BLAS to one thread (:func:`limit_blas_threads`) and makes the
  worker ignore Ctrl-C, which the parent handles: on Ctrl-C the pending points are
  cancelled, the workers are terminated and ``KeyboardInterrupt`` is raised again.

**One pool per run.**  ``with WorkerPool(workers):`` opens one pool for everything inside
the block: every ``run_points``/``stream_tasks`` call with ``workers > 1`` reuses its
processes (and so their solver caches and imports) instead of starting a pool per batch —
``gfbopt run`` opens one around all its studies.  The pool starts workers only as tasks
need them (at most ``workers``); a forked worker holds the modules the driver had imported, a
spawned one imports gfbopt's numerical core (``gfbopt.static``) and then what a task's
function needs (cvxpy only where a geometric program runs).  Outside such a block each call starts and ends its own pool, as before.

**Infrastructure failures are not results.**  A worker that dies (SIGKILL, the OOM killer)
breaks the pool: the tasks that had not finished are run again on a fresh pool, up to
``retries`` times each; a task that still cannot run is reported as
:class:`InfrastructureFailure` (never as a failed point of the analysis).  A stream keeps at
most two tasks per worker submitted (:mod:`gfbopt.pool_stream`): the driver's cost stays in
proportion to the tasks (10⁵ points of a 0.3 ms analysis: 4.8 s of driver CPU, 25.9 s
when every task was submitted at once; results/benchmarks/pool_stream.json).

**How workers start** (:func:`start_method`, the pool's fixed cost).  A spawned worker starts a
new interpreter and imports what its tasks need: 2.5 s CPU per worker for the bearing-pair
design (``gfbopt.design.optimiser`` and the studies behind it), so on a busy machine
``--workers 2`` cost more CPU than it saved.  On Linux the pool now **forks** the driver,
which has imported nearly all of it (0.14 s CPU per worker; the preloaded forkserver 1.4 s:
benchmarks/bench_pool.py), *when forking is safe*: no other Python thread runs in the
driver (a lock another thread holds would stay locked in the child) and no OpenMP runtime is
loaded (libgomp's thread pool does not survive a fork).  The native threads gfbopt's
libraries do start — OpenBLAS's and jemalloc's (pyarrow) — re-create themselves after a fork
(pthread_atfork); CasADi starts none, and a worker never uses the driver's solvers: it gets
an empty cache of its own and forgets the driver's run pool and signal state.  A fork pool
starts its workers all at once, so it is sized to the first batch (at most ``workers``) and
re-made larger when a later batch could use more; a broken pool's threads are joined before
the restart, so the new pool forks too.  Otherwise (a Dask client's threads, an OpenMP
runtime, a thread of the calling program, macOS) the workers come from a
``forkserver`` that has preloaded the gfbopt modules the driver had imported: one import for
the whole pool, then a fork per worker.  A script that runs points on workers must still
guard its top level with ``if __name__ == "__main__":`` (as any multiprocessing program).

A function that accepts a ``cache`` keyword receives the solver cache.  It returns one row
(a dict) or a list of rows; a point that raises becomes one row with ``success = False``
and ``message`` = the error, so a sweep never loses what it computed.  ``tags`` add label
columns (not arguments of ``function``) in front of each point's rows; a tag wins over a
column of the same name that the function returns.
"""
from __future__ import annotations

import contextlib
import contextvars
import inspect
import os
import multiprocessing
import re
import signal
import sys
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from typing import Optional

from .pool_stream import stream_pool
from .runtime import (  # noqa: F401 - re-exported: the executors' failures and signals
    InfrastructureError,
    InfrastructureFailure,
    Interrupted,
    call_task as _call_task,
    check_interrupted,
    interrupt_on_signals,
    forget_signals,
    interrupted,
)
from .static import SolverCache
from .threads import THREAD_VARIABLES, pin_threads, solver_threads

#: The per-worker solver cache (set in each pool worker by :func:`_start_worker`).
_WORKER_CACHE: SolverCache | None = None
#: The pool of the run in progress (``with WorkerPool(...)``), if any.
_ACTIVE_POOL: contextvars.ContextVar = contextvars.ContextVar("gfbopt_pool", default=None)
#: times a task is run again after the pool it ran on broke
DEFAULT_RETRIES = 2
#: start methods a pool accepts (None: :func:`start_method` decides)
START_METHODS = ("fork", "forkserver", "spawn")
#: OpenMP runtimes, whose thread pool does not survive a fork (a loaded one rules fork out)
_OPENMP = re.compile(r"/lib(gomp|iomp5|omp)[-.][^/]*$")


def choose_start_method(platform: str, other_threads: int, openmp_loaded: bool) -> str:
    """The start method of a pool's workers: ``fork`` on Linux when the driver runs no other
    Python thread and has loaded no OpenMP runtime, else ``forkserver`` (POSIX), else
    ``spawn`` (Windows).  macOS is never forked (its system frameworks are not fork-safe)."""
    if platform.startswith("linux") and other_threads == 0 and not openmp_loaded:
        return "fork"
    return "spawn" if platform.startswith("win") else "forkserver"


def default_workers(cores: int, load: float) -> int:
    """Worker processes the machine can give: its free cores, ``cores - load`` (``load`` the
    one-minute load average) rounded to whole cores (a core is free when at least half idle),
    at most ``cores``, at least 1.  2 cores: 2 workers up to a load of 0.5, 1 above."""
    import math

    free = float(cores) - max(0.0, float(load)) if math.isfinite(load) else 1.0
    return max(1, min(int(cores), math.floor(free + 0.5)))


def _openmp_loaded() -> bool:  # no /proc: assume the worst
    try:
        with open("/proc/self/maps") as maps:
            return any(_OPENMP.search(line.rstrip()) for line in maps)
    except OSError:
        return True


def start_method() -> str:
    """How this process would start pool workers now (:func:`choose_start_method` on its
    platform, its other Python threads and its loaded libraries)."""
    return choose_start_method(sys.platform, threading.active_count() - 1,
                               sys.platform.startswith("linux") and _openmp_loaded())


def _preloaded_modules() -> list[str]:
    """The gfbopt modules this process has imported: what the forkserver imports once."""
    return sorted(name for name in list(sys.modules) if name.split(".")[0] == "gfbopt")


def limit_blas_threads() -> None:
    """One BLAS/OpenMP thread for the rest of this process, whatever the environment says
    (:func:`gfbopt.threads.pin_threads`): pool workers would otherwise compete for cores."""
    pin_threads(keep_user_choice=False)


def _start_worker(driver: Optional[int] = None) -> None:
    """Initialiser of a pool worker: BLAS pinned, signals left to the parent, empty cache;
    ``driver`` the pid of the process that made the pool (watched with the parent)."""
    global _WORKER_CACHE
    import os

    # signals go to the driver, which writes what finished and then ends the workers
    # (SIGKILL); a SIGTERM sent to the whole process group does not break the pool
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    # libraries loaded later in the worker (IPOPT/MUMPS and their OpenMP runtime, when the
    # first solver is built) read these at load time; threadpoolctl covers those already loaded
    for var in THREAD_VARIABLES:
        os.environ[var] = "1"
    limit_blas_threads()
    _WORKER_CACHE = SolverCache()
    _ACTIVE_POOL.set(None)          # a forked worker forgets the driver's pool and signals
    forget_signals()
    _exit_with_parent(driver=driver)


def _alive(pid: int) -> bool:
    import os

    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _exit_with_parent(period: float = 1.0, driver: Optional[int] = None) -> None:
    """End this worker within ``period`` seconds of its parent's death (``kill -9`` of the
    driver): a daemon thread polls the parent pid (the worker is re-parented when the
    driver dies), so no orphaned worker keeps computing points nobody will store.  A
    forkserver's worker has the forkserver as its parent, which outlived a killed driver
    (a test's SIGKILL left the forkserver and both workers running): it also watches
    ``driver``, the pid of the process that made the pool."""
    import os

    parent = os.getppid()
    driver = None if driver in (None, parent) else int(driver)

    def watch() -> None:
        while True:
            time.sleep(period)
            if os.getppid() != parent or (driver is not None and not _alive(driver)):
                os._exit(1)

    threading.Thread(target=watch, name="gfbopt-parent-watch", daemon=True).start()


# ====================================================================== the run's pool
class WorkerPool:
    """One pool of worker processes for a whole run (see the module docstring).

    ``with WorkerPool(workers) as pool:`` makes it the pool of every ``run_points`` and
    ``stream_tasks`` call inside the block; it is closed (workers ended) when the block
    ends, terminated at once on an exception or Ctrl-C.  ``workers <= 1`` runs everything
    in this process with one solver cache for the whole run (:attr:`cache`).
    ``started`` counts the worker processes started (restarts after a broken pool too);
    ``method`` is the current (or last) executor's start method; ``start_method`` forces one
    of :data:`START_METHODS` (default: :func:`start_method` when the executor is made).
    """

    def __init__(self, workers: int = 1, start_method: Optional[str] = None):
        if start_method is not None and start_method not in START_METHODS:
            raise ValueError(f"start_method = {start_method!r}: one of {START_METHODS}")
        self.workers = max(1, int(workers))
        self.cache = SolverCache()
        self.started = 0
        self.restarts = 0
        self.start_method = start_method
        self.method: Optional[str] = None
        self._size = 0
        self._executor: Optional[ProcessPoolExecutor] = None
        self._token = None

    def executor(self, tasks: Optional[int] = None) -> ProcessPoolExecutor:
        """The live executor for a batch of ``tasks`` (created on first use).  Spawn and
        forkserver workers start as tasks need them; a fork pool starts all its workers at
        once, so it gets ``min(workers, tasks)`` and is re-made when a batch could use more."""
        wanted = self.workers if tasks is None else max(1, min(self.workers, tasks))
        if self._executor is not None and self._size < wanted:
            self.close()                               # a fork pool too small for this batch
        if self._executor is None:
            method = self.start_method or start_method()
            context = multiprocessing.get_context(method)
            if method == "forkserver":
                context.set_forkserver_preload(_preloaded_modules())  # once per forkserver
            elif method == "fork":
                sys.stdout.flush()                     # or the children write it again
                sys.stderr.flush()
            self._size = wanted if method == "fork" else self.workers
            self.method = method
            self._executor = ProcessPoolExecutor(max_workers=self._size, mp_context=context,
                                                 initializer=_start_worker,
                                                 initargs=(os.getpid(),))
        return self._executor

    def _processes(self) -> list:
        return list(getattr(self._executor, "_processes", {}).values())  # no public API < 3.14

    def restart(self) -> None:
        """End the current (broken) executor; the next task starts a fresh one."""
        self.terminate()
        self.restarts += 1

    def terminate(self) -> None:
        """Cancel pending tasks and end the workers now (they ignore SIGINT)."""
        if self._executor is None:
            return
        processes = self._processes()
        self.started += len(processes)
        manager = getattr(self._executor, "_executor_manager_thread", None)   # no public API
        self._executor.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            if process.is_alive():
                process.kill()            # workers ignore SIGINT and SIGTERM
        for process in processes:
            process.join(timeout=5)
        if manager is not None and manager is not threading.current_thread():
            manager.join(timeout=5)       # its threads gone, the next pool may fork again
        self._executor = None

    def close(self) -> None:
        """Wait for the running tasks and end the workers."""
        if self._executor is not None:
            self.started += len(self._processes())
            self._executor.shutdown(wait=True)
            self._executor = None

    def __enter__(self) -> "WorkerPool":
        self._token = _ACTIVE_POOL.set(self)
        return self

    def __exit__(self, kind, value, tb) -> None:
        _ACTIVE_POOL.reset(self._token)
        if kind is None:
            self.close()
        else:
            self.terminate()


def active_pool() -> Optional[WorkerPool]:
    """The pool of the run in progress (``with WorkerPool(...)``), or None."""
    return _ACTIVE_POOL.get()


@contextlib.contextmanager
def _pool_for(workers: int, n_tasks: int):
    """The run's pool when one is open (and parallel), else a pool for this call only."""
    pool = active_pool()
    if pool is not None and pool.workers > 1:
        yield pool
        return
    own = WorkerPool(min(workers, n_tasks))
    try:
        yield own
    except BaseException:
        own.terminate()
        raise
    own.close()


def _takes_cache(function: Callable) -> bool:
    try:
        return "cache" in inspect.signature(function).parameters
    except (TypeError, ValueError):
        return False


def _evaluate(function: Callable, point: dict, cache: SolverCache | None) -> list[dict]:
    """``function(**point)`` as a list of rows; an exception becomes one failed row."""
    t0 = time.perf_counter()
    try:
        kwargs = dict(point)
        if _takes_cache(function):
            kwargs["cache"] = cache if cache is not None else worker_cache()
        out = function(**kwargs)
        rows = [dict(r) for r in (out if isinstance(out, list) else [out])]
        for row in rows:
            row.setdefault("success", True)
    except Exception as exc:  # a failed point is data, not a crash of the sweep
        rows = [{"success": False, "message": f"{type(exc).__name__}: {exc}"}]
    for row in rows:
        row.setdefault("wall_time_s", time.perf_counter() - t0)
    return rows


def _in_worker(function: Callable, point: dict) -> list[dict]:
    return _evaluate(function, point, None)


def run_points(function: Callable, points: Sequence[dict], *, workers: int = 1,
               tags: Sequence[dict] | None = None,
               progress: Callable[[float], None] | None = None,
               cache: SolverCache | None = None) -> list[dict]:
    """Evaluate ``function(**point)`` for every point; rows in the order of ``points``.

    Parameters
    ----------
    function : a module-level function (it is pickled to the workers) returning a dict or a
        list of dicts; it receives the solver cache as ``cache=`` if it accepts that keyword
    points : keyword arguments of each call (picklable: numbers, strings, frozen inputs)
    workers : number of processes; 1 runs in this process (inside ``with WorkerPool(n)``
        the run's pool is used whatever ``workers`` > 1 says)
    tags : per point, columns put in front of its rows (labels such as the variant)
    progress : called with the fraction of points done, e.g. a terminal progress bar
    cache : solver cache for the serial executor (default: the run's, or a new one)

    Returns
    -------
    list of rows (dicts): each with ``success``, ``wall_time_s`` and, on failure,
    ``message``.  A point whose worker kept dying is a failed row saying so.
    """
    points = list(points)
    tags = [{} for _ in points] if tags is None else list(tags)
    if len(tags) != len(points):
        raise ValueError("tags must have one entry per point")
    run_pool = active_pool()
    if workers <= 1 or len(points) <= 1 or (run_pool is not None and run_pool.workers <= 1):
        if cache is None:
            cache = run_pool.cache if run_pool is not None else SolverCache()
        results = []
        with solver_threads():           # one BLAS thread for the whole batch
            for k, point in enumerate(points):
                results.append(_evaluate(function, point, cache))
                check_interrupted()          # a solver may have swallowed SIGTERM/SIGINT
                if progress is not None:
                    progress((k + 1) / len(points))
    else:
        results = [None] * len(points)
        for k, result in stream_tasks(_call_points, [(function, p) for p in points],
                                      workers=workers):
            check_interrupted()
            results[k] = result if isinstance(result, list) else [
                {"success": False, "message": f"{type(result).__name__}: {result}"}]
            if progress is not None:
                progress(sum(r is not None for r in results) / len(points))
    return [{**tag, **row, **tag} for tag, rows in zip(tags, results) for row in rows]


def _call_points(argument) -> list[dict]:
    function, point = argument
    return _evaluate(function, point, None)


# ====================================================================== streaming executors
# Design-of-experiments studies (gfbopt.studies.doe, gfbopt.doe.run_doe) send *tasks* — a
# function and a chunk of neighbouring points — and want the rows as each task finishes, to
# write them to the results store.  :func:`stream_tasks` yields ``(index, result)`` in
# completion order from this process, a pool of worker processes, or a Dask cluster.

def worker_cache() -> SolverCache:
    """The solver cache of this process: the per-worker cache of a pool worker or of a Dask
    worker process (created on first use, with BLAS pinned to one thread), one build per
    (grid, film, structure) for the life of the process.  In the driver inside a
    :class:`WorkerPool` block: the run's serial cache."""
    global _WORKER_CACHE
    run_pool = active_pool()
    if run_pool is not None:
        return run_pool.cache
    if _WORKER_CACHE is None:
        limit_blas_threads()
        _WORKER_CACHE = SolverCache()
    return _WORKER_CACHE


def worker_name() -> str:
    """host:pid of this process (the ``worker`` column of a study table)."""
    import os
    import socket

    return f"{socket.gethostname()}:{os.getpid()}"


def connect_scheduler(address: str, timeout: float = 10.0):
    """A ``distributed.Client`` on the Dask scheduler at ``address`` (see
    :func:`gfbopt.cluster.connect_scheduler`)."""
    from .cluster import connect_scheduler as connect

    return connect(address, timeout=timeout)


def stream_tasks(function: Callable, arguments: Sequence, *, workers: int = 1,
                 client=None, retries: int = DEFAULT_RETRIES, tick: Optional[float] = None,
                 status: Optional[Callable[[str], None]] = None):
    """Yield ``(k, function(arguments[k]))`` as each task finishes (completion order).

    ``client``: a ``distributed.Client`` — the tasks run on its cluster
    (:func:`gfbopt.cluster.stream_dask`).  Otherwise ``workers > 1`` runs on the run's
    :class:`WorkerPool` (or a pool for this call) and ``workers <= 1`` runs here.  A task
    that raised yields the exception object; a task whose worker died is run again on a
    fresh pool up to ``retries`` times, then yields :class:`InfrastructureFailure`.
    ``tick`` (seconds): also yield ``(None, None)`` whenever no task finished for that long,
    so the consumer can write what it holds.  Closing the generator early (Ctrl-C in the
    consumer) cancels the pending tasks and ends the workers.
    """
    arguments = list(arguments)
    run_pool = active_pool()
    if client is not None:
        from .cluster import stream_dask

        yield from stream_dask(function, arguments, client, retries=retries, tick=tick,
                               status=status)
    elif workers <= 1 or len(arguments) <= 1 or (run_pool is not None
                                                 and run_pool.workers <= 1):
        for k, argument in enumerate(arguments):
            yield k, _call_task(function, argument)
    else:
        with _pool_for(workers, len(arguments)) as pool:
            yield from stream_pool(function, arguments, pool, retries, tick)
