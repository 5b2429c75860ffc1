"""Sampled studies never mix or misplace results. Each test fails on gfbopt 0.2.0: a failed
point's sampled eccentricity was overwritten with NaN; a foreign summary.json broke every run
after computing; the study hash covered the bearing file's path, not its content, and refused
harmless edits; a damaged part made the store unreadable; ``name = ".."`` wrote into the parent
folder; n = 1e9 or invalid fixed inputs were found only point by point; ``gfbopt run`` had no
--grid; the README's first command dirtied the checkout.

Most tests run in-process on tiny sweeps (a coarse 24x6 grid, a few points: seconds)."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from gfbopt.doe import ResultStore, read_results
from gfbopt.errors import ParameterError
from gfbopt.studies import study_from_dict
from gfbopt.studies.doe import run_sampled
from tiny_sweeps import sweep_toml

ROOT = Path(__file__).resolve().parents[2]
BEARING = ROOT / "problems" / "bearings" / "ruscitto.toml"

def _text(target="eccentricity", low=0.2, high=0.7, n=8) -> str:
    """A tiny static sweep whose points with S < 0 fail (compliance sampled from -0.5)."""
    return sweep_toml(n=n, chunk=2, batch=4, min_success=0.0, variables=(
        ("bearing_number", 0.5, 3.0), (target, low, high), ("compliance", -0.5, 1.5)))


ONSET = """\
kind = "sweep"
title = "onset speed against the clearance"
source = "test"
analysis = "onset_speed"
grid = "24x8"
bearing = "bearing.toml"

[fixed]
rotor_mass_kg = 2.0
speed_low_rpm = 5000.0
speed_high_rpm = 60000.0

[sampling]
method = "lhs"
n = 4
seed = 1

[[sampling.variables]]
name = "radial_clearance"
low = 2.5e-5
high = 4.0e-5
"""


def _static(target="eccentricity", low=0.2, high=0.7, n=None, **changes) -> dict:
    data = tomllib.loads(_text(target, low, high))
    data.update(changes)
    if n is not None:
        data["sampling"]["n"] = n
    return data


def _loaded(data: dict, name="tiny", directory=ROOT):
    return study_from_dict(data, name=name, file=f"{name}.toml", directory=directory)


def _run_cli(*args, cwd=ROOT):
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "gfbopt", "run", *map(str, args)],
                          capture_output=True, text=True, env=env, cwd=cwd, timeout=600)


# ------------------------------------------------------------------ item 4
@pytest.mark.parametrize("target,low,high", [("eccentricity", 0.2, 0.7), ("load", 0.3, 1.2)])
def test_a_failed_point_keeps_its_sampled_input(tmp_path, target, low, high):
    """Points with S < 0 fail; their sampled ε (or W̄) must still be the planned value."""
    loaded = _loaded(_static(target, low, high))
    run_sampled(loaded, tmp_path, write=False)
    frame = read_results(tmp_path / "tiny" / "store")
    plan = loaded.plan.frame.set_index("point")
    failed = frame[~frame["success"].astype(bool)]
    assert len(failed) > 0 and (failed["compliance"] < 0).all()
    for _, row in failed.iterrows():          # exactly the planned input, not NaN
        assert row[target] == plan.loc[row["point"], target]


# ------------------------------------------------------------------ item 5
def test_an_unwritable_results_path_is_refused_before_computing(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(ParameterError, match="is not a folder"):
        run_sampled(_loaded(_static()), blocker)
    with pytest.raises(ParameterError, match="cannot be created"):
        run_sampled(_loaded(_static()), blocker / "sub")


def test_a_foreign_summary_that_is_not_json_is_skipped_with_a_warning(tmp_path):
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "summary.json").write_text("{not json")
    said = []
    for _ in range(2):                         # every later run works the same way
        run_sampled(_loaded(_static(n=2)), tmp_path, notify=said.append)
    index = (tmp_path / "index.md").read_text()
    assert "tiny" in index and "other" not in index
    assert sum("other/summary.json is not a gfbopt study summary" in s for s in said) == 2
    assert not list(tmp_path.rglob("*.tmp*")), "a temporary file was left behind"


def test_a_report_write_that_fails_leaves_the_old_file_whole(tmp_path):
    from gfbopt.studies.output import write_text_atomic

    target = tmp_path / "README.md"
    target.write_text("old, complete")

    def half(tmp):
        tmp.write_text("half of the new")
        raise OSError(28, "No space left on device")

    with pytest.raises(OSError):
        from gfbopt.studies.output import write_atomic
        write_atomic(target, half)
    assert target.read_text() == "old, complete" and not list(tmp_path.glob(".*tmp*"))
    write_text_atomic(target, "new")
    assert target.read_text() == "new"


# ------------------------------------------------------------------ item 6
def _onset(tmp_path, **changes):
    if not (tmp_path / "bearing.toml").exists():
        shutil.copy(BEARING, tmp_path / "bearing.toml")
    data = tomllib.loads(ONSET)
    data.update(changes)
    return _loaded(data, name="onset", directory=tmp_path)


def test_the_study_hash_covers_the_bearing_content_not_harmless_keys(tmp_path):
    base = _onset(tmp_path).plan
    harmless = _onset(tmp_path, title="another title", chunk_size=3, batch_rows=7,
                      notes=["n"], min_success_fraction=0.5, max_points=10).plan
    assert harmless.study_hash == base.study_hash
    for change in ({"grid": "36x8"}, {"fixed": {"rotor_mass_kg": 2.5, "speed_low_rpm":
                                                5000.0, "speed_high_rpm": 60000.0}}):
        assert _onset(tmp_path, **change).plan.study_hash != base.study_hash
    text = (tmp_path / "bearing.toml").read_text()
    (tmp_path / "bearing.toml").write_text(text + "\n# a comment changes nothing\n")
    assert _onset(tmp_path).plan.study_hash == base.study_hash


def test_resume_refuses_when_the_bearing_file_was_edited(tmp_path):
    loaded = _onset(tmp_path)
    out = tmp_path / "results" / "onset" / "store"
    ResultStore.create(out, study="onset", study_hash=loaded.plan.study_hash,   # a first run
                       schema=loaded.plan.schema, inputs=loaded.plan.inputs,
                       study_file=loaded.study.file)
    text = (tmp_path / "bearing.toml").read_text()
    assert "length = 38.1e-3 " in text
    (tmp_path / "bearing.toml").write_text(text.replace("length = 38.1e-3 ", "length = 40e-3 "))
    with pytest.raises(ParameterError) as info:
        run_sampled(_onset(tmp_path), tmp_path / "results", resume=True)
    text = str(info.value)
    assert "changed: bearing file content" in text and "run without --resume" in text
    assert text.count("onset") <= 2 and "\n" not in text      # no name repeated, one line


# ------------------------------------------------------------------ item 9
def test_resume_recomputes_the_points_of_a_damaged_part(tmp_path):
    loaded = _loaded(_static(n=6, batch_rows=2, chunk_size=1))
    run_sampled(loaded, tmp_path, write=False)
    store = tmp_path / "tiny" / "store"
    parts = sorted((store / "parts").glob("part-*.parquet"))
    assert len(parts) == 3
    lost = set(ResultStore(store, json.loads((store / "manifest.json").read_text()))
               ._read_part(parts[1])[0].to_pandas()["point"])
    parts[1].write_bytes(b"PAR1 damaged")
    with pytest.raises(ParameterError, match="is damaged"):
        read_results(store)
    said = []
    result = run_sampled(loaded, tmp_path, resume=True, write=False, notify=said.append)
    assert f"{6 - len(lost)} points already stored" in result.notes[1]
    frame = read_results(store)
    assert sorted(frame["point"]) == list(range(6))
    assert any("moved to" in s and parts[1].name in s for s in said)


# ------------------------------------------------------------------ item 10
@pytest.mark.parametrize("name", ["..", "../../x", "/tmp/abs", "a/b", ".hidden", "", "x" * 101])
def test_a_study_name_must_be_one_safe_folder_name(name):
    with pytest.raises(ParameterError, match="name = .*must be one folder name"):
        _loaded(_static(name=name))


def test_name_dotdot_from_the_command_line_writes_nothing(tmp_path):
    study = tmp_path / "x.toml"
    text = _text()
    study.write_text('name = ".."\n' + text)
    (tmp_path / "README.md").write_text("the user's file")
    out = _run_cli(study, "--results", tmp_path / "results", cwd=tmp_path)
    assert out.returncode == 2 and len(out.stderr.strip().splitlines()) == 1
    assert (tmp_path / "README.md").read_text() == "the user's file"
    assert not (tmp_path / "results").exists()


def test_reports_never_follow_a_symlink_out_or_overwrite_foreign_files(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (tmp_path / "results").mkdir()
    (tmp_path / "results" / "tiny").symlink_to(outside)
    with pytest.raises(ParameterError, match="symlink leading outside"):
        run_sampled(_loaded(_static(n=2)), tmp_path / "results")
    assert not list(outside.iterdir())
    mine = tmp_path / "mine"
    (mine / "tiny").mkdir(parents=True)
    (mine / "tiny" / "README.md").write_text("my notes")
    with pytest.raises(ParameterError, match="holds files gfbopt did not write"):
        run_sampled(_loaded(_static(n=2)), mine)
    run_sampled(_loaded(_static(n=2)), mine, force=True)
    assert "Generated by" in (mine / "tiny" / "README.md").read_text()


# ------------------------------------------------------------------ item 12 / item 14
@pytest.mark.parametrize("sampling,rule", [
    ({"method": "lhs", "n": 10 ** 9, "seed": 1}, "1,000,000,000 points"),
    ({"method": "saltelli", "n": 2 ** 63 - 1, "seed": 1}, "too large"),
    ({"method": "factorial", "levels": 1000}, "1,000,000,000 points")])
def test_a_job_beyond_the_limit_is_refused_at_once_with_the_option(sampling, rule):
    import time

    data = _static()
    data["sampling"].update(sampling)
    t0 = time.perf_counter()
    with pytest.raises(ParameterError) as info:
        _loaded(data)
    assert time.perf_counter() - t0 < 5.0          # counted, never built
    assert rule in str(info.value) and "--max-points" in str(info.value)


def test_max_points_raises_the_limit():
    data = _static()
    data["sampling"]["n"] = 300
    with pytest.raises(ParameterError, match="limit is 200 points"):
        _loaded({**data, "max_points": 200})
    assert len(_loaded({**data, "max_points": 300}).plan.frame) == 300


@pytest.mark.parametrize("key,value,rule", [
    ("batch_rows", 10 ** 9, "must be <= 100000"), ("chunk_size", 10 ** 6, "must be <= 10000"),
    ("min_success_fraction", 2.0, "must be <= 1"), ("sampling.seed", -1, "must be >= 0")])
def test_bounded_keys_are_refused(key, value, rule):
    data = _static()
    if key.startswith("sampling."):
        data["sampling"][key.split(".")[1]] = value
    else:
        data[key] = value
    with pytest.raises(ParameterError, match=rule):
        _loaded(data)


@pytest.mark.parametrize("fixed,rule", [
    ({"length_ratio": -1.0}, "fixed.length_ratio = -1.0: must be > 0"),
    ({"compliance": -0.1}, "must be >= 0")])
def test_invalid_fixed_inputs_are_refused_before_any_solve(fixed, rule):
    data = _static()
    data["fixed"] = fixed
    with pytest.raises(ParameterError, match=rule):
        _loaded(data)


@pytest.mark.parametrize("fixed,rule", [
    ({"speed_low_rpm": 60000.0, "speed_high_rpm": 5000.0}, "must be > speed_low_rpm"),
    ({"rotor_mass_kg": -2.0}, "rotor_mass_kg = -2.0: must be > 0")])
def test_invalid_fixed_onset_inputs_are_refused_before_any_solve(tmp_path, fixed, rule):
    base = tomllib.loads(ONSET)["fixed"]
    with pytest.raises(ParameterError, match=rule):
        _onset(tmp_path, fixed={**base, **fixed})


def test_too_many_workers_and_an_empty_scheduler_are_refused(tmp_path, capsys):
    from gfbopt.cli import main

    study = tmp_path / "tiny.toml"
    study.write_text(_text())
    for args, text in ((("--workers", "100000"), "--max-workers"),
                       (("--scheduler", ""), "must be a scheduler address"),
                       (("--scheduler", "ucx://127.0.0.1:8786"), "ucx:// is not supported")):
        status = main(["run", str(study), *args, "--results", str(tmp_path / "r")])
        err = capsys.readouterr().err
        assert status == 2 and text in err, err
        assert len(err.strip().splitlines()) == 1
    assert not (tmp_path / "r").exists()


# ------------------------------------------------------------------ failed points, foreign files
def test_grid_option_overrides_the_study_grid_and_is_refused_without_one(tmp_path):
    from argparse import Namespace

    from gfbopt.cli.run import _load

    study = tmp_path / "tiny.toml"
    study.write_text(_text())
    loaded = _load(str(study), Namespace(grid="36x10", max_points=None))
    assert str(loaded.plan.grid) == "36x10" and loaded.study.spec["grid"] == "36x10"
    with pytest.raises(ParameterError, match="--grid = '36x10'.*no single grid"):
        _load(str(ROOT / "problems" / "grid_convergence.toml"),
              Namespace(grid="36x10", max_points=None))


def test_running_a_study_leaves_the_checkout_clean_and_its_provenance_clean(tmp_path):
    """A fresh checkout (gfbopt, a study file, the .gitignore) committed, then the README's
    kind of command run in it: git status stays empty and the summary names the clean
    commit."""
    repo = tmp_path / "repo"
    shutil.copytree(ROOT / "gfbopt", repo / "gfbopt",
                    ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / ".gitignore", repo / ".gitignore")
    (repo / "problems").mkdir()
    (repo / "problems" / "tiny.toml").write_text(
        _text(n=2))
    git = ["git", "-C", str(repo), "-c", "user.name=t", "-c", "user.email=t@t"]
    subprocess.run(git[:3] + ["init", "-q"], check=True)
    subprocess.run(git + ["add", "-A"], check=True)
    subprocess.run(git + ["commit", "-qm", "fresh"], check=True)
    env = {**os.environ, "PYTHONPATH": str(repo)}
    out = subprocess.run([sys.executable, "-m", "gfbopt", "run", "problems/tiny.toml",
                          "--workers", "1"], cwd=repo, env=env, capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    assert "gfbopt: tiny 100 %, " in out.stderr     # progress, stderr not a TTY
    status = subprocess.run(git + ["status", "--porcelain", "--untracked-files=all"],
                            capture_output=True, text=True, check=True).stdout
    assert status == "", status
    summary = json.loads((repo / "runs" / "tiny" / "summary.json").read_text())
    head = subprocess.run(git + ["rev-parse", "HEAD"], capture_output=True, text=True,
                          check=True).stdout.strip()
    assert summary["provenance"]["source_commit"] == head
    assert summary["provenance"]["source_dirty"] is False
