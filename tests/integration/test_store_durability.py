"""Results never lost: a worker killed mid-sweep, SIGTERM, a kill -9
while a chunk is still in flight, two runs on one folder.  Each test fails on gfbopt 0.2.0
(BrokenProcessPool rows counted as done; SIGTERM dropped the unwritten buffer; rows were
written only when a result arrived after 30 s; a second run mixed its rows into the first's).

Sweeps are tiny (coarse grid, a few points) or use a trivial Python function through
gfbopt.doe.run_doe, so each test takes seconds; times are generous because the machine may
be shared (they bound a hang, they do not measure speed)."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from gfbopt.doe import SamplePlan, Variable, read_results, run_doe
from tiny_sweeps import sweep_toml

ROOT = Path(__file__).resolve().parents[2]
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}

def _study(tmp_path, n=40, batch=1, name="tiny") -> Path:
    path = tmp_path / f"{name}.toml"
    path.write_text(sweep_toml(n=n, batch=batch))
    return path


def _wait(condition, timeout=180.0, what="condition"):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return
        time.sleep(0.05)
    raise AssertionError(f"timed out waiting for {what}")


def _children(pid: int) -> list[int]:
    """Worker processes of ``pid`` (spawned pool workers; not the resource tracker)."""
    out = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
            cmd = (entry / "cmdline").read_bytes().decode(errors="replace")
        except OSError:
            continue
        ppid = int(stat.rsplit(")", 1)[1].split()[1])
        if ppid == pid and "spawn_main" in cmd:
            out.append(int(entry.name))
    return out


def _parts(store: Path) -> int:
    return len(list((store / "parts").glob("part-*.parquet"))) if store.is_dir() else 0


# ------------------------------------------------------------------ a worker dies
def killer(x, marker):
    """Kills its own worker (SIGKILL, as the OOM killer would) the first time it meets
    x > 0.5; a retry on a fresh pool then computes the point normally."""
    if x > 0.5 and not os.path.exists(marker):
        Path(marker).write_text("killed once")
        os.kill(os.getpid(), signal.SIGKILL)
    return {"y": 2.0 * x}


def test_a_killed_worker_is_retried_and_every_point_computed(tmp_path):
    plan = SamplePlan((Variable("x", 0.0, 1.0),), method="lhs", n=12, seed=3)
    frame = run_doe(killer, plan, tmp_path / "store", outputs=["y"],
                    fixed={"marker": str(tmp_path / "marker")}, workers=2, chunk_size=1,
                    progress=False)
    assert (tmp_path / "marker").exists(), "no worker was killed: the test did not test"
    assert len(frame) == 12 and frame["success"].all(), frame[["x", "message"]]
    assert (frame["y"] == 2.0 * frame["x"]).all()


@pytest.mark.slow  # the command-line variant; the default tier covers the item in-process
def test_gfbopt_run_completes_every_point_when_a_pool_worker_is_killed(tmp_path):
    study = _study(tmp_path, n=40)
    results = tmp_path / "results"
    proc = subprocess.Popen([sys.executable, "-m", "gfbopt", "run", str(study), "--workers",
                             "2", "--results", str(results)], env=ENV, cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    store = results / "tiny" / "store"
    try:
        _wait(lambda: _parts(store) >= 2 or proc.poll() is not None, what="first parts")
        workers = _children(proc.pid)
        assert proc.poll() is None and workers, "the run ended before a worker was killed"
        os.kill(workers[0], signal.SIGKILL)
        out, err = proc.communicate(timeout=300)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, err
    frame = read_results(store)
    assert sorted(frame["point"]) == list(range(40))
    assert frame["success"].all(), frame.loc[~frame["success"], "message"].tolist()
    assert "Traceback" not in err


# ------------------------------------------------------------------ SIGTERM
SIGTERM_SCRIPT = textwrap.dedent("""
    import os, signal, sys
    from gfbopt.doe import run_doe
    from gfbopt.parallel import Interrupted

    def square(x):
        if x == 250:                   # SIGTERM arrives while point 250 is computed
            os.kill(os.getpid(), signal.SIGTERM)
        return {"y": x * x}

    if __name__ == "__main__":
        points = [{"x": k} for k in range(400)]
        try:
            run_doe(square, points, sys.argv[1], outputs=["y"], batch_rows=1000,
                    flush_s=3600, progress=False)
        except Interrupted as exc:
            print(exc.report, file=sys.stderr)
            sys.exit(exc.exit_status)
""")


def test_sigterm_writes_every_finished_row(tmp_path):
    """250 rows finished, none written yet (batch of 1000, no timer within reach): SIGTERM
    must write all 250 and exit 143, saying so."""
    script = tmp_path / "script.py"
    script.write_text(SIGTERM_SCRIPT)
    out = subprocess.run([sys.executable, str(script), str(tmp_path / "store")], env=ENV,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 143, out.stderr
    frame = read_results(tmp_path / "store")
    assert sorted(frame["x"]) == list(range(250))
    assert "250 of 400 points stored" in out.stderr and "Traceback" not in out.stderr


@pytest.mark.slow  # the command-line variant; the default tier covers the item in-process
def test_gfbopt_run_on_sigterm_keeps_the_rows_and_says_how_to_resume(tmp_path):
    study = _study(tmp_path, n=400, batch=100_000)        # never a size-triggered write
    results = tmp_path / "results"
    proc = subprocess.Popen([sys.executable, "-m", "gfbopt", "run", str(study), "--workers",
                             "1", "--results", str(results)], env=ENV, cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        _wait(lambda: (results / "tiny" / "store" / "manifest.json").is_file()
              or proc.poll() is not None, what="the store")
        time.sleep(3.0)                                   # some points finish
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 143, err
    kept = len(read_results(results / "tiny" / "store"))
    line = [e for e in err.splitlines() if "interrupted" in e]
    assert len(line) == 1 and f"SIGTERM: {kept} of 400 points of tiny are stored" in line[0]
    assert "--resume" in line[0] and "Traceback" not in err
    assert 0 < kept < 400


# ------------------------------------------------------------------ the timer
TIMER_SCRIPT = textwrap.dedent("""
    import sys, time
    from gfbopt.doe import run_doe

    def slow_first(x):
        if x == 0:
            time.sleep(600)            # one chunk stays in flight
        return {"y": x + 1.0}

    if __name__ == "__main__":
        run_doe(slow_first, [{"x": k} for k in range(12)], sys.argv[1], outputs=["y"],
                workers=2, chunk_size=1, batch_rows=1000, flush_s=2.0, progress=False)
""")


def test_rows_are_written_on_a_timer_while_a_chunk_is_in_flight(tmp_path):
    """11 points finish in seconds, one never does: the 11 rows must reach the store
    (flush_s = 2 s here; 10 s by default) although no further result arrives, so a kill -9
    keeps them."""
    script = tmp_path / "script.py"
    script.write_text(TIMER_SCRIPT)
    store = tmp_path / "store"
    proc = subprocess.Popen([sys.executable, str(script), str(store)], env=ENV,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        _wait(lambda: _parts(store) >= 1 and len(read_results(store)) == 11
              or proc.poll() is not None, what="the timer's write")
    finally:
        proc.kill()
        proc.wait()
    frame = read_results(store)
    assert sorted(frame["x"]) == list(range(1, 12))


# ------------------------------------------------------------------ one writer
@pytest.mark.slow  # the command-line variant; the default tier covers the item in-process
def test_a_second_run_on_the_same_results_folder_is_refused(tmp_path):
    study = _study(tmp_path, n=400, batch=1)
    results = tmp_path / "results"
    first = subprocess.Popen([sys.executable, "-m", "gfbopt", "run", str(study), "--workers",
                              "1", "--results", str(results)], env=ENV, cwd=tmp_path,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        _wait(lambda: _parts(results / "tiny" / "store") >= 1 or first.poll() is not None,
              what="the first run's parts")
        assert first.poll() is None, "the first run ended too early"
        second = subprocess.run([sys.executable, "-m", "gfbopt", "run", str(study),
                                 "--workers", "1", "--results", str(results)], env=ENV,
                                cwd=tmp_path, capture_output=True, text=True, timeout=300)
    finally:
        first.kill()
        first.wait()
    assert second.returncode == 2
    lines = second.stderr.strip().splitlines()
    assert len(lines) == 1 and f"pid {first.pid}" in lines[0], second.stderr
    assert "is being written by another gfbopt run" in lines[0]
