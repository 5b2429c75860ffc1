"""The CSV context files of the rotor transient (``gfbopt rotor --orbit/--run-up``) and of
``gfbopt orbit`` on a heated bearing name the model as ``gfbopt rotor --speed-range`` and
``gfbopt stability`` do: command, rotor file, grid, the run's options and the conventions
block (each bearing's film/foil/friction/thermal model), and no results in the options."""
from __future__ import annotations

import json

import pytest

from gfbopt.cli import main

#: results of a heated run (gfbopt.transient.rotor_running.RunningPlan.settings and the
#: ramp's end): in the JSON and the tables, never in the provenance options
RESULTS = ("running_line", "running_fixed_points", "running_static_solves",
           "running_interpolation_error", "running_nodes", "running_end",
           "requested_end_rpm", "running_condition", "thermal_models")


def _options(path) -> dict:
    return json.loads(path.read_text())["provenance"]["options"]


@pytest.fixture(scope="module")
def heated_run_up(tmp_path_factory):
    folder = tmp_path_factory.mktemp("run_up")
    assert main(["rotor", "problems/rotors/blower_thermal.toml", "--run-up", "10000", "40000",
                 "--rate", "20000", "--grid", "24x8", "--json", "--csv", str(folder)]) == 0
    return folder


def test_run_up_contexts_name_command_file_and_thermal_model(heated_run_up, capsys):
    names = ("orbit", "components_A", "running_line")
    contexts = [_options(heated_run_up / f"{n}.csv.json") for n in names]
    for options in contexts:
        assert options["command"] == "rotor"
        assert options["rotor_file"] == "problems/rotors/blower_thermal.toml"
        assert options["grid"] == "24x8"
        assert options["speed_profile"]["start_speed_rpm"] == 10000.0
        assert options["speed_profile"]["end_speed_rpm"] == 40000.0     # as asked
        assert options["speed_profile"]["rate_rpm_per_s"] == 20000.0
        assert options["method"] == "rkc"
        bearings = options["conventions"]["bearings"]
        assert sorted(bearings) == ["A", "B"]
        for b in bearings.values():      # the file's [journal]/[thermal]: the heated model
            assert b["thermal_model"] == "heat balance + growth"
            assert b["foil"] == "simple" and b["film"] == "seam"
        assert "quasi-steady" in options["conventions"]["clearance_model"]
        assert not set(RESULTS) & set(options), set(RESULTS) & set(options)
        assert options["arguments"]["--run-up"] == [10000.0, 40000.0]
    assert contexts[0] == contexts[1] == contexts[2]


def test_friction_orbit_context_names_the_friction_model(tmp_path):
    assert main(["rotor", "problems/rotors/blower_friction.toml", "--orbit", "--speed-rpm",
                 "13500", "--revolutions", "20", "--grid", "24x8", "--csv",
                 str(tmp_path)]) == 0
    options = _options(tmp_path / "orbit.csv.json")
    assert options["command"] == "rotor"
    assert options["rotor_file"] == "problems/rotors/blower_friction.toml"
    assert options["speed_profile"]["revolutions"] == 20.0
    for b in options["conventions"]["bearings"].values():       # the file's μ_f, κ
        assert b["friction_coefficient"] == 0.5 and b["friction_stiffness_ratio"] == 2.0
        assert b["thermal_model"] == "isothermal, cold clearance"
    assert "bump friction" in options["conventions"]["bump_friction"]


def test_heated_orbit_context_carries_the_running_point(tmp_path, capsys):
    """gfbopt orbit on a heated bearing file: its CSV context has the clearance model and the
    running point of the JSON (as gfbopt stability's context has), the same values."""
    csv = tmp_path / "X.csv"
    assert main(["orbit", "--bearing", "problems/bearings/ruscitto_thermal.toml",
                 "--speed-rpm", "45000", "--load-newton", "20", "--rotor-mass-kg", "0.2",
                 "--grid", "24x8", "--revolutions", "5", "--json", "--csv", str(csv)]) == 0
    out = json.loads(capsys.readouterr().out)
    options = _options(tmp_path / "X.csv.json")
    assert options["command"] == "orbit"
    assert options["thermal_model"] == out["thermal_model"] == "heat balance + growth"
    # 20 µm cold, grown 1.05 µm (centrifugal) and 2.27 µm (thermal) at 45,000 rpm: 16.67 µm
    assert options["running_clearance_um"] == pytest.approx(16.674, abs=0.01)
    for key in ("cold_clearance_um", "running_clearance_um", "centrifugal_growth_um",
                "thermal_growth_um", "film_temperature_c", "viscosity_pa_s"):
        assert options[key] == out[key], key
    assert "running" not in options            # the nested record stays in the JSON
