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
    with pytest.raises(ParameterError, match=r"--resume = .*holds results of study 'a' with other inputs"):
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


# ------------------------------------------------------------------ durability
def test_a_second_holder_of_the_lock_is_refused_naming_the_first(tmp_path):
    """Two runs on one store mixed their rows in 0.2.0; now the second is refused in one
    line that names the running one (its pid)."""
    from gfbopt.doe.store import lock_store

    with lock_store(tmp_path / "s"):
        script = ("import sys; from gfbopt.doe.store import lock_store\n"
                  "with lock_store(sys.argv[1]): pass\n")
        out = subprocess.run([sys.executable, "-c", script, str(tmp_path / "s")],
                             capture_output=True, text=True, timeout=120)
        assert out.returncode != 0
        assert f"pid {os.getpid()}" in out.stderr and "is being written by another" in \
            out.stderr
    with lock_store(tmp_path / "s"):      # released: the next run takes it
        pass


def test_parts_without_manifest_are_moved_aside_not_taken_over(tmp_path):
    old = ResultStore.create(tmp_path / "s", study="a", study_hash="h1", schema=SCHEMA)
    old.append([{"point": 0, "eccentricity": 0.1}])
    (tmp_path / "s" / "manifest.json").unlink()
    with pytest.raises(ParameterError, match="no manifest.json"):
        ResultStore.create(tmp_path / "s", study="a", study_hash="h1", schema=SCHEMA,
                           resume=True)
    fresh = ResultStore.create(tmp_path / "s", study="a", study_hash="h1", schema=SCHEMA)
    assert fresh.read().empty                       # the orphan rows are not adopted
    assert any("moved aside" in n for n in fresh.notices)
    assert len(list((tmp_path / "s.orphan-1" / "parts").glob("part-*.parquet"))) == 1


def test_a_damaged_part_is_one_line_and_resume_moves_it_aside(tmp_path):
    store = ResultStore.create(tmp_path / "s", study="a", study_hash="h1", schema=SCHEMA)
    store.append([{"point": 0, "load": 1.0}])
    bad = store.append([{"point": 1, "load": 2.0}])
    bad.write_bytes(bad.read_bytes()[:40])          # truncated, as by a failing disk
    (tmp_path / "s" / "parts" / ".part-x.parquet.tmp").write_bytes(b"half")  # kill mid-write
    with pytest.raises(ParameterError) as info:
        read_results(tmp_path / "s")
    assert bad.name in str(info.value) and "is damaged" in str(info.value)
    assert "\n" not in str(info.value)
    again = ResultStore.create(tmp_path / "s", study="a", study_hash="h1", schema=SCHEMA,
                               resume=True)
    assert again.done_points() == {0}               # point 1 is computed again
    assert (tmp_path / "s" / "set-aside" / bad.name).is_file()
    assert not list((tmp_path / "s" / "parts").glob(".part-*.tmp"))
    assert any("temporary" in n for n in again.notices)


def test_a_part_of_another_study_is_refused_on_read(tmp_path):
    a = ResultStore.create(tmp_path / "a", study="a", study_hash="h1", schema=SCHEMA)
    b = ResultStore.create(tmp_path / "b", study="b", study_hash="h2", schema=SCHEMA)
    a.append([{"point": 0, "load": 1.0}])
    foreign = b.append([{"point": 1, "load": 9.0}])
    os.replace(foreign, tmp_path / "a" / "parts" / foreign.name)
    with pytest.raises(ParameterError, match="belongs to another study"):
        read_results(tmp_path / "a")


def test_infrastructure_failures_of_0_2_0_are_not_done(tmp_path):
    store = ResultStore.create(tmp_path / "s", study="a", study_hash="h1", schema=SCHEMA)
    store.append([{"point": 0, "success": True, "message": ""},
                  {"point": 1, "success": False, "message": "the worker process died "
                   "(BrokenProcessPool: A process in the process pool was terminated)"},
                  {"point": 2, "success": False, "message": "FutureCancelledError: x"},
                  {"point": 3, "success": False, "message": "ParameterError: load < 0"}])
    assert store.done_points() == {0, 3}             # 3 failed in the analysis: a result


def test_rows_arriving_together_are_written_in_parts_of_batch_rows(tmp_path):
    """A Dask task brings thousands of rows at once: the buffer writes them in parts of at
    most ``batch_rows`` (before: one part of all of them)."""
    import pyarrow.parquet as pq

    from gfbopt.doe.engine import Outcome, _Buffer

    store = ResultStore.create(tmp_path / "s", study="x", study_hash="h1", schema=SCHEMA)
    outcome = Outcome()
    buffer = _Buffer(store, lambda r: r, batch_rows=3, flush_s=10.0, outcome=outcome)
    buffer.add([{"point": k, "eccentricity": 0.1 * k, "success": True, "message": ""}
                for k in range(10)])
    buffer.flush()
    assert (outcome.rows, outcome.parts) == (10, 4)
    sizes = sorted(len(pq.read_table(p)) for p in store.parts())
    assert sizes == [1, 3, 3, 3]
    assert sorted(read_results(tmp_path / "s")["point"]) == list(range(10))
