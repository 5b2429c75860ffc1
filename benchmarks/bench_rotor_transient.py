"""What a transient of the whole rotor costs (issue 18).

Run:  PYTHONPATH=. python benchmarks/bench_rotor_transient.py [--rate RPM_PER_S] [--out FILE]
(default results/benchmarks/rotor_transient.json)

1. Cost per revolution, rotor against one bearing, in one run (72 × 20, rkc, the same step
   Δτ = 0.1 and stages for both, constant speed 45,000 rpm, the example rotor of issue 16 on
   two Ruscitto bearings): CPU time per shaft revolution of (a) the one-bearing engine
   (gfbopt.transient.integrate_orbits, one rotor) and (b) the rotor transient (both films,
   4 DOF, gyroscopics), interleaved, best of three.  Target ratio ≤ 2.5.
2. Run-up 5,000 → 60,000 rpm at 72 × 20 with G2.5 imbalance at ``--rate`` (default
   50,000 rpm/s, the study's), the rotor of problems/rotor_run_up.toml (it whirls into
   contact past its onset, which ends its run) and the same rotor with a few per cent of
   its inertias on the same bearing loads (``--inertia-scale``; 3 % still whirled into
   contact at 55,000 rpm, 2 % is stable over the ramp): wall and CPU time, shaft
   revolutions, RHS evaluations, the record's size.  Target ≤ 3 min.  The machine's load (uptime) is recorded
   before and after: on a shared 2-core machine other work inflates these times.
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

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, write_report  # noqa: E402
from gfbopt.inputs import Grid  # noqa: E402
from gfbopt.static import SolverCache  # noqa: E402
from gfbopt.studies.runner import load_study  # noqa: E402
from gfbopt.transient import integrate_orbits  # noqa: E402
from gfbopt.transient.rotor_analysis import ramp_profile, run_profile  # noqa: E402
from gfbopt.transient.rotor_io import rotor_input  # noqa: E402
from gfbopt.transient.rotor_run import integrate_rotor  # noqa: E402
from gfbopt.transient.rotor_setup import (build_model, equilibrium_states,  # noqa: E402
                                          set_station_velocities)
from gfbopt.transient.rotor_system import runs  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
GRID = Grid(72, 20)


def load() -> str:
    return os.popen("uptime").read().strip()


def per_revolution(revolutions: float = 3.0, repeats: int = 3) -> dict:
    system = load_study(ROOT / "problems/rotor_run_up.toml").plan["system"]
    rotor = rotor_input(system)
    cache = SolverCache(GRID)
    model, sols = build_model(rotor, 45_000.0, GRID, cache=cache)
    tm = model.bearings[0].tm
    z0 = set_station_velocities(model, equilibrium_states(model, 1),
                                [[7e-4, 7e-4], [7e-4, 7e-4]])
    step = {"time_step": 0.1, "stages": 6}
    one_t, rot_t, evals = [], [], {}
    for _ in range(repeats):
        t0 = time.process_time()
        one = integrate_orbits(tm, [10.0], revolutions, method="rkc", **step)
        one_t.append((time.process_time() - t0) / revolutions)
        t0 = time.process_time()
        run = integrate_rotor(model, runs(1), 2 * math.pi * revolutions, z0.copy(), **step)
        rot_t.append((time.process_time() - t0) / revolutions)
        evals = {"one_bearing": one.evaluations, "rotor": run.evaluations}
    return {"grid": str(GRID), "speed_rpm": 45_000.0, "method": "rkc", **step,
            "revolutions_per_run": revolutions, "repeats": repeats,
            "one_bearing_cpu_s_per_revolution": min(one_t),
            "rotor_cpu_s_per_revolution": min(rot_t),
            "ratio": min(rot_t) / min(one_t), "target_ratio": 2.5,
            "evaluations": evals, "stacked_films": True}


def run_up(rate: float, inertia_scale: float = 1.0) -> dict:
    system = load_study(ROOT / "problems/rotor_run_up.toml").plan["system"]
    profile = ramp_profile(5_000.0, 60_000.0, rate)
    t0, c0 = time.perf_counter(), time.process_time()
    result = run_profile(system, profile, grid=GRID, perturbation="none", linear_onset=False,
                         inertia_scale=inertia_scale)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    d = result.to_dict()
    return {"grid": str(GRID), "inertia_scale": inertia_scale,
            "start_rpm": 5_000.0, "end_rpm": 60_000.0,
            "rate_rpm_per_s": rate, "duration_s": profile.duration_s,
            "revolutions": profile.revolutions,
            "revolutions_integrated": result.run.revolutions,
            "imbalance_g_mm": [p.amount_kg_m * 1e6 for p in system.imbalance],
            "wall_time_s": wall, "cpu_time_s": cpu, "target_wall_s": 180.0,
            "evaluations": result.run.evaluations, "time_step_rad": result.run.time_step,
            "rkc_stages": list(result.run.stages), "contact": d["contact"],
            "contact_speed_rpm": d["contact_speed_rpm"],
            "subsync_appearance_rpm": d["subsync_appearance_rpm"],
            "samples_kept": int(result.run.tau.size),
            "record_bytes": int(result.run.q.nbytes + result.run.min_film.nbytes
                                + result.run.tau.nbytes)}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--rate", type=float, default=50_000.0)
    parser.add_argument("--skip-run-up", action="store_true")
    parser.add_argument("--full-ramp-only", action="store_true",
                        help="only the light rotor's full ramp (no ratio, no example rotor)")
    parser.add_argument("--inertia-scale", type=float, default=0.03,
                        help="inertias of the light rotor over the example's (loads kept)")
    parser.add_argument("--out", default=str(ROOT / "results/benchmarks/rotor_transient.json"))
    args = parser.parse_args()
    out = {"machine": machine_info(load_before=load())}
    if args.full_ramp_only:
        out["run_up_full_ramp"] = run_up(args.rate, inertia_scale=args.inertia_scale)
        print(out["run_up_full_ramp"])
        out["machine"]["load_after"] = load()
        write_report(out, args.out)
        return
    out["per_revolution"] = per_revolution()
    print(out["per_revolution"])
    if not args.skip_run_up:
        # the example rotor whirls past its onset (≈ 12,000 rpm) into contact: its run-up
        # ends there; a rotor with 3 % of its inertias on the same bearing loads (onset
        # ≈ 12,000/√0.03 ≈ 70,000 rpm) runs the whole ramp
        out["run_up_example_rotor"] = run_up(args.rate)
        print(out["run_up_example_rotor"])
        out["run_up_full_ramp"] = run_up(args.rate, inertia_scale=args.inertia_scale)
        print(out["run_up_full_ramp"])
    out["machine"]["load_after"] = load()
    write_report(out, args.out)


if __name__ == "__main__":
    main()
