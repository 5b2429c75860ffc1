"""A dense reference search of the shipped main job's design space (problems/rotor_bearing_design.toml):
a full factorial grid of ``--levels`` levels per variable on the study's search grid, every design
evaluated as the search evaluates it (gfbopt.design.rotor_objectives.evaluate_rotor_design).

    nice -n 10 python benchmarks/rotor_design_reference.py --levels 7 --workers 2

writes results/rotor_bearing_design_reference/grid.csv (one row per design, appended chunk by chunk:
a killed run continues where it stopped) and reference.json (the commands, the space, the best
feasible design of everything stored).  Above three variables a grid is coarse, so the
reference adds many seeds of large-budget searches (many seeds, a large budget):

    nice -n 10 python benchmarks/rotor_design_reference.py --search nsga2 --budget 400 \
        --population 16 --seeds 0 1 2 3
    nice -n 10 python benchmarks/rotor_design_reference.py --search nsga2_refine \
        --budget 400 --step 0.001953125 --improvement 1e-4 --seeds 10 11 12 13 14 15

append to searches.csv (every evaluation, with its method and seed); NSGA-II with 400
evaluations is a method independent of the shipped one, the tightly converged search is the
shipped method run far past its stopping rule from other seeds.  The slow test tests/unit/test_search_convergence.py compares the main job's
converged answer with it.
"""
from __future__ import annotations

import argparse
import itertools
import json
import os
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "results" / "rotor_bearing_design_reference"


def main(argv=None) -> int:
    from gfbopt.design.rotor_objectives import evaluate_rotor_design
    from gfbopt.parallel import run_points
    from gfbopt.studies.runner import load_study

    a = argparse.ArgumentParser()
    a.add_argument("--study", default="problems/rotor_bearing_design.toml")
    a.add_argument("--levels", type=int, default=7)
    a.add_argument("--workers", type=int, default=2)
    a.add_argument("--chunk", type=int, default=40)
    a.add_argument("--search", default=None, help="nsga2 or nsga2_refine: seeded searches")
    a.add_argument("--budget", type=int, default=400)
    a.add_argument("--population", type=int, default=8)
    a.add_argument("--step", type=float, default=1.0 / 128)
    a.add_argument("--improvement", type=float, default=1e-3)
    a.add_argument("--seeds", type=int, nargs="*", default=[0])
    args = a.parse_args(argv)
    from gfbopt.guard import Limits

    plan = load_study(ROOT / args.study, Limits(max_minutes=1e6)).plan
    problem = plan.problem
    OUT.mkdir(parents=True, exist_ok=True)
    command = ("nice -n 10 python benchmarks/rotor_design_reference.py "
               + " ".join(argv if argv is not None else sys.argv[1:]))
    if args.search:
        _searches(plan, args, command)
        return _summary(plan, command)
    axes = [np.linspace(0.0, 1.0, args.levels) for _ in problem.variables]
    designs = [problem.decode(u) for u in itertools.product(*axes)]
    table = OUT / "grid.csv"
    done = set()
    if table.is_file():
        done = set(pd.read_csv(table)["point"].astype(str))
    todo = [d for d in designs if problem.key(d) not in done]
    print(f"{len(designs)} designs, {len(done)} done, {len(todo)} to do", flush=True)
    t0, cpu0 = time.perf_counter(), time.process_time()
    fixed = {"system": plan.system, "settings": plan.settings}
    from gfbopt.design.rotor_objectives import design_outputs

    # one column order for every chunk (a failed row has fewer columns than a solved one)
    columns = (list(pd.read_csv(table, nrows=0).columns) if table.is_file() else
               [*design_outputs(plan.settings), "success", "message", "wall_time_s",
                *problem.names, "point", "feasible"])
    for k in range(0, len(todo), args.chunk):
        part = todo[k:k + args.chunk]
        rows = run_points(evaluate_rotor_design, [{**fixed, **d} for d in part],
                          workers=args.workers)
        out = []
        for d, r in zip(part, rows):
            r = {n: v for n, v in r.items() if n not in fixed}
            r.update(d)
            r["point"] = problem.key(d)
            r["feasible"] = problem.feasible(r)
            out.append(r)
        frame = pd.DataFrame.from_records(out).reindex(columns=columns)
        frame.to_csv(table, mode="a", header=not table.is_file(), index=False)
        print(f"{k + len(part)}/{len(todo)} {time.perf_counter() - t0:.0f} s", flush=True)
    return _summary(plan, command)


def _searches(plan, args, command: str) -> None:
    """Seeded searches of the same space, every evaluation appended to searches.csv."""

    from gfbopt.design.optimiser import executor, optimise
    from gfbopt.design.rotor_objectives import evaluate_rotor_design
    from gfbopt.design.search import SearchSettings
    from gfbopt.parallel import WorkerPool

    table = OUT / "searches.csv"
    done = set()
    if table.is_file():
        old = pd.read_csv(table)
        done = set(zip(old["method"], old["seed"], old["budget"]))
    for seed in args.seeds:
        if (args.search, seed, args.budget) in done:
            continue
        s = SearchSettings(args.search, budget=args.budget, population=args.population,
                           seed=seed, step_tolerance=args.step,
                           improvement=args.improvement)
        t0 = time.perf_counter()
        with WorkerPool(args.workers):
            r = optimise(plan.problem, evaluate_rotor_design, s,
                         fixed={"system": plan.system, "settings": plan.settings},
                         run_tasks=executor(args.workers))
        frame = r.table.copy()
        frame.insert(0, "method", args.search)
        frame.insert(1, "seed", seed)
        frame.insert(2, "budget", args.budget)
        frame["convergence"] = r.convergence
        frame.to_csv(table, mode="a", header=not table.is_file(), index=False)
        feasible = frame[frame["feasible"].astype(bool)]
        print(f"{args.search} seed {seed}: {len(frame)} designs, best "
              f"{feasible['first_onset_speed_rpm'].max():.1f} rpm, {r.convergence}, "
              f"{time.perf_counter() - t0:.0f} s", flush=True)
    with open(OUT / "commands.txt", "a") as f:
        f.write(command + "\n")


def _summary(plan, command: str) -> int:
    """reference.json: the best feasible design of the grid and of every seeded search."""
    problem = plan.problem
    parts = {}
    for name in ("grid", "searches"):
        path = OUT / f"{name}.csv"
        if path.is_file():
            frame = pd.read_csv(path)
            parts[name] = frame[frame["feasible"].astype(bool)]
    everything = pd.concat(list(parts.values()), ignore_index=True)
    best = everything.loc[everything["first_onset_speed_rpm"].idxmax()]
    per = {}
    for name, frame in parts.items():
        if name == "grid":
            per["grid"] = {"designs": int(len(pd.read_csv(OUT / "grid.csv"))),
                           "best_first_onset_rpm":
                           float(frame["first_onset_speed_rpm"].max())}
        else:
            for (method, seed), g in frame.groupby(["method", "seed"]):
                per[f"{method} seed {seed}"] = {
                    "best_first_onset_rpm": float(g["first_onset_speed_rpm"].max())}
    commands = (OUT / "commands.txt").read_text().splitlines() \
        if (OUT / "commands.txt").is_file() else []
    info = {"commands": sorted(set(commands + [command])),
            "study": "problems/rotor_bearing_design.toml", "grid": str(plan.settings.grid),
            "variables": problem.to_dict()["variables"],
            "constraints": problem.to_dict()["constraints"],
            "best_first_onset_rpm": float(best["first_onset_speed_rpm"]),
            "best_design": {n: float(best[n]) for n in problem.names},
            "best_min_film_lowest_speed_um": float(best["min_film_lowest_speed_um"]),
            "best_from": str(best.get("method", "grid")) if isinstance(
                best.get("method"), str) else "grid",
            "parts": per, "load_at_end": list(os.getloadavg())}
    (OUT / "reference.json").write_text(json.dumps(info, indent=2) + "\n")
    print(json.dumps({k: info[k] for k in ("best_first_onset_rpm", "best_design",
                                            "parts")}, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
