"""Progress reporting: a status line when stderr is not a terminal, a tqdm bar when it is."""
import io

import pytest

from gfbopt.progress import StatusLine, progress


class _Clock:
    def __init__(self):
        self.t = 0.0

    def __call__(self):
        return self.t


def test_status_line_is_periodic_with_eta():
    clock, out = _Clock(), io.StringIO()
    line = StatusLine(10, "onset scan", "speed", out, interval_s=10.0, clock=clock)
    clock.t = 5.0
    line.update(2)                     # 5 s < interval: nothing written yet
    assert out.getvalue() == ""
    clock.t = 12.0
    line.update(2)                     # 4 of 10 done in 12 s: ETA 18 s
    assert out.getvalue().strip() == "gfbopt: onset scan 4/10 speed (40 %), 12.0 s, ETA 18.0 s"
    line.close()                       # a final line at the end
    assert len(out.getvalue().splitlines()) == 2


def test_non_terminal_stream_gets_status_line_and_terminal_gets_tqdm(monkeypatch):
    monkeypatch.delenv("GFBOPT_PROGRESS", raising=False)
    assert isinstance(progress(3, stream=io.StringIO()), StatusLine)

    class Tty(io.StringIO):
        def isatty(self):
            return True

    bar = progress(3, desc="x", stream=Tty())
    assert type(bar).__module__.startswith("tqdm")
    bar.close()


def test_disabled_by_environment(monkeypatch):
    monkeypatch.setenv("GFBOPT_PROGRESS", "0")
    out = io.StringIO()
    with progress(3, stream=out) as bar:
        bar.update(3)
    assert out.getvalue() == ""


# ---------------------------------------------------------------- a run of several stages
def test_stage_work_is_rounds_of_parallel_tasks_times_their_cost():
    from gfbopt.progress import Stage

    assert Stage("search", 24, 1.0, 2).work == 12.0          # 12 rounds of 2 workers
    assert Stage("check", 3, 5.0, 2).work == 10.0            # 2 rounds (2 + 1) of cost 5
    assert Stage("check", 1, 5.0, 4).work == 5.0             # one task: one round
    assert Stage("skipped", 0, 9.0, 2).work == 0.0


def test_stages_give_each_stage_its_share_of_the_work():
    """Three stages of 12, 5 and 8 units: the search's end is 12/25 of the run, not the
    70 % the design run used to give its search whatever the rest weighed."""
    from gfbopt.progress import Stage, Stages

    seen = []
    run = Stages(seen.append, [Stage("search", 24, 1.0, 2), Stage("check", 2, 5.0, 2),
                               Stage("tolerances", 16, 1.0, 2)])
    step = run.stage("search")
    step(0.5)
    assert seen[-1] == 6 / 25
    step(1.0)
    assert seen[-1] == 12 / 25
    run.stage("check")(1.0)
    assert seen[-1] == 17 / 25
    run.stage("tolerances")(0.25)
    assert seen[-1] == 19 / 25
    run.finish()
    assert seen[-1] == 1.0 and seen == sorted(seen)       # never backwards


def test_a_stage_that_ends_early_or_is_skipped_counts_only_the_work_it_did():
    """An orbit planned at 60 units stops at contact after 5 % of its revolutions; a
    skipped stage did nothing: the fraction is re-based on the work left, so the ETA of a
    status line (elapsed × remaining / done) is the time of the remaining work."""
    from gfbopt.progress import Stage, Stages

    seen = []
    run = Stages(seen.append, [Stage("search", 10), Stage("orbit", 1, 60.0),
                               Stage("skipped", 4), Stage("check", 10)])
    run.stage("search")(1.0)
    assert seen[-1] == 10 / 84                  # the orbit may run to its end: upper bound
    run.stage("orbit")(0.05)                    # contact: 3 of its 60 units were done
    step = run.stage("check")                   # "skipped" never started
    assert seen[-1] == 13 / 23
    clock, out = _Clock(), io.StringIO()
    line = StatusLine(100, "design", "%", out, interval_s=0.0, clock=clock)
    clock.t = 13.0                              # one second per unit of work so far
    line.update(round(100 * seen[-1]))
    assert out.getvalue().strip() == "gfbopt: design 57 %, 13.0 s, ETA 9.8 s"
    step(1.0)
    assert seen[-1] == 1.0


def test_design_run_stages_count_the_evaluations_of_the_main_job():
    """The shipped design study: 24 searched designs (population 8 on 2 workers), the orbit
    of 200 revolutions at the top speed on 72x20, 2 designs on the 144x36 default grid,
    2 designs at the loss-factor band's other end and 6 tolerance samples each, one
    reproduction — the search is not 70 % of the run."""
    from pathlib import Path

    from gfbopt.progress import Stages
    from gfbopt.studies import load_study
    from gfbopt.studies.rotor_design import grid_cost, run_stages

    root = Path(__file__).resolve().parents[2]
    plan = load_study(root / "problems" / "rotor_bearing_design.toml").plan
    stages = {s.name: s for s in run_stages(plan, 2)}
    assert [(s.tasks, s.slots) for s in stages.values()] == [
        (116, 2), (1, 1), (2, 2), (2 * (1 + 6), 2), (1, 1)]
    assert stages["default-grid check"].cost == pytest.approx((144 * 36 / 360) ** 0.6)
    assert stages["whirl at top speed"].cost == pytest.approx(
        grid_cost(plan.limit_cycle_grid, plan.settings.grid) * 10.0 * 2)
    total = sum(s.work for s in stages.values())
    run = Stages(None, list(stages.values()))
    run.stage("search")(1.0)
    assert run.fraction == pytest.approx(116 / 2 / total)     # 116 designs on 2 workers


def test_a_run_fraction_reads_as_a_percentage():
    clock, out = _Clock(), io.StringIO()
    line = StatusLine(100, "rotor_bearing_design", "%", out, interval_s=0.0, clock=clock)
    clock.t = 10.0
    line.update(40)
    assert out.getvalue().strip() == "gfbopt: rotor_bearing_design 40 %, 10.0 s, ETA 15.0 s"
