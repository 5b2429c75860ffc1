"""The factoriser that keeps each sparsity pattern's fill-reducing order (gfbopt.sparse_lu).

Checked on the matrices it is made for — a static Jacobian and a perturbation matrix
A + sB of the Ruscitto bearing at 36 × 10 — and on a random non-symmetric pattern: the
solution equals a fresh SuperLU factorisation's to round-off (1e-12 relative: both are
partial-pivoting LUs of the same matrix with the same column order), the kept order gives
exactly SuperLU's own fill, a new pattern gets its own order, and the bits of a solution do
not depend on what the factoriser saw before.
"""
import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from gfbopt import Grid, SolverCache, solve_static
from gfbopt.inputs import Rotor, load_bearing_file
from gfbopt.linear import linearise
from gfbopt.rotor.analysis import resolve_case
from gfbopt.sparse_lu import Factoriser, OrderedLU

from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
GRID = Grid(36, 10)


@pytest.fixture(scope="module")
def matrices():
    bearing, options = load_bearing_file(REPO / "problems" / "bearings" / "ruscitto.toml")
    cache = SolverCache(GRID)
    case = resolve_case(bearing, Rotor(2.0), 20.0, options=options, grid=GRID, cache=cache)
    model = case.model(12000.0)
    solver = cache(model, GRID)
    sol = solve_static(model, load=case.load, solver=solver)
    p = solver.parameters(model, True, case.load)
    _, jac = solver.newton_system().residual_and_jacobian(sol.state, p)
    lin = linearise(sol, solver)
    a, b = lin.system(0.5j)
    return {"jacobian": jac, "perturbation": (a + (0.01 + 0.5j) * b).astype(complex).tocsc()}


def _random_matrix(seed: int) -> sp.csc_matrix:
    rng = np.random.default_rng(seed)
    m = sp.random(300, 300, density=0.01, random_state=rng, format="csc")
    return (m + sp.identity(300) * 4.0).tocsc()


@pytest.mark.parametrize("name", ["jacobian", "perturbation"])
def test_the_kept_order_solves_like_a_fresh_lu(matrices, name):
    a = matrices[name]
    factorise = Factoriser()
    first = factorise(a)                          # the first LU of a pattern computes its order
    assert isinstance(first, OrderedLU)
    scaled = a.copy()
    scaled.data = scaled.data * (1.0 + 0.1 * np.cos(np.arange(scaled.nnz)))   # new values
    kept, fresh = factorise(scaled), spla.splu(scaled, permc_spec="MMD_AT_PLUS_A")
    assert isinstance(kept, OrderedLU) and factorise.factorisations == 2
    rhs = np.random.default_rng(1).standard_normal((a.shape[0], 2)).astype(a.dtype)
    for b in (rhs, rhs[:, 0]):
        x = kept.solve(b)
        assert x.shape == b.shape
        assert np.abs(x - fresh.solve(b)).max() <= 1e-12 * np.abs(x).max()
        assert np.abs(scaled @ x - b).max() <= 1e-10 * np.abs(b).max()
    # the same column order, so exactly SuperLU's own fill
    assert kept._lu.L.nnz + kept._lu.U.nnz == fresh.L.nnz + fresh.U.nnz


def test_the_numbers_do_not_depend_on_what_was_factorised_before(matrices):
    """The same matrix gives the same bits as the first LU of a fresh factoriser (a new
    process, a pool worker) and as the tenth of a long-lived one: the serial and the pooled
    sweep rows are compared exactly (tests/integration/test_parallel_executors.py)."""
    a = matrices["perturbation"]
    rhs = np.random.default_rng(2).standard_normal((a.shape[0], 2)).astype(complex)
    fresh = Factoriser()(a).solve(rhs)
    used = Factoriser()
    for k in range(9):
        other = a.copy()
        other.data = other.data * (1.0 + 0.01 * k)
        used(other)
    assert np.array_equal(used(a).solve(rhs), fresh)


def test_each_pattern_gets_its_own_order():
    factorise = Factoriser()
    one, two = _random_matrix(1), _random_matrix(2)
    for m in (one, two, one, two):
        lu = factorise(m)
        b = np.arange(m.shape[0], dtype=float)
        assert np.abs(m @ lu.solve(b) - b).max() <= 1e-10 * np.abs(b).max()
    assert len(factorise._patterns) == 2
    # a pattern that loses an entry (an exact cancellation) is a new pattern
    fewer = one.copy()
    fewer.data[0] = 0.0
    fewer.eliminate_zeros()
    lu = factorise(fewer)
    assert len(factorise._patterns) == 3
    b = np.arange(fewer.shape[0], dtype=float)
    assert np.abs(fewer @ lu.solve(b) - b).max() <= 1e-10 * np.abs(b).max()
