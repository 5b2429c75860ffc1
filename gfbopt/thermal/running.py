"""The running condition of one bearing at a speed: temperatures, growths, viscosity and
clearance solved together to a fixed point with the film's drag power.

Unknowns at a speed ω: the network's temperatures (:mod:`.network`), the running clearance

    c = c₀ − u_c(ω) − α_j R (T_j − T_ref) + α_s (R + c₀)(T_s − T_ref)

(c₀ the cold clearance stated at T_ref, u_c the journal's centrifugal growth
(:mod:`.growth`), the journal growing into the film and the sleeve's bore away from it) and the
film viscosity μ(T_f) (Sutherland, :mod:`.viscosity`).  The drag power of the film at (c, μ)
comes from a static solve; between solves it is predicted by Petroff's scaling

    P(c, μ) = τ · 2π μ ω² R³ L / c

with the torque ratio τ = T/T_Petroff modelled as a function of ln Λ (Λ = 6μωR²/(p_a c²):
under a fixed load τ depends on the speed, μ and c mostly through Λ; it varies slowly), and
the side-leakage flow ṁ_l = q̄ p_a² c³/(12 μ R_g T_f) with the last solve's non-dimensional
outflow q̄.  With τ(ln Λ) and the conductances frozen, the heat balance is one equation in P,

    F(P) = P − τ(ln Λ(P)) 2π μ(T_f(P)) ω² R³ L / c(P) = 0,

the temperatures being linear in P; its lowest root is found by sampling (one vectorised
evaluation) and Brent's method (:mod:`.balance`).  Each static solve adds a point (ln Λ, τ)
(and updates q̄): τ is the seed before any, the solve's after one, then the line through the
last two (a secant method), and after two solves of this point the parabola through the last
three.  Priors solved at other speeds under the same load (:func:`speed_line` passes the two
speeds below) are the first points of that secant, so the first solve's τ is already
extrapolated in ln Λ; the fixed point costs at most 3 static solves per point on the
Ruscitto bearing up to 1 % below its runaway (results/benchmarks/thermal.json).  The point
has converged when the predicted
film temperature differs from the last solve's by at most ``tolerance_k`` (default 0.01 K:
0.2 nm of clearance and 2.5e-5 of μ on a 19 mm steel journal); the state reported is that
prediction, the secant's next iterate, which is closer still.  No root below the closing of the clearance
(c falling to :data:`MIN_RUNNING_CLEARANCE`), even with τ taken where F comes closest to 0,
is thermal runaway — reported in the result, never raised.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Callable, Optional

import numpy as np

from ..errors import ParameterError
from .balance import MIN_RUNNING_CLEARANCE, log_bearing_number
from .balance import Balance as _Balance
from .growth import centrifugal_growth, thermal_growth
from .network import (Conductances, JournalMaterial, NetworkState, ThermalNetwork,
                      solve_network)
from .viscosity import sutherland_viscosity

#: the three models every output names
ISOTHERMAL, CENTRIFUGAL, HEAT_BALANCE = ("isothermal, cold clearance", "centrifugal growth",
                                         "heat balance + growth")
KELVIN = 273.15


@dataclass(frozen=True)
class RunningSpec:
    """One bearing's inputs to the clearance at speed (SI): the bearing's radius R, length L,
    cold clearance c₀ [m], viscosity μ_ref [Pa s] (at the network's viscosity temperature),
    ambient pressure p_a [Pa], and the ``[journal]`` and ``[thermal]`` tables (None: not
    stated)."""

    radius: float
    length: float
    cold_clearance: float
    viscosity: float
    ambient_pressure: float
    journal: Optional[JournalMaterial] = None
    thermal: Optional[ThermalNetwork] = None

    def __post_init__(self) -> None:
        if self.journal is not None:
            self.journal.check(self.radius)
        if self.thermal is not None:
            if self.journal is None:
                raise ParameterError("thermal", "[thermal]", "needs a [journal] table (the "
                                     "journal's thermal growth needs its material)")
            if self.journal.expansion_coefficient is None:
                raise ParameterError("journal.expansion_coefficient", None, "is required "
                                     "with a [thermal] table (the journal's thermal growth "
                                     "α r ΔT needs it)")
            self.thermal.check()
            # without the side leakage, which vanishes with the film's pressure
            self.thermal.conductances(self.radius, self.length, self.cold_clearance,
                                      0.0).check_connected()

    @property
    def model_name(self) -> str:
        """Which model is used: isothermal, centrifugal growth, or heat balance + growth."""
        if self.thermal is not None:
            return HEAT_BALANCE
        return CENTRIFUGAL if self.journal is not None else ISOTHERMAL

    @property
    def ambient_k(self) -> float:
        return self.thermal.ambient_temperature if self.thermal is not None else math.nan

    def centrifugal(self, omega: float) -> float:
        """The journal's centrifugal growth u_c [m] at ω [rad/s] (0 without [journal])."""
        j = self.journal
        if j is None or omega == 0.0:
            return 0.0
        return centrifugal_growth(omega, self.radius, j.inner_radius, j.density,
                                  j.youngs_modulus, j.poisson_ratio)

    def thermal_growths(self, journal_k: float, sleeve_k: float) -> tuple[float, float]:
        """(journal growth, sleeve bore growth) [m] at those temperatures [K]."""
        t = self.thermal
        if t is None:
            return 0.0, 0.0
        return (thermal_growth(self.journal.expansion_coefficient, self.radius,
                               journal_k - t.reference_k),
                thermal_growth(t.sleeve_expansion_coefficient,
                               self.radius + self.cold_clearance, sleeve_k - t.reference_k))

    def viscosity_at(self, film_k: float) -> float:
        """μ(T_f) [Pa s]: Sutherland through the stated viscosity (constant without
        [thermal])."""
        t = self.thermal
        if t is None:
            return self.viscosity
        return float(sutherland_viscosity(film_k, self.viscosity, t.viscosity_k,
                                          t.sutherland_constant))

    def petroff_power(self, omega: float, viscosity: float, clearance: float) -> float:
        """2π μ ω² R³ L / c [W]: Petroff's power of the concentric journal."""
        return 2.0 * math.pi * viscosity * omega**2 * self.radius**3 * self.length / clearance


@dataclass(frozen=True)
class DragSample:
    """What one static solve at a running state tells the fixed point: the drag power [W],
    the torque ratio τ [-] and the non-dimensional side outflow q̄ [-] at clearance c [m],
    viscosity μ [Pa s] and film temperature T_f [K]; ``solution`` the solve's own answer;
    ``speed_rpm`` the speed it was solved at (NaN: not stated; a prior of another speed
    then seeds τ only, without entering the secant in ln Λ)."""

    power_w: float
    torque_ratio: float
    outflow: float
    clearance: float
    viscosity: float
    film_k: float
    solution: object = field(default=None, repr=False, compare=False)
    speed_rpm: float = math.nan

    def solved_torque(self) -> bool:
        """True when τ is the solve's own (not changed after it, e.g. extrapolated)."""
        own = getattr(self.solution, "torque_ratio", None)
        return own is None or own == self.torque_ratio

    def leakage_flow(self, spec: RunningSpec) -> float:
        """Side-leakage mass flow ṁ_l = q̄ p_a² c³/(12 μ R_g T_f) [kg/s]."""
        if self.outflow == 0.0 or spec.thermal is None:
            return 0.0
        return (self.outflow * spec.ambient_pressure**2 * self.clearance**3
                / (12.0 * self.viscosity * spec.thermal.gas_constant * self.film_k))


#: a static solve: (speed [rpm], clearance [m], viscosity [Pa s], film temperature [K]) →
#: DragSample, or None when the film has no equilibrium there
DragFunction = Callable[[float, float, float, float], Optional[DragSample]]


@dataclass(frozen=True)
class RunningPoint:
    """The running condition at one speed (SI; temperatures in K inside, °C in
    :meth:`to_dict`).  ``status``: "running" (converged), "runaway" (no fixed point, or the
    clearance closes with the heat balance) or "closure" (the journal reaches the foil from
    its centrifugal growth alone)."""

    speed_rpm: float
    model: str
    status: str
    message: str
    cold_clearance: float
    running_clearance: float
    centrifugal_growth: float
    journal_thermal_growth: float = 0.0
    sleeve_thermal_growth: float = 0.0
    viscosity: float = math.nan
    network: Optional[NetworkState] = None
    side_leakage_flow: float = 0.0
    static_solves: int = 0
    sample: Optional[DragSample] = field(default=None, repr=False, compare=False)
    reason: str = ""                   # why there is no running state (status not "running")

    @property
    def converged(self) -> bool:
        return self.status == "running"

    @property
    def thermal_growth(self) -> float:
        """Net thermal closing of the clearance [m]: journal growth − sleeve bore growth."""
        return self.journal_thermal_growth - self.sleeve_thermal_growth

    def to_dict(self) -> dict:
        """The columns every output reports (gfbopt/terms/thermal.py).  Without a running
        state (runaway, closure) the clearance, the thermal growths, temperatures and heat
        flows are NaN (null in JSON; ``thermal_message`` says why); the centrifugal growth,
        a function of the speed alone, is kept."""
        n = self.network if self.converged else None
        state = 1.0 if self.converged else math.nan

        def c(kelvin):
            return kelvin - KELVIN if n is not None else math.nan

        return {
            "speed_rpm": self.speed_rpm,
            "thermal_model": self.model, "thermal_status": self.status,
            "thermal_message": self.message,
            "cold_clearance_um": self.cold_clearance * 1e6,
            "running_clearance_um": self.running_clearance * 1e6 * state,
            "centrifugal_growth_um": self.centrifugal_growth * 1e6,
            "thermal_growth_um": self.thermal_growth * 1e6 * state,
            "journal_thermal_growth_um": self.journal_thermal_growth * 1e6 * state,
            "sleeve_thermal_growth_um": self.sleeve_thermal_growth * 1e6 * state,
            "viscosity_pa_s": self.viscosity * state,
            "film_temperature_c": c(n.film_k) if n else math.nan,
            "journal_temperature_c": c(n.journal_k) if n else math.nan,
            "foil_temperature_c": c(n.foil_k) if n else math.nan,
            "sleeve_temperature_c": c(n.sleeve_k) if n else math.nan,
            "cooling_outlet_temperature_c": c(n.cooling_outlet_k) if n else math.nan,
            "heat_generated_w": n.power_w if n else math.nan,
            "heat_to_shaft_w": n.to_shaft_w if n else math.nan,
            "heat_to_housing_w": n.to_housing_w if n else math.nan,
            "heat_to_cooling_w": n.to_cooling_w if n else math.nan,
            "heat_to_side_leakage_w": n.to_side_leakage_w if n else math.nan,
            "side_leakage_kg_s": self.side_leakage_flow if n else math.nan,
            "thermal_static_solves": self.static_solves}


def _rpm_to_omega(speed_rpm: float) -> float:
    if not speed_rpm >= 0 or not math.isfinite(speed_rpm):
        raise ParameterError("speed_rpm", speed_rpm, "must be a finite speed >= 0 [rpm]")
    return speed_rpm * 2.0 * math.pi / 60.0


def without_heat(spec: RunningSpec, speed_rpm: float) -> RunningPoint:
    """The running point of a bearing without [thermal]: the cold clearance less the
    centrifugal growth (none without [journal]); no static solve."""
    uc = spec.centrifugal(_rpm_to_omega(speed_rpm))
    c = spec.cold_clearance - uc
    status, message = "running", ""
    if c <= MIN_RUNNING_CLEARANCE:
        status = "closure"
        close, full = closure_speeds(spec, speed_rpm, uc)
        message = (f"the journal reaches the foil from {close:,.0f} rpm: its centrifugal "
                   f"growth leaves the {MIN_RUNNING_CLEARANCE * 1e6:g} µm floor of the "
                   f"running clearance there and equals the whole "
                   f"{spec.cold_clearance * 1e6:.4g} µm clearance at {full:,.0f} rpm "
                   f"(centrifugal growth {uc * 1e6:.3g} µm of a "
                   f"{spec.cold_clearance * 1e6:.3g} µm clearance at {speed_rpm:,.0f} rpm)")
        return RunningPoint(speed_rpm, spec.model_name, status, message, spec.cold_clearance,
                            math.nan, uc, viscosity=spec.viscosity, reason=message)
    return RunningPoint(speed_rpm, spec.model_name, status, message, spec.cold_clearance, c,
                        uc, viscosity=spec.viscosity)


def closure_speeds(spec: RunningSpec, speed_rpm: float, growth: float) -> tuple:
    """(the speed where the running clearance c₀ − u_c falls to
    :data:`MIN_RUNNING_CLEARANCE`, the speed where u_c = c₀) [rpm], from the centrifugal
    growth ``growth`` [m] at ``speed_rpm``: u_c ∝ ω² (a linear-elastic spinning cylinder,
    :func:`gfbopt.thermal.growth.centrifugal_growth`), so each is speed·√(gap/u_c)."""
    if not growth > 0:
        return math.inf, math.inf
    c0 = spec.cold_clearance
    return (speed_rpm * math.sqrt(max(c0 - MIN_RUNNING_CLEARANCE, 0.0) / growth),
            speed_rpm * math.sqrt(c0 / growth))


def running_point(spec: RunningSpec, speed_rpm: float, drag: DragFunction, *,
                  prior: Optional[DragSample] = None, tolerance_k: float = 1e-2,
                  max_solves: int = 8) -> RunningPoint:
    """The fixed point at ``speed_rpm`` [rpm] (module docstring).  ``drag`` solves the film
    at a running state; ``prior`` (e.g. the previous speed's last sample, or a tuple of the
    last samples of the speeds below, oldest first) seeds τ and q̄ (the last one's), and the
    priors solved at a stated speed with their own τ start the secant in ln Λ (the torque
    model's line through the last two of them gives the first solve's τ), so that the first
    solve is already near the answer.  Without [thermal]:
    :func:`without_heat`.  Counts the static solves in ``static_solves``."""
    cold = without_heat(spec, speed_rpm)
    if spec.thermal is None or not cold.converged:
        return cold                     # no heat balance, or closed by the speed alone
    omega = _rpm_to_omega(speed_rpm)
    t = spec.thermal
    sampled_k: Optional[float] = None              # film temperature of our last solve
    solves, rootless, samples = 0, 0, []
    # (ln Λ, τ) of the solves the torque model is fitted to: the prior's, when it was solved
    # at a stated speed with its own τ, then this point's
    priors = () if prior is None else (tuple(prior) if isinstance(prior, (tuple, list))
                                        else (prior,))
    prior = priors[-1] if priors else None
    history = [(float(log_bearing_number(spec, _rpm_to_omega(p.speed_rpm), p.viscosity,
                                         p.clearance)), p.torque_ratio)
               for p in priors if math.isfinite(p.speed_rpm) and p.solved_torque()]
    sample = prior if prior is not None else DragSample(
        1.0, 1.0, 0.0, spec.cold_clearance, spec.viscosity, t.ambient_temperature)
    while True:
        g = t.conductances(spec.radius, spec.length, spec.cold_clearance,
                           sample.leakage_flow(spec))
        balance = _Balance(spec, omega, _torque_model(history, sample.torque_ratio,
                                                      curved=len(samples) >= 2), g)
        power, closest = balance.lowest_root()
        if power is None:               # solve where F comes closest to 0, then decide
            rootless += 1
            if rootless >= 2 and len(samples) >= 2:
                return _runaway(cold, balance, closest, solves, sample)
            power = closest
        else:
            rootless = 0
        state = _state(spec, speed_rpm, balance, power, g, sample)
        if omega == 0.0:                # no drag at rest: the network at P = 0
            return state
        if not rootless and sampled_k is not None and \
                abs(state.network.film_k - sampled_k) <= tolerance_k:
            return replace(state, static_solves=solves)
        if solves >= max_solves:
            return _runaway(cold, balance, power, solves, sample,
                            why=f"the heat balance did not converge in {max_solves} static "
                            "solves")
        new = drag(speed_rpm, state.running_clearance, state.viscosity,
                   state.network.film_k)
        solves += 1
        if new is None:
            return _runaway(cold, balance, power, solves, sample,
                            why="the film has no equilibrium at the heated clearance")
        samples.append(new)
        history.append((float(log_bearing_number(spec, omega, new.viscosity, new.clearance)),
                        new.torque_ratio))
        sample, sampled_k = new, state.network.film_k


def _torque_model(history: list, seed: float, curved: bool = False) -> Callable:
    """τ(ln Λ): the seed before any solve, the one solve's τ after one, and after two the
    line through the last two solves' (ln Λ, τ) — the local deviation of the drag from
    Petroff's μ/c scaling as a function of the bearing number, which makes the iteration a
    secant method (clipped to τ > 0).  ``history`` may start with priors solved at other
    speeds under the same load: τ depends on the speed, μ and c through Λ (the compliance
    S ∝ 1/c aside), so their points lie near the same curve and the first update is already
    a secant step.  ``curved`` (two solves of this point or more): the parabola through
    the last three points instead (its third point a prior or an earlier solve), whose
    error is of third order in the spacing — near a thermal runaway the fixed point's film
    temperature moves by ~2,000 K per unit of τ, so the line's second-order error decides
    whether a third solve is the last."""
    if not history:
        return lambda log_lambda: seed
    xb, tb = history[-1]
    if len(history) < 2 or history[-2][0] == xb:
        return lambda log_lambda: tb
    xa, ta = history[-2]
    slope = (tb - ta) / (xb - xa)
    floor = 1e-3 * min(t for _, t in history[-3:])
    if curved and len(history) >= 3 and len({x for x, _ in history[-3:]}) == 3:
        x0, t0 = history[-3]
        bend = (slope - (ta - t0) / (xa - x0)) / (xb - x0)     # second divided difference
        return lambda log_lambda: np.maximum(
            tb + (log_lambda - xb) * (slope + bend * (log_lambda - xa)), floor)
    return lambda log_lambda: np.maximum(tb + slope * (log_lambda - xb), floor)


def _state(spec: RunningSpec, speed_rpm: float, balance: _Balance, power: float,
           g: Conductances, sample: DragSample) -> RunningPoint:
    t = spec.thermal
    network = solve_network(power, g, t.ambient_temperature, t.inlet_k, balance.capacity)
    c, gj, gs = balance.clearance(power)
    return RunningPoint(speed_rpm, spec.model_name, "running", "", spec.cold_clearance, c,
                        balance.uc, gj, gs, spec.viscosity_at(network.film_k), network,
                        sample.leakage_flow(spec), 0, sample)


def _runaway(base: RunningPoint, balance: _Balance, closest: float, solves: int,
             sample: DragSample, why: str = "") -> RunningPoint:
    c = balance.clearance(closest)[0]
    top, kind = balance.top()
    t = balance.spec.thermal
    film = (f"film above {t.film_limit_k - KELVIN:.0f} °C: no fixed point below it, "
            f"{t.film_limit_source}")
    if why:
        reason = why
    elif kind == "film" and c > MIN_RUNNING_CLEARANCE * (1 + 1e-6):
        reason = film
    elif c <= MIN_RUNNING_CLEARANCE * (1 + 1e-6):
        reason = "the clearance closes"
    else:
        reason = ("no fixed point: the drag power grows faster with temperature than the "
                  "network carries it away")
    return replace(base, status="runaway", running_clearance=math.nan,
                   message=f"thermal runaway at {base.speed_rpm:.6g} rpm ({reason})",
                   reason=reason, static_solves=solves, sample=sample)


@dataclass(frozen=True)
class SpeedLine:
    """Running points over a speed range, and the first speed where there is none."""

    points: tuple
    limit_rpm: float = math.nan           # first failing speed (NaN: none in the range)
    limit_low_rpm: float = math.nan       # the last good speed below it
    limit_kind: str = ""                  # "runaway" or "closure"
    limit_reason: str = ""                # the failing point's reason

    @property
    def message(self) -> str:
        if not math.isfinite(self.limit_rpm):
            return ""
        bracket = (f"bracketed in [{self.limit_low_rpm:,.0f}, {self.limit_rpm:,.0f}] rpm")
        if self.limit_kind == "closure":     # closed form (closure_speeds): exact
            return self.limit_reason or f"the journal reaches the foil from " \
                f"{self.limit_rpm:,.0f} rpm ({bracket})"
        return (f"thermal runaway from {self.limit_rpm:,.0f} rpm ({bracket}"
                + (f"; {self.limit_reason}" if self.limit_reason else "") + ")")


def speed_line(spec: RunningSpec, speeds_rpm, drag: DragFunction, *,
               bracket: float = 0.005, **kwargs) -> SpeedLine:
    """Running points at increasing ``speeds_rpm``, each seeded by the two below; at the
    first failure, the limit speed is bracketed by bisection to ``bracket`` (relative); a
    closure by the centrifugal growth alone is found in closed form
    (:func:`closure_speeds`), a closure or runaway of the heat balance by bisection.  The
    last point is the first failing one's (at the speed asked)."""
    points, priors = [], ()
    speeds = sorted(float(s) for s in speeds_rpm)

    def seeded(priors, point):           # the last two converged samples, oldest first
        return (priors + (point.sample,))[-2:] if point.sample is not None else priors

    for k, speed in enumerate(speeds):
        point = running_point(spec, speed, drag, prior=priors or None, **kwargs)
        points.append(point)
        if not point.converged:
            low = speeds[k - 1] if k else 0.0
            high, failing = speed, point
            low = low if without_heat(spec, low).converged else 0.0
            cold = without_heat(spec, speed)
            if cold.status == "closure":    # closed form; the heat balance may fail below
                close = closure_speeds(spec, speed, cold.centrifugal_growth)[0]
                high = min(speed, max(close * (1 + 1e-12), low))
                failing = without_heat(spec, high)
            while high - low > bracket * high:
                mid = 0.5 * (low + high)
                trial = running_point(spec, mid, drag, prior=priors or None, **kwargs)
                if trial.converged:
                    low, priors = mid, seeded(priors, trial)
                else:
                    high, failing = mid, trial
            return SpeedLine(tuple(points), high, low, failing.status,
                             failing.reason)
        priors = seeded(priors, point)
    return SpeedLine(tuple(points))
