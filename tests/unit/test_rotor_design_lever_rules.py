"""Every lever of each bearing: the per-bearing preload levers reach the bearing they name,
and a lever a bearing cannot take is one ParameterError line naming the file, the key and
the rule, at plan time (before any solve)."""
import copy
from pathlib import Path

import pytest

from gfbopt.design.rotor_objectives import EvaluationSettings, apply_design
from gfbopt.errors import ParameterError
from gfbopt.inputs import read_toml
from gfbopt.inputs.grid import Grid
from gfbopt.studies import study_from_dict

ROOT = Path(__file__).resolve().parents[2]
FILE = ROOT / "problems" / "rotor_bearing_design.toml"
NAME = "problems/rotor_bearing_design.toml"


def _plan(variables, **top):
    data = copy.deepcopy(read_toml(FILE))
    data["variables"] = variables
    data["robustness"]["tolerances"] = {}
    data.update(top)
    return study_from_dict(data, name="t", file=NAME, directory=FILE.parent).plan


def _refusal(variables, **top) -> str:
    with pytest.raises(ParameterError) as info:
        _plan(variables, **top)
    text = str(info.value)
    assert "\n" not in text
    return text


C = {"name": "A:radial_clearance_um", "low": 15.0, "high": 35.0}


def test_the_shipped_study_designs_each_bearing_separately():
    plan = _plan(read_toml(FILE)["variables"])
    names = plan.problem.names
    assert {n.split(":")[0] for n in names} == {"A", "B"}
    assert {n.split(":")[1] for n in names} == {"radial_clearance_um", "preload_depth_um"}
    assert plan.search.method == "nsga2_refine"


def test_per_bearing_preload_levers_reach_their_bearing():
    plan = _plan([C, {"name": "A:preload_depth_um", "low": 0.0, "high": 10.0},
                  {"name": "B:preload_depth_um", "low": 0.0, "high": 10.0},
                  {"name": "B:preload_offset_deg", "low": 0.0, "high": 60.0},
                  {"name": "B:preload_width_deg", "low": 30.0, "high": 90.0}])
    s = EvaluationSettings(4000.0, 45000.0, 56250.0, Grid.parse("36x10"))
    system, _ = apply_design(plan.system, {"A:radial_clearance_um": 20.0,
                                           "A:preload_depth_um": 4.0,
                                           "B:preload_depth_um": 6.0,
                                           "B:preload_offset_deg": 30.0,
                                           "B:preload_width_deg": 45.0}, s)
    a, b = (x.geometry for x in system.bearings)
    assert a.radial_clearance == pytest.approx(20e-6)
    assert (a.build.bore.preload_depth, a.build.bore.offset_deg,
            a.build.bore.width_deg) == (pytest.approx(4e-6), 0.0, 60.0)
    assert (b.build.bore.preload_depth, b.build.bore.offset_deg,
            b.build.bore.width_deg) == (pytest.approx(6e-6), 30.0, 45.0)


def test_a_preload_as_deep_as_the_clearance_is_refused():
    text = _refusal([C, {"name": "A:preload_depth_um", "low": 0.0, "high": 15.0}])
    assert text.startswith(f"{NAME}: variables[1].high = 15")
    assert "closes the film" in text and "bearing A" in text
    # bearing B keeps the file's clearance (≈ 31.8 µm on the Ruscitto bearing): 15 µm is fine
    _plan([C, {"name": "B:preload_depth_um", "low": 0.0, "high": 15.0}])


def test_lobes_on_a_bearing_with_pads_are_refused():
    text = _refusal([C, {"name": "A:preload_depth_um", "low": 0.0, "high": 8.0},
                     {"name": "A:pads", "values": [1, 3]}],
                    bore={"kind": "lobes", "count": 3, "offset_deg": 0.0})
    assert text.startswith(f"{NAME}: variables[2].name = ") and "A:pads" in text
    assert "cannot take pads" in text


def test_a_shim_width_with_lobes_or_overlapping_shims_is_refused():
    text = _refusal([{"name": "preload_depth_um", "low": 0.0, "high": 8.0},
                     {"name": "preload_width_deg", "low": 30.0, "high": 90.0}],
                    bore={"kind": "lobes", "count": 3, "offset_deg": 0.0})
    assert text.startswith(f"{NAME}: variables[1].name") and "a shim's" in text
    text = _refusal([{"name": "preload_depth_um", "low": 0.0, "high": 8.0},
                     {"name": "preload_width_deg", "low": 30.0, "high": 150.0}])
    assert text.startswith(f"{NAME}: variables[1].high = 150") and "overlap" in text


def test_a_preload_lever_without_a_preload_is_refused():
    text = _refusal([C, {"name": "A:preload_offset_deg", "low": 0.0, "high": 60.0}])
    assert text.startswith(f"{NAME}: variables[1].name = ")
    assert "A:preload_offset_deg" in text
    assert "changes nothing" in text


def test_the_what_it_would_take_table_is_passed_through():
    table = {"loss_factor": {"low": 0.0, "high": 0.5}}
    try:
        plan = _plan(read_toml(FILE)["variables"], what_it_would_take=table)
    except ParameterError as exc:        # a schema without the key refuses it: not ours
        pytest.fail(f"the study schema does not take [what_it_would_take]: {exc}")
    assert plan.what_it_would_take == table
