"""Nonlinear transients of a rigid rotor on gas foil bearings (numpy, batched over rotors).

==========================  ========================================================================
module                      responsibility
==========================  ========================================================================
:mod:`.system`              the method-of-lines system: state Φ = P H and the journal, right-hand
                            side, recovery of P and H through the foil law, stiffness bound
:mod:`.rk4`                 classic Runge–Kutta, batched (the reference method)
:mod:`.bdf`                 scipy's implicit BDF with a sparse Jacobian, rotor by rotor
:mod:`.orbit`               the driver :func:`integrate_orbits` and the :data:`METHODS` table
:mod:`.result`              :class:`OrbitBatch`, the result every method returns
:mod:`.fits`                matrix-pencil growth rates and verdicts
:mod:`.critical_mass`       the critical-mass search and limit-cycle amplitudes
==========================  ========================================================================

Imports point one way: system → methods → orbit → critical_mass (no cycle).
"""
from .critical_mass import CriticalMass, find_critical_mass, limit_cycle_amplitudes
from .fits import VERDICTS, classify, fit_growth_rate
from .orbit import METHODS, integrate_orbits
from .result import OrbitBatch
from .rk4 import RK4_STABILITY_RADIUS, STEP_SAFETY, rk4_step, stable_time_step
from .system import (RightHandSide, State, TransientModel, equilibrium_state, film_force,
                     flux_residual, pressure_and_film, stiffness_bound, transient_model)

__all__ = ["CriticalMass", "METHODS", "OrbitBatch", "RK4_STABILITY_RADIUS", "RightHandSide",
           "STEP_SAFETY", "State", "TransientModel", "VERDICTS", "classify",
           "equilibrium_state", "film_force", "find_critical_mass", "fit_growth_rate",
           "flux_residual", "integrate_orbits", "limit_cycle_amplitudes", "pressure_and_film",
           "rk4_step", "stable_time_step", "stiffness_bound", "transient_model"]
