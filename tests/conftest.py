"""Shared fixtures: solvers are expensive to build (~0.6 s), so build each once per session."""
import pytest

from gfbopt import Grid, StaticSolver


@pytest.fixture(scope="session")
def periodic_solver():
    return StaticSolver(Grid(72, 20), film="periodic")


@pytest.fixture(scope="session")
def coarse_periodic_solver():
    return StaticSolver(Grid(36, 10), film="periodic")


@pytest.fixture(scope="session")
def local_law_solver():
    return StaticSolver(Grid(72, 20), film="periodic", foil_law="local")
