"""The clearance at speed: centrifugal and thermal growth of the journal and the sleeve, the
gas viscosity against temperature (Sutherland), a lumped thermal network of each bearing and
the fixed point that ties them to the film's drag power.

- :mod:`.growth`: Lamé plane-stress discs and rings, thermal growth Δr = α r ΔT;
- :mod:`.viscosity`: Sutherland's law;
- :mod:`.network`: the lumped thermal network (film, journal, foil, sleeve nodes);
- :mod:`.balance`: the heat balance with the film's torque ratio frozen, and its lowest root;
- :mod:`.running`: the fixed point per speed and the running clearance;
- :mod:`.bearing`: the film's drag at a running state (static solves) and the warm bearing;
- :mod:`.files`: a bearing file's ``[journal]`` and ``[thermal]`` tables → RunningSpec.

The analyses at the running condition that call the rotor's (stability, onset, capacity,
lift-off) are :mod:`gfbopt.rotor.running_bearing` (in the rotor's floor, above this one);
docs/thermal.md states the equations, constants and what the lumped model leaves out.
"""
from __future__ import annotations

from .growth import (centrifugal_growth, hollow_disc_growth_closed_form,
                     solid_disc_growth_closed_form, thermal_growth, thin_ring_growth)
from .viscosity import sutherland_viscosity

__all__ = ["centrifugal_growth", "hollow_disc_growth_closed_form",
           "solid_disc_growth_closed_form", "sutherland_viscosity", "thermal_growth",
           "thin_ring_growth"]
