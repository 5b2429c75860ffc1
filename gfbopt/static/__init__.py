"""Static equilibrium of a journal in a gas foil bearing: CasADi model, IPOPT solve.

The discrete Reynolds equation (:mod:`gfbopt.discretisation`), the foil law
(:mod:`gfbopt.physics.foil_laws`) and the force balance are assembled once per grid and
formulation (:mod:`.model`, :class:`StaticSolver` in :mod:`.build`); the operating values (Λ,
S, C, L/D, the eccentricity or load, the seam angle and the model switches) are CasADi
*parameters*, so one build serves a whole sweep.  :func:`solve_static` (:mod:`.solve`) finds
the equilibrium and returns a :class:`StaticSolution` (:mod:`.solution`) whose residuals are
recomputed with numpy (:func:`.solve.postprocess`).

Frame and conventions
---------------------
X lies along the static load (the direction the load pushes the journal), θ is measured from
+X in the direction of rotation.  The journal centre sits at (X, Y) = ε (cos φ, sin φ), φ the
attitude angle, so the film is H = 1 − ε cos(θ − φ) + W, thickest at θ = π + φ.  The film
force on the journal is F = −∬ (P − 1)(cos θ, sin θ) dθ dZ (per p_a R²); equilibrium is
F_X + W̄ = 0, F_Y = 0.  The grid starts at the seam (the welded end of the top foil) at
θ = θ_s: either an input angle from the load line, or θ_s = π + φ (the thesis's convention,
seam on the maximum-film line).

IPOPT solves the square system (zero objective) keeping P > 0 and H > 0 by bounds; the
unknowns and equations are listed in :mod:`.model`.
"""
from .build import (
    PerturbationBlocks,
    SolverCache,
    StaticSolver,
    default_ipopt_options,
    solver_for,
    solver_key,
)
from .model import PARAMETERS, Layout
from .solution import StaticSolution
from .solve import RESIDUAL_TOLERANCE, consistent_state, solve_static

__all__ = [
    "PARAMETERS", "RESIDUAL_TOLERANCE", "Layout", "PerturbationBlocks", "SolverCache",
    "StaticSolution", "StaticSolver", "consistent_state", "default_ipopt_options",
    "solve_static", "solver_for", "solver_key",
]
