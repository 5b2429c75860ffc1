"""What the bumps' Coulomb friction costs the rotor transient, and the blower's top-speed run.

Run:  OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python benchmarks/bench_rotor_friction.py
      [--repeats N] [--out FILE] [--eta η] [--only-damped]
      (default results/benchmarks/rotor_friction.json)

1. ``per_revolution``: CPU time (time.process_time) per shaft revolution of the rotor
   transient of problems/rotors/blower_friction.toml (μ_f = 0.5, κ = 2 at both bearings:
   sliders integrated) against problems/rotors/blower.toml (the same rotor and bearings without
   friction: the fused films of today), 72 × 20, 60,000 rpm, cylindrical kick 1e-3, imbalance
   on, 3 revolutions (both in their films: the friction run closes B's film after 7.4).
   Interleaved A B A B, ``--repeats`` pairs, the median and the range of the per-pair ratios.
   Two step rules: ``fixed`` — rkc at Δτ = 0.1 with 6 stages for both (the ratio is the
   films' and the sliders' cost per step), and ``default`` — each run's own rkc rule (the
   step from accuracy, the stages from its stiffness bound: what a user gets), with the
   evaluations per revolution of each.  Target ratio ≤ 2.
2. ``blower_top_speed``: ``gfbopt.transient.rotor_orbit`` of blower_friction at 60,000 rpm
   for 100 revolutions at 72 × 20 (statics, model and integration, CPU), how it ended at each
   bearing, against the describing function's verdict (gfbopt.rotor.friction_onset
   .settled_whirl, same grid).
3. ``blower_limit_cycle``: the same at 13,500 rpm (just above the onset) for 400 revolutions,
   where the whirl settles on a limit cycle.  Target ≤ 60 s CPU.
4. ``per_revolution_damped``: part 1 with a loss factor η (``--eta``, default 0.2) at both
   bearings of both rotors: friction + η (the Kelvin–Voigt W and the sliders in its rate)
   against η alone (the damped fused films of today).  ``--only-damped`` runs this part only
   and adds its key to the existing ``--out`` file, keeping the others as they were.

The machine's load (uptime) is stated before and after each part: 2 cores shared with other
jobs, so only CPU time and interleaved ratios are meaningful.
"""
from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from dataclasses import replace  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, tree_label, write_report  # noqa: E402
from gfbopt.inputs import Grid  # noqa: E402
from gfbopt.inputs.rotor_system import load_rotor  # noqa: E402
from gfbopt.transient.rotor_analysis import rotor_orbit  # noqa: E402
from gfbopt.transient.rotor_io import rotor_input  # noqa: E402
from gfbopt.transient.rotor_run import integrate_rotor  # noqa: E402
from gfbopt.transient.rotor_setup import (build_model, equilibrium_states,  # noqa: E402
                                          set_station_velocities)
from gfbopt.transient.rotor_system import runs  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
ROTORS = ROOT / "problems" / "rotors"
GRID = Grid(72, 20)
SPEED = 60_000.0
REVOLUTIONS = 3.0


def load() -> str:
    return os.popen("uptime").read().strip()


def _setup(name: str, eta: float = 0.0):
    system = load_rotor(ROTORS / f"{name}.toml")
    if eta > 0:
        system = replace(system, bearings=tuple(
            replace(b, options=replace(b.options, loss_factor=eta)) for b in system.bearings))
    model, _ = build_model(rotor_input(system), SPEED, GRID)
    z = set_station_velocities(model, equilibrium_states(model, 1),
                               [[7.07e-4, 7.07e-4], [7.07e-4, 7.07e-4]])
    return model, z


def per_revolution(repeats: int, eta: float = 0.0) -> dict:
    """Part 1 (η = 0: friction against bare) or part 4 (η > 0: friction + η against η)."""
    cases = {"friction": _setup("blower_friction", eta), "bare": _setup("blower", eta)}
    duration = 2 * math.pi * REVOLUTIONS
    rules = {"fixed": {"time_step": 0.1, "stages": 6}, "default": {}}
    out = {"grid": str(GRID), "speed_rpm": SPEED, "revolutions_per_run": REVOLUTIONS,
           "method": "rkc", "pairs": repeats, "target_ratio": 2.0,
           "load_before": load()}
    if eta > 0:
        out.update(loss_factor=eta, cases="friction: blower_friction with η at both "
                   "bearings (Kelvin–Voigt W and sliders); bare: blower with η (no friction)",
                   reference_whirl_ratio={name: [b.tm.foil_state.reference_whirl_ratio
                                                 for b in model.bearings]
                                          for name, (model, _) in cases.items()})
    for rule, step in rules.items():
        cpu = {k: [] for k in cases}
        info = {}
        for _ in range(repeats):                      # A B A B
            for name, (model, z) in cases.items():
                t = time.process_time()
                run = integrate_rotor(model, runs(1), duration, z.copy(), method="rkc", **step)
                cpu[name].append((time.process_time() - t) / REVOLUTIONS)
                assert run.success and not run.contact[0], run.message
                info[name] = {"evaluations_per_revolution": run.evaluations / REVOLUTIONS,
                              "damped": all(b.tm.foil_state is not None
                                            for b in model.bearings),
                              "time_step_rad": run.time_step, "rkc_stages": list(run.stages),
                              "sliders_integrated": run.sliders is not None}
        ratios = [a / b for a, b in zip(cpu["friction"], cpu["bare"])]
        out[rule] = {"step": step or "each run's own rkc rule",
                     **{f"{k}_cpu_s_per_revolution_median": statistics.median(v)
                        for k, v in cpu.items()},
                     **{f"{k}_cpu_s_per_revolution_each": v for k, v in cpu.items()},
                     "ratio_median": statistics.median(ratios),
                     "ratio_range": [min(ratios), max(ratios)], "runs": info}
    out["load_after"] = load()
    return out


def blower_top_speed() -> dict:
    from gfbopt.rotor.friction_onset import settled_whirl
    from gfbopt.rotor.supports import resolve_rotor

    system = load_rotor(ROTORS / "blower_friction.toml")
    before = load()
    t0 = time.process_time()
    result = rotor_orbit(system, SPEED, 100, grid=GRID)
    cpu = time.process_time() - t0
    d = result.to_dict()
    t0 = time.process_time()
    df = settled_whirl(resolve_rotor(system, GRID), SPEED)
    df_cpu = time.process_time() - t0
    return {"rotor_file": "problems/rotors/blower_friction.toml", "grid": str(GRID),
            "speed_rpm": SPEED, "revolutions_asked": 100,
            "revolutions_integrated": d["revolutions_integrated"],
            "cpu_s": cpu, "target_cpu_s": 60.0, "evaluations": d["evaluations"],
            "rkc_stages": d["rkc_stages"], "model": d["bump_friction"],
            "contact": d["contact"], "contact_bearing": d["contact_bearing"],
            "contact_time_s": d["contact_time_s"],
            "bearings": [{"bearing": b["bearing"], "kind": b["friction_orbit_kind"],
                          "verdict": b["friction_orbit_verdict"], "min_film_um": b["min_film_um"]}
                         for b in d["bearings"]],
            "describing_function": {"verdict": df.verdict, "bounded": df.bounded,
                                    "small_motion_inertia_scale":
                                        df.small_motion_inertia_scale,
                                    "mode": df.label, "cpu_s": df_cpu},
            "load_before": before, "load_after": load()}


#: the code this benchmark measures (its state is recorded beside the tree's)
MEASURED = ["gfbopt/transient", "benchmarks/bench_rotor_friction.py"]


def measured_state() -> dict:
    import subprocess

    def git(*args):
        return subprocess.run(["git", *args], cwd=str(ROOT), capture_output=True,
                              text=True).stdout.strip()
    return {"commit": git("rev-parse", "HEAD"),
            "measured_files_dirty": bool(git("status", "--porcelain", "--", *MEASURED))}


def blower_limit_cycle(speed: float = 13_500.0, revolutions: float = 400) -> dict:
    """The blower on rubbing bumps just above its onset, 72 × 20, the file's imbalance: CPU of
    the whole ``rotor_orbit`` (statics, model, integration) and how it ended per bearing."""
    system = load_rotor(ROTORS / "blower_friction.toml")
    before = load()
    t0 = time.process_time()
    d = rotor_orbit(system, speed, revolutions, grid=GRID).to_dict()
    cpu = time.process_time() - t0
    keys = ("friction_orbit_kind", "friction_orbit_amplitude_um",
            "friction_orbit_previous_amplitude_um", "friction_orbit_whirl_frequency_hz",
            "friction_orbit_whirl_ratio", "friction_orbit_verdict", "min_film_um")
    return {"rotor_file": "problems/rotors/blower_friction.toml", "grid": str(GRID),
            "speed_rpm": speed, "revolutions": revolutions, "cpu_s": cpu,
            "target_cpu_s": 60.0, "evaluations": d["evaluations"],
            "rkc_stages": d["rkc_stages"], "contact": d["contact"],
            "bearings": [{"bearing": b["bearing"], **{k: b.get(k) for k in keys}}
                         for b in d["bearings"]],
            "load_before": before, "load_after": load()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--out", default=str(ROOT / "results/benchmarks/rotor_friction.json"))
    parser.add_argument("--eta", type=float, default=0.2,
                        help="loss factor η of part 4 (friction + η against η alone)")
    parser.add_argument("--only-damped", action="store_true",
                        help="run part 4 only and add its key to the existing --out file")
    args = parser.parse_args()
    if not (math.isfinite(args.eta) and args.eta > 0):
        parser.exit(2, f"--eta = {args.eta}: must be finite and > 0 (the loss factor of "
                       "part 4)\n")
    if args.only_damped:
        if not Path(args.out).is_file():
            parser.exit(2, f"--out = {args.out}: --only-damped adds a key to an existing "
                           "results file, and there is none\n")
        out = json.loads(Path(args.out).read_text())
        out["per_revolution_damped"] = {"machine": machine_info(), "source": tree_label(ROOT),
                                        "measured_code": measured_state(),
                                        **per_revolution(args.repeats, args.eta)}
    else:
        out = {"machine": machine_info(), "source": tree_label(ROOT),
               "measured_code": measured_state(),
               "per_revolution": per_revolution(args.repeats),
               "per_revolution_damped": per_revolution(args.repeats, args.eta),
               "blower_top_speed": blower_top_speed(),
               "blower_limit_cycle": blower_limit_cycle()}
    path = write_report(out, args.out)
    parts = (("per_revolution_damped", "friction+η/η"),) if args.only_damped else (
        ("per_revolution", "friction/bare"), ("per_revolution_damped", "friction+η/η"))
    for key, words in parts:
        p = out[key]
        for rule in ("fixed", "default"):
            print(f"{rule:8s} {words} CPU per revolution: median "
                  f"{p[rule]['ratio_median']:.2f} (pairs {p[rule]['ratio_range'][0]:.2f}–"
                  f"{p[rule]['ratio_range'][1]:.2f}; target ≤ 2)")
    if args.only_damped:
        print(f"written {path}")
        return
    b = out["blower_top_speed"]
    print(f"blower_friction 60,000 rpm 72x20: {b['cpu_s']:.1f} s CPU; "
          + "; ".join(f"{e['bearing']}: {e['verdict']}" for e in b["bearings"])
          + f"; describing function: {b['describing_function']['verdict']}")
    c = out["blower_limit_cycle"]
    print(f"blower_friction 13,500 rpm 72x20, {c['revolutions']:g} revolutions: "
          f"{c['cpu_s']:.1f} s CPU; "
          + "; ".join(f"{e['bearing']}: {e['friction_orbit_verdict']}" for e in c["bearings"]))
    print(f"written {path}")


if __name__ == "__main__":
    main()
