"""Sparse LU factorisations whose fill-reducing order is computed once per sparsity pattern.

Every sparse LU in gfbopt's searches is SuperLU (:func:`scipy.sparse.linalg.splu`) with the
columns ordered by minimum degree on A + Aᵀ (``permc_spec="MMD_AT_PLUS_A"``): the matrices
(static Jacobians, perturbation matrices A + sB) are structurally near-symmetric five-point
stencils plus a few lifted rows.  Inside a search the same sparsity pattern is factorised
again and again with new values (a Newton step, a new speed, a new shift), and SuperLU
recomputes the ordering every time: at 144 × 36 (5,466 unknowns) it is a quarter to a third
of the factorisation (measured 16–28 ms with it, 12–19 ms on the matrix permuted by the kept
order; benchmarks/bench_onset.py, static section: ``one_lu_cpu_s`` against
``one_lu_kept_order_cpu_s``).

:class:`Factoriser` keeps, per pattern, the order SuperLU chose the first time (its column
permutation, elimination-tree postorder included) and factorises later matrices of that
pattern permuted symmetrically by it, with ``permc_spec="NATURAL"``: the same columns in the
same order, the same fill (checked: the same number of factor entries), and SuperLU's own
partial pivoting on the rows.  The solution is the same to round-off
(tests/unit/test_sparse_lu.py: ≤ 1e-12 relative against a fresh SuperLU LU).

Every LU, the first of a pattern included, is made on the permuted matrix, so the numbers do
not depend on what was factorised before: the same matrix gives the same bits in a fresh
process, a pool worker or after a long search (the order is a function of the pattern
alone: minimum degree and the elimination-tree postorder read only the structure).  The
first LU of a pattern is therefore made twice (once for the order), once per build.

A factoriser belongs to the object that owns the pattern (a static build, a Newton system),
so nothing is shared between builds or processes.
"""
from __future__ import annotations

from typing import Optional

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .threads import single_threaded

#: SuperLU's fill-reducing ordering of the first factorisation of a pattern
ORDERING = "MMD_AT_PLUS_A"
#: patterns a factoriser keeps (a build meets a handful: real and complex, bordered or not)
KEPT_PATTERNS = 16


class PatternError(Exception):
    """A kept order that does not reproduce its pattern (an internal error, never a
    singular matrix: SuperLU's RuntimeError says that)."""


class OrderedLU:
    """The LU of P A Pᵀ (P: the kept order) that solves A x = b like SuperLU's own object."""

    def __init__(self, lu, order: np.ndarray, inverse: np.ndarray):
        self._lu = lu
        self._order, self._inverse = order, inverse
        self.shape = lu.shape

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """x = A⁻¹ ``rhs`` (a vector or a matrix of right-hand sides)."""
        y = self._lu.solve(np.take(np.asarray(rhs), self._order, axis=0))
        return np.take(y, self._inverse, axis=0)        # x[order] = y, as a gather


class _Pattern:
    """A sparsity pattern's kept order: the permuted pattern and where each entry goes."""

    def __init__(self, matrix: sp.csc_matrix, perm_c: np.ndarray):
        self.order = np.argsort(perm_c)
        self.inverse = np.argsort(self.order)
        # entry numbers from 1, so that no entry is an explicit zero scipy could drop
        index = sp.csc_matrix((np.arange(1, matrix.nnz + 1, dtype=float), matrix.indices,
                               matrix.indptr), shape=matrix.shape)
        permuted = index[self.order][:, self.order].tocsc()
        permuted.sort_indices()
        if permuted.nnz != matrix.nnz:
            raise PatternError(f"the permuted pattern has {permuted.nnz} entries, the matrix "
                               f"{matrix.nnz}")
        # entry k of P A Pᵀ is A.data[source[k]]
        self.source = permuted.data.astype(np.int64) - 1
        self.indices, self.indptr = permuted.indices, permuted.indptr

    def permute(self, matrix: sp.csc_matrix) -> sp.csc_matrix:
        return sp.csc_matrix((matrix.data[self.source], self.indices, self.indptr),
                             shape=matrix.shape)


class Factoriser:
    """Sparse LUs with the order of each sparsity pattern kept from its first factorisation
    (module docstring).  ``factorisations`` counts the LUs made."""

    def __init__(self):
        self._patterns: dict = {}
        self.factorisations = 0

    @single_threaded
    def __call__(self, matrix: sp.spmatrix):
        """The LU of ``matrix`` (square, sparse): an object with ``solve``."""
        a = sp.csc_matrix(matrix)
        if not a.has_canonical_format:
            a = a.copy()
            a.sum_duplicates()
        key = (a.shape, a.dtype.kind, a.indptr.tobytes(), a.indices.tobytes())
        pattern: Optional[_Pattern] = self._patterns.pop(key, None)
        if pattern is not None:
            self._patterns[key] = pattern        # most recently used last (evicted last)
        self.factorisations += 1
        if pattern is None:                  # the order: SuperLU's, from a first LU
            order = spla.splu(a, permc_spec=ORDERING).perm_c
            if len(self._patterns) >= KEPT_PATTERNS:
                self._patterns.pop(next(iter(self._patterns)))
            pattern = self._patterns[key] = _Pattern(a, order)
        return OrderedLU(spla.splu(pattern.permute(a), permc_spec="NATURAL"), pattern.order,
                         pattern.inverse)


@single_threaded
def factor(matrix: sp.spmatrix, factoriser: Optional[Factoriser] = None):
    """Sparse LU of ``matrix``: with ``factoriser``, its kept order; without, SuperLU with
    :data:`ORDERING` computed afresh.  That ordering gives ~30 % less fill and ~1.5× faster
    factorisations than SuperLU's default COLAMD on the perturbation matrices (Ruscitto
    bearing at 144 × 36, 5,464 unknowns: 2.7·10⁵ against 3.9·10⁵ factor entries), with the
    same partial pivoting."""
    if factoriser is not None:
        return factoriser(matrix)
    return spla.splu(sp.csc_matrix(matrix), permc_spec=ORDERING)
