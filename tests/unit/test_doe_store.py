"""The results store: fixed schema, atomic parts, resume, refusal to mix studies."""
import os
import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from gfbopt.doe import ResultStore, read_results
from gfbopt.errors import ParameterError

SCHEMA = {"point": "int64", "eccentricity": "float64", "load": "float64", "success": "bool",
          "message": "string"}


def test_columns_that_appear_later_are_kept(tmp_path):
    """A failed row has no outputs and a later row has them: both kept, nulls where missing
    (a directory read without a fixed schema drops such columns silently)."""
    store = ResultStore.create(tmp_path / "s", study="x", study_hash="h1", schema=SCHEMA)
    store.append([{"point": 0, "eccentricity": 0.2, "success": False, "message": "failed"}])
    store.append([{"point": 1, "eccentricity": 0.4, "load": 1.5, "success": True,
                   "message": ""}])
    frame = read_results(tmp_path / "s")
    assert list(frame.columns) == list(SCHEMA)
    assert frame["load"].isna().tolist() == [True, False]
    assert frame.loc[1, "load"] == 1.5 and frame.loc[0, "message"] == "failed"


def test_unknown_column_is_refused(tmp_path):
    store = ResultStore.create(tmp_path / "s", study="x", study_hash="h1", schema=SCHEMA)
    with pytest.raises(ParameterError, match=r"row = 'attitude': is not a column"):
        store.append([{"point": 0, "attitude": 1.0}])


def test_resume_refuses_another_study_and_keeps_old_results_aside(tmp_path):
    store = ResultStore.create(tmp_path / "s", study="a", study_hash="h1", schema=SCHEMA)
    store.append([{"point": 0, "eccentricity": 0.1}])
    with pytest.raises(ParameterError, match=r"--resume = .*holds results of another study"):
        ResultStore.create(tmp_path / "s", study="b", study_hash="h2", schema=SCHEMA,
                           resume=True)
    again = ResultStore.create(tmp_path / "s", study="a", study_hash="h1", schema=SCHEMA,
                               resume=True)
    assert again.done_points() == {0}
    ResultStore.create(tmp_path / "s", study="a", study_hash="h1", schema=SCHEMA)  # fresh
    assert read_results(tmp_path / "s.previous-1")["point"].tolist() == [0]
    assert read_results(tmp_path / "s").empty


def test_each_point_once_when_a_point_is_written_twice(tmp_path):
    store = ResultStore.create(tmp_path / "s", study="a", study_hash="h1", schema=SCHEMA)
    store.append([{"point": 3, "load": 1.0}])
    store.append([{"point": 3, "load": 2.0}])
    assert read_results(tmp_path / "s")["load"].tolist() == [2.0]


WRITER = textwrap.dedent("""
    import sys, time
    from gfbopt.doe import ResultStore
    schema = {"point": "int64", "value": "float64"}
    store = ResultStore.create(sys.argv[1], study="k", study_hash="h", schema=schema,
                               resume=True)
    done = store.done_points()
    for p in range(200):
        if p in done:
            continue
        store.append([{"point": p, "value": p * 0.5}])
        print(p, flush=True)
        time.sleep(0.01)
""")


def test_kill_9_mid_run_then_resume_has_every_point_exactly_once(tmp_path):
    script = tmp_path / "writer.py"
    script.write_text(WRITER)
    target = str(tmp_path / "store")
    proc = subprocess.Popen([sys.executable, str(script), target], stdout=subprocess.PIPE,
                            text=True)
    for _ in range(30):                   # let it write some parts, then kill it hard
        proc.stdout.readline()
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    proc.stdout.close()
    partial = read_results(target)        # readable after SIGKILL
    assert 30 <= len(partial) < 200
    out = subprocess.run([sys.executable, str(script), target], capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    frame = read_results(target)
    assert frame["point"].tolist() == list(range(200))
    np.testing.assert_allclose(frame["value"], np.arange(200) * 0.5)
