"""Nonlinear transients of rotors on gas foil bearings (numpy, batched over rotors).

============================  ======================================================================
module                        responsibility
============================  ======================================================================
:mod:`.system`                the method-of-lines system: state Φ = P H and the journal, right-hand
                              side, recovery of P and H through the foil law, stiffness bound
:mod:`.foil_state`            structural damping (η > 0): the Kelvin–Voigt foil state W,
                              τ_f W' + W = S q, τ_f = η/ν_ref, and why it matches the linear
                              analysis's loss factor at the threshold
:mod:`.rk4`                   classic Runge–Kutta, batched (the reference method)
:mod:`.rkc`                   damped Runge–Kutta–Chebyshev (RKC2), batched: stages from the
                              stiffness bound, step from accuracy (the default of the searches)
:mod:`.bdf`                   scipy's implicit BDF with a sparse Jacobian, rotor by rotor
:mod:`.orbit`                 the one :data:`METHODS` table (integrator, options, packed step),
                              :func:`check_method` and the driver :func:`integrate_orbits`
:mod:`.result`                :class:`OrbitBatch`, the result every method returns
:mod:`.fits`                  matrix-pencil growth rates and verdicts
:mod:`.mode`                  the least-stable linear mode shape as a starting perturbation
:mod:`.critical_mass`         the critical-mass search and limit-cycle amplitudes
:mod:`.hardening_recovery`    the hardening bump's recovery of P and H (guarded Newton per row)
:mod:`.friction_foil`         the bumps' Coulomb friction: each unit's slider state and recovery
:mod:`.friction_steps`        the friction driver's explicit steps (RK4 or damped RKC2)
:mod:`.friction_orbit`        one-bearing orbits with the sliders split off (operator splitting)
*the rotor*                   *a structure of any size (rigid body, condensed shaft) on two films*
:mod:`.rotor_setup`           a rotor in SI as the transient model of the rotor and both films
:mod:`.rotor_io`              the rotor file's dataclasses as :class:`~.rotor_setup.RotorInput`
:mod:`.rotor_model`           the model: a :class:`~gfbopt.rotor.structure.Structure` on its films
:mod:`.rotor_layout`          where each part of a packed batch state sits
:mod:`.rotor_films`           both bearings' films in one fused numpy evaluation
:mod:`.rotor_friction_films`  the fused films of bearings whose bumps rub (with or without η,
                              the sliders in the Kelvin–Voigt rate)
:mod:`.rotor_friction`        each bearing's sliders beside the rotor's state
:mod:`.rotor_running`         each bearing's running line over a ramp (a heated rotor)
:mod:`.rotor_heated`          the heated rotor's model, start and result on its running line
:mod:`.rotor_system`          the whole rotor and both films as one method-of-lines system
:mod:`.rotor_batch`           a batch of rotor runs: speed profile, inertia and imbalance scales
:mod:`.rotor_steps`           the rotor's step rules (its own period, a ramp's speed-following step)
:mod:`.rotor_run`             integrating the rotor with a method of :data:`METHODS` (RKC default)
:mod:`.rotor_result`          the result post-processed for engineers (SI, µm)
:mod:`.spectra`               waterfall, synchronous and subsynchronous components, limit cycles
:mod:`.rotor_analysis`        an orbit at constant speed, a run-up or coast-down
============================  ======================================================================

Imports point one way: foil_state → system → methods → orbit → critical_mass (no cycle);
:mod:`.mode` uses only :mod:`gfbopt.linear`'s Linearisation, the stencil and
:mod:`.foil_state`; :mod:`.foil_state` calls :mod:`gfbopt.linear` (inside a function) for the
default ν_ref.
"""
from .critical_mass import (DEFAULT_METHOD, CriticalMass, find_critical_mass,
                            limit_cycle_amplitudes)
from .foil_state import KelvinVoigtFoil
from .fits import VERDICTS, classify, fit_growth_rate
from .orbit import METHODS, integrate_orbits
from .mode import LinearMode, linear_mode
from .result import OrbitBatch
from .rk4 import RK4_STABILITY_RADIUS, STEP_SAFETY, rk4_step, stable_time_step
from .rkc import accuracy_step, rkc_coefficients, rkc_stability_interval, rkc_step, stages_for
from .system import (RightHandSide, State, TransientModel, equilibrium_state, film_force,
                     flux_residual, pressure_and_film, stiffness_bound, transient_model)

__all__ = ["CriticalMass", "DEFAULT_METHOD", "KelvinVoigtFoil", "LinearMode", "METHODS",
           "OrbitBatch",
           "RK4_STABILITY_RADIUS", "RightHandSide", "accuracy_step", "linear_mode",
           "rkc_coefficients", "rkc_stability_interval", "rkc_step", "stages_for",
           "STEP_SAFETY", "State", "TransientModel", "VERDICTS", "classify",
           "equilibrium_state", "film_force", "find_critical_mass", "fit_growth_rate",
           "flux_residual", "integrate_orbits", "limit_cycle_amplitudes", "pressure_and_film",
           "rk4_step", "stable_time_step", "stiffness_bound", "transient_model"]

# the whole rotor on both bearing films: gfbopt.transient.rotor_analysis
from .rotor_analysis import rotor_orbit, rotor_ramp  # noqa: E402

__all__ += ["rotor_orbit", "rotor_ramp"]
