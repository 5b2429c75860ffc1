"""
Is my rotor stable on this foil bearing? (one bearing, SI)
==========================================================

A 2 kg rotor share carried by the Ruscitto bump-foil bearing
(``problems/bearings/ruscitto.toml``) with a static load of 20 N per bearing: is it stable at
45,000 rpm, with what margin, and from what speed does it whirl?  This is ``gfbopt stability
--bearing ... --rotor-mass-kg 2 --load-newton 20`` from Python, in SI units with speeds in rpm.

The grid is a coarse 36 × 10 so that the example runs in seconds; the default 144 × 36
(``grid=gfbopt.DEFAULT_GRID``) is within 0.5 % of grid convergence.  A grid is given as a
:class:`gfbopt.Grid` or written as on the command line, ``"36x10"``.
"""
# sphinx_gallery_thumbnail_number = 2
import os
from pathlib import Path

import matplotlib.pyplot as plt

import gfbopt
from gfbopt.plotting import plot_coefficients

try:
    ROOT = Path(__file__).resolve().parents[1]      # python examples/THIS.py
except NameError:                                   # sphinx-gallery: run from examples/
    ROOT = Path.cwd().parent
OUT = Path(os.environ.get("GFBOPT_EXAMPLES_OUTPUT", ROOT / "runs" / "examples")) / "stability"
OUT.mkdir(parents=True, exist_ok=True)
GRID = "36x10"

# %%
# The bearing and the operating point
# -----------------------------------
# :func:`gfbopt.load_bearing` reads the bearing file in SI (radius, length, clearance, bump
# foil) with its ``[model]`` table (film convention, foil law).  The rotor is the mass *per
# bearing* [kg]; the operating point is the speed [rpm] and the static load per bearing [N].
bearing = gfbopt.load_bearing(ROOT / "problems" / "bearings" / "ruscitto.toml")
rotor = gfbopt.Rotor(2.0)
point = gfbopt.OperatingPoint(45000.0, 20.0)
result = gfbopt.stability(bearing, rotor, point, grid=GRID)
print(f"at {point.speed_rpm:,.0f} rpm: {result.verdict}; critical mass "
      f"{result.critical_mass_kg:.3g} kg per bearing (mass margin {result.mass_margin:+.1%}); "
      f"least-stable whirl {result.whirl_frequency_hz:.1f} Hz, log decrement "
      f"{result.log_decrement:.3g}")

# %%
# From what speed does it whirl?
# ------------------------------
# :func:`gfbopt.onset_speed` follows the rotor's mass–speed line (mass and load fixed) and
# finds the lowest speed of whirl by secant steps on the mass margin.
onset = gfbopt.onset_speed(bearing, rotor, 20.0, (5000.0, 50000.0), grid=GRID)
print(onset.answer)

scan = sorted(onset.scan, key=lambda row: row["speed_rpm"])
fig, ax = plt.subplots(layout="constrained", figsize=(6.4, 4.2))
ax.plot([r["speed_rpm"] for r in scan], [100 * r["mass_margin"] for r in scan], "o-",
        label="mass margin $M_c/M - 1$")
ax.axhline(0.0, color="k", lw=0.8)
ax.axvline(onset.onset_speed_rpm, color="C3", ls="--",
           label=f"onset {onset.onset_speed_rpm:,.0f} rpm")
ax.set_xlabel("shaft speed [rpm]")
ax.set_ylabel("mass margin [%]")
ax.set_title(f"2 kg per bearing at 20 N on the Ruscitto bearing ({GRID} grid)")
ax.grid(alpha=0.3)
ax.legend()
fig.savefig(OUT / "mass_margin.png", dpi=110)

# %%
# Stiffness and damping for a rotordynamics code
# ----------------------------------------------
# The foil bearing's K [N/m] and C [N s/m] depend on the excitation frequency; at the onset
# they are taken at the whirl frequency (matched whirl).  :func:`gfbopt.coefficient_table`
# gives them against frequency at an operating point, from the linearisation that the
# stability answer carries (``gfbopt stability ... --csv``).
below = gfbopt.stability(bearing, rotor, gfbopt.OperatingPoint(12000.0, 20.0), grid=GRID)
table = gfbopt.coefficient_table(below.linearisation, bearing, 12000.0, None,
                                 below.threshold_whirl_ratio)
print(table.table[["frequency_hz", "kxx_N_per_m", "kyy_N_per_m", "cxx_Ns_per_m"]].round(1))
fig, (ax_k, ax_c) = plt.subplots(1, 2, layout="constrained", figsize=(10, 4.0))
plot_coefficients(table.table, "stiffness", ax=ax_k, title="stiffness at 12,000 rpm, 20 N")
plot_coefficients(table.table, "damping", ax=ax_c, title="damping at 12,000 rpm, 20 N")
fig.savefig(OUT / "coefficients.png", dpi=110)
_ = table.write_csv(OUT / "coefficients.csv")
