"""Onset speed of the blower rotor's bearing A against the orbit amplitude and the friction
coefficient, one bearing carrying its share of the rotor (cylindrical whirl).

Bearing A of problems/rotors/blower.toml: the Ruscitto bearing with its file's formulation,
static load 3.2 kg × 9.81 × 65/100 = 20.4 N, the per-bearing mass M = W/g, so the rotor's
M̄ = M c ω²/W = c ω²/g.  For each case the onset speed is the root of M̄(ω) = M̄c(Λ(ω), A) by
bisection on the speed (4,000–60,000 rpm), M̄c(A) from gfbopt.linear.friction_onset (A in
clearances; A = 0: stuck bumps).  Also the loss-factor model at η = 0.2 beside it.

    python results/bumps_that_rub/study.py      # writes onset_speed.csv next to this file
"""
import math
import sys
import time
from pathlib import Path

import pandas as pd

from gfbopt.inputs import load_bearing
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.options import resolve_model_options
from gfbopt.linear import linear_threshold, linearise
from gfbopt.linear.friction_onset import onset_at_amplitude, settled_amplitude
from gfbopt.static import solve_static

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
GRID = Grid(36, 10)
LOAD_N = 3.2 * 9.80665 * 0.65
G = 9.80665


def critical_mass(bearing, speed, mu, kappa, eta, amplitude):
    kw = resolve_model_options(bearing.options).model_kwargs()
    model = bearing.model(speed, **kw).replace(friction_coefficient=mu,
                                               friction_stiffness_ratio=kappa, loss_factor=eta)
    sol = solve_static(model, load=bearing.nondimensional_load(LOAD_N), grid=GRID)
    lin = linearise(sol)
    if mu == 0 or amplitude == 0:
        return linear_threshold(lin).critical_mass
    return onset_at_amplitude(lin, amplitude).critical_mass


def onset_speed(bearing, mu, kappa, eta, amplitude, low=4000.0, high=60000.0, rtol=1e-4):
    c = bearing.radial_clearance

    def excess(speed):
        omega = speed * math.pi / 30
        return c * omega**2 / G - critical_mass(bearing, speed, mu, kappa, eta, amplitude)

    f_low, f_high = excess(low), excess(high)
    if f_low > 0 or f_high < 0:
        return math.nan
    while high / low - 1 > rtol:
        mid = 0.5 * (low + high)
        if excess(mid) > 0:
            high = mid
        else:
            low = mid
    return 0.5 * (low + high)


def main():
    bearing = load_bearing(ROOT / "problems/bearings/ruscitto.toml")
    rows = []
    t0 = time.process_time()
    cases = [(0.0, 1.0, 0.0, 0.0), (0.0, 1.0, 0.2, 0.0)]
    for mu in (0.1, 0.3):
        for amp in (0.0, 0.05, 0.2, 0.5):
            cases.append((mu, 1.0, 0.0, amp))
    for mu, kappa, eta, amp in cases:
        speed = onset_speed(bearing, mu, kappa, eta, amp)
        rows.append({"friction_coefficient": mu, "friction_stiffness_ratio": kappa,
                     "loss_factor": eta, "orbit_amplitude": amp,
                     "orbit_amplitude_um": round(amp * bearing.radial_clearance * 1e6, 6),
                     "onset_speed_rpm": round(speed, 1)})
        print(rows[-1], flush=True)
    frame = pd.DataFrame(rows)
    frame.to_csv(HERE / "onset_speed.csv", index=False)
    kw = resolve_model_options(bearing.options).model_kwargs()
    omega = 60000.0 * math.pi / 30
    lines = []
    for mu in (0.1, 0.3):
        model = bearing.model(60000.0, **kw).replace(friction_coefficient=mu)
        sol = solve_static(model, load=bearing.nondimensional_load(LOAD_N), grid=GRID)
        orbit = settled_amplitude(linearise(sol), bearing.radial_clearance * omega**2 / G)
        lines.append(f"60,000 rpm, bearing A, μ_f = {mu}, κ = 1: {orbit.verdict}")
        print(lines[-1], flush=True)
    (HERE / "top_speed_verdict.txt").write_text("\n".join(lines) + "\n")
    print(f"{time.process_time() - t0:.1f} s CPU", file=sys.stderr)


if __name__ == "__main__":
    main()
