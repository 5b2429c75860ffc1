"""Results study: the Ruscitto bearing with and without growth and heating, over speed and
cooling flow → results/clearance_at_speed/ (table.csv, summary.json, figure).

Bearing: problems/bearings/ruscitto_thermal.toml (illustrative steel journal and
conductances; its [bearing] and [model] are problems/bearings/ruscitto.toml's), 20 N and
1.5 kg per bearing.  Models: isothermal (cold clearance), centrifugal growth only ([journal]),
heat balance + growth with a cooling flow of 0, 0.5 and 2 g/s through the bump channels
(inlet at ambient, fully mixed).  Per speed: the running condition, the equilibrium, the drag
and the linear stability; per model: the onset of whirl (5,000–60,000 rpm) and the load
capacity at 45,000 rpm for h_min = 5 µm.  The changes are reported, not asserted.

Usage::

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONPATH=. python \\
        benchmarks/study_clearance_at_speed.py [--grid 36x10] [--out results/clearance_at_speed]
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, tree_label  # noqa: E402
from gfbopt.cli.running import running_load_capacity, running_onset, running_stability
from gfbopt.inputs import Grid, OperatingPoint, Rotor
from gfbopt.static import SolverCache
from gfbopt.thermal.files import load_running_bearing

REPO = Path(__file__).resolve().parents[1]
ROTOR, LOAD = Rotor(1.5), 20.0
SPEEDS = [10e3, 15e3, 20e3, 25e3, 30e3, 35e3, 40e3, 45e3, 50e3, 55e3, 60e3]
ONSET_RANGE = (5000.0, 60000.0)


def models(spec):
    """label → RunningSpec."""
    out = {"isothermal": dataclasses.replace(spec, journal=None, thermal=None),
           "centrifugal": dataclasses.replace(spec, thermal=None)}
    for flow in (0.0, 0.5e-3, 2e-3):
        out[f"heat, cooling {flow * 1e3:g} g/s"] = dataclasses.replace(
            spec, thermal=dataclasses.replace(spec.thermal, cooling_mass_flow=flow))
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", default="36x10")
    parser.add_argument("--out", default=str(REPO / "results" / "clearance_at_speed"))
    args = parser.parse_args(argv)
    grid, out = Grid.parse(args.grid), Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    bearing, spec = load_running_bearing(REPO / "problems/bearings/ruscitto_thermal.toml")
    rows, summary, t0 = [], {}, time.process_time()
    for label, model in models(spec).items():
        cache = SolverCache(grid)
        for speed in SPEEDS:
            result, point, warm = running_stability(bearing, model, ROTOR,
                                                    OperatingPoint(speed, LOAD), grid=grid,
                                                    cache=cache)
            d = point.to_dict()
            row = {"model": label, "speed_rpm": speed, **{k: d[k] for k in (
                "thermal_model", "thermal_status", "running_clearance_um",
                "centrifugal_growth_um", "thermal_growth_um", "film_temperature_c",
                "journal_temperature_c", "sleeve_temperature_c", "viscosity_pa_s",
                "heat_generated_w", "heat_to_cooling_w", "heat_to_side_leakage_w",
                "thermal_static_solves")}}
            if result is not None:
                row.update(eccentricity=result.eccentricity,
                           min_film_thickness_um=result.min_film_thickness_um,
                           critical_mass_kg=result.critical_mass_kg,
                           mass_margin=result.mass_margin)
            rows.append(row)
            print(label, speed, d["thermal_status"], round(d["running_clearance_um"], 3),
                  flush=True)
        onset = running_onset(bearing, model, ROTOR, LOAD, ONSET_RANGE, grid=grid,
                              cache=cache)
        capacity = running_load_capacity(bearing, model, 45e3, 5.0, grid=grid, cache=cache)
        summary[label] = {"onset_speed_rpm": onset["onset_speed_rpm"],
                          "onset_answer": onset["answer"],
                          "load_capacity_45krpm_n": capacity["load_capacity_newton"],
                          "capacity_answer": capacity["answer"],
                          "capacity_running_clearance_um": capacity["running_clearance_um"]}
        print(label, summary[label], flush=True)
    table = pd.DataFrame(rows)
    table.to_csv(out / "table.csv", index=False)
    (out / "summary.json").write_text(json.dumps(
        {"machine": machine_info(), "code": tree_label(REPO), "grid": str(grid),
         "rotor_mass_kg": ROTOR.mass_kg, "load_newton": LOAD, "onset_range_rpm": ONSET_RANGE,
         "cpu_s": time.process_time() - t0, "models": summary}, indent=2, default=float))
    _figure(table, out / "clearance_at_speed.png")
    print(f"wrote {out}")
    return 0


def _figure(table, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for label, group in table.groupby("model", sort=False):
        left.plot(group["speed_rpm"], group["running_clearance_um"], marker="o", label=label)
        if group["film_temperature_c"].notna().any():
            right.plot(group["speed_rpm"], group["film_temperature_c"], marker="o",
                       label=f"film, {label}")
            right.plot(group["speed_rpm"], group["journal_temperature_c"], ls="--",
                       label=f"journal, {label}")
    left.set(xlabel="speed [rpm]", ylabel="running clearance [µm]",
             title="Ruscitto bearing, 20 N: clearance at speed")
    right.set(xlabel="speed [rpm]", ylabel="temperature [°C]", title="lumped heat balance")
    left.legend(fontsize=7)
    right.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
