"""
The bearing as built: how much do shims, load and speed give me? (preload, capacity, drag)
==========================================================================================

Three questions a foil-bearing designer asks of the Ruscitto bearing
(``problems/bearings/ruscitto.toml``, radial clearance 20 µm):

1. What does a preload of three 60° shims of 6 µm under the bump strip do to the onset of
   whirl of a 2 kg rotor at 20 N per bearing?
2. What load does the bearing carry at 30,000 rpm with a minimum film of 5 µm (its load
   capacity), and from what speed does it lift off under 20 N?
3. What drag torque [N m] and power loss [W] does it cost, round and shimmed?

A shimmed bearing is a bearing file with a ``[bore]`` table (docs/formats/bearing_file.md);
here it is written next to the figures.  Grids are coarse (36 × 10) to run in seconds: the
shims' sharp edges converge at first order in the grid spacing, so the shipped
``results/ruscitto_preload`` (48 × 12) and finer grids give onsets a few per cent lower.
"""
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import gfbopt
from gfbopt.analyses import bearing_model, static_point
from gfbopt.plotting.bearing import plot_bore_profile, plot_capacity_curve

try:
    ROOT = Path(__file__).resolve().parents[1]      # python examples/THIS.py
except NameError:                                   # sphinx-gallery: run from examples/
    ROOT = Path.cwd().parent
OUT = Path(os.environ.get("GFBOPT_EXAMPLES_OUTPUT", ROOT / "runs" / "examples")) / "as_built"
OUT.mkdir(parents=True, exist_ok=True)
GRID = "36x10"
RUSCITTO = ROOT / "problems" / "bearings" / "ruscitto.toml"

# %%
# A shimmed bearing file
# ----------------------
# The round bearing file, plus a ``[bore]`` table: three shims 60° wide, 6 µm deep, the first
# centred on the load line.
shims = OUT / "ruscitto_3_shims.toml"
shims.write_text(RUSCITTO.read_text() + """
[bore]
kind = "shims"
count = 3
preload_depth = 6e-6           # [m]
width_deg = 60.0               # [deg]
offset_deg = 0.0               # first shim centred on the load line [deg]
""")
bearings = {"round bore": gfbopt.load_bearing(RUSCITTO),
            "3 shims, 6 µm": gfbopt.load_bearing(shims)}

profile = bearings["3 shims, 6 µm"].build.bore.profile(20e-6)
theta_deg = np.linspace(0.0, 360.0, 721)
clearance_um = 20.0 * (1.0 + profile.clearance_change(np.radians(theta_deg)))
fig, ax = plt.subplots(layout="constrained", figsize=(6.4, 3.6))
plot_bore_profile(theta_deg, clearance_um, ax=ax, nominal_um=20.0,
                  title="bore of the shimmed Ruscitto bearing (3 × 60°, 6 µm)")
fig.savefig(OUT / "bore_profile.png", dpi=110)

# %%
# Preload and the onset of whirl
# ------------------------------
rotor = gfbopt.Rotor(2.0)
onsets = {name: gfbopt.onset_speed(b, rotor, 20.0, (5000.0, 60000.0), grid=GRID)
          for name, b in bearings.items()}
for name, onset in onsets.items():
    print(f"{name:>14s}: {onset.answer}")
gain = onsets["3 shims, 6 µm"].onset_speed_rpm / onsets["round bore"].onset_speed_rpm - 1
print(f"the shims raise the onset by {gain:.0%}")

# %%
# Load capacity and lift-off
# --------------------------
# :func:`gfbopt.load_capacity` follows the equilibrium up in load until the minimum film
# reaches the limit; :func:`gfbopt.lift_off_speed` follows it down in speed.
capacity = gfbopt.load_capacity(bearings["round bore"], 30000.0, 5.0, grid=GRID)
lift_off = gfbopt.lift_off_speed(bearings["round bore"], 20.0, 5.0, grid=GRID)
print(capacity.answer)
print(lift_off.answer)
fig, (ax_w, ax_n) = plt.subplots(1, 2, layout="constrained", figsize=(10, 4.0))
plot_capacity_curve(capacity.to_dict(), ax=ax_w, title="load capacity at 30,000 rpm")
plot_capacity_curve(lift_off.to_dict(), ax=ax_n, title="lift-off under 20 N")
fig.savefig(OUT / "capacity.png", dpi=110)

# %%
# Drag torque and power loss against speed
# ----------------------------------------
# Each static equilibrium gives the drag torque over Petroff's (``torque_ratio``) and in SI
# ``drag_torque_nm`` and ``power_loss_w`` (:func:`gfbopt.analyses.static_point`).
speeds = np.linspace(10000.0, 45000.0, 6)
fig, ax = plt.subplots(layout="constrained", figsize=(6.4, 4.2))
for name, bearing in bearings.items():
    rows = [static_point(bearing_model(bearing, speed), load=bearing.nondimensional_load(20.0),
                         grid=gfbopt.as_grid(GRID), geometry=bearing) for speed in speeds]
    ax.plot(speeds, [r["power_loss_w"] for r in rows], "o-", label=name)
    print(f"{name:>14s}: {rows[-1]['power_loss_w']:.1f} W, "
          f"{rows[-1]['drag_torque_nm'] * 1e3:.2f} mN m at {speeds[-1]:,.0f} rpm")
ax.set_xlabel("shaft speed [rpm]")
ax.set_ylabel("power loss [W]")
ax.set_title(f"drag of one Ruscitto bearing under 20 N ({GRID} grid)")
ax.grid(alpha=0.3)
ax.legend()
fig.savefig(OUT / "drag.png", dpi=110)
