"""Every conversion between SI quantities and gfbopt's non-dimensional groups.

This module is the only place where SI values and non-dimensional groups meet (see
``docs/PHYSICS.md``, section "Non-dimensional groups").  Symbols:

=========  ==============================================  =================================
symbol     definition                                      function
=========  ==============================================  =================================
ω          2π N/60 [rad/s], N the shaft speed [rpm]        :func:`rpm_to_rad_per_s`
Λ          6 μ ω R² / (p_a c²)                             :func:`bearing_number_from_speed`
S          p_a α / c                                       :func:`compliance_from_alpha`
C          E_t I_t c / (R⁴ L p_a),  I_t = L t_t³/12        :func:`top_foil_coefficient_from_geometry`
W̄          W / (p_a R²)                                    :func:`load_to_nondimensional`
M̄          M c ω² / W0 (M, W0 per bearing)                 :func:`mass_parameter`
K̄, C̄      K c/(p_a R²), C c ω/(p_a R²)                    :func:`stiffness_scale`,
                                                           :func:`damping_scale`
γ          Ω/ω = 2π f/ω (f the whirl frequency [Hz])       :func:`whirl_frequency_hz`,
                                                           :func:`whirl_ratio_from_frequency`
σ          growth rate per radian of shaft rotation        :func:`growth_rate_per_second`
δ          −2π σ/γ, logarithmic decrement per whirl cycle  :func:`logarithmic_decrement`
H          h/c                                             :func:`film_thickness_um`
W0 = M g   static load of a horizontal rigid rotor         :func:`rotor_weight_newton`
=========  ==============================================  =================================
"""
from __future__ import annotations

import math

from .checks import check_positive


def rpm_to_rad_per_s(speed_rpm: float) -> float:
    """Shaft speed [rpm] → angular speed ω [rad/s]."""
    return check_positive("speed_rpm", speed_rpm) * 2.0 * math.pi / 60.0


def rad_per_s_to_rpm(omega: float) -> float:
    """Angular speed ω [rad/s] → shaft speed [rpm]."""
    return omega * 60.0 / (2.0 * math.pi)


def bearing_number_from_speed(viscosity: float, omega: float, radius: float,
                              ambient_pressure: float, radial_clearance: float) -> float:
    """Bearing number Λ = 6 μ ω R² / (p_a c²) [-].

    viscosity μ [Pa s], omega ω [rad/s], radius R [m], ambient_pressure p_a [Pa],
    radial_clearance c [m].
    """
    return 6.0 * viscosity * omega * radius**2 / (ambient_pressure * radial_clearance**2)


def compliance_from_alpha(alpha: float, ambient_pressure: float, radial_clearance: float) -> float:
    """Compliance coefficient S = p_a α / c [-]; α [m³/N], p_a [Pa], c [m]."""
    return ambient_pressure * alpha / radial_clearance


def top_foil_coefficient_from_geometry(top_foil_youngs_modulus: float, top_foil_thickness: float,
                                       radius: float, length: float, ambient_pressure: float,
                                       radial_clearance: float) -> float:
    """Top-foil bending coefficient C = E_t I_t c / (R⁴ L p_a), I_t = L t_t³/12 [-].

    E_t [Pa], t_t [m], R [m], L [m], p_a [Pa], c [m].
    """
    second_moment = length * top_foil_thickness**3 / 12.0
    return (top_foil_youngs_modulus * second_moment * radial_clearance
            / (radius**4 * length * ambient_pressure))


def load_to_nondimensional(load_newton: float, ambient_pressure: float, radius: float) -> float:
    """Static load W [N] → W̄ = W / (p_a R²) [-]."""
    return load_newton / (ambient_pressure * radius**2)


def load_to_newton(load: float, ambient_pressure: float, radius: float) -> float:
    """W̄ = W / (p_a R²) [-] → W [N]."""
    return load * ambient_pressure * radius**2


def mass_parameter(mass_kg: float, radial_clearance: float, omega: float,
                   load_newton: float) -> float:
    """Rotor mass parameter M̄ = M c ω² / W0 [-].

    mass_kg M: rotor mass carried by one bearing [kg]; radial_clearance c [m]; omega ω
    [rad/s]; load_newton W0: static load on that bearing [N].
    """
    return mass_kg * radial_clearance * omega**2 / load_newton


def mass_from_parameter(mass_parameter_value: float, radial_clearance: float, omega: float,
                        load_newton: float) -> float:
    """Rotor mass per bearing M = M̄ W0 / (c ω²) [kg] (inverse of :func:`mass_parameter`)."""
    return mass_parameter_value * load_newton / (radial_clearance * omega**2)


def stiffness_scale(ambient_pressure: float, radius: float, radial_clearance: float) -> float:
    """p_a R²/c [N/m]: K = K̄ · this; damping C = C̄ · this / ω [N s/m]."""
    return ambient_pressure * radius**2 / radial_clearance


def damping_scale(ambient_pressure: float, radius: float, radial_clearance: float,
                  omega: float) -> float:
    """p_a R²/(c ω) [N s/m]: damping C = C̄ · this.  p_a [Pa], R [m], c [m], ω [rad/s]."""
    return stiffness_scale(ambient_pressure, radius, radial_clearance) / omega


def whirl_ratio_from_frequency(frequency_hz: float, omega: float) -> float:
    """Whirl ratio γ = 2π f/ω [-] of an excitation at f [Hz] on a shaft turning at ω [rad/s]."""
    return 2.0 * math.pi * frequency_hz / omega


def film_thickness_um(film: float, radial_clearance: float) -> float:
    """Film thickness h = H c in micrometres [µm] for H = h/c [-] and c [m]."""
    return film * radial_clearance * 1e6


#: standard gravity g [m/s²] (CGPM 1901)
STANDARD_GRAVITY = 9.80665


def rotor_weight_newton(mass_kg: float) -> float:
    """Static load W0 = M g [N] of a rotor mass M [kg] carried by one bearing of a horizontal
    rigid rotor (gravity only, g = 9.80665 m/s²)."""
    return mass_kg * STANDARD_GRAVITY


def whirl_frequency_hz(whirl_ratio: float, omega: float) -> float:
    """Whirl frequency f = γ ω / (2π) [Hz] for a whirl ratio γ [-] at ω [rad/s]."""
    return whirl_ratio * omega / (2.0 * math.pi)


def growth_rate_per_second(growth_rate: float, omega: float) -> float:
    """Growth rate σ [1/rad of shaft rotation] → σ ω [1/s]."""
    return growth_rate * omega


def logarithmic_decrement(growth_rate: float, whirl_ratio: float) -> float:
    """Logarithmic decrement δ = −2π σ/γ of a whirling mode s = σ + iγ [-] (> 0: stable)."""
    return -2.0 * math.pi * growth_rate / whirl_ratio
