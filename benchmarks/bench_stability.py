"""Speed of the SI stability answers (gfbopt.rotor) in one run.

Case: the Ruscitto et al. (1978) bearing (problems/bearings/ruscitto.toml, its [model] table:
seam with the welded end 180° from the load, axial-mean law, η = 0), a rotor of 2 kg per
bearing under 20 N per bearing.

Measures
--------
* build: the CasADi/IPOPT build of the static model for the bearing's formulation, on a
  fresh SolverCache [s];
* stability: ``stability(bearing, rotor, OperatingPoint(45000, 20))`` after the build, median
  of 3 [s], at 72 × 20 (target ≤ 1 s) and 144 × 36 (target ≤ 3 s), with its parts (static
  solve, linearisation, threshold, least-stable mode) timed separately once;
* onset: ``onset_speed(bearing, rotor, 20, (5000, 50000))`` at 144 × 36 after the build,
  median of 2 (target ≤ 10 s), with its number of threshold evaluations;
* the cost of one impedance evaluation (one sparse complex LU), the unit of everything;
* ``stability()`` with three searches for the least-stable mode, in one run (``mode_search``):
  "near_threshold" — 0.2's search (shift-invert eigenvalues near the threshold whirl only, then
  the secant polish on the characteristic equation; it can miss the least-damped root), "eigs" — the wide reference (three shift-invert searches over whirl ratios 0.02–3),
  "krylov" — the default (one LU, one Krylov space, roots of its reduced model); their
  ratios to "near_threshold" (target for "krylov": ≤ 1.3) and the largest difference of the
  mode found by "krylov" and "eigs".

Usage::

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONPATH=. python benchmarks/bench_stability.py \\
        [--out results/benchmarks/stability_speed.json]

The machine's load average is recorded: on a shared machine the timings scale with it.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, write_report  # noqa: E402
from gfbopt import Grid, SolverCache, solve_static
from gfbopt.inputs import OperatingPoint, Rotor, load_bearing_file
import gfbopt.rotor.analysis as analysis
from gfbopt.linear import (characteristic_root, impedance, least_stable_mode, linear_threshold,
                           linearise, semi_discrete_eigenvalues)
from gfbopt.rotor import onset_speed, stability
from gfbopt.rotor.analysis import resolve_case

REPO = Path(__file__).resolve().parents[1]
BEARING, OPTIONS = load_bearing_file(REPO / "problems" / "bearings" / "ruscitto.toml")
ROTOR, LOAD, SPEED, RANGE = Rotor(2.0), 20.0, 45000.0, (5000.0, 50000.0)
TARGETS = {"stability_72x20_s": 1.0, "stability_144x36_s": 3.0, "onset_144x36_s": 10.0}


def near_threshold_mode(lin, mass, threshold):
    """0.2's least_stable_mode (gfbopt <= 0.2, for timing only): the eigenvalues nearest
    the threshold whirl, polished on the characteristic equation."""
    import math

    import numpy as np

    gamma = threshold.whirl_ratio if math.isfinite(threshold.whirl_ratio) else 0.5
    ev = semi_discrete_eigenvalues(lin, mass, 1j * gamma, count=8)
    whirling = ev[(np.abs(ev.imag) > 0.02) & (np.abs(ev.imag) < 3.0)]
    best = whirling[np.argmax(whirling.real)]
    return characteristic_root(lin, mass, complex(best.real, abs(best.imag)))


#: the least-stable-mode searches compared (module docstring)
MODE_SEARCHES = {
    "near_threshold": near_threshold_mode,
    "eigs": lambda lin, mass, thr: least_stable_mode(lin, mass, thr, method="eigs"),
    "krylov": lambda lin, mass, thr: least_stable_mode(lin, mass, thr, method="krylov"),
}


def mode_search(grid: Grid, cache: SolverCache, speeds=(SPEED, 5000.0), repeats: int = 3
                ) -> dict:
    """``stability()`` at each speed with each least-stable-mode search (MODE_SEARCHES),
    interleaved, median of ``repeats`` [s] wall and CPU; ratios to 0.2's search."""
    out: dict = {}
    original = analysis.least_stable_mode
    try:
        for speed in speeds:
            walls = {k: [] for k in MODE_SEARCHES}
            cpus = {k: [] for k in MODE_SEARCHES}
            modes = {}
            for _ in range(repeats):
                for name, search in MODE_SEARCHES.items():
                    analysis.least_stable_mode = search
                    t0, c0 = time.perf_counter(), time.process_time()
                    r = stability(BEARING, ROTOR, OperatingPoint(speed, LOAD), options=OPTIONS,
                                  grid=grid, cache=cache)
                    walls[name].append(time.perf_counter() - t0)
                    cpus[name].append(time.process_time() - c0)
                    modes[name] = complex(r.growth_rate, r.mode_whirl_ratio)
            wall = {k: statistics.median(v) for k, v in walls.items()}
            cpu = {k: statistics.median(v) for k, v in cpus.items()}
            out[f"{speed:.0f}_rpm"] = {
                "wall_s": wall, "cpu_s": cpu,
                "ratio_to_near_threshold_wall": {k: wall[k] / wall["near_threshold"]
                                                 for k in wall},
                "ratio_to_near_threshold_cpu": {k: cpu[k] / cpu["near_threshold"] for k in cpu},
                "mode": {k: [v.real, v.imag] for k, v in modes.items()},
                "krylov_minus_eigs": abs(modes["krylov"] - modes["eigs"])}
    finally:
        analysis.least_stable_mode = original
    return out


def timed(function, repeats: int) -> tuple[float, list, object]:
    """(median wall time [s], all times, last result) of ``repeats`` calls."""
    times, result = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), times, result


def parts(grid: Grid, cache: SolverCache) -> dict:
    """The pieces of one stability call, timed once each after the build [s]."""
    case = resolve_case(BEARING, ROTOR, LOAD, options=OPTIONS, grid=grid, cache=cache)
    model = case.model(SPEED)
    solver = cache(model, grid)
    out = {}
    t0 = time.perf_counter()
    sol = solve_static(model, load=case.load, solver=solver)
    out["static_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    lin = linearise(sol, solver)
    out["linearise_s"] = time.perf_counter() - t0
    out["impedance_s"], _, _ = timed(lambda: impedance(lin, 0.5j), 5)
    t0 = time.perf_counter()
    thr = linear_threshold(lin)
    out["threshold_s"] = time.perf_counter() - t0
    out["threshold_evaluations"] = thr.evaluations
    t0 = time.perf_counter()
    least_stable_mode(lin, case.mass_parameter(SPEED), thr)
    out["least_stable_mode_s"] = time.perf_counter() - t0
    out["n_states"] = lin.size
    return out


def bench_grid(text: str, onset: bool) -> dict:
    grid = Grid.parse(text)
    cache = SolverCache(grid)
    case = resolve_case(BEARING, ROTOR, LOAD, options=OPTIONS, grid=grid, cache=cache)
    t0 = time.perf_counter()
    cache(case.model(SPEED), grid)
    build_s = time.perf_counter() - t0

    def point():
        return stability(BEARING, ROTOR, OperatingPoint(SPEED, LOAD), options=OPTIONS,
                         grid=grid, cache=cache)

    t0 = time.perf_counter()
    first = point()
    first_s = time.perf_counter() - t0
    median, times, result = timed(point, 3)
    out = {"grid": text, "first_call_s": first_s, "build_s": build_s,
           "stability": {"median_s": median, "times_s": times, "verdict": result.verdict,
                         "critical_mass_kg": result.critical_mass_kg,
                         "critical_mass_parameter": first.critical_mass_parameter},
           "parts": parts(grid, cache)}
    if onset:
        o_median, o_times, o = timed(lambda: onset_speed(BEARING, ROTOR, LOAD, RANGE,
                                                         options=OPTIONS, grid=grid,
                                                         cache=cache), 2)
        out["onset"] = {"median_s": o_median, "times_s": o_times,
                        "onset_speed_rpm": o.onset_speed_rpm,
                        "whirl_frequency_hz": o.whirl_frequency_hz,
                        "evaluations": o.evaluations, "range_rpm": RANGE,
                        "seconds_per_evaluation": o_median / o.evaluations}
    return out


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=str(REPO / "results" / "benchmarks" /
                                             "stability_speed.json"))
    args = parser.parse_args(argv)
    load_before = os.getloadavg()
    coarse, fine = bench_grid("72x20", onset=False), bench_grid("144x36", onset=True)
    fine_grid = Grid.parse("144x36")
    searches = mode_search(fine_grid, SolverCache(fine_grid))
    measured = {"stability_72x20_s": coarse["stability"]["median_s"],
                "stability_144x36_s": fine["stability"]["median_s"],
                "onset_144x36_s": fine["onset"]["median_s"]}
    out = {"machine": machine_info(load_average_before=load_before,
                                   load_average_after=os.getloadavg()),
           "case": {"bearing": BEARING.name, "rotor_mass_kg": ROTOR.mass_kg,
                    "load_newton": LOAD, "speed_rpm": SPEED,
                    "conventions": OPTIONS.to_dict()},
           "grids": [coarse, fine],
           "mode_search_144x36": searches,
           "ratios": {"fine_over_coarse_stability": measured["stability_144x36_s"]
                      / measured["stability_72x20_s"],
                      "onset_over_one_stability_144x36": measured["onset_144x36_s"]
                      / measured["stability_144x36_s"]},
           "targets": {k: {"measured_s": measured[k], "target_s": v, "met": measured[k] <= v}
                       for k, v in TARGETS.items()}}
    print(f"gfbopt stability benchmark — {out['machine']['date']}, load average "
          f"{load_before[0]:.2f} before, {out['machine']['load_average_after'][0]:.2f} after")
    for g in out["grids"]:
        p = g["parts"]
        print(f"  {g['grid']:>7s}: build {g['build_s']:.2f} s, stability {g['stability']['median_s']:.3f}"
              f" s (static {p['static_s']:.3f}, threshold {p['threshold_s']:.3f} = "
              f"{p['threshold_evaluations']} × impedance {p['impedance_s']:.4f}, mode "
              f"{p['least_stable_mode_s']:.3f}), {p['n_states']} states")
    o = fine["onset"]
    print(f"  onset at 144x36: {o['median_s']:.2f} s, {o['evaluations']} thresholds, onset "
          f"{o['onset_speed_rpm']:.1f} rpm at {o['whirl_frequency_hz']:.1f} Hz")
    for speed, m in searches.items():
        w, c, r = m["wall_s"], m["cpu_s"], m["ratio_to_near_threshold_cpu"]
        print(f"  stability() at {speed}, 144x36, CPU s (wall s): " + ", ".join(
            f"{k} {c[k]:.2f} ({w[k]:.2f}; x{r[k]:.2f})" for k in c)
            + f"; |krylov - eigs| = {m['krylov_minus_eigs']:.1e}")
    for name, t in out["targets"].items():
        print(f"  {name:<22s} {t['measured_s']:7.3f} s  target <= {t['target_s']:g} s  "
              f"{'met' if t['met'] else 'NOT met'}")
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
