"""The onset of every mode of a flexible rotor (20 Timoshenko shaft elements, condensed on its
bearings by gfbopt.rotor.condensed) against the rigid rotor of the same mass and inertias, in
one run: CPU(flexible) / CPU(rigid), target ≤ 1.5.

Case: problems/rotors/flexible_rotor.toml over 6,000–60,000 rpm at 72 × 20 (no guide) and
its rigid twin (the shaft's equivalent body, every position re-measured from its centre of
gravity: tests/verification/test_rotor_flexible_shaft.py).  Each run
:func:`gfbopt.rotor.system.rotor_onsets` on a fresh resolved rotor over one built cache; the
two are interleaved ``--repeats`` times and the medians taken (CPU time of this process; the
machine is shared: load before and after recorded).  Also the CPU of building the
structure (shaft assembly and condensation) alone.

``--baseline DIR``: the same measurement of the code in DIR (e.g. ``git archive`` of an older
commit), a process of this script with PYTHONPATH=DIR after each repeat here (A B A B …); the
JSON then has its medians, the new/old CPU of each rotor and the largest relative difference
of the onsets and whirl ratios from the old code's.  ``--source-commit``: the commit the
measured tree is an export of (recorded as the source when the tree is not a checkout).

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONPATH=. python \\
        benchmarks/bench_rotor_flexible.py [--out results/benchmarks/rotor_flexible.json]
        [--repeats 3] [--baseline DIR] [--source-commit HASH]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "verification"))
from machine import machine_info, write_report  # noqa: E402
from gfbopt import Grid, SolverCache  # noqa: E402
from gfbopt.rotor.supports import analysis_structure, resolve_rotor  # noqa: E402
from gfbopt.rotor.system import SpeedLine, rotor_onsets  # noqa: E402
from test_rotor_flexible_shaft import _rigid_twin, _system  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SPAN = (6000.0, 60000.0)
TARGET = 1.5


def _cpu(function):
    c = time.process_time()
    out = function()
    return time.process_time() - c, out


def _modes(result) -> dict:
    return {m.label: {"onset_speed_rpm": m.onset_speed_rpm, "whirl_ratio": m.whirl_ratio,
                      "status": m.status} for m in result.modes}


def _baseline(tree: str, grid: str) -> dict:
    """One repeat of this benchmark on the code in ``tree`` (a process of its own)."""
    out = Path(f"/tmp/bench_rotor_flexible_baseline_{os.getpid()}.json")
    env = dict(os.environ, PYTHONPATH=str(Path(tree).resolve()))
    subprocess.run([sys.executable, __file__, "--grid", grid, "--repeats", "1",
                    "--out", str(out)], env=env, check=True, capture_output=True)
    data = json.loads(out.read_text())
    out.unlink()
    return data


def _difference(new: dict, old: dict, key: str) -> float:
    """The largest relative difference of ``key`` over the modes both list (nan = nan)."""
    out = 0.0
    for label, m in new.items():
        o = old.get(label, {}).get(key, math.nan)
        a = m.get(key, math.nan)
        if math.isnan(a) and math.isnan(o):
            continue
        out = max(out, abs(a / o - 1) if o else math.inf)
    return out


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "results" / "benchmarks" /
                                             "rotor_flexible.json"))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--grid", default="72x20")
    parser.add_argument("--baseline", default=None, help="source tree of the old code")
    parser.add_argument("--source-commit", default=None,
                        help="the commit the measured tree is an export of")
    parser.add_argument("--baseline-commit", default=None,
                        help="the commit the baseline tree is an export of")
    args = parser.parse_args(argv)
    grid = Grid.parse(args.grid)
    load_before = os.getloadavg()
    flexible = _system()
    systems = {"flexible": flexible, "rigid": _rigid_twin(flexible)}
    cache = SolverCache(grid)

    def run(name):
        system = systems[name]
        line = SpeedLine(resolve_rotor(system, grid, cache))
        return rotor_onsets(system, SPAN, grid=grid, line=line, show_progress=False,
                            coarse_grid=None)

    for name in systems:                   # builds
        run(name)
    cpus, answers, old = {n: [] for n in systems}, {}, []
    for _ in range(args.repeats):
        for name in systems:
            cpu, answers[name] = _cpu(lambda: run(name))
            cpus[name].append(cpu)
        if args.baseline:
            old.append(_baseline(args.baseline, args.grid))
    structure_cpu = statistics.median(_cpu(lambda: analysis_structure(flexible))[0]
                                      for _ in range(5))
    med = {k: statistics.median(v) for k, v in cpus.items()}
    out = {"grid": str(grid), "speed_range_rpm": list(SPAN), "cpu_s": cpus,
           "cpu_s_median": med, "ratio_flexible_over_rigid": med["flexible"] / med["rigid"],
           "target": TARGET, "met": med["flexible"] / med["rigid"] <= TARGET,
           "structure_build_cpu_s": structure_cpu,
           "modes": {n: _modes(r) for n, r in answers.items()},
           "source": {"commit": args.source_commit, "tree": "export of that commit"}
           if args.source_commit else {},
           "machine": machine_info(load_average_before=load_before,
                                   load_average_after=os.getloadavg())}
    if old:
        omed = {n: statistics.median(o["cpu_s_median"][n] for o in old) for n in systems}
        out["baseline"] = {
            "source": {"commit": args.baseline_commit, "tree": "export of that commit"},
            "cpu_s_median": omed,
            "cpu_s": {n: [o["cpu_s_median"][n] for o in old] for n in systems},
            "ratio_flexible_over_rigid": omed["flexible"] / omed["rigid"],
            "new_over_old_cpu": {n: med[n] / omed[n] for n in systems},
            "modes": old[-1]["modes"],
            "max_relative_onset_difference_vs_old": {
                n: _difference(out["modes"][n], old[-1]["modes"][n], "onset_speed_rpm")
                for n in systems},
            "max_relative_whirl_difference_vs_old": {
                n: _difference(out["modes"][n], old[-1]["modes"][n], "whirl_ratio")
                for n in systems}}
    print(f"{grid}: flexible {med['flexible']:.2f} s CPU, rigid {med['rigid']:.2f} s; ratio "
          f"{out['ratio_flexible_over_rigid']:.2f} (target {TARGET}); structure build "
          f"{structure_cpu * 1e3:.1f} ms; load {load_before} -> {os.getloadavg()}")
    if old:
        b = out["baseline"]
        print(f"  old code: flexible {b['cpu_s_median']['flexible']:.2f} s, rigid "
              f"{b['cpu_s_median']['rigid']:.2f} s, ratio {b['ratio_flexible_over_rigid']:.2f}; "
              f"new/old {b['new_over_old_cpu']}; onsets differ by "
              f"{b['max_relative_onset_difference_vs_old']}, whirl by "
              f"{b['max_relative_whirl_difference_vs_old']}")
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
