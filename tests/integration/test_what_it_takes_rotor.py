"""What it would take on the real blower rotor (slow: a few dozen two-bearing onset
searches at 24x8): the side load found makes the chosen design stable to the top speed, a
side load 1e-3 of the span smaller does not, and the figures are those of evaluations made
again from scratch."""
from __future__ import annotations

import copy
import math
from pathlib import Path

import pytest

from gfbopt.design.rotor_objectives import evaluate_rotor_design
from gfbopt.design.lever_runs import lever_point
from gfbopt.design.what_it_takes import parse_levers
from gfbopt.inputs import read_toml
from gfbopt.studies import study_from_dict
from gfbopt.studies.rotor_design import run_design

ROOT = Path(__file__).resolve().parents[2]
FILE = ROOT / "problems" / "rotor_bearing_design.toml"

pytestmark = pytest.mark.slow


def test_the_side_load_found_is_the_threshold_on_the_blower(tmp_path):
    data = copy.deepcopy(read_toml(FILE))
    data.update(name="rd_levers", grid="24x8", search_grid="24x8", regrid_designs=1,
                limit_cycle_revolutions=0.0, speed_range_rpm=[4000.0, 24000.0])
    data["variables"] = [{"name": "radial_clearance_um", "low": 18.0, "high": 30.0}]
    data["search"] = {"method": "nsga2", "budget": 4, "population": 4, "seed": 1}
    data["robustness"] = {"samples": 2, "designs": 1, "tolerances": {}}
    data["what_it_would_take"] = {"side_load_n": {"low": 0.0, "high": 200.0},
                                  "loss_factor": {"low": 0.0, "high": 0.02}}
    loaded = study_from_dict(data, name="rd_levers", file=str(FILE), directory=FILE.parent)
    result = run_design(loaded, tmp_path)
    answers = {a["lever"]: a for a in result.answer["what_it_would_take"] or []}
    assert result.answer["stable_to_top_speed"] is False, result.answer["verdict"]
    plan = loaded.plan
    chosen = result.answer["chosen_design"]
    design = {n: float(chosen[n]) for n in plan.problem.names}
    levers = {v.name: v for v in parse_levers(data["what_it_would_take"], str(FILE))}
    side = answers["side_load_n"]
    assert side["threshold_found"], side
    top = plan.settings.top_speed_rpm

    def onset(value: float) -> float:
        row = evaluate_rotor_design(**lever_point(levers["side_load_n"], value, plan.system,
                                                  design, plan.settings), onset_only=True)
        return row["first_onset_speed_rpm"]
    assert onset(side["threshold_value"]) == pytest.approx(side["threshold_onset_speed_rpm"],
                                                           rel=1e-9)
    assert onset(side["threshold_value"]) >= top
    assert onset(side["threshold_value"] - 1e-3 * 200.0) < top    # the smallest, to 1e-3
    eta = answers["loss_factor"]                               # η to 0.02 cannot
    assert not eta["threshold_found"] and eta["at_bound_value"] == 0.02 and eta["at_bound_onset_speed_rpm"] < top
    assert not math.isnan(eta["at_bound_onset_speed_rpm"])


def test_the_override_answers_as_an_edited_copy_on_real_physics(tmp_path):
    """``--rotor`` (a 5 kg blower) and ``--top-speed 30000`` against a copy of the study with
    those keys edited, on the real evaluation at 24x8 with 4 designs: the same summary.json
    except names and timings."""
    import json

    from cli_inprocess import run_cli

    blower = ROOT / "problems" / "rotors" / "blower.toml"
    rotor = tmp_path / "heavy.toml"
    rotor.write_text(blower.read_text().replace("mass = 3.2 ", "mass = 5.0 ").replace(
        '"../bearings/ruscitto.toml"', f'"{ROOT / "problems" / "bearings" / "ruscitto.toml"}"'))
    base = """
kind = "rotor_bearing_design"
title = "tiny"
grid = "24x8"
search_grid = "24x8"
regrid_designs = 1
limit_cycle_revolutions = 0.0
goal = "front"
heaviest_load_factor = 2.0
min_film_um = 1.5
[[variables]]
name = "radial_clearance_um"
low = 18.0
high = 30.0
[search]
method = "nsga2"
budget = 4
population = 4
seed = 1
[what_it_would_take]
side_load_n = {low = 0.0, high = 40.0}
"""
    study = tmp_path / "tiny.toml"
    study.write_text(f'rotor = "{blower}"\nspeed_range_rpm = [4000.0, 45000.0]\n' + base)
    copy_ = tmp_path / "copy.toml"
    copy_.write_text('rotor = "heavy.toml"\nspeed_range_rpm = [4000.0, 30000.0]\n' + base)
    results = tmp_path / "results"
    for args in ([study, "--rotor", rotor, "--top-speed", "30000"], [copy_]):
        out = run_cli("run", *args, "--results", results, "--workers", "1")
        assert out.returncode == 0, out.stderr
    skip = ("name", "title", "source", "problem_file", "wall_time_s", "provenance")

    def answer(name):
        s = json.loads((results / name / "summary.json").read_text())
        s["notes"] = [n for n in s["notes"] if not n.startswith(("Search:", "What it"))]
        return {k: v for k, v in s.items() if k not in skip}
    a, b = answer("tiny_on_heavy_to_30000rpm"), answer("copy")
    assert a == b
    assert a["verdict"].startswith(("Stable to 30,000 rpm", "No design in this space"))
