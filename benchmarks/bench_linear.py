"""Speed of gfbopt's linearised dynamics (gfbopt.linear), in one run: the pieces on the
72 × 20 grid, the threshold's two methods at 72 × 20 and 144 × 36, and ``gfbopt linear`` end to
end at the default grid.

Operating points (ε, Λ, S), L/D = 1:

* (0.4, 2, 0)  rigid,  periodic film;
* (0.4, 2, 1)  simple foundation (axial-mean law), periodic film;
* (0.3, 5, 1)  beam top foil, C = 1 (``top_foil_coefficient``), film='seam' (seam on the
  maximum-film line).

Measures (median of 5 repetitions each)
---------------------------------------
* build: ``solver_for(model, grid)`` [s];
* static: ``solve_static`` cold (no ``initial``) with the prebuilt solver [s];
* linearise: ``linearise(solution, solver)`` [s];
* coefficients: ``coefficients(lin, 10 whirl ratios in [0, 1])`` after the static solve and
  the linearisation [s] (γ = 0 costs two impedance solves, so 11 in all);
* impedance: one ``impedance(lin, 0.5j)`` [s] (the unit of cost of everything above);
* threshold: ``linear_threshold(lin)`` alone [s] (default method), and its number of sparse
  factorisations;
* critical mass: ``solve_static`` cold with a prebuilt solver + ``linearise`` +
  ``linear_threshold`` [s], and the same including the solver build;
* eigenvalues: ``semi_discrete_eigenvalues(lin, M̄crit, 1j·γcrit)`` [s], for reference (with the
  growth rate of the eigenvalue nearest the shift, which should be ≈ 0 at the threshold).

Threshold methods (section ``threshold_methods``), at 72 × 20 and 144 × 36: CPU time
(``time.process_time``, median of 3 repetitions for the reference and 5 for the default) of
``linear_threshold(lin, method="scan")`` (one sparse LU per impedance evaluation, the
reference) and ``linear_threshold(lin)`` (Krylov model on one LU, gfbopt/linear/threshold.py),
their ratio, sparse factorisations and triangular solves, and the relative difference of the
critical mass and whirl ratio between them, for:

* simple : (0.4, 2, 1) axial-mean law, periodic film;
* local : the same with the local law;
* beam : (0.3, 5, 1) beam top foil, film='seam' on the maximum-film line;
* seam : the Ruscitto bearing at 20,000 rpm and 20 N (Λ = 3.4, S = 1.05, W̄0 = 0.55), seam
  (welded end) at 180° from the load;
* eta : simple with structural loss factor η = 0.3;
* multi : rigid, Λ = 40, ε = 0.8, L/D = 1.5, seam at 90°: seven crossings on several branches.

End to end (section ``cli_linear``): wall time of ``gfbopt linear --eccentricity 0.4
--bearing-number 2 --compliance 1 --length-ratio 1 --json`` at the default grid (144 × 36) in a
fresh interpreter (median of 3), and the same with ``linear_threshold`` forced to
``method="scan"`` (the previous behaviour).  Target ≤ 4 s.

Usage::

    PYTHONPATH=. python benchmarks/bench_linear.py [--out results/benchmarks/linear_speed.json]
                                                   [--only points threshold cli]

Prints a table and writes a JSON file with the machine, date, library versions and the BLAS
thread settings.  Note: on a 2-CPU machine ``semi_discrete_eigenvalues`` (ARPACK) was seen to
take seconds instead of ~0.05 s with the default multi-threaded OpenBLAS (the number of
Arnoldi matrix-vector products is the same; each one becomes slow); run with
``OPENBLAS_NUM_THREADS=1`` to compare.
Targets: coefficients (10 whirl ratios) ≤ 0.3 s; linear critical mass including the static
solve (prebuilt solver) ≤ 0.5 s.  Judged on the slowest of the three operating points.
``gfbopt linear`` end to end ≤ 4 s.  The BLAS is limited to one thread here, as in the CLI.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info as _machine_info, write_report  # noqa: E402
from gfbopt import BearingModel, Grid, solve_static, solver_for
from gfbopt.linear import (coefficients, impedance, linear_threshold, linearise,
                           semi_discrete_eigenvalues)
from gfbopt.parallel import limit_blas_threads

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
GRID = Grid(72, 20)
REPEATS = 5
WHIRL_RATIOS = np.linspace(0.0, 1.0, 10)
TARGETS = {"coefficients_s": 0.3, "critical_mass_s": 0.5, "cli_linear_s": 4.0}
THRESHOLD_GRIDS = (Grid(72, 20), Grid(144, 36))
THRESHOLD_REPEATS = {"scan": 3, "krylov": 5}
#: name -> (ε, or ("load", W̄0), model)
THRESHOLD_CASES = {
    "simple": (0.4, BearingModel(bearing_number=2.0, compliance=1.0)),
    "local": (0.4, BearingModel(bearing_number=2.0, compliance=1.0, deflection_law="local")),
    "beam": (0.3, BearingModel(bearing_number=5.0, compliance=1.0, foil="beam",
                               top_foil_coefficient=1.0, film="seam")),
    "seam": (("load", 0.55), BearingModel(bearing_number=3.4, compliance=1.05, film="seam",
                                          seam_angle_deg=180.0)),
    "eta": (0.4, BearingModel(bearing_number=2.0, compliance=1.0, loss_factor=0.3)),
    "multi": (0.8, BearingModel(bearing_number=40.0, foil="rigid", film="seam",
                                length_ratio=1.5, seam_angle_deg=90)),
}
CLI_ARGS = ["linear", "--eccentricity", "0.4", "--bearing-number", "2", "--compliance", "1",
            "--length-ratio", "1", "--json"]
CLI_REPEATS = 3

#: name -> (ε, model)
POINTS = {
    "rigid": (0.4, BearingModel(bearing_number=2.0, compliance=0.0, foil="rigid")),
    "simple": (0.4, BearingModel(bearing_number=2.0, compliance=1.0, foil="simple")),
    "beam": (0.3, BearingModel(bearing_number=5.0, compliance=1.0, foil="beam",
                               top_foil_coefficient=1.0, film="seam")),
}


# ------------------------------------------------------------------------ helpers
def timed(function, repeats: int = REPEATS) -> tuple[float, list[float], object]:
    """Run ``function()`` ``repeats`` times; return (median wall time [s], all times, last result)."""
    times = []
    result = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), times, result


def machine_info() -> dict:
    return _machine_info(grid=str(GRID), repeats=REPEATS,
                         blas_threads="1 (threadpoolctl, as in the CLI)")


def _entry(median: float, times: list[float]) -> dict:
    return {"median_s": median, "times_s": times}


# --------------------------------------------------------------------- benchmarks
def bench_point(name: str, eccentricity: float, model: BearingModel) -> dict:
    """Every timing of the module docstring at one operating point."""
    build, build_times, solver = timed(lambda: solver_for(model, GRID))

    def static():
        return solve_static(model, eccentricity=eccentricity, solver=solver)

    t_static, static_times, sol = timed(static)
    if not sol.success:
        raise RuntimeError(f"{name}: static solve failed: {sol.message}")
    t_lin, lin_times, lin = timed(lambda: linearise(sol, solver))
    t_imp, imp_times, _ = timed(lambda: impedance(lin, 0.5j))
    t_coef, coef_times, coef = timed(lambda: coefficients(lin, WHIRL_RATIOS))
    t_thr, thr_times, thr = timed(lambda: linear_threshold(lin))

    def critical_mass():
        s = solve_static(model, eccentricity=eccentricity, solver=solver)
        return linear_threshold(linearise(s, solver))

    t_crit, crit_times, thr_chain = timed(critical_mass)

    def critical_mass_with_build():
        sv = solver_for(model, GRID)
        s = solve_static(model, eccentricity=eccentricity, solver=sv)
        return linear_threshold(linearise(s, sv))

    t_crit_b, crit_b_times, _ = timed(critical_mass_with_build)

    eig = {}
    if math.isfinite(thr.critical_mass):
        shift = 1j * thr.whirl_ratio
        t_eig, eig_times, ev = timed(
            lambda: semi_discrete_eigenvalues(lin, thr.critical_mass, shift))
        nearest = ev[np.argmin(np.abs(ev - shift))]
        eig = {**_entry(t_eig, eig_times), "nearest_eigenvalue_real": float(nearest.real),
               "nearest_eigenvalue_imag": float(nearest.imag)}
    return {
        "name": name, "eccentricity": eccentricity,
        "model": {"bearing_number": model.bearing_number, "compliance": model.compliance,
                  "foil": model.foil, "top_foil_coefficient": model.top_foil_coefficient,
                  "film": model.film, "length_ratio": model.length_ratio},
        "n_states": lin.size, "nnz_a": int(lin.a.nnz),
        "static_iterations": sol.iterations, "load": sol.load,
        "attitude_deg": sol.attitude_angle_deg,
        "build": _entry(build, build_times),
        "static_cold": _entry(t_static, static_times),
        "linearise": _entry(t_lin, lin_times),
        "impedance_one": _entry(t_imp, imp_times),
        "coefficients": {**_entry(t_coef, coef_times), "n_whirl_ratios": int(WHIRL_RATIOS.size),
                         "impedance_evaluations": int(WHIRL_RATIOS.size
                                                      + np.count_nonzero(WHIRL_RATIOS == 0)),
                         "kxx_at_0": float(coef.stiffness[0, 0, 0]),
                         "cxx_at_0": float(coef.damping[0, 0, 0])},
        "coefficients_after_static": {
            "median_s": t_static + t_lin + t_coef,
            "note": "sum of the medians static_cold + linearise + coefficients"},
        "threshold": {**_entry(t_thr, thr_times), "method": thr.method,
                      "evaluations": thr.evaluations, "factorisations": thr.factorisations,
                      "solves": thr.solves,
                      "critical_mass": thr.critical_mass, "whirl_ratio": thr.whirl_ratio,
                      "stable_for_all_masses": thr.stable_for_all_masses},
        "critical_mass": {**_entry(t_crit, crit_times),
                          "critical_mass": thr_chain.critical_mass,
                          "evaluations": thr_chain.evaluations},
        "critical_mass_with_build": _entry(t_crit_b, crit_b_times),
        "eigenvalues": eig,
    }


def cpu_timed(function, repeats: int) -> tuple[float, list[float], object]:
    """Like :func:`timed` with CPU time of this process (``time.process_time``) [s]."""
    times, result = [], None
    for _ in range(repeats):
        t0 = time.process_time()
        result = function()
        times.append(time.process_time() - t0)
    return statistics.median(times), times, result


def _relative(a: float, b: float) -> float:
    if a == b or (math.isnan(a) and math.isnan(b)):
        return 0.0
    return abs(a - b) / abs(a) if math.isfinite(a) and a != 0 else math.inf


def bench_threshold(name: str, grid: Grid) -> dict:
    """Reference scan against the default (Krylov) threshold at one case and grid."""
    where, model = THRESHOLD_CASES[name]
    if isinstance(where, tuple):
        sol = solve_static(model, load=where[1], grid=grid)
    else:
        sol = solve_static(model, eccentricity=where, grid=grid)
    if not sol.success:
        raise RuntimeError(f"{name}: static solve failed: {sol.message}")
    lin = linearise(sol)
    out = {"name": name, "grid": str(grid), "n_states": lin.size}
    for method, repeats in THRESHOLD_REPEATS.items():
        cpu, times, thr = cpu_timed(lambda m=method: linear_threshold(lin, method=m), repeats)
        out[method] = {"cpu_median_s": cpu, "cpu_times_s": times,
                       "wall_s": thr.wall_time_s, "factorisations": thr.factorisations,
                       "solves": thr.solves, "evaluations": thr.evaluations,
                       "critical_mass": thr.critical_mass, "whirl_ratio": thr.whirl_ratio}
    out["speed_up"] = out["scan"]["cpu_median_s"] / out["krylov"]["cpu_median_s"]
    out["critical_mass_rel_diff"] = _relative(out["scan"]["critical_mass"],
                                              out["krylov"]["critical_mass"])
    out["whirl_ratio_rel_diff"] = _relative(out["scan"]["whirl_ratio"],
                                            out["krylov"]["whirl_ratio"])
    return out


_SCAN_CLI = ("import functools, sys, gfbopt.linear as L; "
             "L.linear_threshold = functools.partial(L.linear_threshold, method='scan'); "
             "from gfbopt.cli import main; sys.exit(main(sys.argv[1:]))")


def bench_cli() -> dict:
    """``gfbopt linear`` end to end in a fresh interpreter, default and reference threshold."""
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    out = {"command": "gfbopt " + " ".join(CLI_ARGS), "grid": "144x36 (default)"}
    for label, prefix in (("krylov", ["-m", "gfbopt"]), ("scan", ["-c", _SCAN_CLI])):
        times, result = [], None
        for _ in range(CLI_REPEATS):
            t0 = time.perf_counter()
            done = subprocess.run([sys.executable, *prefix, *CLI_ARGS], capture_output=True,
                                  text=True, env=env, check=True)
            times.append(time.perf_counter() - t0)
            result = json.loads(done.stdout)
        out[label] = {"wall_median_s": statistics.median(times), "wall_times_s": times,
                      "reported_wall_time_s": result["wall_time_s"],
                      "critical_mass": result["critical_mass"],
                      "whirl_ratio": result["whirl_ratio"]}
    out["speed_up"] = out["scan"]["wall_median_s"] / out["krylov"]["wall_median_s"]
    return out


# ------------------------------------------------------------------------- report
def print_report(out: dict) -> None:
    info = out["machine"]
    print(f"gfbopt linear-dynamics benchmark, grid {info['grid']}, {info['date']}")
    print(f"  {info['platform']}, {info['cpu_count']} CPUs, python {info['python']}, "
          f"casadi {info['casadi']}, numpy {info['numpy']}, scipy {info['scipy']}")
    if "points" in out:
        print_points(out)
    if "threshold_methods" in out:
        print_thresholds(out["threshold_methods"])
    if "cli_linear" in out:
        cli = out["cli_linear"]
        print(f"\n{cli['command']}, {cli['grid']}: wall {cli['krylov']['wall_median_s']:.2f} s "
              f"(reference threshold: {cli['scan']['wall_median_s']:.2f} s, "
              f"×{cli['speed_up']:.1f}); M̄c {cli['krylov']['critical_mass']:.10g} against "
              f"{cli['scan']['critical_mass']:.10g}")
    if out.get("targets"):
        print("\nTargets (slowest operating point)")
        for name, t in out["targets"].items():
            print(f"  {name:<46s} {t['measured']:8.3f}  target {t['target']:<8s} "
                  f"({t['point']:<6s}) {'met' if t['met'] else 'NOT met'}")


def print_thresholds(rows: list) -> None:
    print("\nlinear_threshold: reference scan against the default (Krylov), CPU seconds "
          "(medians)")
    print(f"  {'case':<8s}{'grid':>8s}{'n':>7s}{'scan s':>9s}{'LU':>5s}{'krylov s':>10s}"
          f"{'LU':>4s}{'solves':>8s}{'ratio':>7s}{'ΔM̄c rel':>10s}{'Δγ rel':>9s}")
    for r in rows:
        a, b = r["scan"], r["krylov"]
        print(f"  {r['name']:<8s}{r['grid']:>8s}{r['n_states']:>7d}{a['cpu_median_s']:>9.3f}"
              f"{a['factorisations']:>5d}{b['cpu_median_s']:>10.3f}{b['factorisations']:>4d}"
              f"{b['solves']:>8d}{r['speed_up']:>7.1f}{r['critical_mass_rel_diff']:>10.1e}"
              f"{r['whirl_ratio_rel_diff']:>9.1e}")


def print_points(out: dict) -> None:
    info = out["machine"]
    print(f"  medians of {info['repeats']} repetitions; times in seconds")
    points = out["points"]
    print(f"\n  {'':<34s}" + "".join(f"{p['name']:>10s}" for p in points))

    def row(label, values, fmt="{:10.4f}"):
        print(f"  {label:<34s}" + "".join(fmt.format(v) for v in values))

    row("ε", [p["eccentricity"] for p in points], "{:10.2f}")
    row("Λ", [p["model"]["bearing_number"] for p in points], "{:10.1f}")
    row("S", [p["model"]["compliance"] for p in points], "{:10.1f}")
    print(f"  {'film':<34s}" + "".join(f"{p['model']['film']:>10s}" for p in points))
    row("states n", [p["n_states"] for p in points], "{:10d}")
    row("static load W̄0", [p["load"] for p in points])
    row("solver build", [p["build"]["median_s"] for p in points])
    row("static solve, cold", [p["static_cold"]["median_s"] for p in points])
    row("  IPOPT iterations", [p["static_iterations"] for p in points], "{:10d}")
    row("linearise", [p["linearise"]["median_s"] for p in points])
    row("one impedance Z(0.5i)", [p["impedance_one"]["median_s"] for p in points])
    row("coefficients, 10 γ in [0, 1]", [p["coefficients"]["median_s"] for p in points])
    row("  static + linearise + coeffs", [p["coefficients_after_static"]["median_s"]
                                          for p in points])
    row("linear_threshold alone", [p["threshold"]["median_s"] for p in points])
    row("  sparse factorisations", [p["threshold"]["factorisations"] for p in points],
        "{:10d}")
    row("  M̄crit", [p["threshold"]["critical_mass"] for p in points])
    row("  γcrit", [p["threshold"]["whirl_ratio"] for p in points])
    row("critical mass (static+lin+thr)", [p["critical_mass"]["median_s"] for p in points])
    row("  the same + solver build", [p["critical_mass_with_build"]["median_s"]
                                      for p in points])
    row("semi_discrete_eigenvalues", [p["eigenvalues"].get("median_s", math.nan)
                                      for p in points])
    row("  Re s of nearest eigenvalue", [p["eigenvalues"].get("nearest_eigenvalue_real",
                                                              math.nan) for p in points],
        "{:10.1e}")


def evaluate_targets(out: dict) -> dict:
    result = {}
    if "cli_linear" in out:
        value = out["cli_linear"]["krylov"]["wall_median_s"]
        limit = TARGETS["cli_linear_s"]
        result["gfbopt linear end to end, 144x36 [s]"] = {
            "measured": value, "target": f"<= {limit}", "point": "simple", "met": value <= limit}
    if "points" not in out:
        return result
    checks = {
        "coefficients, 10 whirl ratios [s]": (
            lambda p: p["coefficients"]["median_s"], TARGETS["coefficients_s"]),
        "critical mass incl. static solve [s]": (
            lambda p: p["critical_mass"]["median_s"], TARGETS["critical_mass_s"]),
    }
    for name, (get, limit) in checks.items():
        worst = max(out["points"], key=get)
        value = get(worst)
        result[name] = {"measured": value, "target": f"<= {limit}", "point": worst["name"],
                        "met": value <= limit}
    return result


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=str(REPO / "results" / "benchmarks" /
                                             "linear_speed.json"), help="JSON output path")
    parser.add_argument("--only", nargs="+", choices=("points", "threshold", "cli"),
                        default=("points", "threshold", "cli"), help="sections to run")
    args = parser.parse_args(argv)
    limit_blas_threads()

    out = {"machine": machine_info(),
           "whirl_ratios": WHIRL_RATIOS.tolist(), "targets_s": TARGETS}
    if "points" in args.only:
        out["points"] = [bench_point(name, ecc, model) for name, (ecc, model) in POINTS.items()]
    if "threshold" in args.only:
        out["threshold_methods"] = [bench_threshold(name, grid) for grid in THRESHOLD_GRIDS
                                    for name in THRESHOLD_CASES]
    if "cli" in args.only:
        out["cli_linear"] = bench_cli()
    out["targets"] = evaluate_targets(out)
    print_report(out)
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
