"""Rigid rotors in SI units: is the rotor stable, with what margin, from what speed, and the
bearing's stiffness and damping for rotordynamics codes.

=========================  ==================================================================
module                     answers
=========================  ==================================================================
:mod:`.analysis`           :func:`stability` — verdict, critical mass [kg], mass margin, the
                           least-stable mode (whirl frequency [Hz], growth rate [1/s], log
                           decrement) at one operating point
:mod:`.onset`              :func:`onset_speed` — the lowest speed of whirl on the rotor's
                           mass–speed line (load and mass fixed)
:mod:`.coefficients`       :func:`coefficient_table` — K [N/m], C [N s/m] against excitation
                           frequency [Hz], matched whirl
=========================  ==================================================================

Inputs are :class:`~gfbopt.inputs.rotor.Rotor` (mass per bearing) and
:class:`~gfbopt.inputs.rotor.OperatingPoint` (speed, load per bearing); formulation options
not stated come from the bearing file's ``[model]`` table or the defaults of
:func:`~gfbopt.inputs.options.resolve_model_options`.  The analysis is the non-dimensional
linear model (:mod:`gfbopt.linear`); all SI conversions are in
:mod:`gfbopt.inputs.conversions`.
"""
from ..inputs.rotor import OperatingPoint, Rotor
from .analysis import LoadCapacityError, StabilityResult, largest_converged_load, stability
from .coefficients import CoefficientTable, coefficient_table
from .onset import OnsetResult, onset_speed

__all__ = ["CoefficientTable", "LoadCapacityError", "OnsetResult", "OperatingPoint", "Rotor",
           "StabilityResult", "coefficient_table", "largest_converged_load", "onset_speed",
           "stability"]
