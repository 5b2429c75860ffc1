"""The pool's streaming loop (gfbopt.pool_stream): bounded in-flight tasks, every task once,
retries on a broken pool counted per task, and the same rows as the serial executor."""
import threading
from concurrent.futures import ThreadPoolExecutor
from concurrent.futures.process import BrokenProcessPool

from gfbopt.parallel import run_points
from gfbopt.pool_stream import stream_pool
from gfbopt.runtime import InfrastructureFailure


class _Counting(ThreadPoolExecutor):
    """A thread executor that records the most futures outstanding at once."""

    def __init__(self, workers, broken_at=None):
        super().__init__(max_workers=workers)
        self.lock = threading.Lock()
        self.outstanding = 0
        self.peak = 0
        self.submitted = 0
        self.broken_at = broken_at

    def submit(self, fn, *args):
        if self.broken_at is not None and self.submitted >= self.broken_at:
            raise BrokenProcessPool("planted")
        self.submitted += 1
        with self.lock:
            self.outstanding += 1
            self.peak = max(self.peak, self.outstanding)
        future = super().submit(fn, *args)
        future.add_done_callback(self._done)
        return future

    def _done(self, _future):
        with self.lock:
            self.outstanding -= 1


class _FakePool:
    method = "thread"

    def __init__(self, workers, broken_at=None):
        self.workers = workers
        self.executors = []
        self.broken_at = broken_at
        self.restarts = 0

    def executor(self, tasks):
        if not self.executors or self.executors[-1] is None:
            broken = self.broken_at if not self.executors else None
            self.executors.append(_Counting(self.workers, broken))
        return self.executors[-1]

    def restart(self):
        self.restarts += 1
        self.executors[-1].shutdown()
        self.executors.append(None)

    def terminate(self):
        pass


def _square(x):
    return x * x


def test_in_flight_is_bounded_and_every_task_yields_once():
    pool = _FakePool(workers=3)
    out = dict(stream_pool(_square, list(range(200)), pool, retries=2, tick=None))
    assert out == {k: k * k for k in range(200)}
    # 2 per worker: 6 at most, and the bound is reached (the test can fail both ways)
    assert pool.executors[0].peak == 6
    assert pool.executors[0].submitted == 200


def test_a_broken_submit_restarts_only_the_tasks_not_done():
    """The pool breaks after 10 submits: the rest run on a fresh pool, each exactly once."""
    pool = _FakePool(workers=2, broken_at=10)
    seen = list(stream_pool(_square, list(range(30)), pool, retries=2, tick=None))
    assert sorted(k for k, _ in seen) == list(range(30))
    assert dict(seen) == {k: k * k for k in range(30)}
    assert pool.restarts == 1
    assert pool.executors[0].submitted == 10 and pool.executors[2].submitted == 20


class _AlwaysBroken(_FakePool):
    def executor(self, tasks):
        self.executors.append(_Counting(self.workers, broken_at=0))
        return self.executors[-1]

    def restart(self):
        self.restarts += 1


def test_a_pool_that_never_runs_gives_infrastructure_failures_after_the_retries():
    pool = _AlwaysBroken(workers=2)
    seen = list(stream_pool(_square, [1, 2, 3], pool, retries=2, tick=None))
    assert sorted(k for k, _ in seen) == [0, 1, 2]
    assert all(isinstance(r, InfrastructureFailure) for _, r in seen)
    assert "3 pools in a row" in str(seen[0][1])


def _row(x, y):
    return {"s": x * 10 + y, "name": f"p{x}-{y}"}


def test_process_pool_rows_equal_the_serial_rows():
    """A small sweep on 2 real worker processes (4 tasks in flight at most): the same rows
    in the same (point) order as the serial executor."""
    points = [{"x": x, "y": y} for x in range(6) for y in range(3)]
    drop = lambda rows: [{k: v for k, v in r.items() if k != "wall_time_s"} for r in rows]  # noqa: E731
    serial = drop(run_points(_row, points, workers=1))
    pooled = drop(run_points(_row, points, workers=2))
    assert pooled == serial
    assert [r["s"] for r in pooled] == [x * 10 + y for x in range(6) for y in range(3)]
