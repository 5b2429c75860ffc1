"""The rotor bearing-pair design study end to end on the blower rotor (slow: each evaluation
is a two-bearing onset search, 10-20 s at 36x10 on a loaded 2-core machine)."""
import copy
import math
from pathlib import Path

import numpy as np
import pytest

from gfbopt.design.rotor_objectives import evaluate_rotor_design
from gfbopt.doe.store import read_results
from gfbopt.inputs import read_toml
from gfbopt.studies import study_from_dict
from gfbopt.studies.rotor_design import run_design

ROOT = Path(__file__).resolve().parents[2]
FILE = ROOT / "problems" / "rotor_bearing_design.toml"

pytestmark = pytest.mark.slow


def _tiny(**change):
    data = copy.deepcopy(read_toml(FILE))
    data.update(name="rd_tiny", grid="36x10", regrid_designs=1, limit_cycle_revolutions=20.0)
    data["variables"] = [{"name": "radial_clearance_um", "low": 15.0, "high": 35.0}]
    data["search"] = {"method": "nsga2", "budget": 4, "population": 4, "seed": 1}
    data["robustness"] = {"samples": 2, "designs": 1,
                          "tolerances": {"radial_clearance_um": 1.0}}
    data.update(change)
    return study_from_dict(data, name="rd_tiny", file=str(FILE), directory=FILE.parent)


def test_study_verdict_first_resume_and_reproduced_front(tmp_path):
    loaded = _tiny()
    first = run_design(loaded, tmp_path)
    readme = (tmp_path / "rd_tiny" / "README.md").read_text().splitlines()
    assert readme[0] == first.verdict
    assert readme[0].startswith(("Stable to 45,000 rpm", "No design in this space"))
    assert "36x10" in readme[0]                       # the answer names its grid
    assert first.checks_hold, first.checks
    # the tolerance check is at the loss-factor band's worst end: its worst case is not
    # above the design's onset there (it was above the η = 0 nominal, the sample spanning
    # η up to 0.2)
    robust = first.tables["robustness.csv"].iloc[0]
    worst_end = min((robust["band_low_onset_speed_rpm"], 0.0),
                    (robust["band_high_onset_speed_rpm"], 0.2))
    assert robust["worst_loss_factor"] == worst_end[1]
    assert robust["worst_onset_speed_rpm"] <= worst_end[0]
    assert robust["p05_onset_speed_rpm"] <= worst_end[0]
    for name in ("design_front.png", "onset_vs_variables.png", "evaluations.csv",
                 "pareto_front.csv", "default_grid_check.csv", "robustness.csv"):
        assert (tmp_path / "rd_tiny" / name).is_file(), name
    # resumed: every evaluation answered from the store, none recomputed
    again = run_design(loaded, tmp_path, resume=True)
    assert "0 designs evaluated, 4 answered from the store" in " ".join(again.notes)
    stored = read_results(tmp_path / "rd_tiny" / "store")
    assert len(stored) == 4 and stored["point"].is_unique
    # every Pareto design evaluated again from scratch reproduces its stored objectives:
    # the evaluation is deterministic (fresh solver cache, same warm-start chain), so only
    # round-off may differ (1e-6)
    plan = loaded.plan
    front = first.tables["pareto_front.csv"]
    assert len(front) >= 1
    for _, row in front.iterrows():
        new = evaluate_rotor_design(plan.system, plan.settings, None,
                                    **{n: float(row[n]) for n in plan.problem.names})
        for o in plan.problem.objectives:
            assert new[o.name] == pytest.approx(row[o.name], rel=1e-6)


def test_optimiser_choice_within_a_fine_scan_resolution(tmp_path):
    """One variable (radial clearance 15-35 µm), goal max_onset: a scan at 2.5 µm steps
    (9 designs) knows the best; the Bayesian optimiser with 6 evaluations must choose
    within one scan step of it."""
    loaded = _tiny(goal="max_onset", search={"method": "bayes", "budget": 6, "startup": 3,
                                             "batch": 1, "seed": 0},
                   robustness={"samples": 2, "designs": 1, "tolerances": {}},
                   limit_cycle_revolutions=0.0)
    plan = loaded.plan
    scan = np.linspace(15.0, 35.0, 9)
    onsets = [evaluate_rotor_design(plan.system, plan.settings, None,
                                    radial_clearance_um=float(c))["first_onset_speed_rpm"]
              for c in scan]
    best = scan[int(np.nanargmax(onsets))]
    result = run_design(loaded, tmp_path, write=False)
    chosen = result.tables["chosen.csv"].iloc[0]
    assert abs(chosen["radial_clearance_um"] - best) <= 2.5 + 1e-9
    assert chosen["first_onset_speed_rpm"] >= max(o for o in onsets if math.isfinite(o)) \
        * (1 - 0.02)


def test_first_onset_adapter_agrees_with_rotor_onsets():
    """The design search's first onset (refining only the first crossing, on the least μ_c
    over all modes) against the rotor's own onset of every mode (refining each mode):
    brentq to 1e-3 relative here against 1e-4 there, so they agree to ~1e-3; bound 2e-3
    (measured 1.8e-4 on the blower at 36x10)."""
    from gfbopt.design.rotor_objectives import EvaluationSettings
    from gfbopt.inputs.grid import Grid
    from gfbopt.inputs.rotor_system import load_rotor
    from gfbopt.rotor.system import rotor_onsets

    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    settings = EvaluationSettings(4000.0, 45000.0, 56250.0, Grid.parse("36x10"))
    row = evaluate_rotor_design(system, settings, None)
    ref = rotor_onsets(system, (4000.0, 56250.0), grid=settings.grid, show_progress=False)
    assert row["first_mode"] == ref.first_mode
    assert row["first_onset_speed_rpm"] == pytest.approx(ref.onset_speed_rpm, rel=2e-3)
