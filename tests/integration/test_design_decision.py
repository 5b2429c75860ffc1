"""The answer of a bearing-pair design run as a decision: the verdict said the same way
everywhere, which limit binds, what it would take, the margin — on a planted evaluation
(design_decision_evaluation.planted_evaluation: the first onset linear in the clearance, the
loss factor and a side load, the start-up film limit binding at c = 16.667 µm), so each
run takes about a second and every figure has a known answer."""
from __future__ import annotations

import json
import math
from pathlib import Path

import pandas as pd
import pytest

from cli_inprocess import run_cli
from design_decision_evaluation import planted_evaluation
from gfbopt.studies import load_study
from gfbopt.studies.rotor_design import run_design

ROOT = Path(__file__).resolve().parents[2]
TOP = 45000.0

STUDY = f"""
name = "rd_decision"
kind = "rotor_bearing_design"
title = "a design run's decision"
source = "test"
grid = "36x10"
search_grid = "24x8"
regrid_designs = 1
limit_cycle_revolutions = 0.0
rotor = "{ROOT / 'problems' / 'rotors' / 'blower.toml'}"
speed_range_rpm = [4000.0, {TOP}]
goal = "front"
loss_factor_band = [0.0, 0.2]
heaviest_load_factor = 2.0
min_film_um = 1.5

[[variables]]
name = "radial_clearance_um"
low = 15.0
high = 35.0

[search]
method = "nsga2"
budget = 8
population = 4
seed = 3

[robustness]
samples = 2
designs = 1
[robustness.tolerances]
radial_clearance_um = 1.0

[what_it_would_take]
loss_factor = {{low = 0.0, high = 0.5}}
side_load_n = {{low = 0.0, high = 100.0}}
"""


@pytest.fixture
def study(tmp_path, monkeypatch):
    """The study file with the planted evaluation in place of the rotor's, calls logged."""
    import gfbopt.design.robustness as robustness
    import gfbopt.design.rotor_objectives as objectives

    monkeypatch.setattr(objectives, "evaluate_rotor_design", planted_evaluation)
    monkeypatch.setattr(robustness, "evaluate_rotor_design", planted_evaluation)
    monkeypatch.setenv("GFBOPT_TEST_DESIGN_LOG", str(tmp_path / "calls.log"))
    monkeypatch.setenv("GFBOPT_PROGRESS", "0")
    monkeypatch.delenv("GFBOPT_TEST_ONSET_OFFSET", raising=False)
    path = tmp_path / "rd_decision.toml"
    path.write_text(STUDY)
    return path


def _onset(c: float, eta: float = 0.0, force: float = 0.0) -> float:
    return 12000.0 + 300.0 * (35.0 - c) + 100000.0 * eta + 150.0 * force


def test_verdict_limits_and_what_it_would_take_agree_everywhere(study, tmp_path):
    """No design is stable: the console's last line, the README's first line and
    summary.json's verdict are one text; the limits are counted from evaluations.csv; the
    loss factor that makes the chosen design stable is the planted (45,000 − N₁(c))/10⁵ to
    1e-3 (it meets every limit: η leaves the film alone) and the side load up to 100 N
    reaches 15,000 rpm more at most: none within physical limits."""
    results = tmp_path / "results"
    out = run_cli("run", study, "--results", results, "--workers", "1")
    assert out.returncode == 0, out.stderr
    folder = results / "rd_decision"
    summary = json.loads((folder / "summary.json").read_text())
    readme = (folder / "README.md").read_text().splitlines()
    assert out.stdout.strip().splitlines()[-1] == f"rd_decision: {summary['verdict']}"
    assert readme[0] == summary["verdict"]
    assert summary["stable_to_top_speed"] is False
    assert "passed" not in summary and summary["consistency_checks_hold"] is True
    chosen = summary["chosen_design"]
    c = chosen["radial_clearance_um"]
    assert chosen["first_onset_speed_rpm"] == pytest.approx(_onset(c), rel=1e-12)
    assert f"{summary['best_first_onset_rpm']:,.0f} rpm" in summary["verdict"]
    # the limits, counted again from the table of every evaluation
    table = pd.read_csv(folder / "evaluations.csv")
    film = summary["limits"][0]
    assert film["name"] == "min_film_lowest_speed_um" and film["limit"] == 1.5
    assert film["designs_breaking"] == int((table["min_film_lowest_speed_um"] < 1.5).sum())
    assert film["designs_excluded_only_by_it"] == film["designs_breaking"]
    broken = table[table["min_film_lowest_speed_um"] < 1.5]
    if len(broken):                   # the best of them is the relaxation's design
        best = broken.loc[broken["first_onset_speed_rpm"].idxmax()]
        assert film["relaxed_merit"] == pytest.approx(best["first_onset_speed_rpm"])
        assert film["relaxed_value"] == pytest.approx(best["min_film_lowest_speed_um"])
        assert film["relaxed_breach"] == pytest.approx(       # the CSV holds 7 digits
            (1.5 - best["min_film_lowest_speed_um"]) / 1.5, abs=1e-6)
        assert "Relaxing the start-up film limit from 1.5 µm to" in "\n".join(readme)
    limits_csv = pd.read_csv(folder / "binding_limits.csv")
    assert list(limits_csv["limit_name"]) == [r["name"] for r in summary["limits"]]
    # what it would take
    levers = {a["lever"]: a for a in summary["what_it_would_take"]}
    eta = levers["loss_factor"]
    assert eta["threshold_found"] is True and eta["lever_start"] == 0.0
    assert eta["threshold_value"] == pytest.approx((TOP - _onset(c)) / 1e5, abs=1e-3)
    assert eta["threshold_onset_speed_rpm"] >= TOP and eta["threshold_meets_limits"] is True
    side = levers["side_load_n"]
    assert side["threshold_found"] is False
    assert side["threshold_value"] is None or math.isnan(side["threshold_value"])
    assert side["at_bound_value"] == 100.0
    assert side["at_bound_onset_speed_rpm"] == pytest.approx(_onset(c, force=100.0), rel=1e-12)
    text = "\n".join(readme)
    assert "static side load on the rotor: none within physical limits [0, 100]" in text
    assert (folder / "what_it_would_take.csv").is_file()
    assert (folder / "what_it_would_take_evaluations.csv").is_file()


def test_the_lever_search_resumes_from_its_store(study, tmp_path):
    """A resumed run answers every what-it-would-take evaluation from its store: no
    evaluation with a loss factor other than the band's ends, or with a side load, is
    made again."""
    loaded = load_study(study)
    first = run_design(loaded, tmp_path / "r")
    log = tmp_path / "calls.log"
    calls = log.read_text().splitlines()
    levered = [line for line in calls if float(line.split()[1]) not in (0.0, 0.2)
               or float(line.split()[2]) > 0.0]
    assert levered                              # the lever searches evaluated something
    log.write_text("")
    again = run_design(loaded, tmp_path / "r", resume=True)
    redone = [line for line in log.read_text().splitlines()
              if float(line.split()[1]) not in (0.0, 0.2) or float(line.split()[2]) > 0.0]
    assert redone == []
    assert again.answer["what_it_would_take"] == first.answer["what_it_would_take"]
    assert again.answer["verdict"] == first.answer["verdict"]


def test_a_run_killed_in_its_lever_searches_resumes_with_each_evaluation_once(
        study, tmp_path, monkeypatch):
    """Killed after 5 lever evaluations (Ctrl-C inside the stage): those 5 are in the
    store; the resumed run evaluates only the others, so over both runs every lever
    evaluation of an uninterrupted run is made exactly once, with the same answer."""
    from design_decision_evaluation import _levered

    loaded = load_study(study)
    clean = run_design(loaded, tmp_path / "clean")
    log = tmp_path / "calls.log"
    whole = [line for line in log.read_text().splitlines() if _levered(line)]
    log.write_text("")
    monkeypatch.setenv("GFBOPT_TEST_STOP_AFTER_LEVERS", "5")
    with pytest.raises(KeyboardInterrupt):
        run_design(loaded, tmp_path / "killed")
    monkeypatch.delenv("GFBOPT_TEST_STOP_AFTER_LEVERS")
    from gfbopt.doe.store import read_results

    kept = read_results(tmp_path / "killed" / "rd_decision" / "what_it_takes_store")
    assert len(kept) == 5
    again = run_design(loaded, tmp_path / "killed", resume=True)
    done = [line for line in log.read_text().splitlines() if _levered(line)]
    assert len(done) == len(whole) + 1             # + the call that was killed
    assert sorted(done[:5] + done[6:]) == sorted(whole)
    assert again.answer["what_it_would_take"] == clean.answer["what_it_would_take"]
    assert "5 more answered from the store" in " ".join(again.notes)


def test_a_stable_design_reports_its_margin(study, tmp_path, monkeypatch):
    """Every design stable (the onset raised by 40,000 rpm): the console's last line, the
    README's first line and summary.json say so alike, the margin is the chosen design's
    onset over the top speed and its worst case under the tolerances, and nothing is
    searched for what it would take."""
    monkeypatch.setenv("GFBOPT_TEST_ONSET_OFFSET", "40000")
    out = run_cli("run", study, "--results", tmp_path / "r", "--workers", "1")
    assert out.returncode == 0, out.stderr
    folder = tmp_path / "r" / "rd_decision"
    a = json.loads((folder / "summary.json").read_text())
    readme = (folder / "README.md").read_text().splitlines()
    assert out.stdout.strip().splitlines()[-1] == f"rd_decision: {a['verdict']}"
    assert readme[0] == a["verdict"]
    assert a["stable_to_top_speed"] is True and a["verdict"].startswith("Stable to 45,000 rpm")
    assert a["what_it_would_take"] is None
    assert not (folder / "what_it_would_take.csv").exists()
    m = a["margin"]
    onset = a["chosen_design"]["first_onset_speed_rpm"]
    assert m["first_onset_rpm"] == onset and m["margin_rpm"] == pytest.approx(onset - TOP)
    robust = pd.read_csv(folder / "robustness.csv").iloc[0]
    assert m["worst_onset_under_tolerances_rpm"] == pytest.approx(
        robust["worst_onset_speed_rpm"], rel=1e-6)             # the CSV holds 7 digits
    assert m["worst_onset_under_tolerances_rpm"] <= onset
    assert any(n.startswith("Margin: the chosen design's first onset") for n in a["notes"])
    assert "- Margin: the chosen design's first onset" in "\n".join(readme)


@pytest.mark.parametrize("table, rule", [
    ("loss_factor = {low = 0.0}", "a lever needs its physical bounds"),
    ("loss_factor = {low = 0.0, high = 2.0}", "must lie in [0, 1]"),
    ("pads = {low = 1.0, high = 5.0}", "is a whole number"),
    ("torque = {low = 1.0, high = 5.0}", "is not a lever"),
    ("side_load_n = {low = 5.0, high = 1.0}", "must have low < high")])
def test_a_lever_without_bounds_is_refused_before_any_solve(study, tmp_path, table, rule):
    text = study.read_text().split("[what_it_would_take]")[0] + "[what_it_would_take]\n" + table
    study.write_text(text)
    out = run_cli("run", study, "--results", tmp_path / "results", "--workers", "1")
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and rule in lines[0] and "what_it_would_take." in lines[0]
    assert str(study) in lines[0]
    assert not (tmp_path / "calls.log").exists()
