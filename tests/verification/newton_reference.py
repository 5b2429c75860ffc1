"""Independent reference: sparse Newton for the rigid, periodic gas bearing at a given ε.

This is a hand-written check on gfbopt's CasADi/IPOPT equilibrium (:mod:`gfbopt.static`) for
the case ``BearingModel(foil='rigid', film='periodic')`` with the eccentricity ratio given.
It shares only the stencil *definition* with gfbopt (the residual function and the index
arrays of :mod:`gfbopt.discretisation`); the Jacobian, the Newton iteration and the force
post-processing are written here from scratch.

Discrete problem
----------------
gfbopt's frame puts the load along X, the journal centre at ε (cos φ, sin φ), the film
H = 1 − ε cos(θ − φ), and, for a periodic film, the grid origin on the maximum-film line,
θ_i = π + φ + ψ_i with ψ_i = 2π i / n_θ.  On the grid the film is therefore

    H_i = 1 + ε cos ψ_i                                   (independent of φ)

so the Reynolds residual R(P) does not depend on the attitude angle: the Jacobian of the
(P, φ) system is block-triangular, ∂R/∂φ = 0.  Newton is applied to R(P) = 0 at the interior
nodes; φ then follows in closed form from the force balance F_Y = 0.  With the ψ-frame force
components (per p_a R², Q_i = ∫ (P − 1) dZ by the trapezoid rule)

    F_r = −Σ_i w_i cos ψ_i Q_i ,    F_t = −Σ_i w_i sin ψ_i Q_i ,

the rotation by θ_s = π + φ into the load frame gives F_X = −(F_r cos φ − F_t sin φ) and
F_Y = −(F_r sin φ + F_t cos φ).  F_Y = 0 with a positive load −F_X > 0 fixes

    φ = atan2(−F_t, F_r),     W̄ = −F_X = |F| = hypot(F_r, F_t).

Run as a script to print a comparison with gfbopt and a Jacobian check::

    PYTHONPATH=. python benchmarks/newton_reference.py
"""
from __future__ import annotations

import math
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from gfbopt import discretisation as disc
from gfbopt.inputs import BearingModel, Grid
from gfbopt.physics.closed_forms import first_order_pressure


def film_thickness(stencil: disc.Stencil, eccentricity: float) -> np.ndarray:
    """Rigid film H = 1 + ε cos ψ at every node, flat (length ``stencil.n_nodes``) [-].

    ψ [rad] is measured from the maximum-film line (the grid origin of a periodic film).
    """
    h_rows = 1.0 + eccentricity * np.cos(stencil.psi)
    return np.repeat(h_rows, stencil.n_z_nodes)


def full_pressure(p_unknown: np.ndarray, stencil: disc.Stencil) -> np.ndarray:
    """Pressure at every node [-]: ``p_unknown`` at the interior nodes, P = 1 elsewhere."""
    p = np.ones(stencil.n_nodes)
    p[stencil.unknown] = p_unknown
    return p


def residual(p_unknown: np.ndarray, h: np.ndarray, stencil: disc.Stencil,
             bearing_number: float, dz: float) -> np.ndarray:
    """Steady Reynolds residual at the interior nodes (gfbopt's stencil) [-].

    Parameters
    ----------
    p_unknown : P at the interior nodes, in the order of ``stencil.unknown`` [-]
    h : film thickness H at every node, flat [-]
    stencil : the grid's :class:`gfbopt.discretisation.Stencil`
    bearing_number : Λ [-]
    dz : axial spacing ΔZ [-]
    """
    return disc.reynolds_residual(full_pressure(p_unknown, stencil), h, stencil,
                                  bearing_number, dz)


def jacobian(p_unknown: np.ndarray, h: np.ndarray, stencil: disc.Stencil,
             bearing_number: float, dz: float) -> sp.csc_matrix:
    """Analytic Jacobian ∂R/∂P of :func:`residual` at the interior nodes (sparse CSC) [-].

    Differentiating the fluxes of :func:`gfbopt.discretisation.reynolds_residual`
    (a = face H³ sums, Δθ, ΔZ the spacings; subscripts c, e, w, n, s the node and its
    neighbours)::

        ∂R/∂P_c = −½ P_c [(2H_c³ + H_e³ + H_w³)/Δθ² + (2H_c³ + H_n³ + H_s³)/ΔZ²]
        ∂R/∂P_e = ½ (H_c³ + H_e³) P_e/Δθ² − ½ Λ H_e/Δθ
        ∂R/∂P_w = ½ (H_c³ + H_w³) P_w/Δθ² + ½ Λ H_w/Δθ
        ∂R/∂P_n = ½ (H_c³ + H_n³) P_n/ΔZ²
        ∂R/∂P_s = ½ (H_c³ + H_s³) P_s/ΔZ²

    (the Λ terms of ∂R/∂P_c cancel).  Columns of neighbours on the boundary (P = 1 fixed)
    are dropped.  Entries that land on the same (row, column) pair are summed.
    """
    st = stencil
    p = full_pressure(p_unknown, st)
    dth = st.dpsi
    lam = bearing_number
    hc, he, hw, hn, hs = (h[st.unknown], h[st.east], h[st.west], h[st.north], h[st.south])
    pc, pe, pw, pn, ps = (p[st.unknown], p[st.east], p[st.west], p[st.north], p[st.south])
    hc3 = hc**3
    a_e, a_w, a_n, a_s = hc3 + he**3, hc3 + hw**3, hc3 + hn**3, hc3 + hs**3

    d_c = -0.5 * pc * ((a_e + a_w) / dth**2 + (a_n + a_s) / dz**2)
    d_e = 0.5 * a_e * pe / dth**2 - 0.5 * lam * he / dth
    d_w = 0.5 * a_w * pw / dth**2 + 0.5 * lam * hw / dth
    d_n = 0.5 * a_n * pn / dz**2
    d_s = 0.5 * a_s * ps / dz**2

    # position of each node in the unknown vector, −1 for boundary nodes
    position = np.full(st.n_nodes, -1)
    position[st.unknown] = np.arange(st.n_unknown)
    rows = np.arange(st.n_unknown)
    all_rows, all_cols, all_vals = [rows], [rows], [d_c]
    for neighbour, value in ((st.east, d_e), (st.west, d_w), (st.north, d_n), (st.south, d_s)):
        col = position[neighbour]
        keep = col >= 0
        all_rows.append(rows[keep])
        all_cols.append(col[keep])
        all_vals.append(value[keep])
    n = st.n_unknown
    jac = sp.coo_matrix((np.concatenate(all_vals),
                         (np.concatenate(all_rows), np.concatenate(all_cols))), shape=(n, n))
    return jac.tocsc()   # duplicates summed


def finite_difference_jacobian(p_unknown: np.ndarray, h: np.ndarray, stencil: disc.Stencil,
                               bearing_number: float, dz: float,
                               step: float = 1e-6) -> np.ndarray:
    """Dense central-difference Jacobian of :func:`residual` (for checks on small grids) [-].

    ``step`` is the perturbation of P [-].  The residual is quadratic in P, so central
    differences are exact up to round-off.
    """
    n = p_unknown.size
    jac = np.empty((n, n))
    for k in range(n):          # one column per unknown: a check, not a production path
        dp = np.zeros(n)
        dp[k] = step
        jac[:, k] = (residual(p_unknown + dp, h, stencil, bearing_number, dz)
                     - residual(p_unknown - dp, h, stencil, bearing_number, dz)) / (2 * step)
    return jac


def jacobian_check(bearing_number: float = 1.0, eccentricity: float = 0.5,
                   length_ratio: float = 1.0, grid: Grid = Grid(24, 8),
                   seed: int = 0) -> float:
    """max |J_analytic − J_fd| / max |J_fd| at a randomly perturbed pressure field [-].

    The pressure is the first-order (Ausman) field plus uniform noise of ±0.1, so that no
    symmetry of the smooth solution can hide a wrong entry.
    """
    st = disc.make_stencil(grid, periodic=True)
    dz = st.axial_spacing(length_ratio)
    h = film_thickness(st, eccentricity)
    p0 = _initial_pressure(st, bearing_number, eccentricity, length_ratio)
    p0 = p0 + 0.1 * np.random.default_rng(seed).uniform(-1.0, 1.0, p0.size)
    j_an = jacobian(p0, h, st, bearing_number, dz).toarray()
    j_fd = finite_difference_jacobian(p0, h, st, bearing_number, dz)
    return float(np.abs(j_an - j_fd).max() / np.abs(j_fd).max())


def _initial_pressure(st: disc.Stencil, bearing_number: float, eccentricity: float,
                      length_ratio: float) -> np.ndarray:
    """Ausman's first-order pressure at the interior nodes (gfbopt.static) [-]."""
    model = BearingModel(bearing_number=bearing_number, foil="rigid",
                         length_ratio=length_ratio)
    p = first_order_pressure(model, st.z_nodes(length_ratio), st.psi, eccentricity)
    return np.maximum(p.ravel()[st.unknown], 0.05)


def forces(p_unknown: np.ndarray, stencil: disc.Stencil, dz: float) -> tuple[float, float]:
    """ψ-frame force components (F_r, F_t) = −Σ w (cos ψ, sin ψ) Q, per p_a R² [-]."""
    q = (full_pressure(p_unknown, stencil).reshape(stencil.n_theta_nodes, stencil.n_z_nodes)
         - 1.0) @ stencil.z_weight_unit * dz
    w = stencil.theta_weight
    return (-float(np.sum(w * np.cos(stencil.psi) * q)),
            -float(np.sum(w * np.sin(stencil.psi) * q)))


def solve_rigid_newton(bearing_number: float, eccentricity: float, length_ratio: float = 1.0,
                       grid: Grid = Grid(72, 20), tol: float = 1e-11,
                       max_iter: int = 50) -> dict:
    """Static equilibrium of the rigid periodic gas bearing at a given ε, by sparse Newton.

    Parameters
    ----------
    bearing_number : Λ = 6 μ ω R²/(p_a c²) [-]
    eccentricity : ε = e/c, 0 < ε < 1 [-]
    length_ratio : L/D [-]
    grid : finite-difference grid (n_θ intervals, n_z axial intervals)
    tol : convergence tolerance on max |R| (R scales like P/ΔZ², so about 1e-13 relative
        for the default grid) [-]
    max_iter : maximum number of Newton iterations

    Returns
    -------
    dict with
        load : W̄ = W/(p_a R²) [-]
        attitude_angle_deg : φ, angle from the load line to the line of centres [deg]
        iterations : Newton iterations taken
        residual : max |R| at the solution [-]
        pressure : P, shape (n_θ, n_z + 1), rows from the maximum-film line [-]
        solve_time_s : wall time of the Newton solve including set-up [s]
        force_r, force_t : ψ-frame force components F_r, F_t [-]

    Newton steps J ΔP = −R are solved with SuperLU (``splu``); a backtracking line search
    halves the step until max |R| decreases (and P stays positive).
    """
    t0 = time.perf_counter()
    if not 0.0 < eccentricity < 1.0:
        raise ValueError(f"eccentricity must lie in (0, 1), got {eccentricity!r}")
    st = disc.make_stencil(grid, periodic=True)
    dz = st.axial_spacing(length_ratio)
    h = film_thickness(st, eccentricity)
    p = _initial_pressure(st, bearing_number, eccentricity, length_ratio)
    r = residual(p, h, st, bearing_number, dz)
    norm = np.abs(r).max()
    iterations = 0
    while norm > tol and iterations < max_iter:
        step = spla.splu(jacobian(p, h, st, bearing_number, dz)).solve(-r)
        alpha = 1.0
        while True:
            trial = p + alpha * step
            if trial.min() > 0:
                r_trial = residual(trial, h, st, bearing_number, dz)
                norm_trial = np.abs(r_trial).max()
                if norm_trial < norm or alpha < 1e-4:
                    break
            alpha *= 0.5
        p, r, norm = trial, r_trial, norm_trial
        iterations += 1
    f_r, f_t = forces(p, st, dz)
    return {
        "load": math.hypot(f_r, f_t),
        "attitude_angle_deg": math.degrees(math.atan2(-f_t, f_r)),
        "iterations": iterations,
        "residual": float(norm),
        "pressure": full_pressure(p, st).reshape(st.n_theta_nodes, st.n_z_nodes),
        "solve_time_s": time.perf_counter() - t0,
        "force_r": f_r,
        "force_t": f_t,
        "converged": bool(norm <= tol),
    }


def _compare(points=((0.6, 0.4), (3.0, 0.6)), grid: Grid = Grid(36, 10)) -> None:
    """Print Newton against gfbopt.solve_static at a few (Λ, ε), L/D = 1."""
    from gfbopt import solve_static

    print(f"Jacobian check (24x8): relative error {jacobian_check():.2e}")
    for lam, ecc in points:
        ref = solve_rigid_newton(lam, ecc, 1.0, grid)
        sol = solve_static(BearingModel(bearing_number=lam, foil="rigid", length_ratio=1.0),
                           eccentricity=ecc, grid=grid)
        print(f"Λ={lam} ε={ecc} grid {grid}: Newton W={ref['load']:.12f} "
              f"φ={ref['attitude_angle_deg']:.9f}° ({ref['iterations']} it, "
              f"|R|={ref['residual']:.1e}) | IPOPT W={sol.load:.12f} "
              f"φ={sol.attitude_angle_deg:.9f}° ({sol.iterations} it, "
              f"|R|={sol.residual:.1e}) | rel dW={abs(sol.load / ref['load'] - 1):.1e} "
              f"dφ={abs(sol.attitude_angle_deg - ref['attitude_angle_deg']):.1e}°")


if __name__ == "__main__":
    _compare()
