"""Results study: the blower rotor on two heated Ruscitto bearings over the cooling flow
→ results/blower_cooling/ (speeds.csv, onsets.csv, limits.csv, summary.json, figure).

Rotor: problems/rotors/blower_thermal.toml (3.2 kg, CG 35/65 mm from bearings A/B; both
bearings problems/bearings/ruscitto_thermal.toml: ILLUSTRATIVE solid steel journal and lumped
conductances, not from the source).  Variants: the same rotor isothermal at the cold
clearance (problems/rotors/blower.toml), with the journal's centrifugal growth only
([journal]), and with the heat balance + growth at cooling flows of 0, 0.5, 1, 2 and 5 g/s
through each bearing's bump channels (inlet at ambient, the flow leaving fully mixed at the
foil temperature: the file's defaults; only ``cooling_mass_flow`` changes).  Per variant:
the onset of every mode (gfbopt.rotor.system.rotor_onsets, matched whirl, 4,000–60,000 rpm),
each bearing's running point (running clearance, film temperature, drag power, minimum film)
at each mode's onset, on a speed line 4,000–60,000 rpm and at the top speed 60,000 rpm, and
the speed from which a bearing runs away (gfbopt.rotor.running.runaway_limits, bracketed to
1 %).  The changes are reported, not asserted: no input is tuned.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 PYTHONPATH=. python \\
        benchmarks/study_blower_cooling.py [--grid 72x20] [--out results/blower_cooling]
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
import time
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))  # noqa: E402
from machine import machine_info, tree_label  # noqa: E402
from gfbopt.inputs import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.physics.torque import drag_torque_and_power
from gfbopt.rotor.running import running_summary
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine, rotor_onsets

REPO = Path(__file__).resolve().parents[1]
ROTORS = REPO / "problems" / "rotors"
SPEED_RANGE = (4000.0, 60000.0)
TOP_SPEED = 60000.0
SPEEDS = [4000.0 * k for k in range(1, 16)]          # 4,000 ... 60,000 rpm
FLOWS_G_S = (0.0, 0.5, 1.0, 2.0, 5.0)
#: the design study's film limit (problems/rotor_bearing_design.toml min_film_um), drawn
FILM_LIMIT_UM = 1.5


def _replace_tables(system, keep):
    """The rotor with each bearing's running tables filtered/changed by ``keep(name, items)``
    → items or None (table dropped)."""
    bearings = []
    for b in system.bearings:
        tables = tuple((name, out) for name, items in b.running_tables
                       if (out := keep(name, items)) is not None)
        bearings.append(dataclasses.replace(b, running_tables=tables))
    return dataclasses.replace(system, bearings=tuple(bearings))


def variants():
    """[(variant label, cooling flow [kg/s] or nan, RotorSystem)]."""
    heated = load_rotor(ROTORS / "blower_thermal.toml", running=True)
    out = [("isothermal, cold clearance", math.nan,
            load_rotor(ROTORS / "blower.toml", running=True)),
           ("centrifugal growth only", math.nan,
            _replace_tables(heated, lambda n, items: items if n == "journal" else None))]
    for g in FLOWS_G_S:
        flow = g * 1e-3

        def keep(name, items, flow=flow):
            if name != "thermal":
                return items
            return tuple((k, flow if k == "cooling_mass_flow" else v) for k, v in items)
        label = "heat balance, no cooling flow" if g == 0 else f"heat balance, cooling {g:g} g/s"
        out.append((label, flow, _replace_tables(heated, keep)))
    return out


def bearing_rows(line, speed, variant, flow):
    """One row per bearing at ``speed``: its running point (if any) and equilibrium."""
    st = line.states(speed)
    run = line.rotor.running
    rows = []
    for k, name in enumerate(line.rotor.names):
        row = {"variant": variant, "cooling_mass_flow_kg_s": flow, "speed_rpm": speed,
               "bearing": name, "load_newton": line.rotor.loads[k].magnitude}
        point = run.at(line.rotor.grid, k, speed) if run is not None else None
        if point is not None:
            d = point.to_dict()
            row.update({c: d[c] for c in (
                "thermal_model", "thermal_status", "running_clearance_um",
                "centrifugal_growth_um", "thermal_growth_um", "film_temperature_c",
                "journal_temperature_c", "sleeve_temperature_c", "viscosity_pa_s",
                "heat_to_cooling_w")})
        else:
            row.update(thermal_model="isothermal, cold clearance", thermal_status="running",
                       running_clearance_um=line.rotor.cases[k].bearing.radial_clearance * 1e6)
        s = st.states[k]
        if s is not None:
            sol = s.solution
            _, power = drag_torque_and_power(sol.torque_ratio, sol.model.bearing_number,
                                             s.case.bearing)
            row.update(eccentricity=sol.eccentricity, power_loss_w=power,
                       min_film_thickness_um=sol.min_film * s.case.bearing.radial_clearance
                       * 1e6)
        rows.append(row)
    return rows


def study_variant(label, flow, system, grid):
    t0 = time.process_time()
    line = SpeedLine(resolve_rotor(system, grid))
    onsets = rotor_onsets(system, SPEED_RANGE, line=line, show_progress=False)
    speeds = []
    for speed in SPEEDS:
        speeds += bearing_rows(line, speed, label, flow)
    onset_rows = []
    for m in onsets.modes:
        base = {"variant": label, "cooling_mass_flow_kg_s": flow, "label": m.label,
                "onset_speed_rpm": m.onset_speed_rpm, "whirl_frequency_hz":
                m.whirl_frequency_hz}
        if not math.isfinite(m.onset_speed_rpm):
            onset_rows.append(base)
            continue
        for r in bearing_rows(line, m.onset_speed_rpm, label, flow):
            onset_rows.append({**base, **{c: r.get(c, math.nan) for c in (
                "bearing", "running_clearance_um", "film_temperature_c", "power_loss_w",
                "min_film_thickness_um")}})
    run = running_summary(line, onsets.onset_speed_rpm)
    limits = []
    for k, name in enumerate(line.rotor.names):
        found = [x for x in (run["thermal_limits"] if run else []) if x["bearing"] == name]
        limits.append({"variant": label, "cooling_mass_flow_kg_s": flow, "bearing": name,
                       "limit_rpm": found[0]["limit_rpm"] if found else math.nan,
                       "kind": found[0]["kind"] if found else "",
                       "last_running_rpm": found[0]["last_running_rpm"] if found else math.nan,
                       "first_failing_rpm": (found[0]["first_failing_rpm"] if found
                                             else math.nan)})
    cost = ({k: run[k] for k in ("fixed_points", "static_solves", "max_static_solves")}
            if run else {})
    summary = {"first_mode": onsets.first_mode, "first_onset_speed_rpm":
               onsets.onset_speed_rpm, "cooling_mass_flow_kg_s": flow,
               "thermal_models": run["thermal_models"] if run else "isothermal, cold clearance",
               "running_cost": cost, "cpu_s": time.process_time() - t0}
    print(label, f"first onset {onsets.onset_speed_rpm:,.1f} rpm ({onsets.first_mode}),",
          [(x["bearing"], x["limit_rpm"]) for x in limits], f"{summary['cpu_s']:.1f} s CPU",
          flush=True)
    return speeds, onset_rows, limits, summary


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", default="72x20")
    parser.add_argument("--out", default=str(REPO / "results" / "blower_cooling"))
    args = parser.parse_args(argv)
    grid, out = Grid.parse(args.grid), Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    speeds, onsets, limits, summary, t0 = [], [], [], {}, time.process_time()
    for label, flow, system in variants():
        s, o, lim, summ = study_variant(label, flow, system, grid)
        speeds += s
        onsets += o
        limits += lim
        summary[label] = summ
    tables = {"speeds.csv": pd.DataFrame(speeds), "onsets.csv": pd.DataFrame(onsets),
              "limits.csv": pd.DataFrame(limits)}
    for name, table in tables.items():
        table.to_csv(out / name, index=False, float_format="%.7g")
    (out / "summary.json").write_text(json.dumps(
        {"machine": machine_info(), "code": tree_label(REPO), "grid": str(grid),
         "rotor_file": "problems/rotors/blower_thermal.toml",
         "speed_range_rpm": SPEED_RANGE, "top_speed_rpm": TOP_SPEED,
         "cpu_s": time.process_time() - t0, "variants": summary}, indent=2, default=float))
    _figure(tables["speeds.csv"], out / "clearance_and_temperature.png", grid,
            tables["limits.csv"], [v["first_onset_speed_rpm"] for v in summary.values()])
    print(f"wrote {out} in {time.process_time() - t0:.1f} s CPU")
    return 0


def _figure(table, path, grid, limits, first_onsets):
    """Running clearance, minimum film and film temperature against speed: one colour per
    variant, solid bearing A, dashed bearing B; × where a bearing runs away (its bracketed
    speed, at its last running value); the top speed, the first onsets and the design
    study's film limit drawn."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    fig, axes = plt.subplots(1, 3, figsize=(15, 5))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    styles = {"A": "-", "B": "--"}
    columns = ("running_clearance_um", "min_film_thickness_um", "film_temperature_c")
    handles = []
    for (label, group), colour in zip(table.groupby("variant", sort=False), colours):
        handles.append(Line2D([], [], color=colour, marker="o", ms=3, label=label))
        for name, g in group.groupby("bearing"):
            for ax, column in zip(axes, columns):
                if g[column].notna().any():
                    ax.plot(g["speed_rpm"], g[column], color=colour,
                            ls=styles.get(name, ":"), marker="o", ms=3)
            lim = limits[(limits["variant"] == label) & (limits["bearing"] == name)]
            if len(lim) and pd.notna(lim["limit_rpm"].iloc[0]):
                last = g[g["running_clearance_um"].notna()].iloc[-1]
                for ax, column in zip(axes, columns):
                    ax.plot([lim["limit_rpm"].iloc[0]], [last[column]], "x", color=colour,
                            ms=9, mew=2)
    low, high = min(first_onsets), max(first_onsets)
    for ax in axes:
        ax.axvline(TOP_SPEED, color="k", lw=0.8, ls=":")
        ax.text(TOP_SPEED, 0.02, "top speed ", transform=ax.get_xaxis_transform(),
                ha="right", va="bottom", fontsize=7)
        ax.axvspan(low * 0.995, high * 1.005, color="0.8")
        ax.text(high * 1.02, 0.02, f"first onset {low:,.0f}–{high:,.0f} rpm",
                transform=ax.get_xaxis_transform(), fontsize=7, va="bottom")
        ax.set_xlabel("speed [rpm]")
    axes[1].axhline(FILM_LIMIT_UM, color="r", lw=0.8)
    axes[1].text(SPEED_RANGE[0], FILM_LIMIT_UM, " film limit 1.5 µm (the design study's)",
                 color="r", va="bottom", fontsize=7)
    axes[1].set_ylim(bottom=0)
    axes[0].set(ylabel="running radial clearance [µm]",
                title="Running clearance (cold 20 µm)")
    axes[1].set(ylabel="minimum film thickness [µm]", title="Minimum film")
    axes[2].set(ylabel="mean film temperature [°C]",
                title="Film temperature (lumped heat balance)")
    loads = table.groupby("bearing")["load_newton"].first()
    handles += [Line2D([], [], color="k", ls=styles.get(n, ":"),
                       label=f"bearing {n} ({w:.1f} N)") for n, w in loads.items()]
    handles += [Line2D([], [], color="k", ls="", marker="x", ms=8, mew=2,
                       label="thermal runaway from (bracketed)")]
    axes[2].legend(handles=handles, fontsize=7, loc="upper left")
    fig.suptitle(f"Blower rotor (3.2 kg) on two heated Ruscitto bearings over the cooling "
                 f"flow through the bump channels, grid {grid}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
