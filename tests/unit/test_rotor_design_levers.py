"""The design study's film check at shim edges and its pad lever (default tier: coarse grids,
a few seconds)."""
import copy
import dataclasses
from pathlib import Path

import numpy as np
import pytest

from gfbopt.design.rotor_objectives import (EvaluationSettings, _static, apply_design,
                                            evaluate_rotor_design, film_um)
from gfbopt.inputs import read_toml
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.options import ModelOptions
from gfbopt.physics.bore import step_film
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.static import SolverCache
from gfbopt.studies import study_from_dict

ROOT = Path(__file__).resolve().parents[2]
FILE = ROOT / "problems" / "rotor_bearing_design.toml"


@pytest.fixture(autouse=True, scope="module")
def _one_blas_thread():
    """One BLAS thread, as gfbopt runs and its pool workers use: these small dense and
    sparse solves are several times slower with threads competing on 2 shared cores."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(1):
        yield


def test_step_film_takes_the_shim_side_with_the_smaller_deflection():
    """Four rows, a shim (B = −0.5) on rows 1–2: the steps are 0|1 and 2|3; at each the shim
    row's rigid film plus the smaller W of the two rows.  By hand: rigid films 0.9, 0.3,
    0.2, 0.8 (H − W); W 0.1, 0.4, 0.3, −0.05 → step 0|1: 0.3 + 0.1 = 0.4, step 2|3:
    0.2 − 0.05 = 0.15; no step: inf."""
    w = np.array([[0.1], [0.4], [0.3], [-0.05]])
    rigid = np.array([[0.9], [0.3], [0.2], [0.8]])
    b = np.array([0.0, -0.5, -0.5, 0.0])
    assert step_film(rigid + w, w, b) == pytest.approx(0.15, abs=1e-15)
    assert step_film(rigid + w, w, np.zeros(4)) == np.inf


def _films(design, grid):
    system = study_from_dict(copy.deepcopy(read_toml(FILE)), name="t", file=str(FILE),
                             directory=FILE.parent).plan.system
    g = Grid.parse(grid)
    s = EvaluationSettings(4000.0, 45000.0, 56250.0, g, heaviest_load_factor=2.0)
    cache = SolverCache(g)
    designed, _ = apply_design(system, design, s)
    rotor = resolve_rotor(designed, g, cache, ModelOptions())
    out = []
    for case in rotor.cases:
        sol = _static(case, 4000.0, 2.0 * case.load_newton, g, cache)
        assert sol.success, sol.message
        out.append((sol.min_film * case.bearing.radial_clearance * 1e6,
                    film_um(sol, case.bearing)))
    return out


def test_film_at_shim_edges_is_grid_robust_where_the_nodal_film_is_not():
    """Blower rotor, 3 shims, 4,000 rpm under twice the static loads.  c 16.2 µm with 11.15 µm
    shims: the journal's rigid film at a shim's trailing edge is −0.11 c, so the nodal film
    there (2.69 / 1.68 µm at 36x10 / 72x20, bearing A; 0.30 µm at 144x36) is held open only
    by the edge row's pressure and runs to contact as the grid is refined; the step bound is
    0 (closed) on both grids.  c 22 µm with 6 µm shims: the bound at bearing A is 1.01 /
    1.09 µm (1.05 at 144x36) while the nodal film moves 4.65 → 3.98 (3.19) µm: within 10 %
    on the two grids, where the nodal film moves by more than 10 %."""
    closing = {"radial_clearance_um": 16.2, "preload_depth_um": 11.15}
    for grid in ("36x10", "72x20"):
        (nodal_a, edge_a), (nodal_b, edge_b) = _films(closing, grid)
        assert nodal_a > 1.5 and nodal_b > 1.5          # what the nodal film claimed
        assert edge_a == 0.0 and edge_b == 0.0
    open_ = {"radial_clearance_um": 22.0, "preload_depth_um": 6.0}
    (na1, ea1), _ = _films(open_, "36x10")
    (na2, ea2), _ = _films(open_, "72x20")
    assert abs(ea2 / ea1 - 1) <= 0.10
    assert abs(na2 / na1 - 1) > 0.10


def test_pad_count_acts_at_study_level():
    """A study with ``pads`` as a design variable ([1, 3]): the plan decodes whole numbers,
    the design gives each bearing three evenly spaced pads (the first welded at 180° from the
    load), and the answer moves: at 24x8 on the blower rotor one pad whirls from 12,283 rpm,
    three pads already at the lowest speed, 4,000 rpm (added seams in or beside the loaded
    arc lower the onset, as in the one-bearing preload study: 13,136 → 6,328 rpm for 1 → 3
    pads).  Bound: the onset changes by more than 10 % (measured −67 %)."""
    data = copy.deepcopy(read_toml(FILE))
    data["variables"] = [{"name": "pads", "values": [1, 3]}]
    data["robustness"] = {"samples": 2, "designs": 1, "tolerances": {}}
    plan = study_from_dict(data, name="t", file=str(FILE), directory=FILE.parent).plan
    assert plan.problem.variables[0].values == (1.0, 3.0)
    settings = dataclasses.replace(plan.settings, grid=Grid.parse("24x8"))
    designed, _ = apply_design(plan.system, {"pads": 3.0}, settings)
    pads = designed.bearings[0].geometry.build.pads
    assert [p.leading_end_deg for p in pads] == pytest.approx([180.0, 300.0, 60.0])
    one = evaluate_rotor_design(plan.system, settings, None, pads=1.0)
    three = evaluate_rotor_design(plan.system, settings, None, pads=3.0)
    assert one["success"] and three["success"], (one["message"], three["message"])
    assert one["onset_status"] == "onset"
    assert three["first_onset_speed_rpm"] < 0.9 * one["first_onset_speed_rpm"]


def test_per_zone_bump_variable_acts_and_reduces_to_the_uniform_foil():
    """``zone_edges_deg = [-60, 60, 300]`` and ``zone1_bump_thickness_um`` (the zone round the
    load line): at the bearing's own 101.6 µm the two zones are the uniform foil (same onset
    to 1e-9: the same film and foundation, only built through the zone path; measured
    4e-15); a 60 µm zone there (softer under the load) moves the first onset by more than
    10 % (at 24x8: 12,283 → 9,791 rpm) and its bump stress is the larger of the zones'."""
    data = copy.deepcopy(read_toml(FILE))
    data["zone_edges_deg"] = [-60.0, 60.0, 300.0]
    data["variables"] = [{"name": "zone1_bump_thickness_um", "low": 60.0, "high": 200.0}]
    data["robustness"] = {"samples": 2, "designs": 1, "tolerances": {}}
    plan = study_from_dict(data, name="t", file=str(FILE), directory=FILE.parent).plan
    settings = dataclasses.replace(plan.settings, grid=Grid.parse("24x8"))
    zones = apply_design(plan.system, {"zone1_bump_thickness_um": 60.0},
                         settings)[0].bearings[1].geometry.build.zones
    assert [(z.start_deg, z.end_deg) for z in zones] == [(-60.0, 60.0), (60.0, 300.0)]
    assert zones[0].bump_thickness == pytest.approx(60e-6) and zones[1].bump_thickness is None
    uniform = evaluate_rotor_design(plan.system, settings, None)
    same = evaluate_rotor_design(plan.system, settings, None, zone1_bump_thickness_um=101.6)
    thin = evaluate_rotor_design(plan.system, settings, None, zone1_bump_thickness_um=60.0)
    assert same["first_onset_speed_rpm"] == pytest.approx(uniform["first_onset_speed_rpm"],
                                                          rel=1e-9)
    assert thin["first_onset_speed_rpm"] < 0.9 * uniform["first_onset_speed_rpm"]
    assert thin["bump_stress_mpa"] > 2 * uniform["bump_stress_mpa"]


def test_a_design_evaluated_again_from_scratch_reproduces_its_objectives():
    """Shimmed design (c 20 µm, 6 µm shims) at 24x8, twice, each with a fresh solver cache:
    the evaluation is deterministic (same builds, same warm-start chain along the speeds),
    so the objectives and the film limit agree to round-off; bound 1e-6 (the issue's)."""
    system = study_from_dict(copy.deepcopy(read_toml(FILE)), name="t", file=str(FILE),
                             directory=FILE.parent).plan.system
    s = EvaluationSettings(4000.0, 45000.0, 56250.0, Grid.parse("24x8"),
                           heaviest_load_factor=2.0)
    design = {"radial_clearance_um": 20.0, "preload_depth_um": 6.0}
    first = evaluate_rotor_design(system, s, None, **design)
    again = evaluate_rotor_design(system, s, None, **design)
    assert first["success"], first["message"]
    for name in ("first_onset_speed_rpm", "total_power_loss_w", "min_film_lowest_speed_um"):
        assert again[name] == pytest.approx(first[name], rel=1e-6), name
