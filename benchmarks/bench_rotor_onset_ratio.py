"""The rotor's onset of every mode against the two bearings' one-bearing onset searches, in one
run: the ratio CPU(rotor) / (CPU(bearing A) + CPU(bearing B)), target ≤ 1.2.

Case: problems/rotors/blower.toml over 4,000–60,000 rpm at 144 × 36 (both searches guided by
36 × 10, the default) and 72 × 20 (no guide).  Rotor: :func:`gfbopt.rotor.system.rotor_onsets`
on a fresh SpeedLine over the built cache (as benchmarks/bench_rotor.py times it).  One
bearing: :func:`gfbopt.rotor.onset_speed` for each bearing with its own static load and mass
share (``RotorCase.mass_share_kg``) and its own resolved options, method "secant" (as
benchmarks/bench_onset.py times it).  Also the rotor on the reference line (every crossing at
every speed, ``SpeedLine(local=False)``) when the code has it, and the agreement of the onsets.
All after the builds (a first run of each builds the CasADi solvers); the three are
interleaved ``--repeats`` times and the medians taken (CPU time of this process; the machine
is shared, so the load average before and after is recorded).  Where the time goes: the
rotor's CPU split by stage and grid (statics, full crossings, local crossings).

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONPATH=. python \\
        benchmarks/bench_rotor_onset_ratio.py [--out results/benchmarks/rotor_onset_ratio.json]
        [--repeats 3] [--grids 144x36,72x20]
"""
from __future__ import annotations

import argparse
import inspect
import os
import statistics
import subprocess
import sys
import time
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, write_report  # noqa: E402
from gfbopt import Grid, SolverCache
from gfbopt.inputs import Rotor
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor import onset_speed
from gfbopt.rotor import system as system_module
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine, rotor_onsets

ROOT = Path(__file__).resolve().parents[1]
SPAN = (4000.0, 60000.0)
TARGET = 1.2
MINE = ["gfbopt/rotor", "gfbopt/linear", "benchmarks/bench_rotor_onset_ratio.py"]
LOCAL = "local" in inspect.signature(SpeedLine).parameters


def _source() -> dict:
    def git(*args):
        return subprocess.run(["git", *args], cwd=Path(system_module.__file__).parents[2],
                              capture_output=True, text=True).stdout.strip()
    return {"commit": git("rev-parse", "HEAD"),
            "measured_files_dirty": bool(git("status", "--porcelain", "--", *MINE)),
            "tree_dirty": bool(git("status", "--porcelain", "--untracked-files=no"))}


def _cpu(function):
    c = time.process_time()
    out = function()
    return time.process_time() - c, out


def _breakdown(system, grid: Grid, cache) -> dict:
    """CPU of one rotor run split by stage and grid (wrapping the stage functions)."""
    spent, calls = defaultdict(float), defaultdict(int)
    names = [n for n in ("support_states", "crossings", "local_crossing")
             if hasattr(system_module, n)]
    saved = {n: getattr(system_module, n) for n in names}

    def wrap(name, f):
        def timed(rotor, *args, **kwargs):
            c = time.process_time()
            try:
                return f(rotor, *args, **kwargs)
            finally:
                key = f"{name} {rotor.grid}"
                spent[key] += time.process_time() - c
                calls[key] += 1
        return timed

    for n in names:
        setattr(system_module, n, wrap(n, saved[n]))
    try:
        total, _ = _cpu(lambda: rotor_onsets(system, SPAN, line=SpeedLine(
            resolve_rotor(system, grid, cache)), show_progress=False))
    finally:
        for n, f in saved.items():
            setattr(system_module, n, f)
    out = {k: {"cpu_s": v, "calls": calls[k]} for k, v in sorted(spent.items())}
    out["other_cpu_s"] = total - sum(spent.values())
    out["total_cpu_s"] = total
    return out


def bench(system, grid: Grid, repeats: int) -> dict:
    cache = SolverCache(grid)
    rotor = resolve_rotor(system, grid, cache)

    def run_rotor(local=True):
        line = SpeedLine(resolve_rotor(system, grid, cache), **({"local": local} if LOCAL
                                                                 else {}))
        return rotor_onsets(system, SPAN, line=line, show_progress=False)

    def run_bearing(k):
        case, load = rotor.cases[k], rotor.loads[k]
        return onset_speed(case.bearing, Rotor(rotor.mass_share_kg[k]), load.magnitude, SPAN,
                           options=case.options, grid=grid, cache=cache)

    variants = {"rotor": run_rotor, "bearing_A": lambda: run_bearing(0),
                "bearing_B": lambda: run_bearing(1)}
    if LOCAL:
        variants["rotor_reference_line"] = lambda: run_rotor(False)
    for f in variants.values():                        # builds
        f()
    cpus, answers = defaultdict(list), {}
    for _ in range(repeats):
        for name, f in variants.items():
            cpu, answers[name] = _cpu(f)
            cpus[name].append(cpu)
    med = {k: statistics.median(v) for k, v in cpus.items()}
    bearings = med["bearing_A"] + med["bearing_B"]
    rotor_res = answers["rotor"]
    out = {"grid": str(grid), "cpu_s": dict(cpus), "cpu_s_median": med,
           "ratio_rotor_over_two_bearings": med["rotor"] / bearings,
           "target": TARGET, "met": med["rotor"] / bearings <= TARGET,
           "rotor_modes": {m.label: {"onset_speed_rpm": m.onset_speed_rpm,
                                     "whirl_ratio": m.whirl_ratio, "status": m.status}
                           for m in rotor_res.modes},
           "one_bearing_onsets_rpm": {n: answers[n].onset_speed_rpm
                                      for n in ("bearing_A", "bearing_B")},
           "one_bearing_fine_evaluations": {n: answers[n].evaluations
                                            for n in ("bearing_A", "bearing_B")},
           "rotor_fine_speeds": len({r["speed_rpm"] for r in rotor_res.scan
                                     if r["grid"] == str(grid)}),
           "rotor_coarse_speeds": len({r["speed_rpm"] for r in rotor_res.scan
                                       if r["grid"] != str(grid)})}
    if LOCAL:
        ref = answers["rotor_reference_line"]
        out["ratio_reference_line_over_two_bearings"] = med["rotor_reference_line"] / bearings
        out["max_relative_onset_difference_vs_reference_line"] = max(
            (abs(m.onset_speed_rpm / ref.mode(m.label).onset_speed_rpm - 1)
             for m in rotor_res.modes if m.status == "onset"), default=0.0)
        out["max_relative_whirl_difference_vs_reference_line"] = max(
            (abs(m.whirl_ratio / ref.mode(m.label).whirl_ratio - 1)
             for m in rotor_res.modes if m.status == "onset"), default=0.0)
    out["rotor_breakdown"] = _breakdown(system, grid, cache)
    return out


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "results" / "benchmarks" /
                                             "rotor_onset_ratio.json"))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--grids", default="144x36,72x20")
    args = parser.parse_args(argv)
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    load_before = os.getloadavg()
    runs = [bench(system, Grid.parse(g), args.repeats) for g in args.grids.split(",")]
    out = {"runs": runs, "source": _source(), "local_refinement": LOCAL,
           "machine": machine_info(load_average_before=load_before,
                                   load_average_after=os.getloadavg())}
    for r in runs:
        m = r["cpu_s_median"]
        print(f"{r['grid']}: rotor {m['rotor']:.2f} s CPU, bearings {m['bearing_A']:.2f} + "
              f"{m['bearing_B']:.2f} s; ratio {r['ratio_rotor_over_two_bearings']:.2f} "
              f"(target {TARGET}, {'met' if r['met'] else 'NOT met'})"
              + (f"; reference line {m['rotor_reference_line']:.2f} s, onsets differ by "
                 f"{r['max_relative_onset_difference_vs_reference_line']:.1e}" if LOCAL else ""))
        for k, v in r["rotor_breakdown"].items():
            print(f"    {k}: {v}")
    print(f"load {load_before} -> {os.getloadavg()}; source {out['source']}")
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
