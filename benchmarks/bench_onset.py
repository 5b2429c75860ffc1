"""Speed of the onset search and of warm static solves, ratios in one run.

Case: the Ruscitto et al. (1978) bearing (problems/bearings/ruscitto.toml, its [model]
table: welded end 180° from the load, axial-mean law, η = 0), 2 kg and 20 N per bearing,
speeds 5,000–50,000 rpm.

Measures (CPU time of this process and wall time; one BLAS thread)
-------------------------------------------------------------------
* onset: ``onset_speed`` after the builds (the fine grid's and, for the guided search, the
  36 × 10 guide's), median of ``--repeats``, at 72 × 20 and 144 × 36, for ``method="scan"``
  (0.2's search), ``method="secant"`` without a guide and with the 36 × 10 guide; the
  answers, their differences, evaluations and static solves by method.  The reference run
  to a 1e-11 speed tolerance is timed once and gives the differences that matter (the
  default reference stops at 1e-4).
* static: one warm solve after a 25 % and a 1 % speed step (the scan's and the secant's) at
  72 × 20 and 144 × 36 — IPOPT, the Newton fast path (:mod:`gfbopt.static.newton`: Newton
  and chord steps), and one sparse LU of the same Jacobian (SuperLU with its ordering, the
  factorisation a plain Newton step does); ratios fast path/(plain Newton steps × LU) — the
  target, with the steps a plain Newton iteration (a new LU every step) takes from the same
  start —, fast path/(its own steps × LU) and IPOPT/LU; and the same LU with the order
  SuperLU chose for the pattern kept (:mod:`gfbopt.sparse_lu`, what the fast path does).
* ipopt_options: the warm and the cold IPOPT solve under each option tried against the
  default build.

Usage::

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONPATH=. python benchmarks/bench_onset.py \\
        [--out results/benchmarks/onset_speed.json] [--repeats 3] [--grids 72x20,144x36]
        [--sections onset,static,ipopt_options]

The warm-solve ratio alone (fast path / (plain Newton steps × one LU), target ≤ 2) takes ~10 s:
``--grids 144x36 --sections static``.  The static section times the fast path without the
LU kept from the previous solve, and separately the next speed (0.01 % away) on the kept LU.

The machine's load (``uptime``) is recorded before and after: other work on a shared machine
slows everything down, so compare ratios within one run.
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import scipy.sparse.linalg as spla

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, write_report  # noqa: E402
from gfbopt import Grid, SolverCache, solve_static
from gfbopt.inputs import Rotor, load_bearing_file
from gfbopt.rotor import onset as onset_module
from gfbopt.rotor import onset_speed
from gfbopt.rotor.analysis import resolve_case
from gfbopt.sparse_lu import Factoriser
from gfbopt.static import StaticSolver, newton

REPO = Path(__file__).resolve().parents[1]
BEARING, OPTIONS = load_bearing_file(REPO / "problems" / "bearings" / "ruscitto.toml")
ROTOR, LOAD, RANGE = Rotor(2.0), 20.0, (5000.0, 50000.0)
TARGETS = {"onset_144x36_secant_s": 1.2, "speedup_144x36": 3.0, "newton_per_step_over_lu": 2.0}
#: IPOPT options tried on the warm solve (CasADi nlpsol keys) against the default build
IPOPT_VARIANTS = {
    "default": {},
    "mumps_scaling=0 (no MUMPS scaling)": {"ipopt.mumps_scaling": 0},
    "mumps_permuting_scaling=0": {"ipopt.mumps_permuting_scaling": 0},
    "mumps_pivot_order=7 (MUMPS's automatic choice, the default before AMD)":
        {"ipopt.mumps_pivot_order": 7},
    "mumps_pivot_order=2 (AMF)": {"ipopt.mumps_pivot_order": 2},
    "hessian_constant=yes": {"ipopt.hessian_constant": "yes"},
    "warm_start_init_point=yes": {"ipopt.warm_start_init_point": "yes"},
    "linear_system_scaling=none": {"ipopt.linear_system_scaling": "none"},
    "mu_strategy=adaptive": {"ipopt.mu_strategy": "adaptive"},
}


def uptime() -> str:
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        return f"load average {os.getloadavg()}"


def timed(function, repeats: int) -> dict:
    """Median wall and CPU time [s] of ``repeats`` calls, and the last result."""
    walls, cpus, result = [], [], None
    for _ in range(repeats):
        w, c = time.perf_counter(), time.process_time()
        result = function()
        walls.append(time.perf_counter() - w)
        cpus.append(time.process_time() - c)
    return {"wall_s": statistics.median(walls), "cpu_s": statistics.median(cpus),
            "walls_s": walls, "cpus_s": cpus, "result": result}


def onset_summary(o) -> dict:
    solvers = [r["static_solver"] for r in o.scan + o.coarse_scan]
    return {"onset_speed_rpm": o.onset_speed_rpm, "whirl_ratio": o.whirl_ratio,
            "evaluations": o.evaluations, "coarse_evaluations": len(o.coarse_scan),
            "full_thresholds": sum(r["threshold"] == "full" for r in o.scan),
            "local_thresholds": sum(r["threshold"] == "local" for r in o.scan),
            "newton_statics": solvers.count("newton"), "ipopt_statics": solvers.count("ipopt"),
            "coarse_grid": o.coarse_grid}


def bench_onset(grid: Grid, repeats: int) -> dict:
    cache = SolverCache(grid)
    case = resolve_case(BEARING, ROTOR, LOAD, options=OPTIONS, grid=grid, cache=cache)
    t0 = time.perf_counter()
    cache(case.model(RANGE[0]), grid)
    build_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    cache(case.model(RANGE[0]), onset_module.COARSE_GRID)
    guide_build_s = time.perf_counter() - t0
    common = dict(options=OPTIONS, grid=grid, cache=cache)
    runs = {"scan": dict(method="scan"), "secant": dict(method="secant", coarse_grid=None),
            "secant_guided": dict(method="secant", coarse_grid="36x10")}
    out = {"grid": str(grid), "build_s": build_s, "guide_build_s": guide_build_s}
    for name, kwargs in runs.items():
        t = timed(lambda kw=kwargs: onset_speed(BEARING, ROTOR, LOAD, RANGE, **common, **kw),
                  repeats)
        out[name] = {**{k: v for k, v in t.items() if k != "result"},
                     **onset_summary(t["result"])}
    saved = onset_module.SPEED_TOLERANCE
    onset_module.SPEED_TOLERANCE = 1e-11
    try:
        t = timed(lambda: onset_speed(BEARING, ROTOR, LOAD, RANGE, method="scan", **common), 1)
    finally:
        onset_module.SPEED_TOLERANCE = saved
    out["scan_tight"] = {**{k: v for k, v in t.items() if k != "result"},
                         **onset_summary(t["result"])}
    ref = out["scan_tight"]["onset_speed_rpm"]
    for name in runs:
        out[name]["rel_diff_vs_scan_tight"] = out[name]["onset_speed_rpm"] / ref - 1
    out["rel_diff_scan_default_vs_tight"] = out["scan"]["onset_speed_rpm"] / ref - 1
    for name in ("secant", "secant_guided"):
        out[f"speedup_{name}_cpu"] = out["scan"]["cpu_s"] / out[name]["cpu_s"]
        out[f"speedup_{name}_wall"] = out["scan"]["wall_s"] / out[name]["wall_s"]
    return out


def bench_static(grid: Grid, repeats: int) -> dict:
    cache = SolverCache(grid)
    case = resolve_case(BEARING, ROTOR, LOAD, options=OPTIONS, grid=grid, cache=cache)
    base = 13000.0
    solver = cache(case.model(base), grid)
    start = solve_static(case.model(base), load=case.load, solver=solver)
    system = solver.newton_system()
    rows = []
    for step in (1.25, 1.01):
        model = case.model(base * step)
        p = solver.parameters(model, True, case.load)
        ipopt = timed(lambda: solve_static(model, load=case.load, solver=solver,
                                           initial=start), repeats)

        def fresh_fast():                  # without the LU kept from the previous solve
            system.forget()
            return solve_static(model, load=case.load, solver=solver, initial=start,
                                fast_path=True)
        fast = timed(fresh_fast, repeats)
        raw = timed(lambda: newton.solve(system, start.state, p, reuse=False), repeats)
        # a neighbouring speed of a search (0.01 % away): the LU of the last solve is kept
        near = case.model(base * step * 1.0001)
        solve_static(model, load=case.load, solver=solver, initial=start, fast_path=True)
        p_near = solver.parameters(near, True, case.load)
        reused = timed(lambda: newton.solve(system, fast["result"].state, p_near), repeats)
        _, jac = system.residual_and_jacobian(start.state, p)
        lu = timed(lambda: spla.splu(jac, permc_spec="MMD_AT_PLUS_A"), repeats * 3)
        kept_order = Factoriser()
        kept_order(jac)                    # the pattern's first LU computes its order
        lu_kept = timed(lambda: kept_order(jac), repeats * 3)
        outcome = raw["result"]
        plain = plain_newton_steps(system, start.state, p)
        a, b = ipopt["result"], fast["result"]
        rows.append({
            "speed_step": step, "n_unknowns": int(jac.shape[0]), "jacobian_nnz": int(jac.nnz),
            "ipopt_cpu_s": ipopt["cpu_s"], "ipopt_wall_s": ipopt["wall_s"],
            "ipopt_iterations": a.iterations,
            "fast_path_cpu_s": fast["cpu_s"], "fast_path_wall_s": fast["wall_s"],
            "fast_path_solver": b.solver, "newton_only_cpu_s": raw["cpu_s"],
            "newton_steps": outcome.steps, "newton_factorisations": outcome.factorisations,
            "one_lu_cpu_s": lu["cpu_s"], "one_lu_wall_s": lu["wall_s"],
            "one_lu_kept_order_cpu_s": lu_kept["cpu_s"],
            "kept_order_over_one_lu": lu_kept["cpu_s"] / lu["cpu_s"],
            "kept_lu_next_speed_cpu_s": reused["cpu_s"],
            "kept_lu_next_speed_steps": reused["result"].steps,
            "kept_lu_next_speed_factorisations": reused["result"].factorisations,
            "plain_newton_steps": plain,
            "fast_path_over_steps_lu": fast["cpu_s"] / (outcome.steps * lu["cpu_s"]),
            "fast_path_over_plain_newton_lus": fast["cpu_s"] / (plain * lu["cpu_s"]),
            "ipopt_over_iterations_lu": ipopt["cpu_s"] / (max(a.iterations, 1) * lu["cpu_s"]),
            "ipopt_over_fast_path": ipopt["cpu_s"] / fast["cpu_s"],
            "state_max_diff": float(np.abs(a.state - b.state).max())})
    return {"grid": str(grid), "warm_solves": rows}


def plain_newton_steps(system, x0: np.ndarray, p: np.ndarray) -> int:
    """Steps a plain Newton iteration (a new LU every step) takes from ``x0`` to the fast
    path's tolerance: what "one sparse LU per Newton step" means for this solve."""
    x, steps = np.array(x0, dtype=float), 0
    g = system.residual(x, p)
    while np.abs(g).max() > newton.RESIDUAL_TOLERANCE and steps < 20:
        g, jac = system.residual_and_jacobian(x, p)
        x += spla.splu(jac, permc_spec="MMD_AT_PLUS_A").solve(-g)
        g = system.residual(x, p)
        steps += 1
    return steps


def bench_ipopt_options(grid: Grid, repeats: int) -> dict:
    case = resolve_case(BEARING, ROTOR, LOAD, options=OPTIONS, grid=grid,
                        cache=SolverCache(grid))
    m0, m1 = case.model(13000.0), case.model(16250.0)
    out, reference = {}, None
    for name, options in IPOPT_VARIANTS.items():
        solver = StaticSolver(grid, film=m0.film, foil_law="simple", ipopt_options=options)
        start = solve_static(m0, load=case.load, solver=solver)
        t = timed(lambda s=solver, st=start: solve_static(m1, load=case.load, solver=s,
                                                         initial=st), repeats)
        cold = timed(lambda s=solver: solve_static(m1, load=case.load, solver=s), repeats)
        sol = t["result"]
        reference = sol if reference is None else reference
        out[name] = {"cpu_s": t["cpu_s"], "wall_s": t["wall_s"], "iterations": sol.iterations,
                     "success": sol.success, "cold_cpu_s": cold["cpu_s"],
                     "cold_iterations": cold["result"].iterations,
                     "state_max_diff_vs_default": float(np.abs(sol.state
                                                               - reference.state).max())}
    base, cold_base = out["default"]["cpu_s"], out["default"]["cold_cpu_s"]
    for row in out.values():
        row["cpu_over_default"] = row["cpu_s"] / base
        row["cold_cpu_over_default"] = row["cold_cpu_s"] / cold_base
    return {"grid": str(grid), "from_rpm": 13000.0, "to_rpm": 16250.0, "variants": out}


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=str(REPO / "results" / "benchmarks" /
                                             "onset_speed.json"))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--grids", default="72x20,144x36")
    parser.add_argument("--sections", default="onset,static,ipopt_options",
                        help="comma-separated: onset, static, ipopt_options")
    args = parser.parse_args(argv)
    grids = [Grid.parse(g) for g in args.grids.split(",")]
    sections = set(args.sections.split(","))
    before = uptime()
    print(f"  load before: {before}", flush=True)
    out = {"machine": machine_info(uptime_before=before),
           "case": {"bearing": BEARING.name, "rotor_mass_kg": ROTOR.mass_kg,
                    "load_newton": LOAD, "speed_range_rpm": RANGE,
                    "conventions": OPTIONS.to_dict()},
           "onset": [bench_onset(g, args.repeats) for g in grids] if "onset" in sections
           else [],
           "static": [bench_static(g, args.repeats) for g in grids] if "static" in sections
           else [],
           "ipopt_options": (bench_ipopt_options(grids[-1], args.repeats)
                             if "ipopt_options" in sections else {"variants": {}})}
    out["machine"]["uptime_after"] = uptime()
    measured = {}
    if out["onset"]:
        fine = out["onset"][-1]
        measured.update({"onset_144x36_secant_s": fine["secant_guided"]["cpu_s"],
                         "speedup_144x36": fine["speedup_secant_guided_cpu"]})
    if out["static"]:
        measured["newton_per_step_over_lu"] = max(
            r["fast_path_over_plain_newton_lus"] for r in out["static"][-1]["warm_solves"])
    out["targets"] = {k: {"measured": measured[k], "target": v,
                          "met": measured[k] <= v if k != "speedup_144x36" else
                          measured[k] >= v} for k, v in TARGETS.items() if k in measured}
    print(f"gfbopt onset/static benchmark — {out['machine']['date']}")
    print(f"  before: {before}\n  after:  {out['machine']['uptime_after']}")
    for o in out["onset"]:
        print(f"  onset {o['grid']} (build {o['build_s']:.2f} s, guide build "
              f"{o['guide_build_s']:.2f} s):")
        for name in ("scan", "secant", "secant_guided", "scan_tight"):
            r = o[name]
            print(f"    {name:<14s} cpu {r['cpu_s']:6.2f} s wall {r['wall_s']:6.2f} s  "
                  f"onset {r['onset_speed_rpm']:.6f} rpm  fine {r['evaluations']} "
                  f"({r['full_thresholds']} full, {r['local_thresholds']} local), coarse "
                  f"{r['coarse_evaluations']}, statics newton/ipopt {r['newton_statics']}/"
                  f"{r['ipopt_statics']}")
        print(f"    speed-up (cpu): secant {o['speedup_secant_cpu']:.2f}×, guided "
              f"{o['speedup_secant_guided_cpu']:.2f}×; |new/tight − 1| "
              f"{abs(o['secant']['rel_diff_vs_scan_tight']):.1e} / "
              f"{abs(o['secant_guided']['rel_diff_vs_scan_tight']):.1e}; default scan vs "
              f"tight {o['rel_diff_scan_default_vs_tight']:.1e}")
    for s in out["static"]:
        for r in s["warm_solves"]:
            print(f"  static {s['grid']} step ×{r['speed_step']}: IPOPT {r['ipopt_cpu_s']:.4f} s"
                  f" ({r['ipopt_iterations']} it), fast path {r['fast_path_cpu_s']:.4f} s "
                  f"({r['newton_steps']} steps, {r['newton_factorisations']} LUs), one LU "
                  f"{r['one_lu_cpu_s']:.4f} s ({r['one_lu_kept_order_cpu_s']:.4f} s with the "
                  f"pattern's kept order); plain Newton {r['plain_newton_steps']} steps,"
                  f" fast/(plain steps·LU) {r['fast_path_over_plain_newton_lus']:.2f}, "
                  f"fast/(steps·LU) {r['fast_path_over_steps_lu']:.2f}, IPOPT/(it·LU) "
                  f"{r['ipopt_over_iterations_lu']:.2f}, IPOPT/fast {r['ipopt_over_fast_path']:.2f};"
                  f" Δstate {r['state_max_diff']:.1e}; next speed on the kept LU "
                  f"{r['kept_lu_next_speed_cpu_s']:.4f} s ({r['kept_lu_next_speed_steps']} "
                  f"steps, {r['kept_lu_next_speed_factorisations']} LUs)")
    if out["ipopt_options"]["variants"]:
        print(f"  IPOPT options at {out['ipopt_options']['grid']} (warm 13,000 → 16,250 rpm; "
              "cold at 16,250 rpm):")
    for name, r in out["ipopt_options"]["variants"].items():
        print(f"    {name:<46s} warm {r['cpu_s']:.4f} s ({r['cpu_over_default']:.2f}× default),"
              f" {r['iterations']} it; cold {r['cold_cpu_s']:.4f} s "
              f"({r['cold_cpu_over_default']:.2f}×), {r['cold_iterations']} it; "
              f"Δstate {r['state_max_diff_vs_default']:.1e}")
    for name, t in out["targets"].items():
        print(f"  {name:<26s} {t['measured']:7.3f}  target {t['target']:g}  "
              f"{'met' if t['met'] else 'NOT met'}")
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
