"""A fast path for warm-started static solves: Newton's method on the built CasADi equations.

Inside a search (the onset speed along a rotor's mass–speed line, a continuation) each static
solve starts from the equilibrium of a nearby operating point.  IPOPT then takes the same two
to four iterations a plain Newton iteration takes on the same square system g(x, p) = 0, but
each of its iterations costs several sparse LUs' worth of work (the KKT system is twice the
size, MUMPS analyses it on every call, and the interior-point bookkeeping adds more):
benchmarks/bench_onset.py measures it.  Here the equations and their sparse Jacobian are the
build's own CasADi functions (:meth:`StaticSolver.jacobian_function`, the Jacobian IPOPT is
given), evaluated through CasADi's zero-copy buffers, and a Newton step is one SuperLU
factorisation (columns ordered by minimum degree on A + Aᵀ, the order kept from the build's
first Jacobian: :mod:`gfbopt.sparse_lu`).

Steps.  Each step solves with the current LU; a new one (with a new Jacobian) is made only
when the chord steps on the current one stop paying: after the first step of an LU, the ratio
of each step to the one before is its contraction rate (chord steps multiply the error by
about the change of J since that LU), and a rate above :data:`CHORD_RATE` (less than a digit
a step, where an LU costs about ten residual evaluations and solves) makes the next step a
fresh Newton step.  Measured at 144 × 36 (Ruscitto, speed line 5,000–14,000 rpm): from a
start interpolated off the coarse grid the first Newton step is ~6e-3 and the chord steps on
its LU contract at 0.015–0.03 per step, converged in seven or eight chord steps (25 ms)
where a second LU and its Jacobian cost ~35 ms.  A solve at parameters within
:data:`REUSE_PARAMETERS` of those of the previous solve's last LU (a neighbouring speed of a
search) starts with chord steps on that LU; when that fails, the LU is dropped and the solve
starts again with a fresh one (only a converged solve's LU is kept).  Converged
when max |g| ≤ :data:`RESIDUAL_TOLERANCE`, or when max |g| is below IPOPT's own tolerance and
the last step has stalled at round-off.  Refused (the caller falls back to IPOPT) when the
iterate leaves IPOPT's bounds (P > 0, a total film H > 0, ε ≥ 0, −π/2 ≤ φ ≤ π), when a
factorisation is singular, or when it has not converged in :data:`MAX_STEPS` steps or
:data:`MAX_FACTORISATIONS` LUs.

Because IPOPT's equilibrium is the root of the same g (the bounds are inactive at a solution,
and a square nonsingular system fixes x whatever the barrier does to the multipliers), both
give the same state to the conditioning of J times the residual tolerance:
tests/verification/test_static_newton.py checks ≤ 1e-10.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Optional
import numpy as np
import scipy.sparse as sp

from ..threads import single_threaded

#: largest number of steps (Newton and chord) before the fast path gives up: at the
#: largest chord rate, :data:`CHORD_RATE`, ten steps gain ten digits
MAX_STEPS = 16
#: largest number of sparse LUs (Newton steps) before the fast path gives up
MAX_FACTORISATIONS = 6
#: max |g| accepted as converged [-] (IPOPT's tolerance is 1e-10)
RESIDUAL_TOLERANCE = 1e-11
#: IPOPT's constraint tolerance (ipopt.tol of :func:`~.build.default_ipopt_options`) [-]
IPOPT_TOLERANCE = 1e-10
#: a step whose largest component is below this has stalled at round-off [-]
STALL_STEP = 1e-13
#: a chord step larger than this fraction of the step before makes the next step a fresh
#: Newton step (module docstring) [-]
CHORD_RATE = 0.1
#: a solve whose parameters differ from those of the system's last LU by at most this
#: (relative, parameter by parameter) starts with chord steps on that LU: a speed step of
#: 1 % changes J by ~1 %, so each chord step gains about two digits (a worse rate than
#: :data:`CHORD_RATE` ends the chord after its second step) [-]
REUSE_PARAMETERS = 1e-2
#: the status a converged fast path reports (StaticSolution.status)
STATUS = "Newton_Converged"


@dataclass(frozen=True)
class NewtonOutcome:
    """What the fast path did: the final iterate ``x``, ``converged``, ``steps`` taken,
    ``factorisations`` (sparse LUs), the final max |g| ``residual`` and a ``reason`` when it
    did not converge."""

    x: np.ndarray
    converged: bool
    steps: int
    factorisations: int
    residual: float
    reason: str = ""

    def stats(self) -> dict:
        """The outcome in the keys of IPOPT's stats (what :func:`~.solve.postprocess` reads)."""
        return {"success": self.converged, "iter_count": self.steps,
                "return_status": STATUS if self.converged else f"Newton: {self.reason}"}


class NewtonSystem:
    """g(x, p) and ∂g/∂x of one :class:`~gfbopt.static.StaticSolver` as numpy arrays.

    One per solver and search: it holds CasADi evaluation buffers bound to its own arrays.
    """

    def __init__(self, solver):
        function = solver.jacobian_function()
        pattern = function.sparsity_out(1)
        self.shape = pattern.shape
        self._indices = np.asarray(pattern.row(), dtype=np.int32)
        self._indptr = np.asarray(pattern.colind(), dtype=np.int32)
        self._x = np.zeros(function.size1_in(0))
        self._p = np.zeros(function.size1_in(1))
        self._g = np.zeros(function.size1_out(0))
        self._nz = np.zeros(pattern.nnz())
        self._jac = _bound(function, self._x, self._p, self._g, self._nz)
        self._gr = np.zeros(self._g.size)
        self._res = _bound(solver.residual_function, self._x, self._p, self._gr)
        self.lower, self.upper = solver.bounds
        self.factorise = solver.factoriser
        self.kept: Optional[tuple] = None             # (p, LU) of the last factorisation
        self.kept_before: Optional[tuple] = None      # the one before, other parameters

    def forget(self) -> None:
        """Drop the kept factorisation (the next solve starts with a fresh LU)."""
        self.kept = self.kept_before = None

    def residual(self, x: np.ndarray, p: np.ndarray) -> np.ndarray:
        """g(x, p) (a new array)."""
        self._x[:], self._p[:] = x, p
        self._res()
        return self._gr.copy()

    def residual_and_jacobian(self, x: np.ndarray, p: np.ndarray) -> tuple:
        """(g, ∂g/∂x as CSC) at (x, p)."""
        self._x[:], self._p[:] = x, p
        self._jac()
        jac = sp.csc_matrix((self._nz.copy(), self._indices, self._indptr), shape=self.shape)
        return self._g.copy(), jac

    def inside_bounds(self, x: np.ndarray) -> bool:
        """True when x satisfies IPOPT's bounds (P > 0, a total film > 0, ε ≥ 0, φ range)."""
        return bool(np.all(x >= self.lower) and np.all(x <= self.upper))


def _bound(function, *arrays):
    """Evaluate ``function`` in place on ``arrays`` (inputs then outputs) through CasADi's
    buffer interface; returns the evaluation callable (the buffer stays referenced by it)."""
    buffer, evaluate = function.buffer()
    n_in = function.n_in()
    for k, a in enumerate(arrays):
        (buffer.set_arg if k < n_in else buffer.set_res)(k if k < n_in else k - n_in,
                                                          memoryview(a))

    def run():
        evaluate()
        return buffer
    return run


@single_threaded
def solve(system: NewtonSystem, x0: np.ndarray, p: np.ndarray,
          max_steps: Optional[int] = None, reuse: bool = True) -> NewtonOutcome:
    """Newton's method with chord steps on g(x, p) = 0 from ``x0`` (module docstring); at
    most ``max_steps`` steps (default :data:`MAX_STEPS`) and :data:`MAX_FACTORISATIONS` LUs.
    With ``reuse``, the system's last LU starts the iteration as a chord step when its
    parameters differ from ``p`` by at most :data:`REUSE_PARAMETERS` (relative): a
    neighbouring speed of a search; when that fails, the kept LU is dropped and the
    iteration starts again from ``x0`` with a fresh one (the outcome counts both).  The LU
    of a converged solve is kept for the next one; a failed solve keeps none."""
    max_steps = MAX_STEPS if max_steps is None else max_steps
    kept = None
    for entry in (system.kept, system.kept_before) if reuse else ():
        if (entry is not None and entry[0].shape == p.shape
                and np.all(np.abs(entry[0] - p) <= REUSE_PARAMETERS * np.abs(p))):
            kept = entry[1]
            break
    outcome, lu = _iterate(system, x0, p, max_steps, kept)
    if not outcome.converged and kept is not None:    # a stale LU: again with a fresh one
        again, lu = _iterate(system, x0, p, max_steps, None)
        outcome = replace(again, steps=again.steps + outcome.steps,
                          factorisations=again.factorisations + outcome.factorisations)
    if outcome.converged:
        if system.kept is not None and system.kept[1] is not lu:
            system.kept_before = system.kept          # e.g. the other bearing of a rotor
        system.kept = (np.array(p, dtype=float), lu)
    else:
        system.kept = None
    return outcome


def _iterate(system: NewtonSystem, x0: np.ndarray, p: np.ndarray, max_steps: int,
             lu) -> tuple:
    """(outcome, last LU) of Newton and chord steps from ``x0``, starting on ``lu`` when
    given (module docstring)."""
    x = np.array(x0, dtype=float)
    g = system.residual(x, p)
    last_step, steps, factorisations = np.inf, 0, 0
    refresh = lu is None               # the next step needs a fresh LU
    previous = None                    # the last step made on the current LU
    while True:
        residual = float(np.abs(g).max()) if g.size else 0.0
        if not np.isfinite(residual):
            return NewtonOutcome(x, False, steps, factorisations, residual,
                                 "the residual is not finite"), lu
        if residual <= RESIDUAL_TOLERANCE or (residual <= IPOPT_TOLERANCE
                                              and last_step <= STALL_STEP):
            return NewtonOutcome(x, True, steps, factorisations, residual), lu
        if steps >= max_steps or (refresh and factorisations >= MAX_FACTORISATIONS):
            return NewtonOutcome(x, False, steps, factorisations, residual,
                                 f"not converged in {steps} steps ({factorisations} LUs)"), lu
        if refresh:
            g, jac = system.residual_and_jacobian(x, p)
            try:
                lu = system.factorise(jac)
            except RuntimeError:                      # exactly singular
                return NewtonOutcome(x, False, steps, factorisations, residual,
                                     "singular Jacobian"), lu
            factorisations += 1
            previous = None
        step = lu.solve(-g)
        x += step
        steps += 1
        last_step = float(np.abs(step).max())
        refresh = previous is not None and last_step > CHORD_RATE * previous
        previous = last_step
        if not system.inside_bounds(x):
            return NewtonOutcome(x, False, steps, factorisations, residual,
                                 "the iterate left IPOPT's bounds"), lu
        g = system.residual(x, p)


@single_threaded
def warm_solve(solver, x0: np.ndarray, p: np.ndarray) -> NewtonOutcome:
    """The fast path from a warm start ``x0`` with the parameters ``p`` of
    :meth:`StaticSolver.parameters`, on the solver's own :class:`NewtonSystem`."""
    return solve(solver.newton_system(), x0, p)
