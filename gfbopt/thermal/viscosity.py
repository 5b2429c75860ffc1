"""Gas viscosity against temperature: Sutherland's law.

    μ(T) = μ_ref (T/T_ref)^{3/2} (T_ref + S)/(T + S)

μ_ref [Pa s] is the viscosity stated at T_ref [K] (gfbopt: the bearing file's ``viscosity`` at
the ``[thermal]`` table's ``viscosity_temperature``).  Sutherland's constant for air
S = 110.4 K: U.S. Standard Atmosphere, 1976 (NOAA/NASA/USAF, NOAA-S/T 76-1562), eq. (51),
μ = β T^{3/2}/(T + S), β = 1.458e-6 kg/(m s K^{1/2}); it gives +9.9 % from 300 K to 340 K.
"""
from __future__ import annotations

from ..errors import ParameterError

#: Sutherland's constant of air [K] (U.S. Standard Atmosphere 1976, eq. 51)
SUTHERLAND_AIR_K = 110.4
#: β of the same law [kg/(m s K^½)] (U.S. Standard Atmosphere 1976, eq. 51)
SUTHERLAND_AIR_BETA = 1.458e-6


def sutherland_viscosity(temperature, reference_viscosity, reference_temperature,
                         sutherland_constant=SUTHERLAND_AIR_K):
    """μ(T) [Pa s] by Sutherland's law through (T_ref [K], μ_ref [Pa s]); T [K] (scalars or
    numpy arrays).  μ(T_ref) = μ_ref exactly."""
    if not reference_temperature > 0:
        raise ParameterError("viscosity_temperature", reference_temperature,
                             "must be > 0 K (an absolute temperature)")
    if not sutherland_constant >= 0:
        raise ParameterError("sutherland_constant", sutherland_constant, "must be >= 0 K")
    ratio = temperature / reference_temperature
    return reference_viscosity * ratio**1.5 * (reference_temperature + sutherland_constant) / (
        temperature + sutherland_constant)
