"""The one-bearing transient commands in SI at the edges when given a bearing file: gfbopt
orbit's trace in seconds and µm beside τ and X/c (as the rotor's orbit writes it), its time
step named in radians (``time_step_rad``), and gfbopt critical-mass's masses in kg with the
load in N — the linear one equal to gfbopt stability's critical_mass_kg."""
import json
from pathlib import Path

import pandas as pd
import pytest

from gfbopt.inputs import load_bearing
from gfbopt.inputs.conversions import rpm_to_rad_per_s
from tests.cli_inprocess import run_cli

BEARING = Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto.toml"
POINT = ("--bearing", str(BEARING), "--load-newton", "20", "--speed-rpm", "30000", "--grid",
         "24x8")


def _json(*args) -> dict:
    out = run_cli(*args, "--json")
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def test_the_orbit_trace_in_si(tmp_path):
    out = _json("orbit", *POINT, "--rotor-mass-kg", "2", "--revolutions", "10", "--csv",
                str(tmp_path / "o.csv"))
    c_um = load_bearing(BEARING).radial_clearance * 1e6
    trace = pd.read_csv(tmp_path / "o.csv")
    assert trace["time_s"].to_numpy() == pytest.approx(
        trace["tau"].to_numpy() / rpm_to_rad_per_s(30000.0), rel=1e-7, abs=1e-12)
    for si, nd in (("x_um", "x"), ("y_um", "y"), ("min_film_thickness_um", "min_film")):
        assert trace[si].to_numpy() == pytest.approx(trace[nd].to_numpy() * c_um, rel=1e-6)
    assert out["min_film_thickness_um"] == pytest.approx(out["min_film"] * c_um, rel=1e-12)
    assert out["time_step_rad"] == pytest.approx(0.1) and "time_step" not in out
    context = json.loads((tmp_path / "o.csv.json").read_text())
    assert context["columns"]["x_um"]["unit"] == "µm"


def test_the_critical_mass_in_kg():
    crit = _json("critical-mass", *POINT)
    stability = _json("stability", *POINT, "--rotor-mass-kg", "2")
    assert crit["load_newton"] == 20.0
    assert crit["linear_critical_mass_kg"] == pytest.approx(stability["critical_mass_kg"],
                                                            rel=1e-9)
    ratio = crit["critical_mass_kg"] / crit["linear_critical_mass_kg"]
    assert ratio == pytest.approx(crit["critical_mass"] / crit["linear_critical_mass"],
                                  rel=1e-12)
