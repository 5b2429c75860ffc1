"""gfbopt — analysis and design of rigid rotors on bump-type gas foil bearings.

Pipeline (``docs/ARCHITECTURE.md``): inputs (:mod:`gfbopt.inputs`) → pointwise physics and
foil laws (:mod:`gfbopt.physics`) → grid and stencil (:mod:`gfbopt.discretisation`) →
CasADi/IPOPT equilibrium (:mod:`gfbopt.static`) → linearised dynamics (:mod:`gfbopt.linear`)
and transients (:mod:`gfbopt.transient`) → analyses as table rows (:mod:`gfbopt.analyses`),
executors (:mod:`gfbopt.parallel`), studies (:mod:`gfbopt.studies`), figures
(:mod:`gfbopt.plotting`) and the command line (:mod:`gfbopt.cli`).

What a user calls is at the top (:mod:`gfbopt.api`): ``gfbopt.load_bearing``,
``gfbopt.load_rotor``, one bearing's ``stability``, ``onset_speed``, ``load_capacity``,
``lift_off_speed``, the rotor's ``analyse_rotor``, ``rotor_orbit``, ``rotor_ramp``, and the
study runner ``run_study`` (``gfbopt run``, the bearing-pair design among its studies) and
``run_doe``; each takes ``grid=`` as a :class:`Grid` or as the command line writes it
(``"72x20"``).  Those of :mod:`gfbopt.api` are imported on first use, so ``import gfbopt``
costs only the static solver's imports.

Importing gfbopt changes no global state: BLAS/OpenMP threads are limited to one inside its
solver calls and given back after each (:mod:`gfbopt.threads`); the command line and the pool
workers pin them for the whole process; nothing is set at import.
"""
from .errors import ConvergenceError, GfboptError, ParameterError
from .inputs import (DEFAULT_GRID, BearingGeometry, BearingModel, Grid, OperatingPoint, Rotor)
from .inputs.bearing_file import load_bearing_public as load_bearing
from .inputs.grid import accepts_grid_strings as _accepts_grid_strings
from .inputs.grid import as_grid
from .static import SolverCache, StaticSolution, StaticSolver
from .static import solve_static as _solve_static
from .static import solver_for as _solver_for
from .version import __version__

#: the static solver's functions, taking grid="72x20" too (gfbopt.static's own take a Grid)
solve_static = _accepts_grid_strings(_solve_static)
solver_for = _accepts_grid_strings(_solver_for)

#: names loaded from :mod:`gfbopt.api` on first use (it imports the rotor, transient, study
#: and DOE layers; ``import gfbopt`` stays as cheap as the static solver's imports)
_LAZY = ("analyse_rotor", "coefficient_table", "lift_off_speed", "load_capacity", "load_rotor",
         "load_study", "onset_speed", "rotor_orbit", "rotor_ramp", "run_doe", "run_study",
         "stability")


def __getattr__(name: str):
    """``gfbopt.load_rotor`` and the other entry points of :mod:`gfbopt.api`, imported on
    first use (PEP 562)."""
    if name in _LAZY:
        from . import api
        value = getattr(api, name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'gfbopt' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "BearingGeometry", "BearingModel", "ConvergenceError", "DEFAULT_GRID", "GfboptError",
    "Grid", "OperatingPoint", "ParameterError", "Rotor", "SolverCache", "StaticSolution",
    "StaticSolver", "as_grid", "load_bearing", "solve_static", "solver_for", "__version__",
    *_LAZY,
]
