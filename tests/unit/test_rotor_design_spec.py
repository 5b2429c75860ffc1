"""The rotor bearing-pair design study: its file is validated before any solve — bad input is
one ParameterError naming the file, the key, the value and the rule (exit 2 from the CLI)."""
import copy
import subprocess
import sys
from pathlib import Path

import pytest

from gfbopt.design.rotor_objectives import EvaluationSettings, apply_design
from gfbopt.errors import ParameterError
from gfbopt.inputs import read_toml
from gfbopt.inputs.grid import Grid
from gfbopt.studies import study_from_dict

ROOT = Path(__file__).resolve().parents[2]
FILE = ROOT / "problems" / "rotor_bearing_design.toml"
BASE = read_toml(FILE)
#: the keys these tests index, fixed here (the shipped study designs A and B separately):
#: shared clearance, shared shim depth, their tolerances
BASE["variables"] = [{"name": "radial_clearance_um", "low": 15.0, "high": 35.0},
                     {"name": "preload_depth_um", "low": 0.0, "high": 12.0}]
BASE["robustness"]["tolerances"] = {"radial_clearance_um": 1.0, "preload_depth_um": 1.0}


def _plan(change):
    data = copy.deepcopy(BASE)
    change(data)
    return study_from_dict(data, name="t", file="problems/rotor_bearing_design.toml",
                           directory=FILE.parent).plan


def test_the_shipped_study_plans():
    plan = _plan(lambda d: None)
    assert [o.name for o in plan.problem.objectives] == ["first_onset_speed_rpm",
                                                         "total_power_loss_w"]
    assert plan.settings.grid == Grid.parse("36x10")
    assert plan.default_settings.grid == Grid.parse("144x36")
    assert plan.settings.loss_factor == 0.0 and plan.loss_factor_band == (0.0, 0.2)
    assert plan.settings.search_high_rpm == pytest.approx(1.25 * 45000.0)


def _var(data, k, **kw):
    data["variables"][k].update(kw)


@pytest.mark.parametrize("change, key, rule", [
    (lambda d: _var(d, 0, low=35.0, high=15.0), "variables[0]", "low < high"),
    (lambda d: _var(d, 0, low=20.0, high=20.0), "variables[0]", "low < high"),
    (lambda d: _var(d, 0, name="shaft_colour"), "variables[0].name",
     "is not a design variable"),
    (lambda d: _var(d, 0, name="C:radial_clearance_um"), "variables[0].name",
     "names no bearing"),
    (lambda d: _var(d, 1, name="radial_clearance_um"), "variables[1].name", "twice"),
    (lambda d: _var(d, 1, low=-2.0), "variables[1]", ">= 0"),
    (lambda d: d["variables"].append({"name": "pads", "low": 1.0, "high": 3.0}),
     "variables[2].values", "whole number"),
    (lambda d: d.update(speed_range_rpm=[45000.0, 4000.0]), "speed_range_rpm",
     "0 < lowest < top"),
    (lambda d: d.update(search_high_rpm=30000.0), "search_high_rpm", ">= the top speed"),
    (lambda d: d["robustness"]["tolerances"].update(radial_clearance_um=10.0),
     "robustness.tolerances.radial_clearance_um", "not smaller than the variable's range"),
    (lambda d: d["robustness"]["tolerances"].update(bump_thickness_um=2.0),
     "robustness.tolerances.bump_thickness_um", "not a design variable"),
    (lambda d: d.update(loss_factor_band=[0.3, 0.1]), "loss_factor_band", "0 <= low <= high"),
    (lambda d: d["search"].update(method="bayes"), "search.method", "one objective"),
    (lambda d: d.update(max_lift_off_speed_rpm=3000.0), "lift_off_film_um", "is needed"),
    (lambda d: d["variables"].extend([{"name": "compliance", "low": 0.3, "high": 2.0},
                                      {"name": "bump_pitch_mm", "low": 3.0, "high": 5.0}]),
     "variables", "not both"),
    (lambda d: d.update(goal="cheapest"), "goal", "must be one of"),
    (lambda d: d.update(zone_edges_deg=[0.0, 120.0, 240.0]), "zone_edges_deg",
     "first + 360"),
    (lambda d: d.update(zone_edges_deg=[0.0, 240.0, 120.0, 360.0]), "zone_edges_deg",
     "increasing"),
    (lambda d: (d.update(zone_edges_deg=[0.0, 180.0, 360.0]),
                d["variables"].append({"name": "zone3_bump_thickness_um", "low": 60.0,
                                       "high": 150.0})),
     "variables[2].name", "names bump zone 3"),
    (lambda d: d["variables"].append({"name": "zone1_bump_thickness_um", "low": 60.0,
                                      "high": 150.0}),
     "variables[2].name", "gives 0 zone(s)"),
    (lambda d: d.update(rotor="rotors/missing.toml"), "rotor", ""),
])
def test_bad_input_names_file_key_and_rule(change, key, rule):
    with pytest.raises(ParameterError) as info:
        _plan(change)
    text = str(info.value)
    assert text.startswith(f"problems/rotor_bearing_design.toml: {key}"), text
    assert rule in text
    assert "\n" not in text


def test_cli_refuses_bad_input_in_one_line_with_exit_2(tmp_path):
    text = FILE.read_text().replace("low = 15.0\nhigh = 35.0", "low = 35.0\nhigh = 15.0")
    bad = tmp_path / "bad_design.toml"
    bad.write_text(text.replace('rotor = "rotors/blower.toml"',
                                f'rotor = "{FILE.parent / "rotors" / "blower.toml"}"'))
    out = subprocess.run([sys.executable, "-m", "gfbopt", "run", str(bad),
                          "--results", str(tmp_path / "r")], capture_output=True, text=True,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert out.returncode == 2, out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "variables[0]" in lines[0] and "low < high" in lines[0]
    assert not (tmp_path / "r" / "bad_design").exists()          # nothing was solved


def test_design_values_reach_the_bearings():
    """A design changes both bearings (unprefixed) or one (prefixed), in SI, with the shim
    preload as the bore of the as-built bearing."""
    plan = _plan(lambda d: None)
    s = EvaluationSettings(4000.0, 45000.0, 56250.0, Grid.parse("36x10"))
    system, _ = apply_design(plan.system, {"radial_clearance_um": 25.0,
                                           "B:preload_depth_um": 5.0}, s)
    a, b = (x.geometry for x in system.bearings)
    assert a.radial_clearance == pytest.approx(25e-6) == b.radial_clearance
    assert a.build is None or a.build.bore.kind == "round"
    assert (b.build.bore.kind, b.build.bore.count) == ("shims", 3)
    assert b.build.bore.preload_depth == pytest.approx(5e-6)
    with pytest.raises(ParameterError, match="not a design variable"):
        apply_design(plan.system, {"colour": 1.0}, s)


def test_resume_is_an_option_of_design_studies():
    """gfbopt run --resume acts on a design study (it continues the stored search) and is
    still refused for a study kind that has no store."""
    from argparse import Namespace

    from gfbopt.cli.run import _check_options
    from gfbopt.studies import load_study

    args = Namespace(workers=1, max_workers=None, scheduler=None, resume=True)
    assert _check_options(args, [load_study(FILE)]) == 1
    other = load_study(ROOT / "problems" / "thesis_table_3_1.toml")
    with pytest.raises(ParameterError, match="--resume"):
        _check_options(args, [other])
