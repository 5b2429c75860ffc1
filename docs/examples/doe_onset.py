"""A design of experiments from a Python script: the onset speed of whirl of a 2 kg rotor on
the Ruscitto bearing over a Latin hypercube of radial clearance and bump pitch, into a
results store that survives Ctrl-C, SIGTERM and ``kill -9`` (docs/doe.md).

    python docs/examples/doe_onset.py                      # runs/doe_onset, grid 36x10
    python docs/examples/doe_onset.py runs/x --grid 12x4   # coarse and quick

Run it again after an interruption: it computes only the points not yet stored and returns
the whole table, every point once.
"""
import argparse
import dataclasses
from pathlib import Path

from gfbopt.doe import SamplePlan, Variable, run_doe
from gfbopt.inputs import Grid, Rotor, load_bearing_file
from gfbopt.rotor import onset_speed

BEARING = Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto.toml"


def onset(radial_clearance, bump_pitch, grid, cache=None):
    """One point: the onset speed [rpm] and whirl frequency [Hz] (module level, so the
    worker processes can import it; ``cache`` is the worker's solver cache)."""
    bearing, options = load_bearing_file(BEARING)
    bearing = dataclasses.replace(bearing, radial_clearance=radial_clearance,
                                  bump_pitch=bump_pitch)
    result = onset_speed(bearing, Rotor(2.0), None, (9000.0, 15000.0), options=options,
                         grid=Grid.parse(grid), cache=cache)
    return {"onset_speed_rpm": result.onset_speed_rpm,
            "whirl_frequency_hz": result.whirl_frequency_hz,
            "success": result.success, "message": result.message}


if __name__ == "__main__":                     # the workers are spawned: guard the top level
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("store", nargs="?", default="runs/doe_onset")
    parser.add_argument("--grid", default="36x10")
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    plan = SamplePlan((Variable("radial_clearance", 25e-6, 35e-6),
                       Variable("bump_pitch", 4.0e-3, 5.0e-3)), method="lhs", n=20, seed=7)
    frame = run_doe(onset, plan, args.store, fixed={"grid": args.grid},
                    outputs={"onset_speed_rpm": "float64", "whirl_frequency_hz": "float64"},
                    workers=args.workers, chunk_size=1, batch_rows=1)
    print(frame[["point", "radial_clearance", "bump_pitch", "onset_speed_rpm",
                 "success"]].to_string(index=False))
