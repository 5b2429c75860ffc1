"""Bump-foil structure: compliance, stiffness, stresses and sag of a bump-type foil.

Pure formulas in SI units.  Every function evaluates on Python floats, numpy arrays and
cvxpy expressions alike: they use only ``*``, ``/`` and ``**`` with numeric exponents, so the
same definitions serve the plain evaluation and the geometric program of
:mod:`gfbopt.design.geometry_program` (every quantity here is a monomial in the geometry).
They do not validate their arguments (a cvxpy expression cannot be compared with zero);
callers check their inputs.

Model
-----
Each bump of pitch ``s``, half length ``l0`` and thickness ``t_b`` is idealised as two
cantilevers of length ``l0`` in cylindrical bending (plate modulus E' = E/(1 − ν²)), each
carrying half of the load ``Δp s`` (per unit axial width) that the pressure ``Δp`` puts on one
pitch.  This is the strip model of Heshmat, Walowit & Pinkus (1983), whose tip deflection gives
the compliance per unit area α = 2 s l0³ (1 − ν²)/(E t_b³); the root bending moment of the same
cantilever, Δp s l0 / 2, gives the bending stress σ_b = 3 Δp s l0 / t_b².  The top foil between
two bump crests is a strip of span ``s`` clamped at both crests under the uniform pressure Δp.

Symbols: s pitch [m], l0 half bump length [m], t_b bump thickness [m], t_top top-foil
thickness [m], E Young's modulus [Pa], ν Poisson's ratio [-], Δp design pressure (gauge,
p − p_a) [Pa], p_a ambient pressure [Pa], c radial clearance [m], R bearing radius [m].

References
----------
Heshmat, H., Walowit, J. A. & Pinkus, O. (1983). Analysis of gas-lubricated foil journal
    bearings. Journal of Lubrication Technology 105(4), 647–655.
Young, W. C. & Budynas, R. G. (2002). Roark's Formulas for Stress and Strain, 7th ed.,
    McGraw-Hill. Table 8.1 (straight beams: uniformly distributed load, both ends fixed —
    maximum deflection w l⁴/(384 E I), end moment w l²/12) with the plate modulus
    E/(1 − ν²) of a wide strip in cylindrical bending (Ch. 11).
"""
from __future__ import annotations

import math

__all__ = [
    "bump_bending_stress", "bump_compliance", "bump_deflection", "bump_stiffness_per_area",
    "compliance_coefficient", "number_of_bumps", "stress_at_fixed_compliance",
    "top_foil_sag", "top_foil_stress",
]


def bump_compliance(pitch, half_length, thickness, youngs_modulus, poisson_ratio):
    """Bump-foil compliance per unit area α = 2 s l0³ (1 − ν²) / (E t_b³).

    Heshmat, Walowit & Pinkus (1983), J. Lubr. Technol. 105(4):647–655.

    Parameters
    ----------
    pitch : bump pitch s [m]
    half_length : half bump length l0 [m]
    thickness : bump foil thickness t_b [m]
    youngs_modulus : Young's modulus of the bump foil E [Pa]
    poisson_ratio : Poisson's ratio of the bump foil ν [-]

    Returns
    -------
    α [m³/N]: foil deflection per unit pressure.
    """
    return (2.0 * pitch * half_length**3 * (1.0 - poisson_ratio**2)
            / (youngs_modulus * thickness**3))


def compliance_coefficient(alpha, ambient_pressure, radial_clearance):
    """Compliance coefficient S = p_a α / c (docs/PHYSICS.md).

    Parameters
    ----------
    alpha : bump compliance per unit area α [m³/N]
    ambient_pressure : ambient pressure p_a [Pa]
    radial_clearance : radial clearance c [m]

    Returns
    -------
    S [-]: foil deflection under one ambient pressure, in radial clearances.
    """
    return ambient_pressure * alpha / radial_clearance


def bump_stiffness_per_area(alpha):
    """Bump-foil stiffness per unit area K = 1/α.

    Parameters
    ----------
    alpha : bump compliance per unit area α [m³/N]

    Returns
    -------
    K [N/m³] (pressure per unit deflection), = E t_b³ / (2 s l0³ (1 − ν²)) (Heshmat 1983).
    """
    return 1.0 / alpha


def bump_bending_stress(design_pressure, pitch, half_length, thickness):
    """Root bending stress of a bump, σ_b = 3 Δp s l0 / t_b².

    The cantilever of Heshmat's strip model carries Δp s / 2 per unit width at its tip, so the
    root moment is Δp s l0 / 2 and σ_b = 6 M / t_b².  Equivalently σ_b = (3/2) E' t_b δ / l0²
    with δ = Δp α the bump deflection and E' = E/(1 − ν²).

    Parameters
    ----------
    design_pressure : film pressure above ambient on the foil Δp [Pa]
    pitch : bump pitch s [m]
    half_length : half bump length l0 [m]
    thickness : bump foil thickness t_b [m]

    Returns
    -------
    σ_b [Pa].
    """
    return 3.0 * design_pressure * pitch * half_length / thickness**2


def top_foil_sag(design_pressure, pitch, top_foil_thickness, youngs_modulus, poisson_ratio):
    """Sag of the top foil between two bump crests, Δp s⁴ (1 − ν²) / (32 E t_top³).

    A strip of span s clamped at both crests under uniform pressure (Roark, Young & Budynas
    2002, Table 8.1, both ends fixed: w l⁴/(384 E I)) with I = t_top³/12 per unit width and the
    plate modulus E/(1 − ν²).

    Parameters
    ----------
    design_pressure : film pressure above ambient Δp [Pa]
    pitch : bump pitch s (span between crests) [m]
    top_foil_thickness : top foil thickness t_top [m]
    youngs_modulus : Young's modulus of the top foil E [Pa]
    poisson_ratio : Poisson's ratio of the top foil ν [-]

    Returns
    -------
    Mid-span sag [m].
    """
    return (design_pressure * pitch**4 * (1.0 - poisson_ratio**2)
            / (32.0 * youngs_modulus * top_foil_thickness**3))


def top_foil_stress(design_pressure, pitch, top_foil_thickness):
    """Bending stress of the top foil over a bump crest, Δp s² / (2 t_top²).

    End moment of a clamped-clamped strip under uniform pressure, Δp s²/12 per unit width
    (Roark, Young & Budynas 2002, Table 8.1), and σ = 6 M / t_top².

    Parameters
    ----------
    design_pressure : film pressure above ambient Δp [Pa]
    pitch : bump pitch s [m]
    top_foil_thickness : top foil thickness t_top [m]

    Returns
    -------
    Stress [Pa].
    """
    return design_pressure * pitch**2 / (2.0 * top_foil_thickness**2)


def bump_deflection(design_pressure, alpha):
    """Bump deflection under the design pressure, δ = Δp α.

    Used for a no-flattening limit Δp α ≤ κ h_b (h_b the free bump height, κ < 1).

    Parameters
    ----------
    design_pressure : film pressure above ambient Δp [Pa]
    alpha : bump compliance per unit area α [m³/N]

    Returns
    -------
    δ [m].
    """
    return design_pressure * alpha


def number_of_bumps(radius, pitch):
    """Number of bumps round the bearing, N = 2π R / s (a real number; rounding is the caller's).

    Parameters
    ----------
    radius : bearing radius R [m]
    pitch : bump pitch s [m]

    Returns
    -------
    N [-].
    """
    return 2.0 * math.pi * radius / pitch


def stress_at_fixed_compliance(design_pressure, compliance, pitch, half_length,
                               radial_clearance, ambient_pressure, youngs_modulus,
                               poisson_ratio):
    """Bump bending stress at a given compliance coefficient, thickness eliminated.

    σ_b = 3 Δp (c E' S / (2 p_a))^{2/3} s^{1/3} / l0, E' = E / (1 − ν²): the thickness that
    gives S (from α = 2 s l0³/(E' t_b³), S = p_a α / c) substituted into σ_b = 3 Δp s l0 / t_b².
    At fixed S the stress falls with a longer half bump and rises only weakly with the pitch.

    Parameters
    ----------
    design_pressure : film pressure above ambient Δp [Pa]
    compliance : compliance coefficient S [-]
    pitch : bump pitch s [m]
    half_length : half bump length l0 [m]
    radial_clearance : radial clearance c [m]
    ambient_pressure : ambient pressure p_a [Pa]
    youngs_modulus : Young's modulus E [Pa]
    poisson_ratio : Poisson's ratio ν [-]

    Returns
    -------
    σ_b [Pa].
    """
    plate_modulus = youngs_modulus / (1.0 - poisson_ratio**2)
    return (3.0 * design_pressure
            * (radial_clearance * plate_modulus * compliance / (2.0 * ambient_pressure))
            ** (2.0 / 3.0)
            * pitch ** (1.0 / 3.0) / half_length)
