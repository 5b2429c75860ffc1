"""``gfbopt orbit --bearing FILE`` (and ``gfbopt critical-mass``) on a file with
[journal]/[thermal]: the bearing held at its running condition at --speed-rpm exactly as
``gfbopt static`` holds it (the same running clearance, viscosity and model), its output
naming the thermal model; a file without the tables gives today's orbit."""
import json
import math
from pathlib import Path

import pytest

from gfbopt.cli.running_point import RUNNING_FIELDS
from gfbopt.inputs import Grid, load_bearing
from gfbopt.inputs.conversions import mass_parameter, rpm_to_rad_per_s
from gfbopt.static import solve_static, solver_for
from gfbopt.thermal.running import CENTRIFUGAL, HEAT_BALANCE, ISOTHERMAL
from tests.cli_inprocess import run_cli

BEARINGS = Path(__file__).resolve().parents[2] / "problems" / "bearings"
THERMAL = BEARINGS / "ruscitto_thermal.toml"
GRID = "36x10"
POINT = ("--speed-rpm", "45000", "--load-newton", "20", "--grid", GRID)
ORBIT = ("--rotor-mass-kg", "1", "--revolutions", "2")
#: the model's groups and the bearing analysed, as describe() reports them
MODEL = ("bearing_number", "compliance", "top_foil_coefficient", "length_ratio",
         "radial_clearance_m", "foil", "film", "seam_angle_deg", "deflection_law",
         "loss_factor")


def _json(*args, code=0):
    result = run_cli(*args, "--json")
    assert result.returncode == code, result.stderr
    return json.loads(result.stdout)


@pytest.fixture(scope="module")
def heated():
    return (_json("orbit", "--bearing", THERMAL, *POINT, *ORBIT),
            _json("static", "--bearing", THERMAL, *POINT))


def test_the_orbit_of_a_heated_file_is_on_the_static_commands_model(heated):
    orbit, static = heated
    assert orbit["thermal_model"] == HEAT_BALANCE
    assert orbit["running"]["thermal_status"] == "running"
    for key in RUNNING_FIELDS[:-1]:
        assert key in orbit, key
    # one running point: clearance and viscosity of the heat balance's fixed point, to
    # rounding (both commands iterate the same balance on the same grid and load)
    for key in ("running_clearance_um", "viscosity_pa_s", "film_temperature_c",
                "centrifugal_growth_um", "thermal_growth_um"):
        assert orbit[key] == pytest.approx(static[key], rel=1e-12, abs=0.0), key
    for key in MODEL:
        value = static[key]
        if isinstance(value, float):
            assert orbit[key] == pytest.approx(value, rel=1e-12, abs=0.0), key
        else:
            assert orbit[key] == value, key
    # the warm bearing, not the cold one: 20 µm cold, 16.7 µm running at 45,000 rpm
    assert orbit["radial_clearance_m"] == pytest.approx(orbit["running_clearance_um"] * 1e-6,
                                                        rel=1e-15)
    assert orbit["running_clearance_um"] < 19.0
    # the transient starts from the same equilibrium (IPOPT's tolerance 1e-8 on ε)
    assert orbit["eccentricity"] == pytest.approx(static["eccentricity"], abs=1e-8)
    assert orbit["load"] == pytest.approx(static["load"], rel=1e-12)
    # M̄ = M c ω²/W0 with the running clearance
    assert orbit["mass"] == pytest.approx(mass_parameter(
        1.0, orbit["radial_clearance_m"], rpm_to_rad_per_s(45000.0), 20.0), rel=1e-12)


def test_the_orbits_text_names_the_thermal_model():
    text = run_cli("orbit", "--bearing", THERMAL, *POINT, *ORBIT).stdout
    assert text.startswith("gfbopt orbit — M̄ = ")
    assert "clearance model: heat balance + growth; running clearance" in text
    assert "heat balance: film" in text


def test_a_centrifugal_file_takes_an_eccentricity():
    out = _json("orbit", "--bearing", BEARINGS / "ruscitto_centrifugal.toml", "--speed-rpm",
                "45000", "--eccentricity", "0.3", "--grid", GRID, *ORBIT)
    assert out["thermal_model"] == CENTRIFUGAL and out["eccentricity"] == 0.3
    assert out["thermal_growth_um"] == 0.0 and out["centrifugal_growth_um"] > 0.5
    assert out["radial_clearance_m"] == pytest.approx(
        (20.0 - out["centrifugal_growth_um"]) * 1e-6, rel=1e-12)


@pytest.mark.parametrize("extra, option", [
    (("--eccentricity", "0.3"), "--eccentricity"),                # the heat balance needs W
    (("--load-newton", "20", "--reference-whirl-ratio", "0.5"),   # no damping to match
     "--reference-whirl-ratio"),
])
def test_refusals_are_one_line_before_any_solve(extra, option, monkeypatch):
    from gfbopt.thermal import running

    def no_solve(*args, **kwargs):
        raise AssertionError("the heat balance was solved")

    monkeypatch.setattr(running, "running_point", no_solve)
    result = run_cli("orbit", "--bearing", THERMAL, "--speed-rpm", "45000", *extra,
                     "--grid", GRID, *ORBIT)
    assert result.returncode == 2 and result.stdout == ""
    assert option in result.stderr and len(result.stderr.strip().splitlines()) == 1


def test_a_runaway_is_reported_exit_1(tmp_path):
    src = THERMAL.read_text()
    for old, new in (("journal_to_ambient = 0.5 ", "journal_to_ambient = 0.02"),
                     ("sleeve_to_ambient = 1.0 ", "sleeve_to_ambient = 0.02")):
        assert old in src
        src = src.replace(old, new)
    hot = tmp_path / "hot.toml"
    hot.write_text(src)
    out = _json("orbit", "--bearing", hot, "--speed-rpm", "60000", "--load-newton", "20",
                "--grid", GRID, *ORBIT, code=1)
    assert out["running"]["thermal_status"] == "runaway"
    assert out["running_clearance_um"] is None and "thermal runaway" in out["message"]


def test_a_file_without_the_tables_gives_todays_orbit():
    """No running point's field but the model's name (isothermal, cold clearance); the cold
    bearing's model, equilibrium and M̄."""
    out = _json("orbit", "--bearing", BEARINGS / "ruscitto.toml", *POINT, *ORBIT)
    assert not set(out) & set(RUNNING_FIELDS[1:]) and out["thermal_model"] == ISOTHERMAL
    cold = load_bearing(BEARINGS / "ruscitto.toml")
    model = cold.model(45000.0, film="seam", seam_angle_deg=180.0, foil="simple")
    sol = solve_static(model, load=cold.nondimensional_load(20.0),
                       solver=solver_for(model, Grid.parse(GRID)))
    assert out["radial_clearance_m"] == 20e-6
    assert out["bearing_number"] == model.bearing_number
    assert out["eccentricity"] == sol.eccentricity
    assert out["mass"] == mass_parameter(1.0, 20e-6, rpm_to_rad_per_s(45000.0), 20.0)
    assert math.isfinite(out["min_film"]) and out["success"] is True


def test_the_critical_mass_of_a_heated_file_is_at_the_linear_commands_point():
    crit = _json("critical-mass", "--bearing", THERMAL, *POINT)
    linear = _json("linear", "--bearing", THERMAL, *POINT)
    assert crit["thermal_model"] == linear["thermal_model"] == HEAT_BALANCE
    for key in ("running_clearance_um", "viscosity_pa_s", "film_temperature_c"):
        assert crit[key] == pytest.approx(linear[key], rel=1e-12, abs=0.0), key
    # the transient search is centred on the warm bearing's linear threshold
    assert crit["linear_critical_mass"] == pytest.approx(linear["critical_mass"], rel=1e-9)
    assert crit["success"] and abs(crit["critical_mass"] / crit["linear_critical_mass"]
                                   - 1) < 0.01
    text = run_cli("critical-mass", "--bearing", THERMAL, *POINT).stdout
    assert "clearance model: heat balance + growth; running clearance" in text
    cold = _json("critical-mass", "--bearing", BEARINGS / "ruscitto.toml", *POINT)
    assert not set(cold) & set(RUNNING_FIELDS[1:]) and cold["radial_clearance_m"] == 20e-6
    assert cold["thermal_model"] == ISOTHERMAL
