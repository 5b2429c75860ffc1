"""A bearing-pair design run as a user meets it (``gfbopt run``): what it answers, what it
does when its workers keep dying, and a second run started while it is still reporting.

The rotor's physics is replaced by a cheap analytic evaluation
(design_run_evaluation.cheap_evaluation, the same row as
gfbopt.design.rotor_objectives.evaluate_rotor_design) so each run takes about a second; what
is tested is the run itself: its store, its lock, its exit status and what it prints and
writes.  The pool's workers import that small module (the function is pickled by
reference), so a test can make it kill its own worker."""
from __future__ import annotations

import json
import os
from pathlib import Path

import pandas as pd
import pytest

from cli_inprocess import run_cli
from design_run_evaluation import DEATHS, PARENT, cheap_evaluation
from gfbopt.doe.store import read_results

ROOT = Path(__file__).resolve().parents[2]
TOP = 45000.0


STUDY = f"""
name = "rd_safety"
kind = "rotor_bearing_design"
title = "a design run's safety"
source = "test"
grid = "36x10"
search_grid = "24x8"
regrid_designs = 2
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
samples = 3
designs = 2
[robustness.tolerances]
radial_clearance_um = 1.0
"""


def _cheap(path: Path, monkeypatch) -> None:
    """The cheap evaluation in place of the rotor's, its calls logged beside ``path``."""
    import gfbopt.design.robustness as robustness
    import gfbopt.design.rotor_objectives as objectives

    monkeypatch.setattr(objectives, "evaluate_rotor_design", cheap_evaluation)
    monkeypatch.setattr(robustness, "evaluate_rotor_design", cheap_evaluation)
    monkeypatch.setenv("GFBOPT_TEST_DESIGN_LOG", str(path.parent / "calls.log"))
    monkeypatch.setenv(PARENT, str(os.getpid()))
    monkeypatch.delenv(DEATHS, raising=False)
    monkeypatch.setenv("GFBOPT_PROGRESS", "0")


@pytest.fixture
def study(tmp_path, monkeypatch):
    """The study file, with the cheap evaluation and a call log."""
    path = tmp_path / "rd_safety.toml"
    path.write_text(STUDY)
    _cheap(path, monkeypatch)
    return path


def _calls(tmp_path) -> list:
    log = tmp_path / "calls.log"
    return log.read_text().splitlines() if log.exists() else []


def test_the_answer_is_the_verdict_and_no_output_reads_as_a_pass(study, tmp_path):
    """No design is stable: the run completes (exit 0: an answer, not a failure); the
    console's last line, the README's first line and summary.json's ``verdict`` say so;
    the internal checks are 'consistency checks', never 'passed'; the evaluations table
    has the store's columns (no column empty in every row) and suffixed grid columns their
    quantity's unit; the tolerance check's figures are over one loss factor (the band's
    worst end), so its worst case is not above its nominal; every stage's evaluations are
    the ones the progress weighs."""
    results = tmp_path / "results"
    out = run_cli("run", study, "--results", results, "--workers", "1")
    assert out.returncode == 0, out.stderr
    folder = results / "rd_safety"
    summary = json.loads((folder / "summary.json").read_text())
    lines = out.stdout.strip().splitlines()
    readme = (folder / "README.md").read_text().splitlines()
    assert lines[-1] == f"rd_safety: {summary['verdict']}"
    assert readme[0] == summary["verdict"]
    assert summary["verdict"].startswith("No design in this space is stable to 45,000 rpm")
    assert "passed" not in out.stdout.lower() and "passed" not in summary
    assert "2/2 consistency checks hold" in lines[0]
    assert summary["consistency_checks_hold"] is True
    assert summary["stable_to_top_speed"] is False
    table = pd.read_csv(folder / "evaluations.csv")
    feasible = table[table["feasible"]]
    assert summary["best_first_onset_rpm"] == pytest.approx(
        feasible["first_onset_speed_rpm"].max(), rel=1e-6)
    chosen = summary["chosen_design"]
    assert chosen["first_onset_speed_rpm"] == pytest.approx(summary["best_first_onset_rpm"])
    assert 16.7 <= chosen["radial_clearance_um"] <= 35.0
    # one schema: the store's columns are the table's, none of them empty in every row
    stored = read_results(folder / "store")
    assert list(table.columns) == list(stored.columns)
    assert not [c for c in table.columns if c not in ("message",) and table[c].isna().all()]
    assert "lift_off_speed_rpm" not in table and "capacity_margin" not in table
    text = "\n".join(readme)
    assert "| `first_onset_speed_rpm_search_grid` | rpm |" in text
    assert "| `total_power_loss_w_default_grid` | W |" in text
    # the tolerance check at the band's worst end (η = 0 here: damping raises the onset)
    robust = pd.read_csv(folder / "robustness.csv")
    first = robust.iloc[0]
    assert first["worst_loss_factor"] == 0.0
    assert first["band_high_onset_speed_rpm"] == pytest.approx(
        first["band_low_onset_speed_rpm"] + 800.0)
    assert (robust["worst_onset_speed_rpm"] <= robust["band_low_onset_speed_rpm"]).all()
    assert (robust["p05_onset_speed_rpm"] <= robust["band_low_onset_speed_rpm"]).all()
    assert "at the band's worst end (η = 0)" in text
    # the evaluations each stage did are those the progress counts
    from gfbopt.studies import load_study
    from gfbopt.studies.rotor_design import run_stages

    planned = {s.name: s.tasks for s in run_stages(load_study(study).plan, 1)}
    calls = [line.split() for line in _calls(tmp_path)]
    searched = set(stored["radial_clearance_um"])
    at_search = [c for c in calls if c[0] == "24x8" and c[1] == "0" and float(c[2]) in searched]
    assert len(at_search) == planned["search"] + planned["reproduction"]
    assert len([c for c in calls if c[0] == "36x10"]) == planned["default-grid check"]
    assert len(calls) - len(at_search) - planned["default-grid check"] \
        == planned["tolerances"] == 2 * (1 + 3)


def _losing_executor(workers=1, client=None):
    """An executor that runs the first 4 tasks here and reports every later one lost, as
    gfbopt.parallel.stream_tasks does once a task's worker died on every pool."""
    from gfbopt.parallel import stream_tasks
    from gfbopt.runtime import InfrastructureFailure

    ran = [0]

    def run_tasks(function, arguments):
        for k, result in stream_tasks(function, arguments, workers=1):
            ran[0] += 1
            yield k, (result if ran[0] <= 4 else InfrastructureFailure(
                "the worker process died on 3 pools in a row (killed or out of memory)"))
    return run_tasks


@pytest.mark.parametrize("deaths", [
    "reported by the executor",
    pytest.param("real worker deaths", marks=pytest.mark.slow)])  # four pools: ~30 s
def test_workers_that_die_on_every_pool_stop_the_run_with_the_resume_command(study, tmp_path,
                                                                             monkeypatch,
                                                                             deaths):
    """After the first generation (4 designs) every pool worker kills itself, on the first
    pool and on both retries (``real worker deaths``; or the executor reports those tasks
    lost, as it does then): the run must not tell NSGA-II that the lost designs failed.
    It exits non-zero naming the exact --resume command, stores the 4 evaluated designs
    and nothing of the lost ones; the resume evaluates the rest and ends with the table of
    a run that never lost a worker."""
    import gfbopt.design.optimiser as optimiser

    results = tmp_path / "results"
    if deaths == "real worker deaths":
        monkeypatch.setenv(DEATHS, "4")
    else:
        monkeypatch.setattr(optimiser, "executor", _losing_executor)
    out = run_cli("run", study, "--results", results, "--workers", "2")
    monkeypatch.undo()                       # the workers are healthy again for the resume
    _cheap(study, monkeypatch)
    assert out.returncode == 1, out.stdout + out.stderr
    command = f"gfbopt run {study} --results {results} --resume"
    assert command in out.stderr
    assert "consistency checks" not in out.stdout and "Traceback" not in out.stderr
    stored = read_results(results / "rd_safety" / "store")
    assert len(stored) == 4 and stored["point"].is_unique
    assert not (results / "rd_safety" / "summary.json").exists()
    lost = {float(line.split()[2]) for line in _calls(tmp_path)[4:]}
    assert lost and not lost & set(stored["radial_clearance_um"])
    # the resume ends where a clean run ends
    again = run_cli("run", study, "--results", results, "--workers", "1", "--resume")
    assert again.returncode == 0, again.stderr
    clean = run_cli("run", study, "--results", tmp_path / "clean", "--workers", "1")
    assert clean.returncode == 0, clean.stderr
    cols = ["point", "evaluation", "batch", "radial_clearance_um", "first_onset_speed_rpm"]
    resumed = pd.read_csv(results / "rd_safety" / "evaluations.csv")[cols]
    assert resumed.equals(pd.read_csv(tmp_path / "clean" / "rd_safety" / "evaluations.csv")[cols])
    assert len(read_results(results / "rd_safety" / "store")) == 8


def test_a_second_run_while_the_first_reports_or_writes_is_refused(study, tmp_path,
                                                                   monkeypatch):
    """The store's lock covers the whole run: a second ``gfbopt run`` of the same study into
    the same folder, started while the first is in its report phase (after the search) and
    again while it writes its files, is refused in one line (exit 2), and the first run's
    store is neither moved aside nor touched."""
    import gfbopt.studies.report as report_module
    import gfbopt.studies.rotor_report as rotor_report

    results = tmp_path / "results"
    second = {}

    def intruder(phase, real):
        def wrapped(*args, **kwargs):
            if phase not in second:                  # once (on a lock-free run: no loop)
                second[phase] = None
                second[phase] = run_cli("run", study, "--results", results, "--workers",
                                        "1")
            return real(*args, **kwargs)
        return wrapped

    monkeypatch.setattr(rotor_report, "report", intruder("report", rotor_report.report))
    monkeypatch.setattr(report_module, "write_result",
                        intruder("write", report_module.write_result))
    first = run_cli("run", study, "--results", results, "--workers", "1")
    assert first.returncode == 0, first.stderr
    for phase in ("report", "write"):
        refused = second[phase]
        assert refused.returncode == 2, (phase, refused.stdout, refused.stderr)
        assert len(refused.stderr.strip().splitlines()) == 1
        assert "is being written by another gfbopt run" in refused.stderr
    assert not list(results.glob("rd_safety/store.previous-*"))
    assert len(read_results(results / "rd_safety" / "store")) == 8


def test_the_orbit_at_the_top_speed_reports_its_revolutions(study):
    """The orbit's progress is its revolutions (the design run's bar moves through the
    orbit instead of standing still): fractions rising to 1 unless the film closed first."""
    import dataclasses

    from gfbopt.design.robustness import whirl_at_top_speed
    from gfbopt.inputs.grid import Grid
    from gfbopt.studies import load_study

    plan = load_study(study).plan
    seen = []
    whirl = whirl_at_top_speed(plan.system, {"radial_clearance_um": 25.0},
                               dataclasses.replace(plan.settings, grid=Grid(24, 8)), 3.0,
                               seen.append)
    assert seen and seen == sorted(seen) and 0.0 < seen[-1] <= 1.0
    assert seen[-1] == 1.0 or whirl["contact"]


def test_the_python_api_holds_the_lock_while_it_writes(study, tmp_path, monkeypatch):
    """``gfbopt.studies.run_study`` (the Python route) writes the design's folder inside the
    run, under the store's lock, as ``gfbopt run`` does: a second run started while the
    first writes its files is refused (exit 2) and the first run's store is untouched.  The
    previous runner wrote the files after the lock was released, and the second run was
    accepted."""
    import gfbopt.studies.report as report_module
    import gfbopt.studies.runner as runner
    from gfbopt.studies.runner import run_study

    results = tmp_path / "results"
    second = []

    def intruder(real):
        def wrapped(*args, **kwargs):
            if not second:
                second.append(run_cli("run", study, "--results", results, "--workers", "1"))
            return real(*args, **kwargs)
        return wrapped

    monkeypatch.setattr(report_module, "write_result", intruder(report_module.write_result))
    monkeypatch.setattr(runner, "write_result", intruder(runner.write_result))
    result = run_study(study, results)
    assert result.checks_hold
    assert len(second) == 1
    assert second[0].returncode == 2, (second[0].stdout, second[0].stderr)
    assert "is being written by another gfbopt run" in second[0].stderr
    assert not list(results.glob("rd_safety/store.previous-*"))
    assert (results / "rd_safety" / "summary.json").exists()
    assert len(read_results(results / "rd_safety" / "store")) == 8
