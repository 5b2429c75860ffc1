"""``gfbopt capacity`` refuses a minimum-film limit thinner than any real surface and a speed
below the model's bearing-number floor (one line, exit 2, before any solve), and a load
capacity above the load ceiling 100 p_a L D is an answer, not an error about a load the
user never gave."""
import json
from pathlib import Path

import pytest

from gfbopt import Grid
from gfbopt.errors import ParameterError
from gfbopt.inputs import load_bearing
from gfbopt.inputs.rotor_limits import MAX_SPECIFIC_LOAD_RATIO, MIN_BEARING_NUMBER
from gfbopt.rotor.capacity import MIN_FILM_LIMIT_UM, load_capacity
import gfbopt.rotor.capacity as capacity

from cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
RUSCITTO = REPO / "problems/bearings/ruscitto.toml"
GRID = Grid(24, 8)


@pytest.fixture
def no_solve(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("a static solve was started")
    monkeypatch.setattr(capacity, "solve_static", refuse)


@pytest.mark.parametrize("args, name, rule", [
    (["--speed-rpm", "30000", "--min-film-um", "1e-300"], "--min-film-um",
     f">= {MIN_FILM_LIMIT_UM:g} µm"),
    (["--speed-rpm", "1e-300", "--min-film-um", "5"], "--speed-rpm", "bearing number"),
    (["--lift-off", "--load-newton", "20", "--min-film-um", "5", "--max-speed-rpm", "1e-300"],
     "--max-speed-rpm", "bearing number"),
    (["--lift-off", "--load-newton", "1e9", "--min-film-um", "5"], "--load-newton", "p_a L D")])
def test_impossible_capacity_input_is_one_line_exit_2(capsys, no_solve, args, name, rule):
    from gfbopt.cli import main

    assert main(["capacity", "--bearing", str(RUSCITTO), "--grid", "24x8", *args]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"gfbopt: error: {name} = ") and rule in err and "\n" not in err


def test_speed_floor_is_the_models_bearing_number_floor(no_solve):
    geometry = load_bearing(RUSCITTO)
    slowest = MIN_BEARING_NUMBER / geometry.bearing_number(1.0)
    with pytest.raises(ParameterError, match="speed_rpm"):
        load_capacity(geometry, 0.5 * slowest, 5.0, grid=GRID)


def test_capacity_above_the_load_ceiling_is_an_answer():
    """A rigid foil at 250,000 rpm keeps h_min above 0.01 µm up to 100 p_a L D: the march
    stops there and says so (before: exit 2 naming load_newton = 1.63e4 N)."""
    geometry = load_bearing(RUSCITTO)
    ceiling = MAX_SPECIFIC_LOAD_RATIO * geometry.ambient_pressure * geometry.length \
        * 2 * geometry.radius
    out = run_cli("capacity", "--bearing", str(RUSCITTO), "--speed-rpm", "250000",
                  "--min-film-um", "0.01", "--foil", "rigid", "--grid", "24x8", "--json",
                  cwd=REPO)
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["success"] and data["load_capacity_newton"] is None      # nan in JSON
    assert data["answer"].startswith(f"capacity above the load ceiling of {ceiling:.4g} N")
    loads = [r["load_newton"] for r in data["curve"]]
    assert max(loads) == pytest.approx(ceiling, rel=1e-12)
    assert data["min_film_thickness_um"] > 0.01


def test_a_capacity_the_film_limit_did_not_set_says_so():
    """When the equilibrium is lost (the solve fails) before h_min reaches the limit, the
    answer is the largest load the film carries and says so, with the film it has there —
    never 'h_min = limit' beside a thicker film (before: "load capacity 634.73 N (h_min =
    0.01 µm)" with 0.0222 µm at the answer).  An answer the limit sets keeps its words."""
    from gfbopt.inputs import Grid, load_bearing
    from gfbopt.rotor.capacity import load_capacity

    bearing = load_bearing(str(Path(__file__).resolve().parents[2] / "problems" / "bearings"
                               / "ruscitto.toml"))
    lost = load_capacity(bearing, 30000.0, 0.01, grid=Grid(24, 8))
    assert lost.min_film_thickness_um > 1.5 * 0.01
    assert "equilibrium is lost before h_min reaches 0.01 µm" in lost.answer
    assert f"h_min = {lost.min_film_thickness_um:.4g} µm there" in lost.answer
    assert lost.to_dict()["load_capacity_newton"] == lost.value > 0
    held = load_capacity(bearing, 30000.0, 5.0, grid=Grid(24, 8))
    assert held.min_film_thickness_um == pytest.approx(5.0, rel=1e-6)
    assert held.message == "" and "(h_min = 5 µm)" in held.answer
