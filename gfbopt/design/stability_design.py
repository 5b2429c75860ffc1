"""Choose the bump foil for rotor stability: the compliance S that maximises the onset speed
of whirl, the band of near-best S under each foundation law and loss factor, and the bump
geometry that realises it.

With the simple elastic foundation the bearing's dynamics depend on the bump geometry only
through S = p_a α / c (Heshmat's compliance α = 2 s l0³ (1 − ν²)/(E t_b³)), so the search is
one-dimensional in S (:mod:`gfbopt.design.outer_search`), over the range of S the geometric
program says the bump foil can reach under the stress and manufacturing limits
(:func:`gfbopt.design.geometry_program.compliance_range`).  For every S the figure of merit is
the onset speed of instability of the rotor along its mass–speed line
(:func:`gfbopt.rotor.onset_speed`), subject to the minimum film thickness at the design load
and the film-check speed staying above a limit.  The search runs for every foundation law
(axial-mean, local) and loss factor η asked, because the answer depends on both
(docs/PHYSICS.md §6–§7): the tool reports the optimum of each as a band of S, maps the chosen S
to a geometry with the geometric program (least bump stress), compares with the baseline (the
bearing's own geometry), and confirms the chosen design with the nonlinear transient.

A stiffness change at fixed geometry ranges is made by the bump thickness alone when a trial S
is evaluated (t_b ∝ S^(−1/3) at fixed pitch and half length): the bearing's dynamics see only S,
so which geometry realises a trial S does not change its onset speed.

A bearing file stating ``[journal]``/``[thermal]`` (``running``) has every trial S evaluated
at the running clearance and viscosity of each speed, the baseline and the nonlinear check
too, through the functions ``gfbopt stability`` calls (:mod:`.running_evaluation`).
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from typing import Callable, Optional, Sequence

import numpy as np
import pandas as pd

from ..errors import ParameterError
from ..inputs.bearing import BearingGeometry
from ..inputs.checks import check_positive
from ..inputs.grid import Grid
from ..inputs.options import ModelOptions
from ..inputs.rotor import Rotor
from .outer_search import Evaluation, SearchResult, evaluations_frame, maximise_on_interval
from .spec import BumpDesignSpec

#: Relative width of the onset-speed band reported around each optimum [-]: 2 % of the best
#: onset speed, the order of the model's own uncertainty (grid error on the threshold ~0.2 %,
#: the foundation-law and film-convention choices move onsets by 10–30 %).
BAND = 0.02


@dataclass(frozen=True)
class StabilityDesignSpec:
    """What the designer gives (SI units; per bearing).

    bearing : the housing, clearance and baseline bump geometry
    rotor : rotor mass per bearing [kg]
    load_newton : static load per bearing W0 [N] (None: the rotor's weight M g)
    speed_range_rpm : (low, high) shaft speeds of the search for the onset [rpm]
    min_film_thickness_m : smallest admissible minimum film at the design load [m]
    film_check_speed_rpm : speed at which the film limit is checked [rpm] (default: the low
        end of the speed range, where the film is thinnest)
    geometry : the bump-foil limits and ranges (its clearance, ambient pressure, radius and
        material constants are taken from ``bearing`` when they differ)
    loss_factors : structural loss factors η to search [-]
    deflection_laws : foundation laws to search ('mean', 'local')
    options : film convention and foil options (:class:`~gfbopt.inputs.options.ModelOptions`)
    grid : finite-difference grid of every analysis
    n_scan : scan points of S per (law, η) before refinement
    running : the bearing file's :class:`~gfbopt.thermal.running.RunningSpec` when it states
        ``[journal]``/``[thermal]``: every S evaluated at the running condition of each
        speed (:mod:`.running_evaluation`); None (or the isothermal spec): the cold clearance
    """

    bearing: BearingGeometry
    rotor: Rotor
    load_newton: Optional[float]
    speed_range_rpm: tuple
    min_film_thickness_m: float
    geometry: BumpDesignSpec
    film_check_speed_rpm: Optional[float] = None
    loss_factors: tuple = (0.0, 0.1, 0.2, 0.3)
    deflection_laws: tuple = ("mean", "local")
    options: ModelOptions = field(default_factory=ModelOptions)
    grid: Grid = field(default_factory=lambda: Grid(72, 20))
    n_scan: int = 7
    running: Optional[object] = None

    def __post_init__(self) -> None:
        from .running_evaluation import heated

        if not heated(self.running):        # the isothermal spec is today's route
            object.__setattr__(self, "running", None)
        low, high = self.speed_range_rpm
        if not 0 < low < high:
            raise ParameterError("speed_range_rpm", self.speed_range_rpm,
                                 "must be increasing speeds > 0 [rpm]")
        check_positive("min_film_thickness_m", self.min_film_thickness_m)
        if self.min_film_thickness_m >= self.bearing.radial_clearance:
            raise ParameterError("min_film_thickness_m", self.min_film_thickness_m,
                                 f"must be below the radial clearance "
                                 f"{self.bearing.radial_clearance:g} m")
        for eta in self.loss_factors:
            if not 0.0 <= eta <= 1.0:
                raise ParameterError("loss_factors", eta, "must lie in [0, 1]")
        for law in self.deflection_laws:
            if law not in ("mean", "local"):
                raise ParameterError("deflection_laws", law, "must be 'mean' or 'local'")
        if self.options.foil == "rigid":
            raise ParameterError("options.foil", "rigid", "a rigid bearing has no bump foil "
                                 "to design; use 'simple'")
        object.__setattr__(self, "loss_factors", tuple(self.loss_factors))
        object.__setattr__(self, "deflection_laws", tuple(self.deflection_laws))
        # the GP must see the bearing's own clearance, ambient pressure, radius and material
        b = self.bearing
        object.__setattr__(self, "geometry", dataclasses.replace(
            self.geometry, radial_clearance=b.radial_clearance,
            ambient_pressure=b.ambient_pressure, radius=b.radius,
            youngs_modulus=b.bump_youngs_modulus, poisson_ratio=b.poisson_ratio))

    @property
    def check_speed(self) -> float:
        return self.film_check_speed_rpm or self.speed_range_rpm[0]


def bearing_with_compliance(bearing: BearingGeometry, compliance: float) -> BearingGeometry:
    """The bearing with its bump thickness changed so that S = ``compliance`` [-]
    (α ∝ t_b⁻³ at fixed pitch and half length)."""
    check_positive("compliance", compliance)
    thickness = bearing.bump_thickness * (bearing.compliance / compliance) ** (1.0 / 3.0)
    return dataclasses.replace(bearing, bump_thickness=thickness)


def evaluate_compliance(spec: StabilityDesignSpec, compliance: float, law: str, eta: float,
                        cache=None) -> dict:
    """Onset speed and minimum film of the rotor with compliance S under (law, η): one row.

    Failures (a load the bearing cannot carry, an unconverged solve) are a row with
    ``success = False`` and the message, never an exception.
    """
    from ..rotor import onset_speed, stability
    from ..inputs.rotor import OperatingPoint
    from ..static import SolverCache

    t0 = time.perf_counter()
    cache = cache if cache is not None else SolverCache(spec.grid)
    bearing = bearing_with_compliance(spec.bearing, compliance)
    opts = dataclasses.replace(spec.options, deflection_law=law, loss_factor=eta,
                               foil=spec.options.foil or "simple")
    row = {"compliance": compliance, "deflection_law": law, "loss_factor": eta}
    if spec.running is not None:         # at the running condition of each speed
        from .running_evaluation import evaluate_running
        try:
            found = evaluate_running(spec, bearing, opts, cache)
        except ParameterError as exc:
            return {**row, "onset_speed_rpm": math.nan, "min_film_thickness_um": math.nan,
                    "success": False, "message": str(exc),
                    "wall_time_s": time.perf_counter() - t0}
        return {**row, **geometry_columns(spec.geometry, compliance), **found,
                "wall_time_s": time.perf_counter() - t0}
    try:
        onset = onset_speed(bearing, spec.rotor, spec.load_newton, spec.speed_range_rpm,
                            options=opts, grid=spec.grid, cache=cache)
        if spec.check_speed == spec.speed_range_rpm[0]:
            film = _first_row(onset)
        else:
            film = stability(bearing, spec.rotor, OperatingPoint(spec.check_speed,
                                                                 spec.load_newton),
                             options=opts, grid=spec.grid, cache=cache)
    except ParameterError as exc:        # e.g. load beyond the capacity at this stiffness
        return {**row, "onset_speed_rpm": math.nan, "min_film_thickness_um": math.nan,
                "success": False, "message": str(exc), "wall_time_s": time.perf_counter() - t0}
    row.update(geometry_columns(spec.geometry, compliance))
    low, high = spec.speed_range_rpm
    if onset.stable_over_range:
        merit_speed = high
    elif onset.unstable_at_lower_end:
        merit_speed = low
    else:
        merit_speed = onset.onset_speed_rpm
    return {**row, "onset_speed_rpm": merit_speed,
            "stable_over_range": onset.stable_over_range,
            "unstable_at_lower_end": onset.unstable_at_lower_end,
            "onset_whirl_frequency_hz": onset.whirl_frequency_hz,
            "min_film_thickness_um": film.min_film_thickness_um,
            "mass_margin_at_check_speed": film.mass_margin,
            "success": bool(onset.success and film.success),
            "message": "; ".join(m for m in (film.message, onset.message) if m),
            "wall_time_s": time.perf_counter() - t0}


@dataclass(frozen=True)
class _FilmCheck:
    """The film check at the lowest speed of the range, read from the onset search's first
    scan row (the same cold equilibrium and full threshold :func:`gfbopt.rotor.stability`
    computes there; its least-stable mode is not needed by the design)."""

    min_film_thickness_um: float
    mass_margin: float
    success: bool
    message: str


def _first_row(onset) -> _FilmCheck:
    first = onset.scan[0]
    margin = first["mass_margin"]
    return _FilmCheck(first["min_film_thickness_um"],
                      margin if math.isfinite(first["critical_mass"]) else math.inf,
                      True, first["message"])


def geometry_columns(geometry: BumpDesignSpec, compliance: float) -> dict:
    """The least-stress bump foil that realises S (geometric program), as table columns:
    pitch, half length, thickness [mm], bump stress [MPa], number of bumps, binding limits."""
    from .geometry_program import design_bump_foil

    try:
        d = design_bump_foil(geometry, compliance)
    except ParameterError as exc:
        return {"bump_pitch_mm": math.nan, "half_bump_length_mm": math.nan,
                "bump_thickness_mm": math.nan, "bump_stress_mpa": math.nan,
                "number_of_bumps": math.nan, "binding_limits": "", "geometry_message": str(exc)}
    return {"bump_pitch_mm": d.pitch * 1e3, "half_bump_length_mm": d.half_length * 1e3,
            "bump_thickness_mm": d.thickness * 1e3, "bump_stress_mpa": d.bump_stress / 1e6,
            "number_of_bumps": d.number_of_bumps if d.number_of_bumps is not None else math.nan,
            "binding_limits": "; ".join(d.binding_constraints),
            "geometry_message": "" if d.success else d.message}


def meets_film_limit(row: dict, limit_um: float) -> bool:
    """The minimum film at the film-check speed is at least ``limit_um`` [µm]."""
    return bool(row.get("min_film_thickness_um", -1.0) >= limit_um)


def realised(row: dict) -> bool:
    """A bump foil with a whole number of bumps realises the row's S within the geometric
    limits (no ``geometry_message``, a pitch)."""
    pitch, message = row.get("bump_pitch_mm", math.nan), row.get("geometry_message")
    stated = isinstance(message, str) and message != ""          # NaN in a table: none
    return not stated and pitch is not None and math.isfinite(pitch)


def feasible(row: dict, limit_um: float) -> bool:
    """A design value is feasible when it meets every limit: the film limit
    (:func:`meets_film_limit`) AND a realisable bump foil (:func:`realised`).  (0.2.0 marked
    rows feasible on the film alone, also where no bump foil realises S.)"""
    return meets_film_limit(row, limit_um) and realised(row)


def _serial(function: Callable, points: Sequence[dict]) -> list[dict]:
    return [function(**p) for p in points]


@dataclass(frozen=True)
class LawOptimum:
    """The optimum of one (foundation law, η): best S, its onset speed, the near-best band of
    S, whether a limit decides (``on_bound``) and the search."""

    deflection_law: str
    loss_factor: float
    compliance: float
    onset_speed_rpm: float
    band: tuple
    on_bound: str
    search: SearchResult = field(repr=False)


def search_compliance(spec: StabilityDesignSpec, bounds: tuple, law: str, eta: float,
                      run_points: Callable = _serial) -> LawOptimum:
    """Maximise the onset speed over S in ``bounds`` for one (law, η) (module docstring).

    ``run_points(function, points)`` runs a batch of evaluations (serially by default; a
    process pool from :mod:`gfbopt.parallel` in studies)."""
    limit_um = spec.min_film_thickness_m * 1e6

    def batch(values):
        rows = run_points(evaluate_compliance,
                          [{"spec": spec, "compliance": float(v), "law": law, "eta": eta}
                           for v in values])
        # the search ranks S by the physics under the film limit: an S the bump count cannot
        # realise exactly is reached by the design inside the near-best band (BAND), so the
        # geometry enters the table's `feasible` column, not the ranking
        return [Evaluation(float(v), float(r.get("onset_speed_rpm", math.nan)),
                           meets_film_limit(r, limit_um), bool(r.get("success", False)), r)
                for v, r in zip(values, rows)]

    result = maximise_on_interval(batch, bounds, n_scan=spec.n_scan, log=True, band=BAND)
    return LawOptimum(law, eta, result.best, result.merit, result.band, result.on_bound,
                      result)


def tradeoff_frame(optima: Sequence[LawOptimum]) -> pd.DataFrame:
    """Every evaluation of every (law, η) search as one table (sorted by law, η, S)."""
    frames = []
    for opt in optima:
        frame = evaluations_frame(opt.search, "compliance")
        frame = frame.drop(columns=[c for c in ("merit",) if c in frame])
        frame["meets_film_limit"] = frame["feasible"]
        frame["feasible"] = frame["feasible"].astype(bool) & np.array(
            [realised(r) for r in frame.to_dict(orient="records")], dtype=bool)
        frame["deflection_law"] = opt.deflection_law
        frame["loss_factor"] = opt.loss_factor
        frames.append(frame)
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()


@dataclass(frozen=True)
class StabilityDesignResult:
    """The stability-driven bump-foil design (SI; speeds in rpm).

    recommended : the (law, η) case the recommendation is made for, its optimum S and the
        least-stress geometry (:class:`~gfbopt.design.spec.BumpDesign`)
    optima : one row per (law, η): best S, its onset speed, the band of S within
        :data:`BAND` of it, whether a bound decides, and the baseline's onset speed
    tradeoff : every evaluation (S, onset speed, h_min, margin, geometry, success, message)
    baseline : the bearing's own S evaluated under every (law, η)
    compliance_range : (min, max) S the bump foil can reach under the limits
    confirmation : the nonlinear transient check of the recommended design (dict)
    success, message, wall_time_s
    """

    recommended: dict
    optima: pd.DataFrame
    tradeoff: pd.DataFrame
    baseline: pd.DataFrame
    compliance_range: tuple
    confirmation: dict
    success: bool
    message: str
    wall_time_s: float

    def to_dict(self) -> dict:
        return {"recommended": self.recommended,
                "optima": self.optima.to_dict(orient="records"),
                "baseline": self.baseline.to_dict(orient="records"),
                "compliance_range": list(self.compliance_range),
                "confirmation": self.confirmation, "success": self.success,
                "message": self.message, "wall_time_s": self.wall_time_s}


def confirm_with_transient(spec: StabilityDesignSpec, compliance: float, law: str, eta: float,
                           speed_rpm: float, cache=None) -> dict:
    """Nonlinear check of a design at ``speed_rpm``: the transient critical mass (RKC
    transients from the least-stable linear mode) against the linear one, in kg."""
    from ..inputs.rotor import OperatingPoint
    from ..rotor import stability
    from ..transient import find_critical_mass, transient_model
    from ..transient.mode import linear_mode

    bearing = bearing_with_compliance(spec.bearing, compliance)
    opts = dataclasses.replace(spec.options, deflection_law=law, loss_factor=eta,
                               foil=spec.options.foil or "simple")
    try:
        if spec.running is not None:       # the warm bearing at the speed's running condition
            from .running_evaluation import running_confirmation_case

            res, why = running_confirmation_case(spec, bearing, opts, speed_rpm, cache)
            if res is None:
                return {"success": False, "message": why}
        else:
            res = stability(bearing, spec.rotor, OperatingPoint(speed_rpm, spec.load_newton),
                            options=opts, grid=spec.grid, cache=cache)
        lin = res.linearisation
        mc = res.critical_mass_parameter
        if not math.isfinite(mc) or mc <= 0:
            return {"success": False, "message": f"no finite linear threshold ({mc})"}
        mode = linear_mode(lin, mc, 1j * res.threshold_whirl_ratio)
        crit = find_critical_mass(transient_model(lin.static), linear_estimate=mc,
                                  initial_mode=mode)
    except ParameterError as exc:
        return {"success": False, "message": str(exc)}
    ratio = crit.critical_mass / mc
    return {"speed_rpm": speed_rpm, "compliance": compliance, "deflection_law": law,
            "loss_factor": eta, "linear_critical_mass_kg": res.critical_mass_kg,
            "nonlinear_critical_mass_kg": res.critical_mass_kg * ratio,
            "nonlinear_over_linear": ratio, "transients": crit.transients,
            "method": crit.method, "success": bool(crit.success),
            "message": crit.message}


def design_for_stability(spec: StabilityDesignSpec, run_points: Callable = _serial,
                         progress: Optional[Callable] = None) -> StabilityDesignResult:
    """Search S for every (law, η), recommend a bump foil, compare with the baseline and
    confirm with the nonlinear transient (module docstring).

    The recommendation is made for the first foundation law and the smallest loss factor
    given (no credit for damping one cannot measure); the other cases are reported beside it
    as bands of S, and the summary says whether the recommended S lies inside them.
    """
    from .geometry_program import compliance_range, design_bump_foil

    t0 = time.perf_counter()
    s_min, s_max = compliance_range(spec.geometry)
    # a hair inside the range, so that the geometric program at a bound is not refused by
    # round-off (1e-6 relative: far below any effect on the onset speed)
    s_min, s_max = s_min * (1 + 1e-6), s_max * (1 - 1e-6)
    cases = [(law, eta) for law in spec.deflection_laws for eta in spec.loss_factors]
    optima = []
    for k, (law, eta) in enumerate(cases):
        optima.append(search_compliance(spec, (s_min, s_max), law, eta, run_points))
        if progress is not None:
            progress((k + 1) / (len(cases) + 1))
    s0 = spec.bearing.compliance
    base_rows = run_points(evaluate_compliance, [{"spec": spec, "compliance": s0, "law": law,
                                                  "eta": eta} for law, eta in cases])
    baseline = pd.DataFrame.from_records(base_rows)
    rows = []
    for opt, base in zip(optima, base_rows):
        rows.append({"deflection_law": opt.deflection_law, "loss_factor": opt.loss_factor,
                     "best_compliance": opt.compliance, "best_onset_speed_rpm":
                     opt.onset_speed_rpm, "band_low": opt.band[0], "band_high": opt.band[1],
                     "decided_by_bound": opt.on_bound,
                     "baseline_compliance": s0,
                     "baseline_onset_speed_rpm": base.get("onset_speed_rpm", math.nan),
                     "success": opt.search.success, "message": opt.search.message})
    table = pd.DataFrame.from_records(rows)
    first = optima[0]
    recommended: dict = {"deflection_law": first.deflection_law,
                         "loss_factor": first.loss_factor, "compliance": first.compliance,
                         "onset_speed_rpm": first.onset_speed_rpm, "band": first.band}
    message = ""
    if first.search.success:
        # the least-stress bump foil whose S lies in the near-best band: a whole number of
        # bumps may not reach the single best S exactly, and inside the band the onset speed
        # is within BAND of the best anyway
        design = design_bump_foil(spec.geometry, tuple(first.band)
                                  if first.band[1] > first.band[0] else first.compliance)
        recommended["geometry"] = design.to_dict()
        if design.success:
            recommended["compliance"] = design.compliance
        else:
            message = f"no bump foil realises the recommended S: {design.message}"
        inside = [f"{o.deflection_law}/η={o.loss_factor:g}" for o in optima[1:]
                  if o.search.success and o.band[0] <= first.compliance <= o.band[1]]
        recommended["inside_bands_of"] = inside
        speed = 0.98 * min(first.onset_speed_rpm, spec.speed_range_rpm[1])
        confirmation = confirm_with_transient(spec, recommended["compliance"],
                                              first.deflection_law, first.loss_factor, speed)
    else:
        message = first.search.message
        confirmation = {"success": False, "message": "no design to confirm"}
    if progress is not None:
        progress(1.0)
    return StabilityDesignResult(recommended, table, tradeoff_frame(optima), baseline,
                                 (s_min, s_max), confirmation,
                                 first.search.success and not message, message,
                                 time.perf_counter() - t0)
