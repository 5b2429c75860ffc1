"""The heat balance's validity limit and where a runaway or closure happens (reviewer h10).

* A film hotter than the model's limit has no valid state: by default the top of
  Sutherland's range for air (1900 K, White 2006 Table 1-2), or [thermal]
  max_film_temperature.  ruscitto_thermal.toml with 0.01 W/K to ambient used to report a
  "running" film of 11,098 °C at 30 krpm; now thermal runaway, bracketed from rest (≤ 1 %).
* Closure by the centrifugal growth is found in closed form (u_c ∝ ω²): the 20 µm
  ruscitto_centrifugal clearance is used up at 89,672 rpm (and falls to the 1 µm floor at
  87,401 rpm), not "at 95000 rpm"; no negative running clearance is reported.
* gfbopt capacity with the clearance closed: one answer, every figure of the search null."""
from __future__ import annotations

import dataclasses
import json
import math
import re
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import Grid
from gfbopt.inputs.options import resolve_model_options
from gfbopt.static import SolverCache
from gfbopt.thermal.bearing import FilmCase, FilmDrag
from gfbopt.thermal.files import load_running_bearing
from gfbopt.thermal.network import SUTHERLAND_AIR_MAX_K
from gfbopt.thermal.running import KELVIN, speed_line
from tests.cli_inprocess import run_cli

BEARINGS = Path(__file__).resolve().parents[2] / "problems" / "bearings"
GRID = Grid.parse("24x8")


@pytest.fixture(scope="module")
def hot(tmp_path_factory):
    src = (BEARINGS / "ruscitto_thermal.toml").read_text()
    for old, new in (("journal_to_ambient = 0.5 ", "journal_to_ambient = 0.01"),
                     ("sleeve_to_ambient = 1.0 ", "sleeve_to_ambient = 0.01")):
        assert old in src
        src = src.replace(old, new)
    path = tmp_path_factory.mktemp("hot") / "hot.toml"
    path.write_text(src)
    return path


def _drag(bearing, load):
    return FilmDrag(FilmCase(bearing, resolve_model_options(bearing.options), GRID,
                             SolverCache(GRID), load))


def test_an_impossible_film_temperature_is_a_runaway_bracketed_from_rest(hot):
    result = run_cli("stability", "--bearing", hot, "--rotor-mass-kg", "2", "--speed-rpm",
                     "30000", "--grid", "24x8", "--json")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    assert out["verdict"] == "runaway"                        # never a normal verdict
    for key in ("running_clearance_um", "thermal_growth_um", "film_temperature_c",
                "viscosity_pa_s"):
        assert out[key] is None, key                          # no state after the runaway
    message = out["running"]["thermal_message"]
    assert f"film above {SUTHERLAND_AIR_MAX_K - KELVIN:.0f} °C" in message
    low, high = (float(g.replace(",", "")) for g in re.search(
        r"bracketed in \[([\d,]+), ([\d,]+)\] rpm", message).groups())
    assert high / low - 1 <= 0.01 and high < 30000
    # the bracket is the model's: just below it the film is at most the limit, above none
    bearing, spec = load_running_bearing(hot)
    line = speed_line(spec, [0.98 * low, 1.02 * high], _drag(bearing, 2 * 9.80665))
    good = line.points[0]
    assert good.converged and good.network.film_k <= SUTHERLAND_AIR_MAX_K
    assert not line.points[1].converged and "film above" in line.points[1].message


def test_a_stated_film_limit_moves_the_runaway_down(hot):
    bearing, spec = load_running_bearing(hot)
    limit = 650.0 + KELVIN                         # e.g. a foil coating's service limit
    cooler = dataclasses.replace(spec, thermal=dataclasses.replace(
        spec.thermal, max_film_temperature=limit))
    drag = _drag(bearing, 20.0)
    default = speed_line(spec, [5e3, 25e3], drag)
    stated = speed_line(cooler, [5e3, 25e3], drag)
    assert stated.limit_rpm < default.limit_low_rpm
    assert "film above 650 °C" in stated.message and "max_film_temperature" in stated.message
    below = speed_line(cooler, [stated.limit_low_rpm], drag).points[0]
    assert below.converged and below.network.film_k <= limit
    with pytest.raises(ParameterError, match="max_film_temperature"):
        dataclasses.replace(spec.thermal, max_film_temperature=250.0).check()


def test_closure_is_reported_where_the_growth_uses_the_clearance():
    result = run_cli("stability", "--bearing", BEARINGS / "ruscitto_centrifugal.toml",
                     "--rotor-mass-kg", "2", "--speed-rpm", "95000", "--grid", "24x8",
                     "--json")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    _, spec = load_running_bearing(BEARINGS / "ruscitto_centrifugal.toml")
    growth = spec.centrifugal(95e3 * math.pi / 30)
    full = 95e3 * math.sqrt(20e-6 / growth)
    assert full == pytest.approx(89672, abs=1)                # the reviewer's hand value
    message = out["running"]["thermal_message"]
    assert f"at {full:,.0f} rpm" in message and "at 95000 rpm" not in message
    assert out["running_clearance_um"] is None and out["verdict"] == "closure"
    assert out["centrifugal_growth_um"] == pytest.approx(growth * 1e6, rel=1e-12)


def test_capacity_with_the_clearance_closed_is_one_answer():
    result = run_cli("capacity", "--bearing", BEARINGS / "ruscitto_centrifugal.toml",
                     "--speed-rpm", "95000", "--min-film-um", "2", "--grid", "24x8", "--json")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    assert out["answer"].startswith("no load capacity at 95,000 rpm: the journal reaches")
    for key in ("load_capacity_newton", "load_newton", "min_film_thickness_um",
                "running_clearance_um"):
        assert out[key] is None, key
    assert out["curve"] == [] and out["thermal_static_solves"] == 0
