"""Rigid rotors in SI units: is the rotor stable, with what margin, from what speed, and the
bearing's stiffness and damping for rotordynamics codes.

=========================  ==================================================================
module                     answers
=========================  ==================================================================
*one bearing*
:mod:`.analysis`           :func:`stability` — verdict, critical mass [kg], mass margin, the
                           least-stable mode (whirl frequency [Hz], growth rate [1/s], log
                           decrement) at one operating point
:mod:`.onset`              :func:`onset_speed` — the lowest speed of whirl on the rotor's
                           mass–speed line (load and mass fixed)
:mod:`.speed_line`         the mass–speed line as a function to search; the secant onset root
:mod:`.coefficients`       :func:`coefficient_table` — K [N/m], C [N s/m] against excitation
                           frequency [Hz], matched whirl
:mod:`.capacity`           load capacity and lift-off speed for a minimum-film limit
*a rigid rotor on two bearings*
:mod:`.rigid`              mass, gyroscopic and station matrices, load sharing, dynamic stiffness
:mod:`.supports`           both bearings at one speed: equilibria, linearisations, impedances
:mod:`.reduced`            a bearing's impedance from its Krylov space (Schur form)
:mod:`.matched_whirl`      the exact threshold at one speed: whirl frequencies and inertia scales
:mod:`.probe`              stability below the first threshold crossing
:mod:`.system`             onset of every mode along the speed line (the API ``gfbopt rotor`` wraps)
:mod:`.mode_search`        the mode-by-mode part of that search
:mod:`.modes`              mode shapes and their labels (forward/backward, cylindrical/conical)
:mod:`.campbell`           full-system eigenvalues at one speed
:mod:`.tracking`           Campbell modes tracked over speed and named as the onsets
:mod:`.diagrams`           Campbell diagram, imbalance response, per-bearing approximation
:mod:`.analyse`            :func:`~.analyse.analyse_rotor` — everything ``gfbopt rotor`` answers
:mod:`.ross_bridge`        each bearing's K and C in the form ROSS's ``BearingElement`` takes
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
