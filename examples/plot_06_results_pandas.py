"""
Reading gfbopt's results into pandas: what did the bearing-pair design find?
============================================================================

Every study writes its tables as CSV (and sampled or design studies a Parquet store) in
``results/NAME/`` for the shipped results and ``runs/NAME/`` for yours, with a
``summary.json`` (numbers, checks, provenance) and a ``README.md``.  Column names are the
glossary's (:func:`gfbopt.glossary.describe` gives unit and meaning), so a table reads the
same in every study.  Nothing is computed here: this page reads the shipped results of the
main job (``gfbopt run problems/rotor_bearing_design.toml``) and of the blower rotor.
"""
import json
import os
import tomllib
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

from gfbopt.doe import read_results
from gfbopt.glossary import describe

try:
    ROOT = Path(__file__).resolve().parents[1]      # python examples/THIS.py
except NameError:                                   # sphinx-gallery: run from examples/
    ROOT = Path.cwd().parent
OUT = Path(os.environ.get("GFBOPT_EXAMPLES_OUTPUT", ROOT / "runs" / "examples")) / "results"
OUT.mkdir(parents=True, exist_ok=True)
DESIGN = ROOT / "results" / "rotor_bearing_design"

# %%
# Every design evaluated, and the chosen one
# ------------------------------------------
evaluations = pd.read_csv(DESIGN / "evaluations.csv")
chosen = pd.read_csv(DESIGN / "chosen.csv").iloc[0]
summary = json.loads((DESIGN / "summary.json").read_text())
print(f"{len(evaluations)} designs evaluated, {int(evaluations['feasible'].sum())} feasible; "
      f"the study took {summary['wall_time_s']:.0f} s")
for column in ("first_onset_speed_rpm", "total_power_loss_w", "min_film_lowest_speed_um"):
    unit, meaning = describe(column)
    print(f"{column} [{unit}]: {meaning}")
# the design variables are the study file's, columns of the tables (per bearing: "A:...")
study = tomllib.loads((ROOT / summary["problem_file"]).read_text())
variables = [v["name"] for v in study["variables"]]
design = ", ".join(f"{name} {chosen[name]:.3g}" for name in variables)
print(f"chosen: {design}; first onset {chosen['first_onset_speed_rpm']:,.0f} rpm "
      f"({chosen['first_mode']}), {chosen['total_power_loss_w']:.0f} W at the top speed")

# %%
# The trade-off: first onset against drag
# ---------------------------------------
# The same rows as ``design_front.png`` in the results folder, redrawn from the CSV.
fig, ax = plt.subplots(layout="constrained", figsize=(6.8, 4.6))
for feasible, part in evaluations.groupby("feasible"):
    ax.scatter(part["total_power_loss_w"], part["first_onset_speed_rpm"],
               s=14 if feasible else 8, alpha=0.9 if feasible else 0.4,
               label="feasible" if feasible else "infeasible (film limit)")
ax.scatter([chosen["total_power_loss_w"]], [chosen["first_onset_speed_rpm"]], s=90,
           facecolors="none", edgecolors="C3", lw=2, label="chosen")
ax.set_xlabel("power loss of both bearings at the top speed [W]")
ax.set_ylabel("first onset of whirl [rpm]")
ax.set_title("bearing-pair designs of the 3.2 kg blower rotor (36x10 search grid)")
ax.grid(alpha=0.3)
ax.legend(fontsize=8)
fig.savefig(OUT / "design_trade_off.png", dpi=110)

# %%
# The Parquet store: the same evaluations, typed
# ----------------------------------------------
# :func:`gfbopt.doe.read_results` reads a study's store (the table a rerun with ``--resume``
# continues), with its column types.
store = read_results(DESIGN / "store")
print(store.dtypes.head(12))
print(f"{len(store)} rows in the store")

# %%
# A rotor's modes and Campbell table
# ----------------------------------
blower = ROOT / "results" / "rotor_blower"
modes = pd.read_csv(blower / "modes.csv")
print(modes[["label", "onset_speed_rpm", "whirl_frequency_hz", "onset_status"]].to_string(index=False))
campbell = pd.read_csv(blower / "campbell.csv")
fig, ax = plt.subplots(layout="constrained", figsize=(6.8, 4.4))
for label, part in campbell.groupby("track_label"):
    ax.plot(part["speed_rpm"], part["log_decrement"], "o-", ms=3, label=label)
ax.axhline(0.0, color="k", lw=0.8)
ax.set_xlabel("shaft speed [rpm]")
ax.set_ylabel("log decrement [-]")
ax.set_title("blower rotor: log decrement of each mode (results/rotor_blower, 72x20)")
ax.grid(alpha=0.3)
ax.legend(fontsize=7)
fig.savefig(OUT / "blower_log_decrement.png", dpi=110)
