"""Design of the bump-foil structure: materials and the geometry geometric program.

=============================  ===========================================================
module                         what it holds
=============================  ===========================================================
:mod:`.materials`              foil materials (E, ν, allowable stress) with their sources
:mod:`.spec`                   the design specification and result (validated inputs)
:mod:`.geometry_program`       pitch, half length and thickness for a target compliance S
                               (cvxpy geometric program), infeasibility diagnosis
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
