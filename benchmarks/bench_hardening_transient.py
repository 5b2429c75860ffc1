"""The hardening bump in the one-bearing transient: its cost, and its effect on a limit cycle.

``cost`` (default): CPU seconds per revolution (time.process_time, A/B interleaved, one BLAS
thread) of the hardened transient (n = 3, W_lim = 0.8) against the linear bump, Ruscitto at
30,000 rpm, 20 N, 4 rotors at M̄ = 4, rk4 and rkc, the drivers' own steps.  Measured at 72 × 20
(loaded machine): 1.95× (rk4), 2.2× (rkc), the safeguarded Newton of the row balance.

``cycle``: the friction transient's bounded case (S = 1, κ = 2, 60 N, Λ/2, M̄ = 8, RKC, 80
revolutions, kick 0.03 c, 24 × 8) with μ_f = 0 and 0.05, without hardening and with n = 3,
W_lim = 1.0 and 0.5: how each run ends, beside the describing function's verdict (reported,
not tuned; docs/PHYSICS.md §7a).

    OMP_NUM_THREADS=1 python benchmarks/bench_hardening_transient.py [cost|cycle]
"""
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from gfbopt.inputs import load_bearing  # noqa: E402
from gfbopt.inputs.grid import Grid  # noqa: E402
from gfbopt.inputs.options import resolve_model_options  # noqa: E402
from gfbopt.linear import linear_threshold, linearise  # noqa: E402
from gfbopt.linear.friction_onset import settled_amplitude  # noqa: E402
from gfbopt.static import solve_static  # noqa: E402
from gfbopt.transient.friction_orbit import (friction_outcome,  # noqa: E402
                                             integrate_friction_orbits)
from gfbopt.transient.orbit import integrate_orbits  # noqa: E402
from gfbopt.transient.system import transient_model  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
BEARING = load_bearing(ROOT / "problems/bearings/ruscitto.toml")
KW = resolve_model_options(BEARING.options).model_kwargs()


def _solved(grid, speed=30000.0, load=20.0, lam_factor=1.0, **changes):
    model = BEARING.model(speed, **KW).replace(**changes)
    model = model.replace(bearing_number=model.bearing_number * lam_factor)
    return solve_static(model, load=BEARING.nondimensional_load(load), grid=grid)


def cost(grid=Grid(72, 20), repeats=3):
    tms = {"linear bump": transient_model(_solved(grid)),
           "hardened": transient_model(_solved(grid, hardening_exponent=3.0,
                                               hardening_limit=0.8))}
    best = {}
    for _ in range(repeats):
        for name, tm in tms.items():
            for method in ("rk4", "rkc"):
                t0 = time.process_time()
                integrate_orbits(tm, [4.0] * 4, 1.0, method=method)
                dt = time.process_time() - t0
                best[name, method] = min(best.get((name, method), dt), dt)
    for method in ("rk4", "rkc"):
        a, b = best["linear bump", method], best["hardened", method]
        print(f"{grid} {method}: linear bump {a:.3f} s/rev, hardened {b:.3f} s/rev, "
              f"ratio {b / a:.2f}")


def cycle(grid=Grid(24, 8)):
    for label, more in (("no hardening", {}),
                        ("n = 3, W_lim = 1.0", dict(hardening_exponent=3.0, hardening_limit=1.0)),
                        ("n = 3, W_lim = 0.5", dict(hardening_exponent=3.0, hardening_limit=0.5))):
        for mu in (0.0, 0.05):
            sol = _solved(grid, speed=30000.0, load=60.0, lam_factor=0.5, compliance=1.0,
                          friction_coefficient=mu, friction_stiffness_ratio=2.0, **more)
            lin = linearise(sol)
            run = integrate_friction_orbits(transient_model(sol, friction=True), [8.0], 80.0,
                                            kick=0.03, method="rkc")
            verdict = friction_outcome(run.orbit).verdict
            df = ""
            if mu > 0:
                p = settled_amplitude(lin, 8.0, samples=12, smallest=1e-2, xtol=1e-4)
                df = (f"; describing function: bounded at {p.amplitude:.4g} c" if p.bounded
                      else "; describing function: no bounded orbit inside the film")
            print(f"{label}, μ_f = {mu}: M̄c = {linear_threshold(lin).critical_mass:.4g}, "
                  f"{verdict}{df}", flush=True)


if __name__ == "__main__":
    {"cost": cost, "cycle": cycle}[sys.argv[1] if len(sys.argv) > 1 else "cost"]()
