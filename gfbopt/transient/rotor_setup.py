"""From a rotor described in SI to the transient model of the rotor on its two bearing films.

Statics.  The two bearings carry the reactions that balance the static generalised force
Q_s (gravity, side loads) in force and moment: Σ_k T_kᵀ R_k + Q_s = 0, four equations for the
two film forces R_k, so the load on bearing k is L_k = −R_k (statically determinate).  Each
bearing is solved at its own load, in its own load frame: ψ_k = angle of L_k from the global
x in the direction of rotation (a bearing pushed away from gravity simply has ψ_k ≈ 180°),
with its file's formulation (a seam angle is measured from that bearing's load line).

The rotor description is the minimal interface :class:`RotorInput` (mass matrix,
gyroscopic matrix, two :class:`RotorBearing`, Q_s, imbalance planes); the rotor file's
dataclasses (gfbopt.inputs) convert to it in :mod:`gfbopt.transient.rotor_io`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..errors import ParameterError
from ..inputs.bearing import BearingGeometry
from ..inputs.conversions import rpm_to_rad_per_s
from ..inputs.grid import Grid
from ..static import SolverCache, solve_static
from .rotor_system import (BearingFilm, ImbalancePlane, RotorTransientModel, empty_states,
                           layout, rigid_structure, rotation, station_matrix,
                           structure_transient_model)
from .system import film_force, rigid_film, transient_model


@dataclass(frozen=True)
class RotorBearing:
    """A bearing of the rotor: geometry (SI), axial position z [m] from the CG, the keyword
    arguments of its model (``BearingGeometry.model``: foil, film, seam_angle_deg [deg],
    deflection_law, loss_factor, …), and a label."""

    geometry: BearingGeometry
    position: float
    model_options: dict = field(default_factory=dict)
    label: str = ""


@dataclass(frozen=True, eq=False)
class RotorInput:
    """The rotor as the transient engine needs it (SI): mass_matrix, gyroscopic (per unit
    spin speed) (4, 4) of the rigid body (coordinates :data:`gfbopt.transient.rotor_system.DOF`,
    positions from the CG); bearings : two RotorBearing; static_force (4,) [N, N m]: the
    applied static force and its moment about the axial origin (what the two bearings carry,
    by force and moment balance); imbalance : ImbalancePlane per plane; description : what
    the outputs state about it.

    structure : another rotor structure (:class:`gfbopt.rotor.structure.Structure`, e.g. a
    condensed shaft, positions from its first end), None for the rigid body of the matrices;
    generalised_force : its generalised static force Q_s (n,) [N] (gravity spread over its
    mass, side loads at their stations), required with a structure."""

    mass_matrix: np.ndarray
    gyroscopic: np.ndarray
    bearings: tuple
    static_force: np.ndarray
    imbalance: tuple = ()
    description: dict = field(default_factory=dict)
    structure: object = None
    generalised_force: Optional[np.ndarray] = None

    def with_imbalance(self, imbalance: tuple) -> "RotorInput":
        return RotorInput(self.mass_matrix, self.gyroscopic, self.bearings,
                          self.static_force, tuple(imbalance), self.description,
                          self.structure, self.generalised_force)

    def rotor_structure(self):
        """The structure the transient integrates (the rigid body of the matrices if none)."""
        if self.structure is None:
            return rigid_structure(self.mass_matrix, self.gyroscopic)
        return self.structure

    def structure_force(self) -> np.ndarray:
        """Q_s (n,) of :meth:`rotor_structure` [N, N m]."""
        if self.structure is None:
            return np.asarray(self.static_force, dtype=float)
        if self.generalised_force is None:
            raise ParameterError("generalised_force", None, "a rotor structure needs its "
                                 "generalised static force (gravity_force)")
        return np.asarray(self.generalised_force, dtype=float)


def gravity_force(structure, weight, loads=()) -> np.ndarray:
    """Q_s (n,) [N] of ``structure``: the weight (w_x, w_y) [N] spread over its mass
    (M r, r the rigid translation: 1 on the degrees of freedom named ``x…``/``y…`` times
    w / total mass, 0 on tilts and modal coordinates) and the point ``loads`` (f_x, f_y, z)
    [N, N, m] at their stations S(z)ᵀ f.  The rigid body's is (w_x, w_y, 0, 0) + loads."""
    names = [str(n) for n in structure.dof_names]
    g = np.asarray(weight, dtype=float) / float(structure.total_mass)
    shape = np.array([g[0] if n.startswith("x") else g[1] if n.startswith("y") else 0.0
                      for n in names])
    q = np.asarray(structure.mass(), dtype=float) @ shape
    for fx, fy, z in loads:
        q = q + np.asarray(structure.station(z), dtype=float).T @ np.array([fx, fy], float)
    return q


def static_force_of(loads) -> np.ndarray:
    """Q_s (4,) [N, N m] of point loads ``loads``: (force x [N], force y [N], position z [m])
    each, global frame (gravity is m g along x at z = 0)."""
    q = np.zeros(4)
    for fx, fy, z in loads:
        q += station_matrix(z).T @ np.array([fx, fy], dtype=float)
    return q


def bearing_loads(rotor: RotorInput) -> np.ndarray:
    """Static load L_k (K, 2) [N] that the rotor puts on each bearing (global x, y)."""
    stations = np.hstack([station_matrix(b.position).T for b in rotor.bearings])   # (4, 4)
    reactions = np.linalg.solve(stations, -np.asarray(rotor.static_force, dtype=float))
    return -reactions.reshape(len(rotor.bearings), 2)


def bearing_equilibria(rotor: RotorInput, speed_rpm: float, grid: Grid,
                       cache: Optional[SolverCache] = None,
                       initial: Optional[list] = None) -> tuple[list, np.ndarray]:
    """([StaticSolution] per bearing, frame angles ψ_k [rad]) at ``speed_rpm``.

    A bearing whose static problem does not converge (its share above the load capacity at
    that speed) raises ParameterError naming it, its load and the speed.
    """
    cache = cache if cache is not None else SolverCache(grid)
    loads = bearing_loads(rotor)
    solutions, angles = [], []
    for k, (b, load) in enumerate(zip(rotor.bearings, loads)):
        magnitude = float(np.hypot(*load))
        name = b.label or f"bearing {k + 1}"
        if not magnitude > 1e-9:
            raise ParameterError(f"{name}.load_newton", magnitude, "the statics leave this "
                                 "bearing unloaded: a transient needs a loaded equilibrium "
                                 "to start from")
        model = b.geometry.model(speed_rpm, **b.model_options)
        w = b.geometry.nondimensional_load(magnitude)
        start = None if initial is None else initial[k]
        sol = solve_static(model, load=w, solver=cache(model, grid), initial=start)
        if not sol.success and start is not None:
            sol = solve_static(model, load=w, solver=cache(model, grid))
        if not sol.success:
            raise ParameterError(f"{name}.load_newton", round(magnitude, 4),
                                 f"no static equilibrium at {speed_rpm:,.0f} rpm (IPOPT "
                                 f"status {sol.status}): the load exceeds what the bearing "
                                 "carries at that speed")
        solutions.append(sol)
        angles.append(math.atan2(load[1], load[0]))
    return solutions, np.array(angles)


def build_model(rotor: RotorInput, model_speed_rpm: float, grid: Grid, *,
                reference_speed_rpm: Optional[float] = None,
                reference_whirl_ratio: Optional[float] = None,
                cache: Optional[SolverCache] = None) -> tuple[RotorTransientModel, list]:
    """(the rotor transient model, the static solutions) with each bearing's film model
    built about its equilibrium at ``model_speed_rpm``; time unit τ = ω_ref t with ω_ref
    from ``reference_speed_rpm`` (default the model speed).  ``reference_whirl_ratio``
    ν_ref of a damped foil (η > 0): default each bearing's linear threshold whirl ratio
    (:func:`gfbopt.transient.system.transient_model`).  A bearing whose file states bump
    friction (μ_f > 0) gets its sliders (``transient_model(..., friction=True)``,
    :mod:`.rotor_friction`); with a loss factor η > 0 as well it carries both, the
    Kelvin–Voigt W and the sliders in its rate (:mod:`.foil_state` "With friction"; fused
    rows :mod:`.rotor_friction_films`, or the one-bearing kernels)."""
    cache = cache if cache is not None else SolverCache(grid)
    solutions, angles = bearing_equilibria(rotor, model_speed_rpm, grid, cache)
    omega_m = rpm_to_rad_per_s(model_speed_rpm)
    films = []
    for k, (b, sol, psi) in enumerate(zip(rotor.bearings, solutions, angles)):
        damped = sol.model.loss_factor > 0
        rubbing = bool(getattr(sol.model, "has_friction", False))
        tm = transient_model(sol, reference_whirl_ratio if damped else None,
                             cache(sol.model, grid), friction=rubbing)
        films.append(BearingFilm(tm, b.geometry, float(b.position), float(psi), omega_m,
                                 b.label or f"bearing {k + 1}"))
    ref = omega_m if reference_speed_rpm is None else rpm_to_rad_per_s(reference_speed_rpm)
    model = structure_transient_model(rotor.rotor_structure(), films, rotor.structure_force(),
                                      rotor.imbalance, ref)
    return model, solutions


def frame_angles_deg(model: RotorTransientModel) -> list:
    """ψ_k [deg] of each bearing's load line from the global x."""
    return [math.degrees(b.frame_angle) for b in model.bearings]


def local_to_global(model: RotorTransientModel, k: int, x, y) -> tuple:
    """Bearing k's frame components → global (x, y) (same units)."""
    r = rotation(model.bearings[k].frame_angle)
    return r[0, 0] * x + r[0, 1] * y, r[1, 0] * x + r[1, 1] * y


def imbalance_planes(entries) -> tuple:
    """ImbalancePlane per (amount [kg m], phase [deg], position [m]) entry."""
    out = []
    for k, (amount, phase_deg, position) in enumerate(entries):
        for name, value in (("amount", amount), ("phase_deg", phase_deg),
                            ("position", position)):
            if value is None or not math.isfinite(float(value)):
                raise ParameterError(f"imbalance[{k}].{name}", value, "must be a finite number"
                                     + (" (an imbalance needs a plane: its axial position)"
                                        if name == "position" else ""))
        if not amount > 0:
            raise ParameterError(f"imbalance[{k}].amount", amount, "must be > 0 [kg m]")
        out.append(ImbalancePlane(float(amount), math.radians(float(phase_deg)),
                                  float(position)))
    return tuple(out)


def iso_g_imbalance(grade_mm_per_s: float, mass: float, max_speed_rpm: float) -> float:
    """Permissible residual imbalance U = m e_per [kg m] of balance grade G (ISO 21940-11,
    formerly ISO 1940-1): e_per ω_max = G, G in mm/s."""
    for name, value in (("balance_grade", grade_mm_per_s), ("mass", mass),
                        ("max_speed_rpm", max_speed_rpm)):
        if not (math.isfinite(value) and value > 0):
            raise ParameterError(name, value, "must be finite and > 0")
    return mass * grade_mm_per_s * 1e-3 / rpm_to_rad_per_s(max_speed_rpm)


def equilibrium_states(model: RotorTransientModel, batch: int, solutions=None) -> np.ndarray:
    """States (B, K, L) of the static equilibrium: each film at its bearing's static
    solution (``solutions``, default the one its model was built from), the rotor where
    both journals sit at their equilibria, S_k q = R(ψ_k) c_k (X_k, Y_k) — the rigid body's
    four equations; a structure with stiffness also K q = Q_s + Σ S_kᵀ F_k (its static
    deflection under the films' forces, whose balance the statics made; least squares,
    exact when they balance)."""
    lay = layout(model)
    z = empty_states(model, 1)
    targets, stations, forces = [], [], np.zeros(model.dofs)
    for k, b in enumerate(model.bearings):
        sol = b.tm.static if solutions is None else solutions[k]
        if sol.pressure.shape != b.tm.shape:
            raise ParameterError("solutions", sol.pressure.shape, "must be on the bearing's "
                                 f"grid {b.tm.shape}")
        lay.phi_of(z, k)[0] = sol.pressure * sol.film
        x0 = sol.eccentricity * math.cos(sol.attitude_angle_rad)
        y0 = sol.eccentricity * math.sin(sol.attitude_angle_rad)
        if lay.foil[k] is not None:
            hr = rigid_film(np.array([x0]), np.array([y0]), b.tm)[0]     # with the bore
            w = sol.film - hr[:, None]
            lay.foil_of(z, k)[0] = w if b.tm.foil_state.layout == "nodes" else w[:, 0]
        targets.append(rotation(b.frame_angle) @ np.array([x0, y0]) * b.clearance)
        stations.append(model.station(b.position))
        if not model.rigid:
            fx, fy = film_force(sol.pressure[None], b.tm)
            forces += (model.from_local()[k] @ np.array([float(fx[0]), float(fy[0])]))
    if model.rigid:
        q = np.linalg.solve(np.vstack(stations), np.concatenate(targets))
    else:
        system = np.vstack([model.stiffness] + stations)
        rhs = np.concatenate([model.static_force + forces] + targets)
        q = np.linalg.lstsq(system, rhs, rcond=None)[0]
    lay.rotor_of(z)[0, :model.dofs] = q / model.clearance_ref
    return np.repeat(z, batch, axis=0)


def set_station_velocities(model: RotorTransientModel, z: np.ndarray, velocities) -> np.ndarray:
    """Set q̃' so that the journals move at ``velocities`` (K, 2) [clearances per rad of τ,
    global x, y at each bearing] (one set for every run, or (B, K, 2)); returns ``z``.  A
    structure of more than four degrees of freedom gets the smallest q̃' that does it."""
    v = np.broadcast_to(np.asarray(velocities, dtype=float), (z.shape[0], len(model.bearings), 2))
    stations = np.vstack([model.station(b.position) for b in model.bearings])
    scale = np.array([b.clearance / model.clearance_ref for b in model.bearings])
    rhs = (v * scale[None, :, None]).reshape(z.shape[0], -1)
    n = model.dofs
    if stations.shape[0] == n:
        velocity = np.linalg.solve(stations, rhs.T).T
    else:
        velocity = np.linalg.lstsq(stations, rhs.T, rcond=None)[0].T
    layout(model).rotor_of(z)[:, n:2 * n] = velocity
    return z
