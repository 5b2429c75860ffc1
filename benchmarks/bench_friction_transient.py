"""Cost per revolution of the one-bearing transient with the bumps' friction against without it
(target: ≤ 2×).  CPU seconds (time.process_time), A/B interleaved, one BLAS thread.

The same bearing and grid both ways (Ruscitto, 15,000 rpm, 60 N, S = 1, κ = 2; friction run
μ_f = 0.05, the bare run μ_f = 0), the same fixed step Δτ, the same rotor M̄ = 8 and kick, so the
ratio is the cost of the slider recovery and the play-operator update per step; for rk4 and
for rkc (the bare run through gfbopt.transient.orbit.integrate_orbits, today's driver).

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python benchmarks/bench_friction_transient.py [nθ nZ]
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
from gfbopt.static import solve_static  # noqa: E402
from gfbopt.transient.friction_orbit import integrate_friction_orbits  # noqa: E402
from gfbopt.transient.orbit import integrate_orbits  # noqa: E402
from gfbopt.transient.system import transient_model  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def _model(grid, mu):
    bearing = load_bearing(ROOT / "problems/bearings/ruscitto.toml")
    kw = resolve_model_options(bearing.options).model_kwargs()
    model = bearing.model(30000.0, **kw).replace(compliance=1.0, friction_coefficient=mu,
                                                 friction_stiffness_ratio=2.0)
    model = model.replace(bearing_number=0.5 * model.bearing_number)
    sol = solve_static(model, load=bearing.nondimensional_load(60.0), grid=grid)
    return transient_model(sol, friction=mu > 0)


def main(n_theta=24, n_z=8, revolutions=5.0, repeats=3):
    grid = Grid(n_theta, n_z)
    rub, bare = _model(grid, 0.05), _model(grid, 0.0)
    for method in ("rk4", "rkc"):
        dt = integrate_friction_orbits(rub, [8.0], 0.01, kick=0.03,
                                       method=method).orbit.time_step
        runs = {"friction": lambda: integrate_friction_orbits(
                    rub, [8.0], revolutions, kick=0.03, time_step=dt, method=method),
                "bare": lambda: integrate_orbits(
                    bare, [8.0], revolutions, kick=0.03, time_step=dt, method=method)}
        cpu = {k: [] for k in runs}
        for _ in range(repeats):                     # A/B interleaved
            for name, run in runs.items():
                t = time.process_time()
                run()
                cpu[name].append((time.process_time() - t) / revolutions)
        best = {k: min(v) for k, v in cpu.items()}
        for k, v in best.items():
            print(f"{n_theta}x{n_z} {method} {k:9s} {1e3 * v:8.2f} ms CPU per revolution "
                  f"(Δτ = {dt:.4g})")
        print(f"{n_theta}x{n_z} {method} ratio friction / bare: "
              f"{best['friction'] / best['bare']:.2f} (target <= 2)")


if __name__ == "__main__":
    args = [int(a) for a in sys.argv[1:3]]
    main(*args)
