"""
What does my rotor do when it runs up through its onset? (run-up waterfall)
===========================================================================

The linear onset says from what speed the blower rotor (``problems/rotors/blower.toml``)
whirls; the rotor in time on both bearing films says what it then does.
:func:`gfbopt.rotor_ramp` runs it up at a constant rate with the rotor file's imbalance,
integrating the rigid rotor and both Reynolds films together (stabilised Runge–Kutta–
Chebyshev), and turns the record into a waterfall per bearing: the synchronous 1× line,
and the subsynchronous whirl appearing near the linear onset.  This is ``gfbopt rotor
problems/rotors/blower.toml --run-up 8000 20000 --rate 25000 --grid 36x10 --plot DIR``.

A short run-up on a coarse 36 × 10 grid, to build in seconds; the shipped
``results/rotor_run_up`` runs up to 60,000 rpm at 36 × 10, where the subsynchronous line
appears from 18,575 rpm and the film closes at 20,082 rpm.
"""
import math
import os
from pathlib import Path

import matplotlib.pyplot as plt

import gfbopt
from gfbopt.plotting.waterfall import plot_components, plot_waterfall

try:
    ROOT = Path(__file__).resolve().parents[1]      # python examples/THIS.py
except NameError:                                   # sphinx-gallery: run from examples/
    ROOT = Path.cwd().parent
OUT = Path(os.environ.get("GFBOPT_EXAMPLES_OUTPUT", ROOT / "runs" / "examples")) / "run_up"
OUT.mkdir(parents=True, exist_ok=True)
GRID = "36x10"

# %%
# The run-up
# ----------
# 8,000 → 20,000 rpm at 25,000 rpm/s (0.48 s of rotor time), from the equilibrium at the
# start speed, with the imbalance planes of the rotor file.
system = gfbopt.load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
result = gfbopt.rotor_ramp(system, 8000.0, 20000.0, 25000.0, grid=GRID)
summary = result.to_dict()
linear = result.onset.get("linear_onset_speed_rpm", math.nan)
print(f"linear onset {linear:,.0f} rpm")
for name in result.names:
    appears = result.onset.get(f"subsync_appearance_{name}_rpm", math.nan)
    print(f"bearing {name}: subsynchronous line from {appears:,.0f} rpm")
if summary["contact"]:
    print(f"the film closes at bearing {summary['contact_bearing']} at "
          f"{summary['contact_speed_rpm']:,.0f} rpm: the run stops there (contact is an answer)")

# %%
# The waterfall at each bearing
# -----------------------------
# Amplitude [µm, log colour] against whirl frequency [Hz] and shaft speed [rpm]; the dashed
# line is the linear onset, the dotted one where the subsynchronous line appears.
fig, axes = plt.subplots(1, len(result.names), layout="constrained", figsize=(11, 4.6))
for ax, name, waterfall in zip(axes, result.names, result.waterfalls[0]):
    plot_waterfall(waterfall, ax=ax, bearing=name, linear_onset_rpm=linear,
                   appearance_rpm=result.onset.get(f"subsync_appearance_{name}_rpm", math.nan),
                   title=f"waterfall at bearing {name} ({GRID} grid)")
fig.savefig(OUT / "waterfall.png", dpi=110)

# %%
# The 1× and subsynchronous components against speed
# ---------------------------------------------------
tables = {name: w.table() for name, w in zip(result.names, result.waterfalls[0])
          if w.time_s.size}
fig, axes = plt.subplots(2, 1, layout="constrained", figsize=(6.6, 6.4), sharex=True)
plot_components(tables, axes=axes, linear_onset_rpm=linear,
                threshold_um=result.onset.get("subsync_threshold_um", math.nan),
                title="1× and subsynchronous components, run-up 8,000 → 20,000 rpm")
fig.savefig(OUT / "components.png", dpi=110)
