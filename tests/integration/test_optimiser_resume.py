"""A design optimisation killed with SIGKILL and resumed evaluates every design once and
ends with the same table as an uninterrupted run (gfbopt.design.optimiser)."""
import os
import signal
import subprocess
import sys
import textwrap
import time
from collections import Counter
from pathlib import Path

import pytest

from gfbopt.design import surrogates
from gfbopt.design.optimiser import optimise, store_schema
from gfbopt.design.problem import DesignProblem, Objective, Variable
from gfbopt.design.search import SearchSettings
from gfbopt.doe.store import ResultStore

ZDT = DesignProblem(tuple(Variable(f"x{k}", 0.0, 1.0) for k in range(3)),
                    (Objective("f1"), Objective("f2")))
SETTINGS = SearchSettings("nsga2", budget=48, population=8, seed=11)
OUTPUTS = {"f1": "float64", "f2": "float64"}

DRIVER = textwrap.dedent("""
    import sys
    from gfbopt.design import surrogates
    from gfbopt.design.optimiser import optimise, store_schema
    from gfbopt.design.problem import DesignProblem, Objective, Variable
    from gfbopt.design.search import SearchSettings
    from gfbopt.doe.store import ResultStore

    problem = DesignProblem(tuple(Variable(f"x{k}", 0.0, 1.0) for k in range(3)),
                            (Objective("f1"), Objective("f2")))
    store = ResultStore.create(sys.argv[1], study="t", study_hash="h" * 64,
                               schema=store_schema(problem, {"f1": "float64",
                                                             "f2": "float64"}))
    optimise(problem, surrogates.zdt1, SearchSettings("nsga2", budget=48, population=8,
                                                      seed=11),
             fixed={"delay_s": 0.1, "log_path": sys.argv[2]}, store=store)
""")


def _calls(log: Path) -> Counter:
    if not log.exists():
        return Counter()
    return Counter(" ".join(line.split()[1:]) for line in log.read_text().splitlines())


def test_killed_run_resumes_with_every_design_evaluated_once(tmp_path):
    store_dir, log = tmp_path / "store", tmp_path / "calls.log"
    script = tmp_path / "driver.py"
    script.write_text(DRIVER)
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[2])}
    proc = subprocess.Popen([sys.executable, str(script), str(store_dir), str(log)], env=env)
    try:
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline:       # kill in the third generation (of six)
            # rows are written a part per generation of 8 (and every 5 s): two parts = 16 rows
            if len(list((store_dir / "parts").glob("part-*.parquet"))) >= 2:
                break
            if proc.poll() is not None:
                pytest.fail(f"the driver ended before it was killed (exit {proc.returncode})")
            time.sleep(0.05)
        else:
            pytest.fail("the driver stored fewer than 16 evaluations in 120 s")
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    schema = store_schema(ZDT, OUTPUTS)
    before = ResultStore.create(store_dir, study="t", study_hash="h" * 64, schema=schema,
                                resume=True).read()
    assert 16 <= len(before) < 48
    calls_before = _calls(log)
    store = ResultStore.create(store_dir, study="t", study_hash="h" * 64, schema=schema,
                               resume=True)
    resumed = optimise(ZDT, surrogates.zdt1, SETTINGS,
                       fixed={"delay_s": 0.0, "log_path": str(log)}, store=store)
    assert resumed.reused == len(before)
    assert resumed.evaluated == 48 - len(before)
    calls = _calls(log)
    after = calls - calls_before
    stored_before = {" ".join(f"{k}={float(r[k]).hex()}" for k in ("x0", "x1", "x2"))
                     for _, r in before.iterrows()}
    # no design stored before the kill was evaluated again ...
    assert not set(after) & stored_before
    # ... and every design was evaluated once, except at most the one in flight at the kill
    assert len(calls) == 48
    assert sum(n - 1 for n in calls.values()) <= 1
    final = ResultStore.create(store_dir, study="t", study_hash="h" * 64, schema=schema,
                               resume=True).read()
    assert len(final) == 48 and final["point"].is_unique
    # the resumed run ends where an uninterrupted one does
    clean = optimise(ZDT, surrogates.zdt1, SETTINGS)
    cols = ["point", "evaluation", "batch", "f1", "f2"]
    assert resumed.table[cols].equals(clean.table[cols])
    assert resumed.front["point"].tolist() == clean.front["point"].tolist()


def test_one_pool_for_the_run_gives_the_serial_answer():
    """Two spawn workers kept for the whole run (gfbopt.parallel.WorkerPool: one pool for
    six generations): the same table as the serial run, row for row, whatever the
    completion order."""
    from gfbopt.design.optimiser import executor
    from gfbopt.parallel import WorkerPool

    serial = optimise(ZDT, surrogates.zdt1, SETTINGS)
    with WorkerPool(2) as pool:
        pooled = optimise(ZDT, surrogates.zdt1, SETTINGS, run_tasks=executor(2))
    assert pool.started <= 2               # one pool: a pool per generation would start 12
    cols = ["point", "evaluation", "f1", "f2"]
    assert pooled.table[cols].equals(serial.table[cols])
    # the evaluations ran in the pool's workers, not here (which worker took which task is
    # the scheduler's business: one fast worker may take them all)
    assert not pooled.table["worker"].str.endswith(f":{os.getpid()}").any()


def test_ctrl_c_writes_the_rows_waiting_for_their_part(tmp_path):
    """Rows wait for the end of their generation before they are written (one Parquet part
    per generation, not per row); an interrupt (Ctrl-C) in the middle of a generation must
    still write the rows already finished, so a resume does not compute them again."""
    finished = 5

    def interrupted(function, arguments):
        for k, argument in enumerate(arguments[:finished]):
            yield k, function(argument)
        raise KeyboardInterrupt

    store = ResultStore.create(tmp_path / "store", study="t", study_hash="h" * 64,
                               schema=store_schema(ZDT, OUTPUTS))
    with pytest.raises(KeyboardInterrupt):
        optimise(ZDT, surrogates.zdt1, SETTINGS, store=store, run_tasks=interrupted)
    stored = store.read()
    assert len(stored) == finished
    assert len(store.parts()) == 1


def test_lost_designs_are_neither_stored_nor_told_and_a_resume_ends_as_a_clean_run(tmp_path):
    """The executor loses every design of the third generation (their workers died on every
    pool: gfbopt.parallel.stream_tasks yields InfrastructureFailure for them).  They must not
    be told to NSGA-II as failed designs (its next generation would differ from a clean
    run's): the search stops with InfrastructureError, the store holds the two generations
    evaluated and nothing else, and the resume ends with the clean run's table."""
    from gfbopt.parallel import stream_tasks
    from gfbopt.runtime import InfrastructureError, InfrastructureFailure

    def losing(function, arguments):
        for k, result in stream_tasks(function, arguments, workers=1):
            lost = losing.ran >= 16
            losing.ran += 1
            yield k, InfrastructureFailure("the worker process died on 3 pools") if lost \
                else result
    losing.ran = 0

    schema = store_schema(ZDT, OUTPUTS)
    store = ResultStore.create(tmp_path / "store", study="t", study_hash="h" * 64,
                               schema=schema)
    with pytest.raises(InfrastructureError, match="8 of 8 designs of batch 2"):
        optimise(ZDT, surrogates.zdt1, SETTINGS, store=store, run_tasks=losing)
    clean = optimise(ZDT, surrogates.zdt1, SETTINGS)
    stored = store.read()
    first_two = clean.table[clean.table["batch"] < 2]
    assert sorted(stored["point"]) == sorted(first_two["point"])
    assert store.rows_written() == 16
    resumed = optimise(ZDT, surrogates.zdt1, SETTINGS, store=ResultStore.create(
        tmp_path / "store", study="t", study_hash="h" * 64, schema=schema, resume=True))
    assert resumed.reused == 16 and resumed.evaluated == 32
    cols = ["point", "evaluation", "batch", "f1", "f2", "feasible"]
    assert resumed.table[cols].equals(clean.table[cols])
