"""Speed of gfbopt's static equilibrium (CasADi/IPOPT) on the 72 × 20 grid, in one run.

Measures
--------
* build: time to construct :class:`gfbopt.StaticSolver` (rigid/simple foundation, and the
  beam top foil), median of 3 [s];
* solve: one equilibrium at a given (Λ, ε), rigid periodic film, L/D = 1 — cold
  (``solve_static`` without ``initial``) and warm (``initial=`` the solution at ε − 0.01),
  median of 10 each [s];
* the hand-written sparse Newton (tests/verification/newton_reference.py, the test oracle) on the same point, cold,
  median of 10 [s], and the ratios IPOPT/Newton;
* cold solves at a few low-Λ points where gfbopt's cold start is known to be hard;
* the whole of thesis Tables 3.1 and 3.2, *including* the one solver build they need (both
  tables are one formulation: periodic film, rigid/simple foundation, axial-mean law; Λ, S,
  L/D and the sub-ambient switch are CasADi parameters), solved cold row by row, and again
  with each row warm-started from the previous ε of the same (Λ, S) group.

Table 3.1: rigid, periodic, full film.  Table 3.2: ``BearingModel(bearing_number=1,
compliance=S, foil='simple' if S > 0 else 'rigid', subambient='gumbel')``.

Usage::

    PYTHONPATH=. python benchmarks/bench_static.py [--out results/benchmarks/static_speed.json]

Prints a table and writes a JSON file with the machine, date and library versions.
Targets (from the issue): build ≤ 1 s; solve ≤ 0.1 s warm, ≤ 0.3 s cold and no slower
than the Newton reference; Tables 3.1 + 3.2 ≤ 5 s including the build.
"""
from __future__ import annotations

import argparse
import csv
import importlib.util
import math
import statistics
import sys
import time
from pathlib import Path


sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info as _machine_info, write_report  # noqa: E402
from gfbopt import BearingModel, Grid, StaticSolver, solve_static

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
GRID = Grid(72, 20)
TARGETS = {"build_s": 1.0, "solve_warm_s": 0.1, "solve_cold_s": 0.3, "tables_total_s": 5.0}


def _load_newton_reference():
    spec = importlib.util.spec_from_file_location("newton_reference",
                                                  REPO / "tests" / "verification" / "newton_reference.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


newton_reference = _load_newton_reference()


# ------------------------------------------------------------------------ helpers
def timed(function, repeats: int) -> tuple[float, list[float], object]:
    """Run ``function()`` ``repeats`` times; return (median wall time [s], all times, last result)."""
    times = []
    result = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), times, result


def read_reference(path: Path) -> list[dict]:
    """Rows of a reference CSV (lines starting with '#' are comments), values as float/str."""
    with open(path, newline="") as handle:
        lines = [line for line in handle if not line.startswith("#")]
    rows = []
    for row in csv.DictReader(lines):
        parsed = {}
        for key, value in row.items():
            try:
                parsed[key] = float(value)
            except ValueError:
                parsed[key] = value
        rows.append(parsed)
    return rows


def machine_info() -> dict:
    return _machine_info(grid=str(GRID))


# --------------------------------------------------------------------- benchmarks
def bench_build(repeats: int = 3) -> dict:
    """Median time to build the StaticSolver, foundation and beam formulations [s]."""
    out = {}
    for name, beam in (("foundation", False), ("beam", True)):
        median, times, solver = timed(lambda: StaticSolver(GRID, film="periodic", foil_law="beam" if beam else "simple"),
                                      repeats)
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
        "attitude_deg_ipopt": math.degrees(sol.attitude_angle),
        "attitude_deg_newton": ref["attitude_angle_deg"],
        "attitude_diff_deg": abs(math.degrees(sol.attitude_angle) - ref["attitude_angle_deg"]),
    }


def bench_hard_cold(solver: StaticSolver, points, repeats: int = 3) -> list[dict]:
    """Cold IPOPT solves (with gfbopt's default continuation fallback) at low-Λ points."""
    out = []
    for lam, ecc in points:
        model = BearingModel(bearing_number=lam, foil="rigid", length_ratio=1.0)
        first = solve_static(model, eccentricity=ecc, solver=solver, continuation=False)
        median, times, sol = timed(
            lambda: solve_static(model, eccentricity=ecc, solver=solver), repeats)
        newton, _, ref = timed(
            lambda: newton_reference.solve_rigid_newton(lam, ecc, 1.0, GRID), repeats)
        out.append({"bearing_number": lam, "eccentricity": ecc,
                    "first_attempt_status": first.status,
                    "first_attempt_iterations": first.iterations,
                    "ipopt_cold_s": median, "ipopt_cold_times_s": times,
                    "ipopt_iterations_total": sol.iterations, "success": sol.success,
                    "newton_cold_s": newton, "newton_iterations": ref["iterations"],
                    "load_rel_diff": abs(sol.load / ref["load"] - 1)})
    return out


def table_models(reference_dir: Path) -> list[tuple[str, dict, BearingModel]]:
    """(table, reference row, model) for every row of thesis Tables 3.1 and 3.2."""
    rows = []
    for ref in read_reference(reference_dir / "thesis_table_3_1.csv"):
        rows.append(("3.1", ref, BearingModel(bearing_number=ref["Lambda"], foil="rigid",
                                              length_ratio=ref["L_over_D"])))
    for ref in read_reference(reference_dir / "thesis_table_3_2.csv"):
        s = ref["S"]
        rows.append(("3.2", ref, BearingModel(
            bearing_number=ref["Lambda"], compliance=s, foil="simple" if s > 0 else "rigid",
            length_ratio=ref["L_over_D"], subambient="gumbel")))
    return rows


def bench_tables(reference_dir: Path, warm_chain: bool) -> dict:
    """Build one solver and solve every row of Tables 3.1 and 3.2; total wall time [s].

    With ``warm_chain`` each row is warm-started from the previous row of the same
    (table, Λ, S, L/D) group (rows are in increasing ε in the CSV files).
    """
    rows = table_models(reference_dir)
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
        if table == "3.1":
            ref_load, ref_att = ref["load_ref"], ref["attitude_deg_ref"]
        else:
            ref_load, ref_att = ref["load_peng_carpino"], ref["attitude_deg_peng_carpino"]
        results.append({
            "table": table, "Lambda": model.bearing_number, "eps": ref["eps"],
            "S": model.compliance, "foil": model.foil, "subambient": model.subambient,
            "load": sol.load, "attitude_deg": math.degrees(sol.attitude_angle),
            "load_reference": ref_load, "attitude_deg_reference": ref_att,
            "load_rel_error": sol.load / ref_load - 1,
            "attitude_error_deg": math.degrees(sol.attitude_angle) - ref_att,
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
          f"casadi {info['casadi']}, numpy {info['numpy']}, scipy {info['scipy']}")
    print("\nBuild (median of 3)")
    for name, b in out["build"].items():
        print(f"  {name:<11s} {b['median_s']:7.3f} s   ({b['n_variables']} unknowns)")
    print("\nOne equilibrium, rigid periodic, L/D = 1 (median of 10)")
    print(f"  {'Λ':>4s} {'ε':>5s} {'IPOPT cold':>11s} {'it':>3s} {'IPOPT warm':>11s} {'it':>3s} "
          f"{'Newton':>8s} {'it':>3s} {'cold/N':>7s} {'warm/N':>7s} {'dW rel':>8s} {'dφ °':>8s}")
    for p in out["points"]:
        print(f"  {p['bearing_number']:4.1f} {p['eccentricity']:5.2f} {p['ipopt_cold_s']:9.4f} s "
              f"{p['ipopt_cold_iterations']:3d} {p['ipopt_warm_s']:9.4f} s "
              f"{p['ipopt_warm_iterations']:3d} {p['newton_cold_s']:6.4f} s "
              f"{p['newton_iterations']:3d} {p['ratio_cold_ipopt_over_newton']:7.2f} "
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
    print("\nTargets")
    for name, row in out["targets"].items():
        print(f"  {name:<34s} {row['measured']:8.3f}  target {row['target']:<10} "
              f"{'met' if row['met'] else 'NOT met'}")


def evaluate_targets(out: dict) -> dict:
    main = out["points"][0]
    checks = {
        "build foundation [s]": (out["build"]["foundation"]["median_s"], TARGETS["build_s"]),
        "build beam [s]": (out["build"]["beam"]["median_s"], TARGETS["build_s"]),
        "solve warm [s]": (main["ipopt_warm_s"], TARGETS["solve_warm_s"]),
        "solve cold [s]": (main["ipopt_cold_s"], TARGETS["solve_cold_s"]),
        "solve cold / Newton cold [-]": (main["ratio_cold_ipopt_over_newton"], 1.0),
        "tables 3.1+3.2 cold, with build [s]": (out["tables_cold"]["total_s"],
                                               TARGETS["tables_total_s"]),
    }
    return {name: {"measured": value, "target": f"<= {limit}", "met": value <= limit}
            for name, (value, limit) in checks.items()}


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=str(REPO / "results" / "benchmarks" /
                                             "static_speed.json"), help="JSON output path")
    parser.add_argument("--reference-dir", default="/work/shared/reference",
                        help="folder with thesis_table_3_1.csv and thesis_table_3_2.csv")
    args = parser.parse_args(argv)

    out = {"machine": machine_info()}
    out["build"] = bench_build(3)
    solver = StaticSolver(GRID, film="periodic")
    # the first point is the one the targets are judged on
    out["points"] = [bench_point(solver, lam, 0.6, 10) for lam in (1.0, 0.6, 3.0)]
    out["hard_cold"] = bench_hard_cold(solver, [(0.6, 0.2), (0.6, 0.4)], 3)
    del solver
    out["tables_cold"] = bench_tables(Path(args.reference_dir), warm_chain=False)
    out["tables_warm_chain"] = bench_tables(Path(args.reference_dir), warm_chain=True)
    out["targets"] = evaluate_targets(out)
    print_report(out)
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
