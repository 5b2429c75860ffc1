"""The one-bearing analyses at the running condition: the static equilibrium, the stability
at an operating point and the onset of whirl with the running clearance and viscosity.

The running clearance c(ω, T) and μ(T) enter the bearing's non-dimensional model through
the SI bearing: :func:`warm_bearing` is the :class:`~gfbopt.inputs.bearing.BearingGeometry`
with ``radial_clearance`` = the running clearance and ``viscosity`` = μ(T_f), so Λ = 6μωR²/
(p_a c²), S = p_a α/c, C = E_t I_t c/(R⁴ L p_a), M̄ = M c ω²/W0 and h_min = H c all follow
from the one conversion module.  Λ, S, C and L/D are CasADi parameters of the static build
(:func:`gfbopt.static.build.solver_key`), so a running clearance is a new parameter vector on
the same build — no rebuild (the cache holds one build per grid, film and structure).

A bearing without ``[journal]`` and ``[thermal]`` is analysed as given (the warm bearing is
the bearing itself), so today's isothermal, cold-clearance answers are kept exactly.

This module stays below :mod:`gfbopt.rotor` (the package's floors): the fixed point needs
static solves only.  The analyses that then run :func:`gfbopt.rotor.stability`,
:func:`~gfbopt.rotor.onset_speed` and the capacity searches on the warm bearing are
:mod:`gfbopt.rotor.running_bearing`.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import ParameterError
from ..inputs.bearing import BearingGeometry
from ..inputs.grid import Grid
from .running import DragSample, RunningPoint, RunningSpec, speed_line


def side_outflow(solution) -> float:
    """Non-dimensional axial outflow q̄ = Σ_ends ∮ P H³ max(−∂P/∂n, 0) dθ of a static
    solution (n the outward axial normal; second-order one-sided differences at Z = ±L/D,
    θ weights of the film's quadrature).  ṁ_l = q̄ p_a² c³/(12 μ R_g T) [kg/s]."""
    p, h, z = solution.pressure, solution.film, solution.z
    dz = z[1] - z[0]
    m = p.shape[0]
    dpsi = 2.0 * math.pi / solution.grid.n_theta
    weights = np.full(m, dpsi)
    if solution.model.film != "periodic":
        weights[[0, -1]] *= 0.5
    top = -(3 * p[:, -1] - 4 * p[:, -2] + p[:, -3]) / (2 * dz)       # −∂P/∂Z at +L/D
    bottom = (-3 * p[:, 0] + 4 * p[:, 1] - p[:, 2]) / (2 * dz)       # +∂P/∂Z at −L/D
    flux = (p[:, -1] * h[:, -1]**3 * np.maximum(top, 0.0)
            + p[:, 0] * h[:, 0]**3 * np.maximum(bottom, 0.0))
    return float(weights @ flux)


def warm_bearing(bearing: BearingGeometry, point: RunningPoint) -> BearingGeometry:
    """The bearing at the running condition (module docstring); the bearing itself when
    nothing changes (isothermal, or at rest).  ParameterError when the running clearance
    breaks the bearing's rules (e.g. S > 1000 on a nearly closed clearance)."""
    if point.running_clearance == bearing.radial_clearance and \
            (math.isnan(point.viscosity) or point.viscosity == bearing.viscosity):
        return bearing
    return dataclasses.replace(bearing, radial_clearance=point.running_clearance,
                               viscosity=point.viscosity)


@dataclass(frozen=True)
class FilmCase:
    """What a drag solve needs: the bearing (SI), the resolved formulation options
    (:class:`~gfbopt.inputs.options.ModelOptions`, e.g. a stability case's), the grid, a
    :class:`~gfbopt.static.SolverCache` and the static load [N]."""

    bearing: BearingGeometry
    options: object
    grid: Grid
    cache: object
    load_newton: float


class FilmDrag:
    """The drag function of the fixed point for one case: a warm-started static solve of the
    bearing at (speed, clearance, viscosity) under the case's load, on the case's cached
    build.  Counts its solves (``solves``) and keeps the last solution (``last``).

    ``start`` (optional): (model, solver, load W̄) → a StaticSolution to warm-start the first
    solve from (e.g. a coarse grid's equilibrium interpolated onto this grid), or None."""

    def __init__(self, case: FilmCase, start=None):
        self.case, self.solves, self.last, self.start = case, 0, None, start

    def __call__(self, speed_rpm, clearance, viscosity, film_k) -> Optional[DragSample]:
        from ..physics.torque import drag_torque_and_power
        from ..static import solve_static

        try:
            geometry = dataclasses.replace(self.case.bearing, radial_clearance=clearance,
                                           viscosity=viscosity)
        except ParameterError:
            return None
        model = geometry.model(speed_rpm, **self.case.options.model_kwargs())
        solver = self.case.cache(model, self.case.grid)
        load = geometry.nondimensional_load(self.case.load_newton)
        self.solves += 1
        initial = self.last
        if initial is None and self.start is not None:
            initial = self.start(model, solver, load)
        sol = solve_static(model, load=load, solver=solver, initial=initial,
                           fast_path=initial is not None)
        if not sol.success and initial is not None and self.last is None:
            self.solves += 1
            sol = solve_static(model, load=load, solver=solver)
        if not sol.success and self.last is not None:
            self.solves += 1
            sol = solve_static(model, load=load, solver=solver)
        if not sol.success:
            return None
        self.last = sol
        _, power = drag_torque_and_power(sol.torque_ratio, model.bearing_number, geometry)
        return DragSample(power, sol.torque_ratio, side_outflow(sol), clearance, viscosity,
                          film_k, sol, speed_rpm=float(speed_rpm))


def limit_on_line(spec: RunningSpec, case: FilmCase, low_rpm: float,
                  failing_rpm: float) -> dict:
    """The answer when the running condition fails at ``failing_rpm``: the limit speed
    bracketed from ``low_rpm`` (``thermal_limit_rpm``, ``thermal_limit_kind``, the message
    "thermal runaway from N rpm" or "the journal reaches the foil at N rpm")."""
    drag = FilmDrag(case)
    line = speed_line(spec, [low_rpm, failing_rpm], drag)
    limit = line.limit_rpm if math.isfinite(line.limit_rpm) else failing_rpm
    message = line.message or f"thermal runaway from {limit:.6g} rpm"
    return {"thermal_limit_rpm": limit, "thermal_limit_kind": line.limit_kind or "runaway",
            "message": message, "running": line.points[-1].to_dict(),
            "limit_static_solves": drag.solves}
