"""Radial growth of the journal at speed (centrifugal) and of journal and sleeve with
temperature (thermal), SI units.

Centrifugal growth: a disc of outer radius b (and inner radius a, 0 for a solid journal)
turning at ω [rad/s], in **plane stress** (σ_z = 0).  Plane stress because a journal or shaft
sleeve is free at its ends: for a thin disc it is exact, and for a free long cylinder the
generalised plane-strain solution (ε_z uniform, zero axial force) gives the same radial
displacement at the surface for the solid cylinder (DESIGN_NOTES "Clearance at speed: closed
forms"); plane strain (ε_z = 0, ends held) would apply only to a journal whose ends are
restrained axially, which a rotor's journal is not.

The general Lamé solution of the rotating disc (Timoshenko & Goodier, *Theory of Elasticity*,
3rd ed., 1970, §32):

    u(r) = A r + B/r − (1 − ν²) ρ ω² r³ / (8E)
    σ_r  = E/(1 − ν²) [(1 + ν) A − (1 − ν) B/r² − (3 + ν)(1 − ν²) ρ ω² r² / (8E)]

with free surfaces σ_r(a) = σ_r(b) = 0 (hollow) or B = 0 and σ_r(b) = 0 (solid, finite at the
axis).  :func:`centrifugal_growth` solves those conditions for (A, B) as a 2 × 2 linear system
and evaluates u(b); the closed forms it must meet are
:func:`solid_disc_growth_closed_form` ρω²b³(1 − ν)/(4E),
:func:`hollow_disc_growth_closed_form` ρω²b[(1 − ν)b² + (3 + ν)a²]/(4E) and, as a → b,
:func:`thin_ring_growth` ρω²b³/E (a ring's hoop stress ρω²r², u = r σ_θ/E).

Thermal growth of a free body at a uniform temperature: Δr = α r ΔT (exact for any shape at a
uniform temperature; a temperature varying through the body is left out).
"""
from __future__ import annotations

import numpy as np

from ..errors import ParameterError


def _check_disc(outer_radius, inner_radius, poisson_ratio, youngs_modulus, density):
    if not outer_radius > 0:
        raise ParameterError("radius", outer_radius, "must be > 0 [m]")
    if not 0 <= inner_radius < outer_radius:
        raise ParameterError("inner_radius", inner_radius, f"must satisfy 0 <= inner_radius "
                             f"< the journal radius {outer_radius!r} m (0: a solid journal)")
    if not -1.0 < poisson_ratio < 0.5:
        raise ParameterError("poisson_ratio", poisson_ratio, "must lie in (-1, 0.5)")
    if not youngs_modulus > 0:
        raise ParameterError("youngs_modulus", youngs_modulus, "must be > 0 [Pa]")
    if not density > 0:
        raise ParameterError("density", density, "must be > 0 [kg/m³]")


def lame_constants(omega, outer_radius, inner_radius, density, youngs_modulus,
                   poisson_ratio) -> tuple[float, float]:
    """(A [-], B [m²]) of the rotating disc's displacement u = A r + B/r − k r³, solved from
    the free-surface conditions σ_r = 0 at r = b (and at r = a > 0; B = 0 for a solid disc)
    as a linear system.  Units: ω [rad/s], radii [m], ρ [kg/m³], E [Pa]."""
    b, a, nu = float(outer_radius), float(inner_radius), float(poisson_ratio)
    _check_disc(b, a, nu, youngs_modulus, density)
    k = (1.0 - nu**2) * density * omega**2 / (8.0 * youngs_modulus)
    # σ_r (1 − ν²)/E = (1 + ν) A − (1 − ν) B/r² − (3 + ν) k r²  = 0
    if a == 0.0:
        matrix = np.array([[1.0 + nu, 0.0], [0.0, 1.0]])
        rhs = np.array([(3.0 + nu) * k * b**2, 0.0])
    else:
        # unknowns (A, B/b²): well scaled whatever the radius
        matrix = np.array([[1.0 + nu, -(1.0 - nu)], [1.0 + nu, -(1.0 - nu) * (b / a)**2]])
        rhs = np.array([(3.0 + nu) * k * b**2, (3.0 + nu) * k * a**2])
    a_const, b_scaled = np.linalg.solve(matrix, rhs)
    return float(a_const), float(b_scaled * b**2)


def centrifugal_growth(omega, outer_radius, inner_radius, density, youngs_modulus,
                       poisson_ratio) -> float:
    """Radial growth u(b) [m] of the journal's surface at ω [rad/s], from the general Lamé
    solution (plane stress, free surfaces; module docstring).  inner_radius 0: solid."""
    a_const, b_const = lame_constants(omega, outer_radius, inner_radius, density,
                                      youngs_modulus, poisson_ratio)
    b, nu = float(outer_radius), float(poisson_ratio)
    k = (1.0 - nu**2) * density * omega**2 / (8.0 * youngs_modulus)
    return a_const * b + b_const / b - k * b**3


def solid_disc_growth_closed_form(omega, radius, density, youngs_modulus, poisson_ratio):
    """ρω²b³(1 − ν)/(4E) [m]: a solid disc's surface growth in plane stress."""
    return density * omega**2 * radius**3 * (1.0 - poisson_ratio) / (4.0 * youngs_modulus)


def hollow_disc_growth_closed_form(omega, outer_radius, inner_radius, density,
                                   youngs_modulus, poisson_ratio):
    """ρω²b[(1 − ν)b² + (3 + ν)a²]/(4E) [m]: a hollow disc's outer growth in plane stress."""
    b, a, nu = outer_radius, inner_radius, poisson_ratio
    return density * omega**2 * b * ((1.0 - nu) * b**2 + (3.0 + nu) * a**2) / (
        4.0 * youngs_modulus)


def thin_ring_growth(omega, radius, density, youngs_modulus):
    """ρω²b³/E [m]: a thin ring (hoop stress ρω²b², u = b σ_θ/E), the hollow disc as a → b."""
    return density * omega**2 * radius**3 / youngs_modulus


def thermal_growth(expansion_coefficient, radius, temperature_rise):
    """Δr = α r ΔT [m]: free growth of radius r [m] at a uniform temperature rise ΔT [K] over
    the temperature the dimension was stated at; α [1/K]."""
    return expansion_coefficient * radius * temperature_rise
