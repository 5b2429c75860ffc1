"""gfbopt — analysis and design of rigid rotors on bump-type gas foil bearings.

Pipeline (see docs/ARCHITECTURE.md): inputs (:mod:`gfbopt.parameters`) → grid and stencil
(:mod:`gfbopt.discretisation`) → foil laws (:mod:`gfbopt.foil`) → CasADi/IPOPT equilibrium
(:mod:`gfbopt.static`) → results (frozen dataclasses, pandas tables) → studies, plots and the
command line (:mod:`gfbopt.studies`, :mod:`gfbopt.plotting`, :mod:`gfbopt.cli`).
"""
from .errors import ConvergenceError, GfboptError, ParameterError
from .parameters import DEFAULT_GRID, BearingGeometry, BearingModel, Grid
from .static import StaticSolution, StaticSolver, solve_static, solver_for

__version__ = "0.1.0"

__all__ = [
    "BearingGeometry", "BearingModel", "ConvergenceError", "DEFAULT_GRID", "GfboptError",
    "Grid", "ParameterError", "StaticSolution", "StaticSolver", "solve_static", "solver_for",
    "__version__",
]
