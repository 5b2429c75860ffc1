"""The design main job with the clearance at speed against without: ``gfbopt run
problems/rotor_bearing_design.toml --workers 2 --rotor R`` with R = problems/rotors/blower.toml
(isothermal, cold clearance) and R = problems/rotors/blower_thermal.toml (the same rotor, the
same bearing's [bearing] and [model], plus its [journal] and [thermal] tables: centrifugal
growth and the lumped heat balance, each bearing at its own running clearance and μ(T) at
each speed).  Target: with heat ≤ 1.5× the CPU time without.

Both sides go through the same ``--rotor`` route (gfbopt.studies.user_rotor), so the only
difference is the two tables.  Each run is a fresh process (``--child``) running the real
command line in-process (``gfbopt.cli.main``); the parent records the CPU time of the child
and its workers (``resource.getrusage(RUSAGE_CHILDREN)``, user + system), the wall time and
the load average before and after.  Runs are interleaved A, B, A, B, ...  The optimiser's own
record (designs evaluated, convergence, evaluation seconds) is kept so that a difference in
the number of designs the search asks is seen apart from the cost of one design.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python benchmarks/bench_main_job_heat.py \\
        [--pairs 2] [--workers 2] [--out results/benchmarks/main_job_heat.json]

Where the extra time goes: one run of each at ``--workers 1`` (every evaluation in the child
process) under cProfile, then the functions whose cumulative CPU differs most::

    python benchmarks/bench_main_job_heat.py --child --workers 1 --results DIR \
        --rotor-file problems/rotors/blower.toml --profile iso.pstats     (and blower_thermal)
    python benchmarks/bench_main_job_heat.py --compare-profiles iso.pstats heated.pstats \
        [--out results/benchmarks/main_job_heat.json]     (adds "profile" to the JSON)
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from machine import machine_info, tree_label, write_report  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
STUDY = ROOT / "problems" / "rotor_bearing_design.toml"
ROTORS = {"isothermal": ROOT / "problems" / "rotors" / "blower.toml",
          "heated": ROOT / "problems" / "rotors" / "blower_thermal.toml"}
TARGET_RATIO = 1.5


def _child(workers: int, results: str, rotor: str, profile: str = "") -> None:
    """Run the main job here on ``rotor``; print one JSON line with the optimiser's record."""
    import gfbopt.design.optimiser as optimiser
    from gfbopt.cli import main as cli

    captured: dict = {}
    optimise = optimiser.optimise

    def recorded(*args, **kwargs):
        result = optimise(*args, **kwargs)
        captured["result"] = result
        return result

    optimiser.optimise = recorded
    argv = ["run", str(STUDY), "--workers", str(workers), "--results", results,
            "--rotor", rotor]
    if profile:
        import cProfile

        prof = cProfile.Profile()
        code = prof.runcall(cli, argv)
        prof.dump_stats(profile)
    else:
        code = cli(argv)
    r = captured.get("result")
    search = {}
    if r is not None:
        search = {"convergence": r.convergence, "designs_per_stage": dict(r.stages),
                  "evaluation_s_per_stage": dict(r.stage_time_s), "evaluated": r.evaluated,
                  "reused": r.reused, "repeated": r.repeated,
                  "evaluation_s_mean": r.evaluation_time_s / max(r.evaluated, 1)}
    summary = {}
    for path in Path(results).glob("*/summary.json"):
        s = json.loads(path.read_text())
        summary = {k: s.get(k) for k in ("verdict", "stable_to_top_speed",
                                          "best_first_onset_rpm", "chosen_design")}
    print("BENCH " + json.dumps({"exit_status": code, "search": search, "summary": summary},
                                default=str), flush=True)


def cpu_per_design_ratios(runs) -> list:
    """Per pair, (CPU / designs evaluated) heated over isothermal: the ratio with the search's
    different number of designs taken out (the stages after the search still included)."""
    return [(b["cpu_s"] / b["search"]["evaluated"]) / (a["cpu_s"] / a["search"]["evaluated"])
            for a, b in zip(runs[0::2], runs[1::2])
            if a.get("search", {}).get("evaluated") and b.get("search", {}).get("evaluated")]


def compare_profiles(iso_path: str, heated_path: str, top: int = 25) -> dict:
    """The functions (file:line(function)) whose cumulative time [s] differs most between
    the isothermal and the heated profile, and the totals (cProfile's default clock, the
    wall time of the child process: on a loaded machine, shares rather than CPU seconds)."""
    import pstats

    def table(path):
        st = pstats.Stats(path)
        rows = {}
        for (file, line, func), (_, ncalls, tottime, cumtime, _) in st.stats.items():
            short = "/".join(Path(file).parts[-3:]) if file.startswith("/") else file
            rows[f"{short}:{line}({func})"] = (ncalls, tottime, cumtime)
        return rows, st.total_tt

    iso, iso_total = table(iso_path)
    heated, heated_total = table(heated_path)
    names = set(iso) | set(heated)

    def delta(key, k):
        return heated.get(key, (0, 0.0, 0.0))[k] - iso.get(key, (0, 0.0, 0.0))[k]

    def row(key):
        a, b = iso.get(key, (0, 0.0, 0.0)), heated.get(key, (0, 0.0, 0.0))
        return {"function": key, "calls_isothermal": a[0], "calls_heated": b[0],
                "cumulative_s_isothermal": a[2], "cumulative_s_heated": b[2],
                "self_s_isothermal": a[1], "self_s_heated": b[1]}
    by_cum = sorted(names, key=lambda k: -delta(k, 2))[:top]
    by_self = sorted(names, key=lambda k: -delta(k, 1))[:top]
    return {"total_s_isothermal": iso_total, "total_s_heated": heated_total,
            "largest_cumulative_increase": [row(k) for k in by_cum],
            "largest_self_increase": [row(k) for k in by_self]}


def _run(label: str, workers: int) -> dict:
    env = {**os.environ, "PYTHONPATH": str(ROOT), "GFBOPT_PROGRESS": "0"}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    load = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        out = subprocess.run([sys.executable, __file__, "--child", "--workers", str(workers),
                              "--results", tmp, "--rotor-file", str(ROTORS[label])],
                             env=env, capture_output=True, text=True, check=False)
        wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    lines = [x for x in out.stdout.splitlines() if x.startswith("BENCH ")]
    row = json.loads(lines[-1][6:]) if lines else {"error": out.stderr[-2000:]}
    row.update(model=label, rotor=str(ROTORS[label].relative_to(ROOT)), workers=workers,
               wall_s=wall, cpu_s=cpu, load_before=load, load_after=os.getloadavg())
    s = row.get("search", {})
    print(f"{label:10s}: cpu {cpu:6.1f} s, wall {wall:6.1f} s, load {load[0]:.2f} -> "
          f"{row['load_after'][0]:.2f}; evaluated {s.get('evaluated')}, "
          f"{s.get('convergence')}", flush=True)
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pairs", type=int, default=2)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", default=str(ROOT / "results/benchmarks/main_job_heat.json"))
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--results", default=None, help=argparse.SUPPRESS)
    parser.add_argument("--rotor-file", default=None, help=argparse.SUPPRESS)
    parser.add_argument("--profile", default="", help="child only: cProfile stats file")
    parser.add_argument("--compare-profiles", nargs=2, metavar=("ISO", "HEATED"),
                        default=None, help="add the profiles' comparison to --out")
    args = parser.parse_args()
    if args.compare_profiles:
        out = json.loads(Path(args.out).read_text()) if Path(args.out).is_file() else {}
        out["profile"] = {"what": "one run of each at --workers 1 under cProfile "
                          "(evaluations in the child process), same code as the pairs",
                          **compare_profiles(*args.compare_profiles)}
        write_report(out, args.out)
        return
    if args.child:
        _child(args.workers, args.results, args.rotor_file, args.profile)
        return
    load_start = os.getloadavg()
    runs = []
    for _ in range(args.pairs):
        runs.append(_run("isothermal", args.workers))
        runs.append(_run("heated", args.workers))
    load_end = os.getloadavg()
    pairs = [(a["cpu_s"], b["cpu_s"]) for a, b in zip(runs[0::2], runs[1::2])]
    ratios = [b / a for a, b in pairs]
    per_eval = cpu_per_design_ratios(runs)
    out = machine_info(
        benchmark="main_job_heat", code=tree_label(ROOT), study=str(STUDY.relative_to(ROOT)),
        command=(f"gfbopt run {STUDY.relative_to(ROOT)} --workers {args.workers} --rotor "
                 "problems/rotors/{blower,blower_thermal}.toml"),
        what="CPU s (user + system) of the whole job, child and its workers; A/B interleaved",
        pairs_cpu_s=pairs, ratios=ratios, ratio_mean=sum(ratios) / len(ratios),
        cpu_per_design_ratios=per_eval, target_ratio=TARGET_RATIO,
        target_met=max(ratios) <= TARGET_RATIO, runs=runs, load_average_start=load_start,
        load_average_end=load_end)
    print(f"ratios {', '.join(f'{r:.3f}' for r in ratios)} (target {TARGET_RATIO}); "
          f"per-design CPU ratios {', '.join(f'{r:.3f}' for r in per_eval)}")
    write_report(out, args.out)


if __name__ == "__main__":
    main()
