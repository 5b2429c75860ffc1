"""The process pool's streaming loop: tasks in, ``(index, result)`` out as each finishes.

:func:`stream_pool` is what :func:`gfbopt.parallel.stream_tasks` runs for ``workers > 1``.
It keeps **at most** ``in_flight`` tasks submitted (default: twice the pool's workers) and
waits on those alone: a ``concurrent.futures.wait`` costs time in proportion to the futures
it watches, so waiting on every pending future of a 10⁵-point sweep after each completion
made the driver's cost quadratic (119 s CPU of driver at 10⁵ points of a 1 ms analysis).
Tasks are submitted in index order; the results come in completion order, as before, and a
consumer that wants them in order sorts by index (:func:`gfbopt.parallel.run_points` does).

A pool that breaks (a worker killed, the OOM killer) fails the tasks it held: those are run
again on a fresh pool, each at most ``retries`` times, then yield
:class:`gfbopt.runtime.InfrastructureFailure`; tasks not yet submitted were never tried and
count no attempt.  Closing the generator early (Ctrl-C in the consumer, an error) ends the
workers at once.
"""
from __future__ import annotations

import contextlib
import gc
import warnings
from collections import deque
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, CancelledError, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Optional

from .runtime import InfrastructureFailure, call_task

#: tasks kept submitted per worker: one running, one queued so a worker never idles
IN_FLIGHT_PER_WORKER = 2


@contextlib.contextmanager
def forking(fork: bool):
    """Around the submits that fork: the driver's objects frozen out of the collector
    (:func:`gc.freeze`: a worker neither finalises the driver's garbage, a temporary folder
    or a buffered file, nor copies the pages a collection touches); Python >= 3.12's warning
    of a fork beside (fork-safe) native threads is not shown."""
    if not fork:
        yield
        return
    gc.freeze()
    try:
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", r".*use of fork\(\) may lead to deadlocks",
                                    DeprecationWarning)
            yield
    finally:
        gc.unfreeze()


def _failure(attempts: int) -> InfrastructureFailure:
    return InfrastructureFailure(
        f"the worker process died on {attempts} pools in a row (killed "
        "or out of memory); not a result of these points")


def stream_pool(function: Callable, arguments: list, pool, retries: int,
                tick: Optional[float], in_flight: Optional[int] = None):
    """Yield ``(k, call_task(function, arguments[k]))`` in completion order on ``pool``
    (a :class:`gfbopt.parallel.WorkerPool`); ``(None, None)`` when no task finished for
    ``tick`` seconds.  ``in_flight``: tasks kept submitted (default 2 per worker)."""
    todo = list(range(len(arguments)))
    attempts = [0] * len(arguments)
    while todo:
        queue = deque(todo)
        failed: list[int] = []
        running: dict = {}
        try:
            executor = pool.executor(len(queue))
            limit = in_flight or IN_FLIGHT_PER_WORKER * max(1, pool.workers)
            while queue or running:
                if queue and len(running) < limit and not failed:
                    with forking(pool.method == "fork"):   # a fork pool forks at its first submit
                        while queue and len(running) < limit:
                            k = queue[0]
                            try:
                                future = executor.submit(call_task, function, arguments[k])
                            except BrokenProcessPool:
                                failed.append(queue.popleft())
                                break
                            running[future] = queue.popleft()
                if not running:
                    break
                done, _ = wait(running, timeout=tick, return_when=FIRST_COMPLETED)
                if not done:
                    yield None, None
                    continue
                for future in sorted(done, key=running.get):
                    k = running.pop(future)
                    try:
                        result = future.result()
                    except (BrokenProcessPool, CancelledError):
                        failed.append(k)
                        continue
                    yield k, result
        except BaseException:             # Ctrl-C, error, or the consumer closed us
            pool.terminate()
            raise
        if not failed:
            return
        pool.restart()
        todo = sorted(failed + list(queue))
        for k in sorted(failed):
            attempts[k] += 1
            if attempts[k] > retries:
                todo.remove(k)
                yield k, _failure(attempts[k])
