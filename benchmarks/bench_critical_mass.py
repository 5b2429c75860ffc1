"""The nonlinear critical mass and the README's orbit at the default grid, by method, and the
cost of one revolution against grid size — in one run, on one core.

Run:  PYTHONPATH=. python benchmarks/bench_critical_mass.py [--out FILE.json]
(default results/benchmarks/critical_mass.json; --skip-previous, --skip-scaling;
--damped-only runs section 4 alone, default out results/benchmarks/critical_mass_damped.json)

Operating point: ε = 0.4, Λ = 2, S = 1, L/D = 1, simple foundation (axial-mean
law), periodic film, 144 × 36.  Times are split: the CasADi/IPOPT build, the static solve +
linearisation + linear threshold, the linear mode (one sparse LU), and the transient search
or orbit alone (what this work changes).

1. Critical mass to a relative tolerance of 0.005, centred on the linear threshold:
   the same two-transient search with rkc, rk4 and bdf (all started from the linear mode),
   rkc started from a kick, and the previous search (rk4, a batch of 8 from a kick, 5
   revolutions) for reference.  Accuracy: |M̄_crit / M̄_lin − 1|.
2. ``gfbopt orbit --eccentricity 0.4 --bearing-number 2 --compliance 1 --length-ratio 1
   --mass 2.5 --revolutions 20``: the transient with rkc (timed) and the RK4 evaluation count
   it would need (its step × 4 evaluations; not run).
3. One revolution of one rotor (M̄ = 2.5, kick 1e-3) at 72 × 20, 108 × 28, 144 × 36 and
   216 × 54 with rk4 and rkc: time, evaluations; exponents of time ∝ nodes^p fitted by least
   squares on log–log (RK4: step ∝ Δ², so p ≈ 2; RKC: stages ∝ √ρ ∝ 1/Δ, so p ≈ 1.5).

4. Structural damping: the critical mass with η = 0.3 at 144 × 36, rkc, from the
   damped linear mode, with the Kelvin–Voigt foil state (ν_ref = the linear threshold whirl
   ratio): the axial-mean law at the point above, and the local law with a seam 180° from the
   load.  Seconds of the search and its deviation from the damped linear critical mass
   (target: 1 %), beside the same search without damping (the cost of the foil state).

Targets: critical mass ≤ 10 s within 0.5 % of the linear threshold; the orbit
example ≤ 10 s.  Wall and CPU seconds are both recorded: on a shared machine the wall time
also counts the time spent waiting for a core (the load average is recorded too).
"""
from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, write_report  # noqa: E402
from gfbopt import BearingModel, Grid, solve_static, solver_for  # noqa: E402
from gfbopt.linear import linear_threshold, linearise  # noqa: E402
from gfbopt.transient import (find_critical_mass, integrate_orbits, linear_mode,  # noqa: E402
                              stable_time_step, transient_model, equilibrium_state)

REPO = Path(__file__).resolve().parent.parent
MODEL = BearingModel(bearing_number=2.0, compliance=1.0, length_ratio=1.0)
ECCENTRICITY = 0.4
TOLERANCE = 0.005
TARGETS = {"critical_mass_s": 10.0, "orbit_s": 10.0, "accuracy_rel": 0.005}
SCALING_GRIDS = ((72, 20), (108, 28), (144, 36), (216, 54))


#: CPU seconds of the last :func:`timed` call (this process only: on a shared machine the
#: wall time includes waiting for a core, the CPU time does not)
LAST_CPU = [0.0]


def timed(fn):
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    LAST_CPU[0] = time.process_time() - c0
    return time.perf_counter() - t0, out


def setup(grid: Grid) -> dict:
    build_s, solver = timed(lambda: solver_for(MODEL, grid))
    lin_s, (sol, lin, thr) = timed(lambda: _linear(solver))
    mode_s, mode = timed(lambda: linear_mode(lin, thr.critical_mass, 1j * thr.whirl_ratio))
    return {"build_s": build_s, "static_linear_threshold_s": lin_s, "mode_s": mode_s,
            "sol": sol, "lin": lin, "thr": thr, "mode": mode, "tm": transient_model(sol)}


def _linear(solver):
    sol = solve_static(MODEL, eccentricity=ECCENTRICITY, solver=solver)
    lin = linearise(sol, solver)
    return sol, lin, linear_threshold(lin)


def search(case: dict, label: str, **kwargs) -> dict:
    thr = case["thr"]
    wall, res = timed(lambda: find_critical_mass(case["tm"], tolerance=TOLERANCE,
                                                 linear_estimate=thr.critical_mass,
                                                 **kwargs))
    row = {"label": label, "method": res.method, "start": res.start, "wall_s": wall,
           "cpu_s": LAST_CPU[0],
           "critical_mass": res.critical_mass,
           "rel_to_linear": abs(res.critical_mass / thr.critical_mass - 1),
           "bracket": list(res.bracket), "transients": res.transients, "rounds": res.rounds,
           "rotor_revolutions": res.rotor_revolutions, "evaluations": res.evaluations,
           "success": res.success, "message": res.message}
    print(f"  {label:<38s} {wall:8.2f} s (cpu {LAST_CPU[0]:7.2f} s)  "
          f"M̄c = {res.critical_mass:.6f} "
          f"(|rel − lin| = {100 * row['rel_to_linear']:.4f} %), {res.transients} transients, "
          f"{res.rotor_revolutions:.1f} rotor-rev, {res.evaluations} evaluations", flush=True)
    return row


def orbit_example(case: dict) -> dict:
    tm = case["tm"]
    wall, orbit = timed(lambda: integrate_orbits(tm, [2.5], 20, method="rkc"))
    rk4_dt = stable_time_step(tm, equilibrium_state(tm, 1))
    rk4_evals = 4 * math.ceil(2 * math.pi * 20 / rk4_dt)
    row = {"wall_s": wall, "cpu_s": LAST_CPU[0], "evaluations": orbit.evaluations,
           "time_step": orbit.time_step,
           "verdict": orbit.verdict[0], "growth_rate": float(orbit.growth_rate[0]),
           "whirl_ratio": float(orbit.whirl_ratio[0]), "rk4_time_step": rk4_dt,
           "rk4_evaluations_needed": rk4_evals,
           "evaluation_ratio_rk4_over_rkc": rk4_evals / orbit.evaluations}
    print(f"  orbit M̄ = 2.5, 20 rev, rkc: {wall:.2f} s (cpu {row['cpu_s']:.2f} s), "
          f"{orbit.evaluations} evaluations "
          f"(RK4 would need {rk4_evals}), {orbit.verdict[0]}", flush=True)
    return row


def scaling() -> dict:
    rows = []
    for nt, nz in SCALING_GRIDS:
        grid = Grid(nt, nz)
        build_s, solver = timed(lambda: solver_for(MODEL, grid))
        sol = solve_static(MODEL, eccentricity=ECCENTRICITY, solver=solver)
        tm = transient_model(sol)
        row = {"grid": str(grid), "nodes": sol.pressure.size, "build_s": build_s}
        for method in ("rk4", "rkc"):
            wall, orbit = timed(lambda: integrate_orbits(tm, [2.5], 1, method=method))
            row[method] = {"wall_s": wall, "cpu_s": LAST_CPU[0],
                           "evaluations": orbit.evaluations, "time_step": orbit.time_step}
        print(f"  {row['grid']:>7s}: rk4 {row['rk4']['wall_s']:7.2f} s "
              f"({row['rk4']['evaluations']} ev), rkc {row['rkc']['wall_s']:6.2f} s "
              f"({row['rkc']['evaluations']} ev)", flush=True)
        rows.append(row)
    nodes = np.log([r["nodes"] for r in rows])
    out = {"rows": rows}
    for method in ("rk4", "rkc"):
        out[f"{method}_time_exponent"] = float(np.polyfit(
            nodes, np.log([r[method]["wall_s"] for r in rows]), 1)[0])
        out[f"{method}_cpu_time_exponent"] = float(np.polyfit(
            nodes, np.log([r[method]["cpu_s"] for r in rows]), 1)[0])
        out[f"{method}_evaluation_exponent"] = float(np.polyfit(
            nodes, np.log([r[method]["evaluations"] for r in rows]), 1)[0])
    print(f"  exponents (time ∝ nodes^p): rk4 {out['rk4_time_exponent']:.2f}, rkc "
          f"{out['rkc_time_exponent']:.2f}; cpu: rk4 {out['rk4_cpu_time_exponent']:.2f}, rkc "
          f"{out['rkc_cpu_time_exponent']:.2f}; evaluations: rk4 "
          f"{out['rk4_evaluation_exponent']:.2f}, rkc {out['rkc_evaluation_exponent']:.2f}")
    return out


DAMPED_CASES = {
    "axial-mean law, periodic film": MODEL.replace(loss_factor=0.3),
    "local law, seam 180° from the load": MODEL.replace(loss_factor=0.3, deflection_law="local",
                                                         film="seam", seam_angle_deg=180.0),
}


def damped(grid: Grid) -> list:
    """Section 4: the damped critical mass against the damped linear one, and the cost of
    the foil state (the same search undamped)."""
    rows = []
    for label, model in DAMPED_CASES.items():
        row = {"case": label, "loss_factor": model.loss_factor, **model.options()}
        for eta in (model.loss_factor, 0.0):
            m = model.replace(loss_factor=eta)
            build_s, solver = timed(lambda: solver_for(m, grid))
            sol = solve_static(m, eccentricity=ECCENTRICITY, solver=solver)
            lin_s, (lin, thr) = timed(lambda: (lambda lin: (lin, linear_threshold(lin)))(
                linearise(sol, solver)))
            tm_s, tm = timed(lambda: transient_model(sol, threshold=thr if eta else None))
            mode = linear_mode(lin, thr.critical_mass, 1j * thr.whirl_ratio)
            wall, res = timed(lambda: find_critical_mass(
                tm, tolerance=TOLERANCE, linear_estimate=thr.critical_mass, initial_mode=mode))
            entry = {"build_s": build_s, "linear_threshold_s": lin_s, "transient_model_s": tm_s,
                     "search_wall_s": wall, "search_cpu_s": LAST_CPU[0],
                     "linear_critical_mass": thr.critical_mass,
                     "linear_whirl_ratio": thr.whirl_ratio,
                     "critical_mass": res.critical_mass, "whirl_ratio": res.whirl_ratio,
                     "rel_to_linear": res.critical_mass / thr.critical_mass - 1,
                     "transients": res.transients, "evaluations": res.evaluations,
                     "success": res.success, "message": res.message, **res.damping}
            row["damped" if eta else "undamped"] = entry
            print(f"  {label}, η = {eta:g}: search {wall:.2f} s (cpu {LAST_CPU[0]:.2f} s), "
                  f"M̄c = {res.critical_mass:.6f} against linear {thr.critical_mass:.6f} "
                  f"({100 * entry['rel_to_linear']:+.4f} %), {res.evaluations} evaluations",
                  flush=True)
        row["damping_raises_critical_mass_by"] = (row["damped"]["linear_critical_mass"]
                                                  / row["undamped"]["linear_critical_mass"] - 1)
        row["evaluation_ratio_damped_over_undamped"] = (row["damped"]["evaluations"]
                                                        / row["undamped"]["evaluations"])
        rows.append(row)
    return rows


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(REPO / "results" / "benchmarks" /
                                             "critical_mass.json"))
    parser.add_argument("--skip-previous", action="store_true",
                        help="skip the previous search (rk4, batch of 8, ≈ 100 s)")
    parser.add_argument("--skip-scaling", action="store_true")
    parser.add_argument("--damped-only", action="store_true",
                        help="run section 4 (η > 0) alone")
    args = parser.parse_args(argv)
    grid = Grid()
    if args.damped_only:
        print(f"critical mass with structural damping at {grid}", flush=True)
        out = {"machine": machine_info(grid=str(grid)), "eccentricity": ECCENTRICITY,
               "tolerance": TOLERANCE, "target_rel_to_linear": 0.01, "damped": damped(grid)}
        out["targets_met"] = all(abs(r["damped"]["rel_to_linear"]) <= 0.01 and
                                 r["damped"]["success"] for r in out["damped"])
        out["load_average_at_end"] = os.getloadavg()
        default = REPO / "results" / "benchmarks" / "critical_mass_damped.json"
        write_report(out, default if args.out == parser.get_default("out") else args.out)
        return out
    out = {"machine": machine_info(grid=str(grid)),
           "operating_point": {"eccentricity": ECCENTRICITY, **MODEL.groups(),
                               **MODEL.options()},
           "tolerance": TOLERANCE, "targets": TARGETS}
    print(f"critical mass at {grid} (ε = 0.4, Λ = 2, S = 1, periodic, simple)", flush=True)
    case = setup(grid)
    thr = case["thr"]
    out["setup"] = {k: case[k] for k in ("build_s", "static_linear_threshold_s", "mode_s")}
    out["linear"] = {"critical_mass": thr.critical_mass, "whirl_ratio": thr.whirl_ratio}
    print(f"  build {case['build_s']:.2f} s, static + linear threshold "
          f"{case['static_linear_threshold_s']:.2f} s, mode {case['mode_s']:.2f} s; "
          f"linear M̄c = {thr.critical_mass:.6f}", flush=True)
    mode = case["mode"]
    searches = [search(case, "rkc, two transients, mode start", method="rkc",
                       initial_mode=mode),
                search(case, "rkc, two transients, kick start", method="rkc"),
                search(case, "rk4, two transients, mode start", method="rk4",
                       initial_mode=mode),
                search(case, "bdf, two transients, mode start", method="bdf",
                       initial_mode=mode)]
    if not args.skip_previous:
        searches.append(search(case, "previous: rk4, batch of 8, kick, 5 rev", method="rk4",
                               batch=8, revolutions=5.0, settle=1.0))
    out["critical_mass"] = searches
    best = searches[0]
    for row in searches[1:]:
        row["time_ratio_over_rkc_mode"] = row["wall_s"] / best["wall_s"]
    out["orbit_example"] = orbit_example(case)
    print("critical mass with structural damping (η = 0.3)", flush=True)
    out["damped"] = damped(grid)
    if not args.skip_scaling:
        print("cost of one revolution against grid size", flush=True)
        out["scaling"] = scaling()
    out["targets_met"] = {
        "critical_mass_rkc_s": best["wall_s"] <= TARGETS["critical_mass_s"],
        "critical_mass_rkc_with_mode_s": best["wall_s"] + case["mode_s"]
        <= TARGETS["critical_mass_s"],
        "critical_mass_accuracy": bool(best["rel_to_linear"] <= TARGETS["accuracy_rel"]),
        "orbit_s": out["orbit_example"]["wall_s"] <= TARGETS["orbit_s"],
        "orbit_cpu_s": out["orbit_example"]["cpu_s"] <= TARGETS["orbit_s"]}
    out["load_average_at_end"] = os.getloadavg()
    print(f"targets: {out['targets_met']}")
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
