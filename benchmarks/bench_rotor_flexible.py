"""The onset of every mode of a flexible rotor (20 Timoshenko shaft elements, condensed on its
bearings by gfbopt.rotor.condensed) against the rigid rotor of the same mass and inertias, in
one run: CPU(flexible) / CPU(rigid), target ≤ 1.5 (issue 27).

Case: problems/rotors/flexible_rotor.toml over 6,000–60,000 rpm at 72 × 20 (no guide) and
its rigid twin (the shaft's equivalent body, every position re-measured from its centre of
gravity: tests/verification/test_rotor_flexible_shaft.py).  Each run
:func:`gfbopt.rotor.system.rotor_onsets` on a fresh resolved rotor over one built cache; the
two are interleaved ``--repeats`` times and the medians taken (CPU time of this process; the
machine is shared: load before and after recorded).  Also the CPU of building the
structure (shaft assembly and condensation) alone.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONPATH=. python \\
        benchmarks/bench_rotor_flexible.py [--out results/benchmarks/rotor_flexible.json]
"""
from __future__ import annotations

import argparse
import os
import statistics
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


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "results" / "benchmarks" /
                                             "rotor_flexible.json"))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--grid", default="72x20")
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
    cpus, answers = {n: [] for n in systems}, {}
    for _ in range(args.repeats):
        for name in systems:
            cpu, answers[name] = _cpu(lambda: run(name))
            cpus[name].append(cpu)
    structure_cpu = statistics.median(_cpu(lambda: analysis_structure(flexible))[0]
                                      for _ in range(5))
    med = {k: statistics.median(v) for k, v in cpus.items()}
    out = {"grid": str(grid), "speed_range_rpm": list(SPAN), "cpu_s": cpus,
           "cpu_s_median": med, "ratio_flexible_over_rigid": med["flexible"] / med["rigid"],
           "target": TARGET, "met": med["flexible"] / med["rigid"] <= TARGET,
           "structure_build_cpu_s": structure_cpu,
           "modes": {n: {m.label: {"onset_speed_rpm": m.onset_speed_rpm, "status": m.status}
                         for m in r.modes} for n, r in answers.items()},
           "machine": machine_info(load_average_before=load_before,
                                   load_average_after=os.getloadavg())}
    print(f"{grid}: flexible {med['flexible']:.2f} s CPU, rigid {med['rigid']:.2f} s; ratio "
          f"{out['ratio_flexible_over_rigid']:.2f} (target {TARGET}); structure build "
          f"{structure_cpu * 1e3:.1f} ms; load {load_before} -> {os.getloadavg()}")
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
