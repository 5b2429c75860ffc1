"""``gfbopt static`` and ``gfbopt linear`` on a bearing file with [journal]/[thermal]: the
equilibrium and K, C at the running condition of the file's speed (running clearance and
μ(T)), naming the model; a file without the tables gives today's output."""
import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from gfbopt.inputs import Grid, load_bearing
from gfbopt.linear import linear_threshold, linearise
from gfbopt.static import solve_static, solver_for
from gfbopt.thermal.running import CENTRIFUGAL, HEAT_BALANCE, ISOTHERMAL
from tests.cli_inprocess import run_cli

BEARINGS = Path(__file__).resolve().parents[2] / "problems" / "bearings"
THERMAL = BEARINGS / "ruscitto_thermal.toml"
GRID = "36x10"
RUNNING = ("running_clearance_um", "centrifugal_growth_um", "thermal_growth_um",
           "film_temperature_c", "viscosity_pa_s")
ARGS = ("--speed-rpm", "45000", "--load-newton", "20", "--grid", GRID)


def _json(*args):
    result = run_cli(*args, "--json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def _warm_solution(out):
    """The library's own equilibrium of the bearing at the reported running clearance and
    viscosity (the file's [model]: seam 180°, simple foil)."""
    cold = load_bearing(BEARINGS / "ruscitto.toml")       # same [bearing] and [model]
    warm = dataclasses.replace(cold, radial_clearance=out["running_clearance_um"] * 1e-6,
                               viscosity=out["viscosity_pa_s"])
    model = warm.model(45000.0, film="seam", seam_angle_deg=180.0, foil="simple")
    solver = solver_for(model, Grid.parse(GRID))
    return solve_static(model, load=warm.nondimensional_load(20.0), solver=solver), solver


@pytest.fixture(scope="module")
def static_out():
    return _json("static", "--bearing", THERMAL, *ARGS)


def test_static_of_a_heated_file_is_the_equilibrium_at_the_running_condition(static_out):
    out = static_out
    assert out["thermal_model"] == HEAT_BALANCE and out["running"]["thermal_status"] == "running"
    # c = c0 − u_c − (journal − sleeve thermal growth), and it is the clearance analysed
    assert out["running_clearance_um"] == pytest.approx(
        20.0 - out["centrifugal_growth_um"] - out["thermal_growth_um"], rel=1e-12)
    assert out["radial_clearance_m"] == out["running_clearance_um"] * 1e-6
    assert out["running_clearance_um"] < 20.0 and out["film_temperature_c"] > 20.0
    assert out["viscosity_pa_s"] > 2.98e-5                # Sutherland: hotter, more viscous
    assert out["min_film_thickness_um"] == pytest.approx(
        out["min_film"] * out["running_clearance_um"], rel=1e-12)
    # the drag of this equilibrium is the heat the balance carries away (the fixed point)
    assert out["power_loss_w"] == pytest.approx(out["running"]["heat_generated_w"], rel=1e-6)
    sol, _ = _warm_solution(out)
    assert out["eccentricity"] == pytest.approx(sol.eccentricity, abs=1e-8)
    assert out["attitude_angle_deg"] == pytest.approx(sol.attitude_angle_deg, abs=1e-6)
    text = run_cli("static", "--bearing", THERMAL, *ARGS).stdout
    assert "clearance model: heat balance + growth; running clearance" in text


def test_linear_of_a_heated_file_is_k_and_c_at_the_running_condition(static_out):
    out = _json("linear", "--bearing", THERMAL, *ARGS, "--whirl-ratio", "0.5")
    for key in ("thermal_model", *RUNNING):
        assert out[key] == static_out[key], key
    sol, solver = _warm_solution(out)
    lin = linearise(sol, solver)
    assert out["critical_mass"] == pytest.approx(linear_threshold(lin).critical_mass,
                                                 rel=1e-6)
    from gfbopt.linear import coefficients

    k = coefficients(lin, [0.5]).stiffness[0]
    np.testing.assert_allclose(out["stiffness"]["0.5"], k, rtol=1e-6, atol=1e-9)


def test_centrifugal_file_takes_an_eccentricity():
    out = _json("static", "--bearing", BEARINGS / "ruscitto_centrifugal.toml",
                "--speed-rpm", "45000", "--eccentricity", "0.3", "--grid", GRID)
    assert out["thermal_model"] == CENTRIFUGAL and out["eccentricity"] == 0.3
    assert out["thermal_growth_um"] == 0.0 and out["centrifugal_growth_um"] > 0
    assert out["running_clearance_um"] == pytest.approx(20.0 - out["centrifugal_growth_um"],
                                                        rel=1e-12)


def test_heat_balance_refuses_an_eccentricity_in_one_line():
    result = run_cli("static", "--bearing", THERMAL, "--speed-rpm", "45000",
                     "--eccentricity", "0.3", "--grid", GRID)
    assert result.returncode == 2 and result.stdout == ""
    assert "--eccentricity" in result.stderr and "load" in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1


def test_runaway_is_reported_not_raised(tmp_path):
    src = THERMAL.read_text()
    for old, new in (("journal_to_ambient = 0.5 ", "journal_to_ambient = 0.02"),
                     ("sleeve_to_ambient = 1.0 ", "sleeve_to_ambient = 0.02")):
        src = src.replace(old, new)
    hot = tmp_path / "hot.toml"
    hot.write_text(src)
    result = run_cli("linear", "--bearing", hot, "--speed-rpm", "60000", "--load-newton",
                     "20", "--grid", GRID, "--json")
    assert result.returncode == 1
    out = json.loads(result.stdout)
    assert out["running"]["thermal_status"] == "runaway"
    assert out["running_clearance_um"] is None          # no running state: null in JSON
    assert "thermal runaway" in out["message"] and "thermal runaway" in result.stderr


def test_a_file_without_the_tables_gives_todays_output():
    """No running point's field but the model's name (isothermal, cold clearance), and the
    numbers are the cold bearing's equilibrium."""
    out = _json("static", "--bearing", BEARINGS / "ruscitto.toml", *ARGS)
    assert not set(out) & {"running", *RUNNING} and out["thermal_model"] == ISOTHERMAL
    cold = load_bearing(BEARINGS / "ruscitto.toml")
    model = cold.model(45000.0, film="seam", seam_angle_deg=180.0, foil="simple")
    sol = solve_static(model, load=cold.nondimensional_load(20.0),
                       solver=solver_for(model, Grid.parse(GRID)))
    assert out["eccentricity"] == sol.eccentricity and out["radial_clearance_m"] == 20e-6
    lin = _json("linear", "--bearing", BEARINGS / "ruscitto.toml", *ARGS)
    assert not set(lin) & {"running", *RUNNING} and lin["thermal_model"] == ISOTHERMAL
    assert lin["eccentricity"] == sol.eccentricity
