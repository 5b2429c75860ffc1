"""The rotor on two bearings whose bumps rub, in time: where the whirl above the onset ends.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python results/rotor_friction_transient/run.py

Writes ``cases.csv`` (one row per case and bearing) and ``summary.json`` beside this file.
Every run is ``gfbopt.transient.rotor_orbit`` (the command line's ``gfbopt rotor --orbit``):
the rotor's transient with each bearing's sliders integrated (gfbopt.transient.rotor_friction),
rkc, cylindrical kick 1e-3, the rotor file's imbalance.  Cases:

* ``symmetric``: two identical Ruscitto bearings (S = 1, μ_f = 0.05, κ = 2, 60 N each from a
  side load at the CG, no gravity, no gyroscopics), M̄ = 8 per bearing at 15,000 rpm, 24 × 8,
  80 revolutions, kick 0.03: the one-bearing problem exactly, beside the one-bearing friction
  transient (gfbopt.transient.friction_orbit) and the rotor's describing function
  (gfbopt.rotor.friction_onset.settled_whirl);
* ``blower``: problems/rotors/blower_friction.toml (μ_f = 0.5, κ = 2, assumed values) at
  13,500 rpm (just above its onset) and 60,000 rpm (its top speed), 72 × 20, beside
  problems/rotors/blower.toml (the same without friction) and the describing function; at
  13,500 rpm also at half the step (Δτ = 0.05), on 36 × 10, and without the imbalance (the
  self-excited whirl alone).
"""
from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import json  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from dataclasses import replace  # noqa: E402
from pathlib import Path  # noqa: E402

import pandas as pd  # noqa: E402
from scipy.optimize import brentq  # noqa: E402

from gfbopt.inputs import Grid  # noqa: E402
from gfbopt.inputs.bearing_file import load_bearing  # noqa: E402
from gfbopt.inputs.rotor_system import load_rotor, rotor_from_dict  # noqa: E402
from gfbopt.rotor.friction_onset import settled_whirl  # noqa: E402
from gfbopt.rotor.supports import resolve_rotor  # noqa: E402
from gfbopt.rotor.system import without_gyroscopics  # noqa: E402
from gfbopt.transient.friction_orbit import friction_outcome  # noqa: E402
from gfbopt.transient.friction_orbit import integrate_friction_orbits  # noqa: E402
from gfbopt.transient.rotor_analysis import rotor_orbit  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
ROTORS = ROOT / "problems" / "rotors"


def symmetric_system():
    geometry = load_bearing(ROOT / "problems/bearings/ruscitto.toml")
    thickness = brentq(lambda t: replace(geometry, bump_thickness=t).compliance - 1.0,
                       40e-6, 300e-6, xtol=1e-16)
    omega = 15000.0 * math.pi / 30
    half = 8.0 * 60.0 / (20e-6 * omega ** 2)
    model = {"friction_coefficient": 0.05, "friction_stiffness_ratio": 2.0}
    file = str(ROOT / "problems/bearings/ruscitto.toml")
    system = rotor_from_dict({
        "rotor": {"mass": 2 * half, "transverse_inertia": 0.01, "polar_inertia": 0.001,
                  "gravity": 0.0},
        "side_loads": [{"force": 120.0, "direction_deg": 0.0, "position": 0.0}],
        "bearings": [{"file": file, "position": -0.05, "model": model},
                     {"file": file, "position": 0.05, "model": model}]})
    return replace(without_gyroscopics(system), bearings=tuple(
        replace(b, geometry=replace(b.geometry, bump_thickness=thickness))
        for b in system.bearings))


def orbit_rows(case, system, speed, revolutions, grid, **options):
    t0 = time.process_time()
    result = rotor_orbit(system, speed, revolutions, grid=Grid.parse(grid), **options)
    cpu = time.process_time() - t0
    d = result.to_dict()
    rows = []
    for b in d["bearings"]:
        rows.append({"case": case, "grid": grid, "speed_rpm": speed,
                     "time_step_rad": d["time_step_rad"],
                     "bump_friction": bool(d.get("bump_friction")), "bearing": b["bearing"],
                     "ended": b.get("friction_orbit_kind",
                                    "contact" if d["contact"] else b.get("limit_cycle_status")),
                     "amplitude_um": b.get("friction_orbit_amplitude_um"),
                     "whirl_frequency_hz": b.get("friction_orbit_whirl_frequency_hz"),
                     "whirl_ratio": b.get("friction_orbit_whirl_ratio"),
                     "static_min_film_um": b["min_film_thickness_um"],
                     "min_film_um": b["min_film_um"],
                     "contact_time_ms": (d["contact_time_s"] * 1e3 if d["contact"] else None),
                     "revolutions_integrated": d["revolutions_integrated"], "cpu_s": cpu})
    return rows


def main() -> None:
    rows, summary = [], {}
    # the symmetric rotor against the one-bearing transient and the describing function
    system = symmetric_system()
    rows += orbit_rows("symmetric", system, 15000.0, 80, "24x8", kick=0.03, time_step=0.1,
                       imbalance_scale=0.0)
    resolved = resolve_rotor(system, Grid(24, 8))
    from gfbopt.transient.rotor_io import rotor_input
    from gfbopt.transient.rotor_setup import build_model

    tm = build_model(rotor_input(system), 15000.0, Grid(24, 8))[0].bearings[0].tm
    one = friction_outcome(integrate_friction_orbits(tm, [8.0], 80.0, kick=0.03, method="rkc",
                                                     time_step=0.1).orbit)
    df = settled_whirl(resolved, 15000.0)
    summary["symmetric"] = {"one_bearing": one.verdict,
                            "one_bearing_amplitude_um": one.amplitude * 20.0,
                            "one_bearing_whirl_ratio": one.whirl_ratio,
                            "describing_function": df.verdict,
                            "describing_function_amplitude_um": list(df.amplitude_um),
                            "describing_function_whirl_ratio": df.whirl_ratio}
    # the blower on rubbing bumps and on plain bumps
    rub, bare = load_rotor(ROTORS / "blower_friction.toml"), load_rotor(ROTORS / "blower.toml")
    for speed in (13500.0, 60000.0):
        rows += orbit_rows("blower_friction", rub, speed, 400, "72x20")
        rows += orbit_rows("blower", bare, speed, 400, "72x20")
        df = settled_whirl(resolve_rotor(rub, Grid(72, 20)), speed)
        summary[f"describing_function_{speed:.0f}_rpm"] = {
            "verdict": df.verdict, "mode": df.label,
            "small_motion_inertia_scale": df.small_motion_inertia_scale}
    rows += orbit_rows("blower_friction half step", rub, 13500.0, 400, "72x20", time_step=0.05)
    rows += orbit_rows("blower_friction", rub, 13500.0, 400, "36x10")
    for grid in ("72x20", "36x10"):            # the self-excited whirl alone (no 1x forcing)
        rows += orbit_rows("blower_friction no imbalance", rub, 13500.0, 400, grid,
                           imbalance_scale=0.0)
    df = settled_whirl(resolve_rotor(rub, Grid(36, 10)), 13500.0)
    summary["describing_function_13500_rpm_36x10"] = {
        "verdict": df.verdict, "mode": df.label,
        "small_motion_inertia_scale": df.small_motion_inertia_scale,
        "inertia_scale_at_film_share_1": df.inertia_scale}
    table = pd.DataFrame(rows)
    table.to_csv(HERE / "cases.csv", index=False, float_format="%.6g")
    (HERE / "summary.json").write_text(json.dumps(summary, indent=2, default=float))
    with pd.option_context("display.width", 200, "display.max_columns", 20):
        print(table)
    print(json.dumps(summary, indent=2, default=float))


if __name__ == "__main__":
    sys.exit(main())
