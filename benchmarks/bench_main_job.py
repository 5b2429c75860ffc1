"""The main job (``gfbopt run problems/ruscitto_pitch_design.toml``) at --workers 1 and 2.

In 0.2.0, `gfbopt run` started a spawn pool for every small batch of the design search (9 pools,
18 workers, ≈ 1.9 s of imports each, solvers rebuilt), so ``--workers 2`` was 1.8× slower
than ``--workers 1``.  ``gfbopt run`` now opens one :class:`gfbopt.parallel.WorkerPool` for
the whole run; this benchmark runs the real command line, end to end, in a fresh process per
configuration (``--grid 36x10`` and ``--grid 72x20``), alternating the worker counts over
``--repeats`` rounds (paired runs: the load of a shared machine drifts), and records per run:

* wall time, and CPU time of the command and all its worker processes
  (``resource.getrusage(RUSAGE_CHILDREN)``, user + system);
* the load average before and after (on a shared machine the numbers are upper bounds of the
  idle times, and the ratio between paired runs is what to read);
* the ratio wall(2 workers) / wall(1 worker) per round and its median.

    python benchmarks/bench_main_job.py [--grids 36x10 72x20] [--repeats 1] [--start-with 1]
                                        [--out results/benchmarks/main_job.json]
"""
from __future__ import annotations

import argparse
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from machine import machine_info, write_report

ROOT = Path(__file__).resolve().parents[1]
STUDY = ROOT / "problems" / "ruscitto_pitch_design.toml"


def _without_folder(line: str) -> str:
    """The run's last line without the temporary results folder it names."""
    return re.sub(r" -> \S+$", " -> (temporary results folder)", line)


def _run(grid: str, workers: int) -> dict:
    env = {**os.environ, "PYTHONPATH": str(ROOT), "GFBOPT_PROGRESS": "0"}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    load = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        out = subprocess.run([sys.executable, "-m", "gfbopt", "run", str(STUDY), "--grid",
                              grid, "--workers", str(workers), "--results", tmp], env=env,
                             capture_output=True, text=True, check=False)
        wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    row = {"grid": grid, "workers": workers, "wall_s": wall, "cpu_s": cpu,
           "exit_status": out.returncode, "load_before": load, "load_after": os.getloadavg(),
           "summary": [_without_folder(line) for line in
                       out.stdout.strip().splitlines()[-1:] or [out.stderr.strip()[-300:]]]}
    print(f"grid {grid} workers {workers}: wall {wall:6.1f} s, cpu {cpu:6.1f} s, exit "
          f"{out.returncode}, load {load[0]:.2f}", flush=True)
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grids", nargs="+", default=["36x10", "72x20"])
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--start-with", type=int, choices=(1, 2), default=1,
                        help="worker count of the first run of each pair")
    parser.add_argument("--out", default="results/benchmarks/main_job.json")
    args = parser.parse_args()
    load_start = os.getloadavg()
    print(f"load before: {load_start[0]:.2f} {load_start[1]:.2f} {load_start[2]:.2f}",
          flush=True)
    runs, ratios = [], {}
    for grid in args.grids:
        ratios[grid] = []
        for k in range(args.repeats):
            first = args.start_with if k % 2 == 0 else 3 - args.start_with
            order = (first, 3 - first)                     # paired, alternating order
            pair = {w: _run(grid, w) for w in order}
            runs += list(pair.values())
            ratios[grid].append(pair[2]["wall_s"] / pair[1]["wall_s"])
        print(f"grid {grid}: wall(2 workers)/wall(1 worker) = "
              f"{', '.join(f'{r:.2f}' for r in ratios[grid])}", flush=True)
    load_end = os.getloadavg()
    print(f"load after: {load_end[0]:.2f} {load_end[1]:.2f} {load_end[2]:.2f}", flush=True)
    targets = {"36x10": 30.0, "72x20": 120.0}
    for row in runs:
        if row["grid"] in targets:
            print(f"grid {row['grid']} workers {row['workers']}: wall {row['wall_s']:.1f} s "
                  f"(target {targets[row['grid']]:.0f} s on 2 idle cores: "
                  f"{'met' if row['wall_s'] <= targets[row['grid']] else 'NOT met'})")
    write_report(machine_info(benchmark="main_job", study=str(STUDY.relative_to(ROOT)),
                              runs=runs, load_average_start=load_start,
                              load_average_end=load_end,
                              wall_targets_s=targets,
                              wall_ratio_2_over_1={g: {"per_round": r,
                                                       "median": statistics.median(r)}
                                                   for g, r in ratios.items()},
                              target="wall(2 workers) <= wall(1 worker)"),
                 args.out)


if __name__ == "__main__":
    main()
