"""
Which mode of my rotor whirls first, and from what speed? (Campbell diagram)
============================================================================

The 3.2 kg blower rotor of ``problems/rotors/blower.toml``: rigid, on two Ruscitto foil
bearings 35 mm and 65 mm from its centre of gravity, translating and tilting with
gyroscopic coupling.  :func:`gfbopt.analyse_rotor` is what ``gfbopt rotor`` answers: the
matched-whirl onset of every mode along the speed line, and on request the Campbell diagram
(damped natural frequencies and log decrements over speed) and the imbalance response.

The grid is a coarse 36 × 10 to run in seconds; the shipped ``results/rotor_blower`` is at
72 × 20, where the forward conical mode whirls first from about 12,000 rpm.
"""
import os
from pathlib import Path

import matplotlib.pyplot as plt

import gfbopt
from gfbopt.plotting.rotor import plot_campbell, plot_imbalance_response

try:
    ROOT = Path(__file__).resolve().parents[1]      # python examples/THIS.py
except NameError:                                   # sphinx-gallery: run from examples/
    ROOT = Path.cwd().parent
OUT = Path(os.environ.get("GFBOPT_EXAMPLES_OUTPUT", ROOT / "runs" / "examples")) / "campbell"
OUT.mkdir(parents=True, exist_ok=True)
GRID = "36x10"

# %%
# The rotor file and the onsets
# -----------------------------
# :func:`gfbopt.load_rotor` reads the rotor file (mass, inertias, the two bearing files and
# their axial positions, imbalance planes) and checks it before anything is solved.
system = gfbopt.load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
print(system.body)
analysis = gfbopt.analyse_rotor(system, (5000.0, 30000.0), campbell=True, imbalance=True,
                                grid=GRID, campbell_speeds=6, imbalance_speeds=8,
                                show_progress=False)
for mode in analysis.onsets.modes:
    where = (f"onset {mode.onset_speed_rpm:8,.0f} rpm" if mode.onset_speed_rpm > 0
             else "no onset in 5,000-30,000 rpm")
    print(f"{mode.label:>20s}: {where}, whirl {mode.whirl_frequency_hz:6.1f} Hz")
first = analysis.onsets
print(f"the {first.first_mode} mode whirls first, from {first.onset_speed_rpm:,.0f} rpm "
      f"({first.onset_whirl_frequency_hz:.0f} Hz)")

# %%
# The Campbell diagram
# --------------------
# Top: each mode's damped natural frequency [Hz] against speed, with the 1× line; bottom:
# its log decrement — a mode whirls where its log decrement crosses zero, at the onsets
# marked (the matched-whirl answers, not read off the scan).
onsets = {m.label: m.onset_speed_rpm for m in analysis.onsets.modes}
fig, axes = plt.subplots(2, 1, layout="constrained", figsize=(7.2, 6.4), sharex=True)
plot_campbell(analysis.campbell.table, onsets, axes=axes,
              title=f"Campbell diagram, 3.2 kg blower rotor ({GRID} grid)")
fig.savefig(OUT / "campbell.png", dpi=110)

# %%
# The imbalance response
# ----------------------
# The synchronous orbit at each bearing from the rotor file's imbalance planes, up to the
# first onset (above it the linear response has no meaning: the rotor whirls).
fig, axes = plt.subplots(2, 1, layout="constrained", figsize=(7.2, 6.0), sharex=True)
plot_imbalance_response(analysis.imbalance.table, analysis.imbalance.peaks, onsets,
                        axes=axes, title=f"imbalance response ({GRID} grid)",
                        unstable_from_rpm=analysis.imbalance.unstable_from_rpm)
fig.savefig(OUT / "imbalance_response.png", dpi=110)

# %%
# Every table as pandas
# ---------------------
# ``analysis.tables()`` gives the modes, the threshold scan, the equilibria, the Campbell
# and imbalance tables as DataFrames, with the glossary's column names and units.
tables = analysis.tables()
print(tables["modes"][["label", "onset_speed_rpm", "whirl_frequency_hz"]])
