"""A slow run-up of the blower, cold (blower.toml) against heated (blower_thermal.toml: each
bearing on its running line, quasi-steady in temperature): the 1× peak and the speed where
the subsynchronous line appears, per bearing, and the CPU of each (reported, no
direction asserted).

    python benchmarks/bench_heated_rampup.py --grid 36x10 --start 8000 --end 16000 --rate 10000
"""
from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

import numpy as np

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from gfbopt.inputs.rotor_system import load_rotor  # noqa: E402
from gfbopt.transient.rotor_analysis import rotor_ramp  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def run(path, running: bool, args) -> dict:
    system = load_rotor(ROOT / "problems" / "rotors" / path, running=running)
    t = time.process_time()
    result = rotor_ramp(system, args.start, args.end, args.rate, grid=args.grid,
                        linear_onset=False)
    cpu = time.process_time() - t
    d = result.to_dict()
    out = {"cpu_s": cpu, "success": d["success"], "contact": d["contact"],
           "end_speed_rpm": d["end_speed_rpm"], "revolutions": d["revolutions_integrated"],
           "clearance_model": d.get("clearance_model", "isothermal, cold clearance"),
           "subsync_appearance_rpm": d.get("subsync_appearance_rpm")}
    for b in d["bearings"]:
        out[f"peak_amplitude_um_{b['bearing']}"] = b.get("peak_amplitude_um")
        out[f"peak_speed_rpm_{b['bearing']}"] = b.get("peak_speed_rpm")
        out[f"subsync_appearance_rpm_{b['bearing']}"] = d.get(
            f"subsync_appearance_{b['bearing']}_rpm")
    for name, table in result.tables().items():       # the 1× amplitude at stated speeds
        if name.startswith("components_"):
            bearing = name[len("components_"):-4]
            for n in args.at:          # linear between the windows around it
                out[f"sync_amplitude_um_{bearing}_at_{n:.0f}"] = float(np.interp(
                    n, table["speed_rpm"], table["sync_amplitude_um"], np.nan, np.nan))
    if running:
        out["running_nodes"] = d["running_nodes"]
        out["running_interpolation_error"] = d["running_interpolation_error"]
        out["running_line_ends"] = d["running_line"][-1]
    return out


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--grid", default="36x10")
    p.add_argument("--start", type=float, default=8000.0)
    p.add_argument("--end", type=float, default=16000.0)
    p.add_argument("--rate", type=float, default=10000.0)
    p.add_argument("--at", type=float, nargs="*", default=[9000.0, 11000.0, 13000.0],
                   help="speeds at which the 1x amplitude is reported [rpm]")
    p.add_argument("--out", default=str(ROOT / "results" / "heated_rampup" / "summary.json"))
    args = p.parse_args()
    summary = {"grid": args.grid, "start_rpm": args.start, "end_rpm": args.end,
               "rate_rpm_per_s": args.rate,
               "cold": run("blower.toml", False, args),
               "heated": run("blower_thermal.toml", True, args)}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(summary, indent=1, default=str))
    print(json.dumps(summary, indent=1, default=str))


if __name__ == "__main__":
    main()
