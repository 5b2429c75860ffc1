"""``gfbopt design`` end to end: register the sub-command on a fresh argparse parser, parse,
run, read what it prints.  (The main ``gfbopt`` command wires in ``register`` itself.)"""
import argparse
import json
import math

import pytest

from gfbopt.cli import design as cli_design
from gfbopt.design import OBJECTIVES
from gfbopt.errors import ParameterError

EXAMPLE = ["design", "--target-compliance", "0.664", "--radial-clearance", "32e-6"]


def parse(argv):
    parser = argparse.ArgumentParser(prog="gfbopt")
    cli_design.register(parser.add_subparsers(dest="command", required=True))
    return parser.parse_args(argv)


def run_json(argv, capsys):
    args = parse(argv + ["--json"])
    code = args.handler(args)
    return code, json.loads(capsys.readouterr().out)


def test_design_json_has_the_geometry_and_the_conventions(capsys):
    code, out = run_json(EXAMPLE, capsys)
    assert code == 0
    assert out["status"] == "optimal" and out["success"] is True
    # DESIGN_NOTES example with p_a = 101325 Pa: s = 6 mm, l0 = 2.9 mm, t_b = 181.4 µm,
    # σ_b = 158.6 MPa (solver tolerance ~1e-8 in the logarithms)
    assert out["bump_pitch_m"] == pytest.approx(6e-3, rel=1e-6)
    assert out["half_bump_length_m"] == pytest.approx(2.9e-3, rel=1e-6)
    assert out["bump_thickness_m"] == pytest.approx(181.44e-6, abs=0.01e-6)
    assert out["compliance"] == pytest.approx(0.664, rel=1e-6)
    assert out["bump_stress_pa"] == pytest.approx(158.56e6, abs=0.01e6)
    assert set(out["binding_constraints"]) == {"pitch <= 6 mm", "bump closes within pitch"}
    assert out["compliance_range"] == [pytest.approx(8.47e-4, rel=1e-3),
                                       pytest.approx(1.815, rel=1e-3)]
    assert out["number_of_bumps"] is None
    assert out["relaxations"] == []
    options = out["options"]
    assert options["material"]["name"] == "inconel-x750"
    assert options["youngs_modulus"] == 214e9 and options["poisson_ratio"] == 0.29
    assert options["allowable_stress"] == 310e6 and out["allowable_stress_pa"] == 310e6
    assert options["ambient_pressure"] == 101325.0 and options["design_pressure"] == 1e5
    assert options["pitch_range"] == [2e-3, 6e-3] and options["gap"] == 2e-4
    assert "ASTM B637" in out["conventions"]["material_source"]
    assert "Heshmat, Walowit & Pinkus 1983" in out["conventions"]["references"]
    assert out["conventions"]["units"] == "SI (m, Pa)"


def test_design_with_radius_reports_a_whole_number_of_bumps(capsys):
    code, out = run_json(EXAMPLE + ["--radius", "19.05e-3"], capsys)
    assert code == 0
    assert out["number_of_bumps"] == 20
    assert out["bump_pitch_m"] == pytest.approx(2 * math.pi * 19.05e-3 / 20, rel=1e-12)


def test_infeasible_design_exits_1_and_says_what_must_move(capsys):
    code, out = run_json(EXAMPLE + ["--allowable-stress", "140e6"], capsys)
    assert code == 1
    assert out["success"] is False and out["status"] == "infeasible"
    assert out["bump_pitch_m"] is None  # NaN is written as null
    (move,) = out["relaxations"]
    assert move["limit"] == "allowable stress" and move["unit"] == "MPa"
    assert move["required"] == pytest.approx(158.56, abs=0.01)
    assert "allowable stress must rise by 13.3 % (to 158.6 MPa)" in out["message"]


def test_text_report(capsys):
    args = parse(EXAMPLE + ["--pitch-range", "2e-3", "5e-3", "--material", "inconel-x750-538c"])
    assert args.handler(args) == 0
    text = capsys.readouterr().out
    assert text.startswith("gfbopt design — optimal")
    assert "bump pitch s            5.0000 mm" in text
    assert "E = 184 GPa" in text and "binding" in text and "pitch <= 5 mm" in text


def test_band_target_and_overrides_reach_the_spec(capsys):
    code, out = run_json(["design", "--target-compliance", "0.5", "0.8",
                          "--radial-clearance", "32e-6", "--youngs-modulus", "200e9",
                          "--poisson-ratio", "0.3", "--ambient-pressure", "1e5",
                          "--gap", "0", "--objective", "thickness"], capsys)
    assert code == 0
    assert out["target_compliance"] == [0.5, 0.8] and out["objective"] == "thickness"
    assert out["options"]["youngs_modulus"] == 200e9
    assert out["options"]["poisson_ratio"] == 0.3
    # the thinnest foil is the lower end of its range, 50 µm
    assert out["bump_thickness_m"] == pytest.approx(50e-6, rel=1e-6)


def test_bad_input_raises_parameter_error_for_the_main_command():
    args = parse(["design", "--target-compliance", "0.664", "--radial-clearance", "-1"])
    with pytest.raises(ParameterError, match=r"radial_clearance = -1.0: must be finite and > 0"):
        args.handler(args)
    args = parse(["design", "--target-compliance", "1", "2", "3", "--radial-clearance", "3e-5"])
    with pytest.raises(ParameterError, match=r"target-compliance = \[1.0, 2.0, 3.0\]"):
        args.handler(args)


def test_help_states_the_defaults_and_their_sources(capsys):
    with pytest.raises(SystemExit):
        parse(["design", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "default inconel-x750" in text and "Inconel X-750" in text
    assert "default 101325" in text and "default 1e5, 1 bar" in text
    assert "310 MPa" in text and "ASTM B637" in text and "design choice" in text


def test_objective_choices_match_the_program():
    assert cli_design._OBJECTIVES == OBJECTIVES
