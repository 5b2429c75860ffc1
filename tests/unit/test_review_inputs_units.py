"""One name, one unit (review defects 2 and 4): ``hardening_limit`` is δ_lim in metres in
every output (the non-dimensional δ_lim/c is ``hardening_limit_ratio``), and a [thermal]
temperature typed in Celsius (below Sutherland's 170 K) is refused at file read."""
import json
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs.file_schema import check_table
from gfbopt.inputs.thermal_tables import THERMAL
from gfbopt.terms import friction
from gfbopt.thermal.files import load_running_bearing

from tests.cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]
RUSCITTO = ROOT / "problems/bearings/ruscitto.toml"
THERMAL_FILE = ROOT / "problems/bearings/ruscitto_thermal.toml"
LIMIT_M = 0.4e-3                            # δ_lim; c = 20 µm, so δ_lim/c = 20
HARDENED = "bump_height = 0.5e-3\nhardening_exponent = 3\nhardening_limit = 0.4e-3\n"
POINT = ("--load-newton", "20", "--speed-rpm", "30000", "--grid", "24x8", "--json")


def _keys(obj, name, found):
    """Every value of key ``name`` anywhere in a JSON tree."""
    if isinstance(obj, dict):
        for key, value in obj.items():
            if key == name:
                found.append(value)
            _keys(value, name, found)
    elif isinstance(obj, list):
        for value in obj:
            _keys(value, name, found)
    return found


@pytest.mark.parametrize("command", ["static", "stability"])
def test_hardening_limit_is_metres_in_every_output(tmp_path, command):
    path = tmp_path / "h.toml"
    path.write_text(RUSCITTO.read_text() + HARDENED)
    extra = ("--rotor-mass-kg", "2") if command == "stability" else ()
    out = run_cli(command, "--bearing", str(path), *extra, *POINT, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    limits = _keys(data, "hardening_limit", [])
    assert all(v == LIMIT_M for v in limits)          # before: static printed 20.0 here
    ratios = _keys(data, "hardening_limit_ratio", [])
    assert limits or ratios
    assert all(v == pytest.approx(LIMIT_M / 20e-6, rel=1e-12) for v in ratios)
    assert command != "static" or ratios               # the static output states the ratio


def test_the_glossary_gives_each_name_its_unit():
    assert friction.TERMS["hardening_limit"][0] == "m"
    assert friction.TERMS["hardening_limit_ratio"][0] == "-"


TEMPERATURES = ("ambient_temperature", "reference_temperature", "viscosity_temperature",
                "cooling_inlet_temperature", "max_film_temperature")


@pytest.mark.parametrize("key", TEMPERATURES)
def test_a_celsius_temperature_is_refused_with_the_unit(tmp_path, key):
    text = THERMAL_FILE.read_text().replace("[thermal]\n", f"[thermal]\n{key} = 20\n", 1)
    if key == "ambient_temperature":
        text = text.replace("ambient_temperature = 293.15", "", 1)
    path = tmp_path / "cold.toml"
    path.write_text(text)
    with pytest.raises(ParameterError) as err:
        load_running_bearing(path)
    message = str(err.value)
    assert message.startswith(f"cold.toml: thermal.{key} = 20: must be >= 170 K")
    assert "kelvin" in message and "\n" not in message


def test_the_reviewers_file_exits_2_before_any_solve(tmp_path):
    """Before: accepted as 20 K and answered 'thermal runaway from 22,031 rpm', exit 0."""
    path = tmp_path / "cold.toml"
    path.write_text(THERMAL_FILE.read_text().replace("ambient_temperature = 293.15",
                                                     "ambient_temperature = 20"))
    out = run_cli("stability", "--bearing", str(path), "--rotor-mass-kg", "2", *POINT[:-1],
                  cwd=ROOT)
    assert out.returncode == 2 and out.stdout == ""
    assert len(out.stderr.strip().splitlines()) == 1 and "kelvin" in out.stderr


def test_the_bound_is_sutherlands_170_k():
    base = {"journal_to_ambient": 0.5, "foil_to_sleeve": 5.0, "sleeve_to_ambient": 1.0,
            "sleeve_expansion_coefficient": 12e-6}
    assert check_table({**base, "ambient_temperature": 170.0}, THERMAL, "f")[
        "ambient_temperature"] == 170.0
    with pytest.raises(ParameterError, match="must be >= 170 K"):
        check_table({**base, "ambient_temperature": 169.9}, THERMAL, "f")
