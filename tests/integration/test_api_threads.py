"""The library limits BLAS/OpenMP threads inside its own calls (gfbopt.threads), as the command
line does for its whole process, and gives a program its own setting back afterwards.

Each case runs in a fresh interpreter without the thread variables the test suite sets
(tests/conftest.py), so the libraries start as a user's program would have them.  A probe
wrapped around numpy's ``eigvals`` (the matched-whirl pencils) and scipy's ``splu`` (every
sparse LU) records what threadpoolctl reports while gfbopt runs; no time is measured."""
import json
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")

PROGRAM = r"""
import json, sys
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from threadpoolctl import threadpool_info, threadpool_limits

user = int(sys.argv[1])
if user:                                   # the program's own setting, made in code
    threadpool_limits(user)
counts = lambda: sorted({lib["num_threads"] for lib in threadpool_info()})
seen = {}

def probe(name, real):
    def call(*args, **kwargs):
        seen.setdefault(name, set()).update(counts())
        return real(*args, **kwargs)
    return call

np.linalg.eigvals = probe("eigvals", np.linalg.eigvals)
spla.splu = probe("splu", spla.splu)
spla.eigs = probe("eigs", spla.eigs)          # ARPACK: the Campbell diagram's modes

from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.system import rotor_onsets
from gfbopt.sparse_lu import factor

before = counts()
result = rotor_onsets(load_rotor("problems/rotors/blower.toml"), (8000, 16000),
                      grid=Grid(24, 8), show_progress=False)
after_analysis = counts()
from gfbopt.rotor.analyse import analyse_rotor   # the Campbell diagram's path too
analyse_rotor(load_rotor("problems/rotors/blower.toml"), (8000, 16000), campbell=True,
              campbell_speeds=2, grid=Grid(24, 8), show_progress=False)
after_campbell = counts()
factor(sp.csc_matrix(np.array([[4.0, 1.0], [1.0, 3.0]])))      # the sparse LU called alone
after_lu = counts()
raised = False
try:                                       # a call that raises inside the limit
    rotor_onsets(load_rotor("problems/rotors/blower.toml"), (9000, 8000), grid=Grid(24, 8))
except ValueError:
    raised = True
print(json.dumps({"before": before, "after_analysis": after_analysis, "after_lu": after_lu,
                  "after_campbell": after_campbell,
                  "after": counts(), "raised": raised,
                  "seen": {k: sorted(v) for k, v in seen.items()},
                  "onset": result.onset_speed_rpm}))
"""


def _run(user_threads: int, **environment: str) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in VARIABLES}
    env.update(environment, PYTHONPATH=str(REPO))
    out = subprocess.run([sys.executable, "-c", PROGRAM, str(user_threads)], cwd=REPO,
                         env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_one_blas_thread_inside_library_calls_and_the_users_setting_after():
    # a program that asked for 3 threads: gfbopt's solves see 1, the program 3 again after
    limited = _run(3)
    assert limited["before"] == [3]
    assert set(limited["seen"]) == {"eigvals", "splu", "eigs"}, limited["seen"]
    assert limited["seen"] == {"eigvals": [1], "splu": [1], "eigs": [1]}
    assert limited["raised"]
    assert (limited["after_analysis"] == limited["after_campbell"] == limited["after_lu"]
            == limited["after"] == [3])
    # a user who chose the count in the environment keeps what they have inside gfbopt
    # too, and the answer is the same to round-off whichever count the solves ran with
    chosen = _run(3, OPENBLAS_NUM_THREADS="2", OMP_NUM_THREADS="2")
    assert chosen["before"] == [3]
    assert chosen["seen"] == {"eigvals": [3], "splu": [3], "eigs": [3]}
    assert chosen["after"] == [3]
    assert 8000 < limited["onset"] < 16000
    assert abs(chosen["onset"] / limited["onset"] - 1) <= 1e-12
