"""Throughput of a sampled static sweep (gfbopt.studies.doe) on the 72 × 20 grid.

The study is ``problems/sweep_static_lhs.toml`` with fewer points (``--points``, default 192,
same ranges: Λ ∈ [0.3, 5] log, ε ∈ [0.1, 0.8], S ∈ [0.1, 2] log, L/D ∈ [0.5, 1.5]), run end to
end by :func:`gfbopt.studies.doe.run_sampled` (sample, ordering, chunks, executor, Parquet
store) into a temporary folder, on:

* serial (this process), chunks of 16 with warm starts, and chunks of 1 (no warm starts);
* the process pool with 1 and 2 workers;
* Dask (``distributed.LocalCluster``, processes, 1 thread each) with 1 and 2 workers.

Measures per configuration: wall time (including one solver build per worker, ≈ 0.6 s, and the
worker start-up), points per second, the solve rate per core (points / Σ per-point wall time
in the workers: the steady-state cost of one equilibrium), mean IPOPT iterations, and the
runner overhead per point = (wall × workers − Σ per-point time) / points (start-up, builds,
transfer, store writes), also as a fraction of a solve.  Parallel efficiency on 2 workers =
rate(2) / (2 rate(1)).  The machine's load average is recorded: on a shared machine the
numbers are lower bounds.

    python benchmarks/bench_sweep.py [--points 192] [--out results/benchmarks/sweep.json]
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from machine import machine_info, write_report


def _study(points: int, chunk: int):
    from gfbopt.inputs import read_toml
    from gfbopt.studies import study_from_dict

    root = Path(__file__).resolve().parents[1]
    data = read_toml(root / "problems" / "sweep_static_lhs.toml")
    data["sampling"]["n"] = points
    data["chunk_size"] = chunk
    data["name"] = f"bench_sweep_{chunk}"
    return study_from_dict(data, file="bench_sweep.toml")


def _measure(loaded, label: str, workers: int, client=None) -> dict:
    from gfbopt.doe import read_results
    from gfbopt.studies.doe import run_sampled

    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        run_sampled(loaded, tmp, workers=workers, client=client, write=False)
        wall = time.perf_counter() - t0
        frame = read_results(Path(tmp) / loaded.study.name / "store")
    n = len(frame)
    solve = float(frame["wall_time_s"].sum())
    ok = frame["success"].astype(bool)
    out = {"executor": label, "workers": workers, "points": n, "succeeded": int(ok.sum()),
           "wall_s": wall, "points_per_s": n / wall,
           "points_per_s_per_core": n / wall / workers,
           "solve_rate_per_core": n / solve, "mean_solve_s": solve / n,
           "mean_iterations": float(frame.loc[ok, "iterations"].mean()),
           "overhead_per_point_s": (wall * workers - solve) / n,
           "overhead_fraction_of_solve": (wall * workers - solve) / solve,
           "distinct_workers": int(frame["worker"].nunique())}
    print(f"{label:28s} workers {workers}: {out['points_per_s']:6.2f} points/s, "
          f"solve rate {out['solve_rate_per_core']:6.2f}/s/core, "
          f"{out['mean_iterations']:.1f} it, overhead {out['overhead_per_point_s'] * 1e3:.1f} "
          f"ms/point ({out['overhead_fraction_of_solve']:.1%})", flush=True)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=192)
    parser.add_argument("--out", default="results/benchmarks/sweep.json")
    args = parser.parse_args()
    from gfbopt.parallel import limit_blas_threads

    limit_blas_threads()
    warm, cold = _study(args.points, 16), _study(args.points, 1)
    runs = [_measure(warm, "serial, warm starts", 1), _measure(cold, "serial, no warm starts",
                                                               1),
            _measure(warm, "process pool", 1), _measure(warm, "process pool", 2)]
    try:
        import distributed
    except ImportError:  # pragma: no cover
        distributed = None
    if distributed is not None:
        for n in (1, 2):
            with distributed.LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                          dashboard_address=None) as cluster, \
                    distributed.Client(cluster) as client:
                runs.append(_measure(warm, "dask LocalCluster", n, client))
    rate = {(r["executor"], r["workers"]): r["points_per_s"] for r in runs}
    eff = {ex: rate[(ex, 2)] / (2 * rate[(ex, 1)]) for ex in ("process pool",
                                                                "dask LocalCluster")
           if (ex, 2) in rate}
    for ex, e in eff.items():
        print(f"parallel efficiency on 2 workers, {ex}: {e:.0%}")
    write_report(machine_info(benchmark="sweep", grid="72x20", points=args.points,
                              load_average=os.getloadavg(), runs=runs,
                              parallel_efficiency_2_workers=eff,
                              targets={"solve_rate_per_core": 15.0,
                                       "parallel_efficiency": 0.8,
                                       "overhead_fraction_of_solve": 0.05}), args.out)


if __name__ == "__main__":
    main()
