"""gfbopt — analysis and design of rigid rotors on bump-type gas foil bearings.

Pipeline (see docs/ARCHITECTURE.md): inputs (:mod:`gfbopt.parameters`) → grid and stencil
(:mod:`gfbopt.discretisation`) → foil laws (:mod:`gfbopt.foil`) → CasADi/IPOPT equilibrium
(:mod:`gfbopt.static`) → results (frozen dataclasses, pandas tables) → studies, plots and the
command line (:mod:`gfbopt.studies`, :mod:`gfbopt.plotting`, :mod:`gfbopt.cli`).
"""
import os as _os

# gfbopt's linear algebra is many small sparse factorisations (MUMPS, SuperLU) and batched
# numpy kernels; multi-threaded OpenBLAS makes each of them 10–100× slower on small machines
# (measured: benchmarks/bench_linear.py), and parallel sweeps use processes instead.  Respect
# a value the user has set; otherwise use one BLAS thread.  Must precede the numpy import.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    _os.environ.setdefault(_var, "1")

from .errors import ConvergenceError, GfboptError, ParameterError  # noqa: E402
from .parameters import DEFAULT_GRID, BearingGeometry, BearingModel, Grid  # noqa: E402
from .static import StaticSolution, StaticSolver, solve_static, solver_for  # noqa: E402

__version__ = "0.1.0"

__all__ = [
    "BearingGeometry", "BearingModel", "ConvergenceError", "DEFAULT_GRID", "GfboptError",
    "Grid", "ParameterError", "StaticSolution", "StaticSolver", "solve_static", "solver_for",
    "__version__",
]
