"""Rotors on gas foil bearings in SI units: is the rotor stable, with what margin, from what
speed, in which mode, and the bearing's stiffness and damping for rotordynamics codes.  One
bearing carrying a rigid rotor's share, or a rotor of any size on two bearings (a rigid body
or a flexible shaft), every two-bearing analysis on one structure contract.

=========================  ==================================================================
module                     answers
=========================  ==================================================================
*one bearing*
:mod:`.analysis`           :func:`stability` — verdict, critical mass [kg], mass margin, the
                           least-stable mode (whirl frequency [Hz], growth rate [1/s], log
                           decrement) at one operating point
:mod:`.onset`              :func:`onset_speed` — the lowest speed of whirl on the rotor's
                           mass–speed line (load and mass fixed)
:mod:`.speed_line`         one bearing's mass–speed line (``BearingLine``); the package's one
                           onset secant (``secant_root``)
:mod:`.coefficients`       :func:`coefficient_table` — K [N/m], C [N s/m] against excitation
                           frequency [Hz], matched whirl
:mod:`.capacity`           load capacity and lift-off speed for a minimum-film limit
:mod:`.running_bearing`    one bearing's stability, onset and capacity at its running
                           clearance and viscosity (the heat balance of gfbopt.thermal)
:mod:`.running_files`      the same given a bearing file's path (gfbopt.api, the CLI)
*the rotor's structure*
:mod:`.structure`          the contract: M, G, K, C of any size and the station matrix S(z);
                           the rigid body (``RigidStructure``); ``structure_of(system)``
:mod:`.rigid`              the rigid body's matrices, load sharing, bearing transformations,
                           dynamic stiffness and imbalance forces on any structure
:mod:`.beam_element`       Timoshenko beam element and disk matrices
:mod:`.shaft`              the flexible shaft of beam elements and disks on the contract
:mod:`.condensed`          a shaft condensed on its bearings and a few modes (Craig–Bampton)
*a rotor on two bearings*
:mod:`.supports`           both bearings at one speed: equilibria, linearisations, impedances
:mod:`.reduced`            a bearing's impedance from its Krylov space (Schur form)
:mod:`.running`            each bearing at its running clearance and viscosity at each speed
                           (the heat balance of gfbopt.thermal)
:mod:`.matched_whirl`      the exact threshold at one speed: whirl frequencies and inertia scales
                           of every mode (n degrees of freedom, branches matched by MAC)
:mod:`.probe`              stability below the first threshold crossing
:mod:`.system`             onset of every mode along the speed line (``SpeedLine``, the API
                           ``gfbopt rotor`` wraps)
:mod:`.mode_search`        the mode-by-mode part of that search
:mod:`.modes`              mode shapes and their one label (forward/backward, cylindrical/
                           conical/mixed, bending n)
:mod:`.campbell`           full-system eigenvalues at one speed
:mod:`.tracking`           Campbell modes tracked over speed and named as the onsets
:mod:`.diagrams`           Campbell diagram, imbalance response, per-bearing approximation
:mod:`.friction_onset`     the settled whirl of a rotor whose bumps rub (describing function)
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
