"""The worker pool's fixed cost, and ``gfbopt run --workers 2`` against ``--workers 1``.

Part 1, **fixed cost per worker** for each start method (``spawn``: what gfbopt did before;
``forkserver`` preloading the driver's gfbopt modules; ``fork``), in a fresh driver process
per measurement that holds what ``gfbopt run`` holds when the bearing-pair design
(problems/rotor_bearing_design.toml, the main job) opens its pool.  The driver opens
``WorkerPool(n, start_method=...)`` and runs one task per worker that imports what that job's
tasks import (:data:`WORKER_MODULES`).  The cost is CPU time, user + system: every worker's
own (``os.times`` at the end of its task: interpreter start, imports, initialiser), the
forkserver's (``/proc/PID/stat``) and the driver's while the pool starts, runs and closes;
divided by ``n``.  Methods alternate (A B C A B C ...) over ``--repeats``; medians.

Part 2, **end to end**: ``gfbopt run STUDY --workers 1`` and ``--workers 2`` in turn
(1 2 2 1 ...), each run in a fresh process, CPU and peak memory of the whole process tree
from ``os.wait4``, at "load 0" (nothing started by the benchmark) and "load ≈ 2" (the
benchmark starts ``--competitors`` busy-loop processes, default 1: with the run's own
process about 2 on an idle machine).  The load average before and after each run is
recorded: on a shared machine "load 0" is not idle, so read the paired ratios.  ``--old PATH``
adds the same runs of another checkout (``git worktree add PATH COMMIT``), run with
``PYTHONPATH=PATH``.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python benchmarks/bench_pool.py \\
        [--repeats 3] [--workers 2] [--study problems/rotor_bearing_design.toml] \\
        [--e2e-repeats 2] [--competitors 1] [--old /tmp/old-checkout] [--skip-e2e] \\
        [--out results/benchmarks/pool.json]
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
STUDY = "problems/rotor_bearing_design.toml"
#: what ``gfbopt run`` has imported when the main job opens its pool (driver side)
DRIVER_MODULES = ("gfbopt.cli.run", "gfbopt.studies.rotor_design", "gfbopt.design.optimiser")
#: what a worker of the main job imports to run its tasks (from ``python -X importtime``)
WORKER_MODULES = ("gfbopt.parallel", "gfbopt.design.optimiser", "gfbopt.studies.rotor_design",
                  "gfbopt.rotor.system", "gfbopt.rotor.supports")
METHODS = ("spawn", "forkserver", "fork")
TARGET_S = 0.5


def _cpu_of(pid: int) -> float:
    """User + system CPU seconds of a live process (its own, not its children's)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _memory() -> dict:
    """Resident and proportional set size of this process (MiB), /proc/self/smaps_rollup."""
    out = {}
    for line in Path("/proc/self/smaps_rollup").read_text().splitlines():
        key, _, value = line.partition(":")
        if key in ("Rss", "Pss"):
            out[key.lower() + "_mib"] = int(value.split()[0]) / 1024
    return out


def touch(modules) -> dict:
    """A pool task: import what the main job's tasks import; then this worker's own CPU."""
    import importlib

    for name in modules:
        importlib.import_module(name)
    time.sleep(1.0)                 # so each of the n tasks lands on its own worker
    t = os.times()
    return {"pid": os.getpid(), "cpu_s": t.user + t.system, **_memory()}


def drive(method: str, workers: int) -> dict:
    """One measurement of the pool's fixed cost (runs in a fresh driver process)."""
    import importlib
    import multiprocessing.forkserver as forkserver

    for name in DRIVER_MODULES:
        importlib.import_module(name)
    from gfbopt.parallel import WorkerPool, stream_tasks

    t0, w0 = os.times(), time.perf_counter()
    server_cpu = 0.0
    with WorkerPool(workers, start_method=method) as pool:
        rows = [r for _, r in stream_tasks(touch, [WORKER_MODULES] * workers,
                                           workers=workers)]
        if method == "forkserver":
            server_cpu = _cpu_of(forkserver._forkserver._forkserver_pid)
    t1, wall = os.times(), time.perf_counter() - w0
    driver = (t1.user + t1.system) - (t0.user + t0.system)
    per_pid = {}
    for row in rows:
        if isinstance(row, dict) and row["cpu_s"] >= per_pid.get(row["pid"], row)["cpu_s"]:
            per_pid[row["pid"]] = row                  # a worker's last (largest) reading
    worker_cpu = sum(r["cpu_s"] for r in per_pid.values())
    total = worker_cpu + server_cpu + driver
    return {"method": method, "workers": workers, "worker_processes": len(per_pid),
            "pool_method": pool.method, "workers_cpu_s": worker_cpu,
            "forkserver_cpu_s": server_cpu, "driver_cpu_s": driver, "total_cpu_s": total,
            "cpu_per_worker_s": total / workers, "wall_s": wall,
            "worker_rss_mib": [r.get("rss_mib") for r in per_pid.values()],
            "worker_pss_mib": [r.get("pss_mib") for r in per_pid.values()]}


def _env(pythonpath: Path) -> dict:
    return {**os.environ, "PYTHONPATH": str(pythonpath), "GFBOPT_PROGRESS": "0",
            "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}


def _fixed_cost(method: str, workers: int) -> dict:
    import json

    out = subprocess.run([sys.executable, __file__, "--drive", method, str(workers)],
                         env=_env(ROOT), capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _gfbopt_run(code: Path, study: str, workers: int, extra: list) -> dict:
    """``gfbopt run`` in a fresh process; CPU and peak memory of its tree (os.wait4)."""
    load = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-m", "gfbopt", "run", str(ROOT / study),
                                 "--workers", str(workers), "--results", tmp, *extra],
                                env=_env(code), cwd=tmp, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
        output = proc.stdout.read()
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
    lines = output.strip().splitlines()
    return {"workers": workers, "wall_s": wall, "cpu_s": usage.ru_utime + usage.ru_stime,
            "peak_rss_mib": usage.ru_maxrss / 1024, "exit_status": proc.returncode,
            "load_before": load, "load_after": os.getloadavg(),
            "last_line": lines[-1][-300:] if lines else ""}


def _busy_loops(count: int) -> list:
    return [subprocess.Popen([sys.executable, "-c", "while True: pass"])
            for _ in range(count)]


def _end_to_end(args, codes: dict, save) -> dict:
    """Both phases; ``save(phases)`` after every run (a long benchmark keeps what it has)."""
    phases = {}
    for phase, competitors in (("load_0", 0), ("load_2", args.competitors)):
        loops = _busy_loops(competitors)
        try:
            time.sleep(5.0 if competitors else 0.0)          # let the load average rise
            runs = []
            for k in range(args.e2e_repeats):
                order = (1, args.workers) if k % 2 == 0 else (args.workers, 1)
                for label, code in codes.items():
                    pair = {}
                    for workers in order:
                        row = _gfbopt_run(code, args.study, workers, args.run_args)
                        pair[workers] = row
                        runs.append({"code": label, "repeat": k, **row})
                        save({**phases, phase: {"competing_busy_loops": competitors,
                                                "runs": runs, "complete": False}})
                        print(f"{phase} {label} workers {workers}: wall {row['wall_s']:6.1f} s, "
                              f"cpu {row['cpu_s']:6.1f} s, peak {row['peak_rss_mib']:5.0f} MiB, "
                              f"exit {row['exit_status']}, load {row['load_before'][0]:.2f}",
                              flush=True)
                    runs[-1]["wall_ratio"] = pair[args.workers]["wall_s"] / pair[1]["wall_s"]
                    runs[-1]["cpu_ratio"] = pair[args.workers]["cpu_s"] / pair[1]["cpu_s"]
        finally:
            for loop in loops:
                loop.kill()
                loop.wait()
        summary = {}
        for label in codes:
            mine = [r for r in runs if r["code"] == label]
            ratios = [r for r in mine if "wall_ratio" in r]
            summary[label] = {
                "wall_ratio_median": statistics.median(r["wall_ratio"] for r in ratios),
                "cpu_ratio_median": statistics.median(r["cpu_ratio"] for r in ratios),
                "wall_ratios": [r["wall_ratio"] for r in ratios],
                "cpu_ratios": [r["cpu_ratio"] for r in ratios],
                **{f"workers_{w}_{key}_median": statistics.median(
                    r[key] for r in mine if r["workers"] == w)
                   for w in (1, args.workers) for key in ("wall_s", "cpu_s", "peak_rss_mib")},
                "all_exit_0": all(r["exit_status"] == 0 for r in mine)}
            print(f"{phase} {label}: wall({args.workers})/wall(1) "
                  f"{summary[label]['wall_ratio_median']:.2f}, cpu ratio "
                  f"{summary[label]['cpu_ratio_median']:.2f}", flush=True)
        phases[phase] = {"competing_busy_loops": competitors, "summary": summary, "runs": runs}
    return phases


def main() -> None:
    import json

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--drive", nargs=2, metavar=("METHOD", "WORKERS"),
                        help=argparse.SUPPRESS)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--study", default=STUDY)
    parser.add_argument("--run-args", nargs="*", default=[],
                        help="more options of gfbopt run, e.g. --run-args=--grid=36x10")
    parser.add_argument("--e2e-repeats", type=int, default=2)
    parser.add_argument("--competitors", type=int, default=1)
    parser.add_argument("--old", default=None, help="another checkout to run end to end")
    parser.add_argument("--skip-e2e", action="store_true")
    parser.add_argument("--out", default=str(ROOT / "results/benchmarks/pool.json"))
    args = parser.parse_args()
    if args.drive:
        print(json.dumps(drive(args.drive[0], int(args.drive[1]))))
        return
    sys.path.insert(0, str(ROOT / "benchmarks"))
    sys.path.insert(0, str(ROOT))
    from machine import machine_info, tree_label, write_report

    from gfbopt.provenance import source_state

    load_start = os.getloadavg()
    print(f"load before: {load_start}", flush=True)
    fixed = []
    for k in range(args.repeats):
        for method in METHODS:
            row = _fixed_cost(method, args.workers)
            fixed.append({"repeat": k, "load_before": os.getloadavg(), **row})
            print(f"{method:10s} {args.workers} workers: {row['cpu_per_worker_s']:.3f} s CPU "
                  f"per worker (workers {row['workers_cpu_s']:.2f}, forkserver "
                  f"{row['forkserver_cpu_s']:.2f}, driver {row['driver_cpu_s']:.2f}; "
                  f"Pss {row['worker_pss_mib']} MiB)", flush=True)
    per_method = {m: {"cpu_per_worker_s_median": statistics.median(
        r["cpu_per_worker_s"] for r in fixed if r["method"] == m),
        "worker_pss_mib_median": statistics.median(
        p for r in fixed if r["method"] == m for p in r["worker_pss_mib"] if p is not None)}
        for m in METHODS}
    codes = {"new": ROOT} if args.old is None else {"new": ROOT, "old": Path(args.old)}
    state = source_state()

    def save(e2e):
        write_report(machine_info(
            benchmark="pool", commit=state["commit"], dirty=state["dirty"],
            load_average_start=load_start, load_average_end=os.getloadavg(),
            fixed_cost={"workers": args.workers, "driver_modules": DRIVER_MODULES,
                        "worker_modules": WORKER_MODULES, "per_method": per_method,
                        "target_cpu_per_worker_s": TARGET_S, "runs": fixed},
            end_to_end=None if e2e is None else {
                "study": args.study, "run_args": args.run_args, "workers": args.workers,
                "codes": {k: tree_label(v) for k, v in codes.items()}, **e2e}), args.out)

    save(None)
    if not args.skip_e2e:
        save(_end_to_end(args, codes, save))


if __name__ == "__main__":
    main()
