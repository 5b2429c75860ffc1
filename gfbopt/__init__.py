"""gfbopt — analysis and design of rigid rotors on bump-type gas foil bearings.

Pipeline (``docs/ARCHITECTURE.md``): inputs (:mod:`gfbopt.inputs`) → pointwise physics and
foil laws (:mod:`gfbopt.physics`) → grid and stencil (:mod:`gfbopt.discretisation`) →
CasADi/IPOPT equilibrium (:mod:`gfbopt.static`) → linearised dynamics (:mod:`gfbopt.linear`)
and transients (:mod:`gfbopt.transient`) → analyses as table rows (:mod:`gfbopt.analyses`),
executors (:mod:`gfbopt.parallel`), studies (:mod:`gfbopt.studies`), figures
(:mod:`gfbopt.plotting`) and the command line (:mod:`gfbopt.cli`).

Importing gfbopt changes no global state: BLAS/OpenMP threads are limited to one inside its
solver calls and given back after each (:mod:`gfbopt.threads`); the command line and the pool
workers pin them for the whole process; nothing is set at import.
"""
from .errors import ConvergenceError, GfboptError, ParameterError
from .inputs import DEFAULT_GRID, BearingGeometry, BearingModel, Grid, load_bearing
from .static import SolverCache, StaticSolution, StaticSolver, solve_static, solver_for
from .version import __version__

__all__ = [
    "BearingGeometry", "BearingModel", "ConvergenceError", "DEFAULT_GRID", "GfboptError",
    "Grid", "ParameterError", "SolverCache", "StaticSolution", "StaticSolver", "load_bearing",
    "solve_static", "solver_for", "__version__",
]
