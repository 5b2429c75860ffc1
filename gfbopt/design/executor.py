"""One process pool for a whole optimisation run (an adapter until the one-pool-per-run
executor of issue 19 lands in :mod:`gfbopt.parallel`).

An optimiser sends one small batch per generation; :func:`gfbopt.parallel.stream_tasks`
starts a new pool of spawn processes for every call, and every new worker pays its imports
and rebuilds its solvers (issue 19 measured the 2-worker main job 1.8× *slower* than one
worker for this reason).  :func:`persistent_pool` keeps one pool, with the same worker set-up
as :mod:`gfbopt.parallel` (BLAS pinned, Ctrl-C left to the parent, exit with the parent,
per-worker solver cache), for every batch of the run, and yields an executor with the
``run_tasks(function, arguments)`` interface of :func:`~gfbopt.design.optimiser.optimise`.

A worker that dies breaks a ``ProcessPoolExecutor`` for good: the tasks it took are yielded
as the exception (the optimiser keeps them out of the store, so a resumed run computes them
again) and the next batch gets a fresh pool.
"""
from __future__ import annotations

import multiprocessing
from collections.abc import Iterator
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager

from .. import parallel


class _Pool:
    def __init__(self, workers: int):
        self.workers = workers
        self.pool = None

    def _start(self) -> ProcessPoolExecutor:
        if self.pool is None:
            self.pool = ProcessPoolExecutor(
                max_workers=self.workers, mp_context=multiprocessing.get_context("spawn"),
                initializer=parallel._start_worker)
        return self.pool

    def run_tasks(self, function, arguments) -> Iterator:
        arguments = list(arguments)
        pool = self._start()
        futures = {pool.submit(parallel._call_task, function, a): k
                   for k, a in enumerate(arguments)}
        pending = set(futures)
        broken = False
        try:
            while pending:
                done, pending = wait(pending, return_when=FIRST_COMPLETED)
                for future in done:
                    try:
                        result = future.result()
                    except BrokenProcessPool as exc:
                        broken = True
                        result = BrokenProcessPool(f"the worker process died ({exc})")
                    yield futures[future], result
        except BaseException:           # Ctrl-C, error, or the consumer closed us
            self.close(terminate=True)
            raise
        if broken:
            self.close(terminate=True)

    def close(self, terminate: bool = False) -> None:
        if self.pool is None:
            return
        if terminate:
            parallel._terminate(self.pool)
        else:
            self.pool.shutdown(wait=True)
        self.pool = None


@contextmanager
def persistent_pool(workers: int = 1, client=None):
    """``with persistent_pool(2) as run_tasks: optimise(..., run_tasks=run_tasks)``.

    workers <= 1: this process; ``client`` (a ``distributed.Client``): its cluster, whose
    workers persist anyway (:func:`gfbopt.parallel.stream_tasks`)."""
    if client is not None or workers <= 1:
        def run_tasks(function, arguments):
            return parallel.stream_tasks(function, arguments, workers=1, client=client)

        yield run_tasks
        return
    pool = _Pool(workers)
    try:
        yield pool.run_tasks
    except BaseException:
        pool.close(terminate=True)
        raise
    pool.close()
