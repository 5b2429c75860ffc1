"""
Which bearing pair suits *my* rotor? A design from your own rotor file
======================================================================

The main job of gfbopt (``gfbopt run problems/rotor_bearing_design.toml``) searches the radial
clearance and the shim preload of both foil bearings of the 3.2 kg blower rotor for the front
of first onset of whirl against drag at the top speed.  Here it runs on a rotor of your own:
a 3.0 kg rotor with its centre of gravity midway between two Ruscitto bearings 100 mm apart,
to a top speed of 30,000 rpm.  On the command line that is::

    gfbopt run problems/rotor_bearing_design.toml --rotor my_rotor.toml --top-speed 30000

which answers exactly what a copy of the study file with ``rotor``, ``name``, ``title`` and the
top of ``speed_range_rpm`` changed answers.  From Python, that copy is what this page makes
and hands to :func:`gfbopt.run_study` — with the design space stated (one radial clearance
and one shim depth for both bearings) and a small search (12 designs on a 24 × 8 grid, the
chosen one checked again on 36 × 10, 3 tolerance samples) so that it builds in well under a
minute; the shipped study searches longer on 36 × 10 and checks on 144 × 36.
"""
import json
import os
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

import gfbopt
from gfbopt.inputs import read_toml
from gfbopt.plotting.design_front import plot_design_front
from gfbopt.studies import study_from_dict

try:
    ROOT = Path(__file__).resolve().parents[1]      # python examples/THIS.py
except NameError:                                   # sphinx-gallery: run from examples/
    ROOT = Path.cwd().parent
OUT = Path(os.environ.get("GFBOPT_EXAMPLES_OUTPUT", ROOT / "runs" / "examples")) / "my_rotor"
OUT.mkdir(parents=True, exist_ok=True)
TOP_SPEED_RPM = 30000.0

# %%
# Your rotor file
# ---------------
# Mass and inertias of the rigid rotor, the two bearing files and their positions from the
# centre of gravity [m], and an imbalance plane (docs/formats/rotor_file.md); checked when
# read.  The design study runs the chosen design in time at the top speed with the imbalance.
bearing_file = (ROOT / "problems" / "bearings" / "ruscitto.toml").as_posix()
my_rotor = OUT / "my_rotor.toml"
my_rotor.write_text(f"""
[rotor]
name = "3.0 kg rotor, CG midway between two Ruscitto bearings 100 mm apart"
mass = 3.0                  # [kg]
transverse_inertia = 0.012  # [kg m²] about the centre of gravity
polar_inertia = 0.002       # [kg m²]

[[bearings]]
name = "A"
file = "{bearing_file}"
position = -0.05            # [m] from the centre of gravity

[[bearings]]
name = "B"
file = "{bearing_file}"
position = 0.05             # [m]

[[imbalance]]
name = "impeller"
amount_g_mm = 2.4           # [g mm]: G2.5 at 30,000 rpm for 3 kg
phase_deg = 0.0
position = 0.08             # [m], overhung beyond bearing B
""")
print(gfbopt.load_rotor(my_rotor).body)

# %%
# The design study on it
# ----------------------
# The shipped study file read as a dict (:func:`gfbopt.inputs.read_toml`), with your rotor
# and top speed and a smaller search, validated and planned by
# :func:`gfbopt.studies.study_from_dict` before anything is solved, then run.
study = read_toml(ROOT / "problems" / "rotor_bearing_design.toml")
study.update(name="design_my_rotor", rotor=str(my_rotor),
             title="Bearing pair of my 3.0 kg rotor to 30,000 rpm (a small search)",
             speed_range_rpm=[4000.0, TOP_SPEED_RPM], grid="36x10", search_grid="24x8",
             regrid_designs=1)
# the design space, stated here: one radial clearance and one shim depth for both bearings
study["variables"] = [{"name": "radial_clearance_um", "low": 15.0, "high": 35.0},
                      {"name": "preload_depth_um", "low": 0.0, "high": 12.0}]
study["search"] = {"method": "nsga2", "budget": 12, "population": 6, "seed": 1}
study["robustness"] = {"samples": 3, "seed": 0, "designs": 1,
                       "tolerances": {"radial_clearance_um": 1.0, "preload_depth_um": 1.0}}
for key in ("source", "notes"):          # a study of yours cites no source; its notes are yours
    study.pop(key, None)
loaded = study_from_dict(study, file="design_my_rotor", directory=ROOT / "problems")
result = gfbopt.run_study(loaded, results_root=OUT / "runs", workers=1, force=True)
folder = OUT / "runs" / "design_my_rotor"
print(sorted(p.name for p in folder.iterdir()))

# %%
# The answer
# ----------
# The verdict in words (``summary.json``, also the first lines of the folder's README.md),
# then the tables: every design evaluated, the Pareto front and the chosen design.
summary = json.loads((folder / "summary.json").read_text())
print(summary["verdict"])
evaluations = pd.read_csv(folder / "evaluations.csv")
front = pd.read_csv(folder / "pareto_front.csv")
chosen = None
if (folder / "chosen.csv").is_file():
    chosen = pd.read_csv(folder / "chosen.csv").iloc[0]
    design = ", ".join(f"{v['name']} {chosen[v['name']]:.3g}" for v in study["variables"])
    print(f"chosen: {design}; first onset {chosen['first_onset_speed_rpm']:,.0f} rpm "
          f"({chosen['first_mode']}), {chosen['total_power_loss_w']:.1f} W at "
          f"{TOP_SPEED_RPM:,.0f} rpm")
print(f"{len(evaluations)} designs evaluated, {int(evaluations['feasible'].sum())} feasible")

fig, ax = plt.subplots(layout="constrained", figsize=(7.0, 4.8))
plot_design_front(evaluations, front, None if chosen is None else chosen.to_dict(), TOP_SPEED_RPM,
                  1.25 * TOP_SPEED_RPM, ax=ax,
                  title="designs of my 3.0 kg rotor's bearing pair (24x8 search grid)")
fig.savefig(OUT / "design_front.png", dpi=110)
