"""Design: the bump-foil structure (materials, the geometric program, stability-driven S) and
the bearing pair of a rotor against its top speed.

=============================  ===========================================================
module                         what it holds
=============================  ===========================================================
:mod:`.materials`              foil materials (E, ν, allowable stress) with their sources
:mod:`.spec`                   the design specification and result (validated inputs)
:mod:`.geometry_program`       pitch, half length and thickness for a target compliance S
                               (cvxpy geometric program), infeasibility diagnosis
:mod:`.gp_parts`               the geometric program's variables, monomials and constraints
:mod:`.stability_design`       the compliance S that maximises the onset, and its bump geometry
:mod:`.running_evaluation`     one trial S at the running condition ([journal]/[thermal])
:mod:`.outer_search`           a bounded 1-D search of an expensive figure of merit
*the bearing pair of a rotor*
:mod:`.problem`                variables with ranges, objectives, constraints
:mod:`.rotor_spec`             the design study's keys and their validation
:mod:`.rotor_objectives`       one bearing-pair design evaluated (onsets, power, film)
:mod:`.search`                 the ask/tell search methods (NSGA-II, Bayesian)
:mod:`.optimiser`              ask/tell driver, every evaluation streamed into the store
:mod:`.pareto`                 Pareto fronts, hypervolume
:mod:`.robustness`             tolerances, loss-factor band, default-grid check, top-speed run
:mod:`.surrogates`             analytic problems with known optima (tests, benchmarks)
=============================  ===========================================================

The formulas themselves are in :mod:`gfbopt.physics.bump`.  cvxpy takes about a second to
import, so the geometry program is imported on first use: the materials, the specification
and ``gfbopt design --help`` do not pay for it.
"""
from __future__ import annotations

from .materials import MATERIALS, Material, get_material, material_names

_GEOMETRY_PROGRAM_NAMES = ("BINDING_TOLERANCE", "OBJECTIVES", "BumpDesign", "BumpDesignSpec",
                           "Relaxation", "compliance_range", "design_bump_foil")

__all__ = ["BINDING_TOLERANCE", "MATERIALS", "OBJECTIVES", "BumpDesign", "BumpDesignSpec",
           "Material", "Relaxation", "compliance_range", "design_bump_foil", "get_material",
           "material_names"]


def __getattr__(name: str):
    if name in _GEOMETRY_PROGRAM_NAMES:
        from . import geometry_program
        return getattr(geometry_program, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
