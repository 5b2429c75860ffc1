"""The rotor's two bearings at one speed: each bearing's equilibrium under its own static load,
its linearisation, and its impedance Z_k(iγ) — built once per speed and reused for every
mode, every whirl frequency and every analysis at that speed (threshold, Campbell, imbalance).

Each bearing is analysed through the one-bearing route (:func:`gfbopt.rotor.analysis.
resolve_case` and :func:`~gfbopt.rotor.analysis.equilibrium`): its own bearing file, its own
``[model]`` options (with the rotor file's overrides), its load from the rotor's statics
(:func:`gfbopt.rotor.rigid.bearing_loads`) and its seam re-measured from that load
(:func:`~gfbopt.rotor.rigid.seam_from_load`).  A load beyond capacity at a speed is not a
crash: :func:`support_states` returns the states it could build and the message (with the
largest load the bearing carries) for the one it could not.

The impedance at a speed comes from one sparse LU per bearing and a block Krylov space
(:class:`gfbopt.linear.krylov.ShiftedImpedance`) over the whirl ratios scanned, read in Schur
form (:class:`gfbopt.rotor.reduced.ReducedImpedance`: a triangular solve per value, at whirl
ratios on the axis and at complex s near it alike); a value where the space has not
converged (or a whirl ratio outside it) gets a direct LU (:func:`gfbopt.linear.impedance`).
Values on the axis are cached per whirl ratio.

Statics: each speed's equilibrium starts from the nearest speed already solved with the Newton
fast path (:mod:`gfbopt.static.newton`, a few sparse LUs on the build's own equations); when it
does not converge, :func:`gfbopt.rotor.analysis.equilibrium` solves with IPOPT (warm, then
cold) and reports a load beyond capacity.  Both give the same state (≤ 1e-10,
tests/verification/test_static_newton.py).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Optional

import numpy as np

from ..errors import ParameterError
from ..inputs.conversions import STANDARD_GRAVITY, rpm_to_rad_per_s, stiffness_scale
from ..inputs.grid import DEFAULT_GRID, Grid, as_grid
from ..inputs.options import ModelOptions, merge_options
from ..inputs.rotor import Rotor
from ..inputs.rotor_system import RotorSystem
from ..linear import Linearisation, impedance, linearise
from ..linear.krylov import ShiftedImpedance
from ..static import SolverCache, StaticSolution, solve_static
from ..threads import single_threaded
from .analysis import Case, LoadCapacityError, equilibrium, resolve_case
from .reduced import ReducedImpedance
from .condensed import condensed
from .rigid import BearingLoad, bearing_loads, seam_from_load, transformations
from .structure import is_rigid, structure_of
from .speed_line import transferred_start
from .running import ISOTHERMAL, running_case, running_columns, running_line

#: the grid of a fine grid's first (cold) equilibrium, interpolated as its start, and the
#: cell ratio from which it is used [-]
COLD_GRID = Grid(36, 10)
COLD_FACTOR = 4
#: whirl ratios the threshold scans by default (those of gfbopt.linear.linear_threshold) [-]
WHIRL_RANGE = (0.02, 1.2)


@dataclass(frozen=True)
class RotorCase:
    """A resolved rotor: the system, each bearing's static load and one-bearing
    :class:`~gfbopt.rotor.analysis.Case` (options filled, seam from its own load), the
    transformations T_k = R(α_k)ᵀ S(z_k) (2 × n), the grid and the shared solver cache.

    structure : what every analysis works on (:class:`~gfbopt.rotor.structure.Structure`):
    the rigid body, or a shaft condensed onto its bearings and a few modes
    (:func:`~gfbopt.rotor.condensed.condensed`); default: :func:`analysis_structure`.
    mass_share_kg : each bearing's share of the rotor mass in the per-bearing (half-mass)
    approximation, m |W_k|/(|W_A| + |W_B|) [kg].
    running : the bearings' running condition (:class:`gfbopt.rotor.running.RunningLine`)
    when a bearing file states ``[journal]``/``[thermal]``; None: every bearing isothermal
    at its cold clearance (today's analyses, bit for bit)."""

    system: RotorSystem
    loads: tuple
    cases: tuple
    transforms: tuple
    grid: Grid
    cache: SolverCache = field(repr=False, compare=False)
    structure: object = field(default=None, repr=False, compare=False)
    running: object = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.structure is None:
            object.__setattr__(self, "structure", analysis_structure(self.system))

    @property
    def mass_share_kg(self) -> tuple:
        total = sum(l.magnitude for l in self.loads)
        return tuple(self.structure.total_mass * l.magnitude / total for l in self.loads)

    @property
    def names(self) -> tuple:
        return tuple(b.name for b in self.system.bearings)

    @property
    def positions(self) -> tuple:
        """The bearings' axial positions [m]."""
        return tuple(b.position for b in self.system.bearings)

    def conventions(self) -> dict:
        """The options each bearing is analysed with, its load and frame, as outputs state."""
        frame = FRAME if is_rigid(self.structure) else SHAFT_FRAME
        models = (self.running.models() if self.running is not None
                  else {n: ISOTHERMAL for n in self.names})
        return {"frame": frame, "grid": str(self.grid),
                "bearings": {n: {
                    **c.conventions(), "load_newton": l.magnitude,
                    "load_direction_deg": l.direction_deg,
                    "load_from_gravity_deg": l.away_from_gravity_deg,
                    "position_m": l.position, "bearing_file": s.file,
                    "thermal_model": models[n]}
                    for n, c, l, s in zip(self.names, self.cases, self.loads,
                                          self.system.bearings)},
                "gravity_m_per_s2": self.system.gravity,
                "gravity_direction_deg": self.system.gravity_direction_deg}


def analysis_structure(system: RotorSystem):
    """The structure the analyses work on: the rigid body itself, or the system's shaft
    condensed on its two bearing stations (:mod:`.condensed`)."""
    full = structure_of(system)
    if is_rigid(full):
        return full
    return condensed(full, [b.position for b in system.bearings])


FRAME = ("z along the rotor axis from the centre of gravity; x, y in the bearing plane, the "
         "shaft spinning from x to y; angles from +x in the direction of rotation [deg]; "
         "q = (x, y, ψx = dx/dz, ψy = dy/dz); each bearing's impedance in its own load frame "
         "(X along its static load, Y ahead of it)")
SHAFT_FRAME = ("z along the rotor axis from the shaft's first end; x, y in the bearing plane, "
               "the shaft spinning from x to y; angles from +x in the direction of rotation "
               "[deg]; the shaft of beam elements condensed on its two bearing stations and "
               "its lowest modes with them held (gfbopt.rotor.condensed); each bearing's "
               "impedance in its own load frame (X along its static load, Y ahead of it)")


@single_threaded
def resolve_rotor(system: RotorSystem, grid: Grid = DEFAULT_GRID,
                  cache: Optional[SolverCache] = None,
                  options: Optional[ModelOptions] = None) -> RotorCase:
    """Check and resolve everything before any solve: statics, each bearing's options
    (``options`` stated here win over the rotor and bearing files), its Case and T_k."""
    if not isinstance(system, RotorSystem):
        raise ParameterError("system", system, "must be a RotorSystem (gfbopt.inputs."
                             "rotor_system.load_rotor)")
    grid = as_grid(grid)
    cache = cache if cache is not None else SolverCache(grid)
    loads = bearing_loads(system)
    structure = analysis_structure(system)
    total = sum(l.magnitude for l in loads)
    cases = []
    for support, load in zip(system.bearings, loads):
        resolved = merge_options(options or ModelOptions(), support.options)
        resolved = seam_from_load(resolved, load.away_from_gravity_deg)
        share = structure.total_mass * load.magnitude / total
        try:
            cases.append(resolve_case(support.geometry, Rotor(share), load.magnitude,
                                      options=resolved, grid=grid, cache=cache))
        except ParameterError as exc:
            raise ParameterError(f"bearing {support.name}: {exc.name}", exc.value,
                                 exc.rule) from None
    return RotorCase(system, loads, tuple(cases), transformations(system, loads, structure),
                     grid, cache, structure, running_line(system))


class BearingState:
    """One bearing at one speed: equilibrium, linearisation and Z(iγ) [N/m] on demand."""

    def __init__(self, case: Case, load: BearingLoad, speed_rpm: float,
                 solution: StaticSolution, whirl_range=WHIRL_RANGE, running=None):
        self.case, self.load, self.speed_rpm, self.solution = case, load, speed_rpm, solution
        #: the RunningPoint the case's bearing is at (None: the bearing as given)
        self.running = running
        self.omega = rpm_to_rad_per_s(speed_rpm)
        g = case.bearing
        self.scale = stiffness_scale(g.ambient_pressure, g.radius, g.radial_clearance)
        self.linearisation: Linearisation = linearise(solution, case.cache(solution.model,
                                                                            case.grid))
        self.whirl_range = tuple(whirl_range)
        self._model: Optional[ShiftedImpedance] = None
        self._reduced: Optional[ReducedImpedance] = None
        self._values: dict = {}
        self.direct_solves = 0

    def _krylov(self) -> Optional[ShiftedImpedance]:
        if self._model is None:
            try:
                self._model = ShiftedImpedance(self.linearisation, self.whirl_range)
                self._reduced = ReducedImpedance(self._model)
            except RuntimeError:          # A + s0 B exactly singular: direct solves only
                self._model = False
        return self._model or None

    @single_threaded
    def prepare(self, whirl_ratios) -> None:
        """Converge the Krylov space at these whirl ratios (the threshold's scan)."""
        if self._krylov() is not None:
            self._reduced.converge(1j * np.asarray(whirl_ratios, dtype=float))
            batch = self._reduced.last_batch       # its values on the space as it ended
            if batch is not None and batch[3] == self._model.blocks:
                for s, z, ok in zip(*batch[:3]):
                    if ok:
                        self._values.setdefault(float(s.imag), z)

    def nondimensional(self, whirl_ratio: float) -> np.ndarray:
        """Z̄(iγ) (2 × 2, bearing load frame) [-]."""
        g = float(whirl_ratio)
        if g in self._values:
            return self._values[g]
        low, high = self.whirl_range
        z = self._from_space(1j * g) if low <= g <= high else None
        if z is None:
            z = impedance(self.linearisation, 1j * g)
            self.direct_solves += 1
        self._values[g] = z
        return z

    def nondimensional_many(self, whirl_ratios) -> np.ndarray:
        """Z̄(iγ) at every whirl ratio of an array (n, 2, 2) [-]: the values of
        :meth:`nondimensional`, those of the Krylov space in one batch."""
        gammas = [float(g) for g in whirl_ratios]
        new = [g for g in dict.fromkeys(gammas) if g not in self._values]
        low, high = self.whirl_range
        inside = [g for g in new if low <= g <= high]
        if inside and self._krylov() is not None:
            z, ok = self._reduced.evaluate_many(1j * np.array(inside))
            for g, zg, good in zip(inside, z, ok):
                if good:
                    self._values[g] = zg
        return np.array([self.nondimensional(g) for g in gammas])

    def _from_space(self, s: complex) -> Optional[np.ndarray]:
        return self._reduced.value(s) if self._krylov() is not None else None

    def schur_model(self):
        """The Krylov space in Schur form (:meth:`gfbopt.rotor.reduced.ReducedImpedance.
        schur`), or None without one."""
        return self._reduced.schur() if self._krylov() is not None else None

    def converged_at(self, s: complex) -> bool:
        """True when the Krylov space gives Z̄(s) to its tolerance as it is."""
        return self._krylov() is not None and self._reduced.evaluate(complex(s))[1]

    @single_threaded
    def extend_at(self, s: complex) -> bool:
        """Extend the Krylov space until it gives Z̄(s); True when it grew."""
        if self._krylov() is None:
            return False
        before = self._model.blocks
        self._reduced.value(complex(s))
        return self._model.blocks > before

    def at(self, s: complex) -> np.ndarray:
        """Z̄(s) at complex s [-] (per radian; s = iγ on the axis) with the hysteretic
        foundation of the upper half plane (exact for η = 0): from the Krylov space where it
        has converged (:mod:`.reduced`), else a direct LU."""
        z = self._from_space(complex(s))
        if z is None:
            z = impedance(self.linearisation, complex(s))
            self.direct_solves += 1
        return z

    def impedance(self, whirl_ratio: float) -> np.ndarray:
        """Z_k(iΩ) [N/m] at Ω = γ ω (2 × 2, bearing load frame)."""
        return self.scale * self.nondimensional(whirl_ratio)

    def summary(self) -> dict:
        """The equilibrium, as outputs state it."""
        sol = self.solution
        return {"bearing": self.load.name, "speed_rpm": self.speed_rpm,
                "load_newton": self.load.magnitude, "eccentricity": sol.eccentricity,
                "attitude_angle_deg": sol.attitude_angle_deg,
                "min_film_thickness_um": sol.min_film * self.case.bearing.radial_clearance * 1e6,
                "bearing_number": sol.model.bearing_number, "load_exceeds_capacity": False,
                **running_columns(self.running)}


@dataclass(frozen=True)
class SpeedStates:
    """Both bearings at one speed (``states``), or why not (``failure``: the bearing and the
    capacity message; then ``states`` holds None for it)."""

    speed_rpm: float
    states: tuple
    failure: Optional[dict] = None

    @property
    def ok(self) -> bool:
        return self.failure is None

    @property
    def omega(self) -> float:
        return rpm_to_rad_per_s(self.speed_rpm)


@single_threaded
def support_states(rotor: RotorCase, speed_rpm: float, initial: Optional[tuple] = None,
                   whirl_range=WHIRL_RANGE, guesses: Optional[tuple] = None) -> SpeedStates:
    """Each bearing's equilibrium and linearisation at ``speed_rpm`` [rpm]; warm starts from
    ``guesses`` (StaticSolution per bearing, e.g. :func:`predicted_starts`) or else from
    ``initial`` (a nearby speed's BearingState per bearing).  A bearing loaded beyond its
    capacity is reported in ``failure`` (bearing, message with the largest load it carries),
    not raised.  With ``rotor.running`` each bearing is first put at its running condition
    at this speed (:func:`gfbopt.rotor.running.running_case`: the fixed point, then the
    bearing at that clearance and viscosity, its equilibrium from the fixed point's last
    film); a thermal runaway or closure is a ``failure`` with ``kind``, not raised."""
    states = []
    failure = None
    for k, (case, load) in enumerate(zip(rotor.cases, rotor.loads)):
        guess = initial[k].solution if initial and initial[k] is not None else None
        guess = guesses[k] if guesses and guesses[k] is not None else guess
        point = None
        if rotor.running is not None:      # the bearing at its running condition here
            case, guess, point, failed = running_case(rotor.running, k, case, load,
                                                      speed_rpm, guess, COLD_GRID,
                                                      COLD_FACTOR)
            if failed is not None:
                states.append(None)
                failure = failure or failed
                continue
        try:
            sol = _equilibrium(case, speed_rpm, guess)
        except LoadCapacityError as exc:
            states.append(None)
            failure = failure or {"bearing": load.name, "speed_rpm": speed_rpm,
                                  "load_newton": load.magnitude, "message": exc.rule}
            continue
        states.append(BearingState(case, load, speed_rpm, sol, whirl_range, point))
    return SpeedStates(speed_rpm, tuple(states), failure)


def predicted_starts(near: SpeedStates, other: Optional[SpeedStates], speed_rpm: float,
                     third: Optional[SpeedStates] = None) -> tuple:
    """Each bearing's warm start at ``speed_rpm``: the equilibrium at the nearest speed solved
    (``near``), extrapolated (or interpolated) linearly in ln N through ``other``'s when given
    — the Newton fast path then needs fewer steps — and quadratically through ``third``'s too
    when the three speeds are spread (:func:`_spread`: each at least half the distance from
    ``speed_rpm`` to ``near`` from the others; a scan's speeds, measured at 72 × 20 one or two
    Newton steps fewer than the linear start).  None for a bearing ``near`` lacks."""
    quadratic = third is not None and other is not None and _spread(
        [near.speed_rpm, other.speed_rpm, third.speed_rpm], speed_rpm)
    out = []
    for k, st in enumerate(near.states):
        if st is None:
            out.append(None)
            continue
        sol = st.solution
        two = other.states[k] if other is not None else None
        span = math.log(near.speed_rpm / other.speed_rpm) if two is not None else 0.0
        if two is None or span == 0.0 or two.solution.state.shape != sol.state.shape:
            out.append(sol)
            continue
        three = third.states[k] if quadratic else None
        if three is not None and three.solution.state.shape == sol.state.shape:
            nodes = [math.log(x.speed_rpm) for x in (near, other, third)]
            weights = _lagrange(nodes, math.log(speed_rpm))
            state = sum(w * x.solution.state for w, x in zip(weights, (st, two, three)))
            out.append(replace(sol, state=state))
            continue
        step = math.log(speed_rpm / near.speed_rpm) / span
        out.append(replace(sol, state=sol.state + step * (sol.state - two.solution.state)))
    return tuple(out)


def _spread(speeds: list, speed_rpm: float) -> bool:
    """True when the three ``speeds`` [rpm] (the nearest to ``speed_rpm`` first) lie at least
    half the distance from ``speed_rpm`` to the nearest apart from each other, in ln N: a
    quadratic through them then amplifies the noise of each solution at most ~10-fold."""
    u = [math.log(x) for x in speeds]
    reach = abs(math.log(speed_rpm) - u[0])
    gaps = [abs(u[i] - u[j]) for i, j in ((0, 1), (0, 2), (1, 2))]
    return reach > 0 and min(gaps) >= 0.5 * reach


def _lagrange(nodes: list, u: float) -> list:
    """The weights of the quadratic through ``nodes`` evaluated at ``u``."""
    out = []
    for i, ui in enumerate(nodes):
        w = 1.0
        for j, uj in enumerate(nodes):
            if j != i:
                w *= (u - uj) / (ui - uj)
        out.append(w)
    return out


def _equilibrium(case: Case, speed_rpm: float, guess: Optional[StaticSolution]
                 ) -> StaticSolution:
    """The Newton fast path from ``guess`` (IPOPT from ``guess`` when it does not converge),
    else a cold :func:`~gfbopt.rotor.analysis.equilibrium` (module docstring).  Without a
    guess on a grid of at least :data:`COLD_FACTOR` times :data:`COLD_GRID`'s cells, the
    guess is the equilibrium on that coarse grid interpolated onto this one
    (:func:`gfbopt.rotor.speed_line.transferred_start`): a cold IPOPT solve on the fine grid
    costs several seconds at 144 × 36."""
    model = case.model(speed_rpm)
    if guess is None and (case.grid.n_theta * case.grid.n_z
                          >= COLD_FACTOR * COLD_GRID.n_theta * COLD_GRID.n_z):
        try:
            coarse = equilibrium(replace(case, grid=COLD_GRID), speed_rpm)
            guess = transferred_start(coarse, case.cache(model, case.grid), model)
        except LoadCapacityError:
            guess = None
    if guess is None:
        return equilibrium(case, speed_rpm)
    sol = solve_static(model, load=case.load, solver=case.cache(model, case.grid),
                       initial=guess, continuation=False, fast_path=True)
    return sol if sol.success else equilibrium(case, speed_rpm)


def weight_note(system: RotorSystem) -> str:
    """How the static loads were obtained, for outputs."""
    g = system.gravity
    source = ("standard gravity" if g == STANDARD_GRAVITY else f"g = {g:g} m/s²")
    return (f"weight m g ({source}) along {system.gravity_direction_deg:g}° plus "
            f"{len(system.side_loads)} side load(s), shared by force and moment balance")


def frozen_at_running_condition(system, speed_rpm: float, grid) -> tuple:
    """(the rotor with each bearing frozen at its running condition at ``speed_rpm``: the
    running clearance and the film viscosity of its heat balance there, no tables left, so the
    rotor transient can run it; a summary: the model, each bearing's running point, or
    ``failure`` — a thermal runaway or closure at that speed, in words).  The transient then
    holds the clearance and viscosity of that speed for its whole run (a constant-speed orbit:
    the temperatures are taken as settled)."""
    states = support_states(resolve_rotor(system, grid), speed_rpm)
    if states.failure:
        f = states.failure
        return system, {"model": "heat balance + growth", "speed_rpm": speed_rpm,
                        "failure": f"{f.get('kind', 'failure')} at bearing {f.get('bearing')} "
                                   f"at {speed_rpm:,.0f} rpm: {f.get('message', '')}"}
    bearings, points = [], {}
    for b, st in zip(system.bearings, states.states):
        bearings.append(replace(b, geometry=st.case.bearing, running_tables=()))
        points[b.name] = running_columns(st.running) if st.running is not None else {}
    frozen = replace(system, bearings=tuple(bearings))
    return frozen, {"model": f"heat balance + growth, frozen at the running condition of "
                             f"{speed_rpm:,.0f} rpm", "speed_rpm": speed_rpm,
                    "bearings": points}
