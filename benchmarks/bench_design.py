"""Speed of the bump-foil geometric program (gfbopt.design.geometry_program).

The DESIGN_NOTES example (c = 32 µm, Inconel X-750, Δp = 1 bar, s ∈ [2, 6] mm,
l0 ∈ [0.5, 3] mm, t_b ∈ [50, 200] µm, gap 0.2 mm), targets S spread over [0.3, 1.5].

Measures
--------
* import: importing gfbopt.design.geometry_program (cvxpy) [s];
* single GP: building and solving one design GP (minimum stress at S) — the first in the
  process, then the mean of 50 more at other targets [s];
* design: a whole ``design_bump_foil`` call (4 range GPs + the design GP), the first and the
  mean of 50 more [s], and the time per GP inside it;
* with a radius: ``design_bump_foil`` with the whole-number-of-bumps re-solve [s];
* reference, not used by gfbopt: the same GP written once with the target as a cvxpy
  Parameter (DPP), re-solved 50 times — what caching the compiled problem would save.

Target: ≤ 50 ms per GP after the first.  No assertions; prints one JSON object (and writes it
with ``--out``).

Usage::

    python benchmarks/bench_design.py [--out results/benchmarks/design_speed.json]
"""
from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from machine import machine_info, write_report

REPEATS = 50
TARGET_PER_GP_S = 0.050
TARGETS = np.linspace(0.3, 1.5, REPEATS)


def timed(function, *args):
    start = time.perf_counter()
    result = function(*args)
    return time.perf_counter() - start, result


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="also write the JSON report here")
    args = parser.parse_args(argv)

    start = time.perf_counter()
    import cvxpy as cp

    from gfbopt.design import geometry_program as gp
    from gfbopt.physics import bump
    import_s = time.perf_counter() - start

    spec = gp.BumpDesignSpec(radial_clearance=32e-6)
    spec_radius = gp.BumpDesignSpec(radial_clearance=32e-6, radius=19.05e-3)

    # One design GP (build + solve), through the module's own builder.
    first_gp_s, _ = timed(gp._solve_design, spec, (0.664, 0.664))
    single = [timed(gp._solve_design, spec, (s, s))[0] for s in TARGETS]

    first_design_s, first = timed(gp.design_bump_foil, spec, 0.664)
    designs = [timed(gp.design_bump_foil, spec, float(s)) for s in TARGETS]
    design_times = [t for t, _ in designs]
    per_gp = [t / d.solves for t, d in designs]
    radius_times = [timed(gp.design_bump_foil, spec_radius, float(s))[0] for s in TARGETS[:10]]

    # Reference: the same GP compiled once, the target a Parameter.
    s_, l_, t_ = (cp.Variable(pos=True) for _ in range(3))
    target = cp.Parameter(pos=True, value=0.664)
    alpha = bump.bump_compliance(s_, l_, t_, 214e9, 0.29)
    stress = bump.bump_bending_stress(1e5, s_, l_, t_)
    problem = cp.Problem(cp.Minimize(stress), [
        bump.compliance_coefficient(alpha, 101325.0, 32e-6) == target,
        stress <= 310e6, s_ >= 2e-3, s_ <= 6e-3, l_ >= 0.5e-3, l_ <= 3e-3, t_ >= 50e-6,
        t_ <= 200e-6, (2 * l_ + 0.2e-3) / s_ <= 1])
    first_param_s, _ = timed(lambda: problem.solve(gp=True))
    param = []
    for s in TARGETS:
        target.value = float(s)
        param.append(timed(lambda: problem.solve(gp=True))[0])

    mean_single = statistics.fmean(single)
    out = machine_info(
        cvxpy=cp.__version__, solver=first.solver, repeats=REPEATS,
        import_s=import_s,
        single_gp={"first_s": first_gp_s, "mean_s": mean_single,
                   "median_s": statistics.median(single), "max_s": max(single),
                   "first_over_mean": first_gp_s / mean_single,
                   "mean_over_target": mean_single / TARGET_PER_GP_S},
        design={"first_s": first_design_s, "mean_s": statistics.fmean(design_times),
                "gps_per_design": first.solves,
                "mean_per_gp_s": statistics.fmean(per_gp),
                "first_over_mean": first_design_s / statistics.fmean(design_times),
                "per_gp_over_target": statistics.fmean(per_gp) / TARGET_PER_GP_S},
        design_with_radius={"mean_s": statistics.fmean(radius_times), "repeats": 10},
        reference_parametrised_gp={"first_s": first_param_s, "mean_s": statistics.fmean(param),
                                   "rebuild_over_parametrised":
                                       mean_single / statistics.fmean(param)},
        target_per_gp_s=TARGET_PER_GP_S)
    print(json.dumps(out, indent=2))
    if args.out:
        write_report(out, args.out)
    return out


if __name__ == "__main__":
    main()
