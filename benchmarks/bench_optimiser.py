"""The design optimiser's own cost per evaluation against one real evaluation (target:
overhead ≤ 2 % of an evaluation), in one run.

Measured (serial, one process, so nothing else hides in the numbers):

* NSGA-II (pymoo) on ZDT1, 400 designs in generations of 20, every evaluation streamed into a
  ResultStore as its own Parquet part: the driver's time per design (ask, tell, decoding,
  store writes: ``driver_time_s``) and the residual wall − Σ evaluation time per design (the
  same plus the executor's dispatch);
* the Bayesian option (GP + EI, bayesian-optimization) on Hartmann-3, 32 designs (8 start):
  driver time per design and the best value reached, with its acquisition search at the
  library's default (10,000 random points, 10 L-BFGS-B starts) and at gfbopt's default
  (5,000 random points, no L-BFGS-B polishing);
* one real evaluation: a bearing-pair design of the blower rotor (problems/rotors/
  blower.toml, two Ruscitto bearings, shim preload) on the 36x10 search grid and on the
  default 144x36 grid after the solver builds
  (:func:`gfbopt.design.rotor_objectives.evaluate_rotor_design`), wall and CPU seconds, with
  one BLAS thread as in every gfbopt run.

Run: ``PYTHONPATH=. python benchmarks/bench_optimiser.py`` → results/benchmarks/optimiser.json;
with ``--ranking`` instead: six designs of the main job's space on 36x10, 72x20 and 144x36 and
how the coarse grids rank them (:func:`grid_ranking`) → results/benchmarks/
design_grid_ranking.json; with ``--main-job``: the README's main job at --workers 1 and 2, wall
and CPU seconds (:func:`main_job`) → results/benchmarks/rotor_design_main_job.json; with
``--stages [--old TREE] [--repeats N]``: the main job at --workers 1, CPU seconds of each stage
and the after-search stages' share of the job's CPU (:func:`stage_shares`), this tree against
an older checkout ``TREE`` (``git worktree add``) in interleaved pairs, with the tables' figures
of both → results/benchmarks/rotor_design_stages.json.
The machine's load average is recorded: the 2 cores are shared, so absolute times vary; the
ratios are taken within the run.
"""
from __future__ import annotations

import json
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from gfbopt.design import surrogates  # noqa: E402
from gfbopt.design.optimiser import optimise, store_schema  # noqa: E402
from gfbopt.design.problem import DesignProblem, Objective, Variable  # noqa: E402
from gfbopt.design.search import SearchSettings  # noqa: E402
from gfbopt.doe.store import ResultStore  # noqa: E402


def nsga2_overhead() -> dict:
    problem = DesignProblem(tuple(Variable(f"x{k}", 0.0, 1.0) for k in range(3)),
                            (Objective("f1"), Objective("f2")))
    with tempfile.TemporaryDirectory() as tmp:
        store = ResultStore.create(Path(tmp) / "s", study="bench", study_hash="0" * 64,
                                   schema=store_schema(problem, {"f1": "float64",
                                                                 "f2": "float64"}))
        r = optimise(problem, surrogates.zdt1, SearchSettings("nsga2", budget=400,
                                                               population=20, seed=0),
                     store=store)
        parts = len(store.parts())
    return {"designs": r.asked, "parquet_parts": parts,
            "driver_time_per_design_s": r.driver_time_per_design_s,
            "residual_per_design_s": (r.wall_time_s - r.evaluation_time_s) / r.asked}


def bayes_overhead(samples: int, starts: int, seeds=(0, 1, 2)) -> dict:
    problem = DesignProblem(tuple(Variable(f"x{k}", 0.0, 1.0) for k in range(3)),
                            (Objective("merit", "max"),))
    per, best = [], []
    for seed in seeds:
        r = optimise(problem, surrogates.hartmann3,
                     SearchSettings("bayes", budget=32, startup=8, seed=seed,
                                    acquisition_samples=samples, acquisition_starts=starts))
        per.append(r.driver_time_per_design_s)
        best.append(r.best["merit"] / surrogates.HARTMANN3_MAX)
    return {"acquisition_samples": samples, "acquisition_starts": starts,
            "seeds": list(seeds), "driver_time_per_design_s": float(np.mean(per)),
            "fraction_of_optimum_after_32": [float(b) for b in best]}


def real_evaluation() -> dict:
    from gfbopt.design.rotor_objectives import EvaluationSettings, evaluate_rotor_design
    from gfbopt.inputs.grid import Grid
    from gfbopt.inputs.rotor_system import load_rotor
    from gfbopt.static import SolverCache

    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    out = {}
    for grid in ("36x10", "144x36"):
        settings = EvaluationSettings(4000.0, 45000.0, 56250.0, Grid.parse(grid),
                                      heaviest_load_factor=2.0)
        cache = SolverCache(settings.grid)
        t0, c0 = time.perf_counter(), time.process_time()
        evaluate_rotor_design(system, settings, cache)               # builds the solvers
        cold, cold_cpu = time.perf_counter() - t0, time.process_time() - c0
        times, cpu = [], []
        for clearance, preload in ((17.0, 9.0), (23.0, 4.0)):
            t0, c0 = time.perf_counter(), time.process_time()
            row = evaluate_rotor_design(system, settings, cache, radial_clearance_um=clearance,
                                        preload_depth_um=preload)
            times.append(time.perf_counter() - t0)
            cpu.append(time.process_time() - c0)
            assert row["success"], row["message"]
        out[grid] = {"first_evaluation_s": cold, "first_evaluation_cpu_s": cold_cpu,
                     "evaluation_s": float(np.mean(times)),
                     "evaluation_cpu_s": float(np.mean(cpu)), "evaluations": len(times)}
    return {"grid": "36x10", "first_evaluation_s": out["36x10"]["first_evaluation_s"],
            "evaluation_s": out["36x10"]["evaluation_s"],
            "evaluation_cpu_s": out["36x10"]["evaluation_cpu_s"], "evaluations": 2,
            "by_grid": out}


#: designs (radial clearance, preload depth [µm]) spread over the main job's space, for the
#: ranking check of the search grid against the default grid
RANKING_DESIGNS = ((16.0, 11.0), (18.0, 6.0), (22.0, 3.0), (26.0, 9.0), (30.0, 0.0),
                   (34.0, 5.0))


def grid_ranking(grids=("36x10", "72x20", "144x36")) -> dict:
    """The main job's objectives and film limit for :data:`RANKING_DESIGNS` on each grid,
    and how the coarse grids rank them against the default (last) grid: Spearman's rank
    correlation of the first onset and of the power loss, and the designs whose feasibility
    (minimum film at 4,000 rpm under 2× load ≥ 1.5 µm) differs."""
    from scipy.stats import spearmanr

    from gfbopt.design.rotor_objectives import EvaluationSettings, evaluate_rotor_design
    from gfbopt.inputs.grid import Grid
    from gfbopt.inputs.rotor_system import load_rotor
    from gfbopt.static import SolverCache

    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    rows = {}
    for grid in grids:
        settings = EvaluationSettings(4000.0, 45000.0, 56250.0, Grid.parse(grid),
                                      heaviest_load_factor=2.0)
        cache = SolverCache(settings.grid)
        rows[grid] = []
        for c, d in RANKING_DESIGNS:
            c0 = time.process_time()
            r = evaluate_rotor_design(system, settings, cache, radial_clearance_um=c,
                                      preload_depth_um=d)
            rows[grid].append({"radial_clearance_um": c, "preload_depth_um": d,
                               **{k: r.get(k) for k in ("first_onset_speed_rpm",
                                                        "total_power_loss_w",
                                                        "min_film_lowest_speed_um",
                                                        "success")},
                               "cpu_s": time.process_time() - c0})
            print(grid, rows[grid][-1], flush=True)
    ref = rows[grids[-1]]
    agreement = {}
    for grid in grids[:-1]:
        mine = rows[grid]
        agreement[grid] = {
            "spearman_onset": float(spearmanr([r["first_onset_speed_rpm"] for r in mine],
                                              [r["first_onset_speed_rpm"] for r in ref])[0]),
            "spearman_power": float(spearmanr([r["total_power_loss_w"] for r in mine],
                                              [r["total_power_loss_w"] for r in ref])[0]),
            "feasibility_differs": [[r["radial_clearance_um"], r["preload_depth_um"]]
                                    for r, q in zip(mine, ref)
                                    if (r["min_film_lowest_speed_um"] >= 1.5)
                                    != (q["min_film_lowest_speed_um"] >= 1.5)],
            "largest_onset_change": float(max(abs(r["first_onset_speed_rpm"]
                                                  / q["first_onset_speed_rpm"] - 1)
                                              for r, q in zip(mine, ref)))}
    return {"designs": rows, "agreement_with_" + grids[-1]: agreement,
            "min_film_limit_um": 1.5}


def main_job(workers=(1, 2)) -> dict:
    """The README's main job, ``gfbopt run problems/rotor_bearing_design.toml``, in a child
    process per worker count: wall time and the CPU seconds of the run and its pool workers
    (RUSAGE_CHILDREN of this process; the workers are joined, so theirs count)."""
    import resource
    import subprocess

    out = {}
    for n in workers:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run([sys.executable, "-m", "gfbopt", "run",
                            str(ROOT / "problems" / "rotor_bearing_design.toml"),
                            "--workers", str(n), "--results", tmp], check=True,
                           env={**os.environ, "PYTHONPATH": str(ROOT)},
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            first = (Path(tmp) / "rotor_bearing_design" / "README.md").read_text()
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        out[f"workers_{n}"] = {"wall_s": time.perf_counter() - t0,
                               "cpu_s": (after.ru_utime - before.ru_utime
                                         + after.ru_stime - before.ru_stime),
                               "verdict": first.splitlines()[0]}
        print(n, out[f"workers_{n}"], flush=True)
    return out


#: run in a child process with PYTHONPATH = the tree measured: the main job at --workers 1 in
#: this process, the CPU seconds (time.process_time) of each stage's function, the figures
#: of the robustness and default-grid tables, as JSON on the last line
STAGE_CHILD = r"""
import json, sys, time
import pandas as pd
import gfbopt.cli, gfbopt.design.robustness as rb, gfbopt.design.optimiser as opt
import gfbopt.studies.rotor_report as rr
cpu = {}
def timed(module, name, key):
    function = getattr(module, name)
    def run(*a, **k):
        c0 = time.process_time()
        try:
            return function(*a, **k)
        finally:
            cpu[key] = cpu.get(key, 0.0) + time.process_time() - c0
    setattr(module, name, run)
for module, name, key in ((opt, "optimise", "search"), (rb, "regrid", "default-grid check"),
                          (rb, "robustness", "tolerances"),
                          (rb, "whirl_at_top_speed", "whirl at top speed"),
                          (rr, "_reproduce", "reproduction")):
    timed(module, name, key)
c0 = time.process_time()
gfbopt.cli.main(["run", sys.argv[1], "--workers", "1", "--results", sys.argv[2]])
total = time.process_time() - c0
folder = sys.argv[2] + "/rotor_bearing_design/"
tables = {n: pd.read_csv(folder + n + ".csv").select_dtypes("number").to_dict("list")
          for n in ("robustness", "default_grid_check")}
print(json.dumps({"cpu_s": cpu, "total_cpu_s": total, "tables": tables,
                  "verdict": open(folder + "README.md").read().splitlines()[0]}))
"""
#: the stages after the search whose share of the job's CPU is the target
AFTER_SEARCH = ("default-grid check", "tolerances", "whirl at top speed")


def _stage_run(tree: Path) -> dict:
    import subprocess

    env = {**os.environ, "PYTHONPATH": str(tree), "GFBOPT_PROGRESS": "0",
           "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    load = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run([sys.executable, "-c", STAGE_CHILD,
                              str(ROOT / "problems" / "rotor_bearing_design.toml"), tmp],
                             env=env, cwd=tree, capture_output=True, text=True, check=True)
    row = json.loads(out.stdout.strip().splitlines()[-1])
    after = sum(row["cpu_s"].get(k, 0.0) for k in AFTER_SEARCH)
    row.update(after_search_cpu_s=after, after_search_share=after / row["total_cpu_s"],
               load_before=load, load_after=os.getloadavg())
    print(f"{tree}: {row['total_cpu_s']:.1f} s CPU, after the search {after:.1f} s "
          f"({row['after_search_share']:.1%}), load {load[0]:.2f}", flush=True)
    return row


def _relative_changes(old: dict, new: dict) -> dict:
    """Largest |new/old − 1| of each numeric column of each table."""
    out = {}
    for table, columns in old.items():
        for name, values in columns.items():
            a, b = np.array(values, float), np.array(new[table][name], float)
            scale = np.where(a != 0, np.abs(a), 1.0)
            out[f"{table}.{name}"] = float(np.nanmax(np.abs(b - a) / scale, initial=0.0))
    return out


def stage_shares(old_tree, repeats: int) -> dict:
    """The main job's stage CPU in this tree (and ``old_tree``), interleaved A B A B: per
    run, the CPU of each stage and the after-search share; their medians; the tables'
    figures of the last runs and their largest relative change."""
    import statistics

    trees = {"new": ROOT} | ({"old": Path(old_tree)} if old_tree else {})
    runs = {k: [] for k in trees}
    for r in range(repeats):
        for key in (list(trees) if r % 2 == 0 else list(trees)[::-1]):
            runs[key].append(_stage_run(trees[key]))
    from machine import tree_label

    out = {k: {"tree": tree_label(t), "runs": runs[k],
               "median_total_cpu_s": statistics.median(x["total_cpu_s"] for x in runs[k]),
               "median_after_search_share": statistics.median(
                   x["after_search_share"] for x in runs[k]),
               "median_stage_cpu_s": {s: statistics.median(x["cpu_s"].get(s, 0.0)
                                                         for x in runs[k])
                                      for s in runs[k][0]["cpu_s"]}}
           for k, t in trees.items()}
    if old_tree:
        out["largest_relative_change_of_the_tables"] = _relative_changes(
            runs["old"][-1]["tables"], runs["new"][-1]["tables"])
        out["verdicts_equal"] = runs["old"][-1]["verdict"] == runs["new"][-1]["verdict"]
    return out


def main() -> None:
    from gfbopt.parallel import limit_blas_threads
    from gfbopt.provenance import provenance

    # one BLAS thread, as in every gfbopt run and pool worker: multi-threaded OpenBLAS on
    # these small matrices spins against the other process on 2 shared cores (the 0.2-era
    # figure of 29-51 s per evaluation was mostly that: 1.6 s with one thread, idle)
    limit_blas_threads()
    if "--main-job" in sys.argv:
        out = {"load_average_before": os.getloadavg(), "main_job": main_job(),
               "limit_wall_s": 120.0, "load_average_after": os.getloadavg(),
               "cpu_count": os.cpu_count(), "provenance": provenance()}
        path = ROOT / "results" / "benchmarks" / "rotor_design_main_job.json"
        path.write_text(json.dumps(out, indent=2, default=str))
        return
    if "--stages" in sys.argv:
        arg = lambda name, default: (sys.argv[sys.argv.index(name) + 1]  # noqa: E731
                                     if name in sys.argv else default)
        load = os.getloadavg()
        out = {"load_average_before": load,
               **stage_shares(arg("--old", None), int(arg("--repeats", "2"))),
               "after_search_stages": list(AFTER_SEARCH), "target_share": 0.25,
               "load_average_after": os.getloadavg(), "cpu_count": os.cpu_count(),
               "provenance": provenance()}
        path = ROOT / "results" / "benchmarks" / "rotor_design_stages.json"
        path.write_text(json.dumps(out, indent=2, default=str))
        print(json.dumps({k: v for k, v in out.items() if k in (
            "largest_relative_change_of_the_tables", "verdicts_equal")}, indent=2))
        return
    if "--ranking" in sys.argv:
        out = {"load_average_before": os.getloadavg(), **grid_ranking(),
               "load_average_after": os.getloadavg(), "provenance": provenance()}
        path = ROOT / "results" / "benchmarks" / "design_grid_ranking.json"
        path.write_text(json.dumps(out, indent=2, default=str))
        print(json.dumps(out["agreement_with_144x36"], indent=2))
        return

    load_before = os.getloadavg()
    evaluation = real_evaluation()
    nsga = nsga2_overhead()
    bayes = [bayes_overhead(10_000, 10), bayes_overhead(5000, 0)]
    e = evaluation["evaluation_s"]
    out = {"load_average_before": load_before, "load_average_after": os.getloadavg(),
           "cpu_count": os.cpu_count(), "real_evaluation": evaluation, "nsga2": nsga,
           "bayes": bayes,
           "nsga2_overhead_fraction_of_an_evaluation": nsga["residual_per_design_s"] / e,
           "bayes_overhead_fraction_of_an_evaluation": {
               f"{b['acquisition_samples']}/{b['acquisition_starts']}":
               b["driver_time_per_design_s"] / e for b in bayes},
           "limit_fraction": 0.02, "provenance": provenance()}
    path = ROOT / "results" / "benchmarks" / "optimiser.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(out, indent=2, default=str))
    print(json.dumps({k: v for k, v in out.items() if k != "provenance"}, indent=2,
                     default=str))


if __name__ == "__main__":
    main()
