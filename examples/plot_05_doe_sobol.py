"""
Which input matters most? A design of experiments with Sobol indices and resume
===============================================================================

How much do the radial clearance, the bump pitch and the static load each explain of the
Ruscitto bearing's minimum film and drag at 30,000 rpm?  :func:`gfbopt.run_doe` runs *your*
function over a sample plan into a results store (Parquet parts written as they finish, so
a run killed with Ctrl-C, SIGTERM or ``kill -9`` keeps its finished points), and returns a
pandas table; run again, it computes only the points not yet stored.  A Saltelli plan gives
first-order and total Sobol indices (:func:`gfbopt.doe.sensitivity.sobol_indices`, SALib).

Small on purpose: 64 base samples × (3 + 2) = 320 static solves on a 24 × 8 grid.  The study
file route is ``kind = "sweep"`` (``problems/sweep_*.toml``, docs/doe.md).
"""
import dataclasses
import os
import shutil
import time
from pathlib import Path

import matplotlib.pyplot as plt

import gfbopt
from gfbopt.analyses import bearing_model, static_point
from gfbopt.doe import SamplePlan, Variable
from gfbopt.doe.sensitivity import sobol_indices
from gfbopt.plotting.doe import plot_sobol_indices

try:
    ROOT = Path(__file__).resolve().parents[1]      # python examples/THIS.py
except NameError:                                   # sphinx-gallery: run from examples/
    ROOT = Path.cwd().parent
OUT = Path(os.environ.get("GFBOPT_EXAMPLES_OUTPUT", ROOT / "runs" / "examples")) / "doe"
OUT.mkdir(parents=True, exist_ok=True)
BEARING = gfbopt.load_bearing(ROOT / "problems" / "bearings" / "ruscitto.toml")


# %%
# Your analysis: one point in, a dict of outputs out
# --------------------------------------------------
# A module-level function taking the inputs as keywords (and ``cache=``, the worker's solver
# cache: one CasADi build serves every point).
def film_and_drag(radial_clearance, bump_pitch, load_newton, speed_rpm, grid, cache=None):
    """Minimum film [µm] and power loss [W] of the Ruscitto bearing with this clearance [m]
    and bump pitch [m] under ``load_newton`` [N] at ``speed_rpm`` [rpm]."""
    bearing = dataclasses.replace(BEARING, radial_clearance=radial_clearance,
                                  bump_pitch=bump_pitch)
    row = static_point(bearing_model(bearing, speed_rpm),
                       load=bearing.nondimensional_load(load_newton),
                       grid=gfbopt.as_grid(grid), cache=cache, geometry=bearing)
    return {"min_film_thickness_um": row["min_film_thickness_um"],
            "power_loss_w": row["power_loss_w"], "success": row["success"]}


plan = SamplePlan((Variable("radial_clearance", 15e-6, 35e-6),
                   Variable("bump_pitch", 3.5e-3, 5.5e-3),
                   Variable("load_newton", 10.0, 60.0)), method="saltelli", n=64, seed=3)
store = OUT / "store"
kwargs = dict(fixed={"speed_rpm": 30000.0, "grid": "24x8"},
              outputs={"min_film_thickness_um": "float64", "power_loss_w": "float64"},
              version="film_and_drag 1", progress=False)

# %%
# Run it, then run it again: the second run resumes from the store
# -----------------------------------------------------------------
# The store is emptied first only so that this page starts afresh at every build; a rerun of
# your own script keeps it (``resume=True`` is the default; ``resume=False`` starts a new
# store and keeps the old one aside as ``store.previous-N``).
shutil.rmtree(store, ignore_errors=True)
t0 = time.process_time()
table = gfbopt.run_doe(film_and_drag, plan, store, **kwargs)
first = time.process_time() - t0
t0 = time.process_time()
again = gfbopt.run_doe(film_and_drag, plan, store, **kwargs)
second = time.process_time() - t0
print(f"{len(table)} points in {first:.1f} s CPU; run again: {len(again)} points, "
      f"{second:.2f} s CPU (nothing recomputed: the same table)")
assert again[["point", "power_loss_w"]].equals(table[["point", "power_loss_w"]])
print(table[["point", "radial_clearance", "bump_pitch", "load_newton",
             "min_film_thickness_um", "power_loss_w"]].head().to_string(index=False))

# %%
# Sobol indices
# -------------
# First-order S1 (what the input explains alone) and total ST (with its interactions), with
# 95 % bootstrap intervals — still wide at 64 base samples: a real study takes 256 or more.
fig, axes = plt.subplots(1, 2, layout="constrained", figsize=(10, 4.0))
for ax, output in zip(axes, ("min_film_thickness_um", "power_loss_w")):
    indices = sobol_indices(plan, table, output)
    print(output, indices.table.round(2).to_string(index=False), sep="\n")
    plot_sobol_indices(indices.table, ax=ax, output=output)
fig.suptitle("Sobol indices at 30,000 rpm (Saltelli, N = 64, 24x8 grid)")
fig.savefig(OUT / "sobol_indices.png", dpi=110)

# %%
# The scatter behind them
# -----------------------
fig, ax = plt.subplots(layout="constrained", figsize=(6.4, 4.2))
points = ax.scatter(table["radial_clearance"] * 1e6, table["power_loss_w"],
                    c=table["load_newton"], cmap="viridis", s=18)
fig.colorbar(points, ax=ax, label="static load [N]")
ax.set_xlabel("radial clearance [µm]")
ax.set_ylabel("power loss [W]")
ax.set_title("drag at 30,000 rpm over the Saltelli points")
ax.grid(alpha=0.3)
fig.savefig(OUT / "power_loss_scatter.png", dpi=110)
