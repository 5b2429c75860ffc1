"""Cost of the clearance at speed: static solves per running point, and the onset search
with growth and heat against the isothermal one (targets: ≤ 3 warm static solves
per operating point; the onset ≤ 2× the isothermal search at 144 × 36).

Case: the Ruscitto et al. (1978) bearing, isothermal (problems/bearings/ruscitto.toml) and
with a steel journal and the illustrative heat balance
(problems/bearings/ruscitto_thermal.toml), 2 kg and 20 N per bearing, onset searched over
5,000–50,000 rpm.

Measures (CPU time of this process, one BLAS thread; A/B interleaved, median of
``--repeats``): ``points``: the fixed point's static solves at 10k…60k rpm (60k is 1 % below
the runaway), alone (cold, no prior) and along a speed line (each seeded by the two speeds
below); ``root_search``: CPU of the heat balance's root search (256 samples, one vectorised
evaluation, then Brent) against the same search as a scalar loop; ``onset``: after the builds,
:func:`gfbopt.rotor.onset_speed` on the isothermal file and
:func:`gfbopt.rotor.running_bearing.running_onset` on the thermal one, with their answers,
evaluations and static solves, and the ratio.

Usage::

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONPATH=. python benchmarks/bench_thermal.py \\
        [--out results/benchmarks/thermal.json] [--repeats 2] [--grid 144x36]
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, tree_label, write_report  # noqa: E402
from gfbopt.rotor.running_bearing import running_onset
from gfbopt.inputs import Grid, OperatingPoint, Rotor
from gfbopt.inputs.options import resolve_model_options
from gfbopt.rotor import onset_speed, stability
from gfbopt.static import SolverCache
from gfbopt.thermal.bearing import FilmCase, FilmDrag
from gfbopt.thermal.files import load_running_bearing
from gfbopt.thermal.running import running_point, speed_line

REPO = Path(__file__).resolve().parents[1]
ROTOR, LOAD, RANGE = Rotor(2.0), 20.0, (5000.0, 50000.0)
SPEEDS = (10e3, 20e3, 30e3, 40e3, 50e3, 60e3)   # runaway from 60,625 rpm
TARGETS = {"static_solves_per_point": 3, "onset_ratio": 2.0}


def points_section(grid: Grid) -> dict:
    bearing, spec = load_running_bearing(REPO / "problems/bearings/ruscitto_thermal.toml")
    cache = SolverCache(grid)
    case = FilmCase(bearing, resolve_model_options(bearing.options), grid, cache, LOAD)
    alone = []
    for speed in SPEEDS:
        drag = FilmDrag(case)
        point = running_point(spec, speed, drag)
        alone.append({"speed_rpm": speed, "static_solves": point.static_solves,
                      "running_clearance_um": point.running_clearance * 1e6,
                      "film_temperature_c": point.network.film_k - 273.15,
                      "heat_generated_w": point.network.power_w,
                      "balance_error_w": point.network.heat_out_w - point.network.power_w})
    drag = FilmDrag(case)
    t0 = time.process_time()
    line = speed_line(spec, SPEEDS, drag)
    cpu = time.process_time() - t0
    seeded = [{"speed_rpm": p.speed_rpm, "static_solves": p.static_solves} for p in line.points]
    return {"alone": alone, "seeded": seeded, "seeded_cpu_s": cpu,
            "max_solves_alone": max(p["static_solves"] for p in alone),
            "max_solves_seeded": max(p["static_solves"] for p in seeded)}


def root_search_section(repeats: int = 200) -> dict:
    """CPU per root search [s]: :meth:`gfbopt.thermal.balance.Balance.lowest_root` against
    the same samples evaluated one by one (the search before it was vectorised)."""
    import math

    import numpy as np
    from scipy.optimize import brentq

    from gfbopt.thermal.balance import N_SAMPLES, Balance

    _, spec = load_running_bearing(REPO / "problems/bearings/ruscitto_thermal.toml")
    g = spec.thermal.conductances(spec.radius, spec.length, spec.cold_clearance, 1e-6)
    b = Balance(spec, 45e3 * math.pi / 30, lambda x: np.maximum(0.93 - 0.04 * (x - 2.5),
                                                                1e-3), g)

    def scalar():
        top, _ = b.top()
        grid = np.append(top * np.linspace(0.0, 1.0, N_SAMPLES + 1)[:-1], top * (1 - 1e-12))
        values = [b.residual(float(p)) for p in grid]
        k = next(i for i, v in enumerate(values) if v > 0)
        return brentq(b.residual, grid[k - 1], grid[k], xtol=1e-300, rtol=1e-15,
                      maxiter=200)

    times = {"vectorised": [], "scalar_loop": []}
    for _ in range(repeats):                 # interleaved A/B
        t0 = time.process_time()
        root = b.lowest_root()[0]
        times["vectorised"].append(time.process_time() - t0)
        t0 = time.process_time()
        ref = scalar()
        times["scalar_loop"].append(time.process_time() - t0)
    vec, loop = (statistics.median(times[k]) for k in ("vectorised", "scalar_loop"))
    return {"vectorised_cpu_s": vec, "scalar_loop_cpu_s": loop, "speedup": loop / vec,
            "root_w": root, "root_relative_difference": abs(root - ref) / ref,
            "repeats": repeats}


def onset_section(grid: Grid, repeats: int) -> dict:
    iso_bearing, iso_spec = load_running_bearing(REPO / "problems/bearings/ruscitto.toml")
    hot_bearing, hot_spec = load_running_bearing(
        REPO / "problems/bearings/ruscitto_thermal.toml")
    caches = {"isothermal": SolverCache(grid), "heat": SolverCache(grid)}
    for name, bearing in (("isothermal", iso_bearing), ("heat", hot_bearing)):  # the builds
        onset_speed(bearing, ROTOR, LOAD, RANGE, grid=grid, cache=caches[name])
    times = {"isothermal": [], "heat": []}
    answers = {}
    for _ in range(repeats):
        t0 = time.process_time()
        iso = onset_speed(iso_bearing, ROTOR, LOAD, RANGE, grid=grid,
                          cache=caches["isothermal"])
        times["isothermal"].append(time.process_time() - t0)
        t0 = time.process_time()
        hot = running_onset(hot_bearing, hot_spec, ROTOR, LOAD, RANGE, grid=grid,
                            cache=caches["heat"])
        times["heat"].append(time.process_time() - t0)
        answers = {"isothermal_onset_rpm": iso.onset_speed_rpm,
                   "isothermal_evaluations": iso.evaluations,
                   "heat_onset_rpm": hot["onset_speed_rpm"],
                   "heat_frozen_onset_rpm": hot["frozen_onset_speed_rpm"],
                   "heat_frozen_at_rpm": hot.get("frozen_at_rpm"),
                   "heat_frozen_evaluations": hot["evaluations"],
                   "heat_secant_evaluations": hot["thermal_evaluations"],
                   "heat_static_solves_of_fixed_points": hot["thermal_static_solves"],
                   "heat_running_at_onset": hot["running"]}
    iso_s, hot_s = statistics.median(times["isothermal"]), statistics.median(times["heat"])
    # the stability at one point, isothermal against heat balance (fixed point included)
    from gfbopt.rotor.running_bearing import running_stability
    t0 = time.process_time()
    stability(iso_bearing, ROTOR, OperatingPoint(30e3, LOAD), grid=grid,
              cache=caches["isothermal"])
    point_iso = time.process_time() - t0
    t0 = time.process_time()
    running_stability(hot_bearing, hot_spec, ROTOR, OperatingPoint(30e3, LOAD), grid=grid,
                      cache=caches["heat"])
    point_hot = time.process_time() - t0
    return {**answers, "isothermal_cpu_s": times["isothermal"], "heat_cpu_s": times["heat"],
            "onset_ratio": hot_s / iso_s, "point_30krpm_isothermal_cpu_s": point_iso,
            "point_30krpm_heat_cpu_s": point_hot}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(REPO / "results/benchmarks/thermal.json"))
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--grid", default="144x36")
    args = parser.parse_args(argv)
    grid = Grid.parse(args.grid)
    out = {"machine": machine_info(), "code": tree_label(REPO), "grid": str(grid),
           "case": {"bearings": ["problems/bearings/ruscitto.toml",
                                 "problems/bearings/ruscitto_thermal.toml"],
                    "rotor_mass_kg": ROTOR.mass_kg, "load_newton": LOAD,
                    "onset_range_rpm": RANGE}, "targets": TARGETS}
    out["points"] = points_section(grid)
    print("static solves per point, alone:", [p["static_solves"] for p in out["points"]["alone"]],
          "seeded:", [p["static_solves"] for p in out["points"]["seeded"]])
    out["root_search"] = root_search_section()
    r = out["root_search"]
    print(f"root search: {r['vectorised_cpu_s'] * 1e3:.3g} ms vectorised, "
          f"{r['scalar_loop_cpu_s'] * 1e3:.3g} ms as a scalar loop (×{r['speedup']:.1f}); "
          f"roots differ by {r['root_relative_difference']:.1e}")
    out["onset"] = onset_section(grid, args.repeats)
    o = out["onset"]
    print(f"onset: isothermal {o['isothermal_onset_rpm']:.6g} rpm, heat {o['heat_onset_rpm']:.6g}"
          f" rpm; CPU {o['isothermal_cpu_s']} vs {o['heat_cpu_s']} s: ratio "
          f"{o['onset_ratio']:.2f} (target ≤ {TARGETS['onset_ratio']})")
    write_report(out, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
