"""One memory and time guard for every command and study (gfbopt.guard): a run whose
estimated memory or computing time is above --max-memory-gb or --max-minutes is refused in
one line naming the option or key, its value, the estimate and the option that raises the
limit, exit 2, before the command's handler starts or the study is planned (both replaced
here by functions that fail the test).  The shipped study files and the README's commands
pass the guard at their defaults."""
from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest
from cli_inprocess import run_cli

import gfbopt.cli.capacity as capacity
import gfbopt.cli.rotor as rotor
from gfbopt.cli import build_parser
from gfbopt.cli.size import check_command
from gfbopt.studies import load_study, runner
from gfbopt.studies.base import Kind

ROOT = Path(__file__).resolve().parents[2]
BLOWER = str(ROOT / "problems" / "rotors" / "blower.toml")
BEARING = str(ROOT / "problems" / "bearings" / "ruscitto.toml")
PROBLEMS = sorted((ROOT / "problems").glob("*.toml"))


def _fail(*args, **kwargs):
    raise AssertionError("the work started: a run above the limits must be refused first")


@pytest.fixture
def no_handler(monkeypatch):
    for module in (rotor, capacity):
        monkeypatch.setattr(module, "run", _fail)


@pytest.fixture
def no_plan(monkeypatch):
    """Every study kind's run fails the test, and its plan too (the guard comes before
    both) except for the kinds whose plan only reads their files (runner.PLAN_FIRST: a
    mistake in the file is reported before the time estimate, the memory estimate still
    comes first)."""
    for kind, real in list(runner.KINDS.items()):
        plan = real.plan if kind in runner.PLAN_FIRST else _fail
        monkeypatch.setitem(runner.KINDS, kind, Kind(plan, _fail))


def _refused(r, option: str, value: str, raises: str) -> str:
    err = r.stderr.strip()
    assert r.returncode == 2 and len(err.splitlines()) == 1 and "Traceback" not in err, err
    assert f"{option} = {value}" in err and "estimated" in err and f"raise {raises}" in err, err
    return err


@pytest.mark.parametrize("args, option, value, raises", [
    (["rotor", BLOWER, "--speed-range", "5000", "60000", "--grid", "2000x400"], "grid",
     "'2000x400'", "--max-memory-gb"),
    (["capacity", "--bearing", BEARING, "--speed-rpm", "30000", "--min-film-um", "5",
      "--grid", "2000x2000"], "grid", "'2000x2000'", "--max-memory-gb"),
    (["rotor", BLOWER, "--speed-range", "5000", "60000", "--campbell", "--campbell-speeds",
      "100000"], "--campbell-speeds", "100000", "--max-minutes"),
    # a speed costs a part independent of the grid: 100,000 at 12x4 are not 43 min
    (["rotor", BLOWER, "--speed-range", "8000", "12000", "--grid", "12x4", "--campbell",
      "--campbell-speeds", "100000"], "--campbell-speeds", "100000", "--max-minutes"),
    (["rotor", BLOWER, "--speed-range", "8000", "12000", "--grid", "12x4", "--campbell",
      "--campbell-speeds", "100", "--max-minutes", "2"], "--campbell-speeds", "100",
     "--max-minutes"),
    (["rotor", BLOWER, "--orbit", "--speed-rpm", "13000", "--revolutions", "40",
      "--time-step", "1e-12"], "--time-step", "1e-12", "--max-minutes"),
    (["rotor", BLOWER, "--run-up", "5000", "60000", "--rate", "1e-3", "--force"], "--run-up",
     "[5000.0, 60000.0]", "--max-minutes"),
    (["rotor", BLOWER, "--orbit", "--speed-rpm", "13000", "--revolutions", "10",
      "--max-minutes", "0.001"], "--revolutions", "10.0", "--max-minutes"),
])
def test_a_command_above_the_limits_is_refused_before_it_starts(args, option, value, raises,
                                                                 no_handler):
    err = _refused(run_cli(*args), option, value, raises)
    number = float(re.search(r"estimated ([0-9.e+]+) ", err).group(1))
    assert number > 0


def test_the_options_raise_the_limits():
    """The same runs pass the guard with the limit raised (the guard alone is called)."""
    for args in (["rotor", BLOWER, "--speed-range", "5000", "60000", "--campbell",
                  "--campbell-speeds", "100000", "--max-minutes", "1e9"],
                 ["rotor", BLOWER, "--speed-range", "5000", "60000", "--grid", "2000x400",
                  "--max-memory-gb", "64", "--max-minutes", "1e3"]):
        check_command(build_parser().parse_args(args))


def _design(tmp_path, edit) -> Path:
    text = (ROOT / "problems" / "rotor_bearing_design.toml").read_text()
    text = text.replace('rotor = "rotors/blower.toml"', f'rotor = "{Path(BLOWER).as_posix()}"')
    new = edit(text)
    assert new != text
    path = tmp_path / "design.toml"
    path.write_text(new)
    return path


@pytest.mark.parametrize("old, new, key, value, raises", [
    ("budget = 116", "budget = 1000000000", "search.budget", "1000000000", "--max-minutes"),
    ("population = 8", "population = 1000000", "search.population", "1000000",
     "--max-memory-gb"),
    ("samples = 6", "samples = 1000000000", "robustness.samples", "1000000000",
     "--max-minutes"),
    ('search_grid = "36x10"', 'search_grid = "2000x400"', "search_grid", "'2000x400'",
     "--max-memory-gb"),
])
def test_a_design_study_above_the_limits_is_refused_before_it_runs(
        tmp_path, old, new, key, value, raises, no_plan):
    path = _design(tmp_path, lambda t: t.replace(old, new, 1))
    err = _refused(run_cli("run", str(path), "--results", str(tmp_path / "runs")),
                   f"{path}: {key}", value, raises)
    assert not (tmp_path / "runs").exists()
    assert ("GB of memory" in err) == (raises == "--max-memory-gb")


def test_a_design_study_reports_its_mistake_before_the_time_estimate(tmp_path, no_plan):
    """A reversed speed range in a study too long to run: the mistake, not the estimate."""
    path = _design(tmp_path, lambda t: t.replace("budget = 116", "budget = 1000000000", 1)
                   .replace("speed_range_rpm = [4000.0,", "speed_range_rpm = [90000.0,", 1))
    r = run_cli("run", str(path), "--results", str(tmp_path / "runs"))
    assert r.returncode == 2 and "speed_range_rpm" in r.stderr and "lowest < top" in r.stderr, r.stderr


@pytest.mark.parametrize("study", ["rotor_blower.toml", "rotor_run_up.toml",
                                   "thesis_table_3_1.toml"])
def test_a_study_at_a_huge_grid_is_refused_before_it_is_planned(tmp_path, study, no_plan):
    text = (ROOT / "problems" / study).read_text().replace(
        'rotor = "rotors/', f'rotor = "{(ROOT / "problems" / "rotors").as_posix()}/')
    text = re.sub(r'(?m)^grid = "[0-9x]+"', 'grid = "2000x400"', text)
    if 'grid = "2000x400"' not in text:
        text = text.replace("\nkind = ", '\ngrid = "2000x400"\nkind = ', 1)
    path = tmp_path / study
    path.write_text(text)
    _refused(run_cli("run", str(path), "--results", str(tmp_path / "runs")), f"{path}: grid",
             "'2000x400'", "--max-memory-gb")


def test_run_passes_its_limits_to_the_studies(tmp_path, no_plan):
    path = ROOT / "problems" / "thesis_table_3_2.toml"
    r = run_cli("run", str(path), "--results", str(tmp_path / "runs"), "--max-minutes", "0.01")
    _refused(r, f"{path}: rows", "6", "--max-minutes")


@pytest.mark.parametrize("path", PROBLEMS, ids=lambda p: p.name)
def test_every_shipped_study_passes_the_guard_at_its_defaults(path):
    loaded = load_study(path)                    # validated, guarded and planned
    assert loaded.study.name


def _readme_commands() -> list:
    text = (ROOT / "README.md").read_text()
    commands = []
    for block in re.findall(r"```bash\n(.*?)```", text, flags=re.S):
        for line in block.replace("\\\n", " ").splitlines():
            line = line.split("#")[0].strip()
            args = shlex.split(line)[1:] if line.startswith("gfbopt ") else []
            if args and args[0] not in ("run", "--version"):
                commands.append(args)
    return commands


def test_the_readme_commands_pass_the_guard_at_their_defaults(tmp_path, monkeypatch):
    commands = _readme_commands()
    assert len(commands) >= 8 and any(c[0] == "rotor" for c in commands)
    monkeypatch.chdir(ROOT)
    for args in commands:
        check_command(build_parser().parse_args(args))


@pytest.mark.parametrize("low, high, rule", [
    ("1e-300", "1e300", "exceeds 1000: one analysis spans at most"),
    ("1e-300", "1e-298", "no film carries the rotor there"),
    ("1e6", "1e8", "m/s"),
    ("1", "100", "the rotor is not airborne"),
])
def test_a_speed_range_no_model_can_run_is_refused_as_such(no_handler, low, high, rule):
    """A range outside the rotor's physical limits is refused by the rotor's speed rule
    (gfbopt.inputs.rotor_limits.check_rotor_speeds) before its cost is estimated: not as
    too much work (raising --max-minutes would not make it meaningful), and never as a
    traceback (1e-300 to 1e300 overflowed in the guard's scan count)."""
    r = run_cli("rotor", BLOWER, "--speed-range", low, high)
    err = r.stderr.strip()
    assert r.returncode == 2 and len(err.splitlines()) == 1 and "Traceback" not in err, err
    assert rule in err and "--max-minutes" not in err, err
