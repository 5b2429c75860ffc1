"""The process pool's driver cost and the store's row conversion, before and after.

**Driver** (``stream``): ``--sizes`` points of a cheap numpy analysis (bench_dask's short
bearing, about 0.3 ms a point) in tasks of 4 points (``run_doe``'s default chunk) streamed
through a 2-worker :class:`gfbopt.parallel.WorkerPool` by

* ``old``: the streaming loop before the change (copied below, :func:`_old_stream_pool`):
  every task submitted at once, ``wait`` over every pending future after each completion;
* ``new``: :func:`gfbopt.pool_stream.stream_pool`, at most 2 tasks per worker in flight.

Each run is a subprocess; old and new alternate for ``--repeats`` rounds at each size
(``--large-repeats`` above 10⁴ points); the
driver's CPU is ``getrusage(RUSAGE_SELF)`` (all its threads: the executor's manager thread
included), the workers' excluded.  The rows (index → result) of old and new are compared.
Measured (results/benchmarks/pool_stream.json, load 3-7 from other jobs): driver CPU at
10⁴ points 1.15 → 0.24 s, at 10⁵ points 25.9 → 4.8 s (0.19 ms a task, the executor's own
cost); 1,690 → 3,206 points/s at 10⁵; 10⁴ rows to Arrow 11.2 → 6.0 ms CPU.

**Store** (``conform``): a part of ``--rows`` rows of a study's schema (ints, floats, bools,
strings, a few nulls) converted to an Arrow table by the pandas route
(``_conform`` + ``Table.from_pandas``, before) and by ``_conform_table`` (after), interleaved
in this process, CPU seconds, median of ``--repeats``; the tables are compared.

    OMP_NUM_THREADS=1 python benchmarks/bench_pool_stream.py [--sizes 10000 100000]
        [--repeats 2] [--large-repeats 1] [--old-max 100000] [--out results/benchmarks/pool_stream.json]
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time
from concurrent.futures import FIRST_COMPLETED, CancelledError, wait
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))


def cheap(points: list) -> list:
    """One task: 4 points of bench_dask's short-bearing analysis (about 0.3 ms each)."""
    from bench_dask import short_bearing

    return [short_bearing(load, ratio)["eccentricity"] for load, ratio in points]


def _old_stream_pool(function, arguments, pool, retries, tick):
    """gfbopt.parallel._stream_pool as it was before the change (commit 0c7535c)."""
    from gfbopt.pool_stream import forking
    from gfbopt.runtime import InfrastructureFailure, call_task

    todo = set(range(len(arguments)))
    attempts = [0] * len(arguments)
    while todo:
        try:
            executor = pool.executor(len(todo))
            with forking(pool.method == "fork"):
                futures = {executor.submit(call_task, function, arguments[k]): k
                           for k in sorted(todo)}
        except BrokenProcessPool:
            futures = {}
        broken = not futures
        pending = set(futures)
        try:
            while pending:
                done, pending = wait(pending, timeout=tick, return_when=FIRST_COMPLETED)
                if not done:
                    yield None, None
                    continue
                for future in done:
                    k = futures[future]
                    try:
                        result = future.result()
                    except (BrokenProcessPool, CancelledError):
                        broken = True
                        continue
                    todo.discard(k)
                    yield k, result
        except BaseException:
            pool.terminate()
            raise
        if broken and todo:
            pool.restart()
            for k in sorted(todo):
                attempts[k] += 1
                if attempts[k] > retries:
                    todo.discard(k)
                    yield k, InfrastructureFailure("died")


def _cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def one(config: str, points: int) -> dict:
    """One streamed run in this process: driver CPU, wall, a digest of the rows."""
    from bench_pool_stream import cheap as task      # picklable by module name
    from gfbopt.parallel import WorkerPool
    from gfbopt.pool_stream import stream_pool

    rng = np.random.default_rng(7)
    values = np.column_stack([rng.uniform(0.05, 2.0, points), rng.uniform(0.3, 1.0, points)])
    arguments = [values[k:k + 4].tolist() for k in range(0, points, 4)]
    loop = _old_stream_pool if config == "old" else stream_pool
    out = [None] * len(arguments)
    c0, t0 = _cpu(), time.perf_counter()
    with WorkerPool(2) as pool:
        for k, result in loop(task, arguments, pool, 2, None):
            out[k] = result
    wall, cpu = time.perf_counter() - t0, _cpu() - c0
    flat = np.array([v for rows in out for v in rows])
    return {"config": config, "points": points, "tasks": len(arguments),
            "driver_cpu_s": cpu, "wall_s": wall, "points_per_s": points / wall,
            "rows_sum": float(flat.sum()), "rows": len(flat),
            "rows_digest": float(np.dot(flat, np.arange(1, len(flat) + 1) % 97))}


def _spawn(config: str, points: int) -> dict:
    code = (f"import sys, json; sys.path.insert(0, {str(HERE)!r}); import bench_pool_stream "
            f"as b; print(json.dumps(b.one({config!r}, {points})))")
    load0 = os.getloadavg()[0]
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, env={**os.environ, "OMP_NUM_THREADS": "1",
                                          "OPENBLAS_NUM_THREADS": "1"})
    result = json.loads(out.stdout.strip().splitlines()[-1])
    result["load_before"], result["load_after"] = load0, os.getloadavg()[0]
    return result


def conform_rows(n: int) -> tuple[list[dict], dict]:
    schema = {"point": "int64", "variant": "string", "speed_rpm": "float64",
              "load_N": "float64", "h_min_um": "float64", "stable": "bool",
              "iterations": "int64", "success": "bool", "message": "string",
              "wall_time_s": "float64", "worker": "string"}
    rng = np.random.default_rng(3)
    rows = []
    for k in range(n):
        ok = bool(rng.random() > 0.05)
        rows.append({"point": k, "variant": f"v{k % 7}", "speed_rpm": float(rng.uniform(1e4, 6e4)),
                     "load_N": float(rng.uniform(5, 50)),
                     "h_min_um": float(rng.uniform(2, 9)) if ok else float("nan"),
                     "stable": ok and bool(rng.random() > 0.5), "iterations": int(rng.integers(3, 30)),
                     "success": ok, "message": None if ok else "ParameterError: load",
                     "wall_time_s": float(rng.uniform(0.01, 0.1)), "worker": "host:1234"})
    return rows, schema


def conform_benchmark(n: int, repeats: int) -> dict:
    import pyarrow as pa

    from gfbopt.doe.store import _arrow_schema, _conform, _conform_table

    rows, schema = conform_rows(n)

    def old():
        return pa.Table.from_pandas(_conform(rows, schema), schema=_arrow_schema(schema),
                                    preserve_index=False).replace_schema_metadata(None)

    times = {"pandas": [], "arrow": []}
    for _ in range(repeats):
        for name, fn in (("pandas", old), ("arrow", lambda: _conform_table(rows, schema))):
            t0 = time.process_time()
            table = fn()
            times[name].append(time.process_time() - t0)
    same = old().equals(_conform_table(rows, schema))
    med = {k: statistics.median(v) for k, v in times.items()}
    return {"rows": n, "cpu_s": times, "median_cpu_s": med,
            "ratio_pandas_over_arrow": med["pandas"] / med["arrow"], "tables_equal": same,
            "table_rows": table.num_rows}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[10_000, 100_000])
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--old-max", type=int, default=100_000,
                        help="largest size the old loop runs at (it is quadratic)")
    parser.add_argument("--large-repeats", type=int, default=1,
                        help="rounds at sizes above 10,000 points")
    parser.add_argument("--rows", type=int, default=10_000)
    parser.add_argument("--out", default=str(HERE.parent / "results/benchmarks/pool_stream.json"))
    args = parser.parse_args()
    from machine import machine_info, tree_label, write_report

    runs = []
    for points in args.sizes:
        configs = ["old", "new"] if points <= args.old_max else ["new"]
        for _ in range(args.repeats if points <= 10_000 else args.large_repeats):
            for config in configs:
                runs.append(_spawn(config, points))
                print(json.dumps(runs[-1]), flush=True)
    summary = {}
    for points in args.sizes:
        for config in ("old", "new"):
            mine = [r for r in runs if r["points"] == points and r["config"] == config]
            if mine:
                summary[f"{config}@{points}"] = {
                    "driver_cpu_s": statistics.median(r["driver_cpu_s"] for r in mine),
                    "points_per_s": statistics.median(r["points_per_s"] for r in mine)}
        digests = {(r["rows"], r["rows_digest"]) for r in runs if r["points"] == points}
        summary[f"rows_equal@{points}"] = len(digests) == 1
    conform = conform_benchmark(args.rows, max(3, args.repeats))
    print(json.dumps(conform["median_cpu_s"]), conform["ratio_pandas_over_arrow"])
    report = {"machine": machine_info(code=tree_label(HERE.parent)), "runs": runs,
              "summary": summary, "conform": conform}
    print(json.dumps(summary, indent=1))
    print(write_report(report, args.out))


if __name__ == "__main__":
    main()
