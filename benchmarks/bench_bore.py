"""The bearing as built: a preload or zone change costs no rebuild, and a static
solve with a preload is within 1.2× of the round bore at the same grid — in one run.

Run:  PYTHONPATH=. python benchmarks/bench_bore.py [--out FILE.json] [--grids 72x20 144x36]
(default results/benchmarks/bore.json)

Bearing: Ruscitto (problems/bearings/ruscitto.toml) at 45,000 rpm under 20 N, seam 180° from
the load, simple foundation.  Per grid:

1. **No rebuild.**  One :class:`~gfbopt.static.SolverCache` serves the round bore, 3 shims at
   eight preload depths (1–12 µm), 3 lobes and two zone layouts: the number of builds (must
   be 1) and the build time beside the time of one solve after a parameter change.
2. **Preload costs no solve time.**  Paired, interleaved cold solves (the same cold start,
   continuation on failure) of the round bore and of 3 shims with 5 µm and 10 µm of preload,
   `repeats` times; the ratio of median wall times, the IPOPT iteration counts and the ratio
   per iteration (the same build and sparsity: a preload changes the parameters only, so any
   difference is iterations).  Target ≤ 1.2.  Warm solves (from the previous load of a small
   load sweep, ±20 % around 20 N) are timed the same way.
"""
from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import dataclasses  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, write_report  # noqa: E402
from gfbopt import Grid, solve_static  # noqa: E402
from gfbopt.inputs import load_bearing  # noqa: E402
from gfbopt.inputs.bore_si import BearingBuild, BoreSpec, ZoneSpec  # noqa: E402
from gfbopt.static import SolverCache  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
SPEED, LOAD = 45000.0, 20.0
TARGET_RATIO = 1.2


def _model(bearing, build=None):
    geometry = bearing if build is None else dataclasses.replace(bearing, build=build)
    return geometry.model(SPEED, film="seam", seam_angle_deg=180.0)


def _shims(depth_um: float) -> BearingBuild:
    return BearingBuild(BoreSpec("shims", 3, preload_depth=depth_um * 1e-6, width_deg=60.0))


def no_rebuild(bearing, grid: Grid) -> dict:
    cache = SolverCache(grid)
    t0 = time.perf_counter()
    round_model = _model(bearing)
    solver = cache(round_model)
    build_s = time.perf_counter() - t0
    load = bearing.nondimensional_load(LOAD)
    builds = [_shims(d) for d in (1, 2, 4, 6, 8, 10, 12)]
    builds += [BearingBuild(BoreSpec("lobes", 3, preload_ratio=0.2)),
               BearingBuild(zones=(ZoneSpec(0.0, 180.0, bump_thickness=80e-6),
                                   ZoneSpec(180.0, 360.0))),
               BearingBuild(zones=(ZoneSpec(-90.0, 90.0, bump_pitch=4.0e-3),
                                   ZoneSpec(90.0, 270.0)))]
    times, ok = [], []
    for build in builds:
        model = _model(bearing, build)
        t = time.perf_counter()
        sol = solve_static(model, load=load, solver=cache(model))
        times.append(time.perf_counter() - t)
        ok.append(sol.success)
    return {"builds": len(cache), "variants": len(builds) + 1, "build_s": build_s,
            "solve_after_change_median_s": statistics.median(times),
            "all_converged": all(ok), "same_solver": cache(round_model) is solver}


def paired(bearing, grid: Grid, repeats: int) -> dict:
    cache = SolverCache(grid)
    load = bearing.nondimensional_load(LOAD)
    variants = {"round": _model(bearing), "shims_5um": _model(bearing, _shims(5.0)),
                "shims_10um": _model(bearing, _shims(10.0))}
    for model in variants.values():                      # build (and warm the caches) once
        solve_static(model, load=load, solver=cache(model))
    cold = {k: [] for k in variants}
    iterations = {}
    warm = {k: [] for k in variants}
    sweep = [load * f for f in (0.8, 0.9, 1.0, 1.1, 1.2)]
    for _ in range(repeats):
        for name, model in variants.items():             # interleaved: same machine state
            t = time.perf_counter()
            sol = solve_static(model, load=load, solver=cache(model))
            cold[name].append(time.perf_counter() - t)
            iterations[name] = sol.iterations
            previous = solve_static(model, load=sweep[0], solver=cache(model))
            t = time.perf_counter()
            for w in sweep[1:]:
                previous = solve_static(model, load=w, solver=cache(model), initial=previous)
            warm[name].append((time.perf_counter() - t) / (len(sweep) - 1))
    med = {k: statistics.median(v) for k, v in cold.items()}
    medw = {k: statistics.median(v) for k, v in warm.items()}
    per_iteration = {k: med[k] / max(iterations[k], 1) for k in med}
    return {"cold_median_s": med, "warm_median_s": medw, "iterations": iterations,
            "cold_per_iteration_ratio": {k: per_iteration[k] / per_iteration["round"]
                                         for k in med if k != "round"},
            "cold_ratio": {k: med[k] / med["round"] for k in med if k != "round"},
            "warm_ratio": {k: medw[k] / medw["round"] for k in medw if k != "round"},
            "repeats": repeats}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(REPO / "results/benchmarks/bore.json"))
    parser.add_argument("--grids", nargs="+", default=["72x20", "144x36"])
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    bearing = load_bearing(REPO / "problems/bearings/ruscitto.toml")
    out = {"machine": machine_info(load_average=os.getloadavg()),
           "bearing": bearing.name, "speed_rpm": SPEED, "load_newton": LOAD,
           "target_ratio": TARGET_RATIO, "grids": {}}
    for text in args.grids:
        grid = Grid.parse(text)
        t0 = time.perf_counter()
        entry = {"no_rebuild": no_rebuild(bearing, grid),
                 "solve_time": paired(bearing, grid, args.repeats)}
        worst = max(entry["solve_time"]["cold_ratio"].values())
        entry["meets_target"] = bool(entry["no_rebuild"]["builds"] == 1
                                     and worst <= TARGET_RATIO)
        entry["wall_s"] = time.perf_counter() - t0
        out["grids"][text] = entry
        print(text, entry["no_rebuild"], entry["solve_time"]["cold_ratio"],
              entry["solve_time"]["warm_ratio"], entry["solve_time"]["iterations"])
    out["machine"]["load_average_after"] = os.getloadavg()
    write_report(out, args.out)


if __name__ == "__main__":
    main()
