"""
Using gfbopt's bearings in ROSS: export each bearing's K and C table
====================================================================

ROSS (the open-source rotordynamics package) models shafts, disks and their bending modes;
gfbopt models the foil bearings.  ``gfbopt export-ross`` writes each bearing of a rotor file
as a ROSS 3.x ``BearingElement`` coefficient-table file: stiffness and damping kxx … cyy
[N/m, N s/m] over shaft speeds × whirl frequencies, in the rotor's x–y frame, in the file
format ROSS's own ``BearingElement.save_coefficient_table`` writes.  In ROSS (Python ≥ 3.12,
``pip install -e ".[ross]"``; gfbopt need not be installed there)::

    import ross
    bearing_a = ross.BearingElement.load("bearing_A.toml")   # set bearing_a.n to your node
    ...
    rotor.run_modal(speed, matched_whirl=True)   # each mode at its own whirl frequency

A foil bearing's coefficients depend on the whirl frequency: take them at each mode's own
frequency (matched whirl), and keep ROSS inside the table's span — it extrapolates linearly
outside it.  The blower rotor's onset computed this way in ROSS agrees with gfbopt's to 0.1 %
(``examples/ross_rotor_onset.py``, ``results/rotor_ross_comparison.md``).  This page runs the
command on a coarse 36 × 10 grid and draws what the files hold; ROSS is not needed.
"""
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from gfbopt.cli import main
from gfbopt.inputs import read_toml

try:
    ROOT = Path(__file__).resolve().parents[1]      # python examples/THIS.py
except NameError:                                   # sphinx-gallery: run from examples/
    ROOT = Path.cwd().parent
OUT = Path(os.environ.get("GFBOPT_EXAMPLES_OUTPUT", ROOT / "runs" / "examples")) / "ross"
OUT.mkdir(parents=True, exist_ok=True)

# %%
# The command
# -----------
# Five speeds 8,000–16,000 rpm (around the blower rotor's onset, about 12,000 rpm) and eight
# whirl frequencies from 0.1 × the lowest to 1.5 × the highest shaft frequency.
os.chdir(ROOT)                     # the paths it prints are then the repository's own
status = main(["export-ross", "problems/rotors/blower.toml",
               "--speed-range", "8000", "16000", "--speeds", "5", "--frequencies", "8",
               "--grid", "36x10", "--out", os.path.relpath(OUT / "tables")])
assert status == 0

# %%
# What a file holds
# -----------------
# One table per bearing, ``[BearingElement_<name>]``: ``speed`` and ``frequency`` in rad/s,
# each coefficient an (n_speed × n_frequency) array, the ROSS node ``n`` and the clearance.
table = read_toml(OUT / "tables" / "bearing_A.toml")["BearingElement_A"]
speed_rpm = np.asarray(table["speed"]) * 60.0 / (2.0 * np.pi)
frequency_hz = np.asarray(table["frequency"]) / (2.0 * np.pi)
print(f"node {table['n']}, radial clearance {table['radial_clearance'] * 1e6:.3g} µm, "
      f"{len(speed_rpm)} speeds × {len(frequency_hz)} frequencies")

fig, (ax_k, ax_c) = plt.subplots(1, 2, layout="constrained", figsize=(10.5, 4.2))
for i, speed in enumerate(speed_rpm):
    ax_k.plot(frequency_hz, np.asarray(table["kxx"])[i] / 1e6, "o-", ms=3,
              label=f"{speed:,.0f} rpm")
    ax_c.plot(frequency_hz, np.asarray(table["cxx"])[i], "o-", ms=3, label=f"{speed:,.0f} rpm")
ax_k.set_ylabel("direct stiffness $k_{xx}$ [MN/m]")
ax_c.set_ylabel("direct damping $c_{xx}$ [N s/m]")
for ax in (ax_k, ax_c):
    ax.set_xlabel("whirl frequency [Hz]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, title="shaft speed")
ax_k.set_title("bearing A of the blower rotor: stiffness (36x10 grid)")
ax_c.set_title("bearing A: damping against whirl frequency")
fig.savefig(OUT / "ross_table_bearing_a.png", dpi=110)
