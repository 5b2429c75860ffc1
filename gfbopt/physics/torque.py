"""Drag torque and power loss of a gas journal bearing, in SI (docs/PHYSICS.md §5b).

The torque the drive supplies to turn the journal against the film's shear, per bearing:

    T = ∬ R τ_j dA,   τ_j = μ U/h + (h/2) ∂p/∂x     (on the journal surface, U = ω R)

(the plane-Couette shear of the journal's motion plus the Poiseuille shear of the pressure
gradient on the moving surface: the classical friction of a journal bearing, e.g.
Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film Lubrication*, 2nd ed., 2004, ch. 10;
Szeri, *Fluid Film Lubrication*, 2nd ed., 2011, ch. 3).  Over Petroff's torque of a concentric
journal, T₀ = 2π μ ω R³ L / c, the torque ratio is

    T/T₀ = (1/(4π L/D)) [∬ dθ dZ / H  +  (3/Λ) ∬ H ∂P/∂θ dθ dZ]

whose quadrature is :func:`gfbopt.discretisation.shear_torque`.  Power loss P = T ω.
"""
from __future__ import annotations

import math


def petroff_torque(viscosity, omega, radius, length, radial_clearance):
    """Petroff's torque 2π μ ω R³ L / c [N m] of a concentric journal.

    viscosity μ [Pa s]; omega ω [rad/s]; radius R [m]; length L [m]; radial_clearance c [m].
    """
    return 2.0 * math.pi * viscosity * omega * radius**3 * length / radial_clearance


def omega_from_bearing_number(bearing_number, viscosity, radius, ambient_pressure,
                              radial_clearance):
    """ω [rad/s] of a bearing number Λ = 6 μ ω R²/(p_a c²) [-]."""
    return bearing_number * ambient_pressure * radial_clearance**2 / (6.0 * viscosity
                                                                       * radius**2)


def drag_torque_and_power(torque_ratio, bearing_number, geometry) -> tuple[float, float]:
    """(T [N m], power loss T ω [W]) of a torque ratio T/T₀ at bearing number Λ on a
    :class:`~gfbopt.inputs.bearing.BearingGeometry` (SI)."""
    omega = omega_from_bearing_number(bearing_number, geometry.viscosity, geometry.radius,
                                      geometry.ambient_pressure, geometry.radial_clearance)
    torque = torque_ratio * petroff_torque(geometry.viscosity, omega, geometry.radius,
                                           geometry.length, geometry.radial_clearance)
    return torque, torque * omega
