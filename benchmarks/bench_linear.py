"""Speed of gfbopt's linearised dynamics (gfbopt.linear) on the 72 × 20 grid, in one run.

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
* threshold: ``linear_threshold(lin)`` alone [s], and its number of impedance evaluations;
* critical mass: ``solve_static`` cold with a prebuilt solver + ``linearise`` +
  ``linear_threshold`` [s], and the same including the solver build;
* eigenvalues: ``semi_discrete_eigenvalues(lin, M̄crit, 1j·γcrit)`` [s], for reference (with the
  growth rate of the eigenvalue nearest the shift, which should be ≈ 0 at the threshold).

Usage::

    PYTHONPATH=. python benchmarks/bench_linear.py [--out results/benchmarks/linear_speed.json]

Prints a table and writes a JSON file with the machine, date, library versions and the BLAS
thread settings.  Note: on a 2-CPU machine ``semi_discrete_eigenvalues`` (ARPACK) was seen to
take seconds instead of ~0.05 s with the default multi-threaded OpenBLAS (the number of
Arnoldi matrix-vector products is the same; each one becomes slow); run with
``OPENBLAS_NUM_THREADS=1`` to compare.
Targets: coefficients (10 whirl ratios) ≤ 0.3 s; linear critical mass including the static
solve (prebuilt solver) ≤ 0.5 s.  Judged on the slowest of the three operating points.
"""
from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info as _machine_info, write_report  # noqa: E402
from gfbopt import BearingModel, Grid, solve_static, solver_for
from gfbopt.linear import (coefficients, impedance, linear_threshold, linearise,
                           semi_discrete_eigenvalues)

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
GRID = Grid(72, 20)
REPEATS = 5
WHIRL_RATIOS = np.linspace(0.0, 1.0, 10)
TARGETS = {"coefficients_s": 0.3, "critical_mass_s": 0.5}

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
    return _machine_info(grid=str(GRID), repeats=REPEATS)


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
        "attitude_deg": math.degrees(sol.attitude_angle),
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
        "threshold": {**_entry(t_thr, thr_times), "evaluations": thr.evaluations,
                      "critical_mass": thr.critical_mass, "whirl_ratio": thr.whirl_ratio,
                      "stable_for_all_masses": thr.stable_for_all_masses,
                      "seconds_per_evaluation": t_thr / max(thr.evaluations, 1)},
        "critical_mass": {**_entry(t_crit, crit_times),
                          "critical_mass": thr_chain.critical_mass,
                          "evaluations": thr_chain.evaluations},
        "critical_mass_with_build": _entry(t_crit_b, crit_b_times),
        "eigenvalues": eig,
    }


# ------------------------------------------------------------------------- report
def print_report(out: dict) -> None:
    info = out["machine"]
    print(f"gfbopt linear-dynamics benchmark, grid {info['grid']}, {info['date']}")
    print(f"  {info['platform']}, {info['cpu_count']} CPUs, python {info['python']}, "
          f"casadi {info['casadi']}, numpy {info['numpy']}, scipy {info['scipy']}")
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
    row("  impedance evaluations", [p["threshold"]["evaluations"] for p in points], "{:10d}")
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
    print("\nTargets (slowest operating point)")
    for name, t in out["targets"].items():
        print(f"  {name:<46s} {t['measured']:8.3f}  target {t['target']:<8s} "
              f"({t['point']:<6s}) {'met' if t['met'] else 'NOT met'}")


def evaluate_targets(out: dict) -> dict:
    checks = {
        "coefficients, 10 whirl ratios [s]": (
            lambda p: p["coefficients"]["median_s"], TARGETS["coefficients_s"]),
        "critical mass incl. static solve [s]": (
            lambda p: p["critical_mass"]["median_s"], TARGETS["critical_mass_s"]),
    }
    result = {}
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
    args = parser.parse_args(argv)

    out = {"machine": machine_info(),
           "whirl_ratios": WHIRL_RATIOS.tolist(), "targets_s": TARGETS}
    out["points"] = [bench_point(name, ecc, model) for name, (ecc, model) in POINTS.items()]
    out["targets"] = evaluate_targets(out)
    print_report(out)
    write_report(out, args.out)
    return out


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
