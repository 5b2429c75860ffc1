"""The two-bearing rotor's onset search with each bearing at its running condition
(gfbopt.rotor.running) against the isothermal one: the blower (problems/rotors/blower.toml)
and its heated twin (blower_thermal.toml, the Ruscitto bearing's [journal] and [thermal]),
5,000–60,000 rpm, CPU seconds (time.process_time), single-threaded BLAS, A/B interleaved.

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python benchmarks/bench_rotor_running.py 72x20 3
"""
import json
import sys
import time
from pathlib import Path

from gfbopt.inputs import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.analyse import analyse_rotor

ROTORS = Path(__file__).resolve().parents[1] / "problems" / "rotors"


def one(name: str, grid: Grid) -> dict:
    system = load_rotor(ROTORS / f"{name}.toml", running=True)
    t = time.process_time()
    result = analyse_rotor(system, (5000.0, 60000.0), grid=grid, show_progress=False)
    cpu = time.process_time() - t
    d = result.to_dict()
    return {"cpu_s": cpu, "onset_speed_rpm": d["onset_speed_rpm"],
            "first_mode": d["first_mode"],
            "modes": {m["label"]: m["onset_speed_rpm"] for m in d["modes"]},
            "running_cost": d.get("running_cost"), "thermal_limits": d.get("thermal_limits"),
            "running_at_onset": {k: {c: v.get(c) for c in (
                "speed_rpm", "running_clearance_um", "centrifugal_growth_um",
                "thermal_growth_um", "film_temperature_c", "viscosity_pa_s")}
                for k, v in d.get("running_at_onset", {}).items()}}


def main(grid_text: str = "72x20", repeats: int = 3) -> dict:
    grid = Grid.parse(grid_text)
    one("blower", grid)                      # warm the imports and casadi builds
    one("blower_thermal", grid)
    pairs = []
    for _ in range(repeats):
        a = one("blower", grid)
        b = one("blower_thermal", grid)
        pairs.append((a["cpu_s"], b["cpu_s"]))
    ratios = sorted(b / a for a, b in pairs)
    return {"grid": grid_text, "pairs_cpu_s": pairs, "ratio_median": ratios[len(ratios) // 2],
            "isothermal": a, "heated": b}


if __name__ == "__main__":
    out = main(sys.argv[1] if len(sys.argv) > 1 else "72x20",
               int(sys.argv[2]) if len(sys.argv) > 2 else 3)
    print(json.dumps(out, indent=1, default=str))
