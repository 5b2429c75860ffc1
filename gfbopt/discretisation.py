"""Finite-difference discretisation of the isothermal compressible Reynolds equation.

This module is the one definition of the film physics.  The same functions evaluate on
numpy arrays (numbers) and on CasADi SX column vectors (symbols): they only use
elementwise arithmetic and integer-array indexing, which both support.

Reynolds equation (docs/PHYSICS.md; θ = x/R, Z = z/R, τ = ω t)::

    ∂/∂θ (P H³ ∂P/∂θ) + ∂/∂Z (P H³ ∂P/∂Z) = Λ ∂(PH)/∂θ + 2Λ ∂(PH)/∂τ

written in conservative (flux) form with P H³ ∂P/∂θ = ½ H³ ∂(P²)/∂θ.  On the cell around
node (i, j)::

    R_ij = (F_{i+½} − F_{i−½})/Δθ + (G_{j+½} − G_{j−½})/ΔZ − 2Λ ∂(PH)/∂τ

    F_{i+½} = ½ (H_i³ + H_{i+1}³) (P_{i+1}² − P_i²)/(2Δθ) − Λ (P_i H_i + P_{i+1} H_{i+1})/2
    G_{j+½} = ½ (H_j³ + H_{j+1}³) (P_{j+1}² − P_j²)/(2ΔZ)

Second-order accurate; the fluxes telescope, so the discrete scheme conserves mass and keeps
the Elrod–Burgdorfer invariant Σ_i H_i³ (P_ij² − 1) = 0 of a rigid aligned bearing to
round-off (tests/test_verification.py).

Node numbering: θ-nodes i = 0..m−1 (m = n_theta for a periodic film, n_theta + 1 with a
seam, whose end nodes carry P = 1), axial nodes j = 0..n_z (P = 1 at both ends).  A node's
flat index is k = i (n_z + 1) + j.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import casadi as ca
import numpy as np

from .inputs.grid import Grid
from .physics.algebra import cos, is_symbolic, sin, weighted_sum


@dataclass(frozen=True)
class Stencil:
    """Index arrays and geometry of a θ × Z grid (all angles in rad, lengths / R).

    Attributes
    ----------
    n_theta_nodes : m, number of θ nodes
    n_z_nodes : n_z + 1
    psi : θ-node angles from the grid origin (the seam, or the reference line) [rad]
    dpsi : Δθ [rad]
    unknown : flat indices of the nodes whose pressure is unknown (interior nodes)
    row : θ index i of each unknown node;  east/west/north/south: flat indices of neighbours
    east_row/west_row : θ index of the east/west neighbours
    theta_weight : trapezoid weight of each θ node for ∫ dθ [rad]
    z_weight_unit : trapezoid weights of the axial nodes for ∫ dZ, per unit ΔZ [-]
    periodic : True for a periodic film
    fixed_rows : θ rows held at ambient pressure besides the seam rows (the leading ends of
        further pads and the gaps between pads, :meth:`gfbopt.inputs.bore.AsBuilt.fixed_rows`)
    """

    grid: Grid
    periodic: bool
    n_theta_nodes: int
    n_z_nodes: int
    psi: np.ndarray
    dpsi: float
    unknown: np.ndarray
    row: np.ndarray
    east: np.ndarray
    west: np.ndarray
    north: np.ndarray
    south: np.ndarray
    east_row: np.ndarray
    west_row: np.ndarray
    theta_weight: np.ndarray
    z_weight_unit: np.ndarray
    fixed_rows: tuple = ()

    @property
    def ambient_rows(self) -> np.ndarray:
        """Boolean mask of the θ rows at ambient pressure (seam rows and ``fixed_rows``)."""
        mask = np.zeros(self.n_theta_nodes, dtype=bool)
        if not self.periodic:
            mask[[0, -1]] = True
        mask[list(self.fixed_rows)] = True
        return mask

    @property
    def n_nodes(self) -> int:
        return self.n_theta_nodes * self.n_z_nodes

    @property
    def n_unknown(self) -> int:
        return int(self.unknown.size)

    def axial_spacing(self, length_ratio):
        """ΔZ = 2 (L/D) / n_z [-] (works on numbers and symbols)."""
        return 2.0 * length_ratio / self.grid.n_z

    def z_nodes(self, length_ratio: float) -> np.ndarray:
        """Axial node positions Z_j ∈ [−L/D, L/D] [-]."""
        return np.linspace(-length_ratio, length_ratio, self.n_z_nodes)


def trapezoid_weights(n_nodes: int) -> np.ndarray:
    """Trapezoid-rule weights per unit spacing on ``n_nodes`` equally spaced nodes [-]."""
    w = np.ones(n_nodes)
    w[[0, -1]] = 0.5
    return w


def make_stencil(grid: Grid, periodic: bool, fixed_rows: tuple = ()) -> Stencil:
    """Index arrays of the five-point stencil on ``grid`` for a periodic or seamed film;
    ``fixed_rows`` (θ row indices) are held at ambient pressure too (several pads)."""
    n_theta, n_z = grid.n_theta, grid.n_z
    m = n_theta if periodic else n_theta + 1
    nzn = n_z + 1
    dpsi = 2.0 * math.pi / n_theta
    psi = dpsi * np.arange(m)
    i_all, j_all = np.meshgrid(np.arange(m), np.arange(nzn), indexing="ij")
    interior = (j_all > 0) & (j_all < n_z)
    if not periodic:
        interior &= (i_all > 0) & (i_all < n_theta)
    fixed_rows = tuple(sorted(int(i) for i in fixed_rows))
    if fixed_rows and (periodic or fixed_rows[0] <= 0 or fixed_rows[-1] >= n_theta):
        raise ValueError("fixed rows need a seam film and lie strictly inside the grid")
    interior &= ~np.isin(i_all, fixed_rows)
    i_u = i_all[interior]
    j_u = j_all[interior]
    east_row = (i_u + 1) % m
    west_row = (i_u - 1) % m
    unknown = i_u * nzn + j_u
    theta_weight = dpsi * (np.ones(m) if periodic else trapezoid_weights(m))
    z_weight = trapezoid_weights(nzn)
    return Stencil(grid=grid, periodic=periodic, n_theta_nodes=m, n_z_nodes=nzn, psi=psi,
                   dpsi=dpsi, unknown=unknown, row=i_u,
                   east=east_row * nzn + j_u, west=west_row * nzn + j_u,
                   north=unknown + 1, south=unknown - 1,
                   east_row=east_row, west_row=west_row,
                   theta_weight=theta_weight, z_weight_unit=z_weight, fixed_rows=fixed_rows)


def reynolds_residual(p, h, st: Stencil, bearing_number, dz, d_ph_dt=None):
    """Discrete Reynolds residual R at the unknown nodes (module docstring).

    Parameters
    ----------
    p : pressure P at every node, flat (length st.n_nodes) [-]
    h : film thickness H at every node, flat (length st.n_nodes) [-]
    st : the grid's :class:`Stencil`
    bearing_number : Λ [-]
    dz : axial spacing ΔZ [-]
    d_ph_dt : ∂(PH)/∂τ at the unknown nodes, or None for the steady equation [-]

    Returns the residual at the unknown nodes, in the order of ``st.unknown`` [-].
    Face values of H³ are the means of the two nodes' H³.
    """
    pc, pe, pw, pn, ps = (p[st.unknown], p[st.east], p[st.west], p[st.north], p[st.south])
    hc, he, hw, hn, hs = (h[st.unknown], h[st.east], h[st.west], h[st.north], h[st.south])
    hc3 = hc**3
    dth = st.dpsi
    pc2 = pc * pc
    ph = pc * hc
    flux_e = 0.25 * (hc3 + he**3) * (pe * pe - pc2) / dth - 0.5 * bearing_number * (ph + pe * he)
    flux_w = 0.25 * (hc3 + hw**3) * (pc2 - pw * pw) / dth - 0.5 * bearing_number * (ph + pw * hw)
    flux_n = 0.25 * (hc3 + hn**3) * (pn * pn - pc2) / dz
    flux_s = 0.25 * (hc3 + hs**3) * (pc2 - ps * ps) / dz
    res = (flux_e - flux_w) / dth + (flux_n - flux_s) / dz
    if d_ph_dt is not None:
        res = res - 2 * bearing_number * d_ph_dt
    return res


def axial_integral(p, st: Stencil, dz):
    """Q_i = ∫ (P − 1) dZ at each θ node by the trapezoid rule [-].

    p : pressure at every node, flat (length st.n_nodes), numbers or CasADi symbols [-];
    dz : axial spacing ΔZ [-].  Returns a vector of length st.n_theta_nodes.
    """
    w = st.z_weight_unit
    if is_symbolic(p, dz):
        pm = ca.reshape(p - 1, st.n_z_nodes, st.n_theta_nodes)  # column i = θ node i
        return ca.mtimes(pm.T, ca.DM(w)) * dz
    return (np.reshape(p, (st.n_theta_nodes, st.n_z_nodes)) - 1.0) @ w * dz


def film_forces(q, theta, weights):
    """Film force on the journal F = −∬ (P − 1)(cos θ, sin θ) dθ dZ, per p_a R² [-].

    q : axial integral Q_i = ∫(P − 1) dZ at each θ node [-];  theta : node angles measured
    from the load line in the direction of rotation [rad];  weights : quadrature weights of
    the θ nodes (``Stencil.theta_weight``) [rad].  Returns (F_X, F_Y) with X along the load.
    """
    return (-weighted_sum(weights, cos(theta) * q), -weighted_sum(weights, sin(theta) * q))


def shear_torque(p: np.ndarray, h: np.ndarray, st: Stencil, bearing_number: float,
                 length_ratio: float) -> tuple[float, float]:
    """Drag torque on the journal over Petroff's, (Couette part, pressure-gradient part) [-].

    T / (2π μ ω R³ L / c) = (1/(4π L/D)) [∬ dθ dZ / H + (3/Λ) ∬ H ∂P/∂θ dθ dZ]
    (docs/PHYSICS.md §5b).  p, h : P and H at every node (flat) [-].  The Couette integral is
    the trapezoid rule on the nodes (seam rows half weight; on a periodic film this is the
    periodic trapezoid rule, geometrically convergent for a smooth film); the pressure part
    is the midpoint rule on the θ faces of the stencil, H at a face the mean of its nodes
    (second order), with the trapezoid rule along Z.
    """
    m, nzn = st.n_theta_nodes, st.n_z_nodes
    pm, hm = np.reshape(p, (m, nzn)), np.reshape(h, (m, nzn))
    zw = st.z_weight_unit * st.axial_spacing(length_ratio)
    couette = float(st.theta_weight @ (1.0 / hm) @ zw)
    if st.periodic:
        dp, hf = np.roll(pm, -1, axis=0) - pm, 0.5 * (hm + np.roll(hm, -1, axis=0))
    else:
        dp, hf = pm[1:] - pm[:-1], 0.5 * (hm[1:] + hm[:-1])
    gradient = float(np.sum((hf * dp) @ zw))
    scale = 1.0 / (4.0 * math.pi * length_ratio)
    return scale * couette, scale * 3.0 * gradient / bearing_number
