"""When does each integrator win, and how accurate is RKC's default step?

Run:  PYTHONPATH=. python benchmarks/bench_integrators.py [--out FILE.json]
(default results/benchmarks/integrators.json)

1. Speed (72 × 20, one core, one run): for the rigid bearing (ε, Λ) = (0.4, 2) and the
   simple foil (0.4, 2, S = 1), the time of (a) one rotor for 5 revolutions, (b) a batch of 8
   rotors for 5 revolutions, (c) the critical mass to 0.5 % centred on the linear threshold
   (the default two-transient search from a kick) — with ``method='rk4'``, ``'rkc'`` and
   ``'bdf'`` of gfbopt.transient.
2. Accuracy study behind RKC's default step (``--skip-accuracy`` to leave out): at 72 × 20,
   S = 1, ε = 0.4 and (Λ, L/D) = (2, 1), (0.5, 1), (2, 0.5), one rotor at 1.04 M̄_crit kicked
   as usual for 5 revolutions; growth rate σ and whirl ratio γ (fitted after the first
   revolution) with RKC at Δτ = 0.4, 0.2, 0.1, 0.05 and the default, against RK4 at 0.9 ×
   its stability limit.  The table in the docstring of gfbopt/transient/rkc.py comes from it.
"""
from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, write_report  # noqa: E402
from gfbopt import BearingModel, Grid, solve_static, solver_for  # noqa: E402
from gfbopt.linear import linear_threshold, linearise  # noqa: E402
from gfbopt.transient import find_critical_mass, integrate_orbits, transient_model  # noqa: E402
from gfbopt.transient.rkc import film_time  # noqa: E402

GRID = Grid(72, 20)
METHODS = ("rk4", "rkc", "bdf")
POINTS = {"rigid (0.4, 2, S=0)": BearingModel(bearing_number=2.0, foil="rigid"),
          "simple (0.4, 2, S=1)": BearingModel(bearing_number=2.0, compliance=1.0)}
ACCURACY_POINTS = {"Λ=2, L/D=1": BearingModel(bearing_number=2.0, compliance=1.0),
                   "Λ=0.5, L/D=1": BearingModel(bearing_number=0.5, compliance=1.0),
                   "Λ=2, L/D=0.5": BearingModel(bearing_number=2.0, compliance=1.0,
                                                length_ratio=0.5)}
STEPS = (0.4, 0.2, 0.1, 0.05, None)


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def _point(model):
    solver = solver_for(model, GRID)
    sol = solve_static(model, eccentricity=0.4, solver=solver)
    return sol, linear_threshold(linearise(sol, solver)).critical_mass


def speed() -> dict:
    report = {}
    for name, model in POINTS.items():
        sol, mc = _point(model)
        tm = transient_model(sol)
        row = {"linear_critical_mass": mc}
        for method in METHODS:
            t1, _ = timed(lambda: integrate_orbits(tm, [mc], 5, settle=1, method=method))
            t8, _ = timed(lambda: integrate_orbits(tm, mc * np.linspace(0.98, 1.02, 8), 5,
                                                   settle=1, method=method))
            tc, res = timed(lambda: find_critical_mass(tm, linear_estimate=mc, method=method))
            row[method] = {"one_rotor_5_rev_s": t1, "eight_rotors_5_rev_s": t8,
                           "critical_mass_s": tc, "critical_mass": res.critical_mass,
                           "rel_to_linear": abs(res.critical_mass / mc - 1),
                           "success": res.success}
            print(f"  {name} {method}: 1 rotor × 5 rev {t1:6.2f} s | 8 rotors × 5 rev "
                  f"{t8:6.2f} s | critical mass {tc:6.2f} s → {res.critical_mass:.5g}",
                  flush=True)
        for key in ("one_rotor_5_rev_s", "eight_rotors_5_rev_s", "critical_mass_s"):
            row[f"fastest_{key}"] = min(METHODS, key=lambda m: row[m][key])
        report[name] = row
    return report


def accuracy() -> dict:
    report = {}
    for name, model in ACCURACY_POINTS.items():
        sol, mc = _point(model)
        tm = transient_model(sol)
        mass = 1.04 * mc
        ref = integrate_orbits(tm, [mass], 5, settle=1, method="rk4")
        row = {"film_time": film_time(tm), "rk4_growth_rate": float(ref.growth_rate[0]),
               "rk4_whirl_ratio": float(ref.whirl_ratio[0]), "rk4_evaluations": ref.evaluations,
               "rkc": []}
        for dt in STEPS:
            run = integrate_orbits(tm, [mass], 5, settle=1, method="rkc", time_step=dt)
            row["rkc"].append({"time_step": run.time_step, "default": dt is None,
                               "growth_error": float(run.growth_rate[0] - ref.growth_rate[0]),
                               "whirl_error": float(run.whirl_ratio[0] - ref.whirl_ratio[0]),
                               "evaluations": run.evaluations})
            last = row["rkc"][-1]
            print(f"  {name} Δτ = {run.time_step:.4f}{' (default)' if dt is None else ''}: "
                  f"Δσ = {last['growth_error']:+.2e}, Δγ = {last['whirl_error']:+.2e}, "
                  f"{run.evaluations} evaluations (RK4 {ref.evaluations})", flush=True)
        report[name] = row
    return report


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="results/benchmarks/integrators.json")
    parser.add_argument("--skip-accuracy", action="store_true")
    args = parser.parse_args(argv)
    out = {"machine": machine_info(grid=str(GRID)), "speed": speed()}
    if not args.skip_accuracy:
        out["accuracy"] = accuracy()
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
