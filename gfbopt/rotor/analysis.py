"""Is my rotor stable, and by how much: the linear stability of a rigid rotor in SI units.

The engineer's question — "2 kg per bearing, 20 N per bearing, 45,000 rpm on this bearing: is
it stable, with what margin?" — is answered on the non-dimensional linear model
(:mod:`gfbopt.linear`): the bearing at the speed gives Λ, the load W̄0 = W0/(p_a R²), the rotor
M̄ = M c ω²/W0, and the threshold M̄c(Λ, W̄0) decides (rotors with M̄ < M̄c are stable).  Every
SI ↔ non-dimensional conversion goes through :mod:`gfbopt.inputs.conversions`.

Per bearing: M is the rotor mass one bearing carries and W0 the static load on it
(docs/PHYSICS.md §2); a horizontal rigid rotor loaded by gravity alone has W0 = M g.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Optional, Union

from ..errors import ConvergenceError, ParameterError
from ..inputs.bearing import BearingGeometry
from ..inputs.conversions import (film_thickness_um, growth_rate_per_second,
                                  logarithmic_decrement, mass_from_parameter, mass_parameter,
                                  rpm_to_rad_per_s, whirl_frequency_hz)
from ..inputs.grid import DEFAULT_GRID, Grid, as_grid
from ..inputs.model import BearingModel
from ..inputs.options import ModelOptions, merge_options
from ..inputs.rotor import OperatingPoint, Rotor
from ..linear import (STABILITY_TOLERANCE, Linearisation, LinearThreshold, least_stable_mode,
                      linear_threshold, linearise)
from ..static import SolverCache, StaticSolution, solve_static
from ..threads import single_threaded


@dataclass(frozen=True)
class Case:
    """A resolved stability problem: bearing, rotor, load and the options actually used."""

    bearing: BearingGeometry
    rotor: Rotor
    load_newton: float
    load_source: str
    options: ModelOptions
    grid: Grid
    cache: SolverCache = field(repr=False, compare=False)

    def model(self, speed_rpm: float) -> BearingModel:
        """The non-dimensional model of the bearing at ``speed_rpm`` [rpm]."""
        return self.bearing.model(speed_rpm, **self.options.model_kwargs())

    @property
    def load(self) -> float:
        """W̄0 = W0/(p_a R²) [-]."""
        return self.bearing.nondimensional_load(self.load_newton)

    def mass_parameter(self, speed_rpm: float) -> float:
        """M̄ = M c ω²/W0 of the rotor at ``speed_rpm`` [-]."""
        return mass_parameter(self.rotor.mass_kg, self.bearing.radial_clearance,
                              rpm_to_rad_per_s(speed_rpm), self.load_newton)

    def mass_kg(self, mass_parameter_value: float, speed_rpm: float) -> float:
        """M [kg] of a mass parameter M̄ at ``speed_rpm`` (inverse of :meth:`mass_parameter`)."""
        return mass_from_parameter(mass_parameter_value, self.bearing.radial_clearance,
                                   rpm_to_rad_per_s(speed_rpm), self.load_newton)

    def conventions(self) -> dict:
        """The options used, as every output states them."""
        built = {} if self.bearing.build is None else self.bearing.build.describe()
        # the compliance solved: S = 0 for the rigid foil (BearingGeometry.model's rule)
        solved = 0.0 if self.options.foil == "rigid" else self.bearing.compliance
        return {**self.options.to_dict(), "compliance": solved,
                "length_ratio": self.bearing.length_ratio, "grid": str(self.grid),
                "load_source": self.load_source, **built}


def resolve_case(bearing: BearingGeometry, rotor: Rotor, load_newton: Optional[float], *,
                 film: Optional[str] = None, seam_angle_deg: Union[float, str, None] = None,
                 foil: Optional[str] = None, deflection_law: Optional[str] = None,
                 loss_factor: Optional[float] = None, options: Optional[ModelOptions] = None,
                 grid: Grid = DEFAULT_GRID, cache: Optional[SolverCache] = None,
                 seam_angle=None) -> Case:
    """Check every input and fill the options: stated here, else ``options``, else the
    bearing's own (``bearing.options``: its file's ``[model]`` table), else the defaults
    (:func:`~gfbopt.inputs.options.merge_options`) — the one resolution every route uses.
    ``seam_angle`` (radians in gfbopt <= 0.2) is refused with the conversion to
    ``seam_angle_deg``.  Raises ParameterError before any solver is built."""
    if seam_angle is not None:
        from ..inputs.checks import seam_angle_migration

        raise ParameterError("seam_angle", seam_angle, seam_angle_migration(seam_angle))
    if not isinstance(bearing, BearingGeometry):
        raise ParameterError("bearing", bearing, "must be a BearingGeometry (SI)")
    if not isinstance(rotor, Rotor):
        raise ParameterError("rotor", rotor, "must be a Rotor (mass per bearing in kg)")
    grid = as_grid(grid)
    point = OperatingPoint(1.0, load_newton)          # validates the load
    if options is not None and not isinstance(options, ModelOptions):
        raise ParameterError("options", options, "must be ModelOptions")
    stated = ModelOptions(film=film, seam_angle_deg=seam_angle_deg, foil=foil,
                          deflection_law=deflection_law, loss_factor=loss_factor)
    resolved = merge_options(stated, bearing.options if options is None else options)
    case = Case(bearing, rotor, point.load_on(rotor), point.load_source(), resolved, grid,
                cache if cache is not None else SolverCache(grid))
    case.model(1000.0)                                 # validates the combination (e.g. η, foil)
    return case


class LoadCapacityError(ParameterError):
    """The static load exceeds what the bearing carries at this speed (no equilibrium)."""


@single_threaded
def equilibrium(case: Case, speed_rpm: float,
                initial: Optional[StaticSolution] = None) -> StaticSolution:
    """The static equilibrium under W0 at ``speed_rpm``; :class:`LoadCapacityError` (with the
    largest load that converged, found by a short continuation) if there is none."""
    model = case.model(speed_rpm)
    solver = case.cache(model, case.grid)
    sol = solve_static(model, load=case.load, solver=solver, initial=initial)
    if not sol.success and initial is not None:      # a warm start may mislead: retry cold
        sol = solve_static(model, load=case.load, solver=solver)
    if sol.success:
        return sol
    largest = largest_converged_load(model, case.load, solver)
    raise LoadCapacityError("load_newton", case.load_newton, capacity_rule(
        speed_rpm, case.bearing.load_newton(largest) if largest > 0 else 0.0,
        case.bearing.load_newton(case.load / 64)))


def capacity_rule(speed_rpm: Optional[float], largest: float, lowest: float,
                  unit: str = "N") -> str:
    """The rule of a load the bearing cannot carry: the largest load that converged
    (``largest``, 0 when none did down to ``lowest``, in ``unit``) — one sentence for every
    command that refuses such a load."""
    at = f" ({speed_rpm:.6g} rpm)" if speed_rpm is not None else ""
    unit = f" {unit}" if unit else ""
    if largest > 0:
        return (f"load exceeds the load capacity at this speed{at}: the largest load that "
                f"converged is {largest:.4g}{unit}")
    return (f"load exceeds the load capacity at this speed{at}: no load down to "
            f"{lowest:.3g}{unit} converged")


@single_threaded
def largest_converged_load(model: BearingModel, load: float, solver, steps: int = 6) -> float:
    """The largest W̄ ≤ ``load`` [-] with a converged equilibrium, by a short continuation:
    from W̄/64 up by factors of 2 with warm starts, then ``steps`` bisections between the last
    load that converged and the first that did not.  0.0 if none converged."""
    good, sol = 0.0, None
    trial = load / 64
    while trial < load:
        attempt = solve_static(model, load=trial, solver=solver, initial=sol,
                               continuation=sol is None)
        if not attempt.success:
            break
        good, sol = trial, attempt
        trial *= 2
    if sol is None:
        return 0.0
    bad = min(trial, load)
    for _ in range(steps):
        middle = 0.5 * (good + bad)
        attempt = solve_static(model, load=middle, solver=solver, initial=sol,
                               continuation=False)
        if attempt.success:
            good, sol = middle, attempt
        else:
            bad = middle
    return good


@single_threaded
def threshold_at(case: Case, speed_rpm: float, initial: Optional[StaticSolution] = None,
                 **threshold_options) -> tuple[StaticSolution, Linearisation, LinearThreshold]:
    """(equilibrium, linearisation, linear threshold) at ``speed_rpm`` [rpm]."""
    sol = equilibrium(case, speed_rpm, initial)
    lin = linearise(sol, case.cache(sol.model, case.grid))
    return sol, lin, linear_threshold(lin, **threshold_options)


# ---------------------------------------------------------------------------- result
#: the result's attribute → its name in every dict/JSON/CSV edge (gfbopt.glossary)
GLOSSARY_NAMES = {"load_parameter": "load", "mass_parameter": "mass",
                  "critical_mass_parameter": "critical_mass"}


@dataclass(frozen=True)
class StabilityResult:
    """The linear stability of a rigid rotor at one operating point (SI, per bearing).

    stable : True when the rotor is linearly stable (M̄ < M̄c and no growing mode)
    critical_mass_kg : rotor mass per bearing at the threshold [kg] (inf: stable for every
        mass; 0: unstable for every mass)
    mass_margin : M_crit/M − 1 [-] (> 0 stable; e.g. 0.25 = 25 % more mass would whirl)
    whirl_frequency_hz : whirl frequency of the least-stable mode at this mass [Hz]
    growth_rate_per_s : its growth rate [1/s] (> 0 unstable)
    log_decrement : its logarithmic decrement per whirl cycle [-] (> 0 stable)
    threshold_whirl_frequency_hz : whirl frequency at the threshold (mass M_crit) [Hz]
    eccentricity [-], attitude_angle_deg [deg], min_film_thickness_um [µm]: the equilibrium
    bearing_number Λ [-], load_parameter W̄0 = W0/(p_a R²) [-], mass_parameter M̄ = M c ω²/W0
    [-], critical_mass_parameter M̄c [-], threshold_whirl_ratio γc [-], mode_whirl_ratio [-],
    growth_rate [per radian of shaft rotation]
    speed_rpm, load_newton [N], rotor_mass_kg [kg], conventions (the options used)
    success, message, wall_time_s [s]
    warnings : plausibility flags, each one sentence with the limit it breaks
        (:func:`plausibility`): a film thinner than :data:`MIN_FILM_UM`, a load above the
        rule-of-thumb capacity of the best bump-foil bearings, a least-damped mode whirling
        above running speed.  Empty when nothing looks doubtful.
    """

    stable: bool
    critical_mass_kg: float
    mass_margin: float
    whirl_frequency_hz: float
    growth_rate_per_s: float
    log_decrement: float
    threshold_whirl_frequency_hz: float
    eccentricity: float
    attitude_angle_deg: float
    min_film_thickness_um: float
    bearing_number: float
    load_parameter: float
    mass_parameter: float
    critical_mass_parameter: float
    threshold_whirl_ratio: float
    mode_whirl_ratio: float
    growth_rate: float
    speed_rpm: float
    load_newton: float
    rotor_mass_kg: float
    conventions: dict
    success: bool
    message: str
    wall_time_s: float
    linearisation: Optional[Linearisation] = field(default=None, repr=False, compare=False)
    warnings: tuple = ()

    @property
    def verdict(self) -> str:
        return "stable" if self.stable else "unstable"

    def to_dict(self) -> dict:
        """Every field but the linearisation, plus ``verdict`` (JSON-ready; inf stays inf),
        the non-dimensional groups under the glossary's names (``load``, ``mass``,
        ``critical_mass``: :data:`GLOSSARY_NAMES`), as the command line's JSON and the
        studies' tables name them."""
        out = {GLOSSARY_NAMES.get(k, k): getattr(self, k) for k in self.__dataclass_fields__
               if k != "linearisation"}
        out["verdict"] = self.verdict
        out["warnings"] = list(self.warnings)
        return out


#: a minimum film thinner than this is flagged [µm]: the order of the surface roughness,
#: foil manufacturing tolerances and thermal/centrifugal growth of a foil bearing, where the
#: smooth-film model is doubtful (the limit the bump design study uses too)
MIN_FILM_UM = 5.0
#: load capacity coefficient of the rule of thumb W = D (L D)(D N) [lbf/(in³ krpm)], with L and
#: D in inches and N in krpm (DellaCorte, C. & Valco, M. J. (2000), Load capacity estimation
#: of foil air journal bearings for oil-free turbomachinery applications, Tribol. Trans.
#: 43(4):795–801, NASA/TM-2000-209782): about 1 for the best (third-generation) bump-foil
#: bearings, 0.1–0.5 for earlier ones.  A load above it with D = 1 is flagged: even the best
#: bearings of this size are not known to carry it at this speed.
CAPACITY_COEFFICIENT = 1.0
#: the rule of thumb's unit in SI: 1 lbf/(in³ krpm) in N/(m³ rpm)
_LBF_PER_IN3_KRPM = 4.4482216152605 / 0.0254**3 / 1000.0


def rule_of_thumb_capacity_newton(bearing: BearingGeometry, speed_rpm: float,
                                  coefficient: float = CAPACITY_COEFFICIENT) -> float:
    """W = D (L D)(D N) [N]: DellaCorte & Valco's load capacity of a foil journal bearing of
    length L and diameter D [m] at N [rpm] (:data:`CAPACITY_COEFFICIENT`)."""
    diameter = 2.0 * bearing.radius
    return (coefficient * _LBF_PER_IN3_KRPM * bearing.length * diameter * diameter
            * speed_rpm)


def plausibility(case: Case, sol: StaticSolution, speed_rpm: float,
                 mode_whirl_ratio: float) -> tuple:
    """Flags on a result an engineer would question (see :class:`StabilityResult`): a film
    thinner than :data:`MIN_FILM_UM`, a load above the rule-of-thumb capacity of the best
    bump-foil bearings (:func:`rule_of_thumb_capacity_newton`; the model itself still finds an
    equilibrium far beyond it, the foil deflecting by several clearances), a least-damped mode
    above running speed."""
    flags = []
    film = film_thickness_um(sol.min_film, case.bearing.radial_clearance)
    if film < MIN_FILM_UM:
        flags.append(f"minimum film h_min = {film:.3g} µm is below {MIN_FILM_UM:g} µm: the "
                     "order of surface roughness, foil tolerances and thermal/centrifugal "
                     "growth, where the smooth-film model is doubtful")
    capacity = rule_of_thumb_capacity_newton(case.bearing, speed_rpm)
    if case.load_newton > capacity:
        flags.append(f"load W0 = {case.load_newton:.4g} N is above the rule-of-thumb load "
                     f"capacity of the best bump-foil bearings at {speed_rpm:.6g} rpm, "
                     f"D (L D)(D N) = {capacity:.4g} N with D = {CAPACITY_COEFFICIENT:g} "
                     "lbf/(in³ krpm) (DellaCorte & Valco 2000)")
    if math.isfinite(mode_whirl_ratio) and mode_whirl_ratio > 1.0:
        flags.append(f"the least-damped mode whirls above running speed (whirl ratio "
                     f"{mode_whirl_ratio:.3g}): a rigid-rotor mode; a real rotor's flexible "
                     "modes in that range are not modelled")
    return tuple(flags)


@single_threaded
def stability(bearing: BearingGeometry, rotor: Rotor, operating_point: OperatingPoint, *,
              film: Optional[str] = None, seam_angle_deg: Union[float, str, None] = None,
              foil: Optional[str] = None, deflection_law: Optional[str] = None,
              loss_factor: Optional[float] = None, options: Optional[ModelOptions] = None,
              grid: Grid = DEFAULT_GRID, cache: Optional[SolverCache] = None,
              initial: Optional[StaticSolution] = None, seam_angle=None) -> StabilityResult:
    """Is the rotor stable at this operating point, and with what margin?

    Parameters
    ----------
    bearing : the bearing in SI (:class:`~gfbopt.inputs.bearing.BearingGeometry`)
    rotor : the rotor mass per bearing (:class:`~gfbopt.inputs.rotor.Rotor`) [kg]
    operating_point : speed [rpm] and static load per bearing [N] (None: W0 = M g)
    film, seam_angle_deg, foil, deflection_law, loss_factor : formulation options; None means
        not stated, and then ``options``, else ``bearing.options`` (the bearing file's
        ``[model]`` table, as ``gfbopt stability --bearing FILE`` uses it), else the default
        of :func:`~gfbopt.inputs.options.resolve_model_options` applies (a seam with the
        welded end 180° from the load).  seam_angle_deg [deg] in [0, 360), or 'max_film'
        (the old radian keyword ``seam_angle`` is refused).
    grid : the finite-difference grid; cache : a :class:`~gfbopt.static.SolverCache` to reuse
        builds across calls; initial : a previous equilibrium to warm-start from

    Returns
    -------
    StabilityResult.  The verdict is the linear one: unstable when M̄ ≥ M̄c or when the
    least-stable mode at M̄ grows.  A load the bearing cannot carry at this speed raises
    :class:`LoadCapacityError` (a ParameterError) with the largest load that converged.
    """
    t0 = time.perf_counter()
    if not isinstance(operating_point, OperatingPoint):
        raise ParameterError("operating_point", operating_point,
                             "must be an OperatingPoint (speed in rpm, load in N)")
    case = resolve_case(bearing, rotor, operating_point.load_newton, film=film,
                        seam_angle_deg=seam_angle_deg, seam_angle=seam_angle, foil=foil, deflection_law=deflection_law,
                        loss_factor=loss_factor, options=options, grid=grid, cache=cache)
    return assess(case, operating_point.speed_rpm, initial, t0)


@single_threaded
def assess(case: Case, speed_rpm: float, initial: Optional[StaticSolution] = None,
           t0: Optional[float] = None) -> StabilityResult:
    """:func:`stability` for a resolved :class:`Case` at ``speed_rpm`` [rpm]."""
    t0 = time.perf_counter() if t0 is None else t0
    sol, lin, thr = threshold_at(case, speed_rpm, initial)
    omega = rpm_to_rad_per_s(speed_rpm)
    mbar, mcrit = case.mass_parameter(speed_rpm), thr.critical_mass
    notes = [thr.message] if thr.message else []
    try:
        mode = least_stable_mode(lin, mbar, thr)
        growth, whirl = mode.real, mode.imag
    except ConvergenceError as exc:
        growth, whirl = math.nan, math.nan
        notes.append(f"least-stable mode not found ({exc})")
    above = mbar >= mcrit
    growing = growth > STABILITY_TOLERANCE
    if math.isfinite(growth) and above != growing:
        notes.append(f"the threshold (M̄c = {mcrit:.4g}) and the least-stable mode at "
                     f"M̄ = {mbar:.4g} (growth rate {growth:.3g} per rad) disagree; the "
                     "verdict is 'unstable' if either says so")
    stable = not (above or growing)
    margin = mcrit / mbar - 1.0 if math.isfinite(mcrit) else math.inf
    return StabilityResult(
        stable=stable, critical_mass_kg=case.mass_kg(mcrit, speed_rpm), mass_margin=margin,
        whirl_frequency_hz=whirl_frequency_hz(whirl, omega),
        growth_rate_per_s=growth_rate_per_second(growth, omega),
        log_decrement=(logarithmic_decrement(growth, whirl) if whirl > 0 else math.nan),
        threshold_whirl_frequency_hz=whirl_frequency_hz(thr.whirl_ratio, omega),
        eccentricity=sol.eccentricity, attitude_angle_deg=sol.attitude_angle_deg,
        min_film_thickness_um=film_thickness_um(sol.min_film, case.bearing.radial_clearance),
        bearing_number=sol.model.bearing_number, load_parameter=case.load,
        mass_parameter=mbar, critical_mass_parameter=mcrit,
        threshold_whirl_ratio=thr.whirl_ratio, mode_whirl_ratio=whirl, growth_rate=growth,
        speed_rpm=speed_rpm, load_newton=case.load_newton, rotor_mass_kg=case.rotor.mass_kg,
        conventions=case.conventions(), success=bool(thr.success and math.isfinite(growth)),
        message="; ".join(notes), wall_time_s=time.perf_counter() - t0, linearisation=lin,
        warnings=plausibility(case, sol, speed_rpm, whirl))
