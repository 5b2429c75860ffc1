"""Sampled studies (gfbopt.studies.doe): resume after kill -9, failed points as rows, Dask and
the process pool give the same table, bad study files fail before any solve."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from gfbopt.doe import read_results
from gfbopt.errors import ParameterError
from gfbopt.studies import study_from_dict
from gfbopt.studies.doe import run_sampled

from cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]

STUDY = """\
kind = "sweep"
title = "tiny static sweep"
source = "test"
analysis = "static"
grid = "24x6"
chunk_size = {chunk}
batch_rows = {batch}
min_success_fraction = 0.0

[model]
foil = "simple"

[fixed]
length_ratio = 1.0

[sampling]
method = "lhs"
n = {n}
seed = 5

[[sampling.variables]]
name = "bearing_number"
low = 0.5
high = 3.0

[[sampling.variables]]
name = "eccentricity"
low = 0.2
high = 0.7

[[sampling.variables]]
name = "compliance"
low = {s_low}
high = 1.5
"""


def _write(tmp_path, name="tiny", n=12, chunk=2, batch=2, s_low=0.2) -> Path:
    path = tmp_path / f"{name}.toml"
    path.write_text(STUDY.format(n=n, chunk=chunk, batch=batch, s_low=s_low))
    return path


def _run_cli(*args):
    """``gfbopt run ARGS`` in this process (tests/cli_inprocess.py: same main, exit status and
    output, without an interpreter start per call); the run that is killed stays a process."""
    return run_cli("run", *args, cwd=ROOT)


def _outputs(frame: pd.DataFrame) -> pd.DataFrame:
    return frame.drop(columns=["wall_time_s", "worker"]).sort_values("point") \
        .reset_index(drop=True)


def test_kill_minus_9_then_resume_has_every_point_once(tmp_path):
    study = _write(tmp_path, n=60, chunk=1, batch=1)
    results = tmp_path / "results"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen([sys.executable, "-m", "gfbopt", "run", str(study), "--workers",
                             "1", "--results", str(results)], env=env, cwd=ROOT,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    parts = results / "tiny" / "store" / "parts"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:           # wait until a few parts are written
        if parts.is_dir() and len(list(parts.glob("part-*.parquet"))) >= 3:
            break
        if proc.poll() is not None:
            break
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    partial = read_results(results / "tiny" / "store")
    assert 0 < len(partial) < 60, "the kill did not land mid-run"
    done = _run_cli(study, "--workers", "1", "--resume", "--results", results)
    assert done.returncode == 0, done.stderr
    assert f"{len(partial)} points already stored" in (results / "tiny" / "README.md").read_text()
    frame = read_results(results / "tiny" / "store")
    assert sorted(frame["point"]) == list(range(60))
    assert frame["success"].all()
    csv = pd.read_csv(results / "tiny" / "tiny.csv")
    assert len(csv) == 60 and csv["point"].is_unique


def test_resume_refuses_the_store_of_another_study(tmp_path):
    results = tmp_path / "results"
    first = _write(tmp_path, n=4)
    assert _run_cli(first, "--workers", "1", "--results", results).returncode == 0
    first.write_text(STUDY.format(n=5, chunk=2, batch=2, s_low=0.2))   # same name, new study
    refused = _run_cli(first, "--workers", "1", "--resume", "--results", results)
    assert refused.returncode == 2
    assert "with other inputs (changed: sample plan" in refused.stderr
    assert len(refused.stderr.strip().splitlines()) == 1


def test_a_failing_point_is_a_row_and_the_study_completes(tmp_path):
    # compliance sampled from -0.5: the points with S < 0 are refused by the model
    loaded = study_from_dict(__import__("tomllib").loads(
        STUDY.format(n=10, chunk=3, batch=4, s_low=-0.5)), name="failing",
        file="failing.toml")
    result = run_sampled(loaded, tmp_path, workers=1)
    frame = read_results(tmp_path / "failing" / "store")
    assert len(frame) == 10
    bad = frame[~frame["success"].astype(bool)]
    assert len(bad) > 0 and (frame["compliance"] < 0).sum() == len(bad)
    assert bad["message"].str.contains("compliance").all()
    assert frame.loc[frame["success"].astype(bool), "load"].notna().all()
    assert result.checks[0]["passed"]


def test_wrong_key_fails_before_any_solve(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(STUDY.format(n=4, chunk=2, batch=2, s_low=0.2).replace(
        "seed = 5", "seed = 5\nsamples = 3"))
    out = _run_cli(path, "--results", tmp_path / "results")
    assert out.returncode == 2
    assert out.stderr.strip() == out.stderr.strip().splitlines()[0]
    assert "bad.toml: sampling.samples" in out.stderr
    assert not (tmp_path / "results").exists()
    with pytest.raises(ParameterError, match="sampling.method"):
        text = STUDY.format(n=4, chunk=2, batch=2, s_low=0.2).replace('"lhs"', '"grid"')
        study_from_dict(__import__("tomllib").loads(text), file="x.toml")


def test_unreachable_scheduler_is_one_line_and_writes_nothing(tmp_path, monkeypatch):
    """``gfbopt run --scheduler`` at a closed port: exit 2, one line naming the address,
    nothing written.  Run in this process (tests/cli_inprocess.py) with the connection
    time-out at 2 s instead of the command's 10 s: the refusal is the same, and the 10 s wait
    (in a subprocess, 14 s) made this one of the default tier's slowest tests.  That the
    time-out bounds the wait is test_dask_robustness.py's
    test_a_port_that_is_not_a_scheduler_is_one_line_within_the_timeout."""
    import functools

    import gfbopt.parallel

    monkeypatch.setattr(gfbopt.parallel, "connect_scheduler",
                        functools.partial(gfbopt.parallel.connect_scheduler, timeout=2.0))
    study = _write(tmp_path, n=4)
    out = _run_cli(study, "--scheduler", "tcp://127.0.0.1:9", "--results",
                   tmp_path / "results")
    assert out.returncode == 2
    assert "tcp://127.0.0.1:9" in out.stderr and len(out.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "results").exists()


def test_dask_local_cluster_gives_the_process_pool_table(tmp_path):
    """40 points in 20 chunks of 2: Dask sends them in fewer tasks (several whole chunks a
    task, sized from the measured work) and the rows are the process pool's, exactly."""
    distributed = pytest.importorskip("distributed")
    text = STUDY.format(n=40, chunk=2, batch=3, s_low=0.2)
    loaded = study_from_dict(__import__("tomllib").loads(text), name="same", file="same.toml")
    run_sampled(loaded, tmp_path / "pool", workers=2)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        sent = []
        original = client.map
        client.map = lambda *a, **k: sent.append(len(a[1])) or original(*a, **k)
        result = run_sampled(loaded, tmp_path / "dask", client=client)
    assert "dask" in result.options["executor"]
    assert 1 < len(sent) and sum(sent) < 20, sent
    pool = _outputs(read_results(tmp_path / "pool" / "same" / "store"))
    dask = _outputs(read_results(tmp_path / "dask" / "same" / "store"))
    assert len(pool) == 40 and pool["success"].all()
    pd.testing.assert_frame_equal(pool, dask, check_exact=True)
