"""CPU time of the same rotor analysis from the command line and from the Python API, in one run.

    PYTHONPATH=. python benchmarks/bench_api_threads.py [--grids 36x10 72x20] [--repeats 3] \\
        [--everything] [--out results/benchmarks/api_threads.json]

Every run is a fresh interpreter started without OPENBLAS_NUM_THREADS, OMP_NUM_THREADS and
MKL_NUM_THREADS (removed from the environment if set here), as a user starts either:

* ``cli``: ``gfbopt rotor problems/rotors/blower.toml --speed-range 5000 60000 --grid G --json``
  (the command line pins one BLAS thread for its whole process);
* ``api``: ``analyse_rotor(load_rotor(...), (5000, 60000), grid=Grid.parse(G))`` in a plain
  script (the library limits the threads inside its own calls: gfbopt.threads);
* ``api_user_threads`` (unless ``--no-user-threads``): the same script with
  OPENBLAS_NUM_THREADS = OMP_NUM_THREADS = the machine's CPU count, which the library keeps
  as the user's choice: the BLAS threading the API ran with before it limited its threads.

``--everything`` adds the Campbell diagram, the imbalance response and the half-mass
approximation to every run (``--campbell --imbalance-response --half-mass``; ``campbell=True,
imbalance=True, half_mass=True``).

CPU time is the child's user + system time (getrusage of the waited child: every thread,
interpreter start and imports included, the same for all three); ``analysis_cpu_s`` is the
API script's time.process_time() around the call alone.  The runs are interleaved (the order
rotates each repeat) and the 1-minute load average is recorded before and after each, since
the machine is shared.  The ratio reported per grid is the median over repeats of
api / cli CPU time of the same repeat; the target is <= 1.2.  The onsets of all runs are
compared bit for bit with the command line's.
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
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, write_report  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
ROTOR = "problems/rotors/blower.toml"
SPEED_RANGE = (5000.0, 60000.0)
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
TARGET = 1.2

API_SCRIPT = r"""
import json, sys, time
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.analyse import analyse_rotor
rotor, grid, low, high = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
everything = sys.argv[5] == "1"
system = load_rotor(rotor)
cpu, wall = time.process_time(), time.perf_counter()
result = analyse_rotor(system, (low, high), grid=Grid.parse(grid), show_progress=False,
                       campbell=everything, imbalance=everything, half_mass=everything)
print(json.dumps({"onset_speed_rpm": result.onsets.onset_speed_rpm,
                  "first_mode": result.onsets.first_mode,
                  "analysis_cpu_s": time.process_time() - cpu,
                  "analysis_wall_s": time.perf_counter() - wall}))
"""


def _environment(threads: int | None) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in THREAD_VARIABLES}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
    if threads is not None:
        env["OPENBLAS_NUM_THREADS"] = env["OMP_NUM_THREADS"] = str(threads)
    return env


def _command(variant: str, grid: str, low: float, high: float, everything: bool) -> list:
    if variant == "cli":
        return [sys.executable, "-m", "gfbopt", "rotor", ROTOR, "--speed-range", f"{low:g}",
                f"{high:g}", "--grid", grid, "--json"] + (
            ["--campbell", "--imbalance-response", "--half-mass"] if everything else [])
    return [sys.executable, "-c", API_SCRIPT, ROTOR, grid, f"{low:g}", f"{high:g}",
            str(int(everything))]


def run_once(variant: str, grid: str, low: float, high: float, everything: bool) -> dict:
    """One fresh interpreter: its CPU and wall time, the load around it and its answer."""
    threads = os.cpu_count() if variant == "api_user_threads" else None
    load_before = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall = time.perf_counter()
    out = subprocess.run(_command(variant, grid, low, high, everything), cwd=ROOT,
                         env=_environment(threads), capture_output=True, text=True)
    wall = time.perf_counter() - wall
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode != 0:
        raise RuntimeError(f"{variant} {grid} exited {out.returncode}: {out.stderr[-2000:]}")
    if variant == "cli":
        answer = json.JSONDecoder().raw_decode(out.stdout)[0]
        answer = {"onset_speed_rpm": answer["onset_speed_rpm"],
                  "first_mode": answer["first_mode"]}
    else:
        answer = json.loads(out.stdout.strip().splitlines()[-1])
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    return {"variant": variant, "grid": grid, "blas_threads_env": threads, "cpu_s": cpu,
            "wall_s": wall, "load_1min_before": load_before,
            "load_1min_after": os.getloadavg()[0], **answer}


def _source() -> dict:
    """The commit measured and whether the work tree differed from it."""
    def git(*args):
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True,
                              text=True).stdout.strip()

    return {"commit": git("rev-parse", "HEAD"),
            "uncommitted_changes": bool(git("status", "--porcelain", "--untracked-files=no"))}


def summarise(runs: list, variants: list) -> dict:
    """Per variant: median CPU and wall time; the paired api / cli ratios; bitwise onsets."""
    by = {v: [r for r in runs if r["variant"] == v] for v in variants}
    out = {v: {"cpu_s_median": statistics.median(r["cpu_s"] for r in rs),
               "cpu_s": [r["cpu_s"] for r in rs],
               "wall_s_median": statistics.median(r["wall_s"] for r in rs)}
           for v, rs in by.items()}
    reference = by["cli"][0]["onset_speed_rpm"]
    for v in variants:
        if v != "cli":
            ratios = [a["cpu_s"] / c["cpu_s"] for a, c in zip(by[v], by["cli"])]
            out[v]["cpu_ratio_to_cli"] = ratios
            out[v]["cpu_ratio_to_cli_median"] = statistics.median(ratios)
        out[v]["onsets_rpm"] = sorted({r["onset_speed_rpm"] for r in by[v]})
        out[v]["onset_max_relative_difference_to_cli"] = max(
            abs(r["onset_speed_rpm"] / reference - 1.0) for r in by[v])
    out["api_within_target"] = out["api"]["cpu_ratio_to_cli_median"] <= TARGET
    out["api_onset_bitwise_equal_to_cli"] = all(
        r["onset_speed_rpm"] == reference for r in by["api"] + by["cli"])
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--grids", nargs="+", default=["36x10", "72x20"])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--no-user-threads", action="store_true",
                        help="skip the API run with the user's thread variables set")
    parser.add_argument("--everything", action="store_true",
                        help="Campbell diagram, imbalance response and half-mass onsets too")
    parser.add_argument("--out", default=str(ROOT / "results/benchmarks/api_threads.json"))
    args = parser.parse_args(argv)
    low, high = SPEED_RANGE
    variants = ["cli", "api"] + ([] if args.no_user_threads else ["api_user_threads"])
    runs = []
    for repeat in range(args.repeats):
        for grid in args.grids:
            order = variants[repeat % len(variants):] + variants[:repeat % len(variants)]
            for variant in order:
                row = run_once(variant, grid, low, high, args.everything) | {"repeat": repeat}
                runs.append(row)
                print(f"{grid:>7} {variant:<17} cpu {row['cpu_s']:7.2f} s  wall "
                      f"{row['wall_s']:7.2f} s  load {row['load_1min_before']:.2f}  onset "
                      f"{row['onset_speed_rpm']!r}", flush=True)
    grids = {g: summarise([r for r in runs if r["grid"] == g], variants) for g in args.grids}
    for g, s in grids.items():
        print(f"{g}: api/cli CPU {s['api']['cpu_ratio_to_cli_median']:.2f} (target <= "
              f"{TARGET}), onsets bitwise equal: {s['api_onset_bitwise_equal_to_cli']}"
              + (f"; with the user's {os.cpu_count()} BLAS threads "
                 f"{s['api_user_threads']['cpu_ratio_to_cli_median']:.2f}"
                 if "api_user_threads" in s else ""))
    out = {"benchmark": "bench_api_threads", "rotor": ROTOR, "speed_range_rpm": SPEED_RANGE,
           "analyses": ("onsets, Campbell diagram, imbalance response, half-mass onsets"
                        if args.everything else "onsets"),
           "target_cpu_ratio": TARGET, "repeats": args.repeats, "variants": variants,
           "machine": machine_info(child_thread_env="unset (removed) except api_user_threads",
                                   source=_source()),
           "grids": grids, "runs": runs}
    write_report(out, args.out)
    return 0 if all(s["api_within_target"] for s in grids.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
