"""Glossary entries by subject, merged into the one vocabulary :data:`gfbopt.glossary.GLOSSARY`.

Each module holds a ``TERMS`` dict, column → (unit, meaning), of one subject's tables; a name
defined twice (here or in :mod:`gfbopt.glossary`) is an error at import.  Add a subject by
adding its module to :data:`_PARTS`.
"""
from __future__ import annotations

from . import (answers, as_built, cooling_study, design, design_levers, friction, mode_shape,
               rotor_friction, rotor_friction_transient, rotor_heated_ramp, rotor_running,
               rotor_structure, rotor_transient, shaft, thermal)

_PARTS = (rotor_transient, rotor_structure, shaft, thermal, rotor_running, friction,
          rotor_friction, design, design_levers, mode_shape, rotor_friction_transient,
          rotor_heated_ramp, cooling_study, answers, as_built)


def _merged() -> dict:
    terms: dict[str, tuple[str, str]] = {}
    for part in _PARTS:
        for name, entry in part.TERMS.items():
            if name in terms:
                raise ValueError(f"glossary: {name!r} is defined twice in gfbopt/terms")
            terms[name] = entry
    return terms


#: every subject's entries, merged
TERMS = _merged()
