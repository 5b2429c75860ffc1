"""Dask at 10⁵ points: the driver's CPU share and the points per second, against the process pool.

A cheap analysis (:func:`short_bearing`: the eccentricity of a short, incompressible,
half-Sommerfeld film at a given load, by bisection on a numerical load integral; numpy,
about 1 ms a point) runs at ``--points`` (default 100,000) Latin-hypercube points through
:func:`gfbopt.doe.run_doe` (chunks of 4 points, the default; the whole route: tasks, the
executor, the Parquet store, the table read back) on

* ``dask``: a ``distributed.LocalCluster`` with 2 worker processes of 1 thread, started in
  a process of its own (as the cluster of ``gfbopt run --scheduler`` is: the driver is the
  client alone; the scheduler's CPU is reported beside it);
* ``pool``: the process pool, ``workers=2``;
* ``dask-old`` (``--old PATH``, a checkout of the code before the change, e.g. made with
  ``git worktree add``): the same on the old ``stream_dask`` (one ``client.submit`` a chunk,
  every future's status scanned every 50 ms), run with ``PYTHONPATH=PATH``.

Each run is a subprocess of its own; the configurations alternate (A B C A B C ...) for
``--repeats`` rounds and the medians are reported.  Measured per run: wall time, points per
second, the driver process's CPU (``getrusage``; its main thread alone too), the workers' CPU
(Dask: each worker's ``getrusage`` through ``client.run``; pool: each worker's CPU clock at
its last point, :func:`analysis`), the scheduler process's CPU (Dask), the
driver's CPU share = driver / (driver + workers), the Dask tasks the scheduler ran, and the load average
before and after.  The rows of Dask and the pool are compared (every output equal).

    OMP_NUM_THREADS=1 python benchmarks/bench_dask.py [--points 100000] [--repeats 2]
        [--old /tmp/old-checkout] [--out results/benchmarks/dask.json]
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

_THETA = np.linspace(0.0, np.pi, 401)
_COS, _SIN = np.cos(_THETA), np.sin(_THETA)
_W = np.full(_THETA.size, _THETA[1])
_W[[0, -1]] *= 0.5


def short_bearing(load: float, length_ratio: float) -> dict:
    """Eccentricity and attitude angle of a short bearing (Ocvirk, half-Sommerfeld) carrying
    the non-dimensional ``load`` (μωRL³/c² units over (L/D)²): 40 bisection steps on the
    numerically integrated load (401 nodes)."""
    def components(eps: float):
        p = eps * _SIN / (1.0 + eps * _COS) ** 3
        return -np.dot(p * _COS, _W), np.dot(p * _SIN, _W)

    target = load / length_ratio ** 2
    low, high = 0.0, 0.999
    for _ in range(40):
        mid = 0.5 * (low + high)
        radial, tangential = components(mid)
        if np.hypot(radial, tangential) < target:
            low = mid
        else:
            high = mid
    radial, tangential = components(0.5 * (low + high))
    return {"eccentricity": 0.5 * (low + high),
            "attitude_angle_deg": float(np.degrees(np.arctan2(tangential, radial)))}


def analysis(load: float, length_ratio: float) -> dict:
    """:func:`short_bearing`, and this process's CPU seconds so far (``process_cpu_s``: the
    largest value of a worker is its CPU for the run; pool workers are new processes)."""
    return {**short_bearing(load, length_ratio), "process_cpu_s": time.process_time()}


def _usage() -> float:
    me = resource.getrusage(resource.RUSAGE_SELF)
    return me.ru_utime + me.ru_stime


#: the local cluster, in a process of its own (as a cluster is to ``gfbopt run --scheduler``):
#: the scheduler and the nannies there, 2 worker processes of 1 thread
CLUSTER = """
import sys, time
from distributed import LocalCluster
cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                       dashboard_address=":0")
print(cluster.scheduler_address, flush=True)
time.sleep(86400)
"""


def _tasks_run(dask_scheduler) -> int:
    """Tasks of gfbopt (keys ``gfbopt-...``) the scheduler started, retries included."""
    prefix = dask_scheduler.task_prefixes.get("gfbopt")
    return int(prefix.state_counts.get("processing", 0)) if prefix is not None else 0


def _worker_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def one(config: str, points: int, store: Path) -> dict:
    """Run one configuration in this process; return its measurements."""
    from bench_dask import analysis as function             # by reference, for the workers
    from gfbopt.doe import SamplePlan, Variable, run_doe

    plan = SamplePlan((Variable("load", 0.05, 2.0), Variable("length_ratio", 0.4, 1.5)),
                      method="lhs", n=points, seed=3)
    outputs = {"eccentricity": "float64", "attitude_angle_deg": "float64",
               "process_cpu_s": "float64"}
    load_before = os.getloadavg()
    cluster = client = None
    scheduler_cpu = tasks = None
    if config.startswith("dask"):
        import distributed

        cluster = subprocess.Popen([sys.executable, "-c", CLUSTER], stdout=subprocess.PIPE,
                                   stderr=subprocess.DEVNULL, text=True)
        client = distributed.Client(cluster.stdout.readline().strip(), set_as_default=False)
        import psutil

        scheduler = psutil.Process(cluster.pid)
        scheduler_before = sum(scheduler.cpu_times()[:2])
        workers_before = client.run(_worker_cpu)
    kwargs = {"workers": 2}
    if config == "dask":
        kwargs = {"client": client}
    elif config == "dask-old":                  # the old run_doe has no client=: its engine has
        import functools

        import gfbopt.doe.engine as engine
        engine.execute = functools.partial(engine.execute, client=client)
    me0 = _usage()
    thread0 = time.thread_time()
    t0 = time.perf_counter()
    frame = run_doe(function, plan, store, outputs=outputs, progress=False, version="bench",
                    notify=lambda text: None, **kwargs)
    wall = time.perf_counter() - t0
    thread = time.thread_time() - thread0
    me1 = _usage()
    if client is not None:
        after = client.run(_worker_cpu)
        tasks = client.run_on_scheduler(_tasks_run)
        workers_cpu = sum(after[w] - workers_before.get(w, 0.0) for w in after)
        scheduler_cpu = sum(scheduler.cpu_times()[:2]) - scheduler_before
        client.close()
        cluster.kill()
        cluster.wait()
    else:                                     # pool workers are new processes
        workers_cpu = float(frame.groupby("worker")["process_cpu_s"].max().sum())
    driver = me1 - me0
    ok = frame["success"].astype(bool)
    return {"config": config, "points": int(len(frame)), "succeeded": int(ok.sum()),
            "wall_s": wall, "points_per_s": len(frame) / wall, "driver_cpu_s": driver,
            "driver_main_thread_cpu_s": thread, "workers_cpu_s": workers_cpu,
            "driver_cpu_share": driver / (driver + workers_cpu),
            "driver_cores": driver / wall, "scheduler_process_cpu_s": scheduler_cpu,
            "dask_tasks": tasks,
            "mean_point_s": float(frame["wall_time_s"].mean()),
            "load_before": load_before, "load_after": os.getloadavg()}


def _spawn(config: str, points: int, folder: Path, old: str | None) -> dict:
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    root = old if config == "dask-old" else str(HERE.parent)
    env["PYTHONPATH"] = os.pathsep.join([root, str(HERE)])
    store = folder / f"{config}-{time.monotonic_ns()}"
    done = subprocess.run([sys.executable, str(HERE / "bench_dask.py"), "--one", config,
                           "--points", str(points), "--store", str(store)], env=env,
                          capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{config} failed:\n{done.stderr[-3000:]}")
    out = json.loads(done.stdout.strip().splitlines()[-1])
    out["store"] = str(store)
    return out


def _same_rows(a: str, b: str) -> bool:
    from gfbopt.doe import read_results

    cols = ["point", "load", "length_ratio", "eccentricity", "attitude_angle_deg", "success"]
    x = read_results(a)[cols].sort_values("point").reset_index(drop=True)
    y = read_results(b)[cols].sort_values("point").reset_index(drop=True)
    return bool(x.equals(y))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=100_000)
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--old", default=None, help="checkout of the old code (dask-old)")
    parser.add_argument("--one", default=None, help=argparse.SUPPRESS)
    parser.add_argument("--store", default=None, help=argparse.SUPPRESS)
    parser.add_argument("--out", default="results/benchmarks/dask.json")
    args = parser.parse_args()
    if args.one:
        print(json.dumps(one(args.one, args.points, Path(args.store))))
        return
    from machine import machine_info, write_report

    from gfbopt.provenance import provenance

    info = provenance()                      # the code the runs use (before they start)
    # the tree may be dirty with files this benchmark does not run: list the ones it runs
    own = subprocess.run(["git", "status", "--porcelain", "--", "gfbopt/cluster.py",
                          "gfbopt/doe", "gfbopt/parallel.py", "gfbopt/runtime.py",
                          "benchmarks/bench_dask.py"], cwd=HERE.parent, capture_output=True,
                         text=True).stdout.split("\n")
    configs = ["dask", "pool"] + (["dask-old"] if args.old else [])
    t0 = time.process_time()
    for _ in range(200):
        short_bearing(0.7, 1.0)
    per_point = (time.process_time() - t0) / 200
    runs = []
    load_start = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        for repeat in range(args.repeats):
            for config in configs:
                run = _spawn(config, args.points, Path(tmp), args.old)
                run["repeat"] = repeat
                runs.append(run)
                print(f"{config:9s} {run['points']} points: {run['wall_s']:7.1f} s wall, "
                      f"{run['points_per_s']:7.0f} points/s, driver {run['driver_cpu_s']:6.2f} s "
                      f"CPU = {run['driver_cpu_share']:.1%} of the run's "
                      f"(workers {run['workers_cpu_s']:.1f} s), tasks {run['dask_tasks']}, "
                      f"load {run['load_before'][0]:.1f}", flush=True)
        identical = all(_same_rows(r["store"], p["store"]) for r in runs if r["config"] == "dask"
                        for p in runs if p["config"] == "pool" and p["repeat"] == r["repeat"])
    medians = {}
    for config in configs:
        mine = [r for r in runs if r["config"] == config]
        medians[config] = {key: statistics.median(r[key] for r in mine) for key in
                           ("wall_s", "points_per_s", "driver_cpu_s", "driver_cpu_share",
                            "driver_main_thread_cpu_s", "workers_cpu_s", "driver_cores")}
        medians[config]["dask_tasks"] = mine[0]["dask_tasks"]
    ratio = medians["dask"]["points_per_s"] / medians["pool"]["points_per_s"]
    summary = {"points": args.points, "chunk_size": 4, "analysis_cpu_s_per_point": per_point,
               "dask_driver_cpu_share": medians["dask"]["driver_cpu_share"],
               "dask_driver_cpu_share_target": 0.05,
               "dask_points_per_s": medians["dask"]["points_per_s"],
               "pool_points_per_s": medians["pool"]["points_per_s"],
               "dask_over_pool_points_per_s": ratio,
               "dask_rows_identical_to_pool": identical}
    if args.old:
        summary["old_dask_points_per_s"] = medians["dask-old"]["points_per_s"]
        summary["old_dask_driver_cpu_share"] = medians["dask-old"]["driver_cpu_share"]
    print(json.dumps(summary, indent=2))
    write_report({"machine": machine_info(load_start=load_start, load_end=os.getloadavg()),
                  "commit": info.get("source_commit"), "dirty": info.get("source_dirty"),
                  "dirty_files_on_the_benchmarked_path": [line for line in own if line],
                  "summary": summary, "medians": medians,
                  "runs": [{k: v for k, v in r.items() if k != "store"} for r in runs]},
                 args.out)


if __name__ == "__main__":
    main()
