"""Speed of the rotor on two bearings (gfbopt.rotor.system), in one run:

* onset of every mode of problems/rotors/blower.toml over 4,000–60,000 rpm at 144 × 36 (the
  default grid: the scan guided by 36 × 10, as the one-bearing onset) and at 72 × 20 (no
  guide), timed after the builds (a first run on the same cache builds the CasADi solvers; the
  timed run uses a fresh SpeedLine on the built cache, so its first equilibrium is cold);
* the same at 144 × 36 without the guide, and at 72 × 20 with the reference refinement
  (method "scan": Brent's method to 1e-4), for the ratios and the agreement of the answers;
* the guide's assumption: the largest |μ_c(36 × 10)/μ_c(144 × 36) − 1| at the speeds solved
  on both grids (the guide checks on the fine grid wherever the coarse margin is within 0.15);
* a 20-speed Campbell diagram at 72 × 20 (full-system eigenvalues), after the builds.

Wall and CPU time are both reported: the machine is shared (the load average before and after
is recorded), and CPU time is what the code costs.  Targets: onsets ≤ 10 s at
the default grid, ≤ 3 s at 72 × 20; Campbell ≤ 30 s.

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


def _timed(system, grid: Grid, cache, **kwargs) -> dict:
    line = SpeedLine(resolve_rotor(system, grid, cache))
    t, c = time.perf_counter(), time.process_time()
    res = rotor_onsets(system, SPAN, line=line, show_progress=False, **kwargs)
    wall, cpu = time.perf_counter() - t, time.process_time() - c
    direct = sum(s.direct_solves for st in line._states.values() for s in st.states if s)
    coarse = res.conventions.get("coarse_grid", "")
    return {"grid": str(grid), "options": {k: str(v) for k, v in kwargs.items()},
            "coarse_grid": coarse, "wall_s": wall, "cpu_s": cpu,
            "fine_speeds": len(line._states),
            "coarse_speeds": len({r["speed_rpm"] for r in res.scan if r["grid"] == coarse}),
            "direct_impedance_solves": direct, "first_mode": res.first_mode,
            "onset_speed_rpm": res.onset_speed_rpm,
            "modes": {m.label: m.onset_speed_rpm for m in res.modes}, "_result": res}


def _grid_error(result) -> float:
    """max |μ_c(coarse)/μ_c(fine) − 1| over (speed, label) solved on both grids."""
    rows = {}
    for r in result.scan:
        rows.setdefault((r["speed_rpm"], r["label"]), {})[r["grid"]] = r["inertia_scale"]
    pairs = [v for v in rows.values() if len(v) == 2 and all(x > 0 for x in v.values())]
    return max((abs(a / b - 1) for a, b in (tuple(v.values()) for v in pairs)), default=np.nan)


def _onsets(system, grid: Grid, **kwargs) -> dict:
    cache = SolverCache(grid)
    t = time.perf_counter()
    rotor_onsets(system, SPAN, grid=grid, cache=cache, show_progress=False, **kwargs)
    out = _timed(system, grid, cache, **kwargs)
    out["first_run_with_builds_s"] = time.perf_counter() - t - out["wall_s"]
    return out


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "results" / "benchmarks" /
                                             "rotor_speed.json"))
    args = parser.parse_args(argv)
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    load_before = os.getloadavg()
    fine, medium = Grid(144, 36), Grid(72, 20)
    runs = [_onsets(system, fine), _onsets(system, medium)]
    cache = SolverCache(fine)
    rotor_onsets(system, SPAN, grid=fine, cache=cache, show_progress=False)
    runs.append(_timed(system, fine, cache, coarse_grid=None))
    cache = SolverCache(medium)
    rotor_onsets(system, SPAN, grid=medium, cache=cache, show_progress=False)
    runs.append(_timed(system, medium, cache, method="scan"))
    error = _grid_error(runs[0]["_result"])
    out = {"onsets": [{k: v for k, v in r.items() if k != "_result"} for r in runs]}
    out["ratios"] = {
        "guided_over_unguided_cpu_144x36": runs[0]["cpu_s"] / runs[2]["cpu_s"],
        "secant_over_brent_cpu_72x20": runs[1]["cpu_s"] / runs[3]["cpu_s"],
        "onset_guided_vs_unguided_144x36": runs[0]["onset_speed_rpm"]
        / runs[2]["onset_speed_rpm"] - 1,
        "onset_secant_vs_brent_72x20": runs[1]["onset_speed_rpm"]
        / runs[3]["onset_speed_rpm"] - 1}
    out["guide_grid_error"] = {"max_relative_inertia_scale_difference_36x10_144x36": error,
                               "checked_below": 0.15}
    grid = medium
    cache = SolverCache(grid)
    line = SpeedLine(resolve_rotor(system, grid, cache))
    line.states(SPAN[0])                                  # builds
    speeds = list(np.linspace(*SPAN, 20))
    t, c = time.perf_counter(), time.process_time()
    diagram = campbell_diagram(line, speeds, show_progress=False)
    out["campbell_72x20"] = {"speeds": 20, "wall_s": time.perf_counter() - t,
                             "cpu_s": time.process_time() - c,
                             "eigenvalues": len(diagram.table),
                             "tracks": int(diagram.table["mode"].nunique())}
    out["targets_s"] = {"onsets_default_grid": 10.0, "onsets_72x20": 3.0, "campbell_72x20": 30.0}
    out["machine"] = machine_info(load_average_before=load_before,
                                  load_average_after=os.getloadavg())
    for o in out["onsets"]:
        print(f"onsets at {o['grid']} {o['options'] or ''} (guide {o['coarse_grid'] or '-'}): "
              f"{o['wall_s']:.2f} s wall, {o['cpu_s']:.2f} s CPU after builds "
              f"({o['fine_speeds']} speeds on the grid, {o['coarse_speeds']} on the guide); "
              f"first {o['first_mode']} at {o['onset_speed_rpm']:.3f} rpm")
    print(f"Campbell 20 speeds at 72x20: {out['campbell_72x20']['wall_s']:.2f} s wall, "
          f"{out['campbell_72x20']['cpu_s']:.2f} s CPU; ratios {out['ratios']}; guide grid "
          f"error {error:.3g}; load {load_before} -> {os.getloadavg()}")
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
