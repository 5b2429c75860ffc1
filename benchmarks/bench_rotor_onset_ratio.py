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
rotor's CPU split by stage and grid (statics, full crossings, local crossings by Krylov
spaces, and ``local_crossing direct``: the secant's last steps by one direct LU per bearing).

Where the grid has no coarse guide by default (72 × 20: fewer than GUIDE_FACTOR = 8 times
36 × 10's cells), the rotor is also timed with the 36 × 10 guide (``rotor_guided``: a different
secant path, so its onsets differ from the default's by up to the secant's own error).
``--source-commit`` / ``--baseline-commit``: the commits the measured and the baseline trees
are exports of (``git archive``), recorded as their sources when the trees are not checkouts.
``coarse_scan_above_every_onset`` (in the breakdown): the guide's CPU at the scan speeds above
the first one where every mode is unstable — the scan of every mode over the whole range,
which the one-bearing searches (each stopping at its first unstable speed) do not make.
``--roots``: each onset also found by Brent's method on the reference line's full crossings to
a relative 1e-10 around the answer (the root the secants approach; slow: ~30 full crossings a
mode), and the distance of each variant's onset from it.

``--baseline DIR``: the same measurement of the code in DIR (a ``git worktree`` of an older
commit), a process of this script with PYTHONPATH=DIR after each repeat here (A B A B …);
the JSON then has its medians, the ratio of the rotor's CPU new/old and the largest relative
difference of the onsets and whirl ratios from the old code's.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONPATH=. python \\
        benchmarks/bench_rotor_onset_ratio.py [--out results/benchmarks/rotor_onset_ratio.json]
        [--repeats 3] [--grids 144x36,72x20] [--roots]
"""
from __future__ import annotations

import argparse
import inspect
import json
import os
import statistics
import subprocess
import sys
import math
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
from scipy.optimize import brentq

from gfbopt.rotor.onset import check_coarse_grid
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine, rotor_onsets, scan_speeds

ROOT = Path(__file__).resolve().parents[1]
SPAN = (4000.0, 60000.0)
TARGET = 1.2
MINE = ["gfbopt/rotor", "gfbopt/linear", "benchmarks/bench_rotor_onset_ratio.py"]
LOCAL = "local" in inspect.signature(SpeedLine).parameters


def _source(commit=None) -> dict:
    if commit:
        return {"commit": commit, "tree": "export of that commit (git archive)",
                "measured_files_dirty": False, "tree_dirty": False}

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


def _speed_of(args) -> float:
    """The speed [rpm] a stage function is called at: support_states(rotor, speed, …),
    crossings / local_crossing(rotor, states, …)."""
    first = args[0]
    return float(getattr(first, "speed_rpm", first))


def _breakdown(system, grid: Grid, cache) -> dict:
    """CPU of one rotor run split by stage and grid (wrapping the stage functions), and the
    coarse guide's CPU at the scan speeds above the first one where every mode with an onset
    is unstable (``coarse_scan_above_every_onset``: what the rotor's scan of every mode over
    the whole range costs beyond the one-bearing searches, which stop at their own first
    unstable speed)."""
    spent, calls = defaultdict(float), defaultdict(int)
    per_speed = defaultdict(float)          # (grid, speed) -> CPU of every stage there
    names = [n for n in ("support_states", "crossings", "local_crossing")
             if hasattr(system_module, n)]
    saved = {n: getattr(system_module, n) for n in names}

    def wrap(name, f):
        def timed(rotor, *args, **kwargs):
            c = time.process_time()
            try:
                return f(rotor, *args, **kwargs)
            finally:
                key = f"{name}{' direct' if kwargs.get('direct') else ''} {rotor.grid}"
                spent[key] += time.process_time() - c
                calls[key] += 1
                per_speed[(str(rotor.grid), _speed_of(args))] += time.process_time() - c
        return timed

    for n in names:
        setattr(system_module, n, wrap(n, saved[n]))
    try:
        total, result = _cpu(lambda: rotor_onsets(system, SPAN, line=SpeedLine(
            resolve_rotor(system, grid, cache)), show_progress=False))
    finally:
        for n, f in saved.items():
            setattr(system_module, n, f)
    out = {k: {"cpu_s": v, "calls": calls[k]} for k, v in sorted(spent.items())}
    out["other_cpu_s"] = total - sum(spent.values())
    out["total_cpu_s"] = total
    guide = result.conventions.get("coarse_grid") or str(grid)
    speeds = scan_speeds(*SPAN)
    onsets = [m.onset_speed_rpm for m in result.modes]
    if all(m.status == "onset" for m in result.modes) and onsets:
        above = [s for s in speeds if s > max(onsets)]
        every = above[0] if above else None
        later = [s for s in speeds if every is not None and s > every]
        out["coarse_scan_above_every_onset"] = {
            "grid": guide, "every_mode_unstable_from_rpm": every, "scan_speeds": len(later),
            "cpu_s": sum(per_speed[(guide, s)] for s in later)}
    return out


def _baseline(tree: str, grid: str, commit=None) -> dict:
    """One repeat of this benchmark on the code in ``tree`` (a process of its own)."""
    out = Path(f"/tmp/bench_rotor_onset_ratio_baseline_{os.getpid()}.json")
    env = dict(os.environ, PYTHONPATH=str(Path(tree).resolve()))
    subprocess.run([sys.executable, __file__, "--grids", grid, "--repeats", "1",
                    "--out", str(out)] + (["--source-commit", commit] if commit else []),
                   env=env, check=True, capture_output=True)
    data = json.loads(out.read_text())
    out.unlink()
    return {"source": data["source"], **data["runs"][0]}


def _compare(run: dict, old: list) -> dict:
    """The old code's medians over its processes and how the new run compares."""
    names = ("rotor", "bearing_A", "bearing_B")
    med = {n: statistics.median(o["cpu_s_median"][n] for o in old) for n in names}
    modes = old[-1]["rotor_modes"]
    diff = {k: max((abs(m[k] / modes[label][k] - 1) for label, m in run["rotor_modes"].items()
                    if m["status"] == "onset"), default=0.0)
            for k in ("onset_speed_rpm", "whirl_ratio")}
    return {"source": old[-1]["source"], "cpu_s_median": med,
            "cpu_s": {n: [o["cpu_s_median"][n] for o in old] for n in names},
            "ratio_rotor_over_two_bearings": med["rotor"] / (med["bearing_A"]
                                                             + med["bearing_B"]),
            "rotor_new_over_old_cpu": run["cpu_s_median"]["rotor"] / med["rotor"],
            "rotor_modes": modes, "rotor_breakdown": old[-1]["rotor_breakdown"],
            "max_relative_onset_difference_vs_old": diff["onset_speed_rpm"],
            "max_relative_whirl_difference_vs_old": diff["whirl_ratio"]}


GUIDE = "36x10"


def _differences(result, other) -> dict:
    """Largest relative differences of ``result``'s onsets and whirl ratios from ``other``'s."""
    modes = [m for m in result.modes if m.status == "onset"]
    return {"onset": max((abs(m.onset_speed_rpm / other.mode(m.label).onset_speed_rpm - 1)
                          for m in modes), default=0.0),
            "whirl": max((abs(m.whirl_ratio / other.mode(m.label).whirl_ratio - 1)
                          for m in modes), default=0.0)}


def _roots(system, grid: Grid, cache, answers: dict) -> dict:
    """Each onset of the default search as Brent's root of ln μ_c on the reference line (every
    crossing at every speed) to a relative 1e-10, bracketed by ±1e-5 around the answer
    (widened tenfold until the sign changes), and each variant's relative distance from it."""
    line = SpeedLine(resolve_rotor(system, grid, cache), local=False)
    out = {}
    for m in answers["rotor"].modes:
        if m.status != "onset":
            continue

        def g(speed, label=m.label, whirl=m.whirl_ratio):
            return math.log(line.follow(speed, label, whirl).inertia_scale)
        width = 1e-5
        while g(m.onset_speed_rpm * (1 - width)) <= 0 or g(m.onset_speed_rpm * (1 + width)) > 0:
            width *= 10
        root = brentq(g, m.onset_speed_rpm * (1 - width), m.onset_speed_rpm * (1 + width),
                      xtol=1e-10 * m.onset_speed_rpm, rtol=1e-12)
        out[m.label] = {"root_rpm": root} | {
            f"{name}_relative_error": answers[name].mode(m.label).onset_speed_rpm / root - 1
            for name in answers if name.startswith("rotor")}
    return out


def bench(system, grid: Grid, repeats: int, after_repeat=None, roots: bool = False) -> dict:
    cache = SolverCache(grid)
    rotor = resolve_rotor(system, grid, cache)

    def run_rotor(local=True, coarse_grid="auto"):
        line = SpeedLine(resolve_rotor(system, grid, cache), **({"local": local} if LOCAL
                                                                 else {}))
        return rotor_onsets(system, SPAN, line=line, show_progress=False,
                            coarse_grid=coarse_grid)

    def run_bearing(k):
        case, load = rotor.cases[k], rotor.loads[k]
        return onset_speed(case.bearing, Rotor(rotor.mass_share_kg[k]), load.magnitude, SPAN,
                           options=case.options, grid=grid, cache=cache)

    variants = {"rotor": run_rotor, "bearing_A": lambda: run_bearing(0),
                "bearing_B": lambda: run_bearing(1)}
    if LOCAL:
        variants["rotor_reference_line"] = lambda: run_rotor(False)
    guided = check_coarse_grid("auto", grid) is None
    if guided:
        variants["rotor_guided"] = lambda: run_rotor(coarse_grid=GUIDE)
    for f in variants.values():                        # builds
        f()
    cpus, answers = defaultdict(list), {}
    for _ in range(repeats):
        for name, f in variants.items():
            cpu, answers[name] = _cpu(f)
            cpus[name].append(cpu)
        if after_repeat is not None:
            after_repeat()
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
    if guided:
        diff = _differences(answers["rotor_guided"], rotor_res)
        out["rotor_guided"] = {
            "coarse_grid": GUIDE, "ratio_over_two_bearings": med["rotor_guided"] / bearings,
            "max_relative_onset_difference_vs_default": diff["onset"],
            "max_relative_whirl_difference_vs_default": diff["whirl"],
            "rotor_modes": {m.label: {"onset_speed_rpm": m.onset_speed_rpm,
                                      "whirl_ratio": m.whirl_ratio, "status": m.status}
                            for m in answers["rotor_guided"].modes}}
    if roots:
        out["roots"] = _roots(system, grid, cache, answers)
    out["rotor_breakdown"] = _breakdown(system, grid, cache)
    return out


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "results" / "benchmarks" /
                                             "rotor_onset_ratio.json"))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--grids", default="144x36,72x20")
    parser.add_argument("--baseline", default=None, help="source tree of the old code")
    parser.add_argument("--source-commit", default=None,
                        help="the commit the measured tree is an export of")
    parser.add_argument("--baseline-commit", default=None,
                        help="the commit the baseline tree is an export of")
    parser.add_argument("--roots", action="store_true",
                        help="also each onset's root by Brent's method (slow)")
    args = parser.parse_args(argv)
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    load_before, source = os.getloadavg(), _source(args.source_commit)  # as it starts
    runs = []
    for g in args.grids.split(","):
        old = []
        run = bench(system, Grid.parse(g), args.repeats,
                    after_repeat=(lambda gg=g, o=old: o.append(
                        _baseline(args.baseline, gg, args.baseline_commit)))
                    if args.baseline else None, roots=args.roots)
        if old:
            run["baseline"] = _compare(run, old)
        runs.append(run)
    out = {"runs": runs, "source": source, "local_refinement": LOCAL,
           "machine": machine_info(load_average_before=load_before,
                                   load_average_after=os.getloadavg())}
    for r in runs:
        m = r["cpu_s_median"]
        print(f"{r['grid']}: rotor {m['rotor']:.2f} s CPU, bearings {m['bearing_A']:.2f} + "
              f"{m['bearing_B']:.2f} s; ratio {r['ratio_rotor_over_two_bearings']:.2f} "
              f"(target {TARGET}, {'met' if r['met'] else 'NOT met'})"
              + (f"; reference line {m['rotor_reference_line']:.2f} s, onsets differ by "
                 f"{r['max_relative_onset_difference_vs_reference_line']:.1e}" if LOCAL else ""))
        if "rotor_guided" in r:
            v = r["rotor_guided"]
            print(f"  guided by {v['coarse_grid']}: rotor {m['rotor_guided']:.2f} s, ratio "
                  f"{v['ratio_over_two_bearings']:.2f}; onsets differ from the default's by "
                  f"{v['max_relative_onset_difference_vs_default']:.1e}")
        for label, v in r.get("roots", {}).items():
            print(f"  {label}: root {v['root_rpm']:.10g} rpm; relative errors "
                  + ", ".join(f"{k} {e:+.1e}" for k, e in v.items() if k != "root_rpm"))
        for k, v in r["rotor_breakdown"].items():
            print(f"    {k}: {v}")
        above = r["rotor_breakdown"].get("coarse_scan_above_every_onset")
        if above:
            rest = r["rotor_breakdown"]["total_cpu_s"] - above["cpu_s"]
            print(f"  the {above['grid']} scan above {above['every_mode_unstable_from_rpm']:,.0f}"
                  f" rpm (every mode unstable): {above['scan_speeds']} speeds, "
                  f"{above['cpu_s']:.2f} s of {r['rotor_breakdown']['total_cpu_s']:.2f} s; "
                  f"the rest over the two bearings: "
                  f"{rest / (m['bearing_A'] + m['bearing_B']):.2f}")
        if "baseline" in r:
            b = r["baseline"]
            print(f"  old code ({b['source']['commit'][:8]}): rotor {b['cpu_s_median']['rotor']:.2f}"
                  f" s, ratio {b['ratio_rotor_over_two_bearings']:.2f}; new/old rotor CPU "
                  f"{b['rotor_new_over_old_cpu']:.2f}; onsets differ from the old by "
                  f"{b['max_relative_onset_difference_vs_old']:.1e}, whirl by "
                  f"{b['max_relative_whirl_difference_vs_old']:.1e}")
    print(f"load {load_before} -> {os.getloadavg()}; source {out['source']}")
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
