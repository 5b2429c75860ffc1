"""The rotor's settled whirl above its small-motion onset with rubbing bumps (bumps that rub,
gfbopt.rotor.friction_onset.settled_whirl), 36 x 10:

* the blower rotor (problems/rotors/blower_friction.toml) at speeds just above its stuck onset
  and at its top speed 60,000 rpm, for three friction settings (μ_f, κ) = (0.2, 1), (0.5, 2),
  (0.9, 5). The largest is μ_f = 0.9, not 1: the model needs 0 ≤ μ_f < 1 (the slipping foil's
  balance W = S(1 − μ_f) q; at μ_f ≥ 1 friction alone would carry the pressure), and gfbopt
  refuses μ_f ≥ 1 at file read and in BearingModel;
* the planted symmetric rotor of tests/verification/test_rotor_friction_orbit.py (two S = 3
  bearings, μ_f = 0.5, κ = 2, 20 N each, 15,000 rpm, M̄ = 4.145 per bearing) beside the
  one-bearing describing function it must reproduce.

Where the describing function finds no bounded orbit (bounded False) the row leaves
settled_orbit_um, settled_whirl_hz and settled_min_film_um empty (NaN), as
gfbopt.design.robustness does.

Run: OMP_NUM_THREADS=1 PYTHONPATH=. python results/bumps_that_rub/rotor_settled_whirl.py
(writes rotor_settled_whirl.csv next to this file)
"""
import math
import sys
import time
from dataclasses import replace
from pathlib import Path

import pandas as pd

from gfbopt.inputs import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.linear.friction_onset import settled_amplitude
from gfbopt.rotor.friction_onset import settled_whirl
from gfbopt.rotor.supports import resolve_rotor

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "tests" / "verification"))
GRID = Grid(36, 10)


def rows_of(case, out, cpu):
    bounded = bool(out.bounded)
    return [{**case, "bearing": b, "settled_orbit_um": float(a) if bounded else math.nan,
             "settled_whirl_hz": float(out.whirl_frequency_hz) if bounded else math.nan,
             "settled_min_film_um": float(out.min_film_um) if bounded else math.nan,
             "small_motion_inertia_scale": float(out.small_motion_inertia_scale),
             "settled_inertia_scale": float(out.inertia_scale), "film_share": out.film_share,
             "bounded": bounded, "friction_verdict": out.verdict,
             "friction_model": out.model, "cpu_s": cpu}
            for b, a in zip(out.bearings, out.amplitude_um)]


def main():
    rows = []
    blower = load_rotor(ROOT / "problems" / "rotors" / "blower_friction.toml")
    for mu, kappa in ((0.2, 1.0), (0.5, 2.0), (0.9, 5.0)):
        system = replace(blower, bearings=tuple(replace(b, options=replace(
            b.options, friction_coefficient=mu, friction_stiffness_ratio=kappa))
            for b in blower.bearings))
        rotor = resolve_rotor(system, GRID)
        for speed in (12950.0, 13500.0, 60000.0):
            t = time.process_time()
            out = settled_whirl(rotor, speed)
            rows += rows_of({"rotor": "blower_friction", "friction_coefficient": mu,
                             "friction_stiffness_ratio": kappa, "speed_rpm": speed}, out,
                            time.process_time() - t)
    from test_rotor_friction_orbit import CLEARANCE, SPEED, _rotor

    rotor, states = _rotor(4.145)
    t = time.process_time()
    out = settled_whirl(rotor, SPEED, states=states)
    rows += rows_of({"rotor": "planted symmetric (S = 3)", "friction_coefficient": 0.5,
                     "friction_stiffness_ratio": 2.0, "speed_rpm": SPEED}, out,
                    time.process_time() - t)
    one = settled_amplitude(states.states[0].linearisation, 4.145, samples=10,
                            smallest=1e-2, xtol=1e-4)
    table = pd.DataFrame(rows)
    table.to_csv(HERE / "rotor_settled_whirl.csv", index=False)
    for _, r in table.iterrows():
        print(f"{r['rotor']}, mu_f={r['friction_coefficient']:g}, kappa="
              f"{r['friction_stiffness_ratio']:g}, {r['speed_rpm']:,.0f} rpm, bearing "
              f"{r['bearing']}: mu_c {r['small_motion_inertia_scale']:.4f} -> "
              f"{r['settled_inertia_scale']:.4f}; {r['friction_verdict']}")
    print(f"one-bearing describing function of the planted case: A = {one.amplitude:.7f} c = "
          f"{one.amplitude * CLEARANCE * 1e6:.4f} um at gamma {one.whirl_ratio:.7f}; rotor: "
          f"{out.amplitude_um[0]:.4f} um at gamma {out.whirl_ratio:.7f}")


if __name__ == "__main__":
    main()
