"""Speed of the rotor on two bearings (gfbopt.rotor.system, issue 16), in one run:

* onset of every mode of problems/rotors/blower.toml over 4,000–60,000 rpm at 144 × 36 (the
  default grid) and at 72 × 20, timed after the builds (a first run on the same cache builds
  the CasADi solvers; the timed run uses a fresh SpeedLine on the built cache);
* a 20-speed Campbell diagram at 72 × 20 (full-system eigenvalues), after the builds;
* how often each bearing's impedance was computed by a direct LU rather than read from its
  Krylov space (the per-bearing impedance at a speed is reused for every mode and frequency).

Targets from the issue: onsets ≤ 10 s at the default grid, ≤ 3 s at 72 × 20; Campbell ≤ 30 s.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONPATH=. python benchmarks/bench_rotor.py \\
        [--out results/benchmarks/rotor_speed.json]
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, write_report  # noqa: E402
from gfbopt import Grid, SolverCache
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.diagrams import campbell_diagram
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine, rotor_onsets

ROOT = Path(__file__).resolve().parents[1]
SPAN = (4000.0, 60000.0)


def _onsets(system, grid: Grid) -> dict:
    cache = SolverCache(grid)
    t = time.perf_counter()
    rotor_onsets(system, SPAN, grid=grid, cache=cache, show_progress=False)
    first = time.perf_counter() - t
    line = SpeedLine(resolve_rotor(system, grid, cache))
    t, c = time.perf_counter(), time.process_time()
    res = rotor_onsets(system, SPAN, line=line, show_progress=False)
    wall, cpu = time.perf_counter() - t, time.process_time() - c
    direct = sum(s.direct_solves for st in line._states.values() for s in st.states if s)
    return {"grid": str(grid), "first_run_with_builds_s": first, "wall_s": wall, "cpu_s": cpu,
            "speeds": len(line._states), "direct_impedance_solves": direct,
            "first_mode": res.first_mode, "onset_speed_rpm": res.onset_speed_rpm,
            "modes": {m.label: m.onset_speed_rpm for m in res.modes}}


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "results" / "benchmarks" /
                                             "rotor_speed.json"))
    args = parser.parse_args(argv)
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    load_before = os.getloadavg()
    out = {"onsets": [_onsets(system, Grid(144, 36)), _onsets(system, Grid(72, 20))]}
    grid = Grid(72, 20)
    cache = SolverCache(grid)
    line = SpeedLine(resolve_rotor(system, grid, cache))
    line.states(SPAN[0])                                  # builds
    speeds = list(np.linspace(*SPAN, 20))
    t, c = time.perf_counter(), time.process_time()
    diagram = campbell_diagram(line, speeds, show_progress=False)
    out["campbell_72x20"] = {"speeds": 20, "wall_s": time.perf_counter() - t,
                             "cpu_s": time.process_time() - c,
                             "eigenvalues": len(diagram.table)}
    out["targets_s"] = {"onsets_default_grid": 10.0, "onsets_72x20": 3.0, "campbell_72x20": 30.0}
    out["machine"] = machine_info(load_average_before=load_before,
                                  load_average_after=os.getloadavg())
    for o in out["onsets"]:
        print(f"onsets at {o['grid']}: {o['wall_s']:.2f} s after builds ({o['cpu_s']:.2f} s CPU"
              f", {o['speeds']} speeds, {o['direct_impedance_solves']} direct Z solves); "
              f"first {o['first_mode']} at {o['onset_speed_rpm']:.1f} rpm")
    print(f"Campbell 20 speeds at 72x20: {out['campbell_72x20']['wall_s']:.2f} s")
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
