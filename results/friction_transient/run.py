"""The one-bearing transient with the bumps' friction against the describing function.

Cases (Ruscitto bearing file, its formulation; grids as named; the same grid for the linear
and the transient answer of each row):

* bounded: S = 1, κ = 2, μ_f = 0.05, 15,000 rpm (Λ of 30,000 rpm halved), 60 N, M̄ = 8, kicked
  from the equilibrium (kick 0.03), 80 revolutions, at 24 × 8 (also with Δτ halved, and with
  RKC) and 36 × 10;
* contact: the shipped bearing at 30,000 rpm, 20 N, μ_f = 0.2, κ = 1, M̄ = 1.3 × the stuck onset;
* thin margin: S = 3, κ = 2, μ_f = 0.5 and 0.9, 15,000 rpm, 20 N, M̄ = 4.2
  (0.13 % above the stuck onset at 24 × 8), kick 0.08, 300 revolutions.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python results/friction_transient/run.py
writes cases.csv next to this file (CPU seconds per case in the last column).
"""
import math
import time
from pathlib import Path

import pandas as pd

from gfbopt.inputs import load_bearing
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.options import resolve_model_options
from gfbopt.linear import linear_threshold, linearise
from gfbopt.linear.friction_onset import settled_amplitude
from gfbopt.static import solve_static
from gfbopt.transient.friction_orbit import friction_outcome, integrate_friction_orbits
from gfbopt.transient.system import transient_model

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def solved(grid, load, lam_factor, **changes):
    bearing = load_bearing(ROOT / "problems/bearings/ruscitto.toml")
    kw = resolve_model_options(bearing.options).model_kwargs()
    model = bearing.model(30000.0, **kw).replace(**changes)
    model = model.replace(bearing_number=model.bearing_number * lam_factor)
    return solve_static(model, load=bearing.nondimensional_load(load), grid=grid)


def case(name, grid, load, lam_factor, mass, revolutions, kick, step_factor=1.0,
         mass_over_onset=False, method="rk4", **changes):
    t0 = time.process_time()
    sol = solved(Grid(*grid), load, lam_factor, **changes)
    lin = linearise(sol)
    stuck = linear_threshold(lin).critical_mass
    mass = mass * stuck if mass_over_onset else mass
    df = settled_amplitude(lin, mass, samples=12, smallest=1e-2, xtol=1e-4)
    tm = transient_model(sol, friction=True)
    step = None
    if step_factor != 1.0:
        step = step_factor * integrate_friction_orbits(tm, [mass], 0.01, kick=kick,
                                                       method=method).orbit.time_step
    run = integrate_friction_orbits(tm, [mass], revolutions, kick=kick, time_step=step,
                                    method=method)
    out = friction_outcome(run.orbit)
    row = {"case": name, "grid": f"{grid[0]}x{grid[1]}", "method": method, "mass": mass, "stuck_onset": stuck,
           "df_bounded": df.bounded, "df_amplitude": df.amplitude, "df_whirl": df.whirl_ratio,
           "outcome": out.kind, "amplitude": out.amplitude, "previous": out.previous,
           "whirl_ratio": out.whirl_ratio, "min_film": out.min_film,
           "contact_revolution": out.contact_tau / (2 * math.pi),
           "time_step": run.orbit.time_step, "revolutions": revolutions,
           "cpu_s": time.process_time() - t0}
    print(row, flush=True)
    return row


def main():
    bounded = dict(load=60.0, lam_factor=0.5, compliance=1.0, friction_coefficient=0.05,
                   friction_stiffness_ratio=2.0)
    thin = dict(load=20.0, lam_factor=0.5, compliance=3.0, friction_stiffness_ratio=2.0)
    rows = [case("bounded", (24, 8), mass=8.0, revolutions=80, kick=0.03, **bounded),
            case("bounded, step/2", (24, 8), mass=8.0, revolutions=80, kick=0.03,
                 step_factor=0.5, **bounded),
            case("bounded", (24, 8), mass=8.0, revolutions=80, kick=0.03, method="rkc",
                 **bounded),
            case("bounded", (36, 10), mass=8.0, revolutions=80, kick=0.03, **bounded),
            case("contact", (24, 8), load=20.0, lam_factor=1.0, mass=1.3, revolutions=80,
                 kick=0.03, mass_over_onset=True, friction_coefficient=0.2),
            case("thin margin mu 0.5", (24, 8), mass=4.2, revolutions=300, kick=0.08,
                 friction_coefficient=0.5, **thin),
            case("thin margin mu 0.9", (24, 8), mass=4.2, revolutions=300, kick=0.08,
                 friction_coefficient=0.9, **thin)]
    pd.DataFrame(rows).to_csv(HERE / "cases.csv", index=False)


if __name__ == "__main__":
    main()
