"""One design of the bearing pair of a rotor, evaluated: the rotor-level figures of merit and
limits a designer weighs (SI; speeds in rpm).

A *design* is a dict of design-variable values (names of :data:`DESIGN_VARIABLES`, optionally
prefixed by a bearing's name, ``"A:radial_clearance_um"``, to change that bearing only;
unprefixed names change both).  :func:`apply_design` turns it into a new
:class:`~gfbopt.inputs.rotor_system.RotorSystem`; :func:`evaluate_rotor_design` computes

* the onset of every mode of the rotor on its two bearings along the speed line
  (:func:`gfbopt.rotor.system.rotor_onsets`: matched whirl, each bearing at its own load) —
  ``first_onset_speed_rpm`` is the first onset over all modes, censored at the top of the
  search range when every mode is stable there (``onset_status`` says which);
* the power lost in both films at the top speed (``total_power_loss_w``, from the drag torque of
  :mod:`gfbopt.physics.torque`) and the minimum film there;
* the minimum film at the lowest speed under the heaviest load (the static loads times
  ``heaviest_load_factor``), the smaller of the two bearings;
* optionally the lift-off speed (the larger of the two bearings) and the load-capacity
  margin (capacity at the lowest speed over the static load, the smaller)
  (:mod:`gfbopt.rotor.capacity`), only when their film limits are given (otherwise the
  columns are absent, :func:`design_outputs`);
* the bump foil's bending stress, the top-foil sag over the clearance and the bump closing
  ratio (2 l0 + gap)/s, with the formulas of :mod:`gfbopt.physics.bump` that the geometric
  program limits; a ``compliance`` variable is realised by the geometric program
  (:func:`gfbopt.design.geometry_program.design_bump_foil`, least stress) instead.

A failure of the physics (a load beyond the capacity at every speed, a geometry the GP cannot
make) is a row with ``success = False`` and the message, never an exception.
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from typing import Optional

from ..errors import ParameterError
from ..inputs.grid import Grid

#: design variables a study may name: unit, and what it changes
DESIGN_VARIABLES = {
    "radial_clearance_um": ("µm", "radial clearance c"),
    "length_mm": ("mm", "bearing length L"),
    "bump_pitch_mm": ("mm", "bump pitch s"),
    "bump_half_length_mm": ("mm", "half bump length l0"),
    "bump_thickness_um": ("µm", "bump foil thickness t_b"),
    "compliance": ("-", "compliance S, realised by the geometric program (least stress)"),
    "preload_depth_um": ("µm", "mechanical preload depth (shim thickness or lobe depth)"),
    "preload_count": ("-", "number of shims or lobes (whole)"),
    "preload_offset_deg": ("deg", "centre of the first shim or lobe from the load line"),
    "preload_width_deg": ("deg", "angular width of each shim (shims only)"),
    "pads": ("-", "number of top-foil pads, evenly spaced (whole)"),
}
#: the variables that make the preload (the study's ``[bore]`` form)
PRELOAD = ("preload_depth_um", "preload_count", "preload_offset_deg", "preload_width_deg")
#: the bump-geometry variables that ``compliance`` replaces
BUMP_GEOMETRY = ("bump_pitch_mm", "bump_half_length_mm", "bump_thickness_um")
#: SI attribute and scale of each bump-geometry variable
_BUMP_SI = {"bump_pitch_mm": ("bump_pitch", 1e-3),
            "bump_half_length_mm": ("bump_half_length", 1e-3),
            "bump_thickness_um": ("bump_thickness", 1e-6)}


def zone_variable(var: str):
    """(zone number k ≥ 1, bump variable) for a per-zone name ``zoneK_<bump variable>``
    (e.g. ``zone2_bump_thickness_um``: the bump foil of the second zone of ``zone_edges_deg``
    round the bearing), else None."""
    head, _, rest = var.partition("_")
    if head.startswith("zone") and head[4:].isdigit() and int(head[4:]) >= 1 \
            and rest in BUMP_GEOMETRY:
        return int(head[4:]), rest
    return None


def known_variable(var: str) -> bool:
    """True for a name of :data:`DESIGN_VARIABLES` or a per-zone bump variable."""
    return var in DESIGN_VARIABLES or zone_variable(var) is not None
#: output columns of one evaluation and their store types
OUTPUTS = {
    "first_onset_speed_rpm": "float64", "first_mode": "string", "onset_status": "string",
    "onset_whirl_frequency_hz": "float64", "stable_to_top_speed": "bool",
    "total_power_loss_w": "float64", "min_film_top_speed_um": "float64",
    "min_film_lowest_speed_um": "float64", "lift_off_speed_rpm": "float64",
    "capacity_margin": "float64", "bump_stress_mpa": "float64",
    "top_foil_sag_ratio": "float64", "bump_closing_ratio": "float64",
    "compliance_a": "float64", "compliance_b": "float64", "grid": "string",
}


def design_outputs(settings: "EvaluationSettings") -> dict:
    """The columns of :data:`OUTPUTS` an evaluation with ``settings`` computes: the lift-off
    speed only with ``lift_off_film_um``, the capacity margin only with ``capacity_film_um``
    (a column empty in every row is left out of the store and the tables)."""
    skip = {"lift_off_speed_rpm": settings.lift_off_film_um is None,
            "capacity_margin": settings.capacity_film_um is None}
    return {k: v for k, v in OUTPUTS.items() if not skip.get(k, False)}


@dataclass(frozen=True)
class EvaluationSettings:
    """What every design is evaluated with (SI, rpm).

    speed_low_rpm, top_speed_rpm : lowest and top running speeds; search_high_rpm : top of
    the onset search (≥ top speed: designs stable beyond the top speed are still ranked);
    loss_factor : η of both bearings for the nominal evaluation; grid; heaviest_load_factor :
    the heaviest load over the static one; lift_off_film_um : h_min limit of the lift-off
    speed (None: not computed); capacity_film_um : h_min limit of the load capacity at the
    lowest speed (None: not computed); design_pressure_pa, gap_m : of the bump stress and
    closing; bore_kind, bore_width_deg, bore_offset_deg, preload_count : the preload's form
    when ``preload_depth_um`` is a variable; pad_offset_deg : leading end of the first pad
    from the load line; bump_spec : the geometric program's limits (``compliance`` variable).
    """

    speed_low_rpm: float
    top_speed_rpm: float
    search_high_rpm: float
    grid: Grid
    loss_factor: float = 0.0
    heaviest_load_factor: float = 1.0
    lift_off_film_um: Optional[float] = None
    capacity_film_um: Optional[float] = None
    design_pressure_pa: float = 1e5
    gap_m: float = 0.2e-3
    bore_kind: str = "shims"
    bore_width_deg: float = 60.0
    bore_offset_deg: float = 0.0
    preload_count: int = 3
    pad_offset_deg: float = 180.0
    bump_spec: object = None
    zone_edges_deg: tuple = ()


def _split(name: str) -> tuple:
    """("A", "radial_clearance_um") for "A:radial_clearance_um"; (None, name) otherwise."""
    if ":" in name:
        bearing, var = name.split(":", 1)
        return bearing, var
    return None, name


def _bearing_design(geometry, values: dict, settings: EvaluationSettings):
    """A BearingGeometry with the design values applied (see DESIGN_VARIABLES)."""
    from ..inputs.bore_si import BearingBuild, BoreSpec, PadSpec

    change = {}
    if "radial_clearance_um" in values:
        change["radial_clearance"] = values["radial_clearance_um"] * 1e-6
    if "length_mm" in values:
        change["length"] = values["length_mm"] * 1e-3
    for var, (key, scale) in _BUMP_SI.items():
        if var in values:
            change[key] = values[var] * scale
    build = geometry.build or BearingBuild()
    zoned = {zone_variable(v): x for v, x in values.items() if zone_variable(v)}
    if zoned:
        from ..inputs.bore_si import ZoneSpec

        edges = settings.zone_edges_deg
        zones = []
        for k in range(1, len(edges)):
            si = {_BUMP_SI[var][0]: zoned[(k, var)] * _BUMP_SI[var][1]
                  for var in BUMP_GEOMETRY if (k, var) in zoned}
            zones.append(ZoneSpec(edges[k - 1], edges[k], **si))
        build = dataclasses.replace(build, zones=tuple(zones))
    if any(v in values for v in PRELOAD):
        count = int(round(values.get("preload_count", settings.preload_count)))
        held = build.bore.preload_depth if build.bore.kind in ("shims", "lobes") else None
        depth = (values["preload_depth_um"] * 1e-6 if "preload_depth_um" in values
                 else held or 0.0)         # the bearing file's own depth when not varied
        width = values.get("preload_width_deg", settings.bore_width_deg)
        bore = (BoreSpec() if depth == 0.0 or count == 0 else
                BoreSpec(settings.bore_kind, count, preload_depth=depth,
                         width_deg=width if settings.bore_kind == "shims" else 0.0,
                         offset_deg=values.get("preload_offset_deg",
                                               settings.bore_offset_deg)))
        build = dataclasses.replace(build, bore=bore)
    if "pads" in values:
        n = int(round(values["pads"]))
        build = dataclasses.replace(build, pads=tuple(
            PadSpec((settings.pad_offset_deg + k * 360.0 / n) % 360.0, 360.0 / n)
            for k in range(n)) if n > 1 else ())
    if build != (geometry.build or BearingBuild()):
        change["build"] = build
    return dataclasses.replace(geometry, **change) if change else geometry


def apply_design(system, design: dict, settings: EvaluationSettings) -> tuple:
    """(the RotorSystem with the design applied, per-bearing GP results or {})."""
    names = [b.name for b in system.bearings]
    per = {n: {} for n in names}
    for name, value in design.items():
        bearing, var = _split(name)
        if not known_variable(var):
            raise ParameterError("design", name, f"is not a design variable (known: "
                                 f"{', '.join(DESIGN_VARIABLES)}, zoneK_<bump variable>)")
        zone = zone_variable(var)
        if zone is not None and zone[0] >= len(settings.zone_edges_deg):
            raise ParameterError("design", name, f"names zone {zone[0]}, but zone_edges_deg "
                                 f"gives {max(len(settings.zone_edges_deg) - 1, 0)} zones")
        for n in ([bearing] if bearing else names):
            if n not in per:
                raise ParameterError("design", name, f"names no bearing of the rotor "
                                     f"({', '.join(names)})")
            per[n][var] = float(value)
    gp = {}
    supports = []
    for support in system.bearings:
        values = dict(per[support.name])
        geometry = _bearing_design(support.geometry, values, settings)
        if "compliance" in values:
            geometry, gp[support.name] = _realise_compliance(geometry, values["compliance"],
                                                             settings)
        supports.append(dataclasses.replace(support, geometry=geometry))
    return dataclasses.replace(system, bearings=tuple(supports)), gp


def _realise_compliance(geometry, compliance: float, settings: EvaluationSettings):
    """The least-stress bump foil with S = ``compliance`` (geometric program)."""
    from .geometry_program import design_bump_foil

    spec = dataclasses.replace(
        settings.bump_spec, radial_clearance=geometry.radial_clearance,
        radius=geometry.radius, ambient_pressure=geometry.ambient_pressure,
        youngs_modulus=geometry.bump_youngs_modulus, poisson_ratio=geometry.poisson_ratio)
    d = design_bump_foil(spec, compliance)
    if not d.success:
        raise ParameterError("compliance", compliance, f"no bump foil realises it: "
                             f"{d.message}")
    return dataclasses.replace(geometry, bump_pitch=d.pitch, bump_half_length=d.half_length,
                               bump_thickness=d.thickness), d


def structural_limits(geometry, settings: EvaluationSettings) -> dict:
    """Bump stress [MPa], top-foil sag / c and bump closing (2 l0 + gap)/s of a bearing —
    the largest over its bump zones when it has zones."""
    from ..physics.bump import bump_bending_stress, top_foil_sag

    zones = geometry.build.zones if geometry.build is not None else ()
    if zones:
        parts = [structural_limits(dataclasses.replace(geometry, build=None, **{
            key: getattr(z, key) for key in ("bump_pitch", "bump_half_length",
                                             "bump_thickness")
            if getattr(z, key) is not None}), settings) for z in zones]
        return {k: max(p[k] for p in parts) for k in parts[0]}
    g = geometry
    dp = settings.design_pressure_pa
    return {"bump_stress_mpa": bump_bending_stress(dp, g.bump_pitch, g.bump_half_length,
                                                   g.bump_thickness) / 1e6,
            "top_foil_sag_ratio": top_foil_sag(dp, g.bump_pitch, g.top_foil_thickness,
                                               g.top_foil_youngs_modulus, g.poisson_ratio)
            / g.radial_clearance,
            "bump_closing_ratio": (2 * g.bump_half_length + settings.gap_m) / g.bump_pitch}


def _static(case, speed_rpm: float, load_newton: float, grid: Grid, cache):
    """The equilibrium under ``load_newton`` [N], cold: on a grid of at least
    :data:`~gfbopt.rotor.supports.COLD_FACTOR` times the cells of
    :data:`~gfbopt.rotor.supports.COLD_GRID`, from that coarse grid's equilibrium
    interpolated (the Newton fast path, the same root as IPOPT's to 1e-10), as the speed
    line's first equilibrium; IPOPT with continuation when that does not converge."""
    from ..rotor.speed_line import transferred_start
    from ..rotor.supports import COLD_FACTOR, COLD_GRID
    from ..static import solve_static

    model = case.model(speed_rpm)
    load = case.bearing.nondimensional_load(load_newton)
    solver = cache(model, grid)
    if grid.n_theta * grid.n_z >= COLD_FACTOR * COLD_GRID.n_theta * COLD_GRID.n_z:
        coarse = solve_static(model, load=load, solver=cache(model, COLD_GRID),
                              continuation=True)
        if coarse.success:
            sol = solve_static(model, load=load, solver=solver, continuation=False,
                               initial=transferred_start(coarse, solver, model),
                               fast_path=True)
            if sol.success:
                return sol
    return solve_static(model, load=load, solver=solver, continuation=True)


def film_um(sol, bearing) -> float:
    """The minimum film [µm] of a static solution: the smallest nodal film, or with a
    sharp-edged (shim) bore the film at its steps when smaller
    (:func:`gfbopt.physics.bore.step_film`, a grid-robust bound: the nodal film at a shim
    edge is not converged on any practical grid); 0 when the film closes there."""
    from ..physics.bore import step_film

    h = sol.min_film
    ab = sol.model.as_built
    if ab is not None and ab.bore.kind == "shims" and not ab.bore.is_round:
        h = min(h, step_film(sol.film, sol.deflection, ab.bore_rows(sol.theta)))
    return max(h, 0.0) * bearing.radial_clearance * 1e6


def _film_and_power(rotor, line, settings: EvaluationSettings, cache) -> dict:
    from ..physics.torque import drag_torque_and_power

    top = line.states(settings.top_speed_rpm)
    power, film_top = 0.0, math.inf
    if not top.ok:
        power = film_top = math.nan
    else:
        for state in top.states:
            sol = state.solution
            power += drag_torque_and_power(sol.torque_ratio, sol.model.bearing_number,
                                           state.case.bearing)[1]
            film_top = min(film_top, film_um(sol, state.case.bearing))
    film_low = math.inf
    for case in rotor.cases:
        sol = _static(case, settings.speed_low_rpm,
                      case.load_newton * settings.heaviest_load_factor, settings.grid, cache)
        film_low = min(film_low, film_um(sol, case.bearing) if sol.success else 0.0)
    return {"total_power_loss_w": power, "min_film_top_speed_um": film_top,
            "min_film_lowest_speed_um": film_low}


def _capacity_rows(rotor, settings: EvaluationSettings, cache) -> dict:
    from ..rotor.capacity import lift_off_speed, load_capacity

    out = {}
    if settings.lift_off_film_um is not None:
        speeds = [lift_off_speed(c.bearing, c.load_newton, settings.lift_off_film_um,
                                 max_speed_rpm=settings.top_speed_rpm, options=c.options,
                                 grid=settings.grid, cache=cache) for c in rotor.cases]
        out["lift_off_speed_rpm"] = max(s.value if s.success else math.inf for s in speeds)
    if settings.capacity_film_um is not None:
        caps = [load_capacity(c.bearing, settings.speed_low_rpm, settings.capacity_film_um,
                              options=c.options, grid=settings.grid, cache=cache)
                for c in rotor.cases]
        out["capacity_margin"] = min((r.value / c.load_newton) if r.success else 0.0
                                     for r, c in zip(caps, rotor.cases))
    return out


from .rotor_onset import (  # noqa: E402,F401 - the onset search, re-exported
    NEAR_TOLERANCE, ONSET_TOLERANCE, _lowest, _onset_row, _secant_near, first_onset)


def evaluate_rotor_design(system, settings: EvaluationSettings, cache=None,
                          near_onset_rpm: Optional[float] = None, onset_only: bool = False,
                          **design) -> dict:
    """Every output of :func:`design_outputs` for one design (module docstring); a physics
    failure is a row with ``success = False`` and its message.  After the search:
    ``near_onset_rpm``, a nearby problem's first onset where the search starts
    (:func:`first_onset`); ``onset_only``: the first onset only (the tolerance check's
    rows; ``success`` when it was found), no film, power or capacity."""
    from ..inputs.options import ModelOptions
    from ..rotor.supports import resolve_rotor
    from ..rotor.system import SpeedLine
    from ..static import SolverCache

    t0 = time.perf_counter()
    cache = cache if cache is not None else SolverCache(settings.grid)
    row: dict = {"grid": str(settings.grid)}
    try:
        designed, _ = apply_design(system, design, settings)
        limits = [structural_limits(b.geometry, settings) for b in designed.bearings]
        row.update({k: max(l[k] for l in limits) for k in limits[0]})
        row["compliance_a"] = designed.bearings[0].geometry.compliance
        row["compliance_b"] = designed.bearings[1].geometry.compliance
        options = ModelOptions(loss_factor=settings.loss_factor)
        rotor = resolve_rotor(designed, settings.grid, cache, options)
        line = SpeedLine(rotor)
        row.update(first_onset(line, settings, near_onset_rpm))
        if onset_only:
            row["success"] = True
        else:
            row.update(_film_and_power(rotor, line, settings, cache))
            row.update(_capacity_rows(rotor, settings, cache))
            row["success"] = bool(math.isfinite(row["total_power_loss_w"]))
        row["message"] = "" if row["success"] else ("a bearing cannot carry its load at the "
                                                    "top speed")
    except ParameterError as exc:
        row.update(success=False, message=str(exc))
    row["wall_time_s"] = time.perf_counter() - t0
    return row


def design_conventions(system, design: dict, settings: EvaluationSettings) -> dict:
    """The conventions every evaluation of ``design`` states (the rotor's frame, each
    bearing's resolved formulation — film, seam angle, foil, deflection law, loss factor —,
    load, position, file and clearance model: :meth:`gfbopt.rotor.supports.RotorCase.
    conventions`), resolved as :func:`evaluate_rotor_design` resolves them, no solve."""
    from ..inputs.options import ModelOptions
    from ..rotor.supports import resolve_rotor

    designed, _ = apply_design(system, design, settings)
    return resolve_rotor(designed, settings.grid,
                         options=ModelOptions(loss_factor=settings.loss_factor)).conventions()
