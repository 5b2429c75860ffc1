"""The converged search (nsga2_refine) killed with SIGKILL in its refinement stage and
resumed: every design evaluated once (but the one in flight at the kill), the same table and
the same convergence status as an uninterrupted run."""
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
from gfbopt.design.problem import Constraint, DesignProblem, Objective, Variable
from gfbopt.design.search import SearchSettings
from gfbopt.doe.store import ResultStore

BOWL = DesignProblem((Variable("x", 0.0, 1.0), Variable("y", 0.0, 1.0)), (Objective("f"),),
                     (Constraint("sum_xy", upper=1.0),))
SETTINGS = SearchSettings("nsga2_refine", budget=400, population=8, generations=3, seed=4,
                          step_tolerance=1e-4, improvement=1e-9)
OUTPUTS = {"f": "float64", "sum_xy": "float64"}

DRIVER = textwrap.dedent("""
    import sys
    from gfbopt.design import surrogates
    from gfbopt.design.optimiser import optimise, store_schema
    from gfbopt.design.problem import Constraint, DesignProblem, Objective, Variable
    from gfbopt.design.search import SearchSettings
    from gfbopt.doe.store import ResultStore

    problem = DesignProblem((Variable("x", 0.0, 1.0), Variable("y", 0.0, 1.0)),
                            (Objective("f"),), (Constraint("sum_xy", upper=1.0),))
    store = ResultStore.create(sys.argv[1], study="t", study_hash="h" * 64,
                               schema=store_schema(problem, {"f": "float64",
                                                             "sum_xy": "float64"}))
    optimise(problem, surrogates.pinched_bowl,
             SearchSettings("nsga2_refine", budget=400, population=8, generations=3, seed=4,
                            step_tolerance=1e-4, improvement=1e-9),
             fixed={"delay_s": 0.05, "log_path": sys.argv[2]}, store=store)
""")


def _calls(log: Path) -> Counter:
    if not log.exists():
        return Counter()
    return Counter(" ".join(line.split()[1:]) for line in log.read_text().splitlines())


def test_a_run_killed_in_the_refinement_resumes_with_every_design_once(tmp_path):
    store_dir, log = tmp_path / "store", tmp_path / "calls.log"
    script = tmp_path / "driver.py"
    script.write_text(DRIVER)
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[2])}
    proc = subprocess.Popen([sys.executable, str(script), str(store_dir), str(log)], env=env)
    try:
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline:
            # a part per batch: three NSGA-II generations, then the refinement's batches;
            # six parts = at least three refinement batches stored
            if len(list((store_dir / "parts").glob("part-*.parquet"))) >= 6:
                break
            if proc.poll() is not None:
                pytest.fail(f"the driver ended before it was killed (exit {proc.returncode})")
            time.sleep(0.02)
        else:
            pytest.fail("the driver stored fewer than six batches in 120 s")
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    schema = store_schema(BOWL, OUTPUTS)
    before = ResultStore.create(store_dir, study="t", study_hash="h" * 64, schema=schema,
                                resume=True).read()
    clean = optimise(BOWL, surrogates.pinched_bowl, SETTINGS)
    assert 24 < len(before) < len(clean.table)          # killed inside the refinement
    calls_before = _calls(log)
    resumed = optimise(BOWL, surrogates.pinched_bowl, SETTINGS,
                       fixed={"delay_s": 0.0, "log_path": str(log)},
                       store=ResultStore.create(store_dir, study="t", study_hash="h" * 64,
                                                schema=schema, resume=True))
    assert resumed.reused == len(before)
    assert resumed.evaluated == len(clean.table) - len(before)
    stored_before = {" ".join(f"{k}={float(r[k]).hex()}" for k in ("x", "y"))
                     for _, r in before.iterrows()}
    calls = _calls(log)
    assert not set(calls - calls_before) & stored_before    # nothing stored is redone
    assert len(calls) == len(clean.table)                   # every design evaluated ...
    assert sum(n - 1 for n in calls.values()) <= 1          # ... once, but the one in flight
    cols = ["point", "evaluation", "batch", "f", "sum_xy"]
    assert resumed.table[cols].equals(clean.table[cols])
    assert resumed.convergence == clean.convergence and resumed.converged
    assert resumed.stage_counts == clean.stage_counts
