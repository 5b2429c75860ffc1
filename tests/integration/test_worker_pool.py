"""One worker pool per run: inside ``with WorkerPool(n)`` every run_points call
reuses the same worker processes and their solver caches, starts no more workers than the
work needs, and the workers import gfbopt's numerical core only (no cvxpy).  On 0.2.0 each
call started a new spawn pool (the main job: 9 pools, 18 workers, solvers rebuilt each time),
so --workers 2 was 1.8x slower than --workers 1 (speed: benchmarks/bench_main_job.py)."""
import os
import sys

from gfbopt import BearingModel, Grid, analyses
from gfbopt.parallel import WorkerPool, run_points

GRID = Grid(24, 8)
MODEL = BearingModel(bearing_number=2.0, compliance=1.0, foil="simple", film="seam")


def report(eccentricity, cache):
    """A static solve in a worker, with the worker's pid, its cache size and its imports."""
    row = analyses.static_point(MODEL, eccentricity=eccentricity, grid=GRID, cache=cache)
    return {**row, "pid": os.getpid(), "solvers": len(cache), "solver": id(cache(MODEL, GRID)),
            "cvxpy": "cvxpy" in sys.modules, "matplotlib": "matplotlib" in sys.modules}


def test_batches_of_a_run_share_one_pool_and_its_solvers():
    with WorkerPool(2) as pool:
        first = run_points(report, [{"eccentricity": e} for e in (0.1, 0.2, 0.3, 0.4)],
                           workers=2)
        second = run_points(report, [{"eccentricity": e} for e in (0.5, 0.6, 0.7)],
                            workers=2)
        workers = {p.pid for p in pool._processes()}
    rows = first + second
    assert {r["pid"] for r in rows} <= workers and os.getpid() not in workers
    assert pool.started == len(workers) <= 2 and pool.restarts == 0   # one pool, <= 2 workers
    for pid in {r["pid"] for r in rows}:                 # one build per worker, both batches
        assert len({r["solver"] for r in rows if r["pid"] == pid}) == 1
    assert all(r["success"] for r in rows)
    assert not any(r["cvxpy"] or r["matplotlib"] for r in rows)


def test_the_pool_starts_only_the_workers_the_work_needs():
    with WorkerPool(4) as pool:
        rows = run_points(report, [{"eccentricity": 0.2}, {"eccentricity": 0.3}], workers=4)
    assert pool.started <= 2 and len({r["pid"] for r in rows}) <= 2


def test_one_worker_keeps_one_solver_cache_for_the_whole_run():
    with WorkerPool(1) as pool:
        run_points(report, [{"eccentricity": 0.2}], workers=1)
        rows = run_points(report, [{"eccentricity": 0.3}], workers=1)
    assert rows[0]["pid"] == os.getpid() and rows[0]["solvers"] == 1
    assert len(pool.cache) == 1 and pool.started == 0
