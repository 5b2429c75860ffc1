"""A design study's fixed inputs (the bore's form, the pad offset, the zone edges) are checked
when it is planned: before, a 3 × 200° shim bore or an offset of 1e300° made every design fail
and the run ended "No design in this space meets every limit" with exit 0."""
import pytest

from gfbopt.errors import ParameterError
from tests.cli_inprocess import run_cli
from tests.unit.test_rotor_design_spec import FILE, _plan


@pytest.mark.parametrize("change, key, rule", [
    (lambda d: d["bore"].update(width_deg=200.0), "bore.width_deg", "overlap"),
    (lambda d: d["bore"].update(offset_deg=1e300), "bore.offset_deg", "degrees"),
    (lambda d: d["bore"].update(count=40), "bore.count", "must be <= 12"),
    (lambda d: (d.update(pad_offset_deg=-1e300),
                d["variables"].append({"name": "pads", "values": [1, 3]})),
     "pad_offset_deg", "degrees"),
    (lambda d: d["variables"].append({"name": "pads", "values": [1, 30]}),
     "variables[2].values", "at most 12 top-foil pads"),
    (lambda d: d["variables"][0].update(low=1e-300), "variables[0].low", "radial_clearance"),
    (lambda d: d.update(min_film_um=1e300), "min_film_um", "below the radial clearance"),
    (lambda d: d.update(speed_range_rpm=[1000.0, 1e7]), "speed_range_rpm", "surface"),
])
def test_an_invalid_fixed_input_is_refused_at_plan_time(change, key, rule):
    with pytest.raises(ParameterError) as exc:
        _plan(change)
    assert exc.value.name.endswith(key) and rule in exc.value.rule, str(exc.value)


def test_the_command_line_exits_2_before_any_solve(tmp_path):
    text = FILE.read_text().replace("width_deg = 60.0", "width_deg = 200.0")
    study = tmp_path / "rotor_bearing_design.toml"
    rotor = (FILE.parent / "rotors" / "blower.toml").as_posix()
    study.write_text(text.replace('rotor = "rotors/blower.toml"', f'rotor = "{rotor}"'))
    out = run_cli("run", study, "--results", tmp_path / "results", "--workers", "1")
    assert out.returncode == 2, out.stderr[-500:]
    assert out.stderr.count("gfbopt: error:") == 1 and "bore.width_deg" in out.stderr
    assert not (tmp_path / "results" / "rotor_bearing_design" / "evaluations.csv").exists()
