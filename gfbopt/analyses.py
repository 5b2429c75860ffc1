"""Analyses: one operating point in, one flat table row out.

These are the compositions that the studies, the command line and design-of-experiments
sweeps share.  Each function takes a :class:`~gfbopt.inputs.BearingModel` and an operating
point (``eccentricity`` or ``load``) and returns a dict whose keys are the column names of
:mod:`gfbopt.glossary`: the inputs (Λ, S, L/D, C and the operating point), the outputs and
the diagnostics ``success``, ``message``, ``iterations`` (static solve) and ``wall_time_s``.

A solve that does not converge is a row with ``success = False``, NaN outputs and the
solver's message — never an exception.  Bad input (a ParameterError) is still raised: it is
a mistake of the caller, found before anything is solved.

Every function takes ``grid`` and ``cache``: pass a :class:`~gfbopt.static.SolverCache`
to reuse solver builds across points (a build takes ≈ 0.6 s on 72 × 20); without one a
solver is built for the call.  The functions are module level and take plain, picklable
arguments, so :func:`gfbopt.parallel.run_points` can run them on worker processes.
"""
from __future__ import annotations

import math
import time
from typing import Optional, Sequence

import numpy as np

from .errors import ParameterError
from .inputs import DEFAULT_GRID, BearingGeometry, BearingModel, Grid
from .inputs.conversions import mass_from_parameter, rpm_to_rad_per_s
from .static import SolverCache, StaticSolution, solve_static, solver_for

def bearing_model(bearing: BearingGeometry, speed_rpm: float, *, film: Optional[str] = None,
                  seam_angle_deg=None, foil: Optional[str] = None,
                  deflection_law: Optional[str] = None, loss_factor: Optional[float] = None,
                  options=None, **extra) -> BearingModel:
    """The non-dimensional model of a bearing in SI at ``speed_rpm`` [rpm], its formulation
    resolved as every route resolves it: the options stated here, else ``options``
    (:class:`~gfbopt.inputs.options.ModelOptions`), else the bearing's own
    (``bearing.options``: its file's ``[model]`` table), else the defaults
    (:func:`~gfbopt.inputs.options.merge_options`) — as ``gfbopt static/linear --bearing
    FILE`` and the ``load_sweep`` / ``linear_coefficients`` studies do.  seam_angle_deg [deg]
    in [0, 360) or 'max_film'; ``extra``: the keys a bearing file does not state
    (``subambient``, ``compression_only``).

    Example: ``solve_static(bearing_model(load_bearing(FILE), 30000),
    load=bearing.nondimensional_load(20.0))``.
    """
    from .inputs.options import ModelOptions, merge_options

    if options is not None and not isinstance(options, ModelOptions):
        raise ParameterError("options", options, "must be ModelOptions")
    stated = ModelOptions(film=film, seam_angle_deg=seam_angle_deg, foil=foil,
                          deflection_law=deflection_law, loss_factor=loss_factor)
    resolved = merge_options(stated, bearing.options if options is None else options)
    return bearing.model(speed_rpm, **resolved.model_kwargs(), **extra)


#: outputs of a static solve (NaN when it failed)
STATIC_OUTPUTS = ("eccentricity", "attitude_angle_deg", "load", "min_film", "torque_ratio")


def _solver(model: BearingModel, grid: Optional[Grid], cache: Optional[SolverCache]):
    grid = grid or DEFAULT_GRID
    return cache(model, grid) if cache is not None else solver_for(model, grid)


def equilibrium(model: BearingModel, *, eccentricity: Optional[float] = None,
                load: Optional[float] = None, grid: Optional[Grid] = None,
                cache: Optional[SolverCache] = None,
                initial: Optional[StaticSolution] = None) -> StaticSolution:
    """The static equilibrium at ``eccentricity`` ε [-] or ``load`` W̄ [-] on ``grid``, with
    the cached solver for the model's formulation (a warm start from ``initial``)."""
    return solve_static(model, eccentricity=eccentricity, load=load, initial=initial,
                        solver=_solver(model, grid, cache))


def static_row(model: BearingModel, solution: StaticSolution,
               geometry: Optional[BearingGeometry] = None) -> dict:
    """The flat row of a static solution: Λ, S, L/D, C; ε, φ [deg], W̄, H_min, the torque
    ratio T/T₀; with a ``geometry`` also W [N], h_min [µm], the drag torque [N m] and the
    power loss [W]; diagnostics ``success``, ``message``, ``status``, ``iterations``,
    ``residual``.  Outputs are NaN when the solve failed."""
    from .physics.torque import drag_torque_and_power

    ok = bool(solution.success)
    nan = math.nan
    row = {**model.groups(),
           "eccentricity": solution.eccentricity if ok else nan,
           "attitude_angle_deg": solution.attitude_angle_deg if ok else nan,
           "load": solution.load if ok else nan,
           "min_film": solution.min_film if ok else nan,
           "torque_ratio": solution.torque_ratio if ok else nan}
    if geometry is not None:
        row["load_newton"] = geometry.load_newton(solution.load) if ok else nan
        row["min_film_thickness_um"] = (solution.min_film * geometry.radial_clearance * 1e6
                                        if ok else nan)
        torque, power = drag_torque_and_power(solution.torque_ratio, model.bearing_number,
                                              geometry)
        row["drag_torque_nm"], row["power_loss_w"] = (torque, power) if ok else (nan, nan)
    row.update(success=ok, message=solution.message, status=solution.status,
               iterations=solution.iterations, residual=solution.residual)
    return row


def _target(eccentricity, load) -> dict:
    return {"eccentricity": eccentricity} if load is None else {"load": load}


def static_point(model: BearingModel, *, eccentricity: Optional[float] = None,
                 load: Optional[float] = None, grid: Optional[Grid] = None,
                 cache: Optional[SolverCache] = None,
                 geometry: Optional[BearingGeometry] = None) -> dict:
    """Static equilibrium at one operating point, as a row (:func:`static_row`).

    Parameters
    ----------
    model : the non-dimensional bearing
    eccentricity : ε = e/c [-], or
    load : W̄ = W / (p_a R²) [-]
    grid : finite-difference grid (default :data:`gfbopt.inputs.DEFAULT_GRID`)
    cache : solver cache (one build per grid, film and structure)
    geometry : the dimensional bearing, to add h_min [µm]
    """
    t0 = time.perf_counter()
    sol = equilibrium(model, eccentricity=eccentricity, load=load, grid=grid, cache=cache)
    row = static_row(model, sol, geometry)
    row["wall_time_s"] = time.perf_counter() - t0
    return row


def load_curve(model: BearingModel, loads: Sequence[float], *,
               grid: Optional[Grid] = None, cache: Optional[SolverCache] = None,
               geometry: Optional[BearingGeometry] = None) -> list[dict]:
    """Static equilibria along increasing loads W̄ [-], each warm-started from the last
    converged one (a failed warm start is retried cold).  One row per load."""
    rows, previous = [], None
    for load in loads:
        t0 = time.perf_counter()
        sol = equilibrium(model, load=load, grid=grid, cache=cache, initial=previous)
        if not sol.success:  # retry cold before giving up on the point
            sol = equilibrium(model, load=load, grid=grid, cache=cache)
        previous = sol if sol.success else previous
        row = static_row(model, sol, geometry)
        if geometry is not None:
            row["load_newton"] = geometry.load_newton(load)
        row["wall_time_s"] = time.perf_counter() - t0
        rows.append(row)
    return rows


def _linear_threshold(sol: StaticSolution, solver):
    from .linear import linear_threshold, linearise

    return linear_threshold(linearise(sol, solver))


def _static_part(model, sol) -> dict:
    """Inputs and static outputs of a stability row (the static diagnostics renamed)."""
    row = static_row(model, sol)
    return {**{k: row[k] for k in (*model.groups(), *STATIC_OUTPUTS)},
            "static_success": row["success"], "iterations": row["iterations"]}


def linear_threshold_point(model: BearingModel, *, eccentricity: Optional[float] = None,
                           load: Optional[float] = None, grid: Optional[Grid] = None,
                           cache: Optional[SolverCache] = None) -> dict:
    """Linear stability threshold of the rigid rotor at one operating point.

    Returns the static row plus ``critical_mass`` M̄ = M c ω²/W0 [-] (inf when stable for
    every mass), ``whirl_ratio`` at the threshold [-], ``stable_for_all_masses``; ``success``
    is False when the static solve failed or no threshold could be found.
    """
    t0 = time.perf_counter()
    solver = _solver(model, grid, cache)
    sol = solve_static(model, **_target(eccentricity, load), solver=solver)
    row = {**_static_part(model, sol), "critical_mass": math.nan, "whirl_ratio": math.nan,
           "stable_for_all_masses": False, "message": sol.message}
    if sol.success:
        thr = _linear_threshold(sol, solver)
        row.update(critical_mass=thr.critical_mass, whirl_ratio=thr.whirl_ratio,
                   stable_for_all_masses=thr.stable_for_all_masses, message=thr.message)
    row["success"] = bool(sol.success and (math.isfinite(row["critical_mass"])
                                           or row["stable_for_all_masses"]))
    row["wall_time_s"] = time.perf_counter() - t0
    return row


def critical_mass_point(model: BearingModel, *, eccentricity: Optional[float] = None,
                        load: Optional[float] = None, grid: Optional[Grid] = None,
                        cache: Optional[SolverCache] = None, tolerance: float = 0.005,
                        revolutions: Optional[float] = None, method: str = "rkc",
                        start: str = "mode") -> dict:
    """Nonlinear (transient) critical mass beside the linear threshold at one point.

    The search (:func:`gfbopt.transient.find_critical_mass`) is centred on the linear
    threshold and stops when the bracket is within 2 × ``tolerance`` (relative).

    Parameters
    ----------
    tolerance : relative half-width of the final bracket on M̄ [-]
    revolutions : shaft revolutions per transient [-] (None: the search's default, one whirl
        period when starting from the linear mode)
    method : integration method, a key of :data:`gfbopt.transient.METHODS` (default 'rkc':
        the same growth rates as 'rk4' at ~13× less cost at the default grid)
    start : 'mode' — each transient starts from the least-stable linear mode shape (a clean
        growth-rate fit after about one whirl period); 'kick' — from a small journal kick

    Returns
    -------
    The static row plus ``linear_critical_mass``, ``linear_whirl_ratio``, ``critical_mass``,
    ``whirl_ratio``, ``bracket_low``, ``bracket_high``, ``transients``,
    ``rotor_revolutions``, ``nonlinear_over_linear``, ``success``, ``message``,
    ``wall_time_s``.
    """
    from .transient import find_critical_mass, transient_model
    from .transient.mode import linear_mode

    t0 = time.perf_counter()
    solver = _solver(model, grid, cache)
    sol = solve_static(model, **_target(eccentricity, load), solver=solver)
    row = {**_static_part(model, sol), "linear_critical_mass": math.nan,
           "linear_whirl_ratio": math.nan, "critical_mass": math.nan, "whirl_ratio": math.nan,
           "bracket_low": math.nan, "bracket_high": math.nan, "transients": 0,
           "rotor_revolutions": 0.0, "nonlinear_over_linear": math.nan,
           "success": False, "message": sol.message}
    if sol.success:
        from .linear import linear_threshold, linearise

        linearisation = linearise(sol, solver)
        lin = linear_threshold(linearisation)
        mode = None
        if start == "mode" and math.isfinite(lin.critical_mass) and lin.critical_mass > 0:
            mode = linear_mode(linearisation, lin.critical_mass, 1j * lin.whirl_ratio)
        result = find_critical_mass(transient_model(sol, threshold=lin), tolerance=tolerance,
                                    linear_estimate=lin.critical_mass,
                                    revolutions=revolutions, method=method,
                                    initial_mode=mode)
        row.update(linear_critical_mass=lin.critical_mass, linear_whirl_ratio=lin.whirl_ratio,
                   critical_mass=result.critical_mass, whirl_ratio=result.whirl_ratio,
                   bracket_low=result.bracket[0], bracket_high=result.bracket[1],
                   transients=result.transients, rotor_revolutions=result.rotor_revolutions,
                   nonlinear_over_linear=result.critical_mass / lin.critical_mass,
                   success=result.success, message=result.message)
    row["wall_time_s"] = time.perf_counter() - t0
    return row


def coefficients_point(model: BearingModel, *, whirl_ratios: Sequence[float],
                       eccentricity: Optional[float] = None, load: Optional[float] = None,
                       grid: Optional[Grid] = None, cache: Optional[SolverCache] = None,
                       geometry: Optional[BearingGeometry] = None,
                       speed_rpm: Optional[float] = None) -> list[dict]:
    """Stiffness and damping at one operating point, one row per whirl ratio γ [-].

    Load frame (x along the static load).  Non-dimensional ``kxx`` … ``cyy`` always; with
    ``geometry`` and ``speed_rpm`` [rpm] also ``frequency_hz``, ``kxx_N_per_m`` …
    ``cyy_Ns_per_m``, ``load_newton`` and ``critical_mass_kg``.  Each row carries
    the operating point (ε, φ) and the linear threshold (``critical_mass``,
    ``threshold_whirl_ratio``).  A failed static solve is one row with ``success`` False.
    """
    from .linear import coefficients, dimensional_coefficients, linear_threshold, linearise

    t0 = time.perf_counter()
    solver = _solver(model, grid, cache)
    sol = solve_static(model, **_target(eccentricity, load), solver=solver)
    base = _static_part(model, sol)
    if not sol.success:
        return [{**base, "success": False, "message": sol.message,
                 "wall_time_s": time.perf_counter() - t0}]
    lin = linearise(sol, solver)
    thr = linear_threshold(lin)
    coeffs = coefficients(lin, whirl_ratios)
    table = coeffs.to_frame()
    if geometry is not None and speed_rpm is not None:
        dimensional = dimensional_coefficients(coeffs, geometry, speed_rpm)
        table = dimensional.join(table.drop(columns="whirl_ratio"))
        load_newton = geometry.load_newton(sol.load if load is None else load)
        base["load_newton"] = load_newton
        base["critical_mass_kg"] = mass_from_parameter(
            thr.critical_mass, geometry.radial_clearance, rpm_to_rad_per_s(speed_rpm),
            load_newton)
    base.update(critical_mass=thr.critical_mass, threshold_whirl_ratio=thr.whirl_ratio,
                success=bool(thr.success), message=thr.message,
                wall_time_s=time.perf_counter() - t0)
    return [{**rec, **base} for rec in table.to_dict("records")]


def impedance_point(model: BearingModel, *, whirl_ratios: Sequence[float],
                    eccentricity: Optional[float] = None, load: Optional[float] = None,
                    grid: Optional[Grid] = None,
                    cache: Optional[SolverCache] = None) -> list[dict]:
    """The complex impedance Z(iγ) = K + iγC (load frame, non-dimensional) at one point,
    one row per whirl ratio γ [-]: ``zxx_re``, ``zxx_im``, … ``zyy_im``."""
    from .linear import impedance, linearise

    t0 = time.perf_counter()
    solver = _solver(model, grid, cache)
    sol = solve_static(model, **_target(eccentricity, load), solver=solver)
    base = _static_part(model, sol)
    if not sol.success:
        return [{**base, "success": False, "message": sol.message,
                 "wall_time_s": time.perf_counter() - t0}]
    lin = linearise(sol, solver)
    rows = []
    for gamma in whirl_ratios:
        z = impedance(lin, 1j * gamma)
        row = {**base, "whirl_ratio": float(gamma)}
        for i, a in enumerate("xy"):
            for j, b in enumerate("xy"):
                row[f"z{a}{b}_re"], row[f"z{a}{b}_im"] = float(z[i, j].real), float(z[i, j].imag)
        rows.append(row)
    elapsed = time.perf_counter() - t0
    for row in rows:
        row.update(success=True, message="", wall_time_s=elapsed)
    return rows


def impedance_matrix(row: dict) -> np.ndarray:
    """The 2 × 2 complex impedance of a row of :func:`impedance_point`."""
    return np.array([[row[f"z{a}{b}_re"] + 1j * row[f"z{a}{b}_im"] for b in "xy"]
                     for a in "xy"])
