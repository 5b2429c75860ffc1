"""Shared fixtures: solvers are expensive to build (~0.6 s), so build each once per session.

The default tier runs on every core (pytest-xdist, ``-n logical`` in pyproject.toml); each
worker is its own process with its own session fixtures.  ``python -m pytest -n 0`` runs in
one process (for --pdb or a single quick test)."""
import os

# One BLAS/OpenMP thread per test process, as the command line and the pool workers pin
# themselves (gfbopt.cli._limit_threads, gfbopt.parallel._start_worker): gfbopt's linear
# algebra is many small factorisations, and two xdist workers each running two BLAS threads on
# a 2-core machine would compete for the cores.  Set before numpy/CasADi load (they read these
# at load time) and inherited by the workers and every subprocess a test starts; a value the
# user set is kept.
if not any(os.environ.get(v) for v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS",
                                       "MKL_NUM_THREADS")):
    for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[_var] = "1"

import pytest  # noqa: E402

from gfbopt import Grid, StaticSolver  # noqa: E402


def pytest_configure(config):
    """The same pin for libraries a plugin loaded before this file (threadpoolctl)."""
    if os.environ.get("OPENBLAS_NUM_THREADS") == "1":
        from threadpoolctl import threadpool_limits

        threadpool_limits(1)


@pytest.fixture(scope="session")
def periodic_solver():
    return StaticSolver(Grid(72, 20), film="periodic")


@pytest.fixture(scope="session")
def coarse_periodic_solver():
    return StaticSolver(Grid(36, 10), film="periodic")


@pytest.fixture(scope="session")
def local_law_solver():
    return StaticSolver(Grid(72, 20), film="periodic", foil_law="local")
