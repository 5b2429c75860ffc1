"""Speed of gfbopt's static equilibrium (CasADi/IPOPT): build, solve, CLI, in one run.

Measures
--------
* build formulations, at 72 × 20 and 144 × 36: the current build (θ-strip Reynolds mapped in
  MX, Jacobian by the chain rule, :mod:`gfbopt.static.model`), median of 3, wall and CPU
  time [s], split into the symbolic problem and the rest (functions + ``nlpsol``); and the
  flat-SX reference formulation (the residual expanded to one SX graph, CasADi's AD Jacobian
  and its default derivative functions: what gfbopt ≤ 0.2 built), once per grid; ratio;
* serialisation: the built ``nlpsol`` saved with ``Function.save`` and loaded with
  ``casadi.Function.load`` (what a disk cache of the build would do): load time against the
  build time, file size, and the loaded solver's solution against the built one's;
* build: time to construct :class:`gfbopt.StaticSolver` at 72 × 20 (rigid/simple foundation,
  and the beam top foil), median of 3 [s];
* solve: one equilibrium at a given (Λ, ε), rigid periodic film, L/D = 1 — cold
  (``solve_static`` without ``initial``) and warm (``initial=`` the solution at ε − 0.01),
  median of 10 each [s];
* the hand-written sparse Newton (tests/verification/newton_reference.py, the test oracle) on
  the same point, cold, median of 10 [s], and the ratios IPOPT/Newton;
* cold solves at a few low-Λ points where gfbopt's cold start is known to be hard;
* the whole of thesis Tables 3.1 and 3.2, *including* the one solver build they need (both
  tables are one formulation: periodic film, rigid/simple foundation, axial-mean law; Λ, S,
  L/D and the sub-ambient switch are CasADi parameters), solved cold row by row, and again
  with each row warm-started from the previous ε of the same (Λ, S) group;
* the command line end to end at the default grid 144 × 36: ``gfbopt static`` and
  ``gfbopt linear`` (ε = 0.5, Λ = 1, ``--json``), each called twice in fresh processes, wall
  and CPU time [s] (the machine's load average is recorded: on a shared machine wall time
  includes waiting for a core, CPU time does not).

Table 3.1: rigid, periodic, full film.  Table 3.2: ``BearingModel(bearing_number=1,
compliance=S, foil='simple' if S > 0 else 'rigid', subambient='gumbel')``.

Usage::

    PYTHONPATH=. python benchmarks/bench_static.py [--out results/benchmarks/static_speed.json]
        [--sections formulations,serialisation,build,points,tables,cli]

Prints a table and writes a JSON file with the machine, date and library versions.
Targets: build ≤ 1 s at 72 × 20; solve ≤ 0.1 s warm, ≤ 0.3 s cold and no slower than the
Newton reference; Tables 3.1 + 3.2 ≤ 5 s including the build; at the default grid
``gfbopt static`` ≤ 2 s and ``gfbopt linear`` ≤ 4 s end to end on the second call.
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import casadi as ca
import numpy as np


sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info as _machine_info, write_report  # noqa: E402
from gfbopt import DEFAULT_GRID, BearingModel, Grid, StaticSolver, solve_static  # noqa: E402
from gfbopt.static import PARAMETERS, default_ipopt_options  # noqa: E402
from gfbopt.static.model import build_problem  # noqa: E402
from gfbopt.inputs.bearing_file import read_toml  # noqa: E402

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
GRID = Grid(72, 20)
FORMULATION_GRIDS = (Grid(72, 20), DEFAULT_GRID)
SECTIONS = ("formulations", "serialisation", "build", "points", "tables", "cli")
TARGETS = {"build_s": 1.0, "solve_warm_s": 0.1, "solve_cold_s": 0.3, "tables_total_s": 5.0,
           "cli_static_s": 2.0, "cli_linear_s": 4.0}
#: the CLI calls timed end to end (default grid): ε = 0.5, Λ = 1, simple foundation S = 0
CLI_POINT = ["--eccentricity", "0.5", "--bearing-number", "1", "--json"]


def _load_newton_reference():
    spec = importlib.util.spec_from_file_location("newton_reference",
                                                  REPO / "tests" / "verification" / "newton_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


newton_reference = _load_newton_reference()


# ------------------------------------------------------------------------ helpers
def timed_cpu(function, repeats: int) -> dict:
    """Run ``function()`` ``repeats`` times: median wall and CPU time [s], all wall times, and
    the last result (key ``result``)."""
    wall, cpu = [], []
    result = None
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        result = function()
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return {"median_s": statistics.median(wall), "cpu_median_s": statistics.median(cpu),
            "times_s": wall, "result": result}


def timed(function, repeats: int) -> tuple[float, list[float], object]:
    """Run ``function()`` ``repeats`` times; return (median wall time [s], all times, last result)."""
    times = []
    result = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), times, result


def machine_info() -> dict:
    return _machine_info(grid=str(GRID))


# ------------------------------------------------------------ build formulations
def _flat_reference_build(solver: StaticSolver) -> ca.Function:
    """The flat-SX formulation of the same equations: the residual expanded into one SX
    graph, and an ``nlpsol`` left to derive its own Jacobian (and gradient of the
    Lagrangian) by AD of that graph, with the same empty Hessian: gfbopt ≤ 0.2's build."""
    flat = solver.residual_function.expand()
    x = ca.SX.sym("x", solver.layout.size)
    p = ca.SX.sym("p", len(PARAMETERS))
    g = flat(x, p)
    opts = default_ipopt_options()
    for key in ("no_nlp_grad", "calc_lam_p"):
        opts.pop(key)
    lam_f, lam_g = ca.SX.sym("lam_f"), ca.SX.sym("lam_g", g.shape[0])
    opts["hess_lag"] = ca.Function("zero_hessian", [x, p, lam_f, lam_g],
                                   [ca.SX(ca.Sparsity(x.shape[0], x.shape[0]))],
                                   ["x", "p", "lam_f", "lam_g"], ["triu_hess_gamma_x_x"])
    return ca.nlpsol("flat_reference", "ipopt", {"x": x, "p": p, "f": 0, "g": g}, opts)


def bench_formulations(grids=FORMULATION_GRIDS, repeats: int = 3) -> list[dict]:
    """Current build (median of ``repeats``; symbolic problem vs the rest) against the flat-SX
    reference build (once) at each grid, and the two Jacobians compared at one state."""
    StaticSolver(Grid(12, 4))            # load the IPOPT plugin once, outside the timings
    out = []
    for grid in grids:
        build = timed_cpu(lambda grid=grid: StaticSolver(grid), repeats)
        solver = build.pop("result")
        problem = timed_cpu(lambda s=solver: build_problem(s.stencil, s.law, s.law_data),
                            repeats)
        problem.pop("result")
        reference = timed_cpu(lambda s=solver: _flat_reference_build(s), 1)
        flat = reference.pop("result")
        model = BearingModel(bearing_number=1.0, compliance=0.5)
        sol = solve_static(model, eccentricity=0.6, solver=solver)
        p = solver.parameters(model, False, 0.6)
        _, jac = solver.jacobian_function()(sol.state, p)
        _, jac_flat = flat.get_function("nlp_jac_g")(sol.state, p)
        diff = np.abs(np.asarray(jac.nonzeros()) - np.asarray(jac_flat.nonzeros())).max()
        out.append({
            "grid": str(grid), "n_unknowns": solver.layout.size,
            "build": build, "symbolic_problem": problem,
            "flat_reference_build": reference,
            "ratio_flat_over_build": reference["median_s"] / build["median_s"],
            "jacobian_same_sparsity": jac.sparsity() == jac_flat.sparsity(),
            "jacobian_max_rel_diff": float(diff / np.abs(jac_flat.nonzeros()).max()),
            "flat_reference_jacobian_instructions":
                flat.get_function("nlp_jac_g").n_instructions(),
        })
    return out


def bench_serialisation(grids=FORMULATION_GRIDS, repeats: int = 3) -> list[dict]:
    """Would a disk cache of the build pay?  Save the built nlpsol, load it back (CasADi's
    own serialisation, IPOPT plugin, custom Jacobian and Hessian), and compare the load time
    with the build time; the loaded solver must solve to the same state."""
    out = []
    model = BearingModel(bearing_number=1.0, compliance=0.5)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "static_nlpsol.casadi")
        for grid in grids:
            build = timed_cpu(lambda grid=grid: StaticSolver(grid), repeats)
            solver = build.pop("result")
            save = timed_cpu(lambda s=solver: s._nlp.save(path), 1)
            save.pop("result")
            load = timed_cpu(lambda: ca.Function.load(path), repeats)
            loaded = load.pop("result")
            built_sol = solve_static(model, eccentricity=0.6, solver=solver)
            solver._nlp = loaded
            loaded_sol = solve_static(model, eccentricity=0.6, solver=solver)
            out.append({
                "grid": str(grid), "build": build, "save": save, "load": load,
                "file_mb": os.path.getsize(path) / 1e6,
                "ratio_load_over_build_wall": load["median_s"] / build["median_s"],
                "ratio_load_over_build_cpu": load["cpu_median_s"] / build["cpu_median_s"],
                "loaded_state_max_diff": float(np.abs(loaded_sol.state
                                                      - built_sol.state).max()),
            })
    return out


# ------------------------------------------------------------------ command line
def _run_cli(command: str) -> dict:
    """One ``gfbopt COMMAND`` at the default grid in a fresh process: wall and CPU [s]."""
    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    load = os.getloadavg()[0]
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "gfbopt", command, *CLI_POINT], env=env,
                          capture_output=True, text=True, check=False)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    row = {"command": command, "wall_s": wall, "cpu_s": cpu, "load_average_1min": load,
           "returncode": proc.returncode}
    if proc.returncode == 0:
        data = json.loads(proc.stdout)
        row.update({k: data[k] for k in ("success", "solve_time_s", "wall_time_s",
                                         "critical_mass") if k in data})
    else:
        row["stderr"] = proc.stderr[-2000:]
    return row


def bench_cli(calls: int = 2) -> dict:
    """``gfbopt static`` and ``gfbopt linear`` at the default grid, ``calls`` times each."""
    return {command: [_run_cli(command) for _ in range(calls)]
            for command in ("static", "linear")}


# ------------------------------------------------------------ 72 × 20 benchmarks
def bench_build(repeats: int = 3) -> dict:
    """Median time to build the StaticSolver, foundation and beam formulations [s]."""
    out = {}
    for name, beam in (("foundation", False), ("beam", True)):
        law = "beam" if beam else "simple"
        median, times, solver = timed(
            lambda law=law: StaticSolver(GRID, film="periodic", foil_law=law), repeats)
        out[name] = {"median_s": median, "times_s": times,
                     "n_variables": solver.layout.size, "n_equations": solver.n_equations}
    return out


def bench_point(solver: StaticSolver, bearing_number: float, eccentricity: float,
                repeats: int = 10) -> dict:
    """Cold and warm IPOPT solves and the cold Newton reference at one rigid point."""
    model = BearingModel(bearing_number=bearing_number, foil="rigid", length_ratio=1.0)
    cold, cold_times, sol = timed(
        lambda: solve_static(model, eccentricity=eccentricity, solver=solver), repeats)
    nearby = solve_static(model, eccentricity=eccentricity - 0.01, solver=solver)
    warm, warm_times, warm_sol = timed(
        lambda: solve_static(model, eccentricity=eccentricity, solver=solver, initial=nearby),
        repeats)
    newton, newton_times, ref = timed(
        lambda: newton_reference.solve_rigid_newton(bearing_number, eccentricity, 1.0, GRID),
        repeats)
    return {
        "bearing_number": bearing_number, "eccentricity": eccentricity, "length_ratio": 1.0,
        "ipopt_cold_s": cold, "ipopt_cold_times_s": cold_times,
        "ipopt_cold_iterations": sol.iterations, "ipopt_cold_success": sol.success,
        "ipopt_warm_s": warm, "ipopt_warm_times_s": warm_times,
        "ipopt_warm_iterations": warm_sol.iterations, "ipopt_warm_success": warm_sol.success,
        "newton_cold_s": newton, "newton_cold_times_s": newton_times,
        "newton_iterations": ref["iterations"], "newton_residual": ref["residual"],
        "ratio_cold_ipopt_over_newton": cold / newton,
        "ratio_warm_ipopt_over_newton": warm / newton,
        "load_ipopt": sol.load, "load_newton": ref["load"],
        "load_rel_diff": abs(sol.load / ref["load"] - 1),
        "attitude_deg_ipopt": sol.attitude_angle_deg,
        "attitude_deg_newton": ref["attitude_angle_deg"],
        "attitude_diff_deg": abs(sol.attitude_angle_deg - ref["attitude_angle_deg"]),
    }


def bench_hard_cold(solver: StaticSolver, points, repeats: int = 3) -> list[dict]:
    """Cold IPOPT solves (with gfbopt's default continuation fallback) at low-Λ points."""
    out = []
    for lam, ecc in points:
        model = BearingModel(bearing_number=lam, foil="rigid", length_ratio=1.0)
        first = solve_static(model, eccentricity=ecc, solver=solver, continuation=False)
        median, times, sol = timed(
            lambda m=model, e=ecc: solve_static(m, eccentricity=e, solver=solver), repeats)
        newton, _, ref = timed(
            lambda lam=lam, e=ecc: newton_reference.solve_rigid_newton(lam, e, 1.0, GRID),
            repeats)
        out.append({"bearing_number": lam, "eccentricity": ecc,
                    "first_attempt_status": first.status,
                    "first_attempt_iterations": first.iterations,
                    "ipopt_cold_s": median, "ipopt_cold_times_s": times,
                    "ipopt_iterations_total": sol.iterations, "success": sol.success,
                    "newton_cold_s": newton, "newton_iterations": ref["iterations"],
                    "load_rel_diff": abs(sol.load / ref["load"] - 1)})
    return out


def table_models(problems_dir: Path) -> list[tuple[str, dict, BearingModel]]:
    """(table, reference row, model) for every row of thesis Tables 3.1 and 3.2, read from
    the shipped study files (problems/thesis_table_3_1.toml, thesis_table_3_2.toml: L/D = 1;
    Table 3.1 against Yang et al., Table 3.2 under the Gümbel force against Peng & Carpino)."""
    rows = []
    for table, name, reference in (("3.1", "thesis_table_3_1", "yang"),
                                   ("3.2", "thesis_table_3_2", "peng_carpino")):
        spec = read_toml(problems_dir / f"{name}.toml")
        for row in spec["rows"]:
            s = float(row.get("compliance", 0.0))
            published = row["published"][reference]
            ref = {"eps": row["eccentricity"], "load_ref": published["load"],
                   "attitude_deg_ref": published["attitude_angle_deg"]}
            if table == "3.1":
                model = BearingModel(bearing_number=row["bearing_number"], foil="rigid",
                                     length_ratio=1.0)
            else:
                model = BearingModel(bearing_number=row["bearing_number"], compliance=s,
                                     foil="simple" if s > 0 else "rigid", length_ratio=1.0,
                                     subambient="gumbel")
            rows.append((table, ref, model))
    return rows


def bench_tables(problems_dir: Path, warm_chain: bool) -> dict:
    """Build one solver and solve every row of Tables 3.1 and 3.2; total wall time [s].

    With ``warm_chain`` each row is warm-started from the previous row of the same
    (table, Λ, S, L/D) group (rows are in increasing ε in the CSV files).
    """
    rows = table_models(problems_dir)
    t0 = time.perf_counter()
    solver = StaticSolver(GRID, film="periodic")
    build = time.perf_counter() - t0
    results = []
    previous = {}
    for table, ref, model in rows:
        key = (table, model.bearing_number, model.compliance, model.length_ratio)
        initial = previous.get(key) if warm_chain else None
        t1 = time.perf_counter()
        sol = solve_static(model, eccentricity=ref["eps"], solver=solver, initial=initial)
        elapsed = time.perf_counter() - t1
        previous[key] = sol
        ref_load, ref_att = ref["load_ref"], ref["attitude_deg_ref"]
        results.append({
            "table": table, "Lambda": model.bearing_number, "eps": ref["eps"],
            "S": model.compliance, "foil": model.foil, "subambient": model.subambient,
            "load": sol.load, "attitude_deg": sol.attitude_angle_deg,
            "load_reference": ref_load, "attitude_deg_reference": ref_att,
            "load_rel_error": sol.load / ref_load - 1,
            "attitude_error_deg": sol.attitude_angle_deg - ref_att,
            "success": sol.success, "iterations": sol.iterations, "solve_s": elapsed})
    total = time.perf_counter() - t0
    return {"total_s": total, "build_s": build, "solves_s": total - build,
            "warm_chain": warm_chain, "all_success": all(r["success"] for r in results),
            "rows": results}


# ------------------------------------------------------------------------- report
def print_report(out: dict) -> None:
    info = out["machine"]
    print(f"gfbopt static benchmark, grid {info['grid']}, {info['date']}")
    print(f"  {info['platform']}, {info['cpu_count']} CPUs, python {info['python']}, "
          f"casadi {info['casadi']}, numpy {info['numpy']}, scipy {info['scipy']}; "
          f"load average at start {info['load_average_1min']:.2f}")
    if "formulations" in out:
        print("\nBuild formulations (current: median of 3; flat-SX reference: once)")
        print(f"  {'grid':>7s} {'unknowns':>8s} {'build':>8s} {'cpu':>7s} {'symbolic':>9s} "
              f"{'flat SX':>8s} {'cpu':>7s} {'flat/new':>8s} {'same J':>6s} {'dJ rel':>8s}")
        for r in out["formulations"]:
            b, f = r["build"], r["flat_reference_build"]
            print(f"  {r['grid']:>7s} {r['n_unknowns']:8d} {b['median_s']:7.3f}s "
                  f"{b['cpu_median_s']:6.3f}s {r['symbolic_problem']['median_s']:8.3f}s "
                  f"{f['median_s']:7.3f}s {f['cpu_median_s']:6.3f}s "
                  f"{r['ratio_flat_over_build']:8.1f} {r['jacobian_same_sparsity']!s:>6s} "
                  f"{r['jacobian_max_rel_diff']:8.1e}")
    if "serialisation" in out:
        print("\nSerialised nlpsol (what a disk cache would load) vs building it (median of 3)")
        for r in out["serialisation"]:
            print(f"  {r['grid']:>7s} build {r['build']['median_s']:.3f} s "
                  f"(cpu {r['build']['cpu_median_s']:.3f}); load {r['load']['median_s']:.3f} s "
                  f"(cpu {r['load']['cpu_median_s']:.3f}); save {r['save']['median_s']:.3f} s; "
                  f"{r['file_mb']:.1f} MB; load/build {r['ratio_load_over_build_wall']:.2f} "
                  f"(cpu {r['ratio_load_over_build_cpu']:.2f}); "
                  f"loaded solution differs by {r['loaded_state_max_diff']:.1e}")
    if "build" in out:
        print("\nBuild at 72 × 20 (median of 3)")
        for name, b in out["build"].items():
            print(f"  {name:<11s} {b['median_s']:7.3f} s   ({b['n_variables']} unknowns)")
    if "points" in out:
        print("\nOne equilibrium, rigid periodic, L/D = 1 (median of 10)")
        print(f"  {'Λ':>4s} {'ε':>5s} {'IPOPT cold':>11s} {'it':>3s} {'IPOPT warm':>11s} "
              f"{'it':>3s} {'Newton':>8s} {'it':>3s} {'cold/N':>7s} {'warm/N':>7s} "
              f"{'dW rel':>8s} {'dφ °':>8s}")
        for p in out["points"]:
            print(f"  {p['bearing_number']:4.1f} {p['eccentricity']:5.2f} "
                  f"{p['ipopt_cold_s']:9.4f} s {p['ipopt_cold_iterations']:3d} "
                  f"{p['ipopt_warm_s']:9.4f} s {p['ipopt_warm_iterations']:3d} "
                  f"{p['newton_cold_s']:6.4f} s {p['newton_iterations']:3d} "
                  f"{p['ratio_cold_ipopt_over_newton']:7.2f} "
                  f"{p['ratio_warm_ipopt_over_newton']:7.2f} {p['load_rel_diff']:8.1e} "
                  f"{p['attitude_diff_deg']:8.1e}")
        print("\nHard cold starts (median of 3; gfbopt's continuation fallback included)")
        for p in out["hard_cold"]:
            print(f"  Λ={p['bearing_number']:.1f} ε={p['eccentricity']:.2f}: first attempt "
                  f"{p['first_attempt_status']} ({p['first_attempt_iterations']} it); "
                  f"with fallback {p['ipopt_cold_s']:.3f} s, {p['ipopt_iterations_total']} it, "
                  f"success={p['success']}; Newton {p['newton_cold_s']:.4f} s "
                  f"({p['newton_iterations']} it)")
    for key, label in (("tables_cold", "cold rows"), ("tables_warm_chain", "warm chain")):
        if key not in out:
            continue
        t = out[key]
        print(f"\nTables 3.1 + 3.2, {label}: total {t['total_s']:.3f} s "
              f"(build {t['build_s']:.3f} s + solves {t['solves_s']:.3f} s), "
              f"all success: {t['all_success']}")
        if key == "tables_cold":
            print(f"  {'tab':>3s} {'Λ':>4s} {'ε':>5s} {'S':>3s} {'W̄':>8s} {'ref':>8s} "
                  f"{'err %':>7s} {'φ °':>7s} {'ref':>6s} {'err °':>6s} {'it':>3s} {'s':>6s}")
            for r in t["rows"]:
                print(f"  {r['table']:>3s} {r['Lambda']:4.1f} {r['eps']:5.2f} {r['S']:3.0f} "
                      f"{r['load']:8.4f} {r['load_reference']:8.4f} "
                      f"{100 * r['load_rel_error']:7.2f} {r['attitude_deg']:7.2f} "
                      f"{r['attitude_deg_reference']:6.2f} {r['attitude_error_deg']:6.2f} "
                      f"{r['iterations']:3d} {r['solve_s']:6.3f}")
    if "cli" in out:
        print(f"\nCommand line at the default grid {DEFAULT_GRID} (fresh process per call)")
        for command, calls in out["cli"].items():
            for k, c in enumerate(calls, 1):
                extra = (f"success={c.get('success')}" if c["returncode"] == 0
                         else f"FAILED (exit {c['returncode']})")
                print(f"  gfbopt {command:<6s} call {k}: wall {c['wall_s']:6.2f} s, "
                      f"cpu {c['cpu_s']:6.2f} s, load average {c['load_average_1min']:.2f}, "
                      f"{extra}")
    print("\nTargets")
    for name, row in out["targets"].items():
        print(f"  {name:<40s} {row['measured']:8.3f}  target {row['target']:<10} "
              f"{'met' if row['met'] else 'NOT met'}")


def evaluate_targets(out: dict) -> dict:
    checks = {}
    if "build" in out:
        checks["build foundation [s]"] = (out["build"]["foundation"]["median_s"],
                                          TARGETS["build_s"])
        checks["build beam [s]"] = (out["build"]["beam"]["median_s"], TARGETS["build_s"])
    if "points" in out:
        main = out["points"][0]
        checks["solve warm [s]"] = (main["ipopt_warm_s"], TARGETS["solve_warm_s"])
        checks["solve cold [s]"] = (main["ipopt_cold_s"], TARGETS["solve_cold_s"])
        checks["solve cold / Newton cold [-]"] = (main["ratio_cold_ipopt_over_newton"], 1.0)
    if "tables_cold" in out:
        checks["tables 3.1+3.2 cold, with build [s]"] = (out["tables_cold"]["total_s"],
                                                         TARGETS["tables_total_s"])
    if "cli" in out:
        for command, target in (("static", "cli_static_s"), ("linear", "cli_linear_s")):
            second = out["cli"][command][-1]
            checks[f"gfbopt {command} 2nd call, wall [s]"] = (second["wall_s"],
                                                              TARGETS[target])
            checks[f"gfbopt {command} 2nd call, cpu [s]"] = (second["cpu_s"], TARGETS[target])
    return {name: {"measured": value, "target": f"<= {limit}", "met": value <= limit}
            for name, (value, limit) in checks.items()}


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=str(REPO / "results" / "benchmarks" /
                                             "static_speed.json"), help="JSON output path")
    parser.add_argument("--problems-dir", default=str(REPO / "problems"),
                        help="folder with thesis_table_3_1.toml and thesis_table_3_2.toml")
    parser.add_argument("--sections", default=",".join(SECTIONS),
                        help=f"comma-separated subset of {', '.join(SECTIONS)} (default: all)")
    args = parser.parse_args(argv)
    sections = [name.strip() for name in args.sections.split(",") if name.strip()]
    unknown = sorted(set(sections) - set(SECTIONS))
    if unknown:
        parser.error(f"--sections: unknown {', '.join(unknown)}; choose from "
                     f"{', '.join(SECTIONS)}")

    out = {"machine": dict(machine_info(), load_average_1min=os.getloadavg()[0],
                           sections=sections)}
    if "formulations" in sections:
        out["formulations"] = bench_formulations()
    if "serialisation" in sections:
        out["serialisation"] = bench_serialisation()
    if "build" in sections:
        out["build"] = bench_build(3)
    if "points" in sections:
        solver = StaticSolver(GRID, film="periodic")
        # the first point is the one the targets are judged on
        out["points"] = [bench_point(solver, lam, 0.6, 10) for lam in (1.0, 0.6, 3.0)]
        out["hard_cold"] = bench_hard_cold(solver, [(0.6, 0.2), (0.6, 0.4)], 3)
        del solver
    if "tables" in sections:
        out["tables_cold"] = bench_tables(Path(args.problems_dir), warm_chain=False)
        out["tables_warm_chain"] = bench_tables(Path(args.problems_dir), warm_chain=True)
    if "cli" in sections:
        out["cli"] = bench_cli(2)
    out["targets"] = evaluate_targets(out)
    print_report(out)
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
