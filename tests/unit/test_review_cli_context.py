"""The reviewer's context defects (gfbopt/cli): every CSV context file and ROSS table names
the model that made its numbers — stability's clearance model and running clearance, the
rotor's conventions block (each bearing's film, foil, friction, clearance model: the
command's --json conventions, the same dict), export-ross's bump friction in the TOML header
and the .json — and ``stability --json`` uses the glossary's names ``load``, ``mass``,
``critical_mass`` (as critical-mass, static and linear do).  Grids 24x8."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from gfbopt.glossary import describe
from tests.cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
B = REPO / "problems" / "bearings"
R = REPO / "problems" / "rotors"
STABILITY = ("stability", "--rotor-mass-kg", "2", "--load-newton", "20", "--speed-rpm",
             "30000", "--grid", "24x8")


def _ok(*args):
    out = run_cli(*args)
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_stability_csv_context_names_the_clearance_model(tmp_path):
    """ruscitto_thermal at 30,000 rpm: the context's options hold the heat balance and the
    running clearance of the JSON (the same number, < 20 µm cold)."""
    csv = tmp_path / "st.csv"
    data = json.loads(_ok(*STABILITY, "--bearing", str(B / "ruscitto_thermal.toml"), "--csv",
                          str(csv), "--json"))
    options = json.loads((tmp_path / "st.csv.json").read_text())["provenance"]["options"]
    assert options["thermal_model"] == data["thermal_model"] == "heat balance + growth"
    assert options["running_clearance_um"] == data["running_clearance_um"]
    assert 15.0 < options["running_clearance_um"] < 20.0
    assert options["film_temperature_c"] == data["film_temperature_c"]
    assert data["provenance"]["options"]["running_clearance_um"] == data[
        "running_clearance_um"]


def test_rotor_csv_context_holds_the_conventions(tmp_path):
    """blower_friction: each CSV's context has the --json's conventions block, with each
    bearing's friction coefficient 0.5 and its clearance model."""
    folder = tmp_path / "out"
    args = ("rotor", str(R / "blower_friction.toml"), "--speed-range", "10000", "40000",
            "--grid", "24x8", "--json")
    data = json.loads(_ok(*args, "--csv", str(folder)))
    sides = sorted(folder.glob("*.csv.json"))
    assert len(sides) >= 3                       # modes, threshold_scan, equilibria
    for side in sides:
        options = json.loads(side.read_text())["provenance"]["options"]
        assert options["conventions"] == json.loads(json.dumps(data["conventions"]))
        for name in ("A", "B"):
            bearing = options["conventions"]["bearings"][name]
            assert bearing["friction_coefficient"] == 0.5
            assert bearing["foil"] == "simple" and bearing["deflection_law"] == "mean"
            assert bearing["thermal_model"] == "isothermal, cold clearance"


def test_export_ross_names_the_bump_friction(tmp_path):
    out = tmp_path / "ross"
    _ok("export-ross", str(R / "blower_friction.toml"), "--speed-range", "10000", "40000",
        "--grid", "24x8", "--out", str(out))
    for name in ("A", "B"):
        header = [l for l in (out / f"bearing_{name}.toml").read_text().splitlines()
                  if l.startswith("#")]
        model = [l for l in header if l.startswith("# model:")]
        assert len(model) == 1 and "bump friction μ_f = 0.5 (κ = 2)" in model[0]
        side = json.loads((out / f"bearing_{name}.toml.json").read_text())
        conv = side["provenance"]["options"]["conventions"]["bearings"][name]
        assert conv["friction_coefficient"] == 0.5
        assert conv["friction_stiffness_ratio"] == 2.0


def test_stability_json_uses_the_glossary_names():
    """load, mass, critical_mass (glossary) replace load_parameter, mass_parameter,
    critical_mass_parameter; M̄ = M c ω²/W0 = 2 kg × 20e-6 m × (π 1000 rad/s)² / 20 N."""
    import math

    data = json.loads(_ok(*STABILITY, "--bearing", str(B / "ruscitto.toml"), "--json"))
    for old in ("load_parameter", "mass_parameter", "critical_mass_parameter"):
        assert old not in data
    for name in ("load", "mass", "critical_mass"):
        describe(name)                           # in the glossary (KeyError otherwise)
    omega = 30000 * 2 * math.pi / 60
    assert data["mass"] == pytest.approx(2 * 20e-6 * omega ** 2 / 20, rel=1e-12)
    assert data["load"] == pytest.approx(20 / (1e5 * 19.05e-3 ** 2), rel=1e-12)
    assert data["critical_mass_kg"] == pytest.approx(
        data["critical_mass"] * 20 / (20e-6 * omega ** 2), rel=1e-9)


def test_stability_onset_scan_uses_the_glossary_names():
    """The onset search's scan rows name M̄ and M̄c as the operating point does; a row at
    30,000 rpm has M̄ = 2 × 20e-6 × (π 1000)²/20 (the rotor and load of the run)."""
    import math

    data = json.loads(_ok(*STABILITY, "--bearing", str(B / "ruscitto.toml"), "--onset",
                          "--json"))
    rows = data["onset"]["scan"]
    assert rows
    for row in rows:
        assert "mass_parameter" not in row and "critical_mass_parameter" not in row
        omega = row["speed_rpm"] * 2 * math.pi / 60
        assert row["mass"] == pytest.approx(2 * 20e-6 * omega ** 2 / 20, rel=1e-9)
        assert "critical_mass" in row
