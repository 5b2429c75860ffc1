"""The Python route to a DOE: the worked example docs/examples/doe_onset.py —
a 20-point onset-speed sweep through gfbopt.doe.run_doe — killed with SIGKILL once at least
half of its points are stored, then run again: every point exactly once, the second run
computing only the missing ones.  On 0.2.0 the Python route (gfbopt.parallel.run_points)
kept nothing after a kill and had no resume.  Grid 12x4 and a narrow speed range keep it to
seconds per point (the numbers are not checked here, only that none is lost or doubled)."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from gfbopt.doe import read_results
from gfbopt.errors import ParameterError

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "docs" / "examples" / "doe_onset.py"
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}


def _stored(store: Path) -> int:
    try:
        return len(read_results(store))
    except (ParameterError, OSError):
        return 0


@pytest.mark.slow  # 20 onset searches and two interpreters (about 15 s idle)
def test_the_worked_example_killed_at_half_resumes_with_every_point_once(tmp_path):
    store = tmp_path / "doe_onset"
    args = [sys.executable, str(SCRIPT), str(store), "--grid", "12x4"]
    proc = subprocess.Popen(args, env=ENV, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 600
    while time.monotonic() < deadline and proc.poll() is None and _stored(store) < 10:
        time.sleep(0.1)
    assert proc.poll() is None, "the script ended before it was killed"
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    first = read_results(store)
    assert 10 <= len(first) < 20                  # killed at >= 50 %
    done = subprocess.run(args, env=ENV, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr
    frame = read_results(store)
    assert sorted(frame["point"]) == list(range(20))
    assert frame["success"].all(), frame["message"].tolist()
    again = frame.set_index("point").loc[first["point"]]
    assert (again["worker"] == first.set_index("point")["worker"]).all(), \
        "a stored point was computed again"
    assert 9000 < frame["onset_speed_rpm"].min() and frame["onset_speed_rpm"].max() < 15000


def test_a_store_of_another_plan_is_refused_naming_what_changed(tmp_path):
    from gfbopt.doe import run_doe

    run_doe(abs_value, [{"x": -1.0}, {"x": 2.0}], tmp_path / "s", outputs=["y"],
            progress=False)
    with pytest.raises(ParameterError, match=r"changed: sample plan\)"):
        run_doe(abs_value, [{"x": -1.0}, {"x": 3.0}], tmp_path / "s", outputs=["y"],
                progress=False)
    frame = run_doe(abs_value, [{"x": -1.0}, {"x": 3.0}], tmp_path / "s", outputs=["y"],
                    resume=False, progress=False)
    assert frame["y"].tolist() == [1.0, 3.0]
    with pytest.raises(ParameterError, match="inputs and outputs never share a column"):
        run_doe(abs_value, [{"x": 1.0}], tmp_path / "t", outputs=["x"], progress=False)


def abs_value(x):
    return {"y": abs(x)}


def test_run_doe_on_a_dask_client_gives_the_pool_table(tmp_path):
    """``run_doe(..., client=)`` runs the chunks on a Dask cluster (several chunks a task)
    and returns the process pool's table; 0.2.0's run_doe had no Dask route."""
    distributed = pytest.importorskip("distributed")
    from gfbopt.doe import run_doe

    plan = [{"x": float(x)} for x in range(-30, 30)]
    pool = run_doe(abs_value, plan, tmp_path / "pool", outputs=["y"], workers=2,
                   chunk_size=2, progress=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        dask = run_doe(abs_value, plan, tmp_path / "dask", outputs=["y"], client=client,
                       chunk_size=2, progress=False)
    columns = ["point", "x", "y", "success", "message"]
    assert dask[columns].equals(pool[columns])
    assert dask["y"].tolist() == [abs(p["x"]) for p in plan]
