"""One Timoshenko beam element of a spinning shaft, and a rigid disk: their matrices in SI.

Degrees of freedom of a node (the sign convention of :mod:`gfbopt.rotor.rigid`): x, y the
axis's displacement [m]; ψx, ψy the cross-section's rotations [rad], which are dx/dz and
dy/dz in the Euler–Bernoulli limit (shear off).  Both bending planes (x–z and y–z) then have
the same element matrices, with no sign flip.  An element joins nodes a and b; its 8 degrees
of freedom are (x_a, y_a, ψx_a, ψy_a, x_b, y_b, ψx_b, ψy_b).

Per bending plane, with (w_a, β_a, w_b, β_b) and ξ = s/l ∈ [0, 1], the interdependent
interpolation of the Timoshenko beam (exact for the static homogeneous beam; Friedman &
Kosmatka 1993, Comput. Struct. 47, 473–481), Φ = 12 E I/(κ G A l²):

    w(ξ) = [1 − 3ξ² + 2ξ³ + Φ(1 − ξ),  l(ξ − 2ξ² + ξ³ + Φ(ξ − ξ²)/2),
            3ξ² − 2ξ³ + Φ ξ,           l(−ξ² + ξ³ − Φ(ξ − ξ²)/2)] / (1 + Φ)
    β(ξ) = [6(ξ² − ξ)/l,  1 − 4ξ + 3ξ² + Φ(1 − ξ),  6(ξ − ξ²)/l,  −2ξ + 3ξ² + Φ ξ] / (1 + Φ)

and the matrices are the integrals of the energies (Gauss–Legendre, exact for these degrees):

    M = ∫ ρA wᵀw ds + ∫ ρI βᵀβ ds          (translational + rotary inertia)
    K = ∫ EI β'ᵀβ' ds + ∫ κGA (w' − β)ᵀ(w' − β) ds
    G: the x-plane rows against the y-plane columns are +∫ ρ(2I) βᵀβ ds, the transpose
       block −: the spinning section's polar inertia ρ J = 2ρI per length, the same skew
       G[ψx, ψy] = +I_p of the rigid body (M q̈ + ω G q̇ + K q = Q).

Φ → 0 gives the Euler–Bernoulli element (cubic Hermite w).  The shear coefficient of a
hollow circular section, m = d_i/d_o, is Cowper's (1966, "The shear coefficient in
Timoshenko's beam theory", J. Appl. Mech. 33, 335–340, Table 1), the default of ROSS 3.x:

    κ = 6(1 + ν)(1 + m²)² / ((7 + 6ν)(1 + m²)² + (20 + 12ν) m²),     G = E/(2(1 + ν)).

A disk at a node adds m to x and y, I_t to ψx and ψy, and ±I_p to G[ψx, ψy] / G[ψy, ψx].
"""
from __future__ import annotations

import math

import numpy as np

#: Gauss–Legendre points and weights on [0, 1] (5 points: exact to degree 9; the integrands
#: are at most of degree 6)
_XI, _WEIGHTS = np.polynomial.legendre.leggauss(5)
_XI, _WEIGHTS = 0.5 * (_XI + 1.0), 0.5 * _WEIGHTS

#: the x-plane's and the y-plane's places among an element's 8 degrees of freedom
X_PLANE = (0, 2, 4, 6)
Y_PLANE = (1, 3, 5, 7)


def shear_coefficient(inner_diameter: float, outer_diameter: float, poisson: float) -> float:
    """Cowper's κ of a hollow circular section [-] (module docstring)."""
    m2 = (inner_diameter / outer_diameter) ** 2
    r = (1.0 + m2) ** 2
    return 6.0 * (1.0 + poisson) * r / ((7.0 + 6.0 * poisson) * r + (20.0 + 12.0 * poisson) * m2)


def section(outer_diameter: float, inner_diameter: float) -> tuple[float, float]:
    """(A [m²], I [m⁴]) of a hollow circular section, I the diametral second moment."""
    area = math.pi / 4.0 * (outer_diameter ** 2 - inner_diameter ** 2)
    inertia = math.pi / 64.0 * (outer_diameter ** 4 - inner_diameter ** 4)
    return area, inertia


def shape_functions(xi, length: float, phi: float) -> tuple[np.ndarray, np.ndarray]:
    """(N_w, N_β) at ξ (array): rows of 4 over (w_a, β_a, w_b, β_b) (module docstring)."""
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    l, p, d = length, phi, 1.0 + phi
    nw = np.stack([1 - 3 * xi**2 + 2 * xi**3 + p * (1 - xi),
                   l * (xi - 2 * xi**2 + xi**3 + p * (xi - xi**2) / 2),
                   3 * xi**2 - 2 * xi**3 + p * xi,
                   l * (-xi**2 + xi**3 - p * (xi - xi**2) / 2)], axis=-1) / d
    nb = np.stack([6 * (xi**2 - xi) / l, 1 - 4 * xi + 3 * xi**2 + p * (1 - xi),
                   6 * (xi - xi**2) / l, -2 * xi + 3 * xi**2 + p * xi], axis=-1) / d
    return nw, nb


def _derivatives(xi, length: float, phi: float) -> tuple[np.ndarray, np.ndarray]:
    """(dN_w/ds, dN_β/ds) at ξ (s = ξ l)."""
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    l, p, d = length, phi, 1.0 + phi
    dw = np.stack([(-6 * xi + 6 * xi**2 - p) / l,
                   1 - 4 * xi + 3 * xi**2 + p * (1 - 2 * xi) / 2,
                   (6 * xi - 6 * xi**2 + p) / l,
                   -2 * xi + 3 * xi**2 - p * (1 - 2 * xi) / 2], axis=-1) / d
    db = np.stack([6 * (2 * xi - 1) / l**2, (-4 + 6 * xi - p) / l,
                   6 * (1 - 2 * xi) / l**2, (-2 + 6 * xi + p) / l], axis=-1) / d
    return dw, db


def plane_matrices(length: float, area: float, inertia: float, density: float,
                   modulus: float, shear_modulus: float, kappa: float,
                   shear: bool = True) -> dict:
    """One bending plane's 4 × 4 matrices {'mass', 'rotary', 'stiffness'} and 'phi' [-]
    (rotary: ∫ ρI βᵀβ ds, the block that the gyroscopic matrix doubles); ``shear`` False:
    the Euler–Bernoulli element (Φ = 0)."""
    phi = 12.0 * modulus * inertia / (kappa * shear_modulus * area * length**2) if shear else 0.0
    nw, nb = shape_functions(_XI, length, phi)
    dw, db = _derivatives(_XI, length, phi)
    wl = _WEIGHTS * length
    gamma = dw - nb                                   # the shear strain's shape
    mass = density * area * np.einsum("g,gi,gj->ij", wl, nw, nw)
    rotary = density * inertia * np.einsum("g,gi,gj->ij", wl, nb, nb)
    stiffness = modulus * inertia * np.einsum("g,gi,gj->ij", wl, db, db)
    if shear:
        stiffness = stiffness + kappa * shear_modulus * area * np.einsum(
            "g,gi,gj->ij", wl, gamma, gamma)
    return {"mass": mass, "rotary": rotary, "stiffness": stiffness, "phi": phi}


def element_matrices(length: float, outer_diameter: float, inner_diameter: float,
                     density: float, modulus: float, poisson: float,
                     shear: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(M, G, K) of one element, 8 × 8 over (x_a, y_a, ψx_a, ψy_a, x_b, y_b, ψx_b, ψy_b)
    [kg, kg m, kg m², N/m, …]; G per rad/s of spin (skew).  ``shear`` False: Euler–Bernoulli
    with rotary inertia."""
    area, inertia = section(outer_diameter, inner_diameter)
    kappa = shear_coefficient(inner_diameter, outer_diameter, poisson)
    g_mod = modulus / (2.0 * (1.0 + poisson))
    p = plane_matrices(length, area, inertia, density, modulus, g_mod, kappa, shear)
    m, g, k = (np.zeros((8, 8)) for _ in range(3))
    for plane in (X_PLANE, Y_PLANE):
        ix = np.ix_(plane, plane)
        m[ix] = p["mass"] + p["rotary"]
        k[ix] = p["stiffness"]
    g[np.ix_(X_PLANE, Y_PLANE)] = 2.0 * p["rotary"]
    g[np.ix_(Y_PLANE, X_PLANE)] = -2.0 * p["rotary"]
    return m, g, k


def disk_matrices(mass: float, transverse_inertia: float,
                  polar_inertia: float) -> tuple[np.ndarray, np.ndarray]:
    """(M, G) of a rigid disk at a node, 4 × 4 over (x, y, ψx, ψy)."""
    m = np.diag([mass, mass, transverse_inertia, transverse_inertia])
    g = np.zeros((4, 4))
    g[2, 3], g[3, 2] = polar_inertia, -polar_inertia
    return m, g


def interpolation(xi: float, length: float, phi: float) -> np.ndarray:
    """The 2 × 8 matrix giving the axis's (x, y) at ξ ∈ [0, 1] of an element from its 8
    degrees of freedom: the element's own displacement interpolation N_w (cubic Hermite in
    the Euler–Bernoulli limit)."""
    nw = shape_functions(xi, length, phi)[0][0]
    s = np.zeros((2, 8))
    s[0, list(X_PLANE)] = nw
    s[1, list(Y_PLANE)] = nw
    return s
