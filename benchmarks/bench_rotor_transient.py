"""What a transient of the whole rotor costs.

Run:  PYTHONPATH=. python benchmarks/bench_rotor_transient.py [--case NAME ...] [--out FILE]
(default: the per-revolution ratio and the full-ramp case, results/benchmarks/rotor_transient.json)

1. Cost per revolution, rotor against one bearing, in one run (72 × 20, rkc, the same step
   Δτ = 0.1 and stages for both, constant speed 45,000 rpm, the rotor of
   problems/rotors/blower.toml on its two Ruscitto bearings): CPU time per shaft revolution
   of (a) the one-bearing engine (gfbopt.transient.integrate_orbits, one rotor) and (b) the
   rotor transient (both films, 4 DOF, gyroscopics), interleaved, best of three.  Target
   ratio ≤ 2.5.
2. Run-up 5,000 → 60,000 rpm at 72 × 20 with imbalance at ``--rate`` (default 50,000 rpm/s,
   the study's: 1.1 s, 596 shaft revolutions), target ≤ 3 min on 2 cores.  Cases:

   * ``preloaded`` (the full-ramp case, default): the study rotor (3.2 kg, G2.5 imbalance of
     problems/rotor_run_up.toml) on the same Ruscitto bearings built with 3 shims of 0.6 c
     (60° wide, centred at 0°, 120°, 240° from the load: problems/ruscitto_preload.toml's
     deepest preload), a bump loss factor η = 0.3, and a static side load of 60 N at the
     CG along gravity (a process or gear load: the bearings carry 2.9× the weight).
     Preload, structural damping and a firm static load are the levers that keep a
     foil-bearing rotor in its film at speed.  In this model no gravity-loaded rotor on
     these bearings is linearly stable at 60,000 rpm (the onset needs c ω²/g ≤ M̄_crit,
     whatever the mass), and each lever alone is not enough: the round undamped bore whirls
     into contact at ≈ 20,000 rpm, 3 shims + η = 0.3 at ≈ 52,600 rpm, 60 N alone moves the
     linear onset to ≈ 21,400 rpm (36 × 10 explorations); together the rotor runs the whole
     ramp in its film with no subsynchronous line.
   * ``study``: the study rotor as it is (its run ends at contact, ≈ 20,000 rpm).
   * ``light``: the study rotor with 2 % of its inertias on the same bearing loads (the
     previous full-ramp case; a static load ≈ 50× its weight, not a real machine, but its fast
     rigid-body frequency sets the step: the most evaluations per revolution).

   For each: wall and CPU time, the machine's load (uptime) before and after, shaft
   revolutions, RHS evaluations, steps and stages, the record's size (what the run keeps:
   4 + K floats per run per sample, never the films).
3. With ``--before TREE`` (a checkout of an earlier commit, e.g. ``git worktree add
   /tmp/old <commit>``), old against new in one run:

   * ``rhs_evaluation``: CPU time of one right-hand-side evaluation of the rotor (both
     films, 72 × 20, one run on a ramp, near the 30,000 rpm equilibrium) for the
     ``preloaded`` (damped, the bearings' τ_f differ) and ``study`` (undamped) rotors,
     measured in child processes that alternate old and new (A B A B, ``--repeats``), each
     the median of 5 batches of 1,000 evaluations; medians of the repeats and their ratio
     (target ≥ 2);
   * ``run_up_before``: the old tree's own run-up cases (its benchmark script, run before
     the new code's), CPU time, evaluations and the answers beside the new ones
     (``run_up_change``).
"""
from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import dataclasses  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, tree_label, write_report  # noqa: E402
from gfbopt.inputs import Grid  # noqa: E402
from gfbopt.inputs.bore_si import BearingBuild, BoreSpec  # noqa: E402
from gfbopt.inputs.rotor_system import SideLoad  # noqa: E402
from gfbopt.static import SolverCache  # noqa: E402
from gfbopt.studies.runner import load_study  # noqa: E402
from gfbopt.transient import integrate_orbits  # noqa: E402
from gfbopt.transient.rotor_analysis import ramp_profile, run_profile  # noqa: E402
from gfbopt.transient.rotor_io import rotor_input  # noqa: E402
from gfbopt.transient.rotor_run import integrate_rotor  # noqa: E402
from gfbopt.transient.rotor_setup import (build_model, equilibrium_states,  # noqa: E402
                                          set_station_velocities)
from gfbopt.transient.rotor_system import RotorRightHandSide, runs  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
GRID = Grid(72, 20)
CASES = ("preloaded", "study", "light")
#: the full-ramp case's bearings: problems/ruscitto_preload.toml's deepest preload, η = 0.3
PRELOAD = BoreSpec("shims", 3, preload_ratio=0.6, width_deg=60.0, offset_deg=0.0)
LOSS_FACTOR = 0.3
SIDE_LOAD_N = 60.0
LIGHT_INERTIA_SCALE = 0.02
#: what the speed work changed (the measured code), for the tree-state record
MEASURED = ["gfbopt/transient", "gfbopt/discretisation.py", "gfbopt/physics",
            "benchmarks/bench_rotor_transient.py"]
RHS_CASES = ("preloaded", "study")


def load() -> str:
    return os.popen("uptime").read().strip()


def study_system():
    return load_study(ROOT / "problems/rotor_run_up.toml").plan["system"]


def preloaded_system():
    """The study rotor on its bearings built with :data:`PRELOAD`, loss factor η, and a side
    load of :data:`SIDE_LOAD_N` at the CG along gravity."""
    system = study_system()
    bearings = tuple(dataclasses.replace(
        b, geometry=dataclasses.replace(b.geometry, build=BearingBuild(bore=PRELOAD)),
        options=dataclasses.replace(b.options, loss_factor=LOSS_FACTOR))
        for b in system.bearings)
    return dataclasses.replace(system, bearings=bearings,
                               side_loads=(SideLoad(SIDE_LOAD_N, 0.0, 0.0),))


def per_revolution(revolutions: float = 3.0, repeats: int = 3) -> dict:
    rotor = rotor_input(study_system())
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


def run_up(case: str, rate: float) -> dict:
    system = preloaded_system() if case == "preloaded" else study_system()
    mu = LIGHT_INERTIA_SCALE if case == "light" else 1.0
    profile = ramp_profile(5_000.0, 60_000.0, rate)
    before = load()
    t0, c0 = time.perf_counter(), time.process_time()
    result = run_profile(system, profile, grid=GRID, perturbation="none", linear_onset=False,
                         inertia_scale=mu)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    d = result.to_dict()
    r = result.run
    return {"case": case, "grid": str(GRID), "inertia_scale": mu,
            "bore": PRELOAD.describe() if case == "preloaded" else {"bore": "round"},
            "loss_factor": LOSS_FACTOR if case == "preloaded" else 0.0,
            "side_load_n": SIDE_LOAD_N if case == "preloaded" else 0.0,
            "start_rpm": 5_000.0, "end_rpm": 60_000.0,
            "rate_rpm_per_s": rate, "duration_s": profile.duration_s,
            "revolutions": profile.revolutions,
            "revolutions_integrated": r.revolutions,
            "imbalance_g_mm": [p.amount_kg_m * 1e6 for p in system.imbalance],
            "wall_time_s": wall, "cpu_time_s": cpu, "target_wall_s": 180.0,
            "load_before": before, "load_after": load(),
            "evaluations": r.evaluations, "last_time_step_rad": r.time_step,
            "rkc_stages": list(r.stages), "step_rule": r.options.get("step_rule"),
            "contact": d["contact"], "contact_speed_rpm": d["contact_speed_rpm"],
            "subsync_appearance_rpm": d["subsync_appearance_rpm"],
            "min_film_um": [b.get("min_film_um") for b in d["bearings"]],
            "peak_sync_amplitude_um": [b.get("peak_sync_amplitude_um") for b in d["bearings"]],
            # the ramp's peak 1x response since the result's sync_amplitude_um (major semi-axis)
            "peak_amplitude_um": [b.get("peak_amplitude_um") for b in d["bearings"]],
            "peak_speed_rpm": [b.get("peak_speed_rpm") for b in d["bearings"]],
            "samples_kept": int(r.tau.size),
            "record_bytes": int(r.q.nbytes + r.min_film.nbytes + r.tau.nbytes)}


def source(root: Path = ROOT) -> dict:
    """The commit of ``root`` and whether its measured files or its tree differ from it."""
    def git(*args):
        return subprocess.run(["git", *args], cwd=root, capture_output=True,
                              text=True).stdout.strip()
    return {"commit": git("rev-parse", "HEAD"),
            "measured_files_dirty": bool(git("status", "--porcelain", "--", *MEASURED)),
            "tree_dirty": bool(git("status", "--porcelain", "--untracked-files=no"))}


def rhs_probe(evaluations: int = 1000, batches: int = 5) -> dict:
    """ms of CPU per rotor right-hand-side evaluation (median of ``batches``) per case, with
    whatever gfbopt is importable (the child process of :func:`rhs_evaluation`)."""
    import gfbopt
    out = {"gfbopt_path": str(Path(gfbopt.__file__).parent)}
    for case in RHS_CASES:
        system = preloaded_system() if case == "preloaded" else study_system()
        model, _ = build_model(rotor_input(system), 30_000.0, GRID, cache=SolverCache(GRID))
        z = set_station_velocities(model, equilibrium_states(model, 1),
                                   [[7e-4, 7e-4], [7e-4, 7e-4]])
        z[:, 0, -1] = 0.3                                     # τ, on the ramp
        rhs = RotorRightHandSide(model, runs(1, ramp=0.001))
        for _ in range(100):
            rhs(z)
        times = []
        for _ in range(batches):
            t0 = time.process_time()
            for _ in range(evaluations):
                rhs(z)
            times.append((time.process_time() - t0) / evaluations * 1e3)
        out[case] = statistics.median(times)
    return out


def _child(tree: Path, args: list) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    return subprocess.run([sys.executable, *args], env=env, capture_output=True, text=True,
                          check=True)


def rhs_evaluation(before: Path, repeats: int) -> dict:
    """Old (``before``) against new per-evaluation CPU, alternating child processes."""
    rows = {"before": [], "after": []}
    for _ in range(repeats):
        for label, tree in (("before", before), ("after", ROOT)):
            done = _child(tree, [__file__, "--rhs-probe"])
            rows[label].append(json.loads(done.stdout.strip().splitlines()[-1]))
    out = {"grid": str(GRID), "speed_rpm": 30_000.0, "runs": 1, "repeats": repeats,
           "evaluations_per_batch": 1000, "batches": 5, "target_ratio": 2.0,
           "before_source": source(before), "before_tree": tree_label(before),
           "after_tree": tree_label(ROOT)}
    for label, tree in (("before", before), ("after", ROOT)):   # each child ran its own tree
        assert all(Path(r["gfbopt_path"]).resolve().is_relative_to(Path(tree).resolve())
                   for r in rows[label]), (label, tree)
    for case in RHS_CASES:
        old = [r[case] for r in rows["before"]]
        new = [r[case] for r in rows["after"]]
        out[case] = {"before_ms": statistics.median(old), "after_ms": statistics.median(new),
                     "ratio": statistics.median(old) / statistics.median(new),
                     "before_ms_each": old, "after_ms_each": new}
    return out


def run_up_before(before: Path, case: str, rate: float) -> dict:
    """The old tree's own benchmark of one run-up case."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "before.json"
        _child(before, [str(before / "benchmarks/bench_rotor_transient.py"), "--skip-ratio",
                        "--case", case, "--rate", str(rate), "--out", str(out)])
        return json.loads(out.read_text())[f"run_up_{case}"]


ANSWERS = ("contact", "contact_speed_rpm", "subsync_appearance_rpm", "min_film_um",
           "peak_sync_amplitude_um", "peak_amplitude_um", "peak_speed_rpm",
           "revolutions_integrated")


def change(old: dict, new: dict) -> dict:
    """CPU and evaluation ratios (before/after) and the answers side by side."""
    return {"cpu_ratio": old["cpu_time_s"] / new["cpu_time_s"],
            "evaluations_ratio": old["evaluations"] / new["evaluations"],
            "cpu_per_evaluation_ms": [old["cpu_time_s"] / old["evaluations"] * 1e3,
                                      new["cpu_time_s"] / new["evaluations"] * 1e3],
            "answers_before_after": {k: [old.get(k), new.get(k)] for k in ANSWERS}}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--rate", type=float, default=50_000.0)
    parser.add_argument("--case", action="append", choices=CASES,
                        help="run-up case(s) (default: preloaded); repeat for several")
    parser.add_argument("--skip-ratio", action="store_true",
                        help="no per-revolution ratio (run-ups only)")
    parser.add_argument("--ratio-only", action="store_true", help="no run-up")
    parser.add_argument("--out", default=str(ROOT / "results/benchmarks/rotor_transient.json"))
    parser.add_argument("--before", type=Path, help="a checkout of the old code: old against "
                        "new per evaluation and per run-up, in one run")
    parser.add_argument("--repeats", type=int, default=5, help="A/B pairs of the RHS timing")
    parser.add_argument("--rhs-probe", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.rhs_probe:
        print(json.dumps(rhs_probe()))
        return
    out = {"machine": machine_info(load_before=load()), "source": source()}
    if args.before is not None:
        out["rhs_evaluation"] = rhs_evaluation(args.before, args.repeats)
        print(out["rhs_evaluation"], flush=True)
    if not args.skip_ratio:
        out["per_revolution"] = per_revolution()
        print(out["per_revolution"], flush=True)
    for case in [] if args.ratio_only else args.case or ["preloaded"]:
        if args.before is not None:
            out.setdefault("run_up_before", {})[case] = run_up_before(args.before, case,
                                                                      args.rate)
        out[f"run_up_{case}"] = run_up(case, args.rate)
        print(out[f"run_up_{case}"], flush=True)
        if args.before is not None:
            out.setdefault("run_up_change", {})[case] = change(out["run_up_before"][case],
                                                               out[f"run_up_{case}"])
    out["machine"]["load_after"] = load()
    write_report(out, args.out)


if __name__ == "__main__":
    main()
