"""Running chunks of points into a results store so that nothing finished is lost.

Shared by the sampled studies (:mod:`gfbopt.studies.doe`) and the Python route
(:func:`gfbopt.doe.run_doe`).  :func:`execute` sends the chunks to an executor
(:func:`gfbopt.parallel.stream_tasks`: this process, the run's pool, a Dask cluster) and
writes the rows to the store:

* **in batches, and on a timer**: the rows the driver holds are written when there are
  ``batch_rows`` of them, and by a timer thread at most ``flush_s`` (10 s) after the first
  of them arrived — also while chunks are still in flight — so a ``kill -9`` loses at
  most ``flush_s`` of finished work held by the driver (plus the chunks being computed,
  which were never finished).  In this process (one worker) rows arrive point by point.
* **signals**: SIGTERM and SIGINT raise :class:`gfbopt.parallel.Interrupted`; the buffer is
  written before it propagates (``finally``), and the workers are stopped.
* **infrastructure failures are not stored**: a chunk whose workers kept dying (or a lost
  cluster) is reported in :attr:`Outcome.lost` and computed by the next ``--resume``; only
  failures of the analysis itself are rows (``success = false`` and the error).
"""
from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Optional

#: seconds after which rows held by the driver are written, whatever their number
FLUSH_S = 10.0


@dataclass
class Outcome:
    """What :func:`execute` did: rows written, points lost to infrastructure failures (not
    stored), parts written, and why it stopped early (the exception, re-raised)."""

    rows: int = 0
    parts: int = 0
    lost: list = field(default_factory=list)


class RowBuffer:
    """Rows held by a driver until written to a results store — the one row buffer of the
    sampled studies (:func:`execute`, with a timer thread) and of the design optimiser
    (:func:`gfbopt.design.optimiser.optimise`, which calls :meth:`tick` as rows arrive and
    on the executor's ticks).

    Rows are written in parts of at most ``batch_rows``: when that many are held, on
    :meth:`flush`, and once the oldest row held is ``flush_s`` old (:meth:`tick` or the
    :meth:`timer` thread).  ``conform(row)`` makes a row the store's (e.g. its columns
    only); ``outcome`` counts the rows and parts written; ``store`` None: nothing is kept.
    """

    def __init__(self, store, conform: Callable[[dict], dict], batch_rows: int,
                 flush_s: float, outcome: Optional[Outcome] = None):
        self.store = store
        self.conform = conform
        self.batch_rows = batch_rows
        self.flush_s = flush_s
        self.outcome = outcome if outcome is not None else Outcome()
        self.rows: list = []
        self.oldest = None
        self.lock = threading.Lock()
        self.error: Optional[BaseException] = None

    def add(self, rows: Iterable[dict]) -> None:
        if self.store is None:
            return
        with self.lock:
            for row in rows:
                self.rows.append(self.conform(row))
            if self.rows and self.oldest is None:
                self.oldest = time.monotonic()
            due = len(self.rows) >= self.batch_rows
        if due:
            self.flush()
        else:
            self.tick()

    def flush(self) -> None:
        """Write the rows held, in parts of at most ``batch_rows`` (a Dask task may bring
        thousands of rows at once)."""
        with self.lock:
            while self.rows:
                part = self.rows[:self.batch_rows]
                self.store.append(part)
                self.outcome.rows += len(part)
                self.outcome.parts += 1
                del self.rows[:len(part)]
            self.oldest = None

    def due(self) -> bool:
        return self.oldest is not None and time.monotonic() - self.oldest >= self.flush_s

    def tick(self) -> None:
        """Write the rows held if the oldest is ``flush_s`` old."""
        if self.due():
            self.flush()

    def timer(self, stop: threading.Event) -> None:
        """Thread body: write the rows once they are ``flush_s`` old."""
        period = max(0.05, min(1.0, self.flush_s / 4))
        while not stop.wait(period):
            if self.due():
                try:
                    self.flush()
                except BaseException as exc:  # noqa: BLE001 - reported by the main thread
                    self.error = exc
                    return


#: the earlier private name (tests and callers of before)
_Buffer = RowBuffer


def execute(function: Callable, tasks: list, store, *, conform: Callable[[dict], dict],
            batch_rows: int = 256, workers: int = 1, client=None,
            iterate: Optional[Callable] = None, failed_rows: Optional[Callable] = None,
            progress: Optional[Callable[[int], None]] = None, flush_s: float = FLUSH_S,
            status: Optional[Callable[[str], None]] = None) -> Outcome:
    """Run ``function(task)`` (a list of rows) for every task and write the rows to ``store``.

    ``iterate(task)``: an iterator over the same rows, used in this process so rows arrive
    point by point; ``failed_rows(task, error)``: rows for a task that raised as a whole (an
    error of the analysis); ``progress(n)``: called with the number of rows just finished.
    Tasks carry their points in ``task["points"]`` (each with its ``point`` key).
    Exceptions (Ctrl-C, SIGTERM, a lost cluster) propagate after the buffer is written.
    """
    from ..parallel import (
        InfrastructureFailure,
        active_pool,
        check_interrupted,
        interrupt_on_signals,
        stream_tasks,
    )

    outcome = Outcome()
    buffer = RowBuffer(store, conform, batch_rows, flush_s, outcome)
    stop = threading.Event()
    timer = threading.Thread(target=buffer.timer, args=(stop,), name="gfbopt-flush",
                             daemon=True)
    run_pool = active_pool()
    serial = client is None and (workers <= 1 or len(tasks) <= 1 or (
        run_pool is not None and run_pool.workers <= 1))

    def take(rows: list) -> None:
        if buffer.error is not None:
            raise buffer.error
        buffer.add(rows)
        if progress is not None:
            progress(len(rows))

    timer.start()
    try:
        with interrupt_on_signals():
            if serial and iterate is not None:
                for task in tasks:
                    for row in iterate(task):
                        # a row computed here while a signal arrived is dropped (its solve
                        # may have been cut short: CasADi turns the interrupt into a failed
                        # solve); the point is computed again on resume
                        check_interrupted()
                        take([row])
            else:
                stream = stream_tasks(function, tasks, workers=workers, client=client,
                                      tick=min(1.0, flush_s), status=status)
                try:
                    for k, result in stream:
                        if k is None:
                            check_interrupted()
                            if buffer.error is not None:
                                raise buffer.error
                            continue
                        if isinstance(result, InfrastructureFailure):
                            outcome.lost += [p["point"] for p in tasks[k]["points"]]
                            continue
                        if not isinstance(result, list):
                            result = failed_rows(tasks[k], result) if failed_rows else []
                        take(result)              # a worker's rows are whole: kept
                        check_interrupted()
                finally:
                    stream.close()
    finally:                                # Ctrl-C, SIGTERM, a lost cluster: keep the rows
        stop.set()
        timer.join()
        with _signals_ignored():
            buffer.flush()
    return outcome


class _signals_ignored:
    """A second SIGTERM/SIGINT while the last rows are written does not cut the write."""

    def __enter__(self):
        import signal

        self.previous = {}
        if threading.current_thread() is threading.main_thread():
            for s in (signal.SIGTERM, signal.SIGINT):
                self.previous[s] = signal.signal(s, signal.SIG_IGN)
        return self

    def __exit__(self, *exc):
        import signal

        for s, h in self.previous.items():
            signal.signal(s, h)
