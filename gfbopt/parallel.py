"""Executors: evaluate many independent points, serially or on a pool of processes.

``run_points(function, points, workers=...)`` calls ``function(**point)`` for every point
and returns the rows in the order of ``points``, whichever executor ran them:

* ``workers <= 1`` (or a single point): in this process, one :class:`SolverCache` for the
  call (or the ``cache`` given);
* ``workers > 1``: a pool of ``spawn`` processes.  IPOPT/MUMPS is not thread-safe and a CasADi
  solver cannot be pickled, so only the points travel; every worker builds its solvers
  itself, once per (grid, film, structure), in its **per-worker solver cache** — the one
  piece of module-level state in gfbopt, created by the worker initialiser
  (:func:`_start_worker`) and living as long as the worker process.  The initialiser also
  pins BLAS to one thread (:func:`limit_blas_threads`) and makes the worker ignore Ctrl-C,
  which the parent handles: on Ctrl-C the pending points are cancelled, the workers are
  terminated and ``KeyboardInterrupt`` is raised again.

Workers are started with ``spawn``: a script that runs points on workers must guard its
top level with ``if __name__ == "__main__":`` (as any multiprocessing program).

A function that accepts a ``cache`` keyword receives the solver cache.  It returns one row
(a dict) or a list of rows; a point that raises becomes one row with ``success = False``
and ``message`` = the error, so a sweep never loses what it computed.  ``tags`` add label
columns (not arguments of ``function``) in front of each point's rows; a tag wins over a
column of the same name that the function returns.
"""
from __future__ import annotations

import inspect
import multiprocessing
import signal
import time
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool

from .static import SolverCache

#: The per-worker solver cache (set in each pool worker by :func:`_start_worker`).
_WORKER_CACHE: SolverCache | None = None


def limit_blas_threads() -> None:
    """One BLAS/OpenMP thread in this process (threadpoolctl): gfbopt's linear algebra is
    many small sparse factorisations, which multi-threaded BLAS slows down, and the
    workers of a pool would otherwise compete for the same cores."""
    from threadpoolctl import threadpool_limits

    threadpool_limits(1)


def _start_worker() -> None:
    """Initialiser of a pool worker: BLAS pinned, Ctrl-C left to the parent, empty cache."""
    global _WORKER_CACHE
    import os

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # libraries loaded later in the worker (IPOPT/MUMPS and their OpenMP runtime, when the
    # first solver is built) read these at load time; threadpoolctl covers those already loaded
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[var] = "1"
    limit_blas_threads()
    _WORKER_CACHE = SolverCache()
    _exit_with_parent()


def _exit_with_parent(period: float = 1.0) -> None:
    """End this worker within ``period`` seconds of its parent's death (``kill -9`` of the
    driver): a daemon thread polls the parent pid (the worker is re-parented when the
    driver dies), so no orphaned worker keeps computing points nobody will store."""
    import os
    import threading

    parent = os.getppid()

    def watch() -> None:
        while True:
            time.sleep(period)
            if os.getppid() != parent:
                os._exit(1)

    threading.Thread(target=watch, name="gfbopt-parent-watch", daemon=True).start()


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
            kwargs["cache"] = cache if cache is not None else _WORKER_CACHE
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
    workers : number of processes; 1 runs in this process
    tags : per point, columns put in front of its rows (labels such as the variant)
    progress : called with the fraction of points done, e.g. a terminal progress bar
    cache : solver cache for the serial executor (a new one when None); ignored by the pool

    Returns
    -------
    list of rows (dicts): each with ``success``, ``wall_time_s`` and, on failure,
    ``message``.
    """
    points = list(points)
    tags = [{} for _ in points] if tags is None else list(tags)
    if len(tags) != len(points):
        raise ValueError("tags must have one entry per point")
    if workers <= 1 or len(points) <= 1:
        cache = cache if cache is not None else SolverCache()
        results = []
        for k, point in enumerate(points):
            results.append(_evaluate(function, point, cache))
            if progress is not None:
                progress((k + 1) / len(points))
    else:
        results = _run_pool(function, points, workers, progress)
    return [{**tag, **row, **tag} for tag, rows in zip(tags, results) for row in rows]


def _run_pool(function: Callable, points: list, workers: int, progress) -> list[list[dict]]:
    context = multiprocessing.get_context("spawn")
    pool = ProcessPoolExecutor(max_workers=min(workers, len(points)), mp_context=context,
                               initializer=_start_worker)
    results: list = [None] * len(points)
    try:
        futures = {pool.submit(_in_worker, function, p): k for k, p in enumerate(points)}
        pending = set(futures)
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for future in done:
                k = futures[future]
                try:
                    results[k] = future.result()
                except BrokenProcessPool as exc:
                    results[k] = [{"success": False, "message": "the worker process died "
                                   f"(BrokenProcessPool: {exc})"}]
            if progress is not None:
                progress(sum(r is not None for r in results) / len(points))
    except BaseException:                 # Ctrl-C or an error in the parent: stop the workers
        _terminate(pool)
        raise
    pool.shutdown(wait=True)
    return results


def _terminate(pool: ProcessPoolExecutor) -> None:
    """Cancel the pending points and end the workers now (they ignore SIGINT)."""
    processes = list(getattr(pool, "_processes", {}).values())  # no public API before 3.14
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        if process.is_alive():
            process.terminate()
    for process in processes:
        process.join(timeout=5)


# ====================================================================== streaming executors
# Design-of-experiments studies (gfbopt.studies.doe) send *tasks* — a function and a chunk of
# neighbouring points — and want the rows as each task finishes, to write them to the results
# store in batches.  :func:`stream_tasks` yields ``(index, result)`` in completion order from
# this process, a local pool of spawn processes, or a Dask distributed cluster.

def worker_cache() -> SolverCache:
    """The solver cache of this process: the per-worker cache of a pool worker or of a Dask
    worker process (created on first use, with BLAS pinned to one thread), one build per
    (grid, film, structure) for the life of the process."""
    global _WORKER_CACHE
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
    """A ``distributed.Client`` on the Dask scheduler at ``address``; ParameterError naming
    the address when it cannot be reached (or dask.distributed is not installed)."""
    from .errors import ParameterError

    try:
        from distributed import Client
    except ImportError:  # pragma: no cover - optional extra
        raise ParameterError("--scheduler", address, "needs dask[distributed] "
                             "(pip install 'gfbopt[dask]')") from None
    try:
        return Client(address, timeout=timeout, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as exc:
        raise ParameterError("--scheduler", address, f"cannot be reached "
                             f"({type(exc).__name__}: {str(exc).splitlines()[0][:120]})"
                             ) from None


def _call_task(function: Callable, argument):
    """Run one task in a worker; an exception is returned (as data), never raised."""
    try:
        return function(argument)
    except Exception as exc:  # noqa: BLE001 - a failed task is rows with its error
        return exc


def stream_tasks(function: Callable, arguments: Sequence, *, workers: int = 1,
                 client=None):
    """Yield ``(k, function(arguments[k]))`` as each task finishes (completion order).

    ``client``: a ``distributed.Client`` — the tasks run on its cluster (only the
    arguments travel; a worker's solvers live in its process, :func:`worker_cache`).
    Otherwise ``workers > 1`` runs a pool of spawn processes (BLAS pinned, Ctrl-C left to
    the parent, terminated on Ctrl-C or error) and ``workers <= 1`` runs here.  A task that
    raised yields the exception object; a worker that died yields a BrokenProcessPool error.
    Closing the generator early (Ctrl-C in the consumer) cancels the pending tasks.
    """
    arguments = list(arguments)
    if client is not None:
        yield from _stream_dask(function, arguments, client)
    elif workers <= 1 or len(arguments) <= 1:
        for k, argument in enumerate(arguments):
            yield k, _call_task(function, argument)
    else:
        yield from _stream_pool(function, arguments, workers)


def _stream_pool(function: Callable, arguments: list, workers: int):
    context = multiprocessing.get_context("spawn")
    pool = ProcessPoolExecutor(max_workers=min(workers, len(arguments)), mp_context=context,
                               initializer=_start_worker)
    try:
        futures = {pool.submit(_call_task, function, a): k for k, a in enumerate(arguments)}
        pending = set(futures)
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for future in done:
                try:
                    result = future.result()
                except BrokenProcessPool as exc:
                    result = BrokenProcessPool(f"the worker process died ({exc})")
                yield futures[future], result
    except BaseException:                 # Ctrl-C, error, or the consumer closed us
        _terminate(pool)
        raise
    pool.shutdown(wait=True)


def _stream_dask(function: Callable, arguments: list, client):
    from distributed import as_completed

    futures = client.map(_call_task, [function] * len(arguments), arguments, pure=False)
    index = {f.key: k for k, f in enumerate(futures)}
    try:
        for future in as_completed(futures, loop=client.loop):
            try:
                result = future.result()
            except Exception as exc:  # noqa: BLE001 - a lost worker, a killed task
                result = exc
            yield index[future.key], result
    except BaseException:
        client.cancel(futures)
        raise
