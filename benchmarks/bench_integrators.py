"""When does each integrator win?  RK4 (batched numpy) against BDF (scipy, sparse Jacobian).

Run:  python benchmarks/bench_integrators.py [--out results/benchmarks/integrators.json]

On the 72 × 20 grid, for the rigid bearing (ε, Λ) = (0.4, 2) and the simple foil model
(0.4, 2, S = 1): the time of (a) one rotor for 5 revolutions, (b) a batch of 8 rotors for 5
revolutions, (c) the critical mass to 0.5 % centred on the linear threshold — with
``method='rk4'`` and ``method='bdf'`` of gfbopt.transient.  One run, one core.
"""
from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import datetime  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import gfbopt  # noqa: E402
from gfbopt import BearingModel, Grid, solve_static, solver_for  # noqa: E402
from gfbopt.linear import linear_threshold, linearise  # noqa: E402
from gfbopt.transient import find_critical_mass, integrate_orbits, transient_model  # noqa: E402

POINTS = {"rigid (0.4, 2, S=0)": BearingModel(bearing_number=2.0, foil="rigid"),
          "simple (0.4, 2, S=1)": BearingModel(bearing_number=2.0, compliance=1.0)}


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="results/benchmarks/integrators.json")
    args = parser.parse_args(argv)
    grid = Grid(72, 20)
    report = {"date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
              "platform": platform.platform(), "gfbopt": gfbopt.__version__,
              "grid": str(grid), "points": {}}
    for name, model in POINTS.items():
        solver = solver_for(model, grid)
        sol = solve_static(model, eccentricity=0.4, solver=solver)
        mc = linear_threshold(linearise(sol, solver)).critical_mass
        tm = transient_model(sol)
        row = {"linear_critical_mass": mc}
        for method in ("rk4", "bdf"):
            t1, _ = timed(lambda: integrate_orbits(tm, [mc], 5, settle=1, method=method))
            t8, _ = timed(lambda: integrate_orbits(tm, mc * np.linspace(0.98, 1.02, 8), 5,
                                                   settle=1, method=method))
            tc, res = timed(lambda: find_critical_mass(tm, linear_estimate=mc, method=method))
            row[method] = {"one_rotor_5_rev_s": t1, "eight_rotors_5_rev_s": t8,
                           "critical_mass_s": tc, "critical_mass": res.critical_mass,
                           "success": res.success}
        row["winner_one_rotor"] = min(("rk4", "bdf"), key=lambda m: row[m]["one_rotor_5_rev_s"])
        row["winner_critical_mass"] = min(("rk4", "bdf"), key=lambda m: row[m]["critical_mass_s"])
        report["points"][name] = row
        print(f"{name}: linear M̄c = {mc:.5g}")
        for method in ("rk4", "bdf"):
            r = row[method]
            print(f"  {method}: 1 rotor × 5 rev {r['one_rotor_5_rev_s']:6.2f} s | 8 rotors × 5 rev "
                  f"{r['eight_rotors_5_rev_s']:6.2f} s | critical mass {r['critical_mass_s']:6.2f} s "
                  f"→ {r['critical_mass']:.5g}")
        print(f"  faster: one rotor {row['winner_one_rotor']}, critical mass "
              f"{row['winner_critical_mass']}")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(report, indent=2))
    return report


if __name__ == "__main__":
    main()
