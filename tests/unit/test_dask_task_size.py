"""The sizing rule of Dask tasks (gfbopt.cluster.task_size): one chunk until a task has been
measured, then ``task_seconds`` of work, ramped, capped and shared among the workers.  The
old stream_dask sent every chunk as its own task (250,000 tasks for 10**6 points in chunks of
4, about 8 ms of Dask overhead each)."""
import math

import pytest

from gfbopt.cluster import (
    GROWTH,
    MAX_TASK_CHUNKS,
    TASK_SECONDS,
    call_batch,
    check_task_seconds,
    in_flight,
    task_size,
)
from gfbopt.errors import ParameterError


def test_one_chunk_until_something_was_measured():
    assert task_size(None, remaining=250_000, workers=2, largest=0) == 1
    assert task_size(0.004, remaining=250_000, workers=2, largest=0) == 1
    assert task_size(None, remaining=0, workers=2, largest=0) == 0


def test_a_measured_task_is_twenty_seconds_of_work():
    # 4 ms a chunk (4 points of 1 ms): 20 s is 5,000 chunks, reached once the ramp allows it
    assert TASK_SECONDS == 20.0
    assert task_size(0.004, remaining=250_000, workers=2, largest=5_000) == 5_000
    assert task_size(0.5, remaining=250_000, workers=2, largest=1_000) == 40
    assert task_size(0.5, remaining=250_000, workers=2, largest=1_000, target_s=60) == 120
    assert task_size(0.5, remaining=250_000, workers=2, largest=1_000, target_s=10) == 20


def test_the_ramp_grows_by_at_most_four():
    sizes, largest = [], 0
    for _ in range(8):
        size = task_size(0.004 if largest else None, remaining=250_000, workers=2,
                         largest=largest)
        sizes.append(size)
        largest = max(largest, size)
    assert GROWTH == 4
    assert sizes == [1, 4, 16, 64, 256, 1024, 4096, 5000]


def test_enough_tasks_for_every_worker_and_a_cap():
    # 100 chunks left on 4 workers: at most ceil(100 / 8) = 13 chunks a task
    assert task_size(1e-4, remaining=100, workers=4, largest=10**6) == 13
    assert task_size(1e-4, remaining=1, workers=4, largest=10**6) == 1
    # 0 workers connected counts as 1
    assert task_size(1e-4, remaining=100, workers=0, largest=10**6) == 50
    # a chunk of microseconds: the cap bounds one task's message
    assert task_size(1e-7, remaining=10**9, workers=2, largest=10**9) == MAX_TASK_CHUNKS
    # a chunk slower than the target: one chunk a task
    assert task_size(300.0, remaining=1000, workers=2, largest=1) == 1


def test_each_task_is_within_ten_to_sixty_seconds_away_from_the_end():
    for per in (1e-3, 0.01, 0.37, 2.0, 9.0):
        size = task_size(per, remaining=10**6, workers=2, largest=10**6)
        if size < MAX_TASK_CHUNKS and size > 1:
            assert 10.0 <= size * per <= 60.0, (per, size)
            assert math.isclose(size * per, 20.0, rel_tol=per / 20.0 + 1e-12)


def test_task_seconds_must_be_in_range():
    assert check_task_seconds(10) == 10.0 and check_task_seconds(60.0) == 60.0
    for bad in (5, 61, True, "20", float("nan")):
        with pytest.raises(ParameterError, match=r"task_seconds.*\[10, 60\]"):
            check_task_seconds(bad)


def test_two_tasks_per_worker_on_the_cluster():
    assert [in_flight(w) for w in (0, 1, 2, 8)] == [2, 2, 4, 16]


def test_a_batch_runs_each_chunk_and_keeps_errors_as_results():
    seconds, results = call_batch(lambda x: 10 // x, [1, 0, 5])
    assert seconds >= 0.0
    assert results[0] == 10 and results[2] == 2
    assert isinstance(results[1], ZeroDivisionError)
