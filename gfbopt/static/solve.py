"""Solving for the static equilibrium: cold start, warm start and continuation.

A cold start uses Ausman's first-order pressure with every lifted variable made consistent
(:func:`consistent_state`); when IPOPT fails from it, the eccentricity or load is marched up
from a small value, warm-starting each step.  :func:`postprocess` re-evaluates the discrete
Reynolds residual, the foil equations and the film force on IPOPT's raw solution (the numpy
path of :mod:`gfbopt.discretisation`), so what a :class:`StaticSolution` reports is checked.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Optional

import numpy as np

from .. import discretisation as disc
from ..errors import ConvergenceError, ParameterError
from ..inputs.checks import _ABSENT, check_finite, check_positive
from ..inputs.grid import DEFAULT_GRID, Grid
from ..inputs.model import BearingModel, radian_keyword_migration
from ..physics.closed_forms import first_order_pressure, small_eccentricity_limit
from ..physics.bore import first_order_bore_pressure
from ..physics.film import force_gauge, rigid_film_polar
from ..threads import single_threaded
from . import newton
from .build import StaticSolver, fixed_origin, row_values, solver_for
from .solution import StaticSolution, foil_parameters

#: residual tolerance on the Reynolds and force equations accepted as converged [-]
RESIDUAL_TOLERANCE = 1e-7


def _cold_guess(solver: StaticSolver, model: BearingModel, eccentricity: float,
                attitude: Optional[float] = None) -> np.ndarray:
    """A starting point: Ausman's first-order pressure and every lifted variable consistent."""
    st = solver.stencil
    _, phi0 = small_eccentricity_limit(model)
    # The attitude angle falls roughly like (1 − ε²) as the film closes (cf. the short-bearing
    # law tan φ = π √(1 − ε²)/(4ε)); compliance delays the closing.
    closing = min(eccentricity / (1.0 + model.compliance), 0.95)
    phi0 = min(max(phi0 * (1.0 - closing**2), 0.05), 1.5) if attitude is None else attitude
    origin = fixed_origin(model)
    seam = math.pi + phi0 if origin is None else origin
    theta = seam + st.psi
    shrink = 1.0 / (1.0 + model.compliance)       # a compliant film carries less pressure
    z = st.z_nodes(model.length_ratio)
    p = first_order_pressure(model, z, theta - phi0 - math.pi,
                             min(eccentricity, 0.8) * shrink).ravel()
    bore = row_values(model, st, origin)[0]
    if bore.any():          # a preloaded bore raises pressure of its own (physics/bore.py)
        p = p + shrink * first_order_bore_pressure(bore, z, model.bearing_number,
                                                   model.length_ratio, st.periodic).ravel()
    p_full = np.ones(st.n_nodes)
    p_full[st.unknown] = np.maximum(p[st.unknown], 0.05)
    return consistent_state(solver, model, p_full, eccentricity, phi0)


def consistent_state(solver: StaticSolver, model: BearingModel, p_full: np.ndarray,
                     eccentricity: float, attitude: float) -> np.ndarray:
    """The solver vector x for a pressure field, ε and φ [rad], with every lifted variable
    (film, axial integrals, beam dofs, force partial sums) computed to match."""
    st, lay = solver.stencil, solver.layout
    origin = fixed_origin(model)
    seam = math.pi + attitude if origin is None else origin
    theta = seam + st.psi
    dz = st.axial_spacing(model.length_ratio)
    q = disc.axial_integral(p_full, st, dz)
    qf = disc.axial_integral(1 + force_gauge(p_full - 1, model.subambient == "gumbel"), st, dz)
    mean_gauge = q / (2 * model.length_ratio)
    x = np.zeros(lay.size)
    x[lay.pressure] = p_full[st.unknown]
    bore, s_rows = row_values(model, st, origin)
    h_rigid = rigid_film_polar(eccentricity, attitude, theta) + bore
    x[lay.film], x[lay.beam] = solver.law.start(h_rigid, mean_gauge,
                                                foil_parameters(model, s_rows), st,
                                                solver.law_data)
    x[lay.axial] = q
    x[lay.force] = qf
    parts = [disc.film_forces(qf[b], st.psi[b], st.theta_weight[b])
             for b in solver.force_blocks]
    nb = len(parts)
    sums = x[lay.partial_sums]
    sums[:nb] = [f[0] for f in parts]
    sums[nb:] = [f[1] for f in parts]
    x[lay.partial_sums] = sums
    x[lay.eccentricity] = eccentricity
    x[lay.attitude] = attitude
    return x


def _check_target(model: BearingModel, eccentricity, load):
    if (eccentricity is None) == (load is None):
        raise ParameterError("eccentricity/load", (eccentricity, load),
                             "give exactly one of eccentricity or load")
    if eccentricity is not None:
        e = check_finite("eccentricity", eccentricity)
        if e < 0:
            raise ParameterError("eccentricity", eccentricity, "must be >= 0")
        if model.is_rigid and e >= 1.0:
            raise ParameterError("eccentricity", eccentricity,
                                 "must be < 1 for a rigid bearing (the journal would touch)")
        if e > 5.0:
            raise ParameterError("eccentricity", eccentricity, "must be <= 5")
        return False, e
    return True, check_positive("load", load)


def postprocess(solver: StaticSolver, model: BearingModel, x: np.ndarray, stats: dict,
                load_mode: bool, target: float, elapsed: float,
                position_mode: bool = False) -> StaticSolution:
    """Recompute everything from the raw solution with numpy: residual, forces, profiles."""
    st, lay = solver.stencil, solver.layout
    ecc = float(x[lay.eccentricity])
    phi = float(x[lay.attitude])
    origin = fixed_origin(model)
    seam = (math.pi + phi) if origin is None else float(origin)
    theta = seam + st.psi
    bore, s_rows = row_values(model, st, origin)
    p = np.ones(st.n_nodes)
    p[st.unknown] = x[lay.pressure]
    dz = st.axial_spacing(model.length_ratio)
    q = disc.axial_integral(p, st, dz)
    mean_gauge = q / (2 * model.length_ratio)
    h_rigid = rigid_film_polar(ecc, phi, theta) + bore
    nzn = st.n_z_nodes
    w_nodes, foil_res = solver.law.deflection(p, mean_gauge, x[lay.beam],
                                              foil_parameters(model, s_rows), st,
                                              solver.law_data)
    h = np.repeat(h_rigid, nzn) + w_nodes
    reynolds = disc.reynolds_residual(p, h, st, model.bearing_number, dz)
    force_p = 1 + force_gauge(p - 1, model.subambient == "gumbel")
    fx, fy = disc.film_forces(disc.axial_integral(force_p, st, dz), theta,
                              st.theta_weight)
    if position_mode:
        force_res = 0.0
    elif load_mode:
        force_res = math.hypot(fx + target, fy)
    else:
        force_res = abs(fy)
    residual = max(float(np.abs(reynolds).max()) if reynolds.size else 0.0, foil_res)
    status = str(stats.get("return_status", "unknown"))
    hmat = h.reshape(st.n_theta_nodes, nzn)
    ok = bool(bool(stats.get("success", False)) and residual < RESIDUAL_TOLERANCE
          and force_res < RESIDUAL_TOLERANCE * max(1.0, abs(target)) and hmat.min() > 0
          and p.min() > 0)
    hmin, angle = _minimum_film(hmat, theta, st.periodic)
    couette, gradient = disc.shear_torque(p, h, st, model.bearing_number, model.length_ratio)
    message = "" if ok else (f"IPOPT status {status}; Reynolds residual {residual:.2e}; "
                             f"force residual {force_res:.2e}; min H {hmat.min():.3g}")
    return StaticSolution(
        model=model, grid=solver.grid, eccentricity=ecc, attitude_angle_rad=phi,
        load=-float(fx), force=(float(fx), float(fy)), min_film=hmin, min_film_angle_rad=angle,
        seam_angle_rad=seam,
        theta=theta, z=st.z_nodes(model.length_ratio),
        pressure=p.reshape(st.n_theta_nodes, nzn), film=hmat,
        deflection=w_nodes.reshape(st.n_theta_nodes, nzn), success=ok, status=status,
        iterations=int(stats.get("iter_count", -1)), residual=residual,
        force_residual=float(force_res), solve_time_s=elapsed, state=x, message=message,
        couette_torque_ratio=couette, pressure_torque_ratio=gradient)


def _minimum_film(hmat: np.ndarray, theta: np.ndarray, periodic: bool) -> tuple[float, float]:
    """Minimum film and its angle, refined by a parabola through the three nearest nodes."""
    hrow = hmat.min(axis=1)
    k = int(np.argmin(hrow))
    n = hrow.size
    if periodic or 0 < k < n - 1:
        a, b, c = hrow[(k - 1) % n], hrow[k], hrow[(k + 1) % n]
        denom = a - 2 * b + c
        if denom > 0:
            shift = 0.5 * (a - c) / denom
            dth = theta[1] - theta[0]
            return float(b - 0.25 * (a - c) * shift), float(theta[k] + shift * dth)
    return float(hrow[k]), float(theta[k])


@single_threaded
def solve_static(model: BearingModel, *, eccentricity: Optional[float] = None,
                 load: Optional[float] = None, attitude_angle_deg: Optional[float] = None,
                 grid: Grid = DEFAULT_GRID,
                 solver: Optional[StaticSolver] = None,
                 initial: Optional[StaticSolution] = None,
                 continuation: bool = True, raise_on_failure: bool = False,
                 fast_path: bool = False, attitude_angle=_ABSENT) -> StaticSolution:
    """Static equilibrium at a given eccentricity ratio or a given load.

    Parameters
    ----------
    model : the non-dimensional bearing
    eccentricity : ε = e/c [-] (then the load and attitude angle are found), or
    load : W̄ = W/(p_a R²) [-] (then ε and the attitude angle are found)
    attitude_angle_deg : with ``eccentricity``, fixes the journal position too [deg], from
        the load line in the direction of rotation: the film force at that position is
        returned (``load`` = −F_X, ``force``) without equilibrium.  (The old radian keyword
        ``attitude_angle`` is refused with the conversion.)
    grid : finite-difference grid (ignored when ``solver`` is given)
    solver : a prebuilt :class:`StaticSolver` (reuse it across a sweep)
    initial : a previous solution to warm-start from (same solver)
    continuation : on failure from a cold start, step the eccentricity/load up from a small
        value, warm-starting each step
    raise_on_failure : raise :class:`ConvergenceError` instead of returning success=False
    fast_path : with ``initial``, try Newton's method on the same equations first
        (:mod:`gfbopt.static.newton`, for warm-started solves inside searches); IPOPT solves
        whenever it does not converge in a few steps.  ``solver`` on the result says which.

    Returns
    -------
    StaticSolution, with ``success``, IPOPT's ``status`` and the ``residual`` recomputed.
    """
    if attitude_angle is not _ABSENT:
        raise ParameterError("attitude_angle", attitude_angle, radian_keyword_migration(
            "attitude_angle", attitude_angle))
    load_mode, target = _check_target(model, eccentricity, load)
    attitude_angle = None                       # the solver's unit: radians
    if attitude_angle_deg is not None:
        if load_mode:
            raise ParameterError("attitude_angle_deg", attitude_angle_deg,
                                 "fixes the position together with eccentricity, not with load")
        attitude_angle = math.radians(check_finite("attitude_angle_deg", attitude_angle_deg))
    if solver is None:
        solver = solver_for(model, grid)
    elif not solver.matches(model, solver.grid):
        raise ParameterError("solver", f"{solver.film} film, {solver.law.name} structure",
                             f"was built for another formulation than film={model.film}, "
                             f"foil={model.foil}, deflection_law={model.deflection_law}")
    t0 = time.perf_counter()
    round_bore = model.as_built is None or model.as_built.bore.is_round
    if not load_mode and target == 0.0 and round_bore:
        sol = _concentric(solver, model, t0)
    elif not load_mode and target == 0.0:
        # a preloaded bore carries pressure with the journal concentric; φ is undefined
        # there, so the film force is found at the position (0, 0)
        sol = _solve_with_continuation(solver, model, False, 0.0, initial, False, t0, 0.0)
    else:
        sol = (_fast_path(solver, model, load_mode, target, initial, t0, attitude_angle)
               if fast_path and initial is not None else None)
        if sol is None:
            sol = _solve_with_continuation(solver, model, load_mode, target, initial,
                                           continuation, t0, attitude_angle)
    if raise_on_failure and not sol.success:
        raise ConvergenceError("static equilibrium did not converge", sol.status,
                               max(sol.residual, sol.force_residual))
    return sol


def _fast_path(solver, model, load_mode, target, initial, t0, attitude=None):
    """The Newton fast path from ``initial`` (None when it does not converge)."""
    if initial.state.size != solver.layout.size:
        return None
    p = solver.parameters(model, load_mode, target, attitude)
    outcome = newton.warm_solve(solver, initial.state, p)
    if not outcome.converged:
        return None
    sol = postprocess(solver, model, outcome.x, outcome.stats(), load_mode, target,
                      time.perf_counter() - t0, attitude is not None)
    return replace(sol, solver="newton") if sol.success else None


def _concentric(solver: StaticSolver, model: BearingModel, t0: float) -> StaticSolution:
    """ε = 0: P ≡ 1, W ≡ 0 solves the discrete equations exactly (checked, not assumed)."""
    x = _cold_guess(solver, model, 0.0)
    sol = postprocess(solver, model, x, {"success": True, "return_status": "Concentric",
                                          "iter_count": 0}, False, 0.0,
                       time.perf_counter() - t0)
    return replace(sol, attitude_angle_rad=float("nan"))


def _solve_with_continuation(solver, model, load_mode, target, initial, continuation, t0,
                             attitude=None):
    p = solver.parameters(model, load_mode, target, attitude)
    if initial is not None and initial.state.size == solver.layout.size:
        x0 = initial.state
    else:
        x0 = _cold_guess(solver, model, target if not load_mode else
                         min(0.5, target / max(small_eccentricity_limit(model)[0], 1e-9)),
                         attitude)
    x, stats = solver.run(x0, p)
    sol = postprocess(solver, model, x, stats, load_mode, target, time.perf_counter() - t0,
                       attitude is not None)
    if sol.success or not continuation:
        return sol
    # Continuation: march the target up from a small value, warm-starting each step.
    iterations = sol.iterations
    start = 0.1 * target
    x_prev = _cold_guess(solver, model, start if not load_mode else
                         min(0.5, start / max(small_eccentricity_limit(model)[0], 1e-9)),
                         attitude)
    value, step = start, (target - start) / 4
    last = None
    while True:
        x, stats = solver.run(x_prev, solver.parameters(model, load_mode, value, attitude))
        iterations += int(stats.get("iter_count", 0))
        trial = postprocess(solver, model, x, stats, load_mode, value, 0.0,
                             attitude is not None)
        if trial.success:
            x_prev, last = x, value
            if value >= target:
                break
            value = min(target, value + step)
        else:
            if last is None:
                value *= 0.5
                if value < 1e-3 * target:
                    break
                continue
            step *= 0.5
            if step < 1e-3 * target:
                break
            value = min(target, last + step)
    final = postprocess(solver, model, x if last == target else x_prev, stats, load_mode,
                         target, time.perf_counter() - t0, attitude is not None)
    final = replace(final, iterations=iterations)
    if last != target:
        final = replace(final, success=False,
                         message=f"continuation stopped at {last!r} of {target!r}; "
                                 + final.message)
    return final
