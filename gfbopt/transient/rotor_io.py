"""The rotor file's dataclasses (:class:`gfbopt.inputs.rotor_system.RotorSystem`) as the
transient engine's :class:`~.rotor_setup.RotorInput`.

The matrices, load sharing and seam rule are :mod:`gfbopt.rotor.rigid`'s:
M, G in the coordinates (x, y, ψx, ψy); each bearing's formulation is its file's ``[model]``
table with the rotor file's overrides, a stated seam angle (fixed in the housing, stated
from gravity) re-measured from that bearing's own load (:func:`~gfbopt.rotor.rigid.seam_from_load`),
the rest filled by :func:`~gfbopt.inputs.options.resolve_model_options`.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import ParameterError
from ..inputs.options import resolve_model_options
from ..inputs.rotor_system import RotorSystem
from .rotor_setup import RotorBearing, RotorInput, gravity_force, imbalance_planes


def rotor_input(system: RotorSystem, imbalance=None) -> RotorInput:
    """The :class:`RotorInput` of ``system``; ``imbalance`` (a tuple of
    :class:`~gfbopt.inputs.rotor_system.ImbalancePlane`) replaces the file's planes."""
    from ..rotor.rigid import (applied_loads, bearing_loads, gyroscopic_matrix, mass_matrix,
                               seam_from_load)

    if not isinstance(system, RotorSystem):
        raise ParameterError("rotor", type(system).__name__, "must be a RotorSystem "
                             "(gfbopt.inputs.rotor_system.load_rotor)")
    loads = bearing_loads(system)
    bearings = []
    for support, load in zip(system.bearings, loads):
        options = resolve_model_options(seam_from_load(support.options,
                                                       load.away_from_gravity_deg))
        bearings.append(RotorBearing(support.geometry, support.position,
                                     options.model_kwargs(), support.name))
    centre = float(getattr(system, "centre_of_gravity", 0.0) or 0.0)
    force, moment = applied_loads(system, centre)
    static = np.array([force[0], force[1], moment[0], moment[1]], dtype=float)
    planes = system.imbalance if imbalance is None else tuple(imbalance)
    unbalance = imbalance_planes([(p.amount_kg_m, p.phase_deg, p.position) for p in planes])
    body = system.body
    description = {
        "rotor": body.name, "mass_kg": body.mass,
        "transverse_inertia_kg_m2": body.transverse_inertia,
        "polar_inertia_kg_m2": body.polar_inertia, "gravity_m_per_s2": system.gravity,
        "gravity_direction_deg": system.gravity_direction_deg,
        "bearings": [{"bearing": s.name, "position_m": s.position,
                      "bearing_file": s.file, **load.to_dict(),
                      **resolve_model_options(seam_from_load(
                          s.options, load.away_from_gravity_deg)).to_dict()}
                     for s, load in zip(system.bearings, loads)],
        "imbalance": [{"amount_kg_m": p.amount_kg_m, "amount_g_mm": p.amount_kg_m * 1e6,
                       "phase_deg": p.phase_deg, "position_m": p.position} for p in planes],
        "source": system.source}
    structure, generalised = shaft_input(system)
    return RotorInput(mass_matrix(body), gyroscopic_matrix(body), tuple(bearings), static,
                      unbalance, description, structure, generalised)


def shaft_input(system: RotorSystem) -> tuple:
    """(structure, Q_s) of a rotor with a shaft: the shaft of beam elements condensed on its
    bearing stations (:func:`gfbopt.rotor.condensed.condensed`, its lowest held modes: the
    transient's step follows the highest mode kept, :func:`.rotor_steps.rotor_frequency`)
    and its weight and side loads as a generalised force (:func:`.rotor_setup.gravity_force`);
    (None, None) for the rigid body."""
    if getattr(system, "shaft", None) is None:
        return None, None
    from ..rotor.condensed import condensed
    from ..rotor.shaft import shaft_structure

    structure = condensed(shaft_structure(system), [b.position for b in system.bearings])
    loads = [(*load.vector, load.position) for load in system.side_loads]
    return structure, gravity_force(structure, system.weight_vector, loads)


def frame_check(rotor: RotorInput, system: RotorSystem) -> float:
    """Largest difference [deg] between the engine's bearing load directions and the rotor
    module's (a consistency check of the two statics)."""
    from ..rotor.rigid import bearing_loads as rotor_loads

    from .rotor_setup import bearing_loads

    mine = bearing_loads(rotor)
    theirs = rotor_loads(system)
    return max(abs((math.degrees(math.atan2(m[1], m[0])) - t.direction_deg + 180) % 360 - 180)
               for m, t in zip(mine, theirs))
