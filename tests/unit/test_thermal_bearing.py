"""The clearance at speed on the bearing: the bearing file's [journal] and [thermal] tables
(refusals before any solve), today's answers kept without them, the heat balance closing on
the real film, and gfbopt stability / capacity reporting it."""
import json
import math
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import Grid, OperatingPoint, Rotor
from gfbopt.cli.running import running_stability
from gfbopt.inputs.bearing_file import load_bearing
from gfbopt.rotor import stability
from gfbopt.static import SolverCache
from gfbopt.thermal.bearing import FilmCase, FilmDrag
from gfbopt.thermal.files import load_running_bearing
from gfbopt.thermal.running import CENTRIFUGAL, HEAT_BALANCE, ISOTHERMAL, speed_line
from tests.cli_inprocess import run_cli

BEARINGS = Path(__file__).resolve().parents[2] / "problems" / "bearings"
THERMAL = BEARINGS / "ruscitto_thermal.toml"
GRID = Grid.parse("24x8")


def with_tables(tmp_path, text, base=THERMAL):
    path = tmp_path / "b.toml"
    src = base.read_text()
    path.write_text(src + "\n" + text if text else src)
    return path


def edit(tmp_path, old, new):
    path = tmp_path / "b.toml"
    src = THERMAL.read_text()
    assert old in src
    path.write_text(src.replace(old, new))
    return path


def test_files_name_their_model():
    assert load_running_bearing(BEARINGS / "ruscitto.toml")[1].model_name == ISOTHERMAL
    assert load_running_bearing(BEARINGS / "ruscitto_centrifugal.toml")[1].model_name == \
        CENTRIFUGAL
    assert load_running_bearing(THERMAL)[1].model_name == HEAT_BALANCE


def test_other_routes_refuse_the_tables_rather_than_answer_cold():
    with pytest.raises(ParameterError, match=r"ruscitto_thermal.toml: \[journal\].*cold "
                                             r"clearance"):
        load_bearing(THERMAL)


@pytest.mark.parametrize("old, new, key", [
    ("journal_to_ambient = 0.5", "journal_to_ambient = -0.5", "thermal.journal_to_ambient"),
    ("cooling_mass_flow = 0.0", "cooling_mass_flow = -1e-3", "thermal.cooling_mass_flow"),
    ("inner_radius = 0.0 ", "inner_radius = 19.05e-3 ", "journal.inner_radius"),
    ("inner_radius = 0.0 ", "inner_radius = 0.03 ", "journal.inner_radius"),
    ("density = 7850.0", "", "journal.density"),
    ("expansion_coefficient = 12e-6  # alpha_j [1/K]", "", "journal.expansion_coefficient"),
    ("ambient_temperature = 293.15", "ambient_temperature = -10.0",
     "thermal.ambient_temperature"),
    ("journal_to_ambient = 0.5", "journal_to_ambient = 0.5\nfilm_to_journal = 0.0\n"
     "film_to_foil = 0.0", "thermal"),
])
def test_bad_tables_refused_in_one_line(tmp_path, old, new, key):
    path = edit(tmp_path, old, new)
    with pytest.raises(ParameterError) as err:
        load_running_bearing(path)
    text = str(err.value)
    assert text.startswith("b.toml: ") and key in text and "\n" not in text
    result = run_cli("stability", "--bearing", path, "--rotor-mass-kg", "1",
                     "--speed-rpm", "30000", "--grid", "24x8")
    assert result.returncode == 2 and key in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1


def test_thermal_needs_journal(tmp_path):
    src = THERMAL.read_text()
    cut = src[src.index("# The journal"):src.index("# The lumped")]
    path = tmp_path / "b.toml"
    path.write_text(src.replace(cut, ""))
    with pytest.raises(ParameterError, match=r"b.toml: thermal.*needs a \[journal\]"):
        load_running_bearing(path)


def test_isothermal_file_keeps_todays_answers_exactly():
    bearing, spec = load_running_bearing(BEARINGS / "ruscitto.toml")
    result, point, _ = running_stability(bearing, spec, Rotor(1.5), OperatingPoint(30e3, 20.0),
                                      grid=GRID)
    today = stability(bearing, Rotor(1.5), OperatingPoint(30e3, 20.0), grid=GRID)
    assert point.running_clearance == bearing.radial_clearance
    assert point.static_solves == 0
    for key in ("critical_mass_kg", "eccentricity", "whirl_frequency_hz", "bearing_number"):
        assert getattr(result, key) == getattr(today, key)


def test_huge_conductances_give_ambient_and_todays_answers(tmp_path):
    """Conductances of 1e15 W/K and a journal too light to grow: the ambient temperature,
    the cold clearance, the stated μ and today's answers to 1e-10."""
    path = edit(tmp_path, "density = 7850.0", "density = 1e-12")
    src = path.read_text()
    for key in ("journal_to_ambient = 0.5", "foil_to_sleeve = 5.0", "sleeve_to_ambient = 1.0"):
        src = src.replace(key, key.split("=")[0] + "= 1e15")
    path.write_text(src + "film_to_journal = 1e15\nfilm_to_foil = 1e15\n")
    bearing, spec = load_running_bearing(path)
    result, point, _ = running_stability(bearing, spec, Rotor(1.5), OperatingPoint(30e3, 20.0),
                                      grid=GRID)
    today = stability(bearing, Rotor(1.5), OperatingPoint(30e3, 20.0), grid=GRID)
    assert abs(point.network.film_k - 293.15) < 1e-10
    assert point.running_clearance == pytest.approx(bearing.radial_clearance, rel=1e-10)
    assert point.viscosity == pytest.approx(bearing.viscosity, rel=1e-10)
    for key in ("critical_mass_kg", "eccentricity", "whirl_frequency_hz", "bearing_number"):
        assert getattr(result, key) == pytest.approx(getattr(today, key), rel=1e-10)


def test_heat_balance_on_the_film_closes_and_rises_with_speed():
    bearing, spec = load_running_bearing(THERMAL)
    cache = SolverCache(GRID)
    from gfbopt.inputs.options import resolve_model_options
    drag = FilmDrag(FilmCase(bearing, resolve_model_options(bearing.options), GRID, cache, 20.0))
    line = speed_line(spec, [15e3, 30e3, 45e3], drag)
    assert all(p.converged for p in line.points)
    for p in line.points:
        assert p.network.heat_out_w == pytest.approx(p.network.power_w, rel=1e-9)
        assert p.static_solves <= 3
        assert p.network.to_side_leakage_w > 0            # the film's ends do leak
    for name in ("power_w", "film_k"):
        values = [getattr(p.network, name) for p in line.points]
        assert values == sorted(values) and len(set(values)) == 3
    growth = [p.centrifugal_growth + p.thermal_growth for p in line.points]
    assert growth == sorted(growth)
    assert len(cache) == 1                   # the clearance is a parameter: one build


def test_stability_cli_reports_the_running_condition():
    result = run_cli("stability", "--bearing", THERMAL, "--rotor-mass-kg", "1.5",
                     "--load-newton", "20", "--speed-rpm", "30000", "--grid", "24x8",
                     "--json")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    assert out["thermal_model"] == HEAT_BALANCE
    assert 15 < out["running_clearance_um"] < 20 and out["film_temperature_c"] > 20
    assert out["running_clearance_um"] == pytest.approx(
        20 - out["centrifugal_growth_um"] - out["thermal_growth_um"], rel=1e-12)
    assert out["viscosity_pa_s"] > 2.98e-5
    text = run_cli("stability", "--bearing", BEARINGS / "ruscitto.toml", "--rotor-mass-kg",
                   "1.5", "--speed-rpm", "30000", "--grid", "24x8").stdout
    assert "clearance model: isothermal, cold clearance" in text


def test_capacity_cli_reports_the_running_condition():
    result = run_cli("capacity", "--bearing", BEARINGS / "ruscitto_centrifugal.toml",
                     "--speed-rpm", "45000", "--min-film-um", "5", "--grid", "24x8", "--json")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    assert out["thermal_model"] == CENTRIFUGAL
    # a 2 mm steel wall: u = ρω²b[(1 − ν)b² + (3 + ν)a²]/(4E)
    w = 45e3 * math.pi / 30
    b, a = 19.05e-3, 17.05e-3
    u = 7850 * w**2 * b * (0.7 * b**2 + 3.3 * a**2) / (4 * 200e9)
    assert out["centrifugal_growth_um"] == pytest.approx(u * 1e6, rel=1e-12)
    assert out["running_clearance_um"] == pytest.approx(20 - u * 1e6, rel=1e-12)
    assert math.isfinite(out["load_capacity_newton"])


def test_capacity_with_heat_is_at_the_running_condition_of_its_answer():
    from gfbopt.cli.running import running_load_capacity
    from gfbopt.thermal.running import running_point

    bearing, spec = load_running_bearing(THERMAL)
    found = running_load_capacity(bearing, spec, 45e3, 5.0, grid=GRID)
    load = found["load_capacity_newton"]
    assert found["thermal_model"] == HEAT_BALANCE and math.isfinite(load)
    # every load of the search at its own running condition (no frozen curve)
    assert len({row["running_clearance_um"] for row in found["curve"]}) == len(found["curve"])
    from gfbopt.inputs.options import resolve_model_options
    drag = FilmDrag(FilmCase(bearing, resolve_model_options(bearing.options), GRID,
                             SolverCache(GRID), load))
    again = running_point(spec, 45e3, drag)
    # the answer is the root at its own running condition: the same fixed point (measured
    # 4e-16; the warm start of its first solve differs)
    assert again.running_clearance * 1e6 == pytest.approx(found["running_clearance_um"],
                                                          rel=1e-9)


def test_lift_off_and_closure_are_reported(tmp_path):
    lift = run_cli("capacity", "--bearing", THERMAL, "--lift-off", "--load-newton", "30",
                   "--min-film-um", "3", "--grid", "24x8", "--json")
    assert lift.returncode == 0, lift.stderr
    out = json.loads(lift.stdout)
    assert out["thermal_model"] == HEAT_BALANCE and math.isfinite(out["lift_off_speed_rpm"])
    assert out["running"]["speed_rpm"] == pytest.approx(out["lift_off_speed_rpm"], rel=2e-3)
    soft = tmp_path / "soft.toml"
    src = (BEARINGS / "ruscitto_centrifugal.toml").read_text()
    soft.write_text(src.replace("youngs_modulus = 200e9 ", "youngs_modulus = 2e9 "))
    closed = run_cli("stability", "--bearing", soft, "--rotor-mass-kg", "1.5",
                     "--load-newton", "20", "--speed-rpm", "45000", "--grid", "24x8")
    assert closed.returncode == 0, closed.stderr
    # where it happens, in closed form (u_c ∝ ω²), not at the speed asked; no state shown
    _, soft_spec = load_running_bearing(soft)
    growth = soft_spec.centrifugal(45e3 * math.pi / 30)
    close = 45e3 * math.sqrt((20e-6 - 1e-6) / growth)
    full = 45e3 * math.sqrt(20e-6 / growth)
    assert soft_spec.centrifugal(full * math.pi / 30) == pytest.approx(20e-6, rel=1e-12)
    assert (f"the journal reaches the foil from {close:,.0f} rpm" in closed.stdout
            and f"clearance at {full:,.0f} rpm" in closed.stdout), closed.stdout
    assert "running clearance -" not in closed.stdout and "no running state" in closed.stdout


def test_side_outflow_conserves_mass_on_a_periodic_film():
    """With a periodic film the ends are the film's only boundary, so the signed axial flux
    ∮ P H³ (−∂P/∂n) dθ over both ends vanishes (mass conservation); side_outflow's one-sided
    differences meet it to the discretisation error, falling with the grid (measured
    −2.8 %, −0.9 %, −0.27 % of the outflow at 24x8, 48x16, 96x32)."""
    import numpy as np
    from gfbopt.static import solve_static
    from gfbopt.thermal.bearing import side_outflow

    bearing = load_running_bearing(BEARINGS / "ruscitto.toml")[0]
    model = bearing.model(30e3, film="periodic", foil="simple")
    ratios = []
    for text in ("24x8", "48x16"):
        grid = Grid.parse(text)
        sol = solve_static(model, load=bearing.nondimensional_load(20.0), grid=grid)
        p, h, dz = sol.pressure, sol.film, sol.z[1] - sol.z[0]
        top = -(3 * p[:, -1] - 4 * p[:, -2] + p[:, -3]) / (2 * dz)
        bottom = (-3 * p[:, 0] + 4 * p[:, 1] - p[:, 2]) / (2 * dz)
        signed = (2 * np.pi / grid.n_theta) * np.sum(p[:, -1] * h[:, -1]**3 * top
                                                     + p[:, 0] * h[:, 0]**3 * bottom)
        ratios.append(abs(signed) / side_outflow(sol))
    assert ratios[1] < 0.015 and ratios[0] / ratios[1] > 2.5
