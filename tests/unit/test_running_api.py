"""The library and the command line give the same answer for a heated bearing file:
``gfbopt.api.stability`` / ``onset_speed`` / ``load_capacity`` given the file's path equal
``gfbopt stability`` / ``gfbopt capacity`` on it (the same functions,
gfbopt.rotor.running_bearing, on a fresh solver cache each: equal to the last bit), and a
geometry is today's analysis unchanged."""
import json
import math
from pathlib import Path

import pytest

import gfbopt.api as api
from gfbopt.inputs import OperatingPoint, Rotor
from gfbopt.thermal.running import HEAT_BALANCE
from tests.cli_inprocess import run_cli

BEARINGS = Path(__file__).resolve().parents[2] / "problems" / "bearings"
THERMAL = BEARINGS / "ruscitto_thermal.toml"
GRID = "24x8"
RUNNING = ("running_clearance_um", "centrifugal_growth_um", "thermal_growth_um",
           "film_temperature_c", "viscosity_pa_s")


def _cli(*args):
    result = run_cli(*args, "--grid", GRID, "--json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def test_stability_of_a_heated_file_is_the_command_line():
    out = _cli("stability", "--bearing", THERMAL, "--rotor-mass-kg", "1.5", "--load-newton",
               "20", "--speed-rpm", "30000")
    lib = api.stability(str(THERMAL), Rotor(1.5), OperatingPoint(30000.0, 20.0), grid=GRID)
    assert lib.verdict == out["verdict"] and lib.running.converged
    d = lib.to_dict()
    assert d["thermal_model"] == out["thermal_model"] == HEAT_BALANCE
    for key in ("critical_mass_kg", "mass_margin", "whirl_frequency_hz", "eccentricity",
                "min_film_thickness_um", *RUNNING):
        assert d[key] == out[key], key
    assert lib.critical_mass_kg == out["critical_mass_kg"]
    assert 15 < d["running_clearance_um"] < 20          # warmer and grown: below the cold 20 µm
    # a geometry is today's function, unchanged
    cold = api.stability(api.load_bearing(BEARINGS / "ruscitto.toml"), Rotor(1.5),
                         OperatingPoint(30000.0, 20.0), grid=GRID)
    assert cold.critical_mass_kg != d["critical_mass_kg"]


def test_onset_of_a_heated_file_is_the_command_line():
    out = _cli("stability", "--bearing", THERMAL, "--rotor-mass-kg", "2", "--load-newton",
               "20", "--speed-range", "5000", "50000")
    lib = api.onset_speed(THERMAL, Rotor(2.0), 20.0, (5000.0, 50000.0), grid=GRID)
    assert math.isfinite(lib["onset_speed_rpm"])
    assert lib["onset_speed_rpm"] == out["onset_speed_rpm"]
    assert lib["running"] == out["onset"]["running"]
    assert lib["running"]["thermal_model"] == HEAT_BALANCE


def test_load_capacity_of_a_heated_file_is_the_command_line():
    out = _cli("capacity", "--bearing", THERMAL, "--speed-rpm", "30000", "--min-film-um", "5")
    lib = api.load_capacity(THERMAL, 30000.0, 5.0, grid=GRID)
    assert math.isfinite(lib["load_capacity_newton"]) and lib["load_capacity_newton"] > 0
    for key in ("load_capacity_newton", "min_film_thickness_um", "thermal_model", *RUNNING):
        assert lib[key] == out[key], key


def test_a_file_with_bad_tables_is_refused_before_any_solve(tmp_path):
    from gfbopt.errors import ParameterError

    bad = tmp_path / "b.toml"
    bad.write_text(THERMAL.read_text().replace("journal_to_ambient = 0.5",
                                               "journal_to_ambient = -0.5"))
    with pytest.raises(ParameterError, match=r"b.toml: thermal.journal_to_ambient"):
        api.stability(bad, Rotor(1.5), OperatingPoint(30000.0, 20.0), grid=GRID)
