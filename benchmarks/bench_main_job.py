"""The main job, ``gfbopt run problems/rotor_bearing_design.toml --workers 2``, end to end:
wall and CPU time, the share of each stage, evaluations per second and the optimiser's own
overhead (targets: the converged main job ≤ 60 s on 2 idle cores, the optimiser ≤ 2 % of
an evaluation).

Each run is a fresh process (``--child``) that runs the real command line in-process
(``gfbopt.cli.main``) with two read-only instruments: the time at which each stage of the
run's progress (:class:`gfbopt.progress.Stages`: search, whirl at top speed, default-grid
check, tolerances, what it would take, reproduction) is entered, and the optimiser's result
(:class:`gfbopt.design.optimiser.OptimisationResult`: designs and evaluation seconds per
search stage — NSGA-II ``search`` and the local ``refinement`` — its driver time and its
convergence status).  The parent records the wall time, the CPU time of the child and its
workers (``resource.getrusage(RUSAGE_CHILDREN)``, user + system) and the load average
before and after: on a shared machine the times are upper bounds of the idle ones.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python benchmarks/bench_main_job.py \\
        [--repeats 1] [--workers 2] [--out results/benchmarks/main_job.json]
"""
from __future__ import annotations

import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from machine import machine_info, write_report  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
STUDY = ROOT / "problems" / "rotor_bearing_design.toml"
TARGET_S = 60.0
OVERHEAD_TARGET = 0.02


def _child(workers: int, results: str) -> None:
    """Run the main job here with the instruments; print one JSON line."""
    import gfbopt.design.optimiser as optimiser
    import gfbopt.progress as progress
    from gfbopt.cli import main as cli

    entered: list = []
    captured: dict = {}
    stage = progress.Stages.stage

    def timed_stage(self, name):
        entered.append((name, time.perf_counter()))
        return stage(self, name)

    optimise = optimiser.optimise

    def timed_optimise(*args, **kwargs):
        result = optimise(*args, **kwargs)
        captured["result"] = result
        return result

    progress.Stages.stage = timed_stage
    optimiser.optimise = timed_optimise
    t0 = time.perf_counter()
    code = cli(["run", str(STUDY), "--workers", str(workers), "--results", results])
    end = time.perf_counter()
    stages = {}
    marks = entered + [("end", end)]
    for (name, t), (_, t_next) in zip(marks, marks[1:]):
        stages[name] = stages.get(name, 0.0) + (t_next - t)
    stages["start (imports, plan, pool)"] = (entered[0][1] - t0) if entered else end - t0
    r = captured.get("result")
    search = {}
    if r is not None:
        asked = r.asked
        per_eval = r.evaluation_time_s / max(r.evaluated, 1)
        search = {"convergence": r.convergence, "designs_per_stage": dict(r.stages),
                  "evaluation_s_per_stage": dict(r.stage_time_s),
                  "evaluated": r.evaluated, "reused": r.reused, "repeated": r.repeated,
                  "evaluation_s_mean": per_eval,
                  "driver_s": r.driver_time_s, "driver_s_per_design": r.driver_time_s / asked,
                  "overhead_per_evaluation": (r.driver_time_s / asked) / per_eval,
                  "search_wall_s": r.wall_time_s,
                  "evaluations_per_wall_s": r.evaluated / r.wall_time_s}
        feasible = r.table[r.table["feasible"]]
        if len(feasible):
            best = feasible.loc[feasible["first_onset_speed_rpm"].idxmax()]
            search["best_first_onset_rpm"] = float(best["first_onset_speed_rpm"])
            search["best_design"] = {n: float(best[n]) for n in r.problem.names}
            search["best_min_film_lowest_speed_um"] = float(best["min_film_lowest_speed_um"])
    summary = {}
    path = Path(results) / "rotor_bearing_design" / "summary.json"
    if path.is_file():
        s = json.loads(path.read_text())
        summary = {k: s.get(k) for k in ("verdict", "stable_to_top_speed",
                                          "best_first_onset_rpm", "chosen_design")}
    print("BENCH " + json.dumps({"exit_status": code, "stages_wall_s": stages,
                                 "search": search, "summary": summary}), flush=True)


def _run(workers: int) -> dict:
    env = {**os.environ, "PYTHONPATH": str(ROOT), "GFBOPT_PROGRESS": "0"}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    load = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        out = subprocess.run([sys.executable, __file__, "--child", "--workers", str(workers),
                              "--results", tmp], env=env, capture_output=True, text=True,
                             check=False)
        wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    lines = [x for x in out.stdout.splitlines() if x.startswith("BENCH ")]
    row = json.loads(lines[-1][6:]) if lines else {"error": out.stderr[-2000:]}
    shares = {k: v / wall for k, v in row.get("stages_wall_s", {}).items()}
    last = [x for x in out.stdout.splitlines() if x and not x.startswith("BENCH ")][-1:]
    row.update(workers=workers, wall_s=wall, cpu_s=cpu, stage_shares_of_wall=shares,
               load_before=load, load_after=os.getloadavg(),
               last_line=[re.sub(r" -> \S+$", " -> (temporary results folder)", x)
                          for x in last])
    print(f"workers {workers}: wall {wall:6.1f} s, cpu {cpu:6.1f} s, load {load[0]:.2f} -> "
          f"{row['load_after'][0]:.2f}; {row.get('search', {}).get('convergence')}",
          flush=True)
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", default="results/benchmarks/main_job.json")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--results", default=None, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        _child(args.workers, args.results)
        return
    load_start = os.getloadavg()
    runs = [_run(args.workers) for _ in range(args.repeats)]
    load_end = os.getloadavg()
    for row in runs:
        s = row.get("search", {})
        print(f"wall {row['wall_s']:.1f} s (target {TARGET_S:.0f} s on 2 idle cores: "
              f"{'met' if row['wall_s'] <= TARGET_S else 'NOT met'} at load "
              f"{row['load_before'][0]:.1f}); optimiser overhead "
              f"{100 * s.get('overhead_per_evaluation', float('nan')):.3f} % of an "
              f"evaluation (target {100 * OVERHEAD_TARGET:.0f} %)")
    write_report(machine_info(benchmark="main_job", study=str(STUDY.relative_to(ROOT)),
                              command=f"gfbopt run {STUDY.relative_to(ROOT)} --workers "
                                      f"{args.workers}",
                              runs=runs, load_average_start=load_start,
                              load_average_end=load_end, wall_target_s=TARGET_S,
                              overhead_target=OVERHEAD_TARGET,
                              thread_env_note="OMP/OPENBLAS threads as in thread_env"),
                 args.out)


if __name__ == "__main__":
    main()
