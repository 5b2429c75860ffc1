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


def _fresh(body: str, *args: str) -> None:
    """Run ``body(*args)`` of this module in a fresh interpreter: the pool's start method and
    the workers' imports depend on the driver process (another thread, such as pytest-xdist's
    I/O thread, makes fork unsafe; modules the driver imported are inherited), so what is
    tested here is the driver a user's ``gfbopt run`` is.  A failed assertion fails the test
    with the child's traceback."""
    import subprocess
    from pathlib import Path

    here = Path(__file__).resolve().parent
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(here), str(here.parents[1]), os.environ.get("PYTHONPATH", "")])}
    code = f"import test_worker_pool as t; t.{body}(*{list(args)!r})"
    out = subprocess.run([sys.executable, "-c", code], cwd=here, env=env,
                         capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]


def test_batches_of_a_run_share_one_pool_and_its_solvers():
    _fresh("batches_share_one_pool")


def batches_share_one_pool():
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


def fresh_worker(eccentricity, cache):
    """What a worker sees before it solves: its cache (empty in a new worker), the run's
    pool (the driver's; none in a worker)."""
    from gfbopt.parallel import active_pool
    from gfbopt.runtime import interrupted

    before = len(cache)
    row = analyses.static_point(MODEL, eccentricity=eccentricity, grid=GRID, cache=cache)
    return {**row, "pid": os.getpid(), "cache_before": before,
            "sees_pool": active_pool() is not None, "interrupted": interrupted()}


def test_forked_workers_start_clean_and_give_the_serial_rows():
    """The driver has built a solver and holds the run's pool and signal state when it forks:
    the workers must not use any of it (a copied CasADi solver, the driver's cache)."""
    _fresh("forked_workers_start_clean")


def forked_workers_start_clean():
    from gfbopt.parallel import interrupt_on_signals

    points = [{"eccentricity": e} for e in (0.2, 0.3, 0.4, 0.5)]
    serial = run_points(fresh_worker, points, workers=1)
    with interrupt_on_signals(), WorkerPool(2) as pool:
        run_points(fresh_worker, points[:1], workers=2)        # one point: in the driver
        assert len(pool.cache) == 1
        rows = run_points(fresh_worker, points, workers=2)
    assert pool.method == "fork" and pool.restarts == 0
    assert os.getpid() not in {r["pid"] for r in rows}
    first = {}
    for r in rows:
        first.setdefault(r["pid"], r)
    assert all(r["cache_before"] == 0 for r in first.values())   # a new worker: empty cache
    assert not any(r["sees_pool"] or r["interrupted"] for r in rows)
    for a, b in zip(serial, rows):
        assert (a["load"], a["success"]) == (b["load"], b["success"])


def test_with_another_thread_in_the_driver_workers_come_from_the_forkserver():
    import threading

    points = [{"eccentricity": e} for e in (0.2, 0.3, 0.4)]
    serial = run_points(report, points, workers=1)
    stop = threading.Event()
    thread = threading.Thread(target=stop.wait, daemon=True)
    thread.start()
    try:
        with WorkerPool(2) as pool:
            rows = run_points(report, points, workers=2)
    finally:
        stop.set()
        thread.join()
    assert pool.method == "forkserver"
    assert [r["load"] for r in rows] == [r["load"] for r in serial]
    assert os.getpid() not in {r["pid"] for r in rows}


def kill_once(value, marker, always=False):
    """``value ** 2``, but at value 3 the worker kills itself (once, or every time)."""
    import signal
    from pathlib import Path

    if value == 3 and (always or not Path(marker).exists()):
        Path(marker).write_text("killed")
        os.kill(os.getpid(), signal.SIGKILL)
    return {"square": value ** 2, "pid": os.getpid()}


def test_a_killed_fork_worker_is_retried_and_one_that_always_dies_is_reported(tmp_path):
    _fresh("killed_fork_worker", str(tmp_path))


def killed_fork_worker(folder):
    from pathlib import Path

    tmp_path = Path(folder)
    points = [{"value": v, "marker": str(tmp_path / "once")} for v in range(6)]
    methods = []
    with WorkerPool(2) as pool:
        methods.append(pool.executor(6) and pool.method)
        rows = run_points(kill_once, points, workers=2)
        methods.append(pool.method)
    assert methods == ["fork", "fork"]    # the old pool's threads ended before the restart
    assert [r["square"] for r in rows] == [v * v for v in range(6)]
    assert pool.restarts == 1 and all(r["success"] for r in rows)
    always = [{"value": v, "marker": str(tmp_path / "always"), "always": True}
              for v in (2, 3, 4)]
    with WorkerPool(2) as pool:
        rows = run_points(kill_once, always, workers=2)
    assert not rows[1]["success"] and "died on 3 pools in a row" in rows[1]["message"]
    for row, value in ((rows[0], 2), (rows[2], 4)):     # done, or lost with the killer
        assert row.get("square") == value ** 2 or "died on 3 pools" in row["message"]
