"""The bearing-pair design study of a rotor: its file's keys and their validation, before any
solve (every mistake is one ParameterError naming the file, the key, the value and the rule).

A study file (``kind = "rotor_bearing_design"``, e.g. ``problems/rotor_bearing_design.toml``)
names the rotor file, the speeds (lowest and top), the goal, the limits, the design variables
with their ranges, the loss factor as an uncertain band, the search (method, budget, seed),
the manufacturing tolerances of the robustness check, and two grids: the coarse grid the
search runs on and the default grid the chosen and Pareto designs are evaluated again on.

Goals:

* ``front`` — two objectives, maximise the first onset over all modes and minimise the power
  loss at the top speed (NSGA-II): the Pareto front;
* ``max_onset`` — one objective, the first onset (Bayesian or NSGA-II);
* ``stable_then_min_power`` — the rotor must be stable to the top speed (a constraint), then
  the least power loss (one objective).
"""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import ParameterError
from .problem import Constraint, DesignProblem, Objective, Variable
from .rotor_objectives import (BUMP_GEOMETRY, DESIGN_VARIABLES, PRELOAD,
                               EvaluationSettings, known_variable, zone_variable)
from .search import SearchSettings

GOALS = ("front", "max_onset", "stable_then_min_power")
BORE_KINDS = ("shims", "lobes")
#: keys of ``[search]`` that tune the converged search (nsga2_refine), passed to
#: :class:`~.search.SearchSettings` when the study's schema has them
REFINE_KEYS = ("generations", "first_step", "step_tolerance", "improvement")
#: the design variables that take whole numbers
WHOLE = ("preload_count", "pads")


@dataclass(frozen=True)
class RobustnessSpec:
    """± tolerances of design variables (name → half-width, in the variable's unit), the
    sample size and seed (Latin hypercube over the tolerances and the loss-factor band),
    and how many of the best front designs are checked."""

    tolerances: dict
    samples: int
    seed: int
    designs: int


@dataclass(frozen=True)
class RotorDesignPlan:
    """Everything a run needs, validated: the rotor, the problem, the search, the evaluation
    settings on the search grid and on the default grid, the loss-factor band, the goal."""

    system: object
    problem: DesignProblem
    search: SearchSettings
    settings: EvaluationSettings
    default_settings: EvaluationSettings
    loss_factor_band: tuple
    goal: str
    robustness: RobustnessSpec
    study_hash: str
    regrid_designs: int = 3
    limit_cycle_revolutions: float = 0.0
    limit_cycle_grid: object = None
    #: the study's ``[what_it_would_take]`` table as written (None: absent), validated by
    #: :mod:`gfbopt.design.what_it_takes`, not here
    what_it_would_take: object = None


def _zone_edges(edges, where) -> tuple:
    """The bump zones' edges [deg]: increasing, spanning exactly 360° (one line else)."""
    if edges is None:
        return ()
    e = [float(x) for x in edges]
    if len(e) < 2 or any(b <= a for a, b in zip(e, e[1:])) or abs(e[-1] - e[0] - 360.0) > 1e-9:
        raise where.error(list(edges), "must be at least two increasing angles [deg] whose "
                          "last is the first + 360 (the zones cover the bearing once)")
    return tuple(e)


def _variables(rows: list, where, bearings: tuple, zones: int = 0) -> tuple:
    out, seen = [], set()
    for k, row in enumerate(rows):
        w = where / k
        name = row["name"]
        bearing, var = name.split(":", 1) if ":" in name else (None, name)
        if not known_variable(var):
            raise (w / "name").error(name, f"is not a design variable of the rotor's bearings "
                                     f"(known: {', '.join(DESIGN_VARIABLES)}, "
                                     "zoneK_<bump variable>)")
        zone = zone_variable(var)
        if zone is not None and zone[0] > zones:
            raise (w / "name").error(name, f"names bump zone {zone[0]}, but zone_edges_deg "
                                     f"gives {zones} zone(s)")
        if bearing is not None and bearing not in bearings:
            raise (w / "name").error(name, f"names no bearing of the rotor (bearings: "
                                     f"{', '.join(bearings)})")
        if name in seen:
            raise (w / "name").error(name, "is given twice")
        seen.add(name)
        values = row["values"]
        if var in WHOLE and values is None:
            raise (w / "values").error(None, f"{var} is a whole number: give its values "
                                       "(e.g. [1, 3])")
        if values is not None and var in WHOLE and any(v != int(v) or v < 0 for v in values):
            raise (w / "values").error(values, "must be whole numbers >= 0")
        try:
            out.append(Variable(name, low=row["low"], high=row["high"], scale=row["scale"],
                                values=None if values is None else tuple(values)))
        except ParameterError as exc:
            raise w.error(exc.value, exc.rule) from None
        low = min(values) if values is not None else row["low"]
        if var == "preload_offset_deg":
            from ..inputs.bore import START_RANGE_DEG, degrees_in

            for key in ("low", "high"):
                try:
                    degrees_in(name, row[key], *START_RANGE_DEG)
                except ParameterError as exc:
                    raise (w / key).error(row[key], exc.rule) from None
        elif var not in ("preload_depth_um",) and var not in WHOLE and low <= 0:
            raise w.error([row["low"], row["high"]], f"{var} must be > 0")
        if var in ("preload_depth_um",) and low < 0:
            raise w.error([row["low"], row["high"]], "a preload depth must be >= 0")
    names = {v.name.split(":")[-1] for v in out}
    bump = {n for n in names if n in BUMP_GEOMETRY or zone_variable(n)}
    if "compliance" in names and bump:
        raise where.error(sorted(bump), "give either compliance (the "
                          "geometric program picks the bump foil) or the bump geometry, not "
                          "both")
    return tuple(out)


def _tolerances(table: dict, where, variables: tuple) -> dict:
    by_name = {v.name: v for v in variables}
    out = {}
    for name, half in table.items():
        if name not in by_name:
            raise (where / name).error(half, "has a tolerance but is not a design variable "
                                       f"of this study ({', '.join(by_name)})")
        v = by_name[name]
        width = (max(v.values) - min(v.values)) if v.discrete else v.high - v.low
        if v.discrete:
            raise (where / name).error(half, "is a whole-number variable: it has no "
                                       "manufacturing tolerance")
        if 2.0 * half >= width:
            raise (where / name).error(half, f"± tolerance spans {2 * half:g}, not smaller "
                                       f"than the variable's range ({width:g})")
        out[name] = float(half)
    return out


def _problem(spec: dict, where, variables: tuple) -> DesignProblem:
    goal = spec["goal"]
    top = spec["speed_range_rpm"][1]
    constraints = [Constraint("min_film_lowest_speed_um", lower=spec["min_film_um"])]
    if spec["max_lift_off_speed_rpm"] is not None:
        constraints.append(Constraint("lift_off_speed_rpm",
                                      upper=spec["max_lift_off_speed_rpm"]))
    if spec["min_capacity_margin"] is not None:
        constraints.append(Constraint("capacity_margin", lower=spec["min_capacity_margin"]))
    if spec["allowable_stress_mpa"] is not None:
        constraints.append(Constraint("bump_stress_mpa", upper=spec["allowable_stress_mpa"]))
    if spec["sag_limit"] is not None:
        constraints.append(Constraint("top_foil_sag_ratio", upper=spec["sag_limit"]))
    if any(v.name.split(":")[-1] in BUMP_GEOMETRY or zone_variable(v.name.split(":")[-1])
           for v in variables):
        constraints.append(Constraint("bump_closing_ratio", upper=1.0))
    if goal == "front":
        objectives = (Objective("first_onset_speed_rpm", "max"), Objective("total_power_loss_w"))
    elif goal == "max_onset":
        objectives = (Objective("first_onset_speed_rpm", "max"),)
    else:
        objectives = (Objective("total_power_loss_w"),)
        constraints.append(Constraint("first_onset_speed_rpm", lower=top))
    if goal == "front" and spec["search"]["method"] == "bayes":
        raise (where / "search" / "method").error("bayes", "optimises one objective; goal "
                                                  "'front' has two (use 'nsga2')")
    return DesignProblem(variables, objectives, tuple(constraints))


def _check_buildable(study, system, variables: tuple, settings: EvaluationSettings) -> None:
    """The fixed inputs every design is built with, checked at plan time (a bore of 500°
    shims or a pad offset of 1e300° would make every design fail, and the search end in "no
    design meets every limit"): the bore's form and the pad offset on their own, then the
    design at the middle of every range (the largest whole number) built on the rotor — each
    refusal one line naming the study key."""
    from ..inputs.bore import START_RANGE_DEG, degrees_in
    from ..inputs.bore_si import BoreSpec
    from .rotor_objectives import apply_design

    bore = BoreSpec(settings.bore_kind, settings.preload_count, preload_ratio=0.5,
                    width_deg=settings.bore_width_deg if settings.bore_kind == "shims" else 0.0,
                    offset_deg=settings.bore_offset_deg)
    try:
        bore.profile(None)
    except ParameterError as exc:
        raise study.where("bore", exc.name.split(".")[-1]).error(exc.value, exc.rule) \
            from None
    try:
        degrees_in("pad_offset_deg", settings.pad_offset_deg, *START_RANGE_DEG)
        if settings.zone_edges_deg:
            degrees_in("zone_edges_deg", settings.zone_edges_deg[0], *START_RANGE_DEG)
    except ParameterError as exc:
        raise study.where(exc.name).error(exc.value, exc.rule) from None
    built = [v for v in variables if v.name.split(":")[-1] != "compliance"]  # (GP's own)
    for k, v in enumerate(variables):         # each range's ends, alone on the rotor's bearings
        if v not in built:
            continue
        for end, u in (("low", 0.0), ("high", 1.0 - 1e-12)):
            value = v.decode(u)
            try:
                apply_design(system, {v.name: value}, settings)
            except ParameterError as exc:
                key = ("values" if v.discrete else end)
                raise study.where("variables", k, key).error(value, f"{v.name} = {value:g} "
                                                             f"cannot be built on the rotor's "
                                                             f"bearings: {exc}") from None
    probe = {v.name: v.decode(1.0 - 1e-9 if v.discrete else 0.5) for v in built}
    try:
        apply_design(system, probe, settings)
    except ParameterError as exc:
        raise study.where("variables").error(probe, f"the design at the middle of every "
                                             f"range cannot be built with the study's fixed "
                                             f"inputs: {exc}") from None


def _on(bearing: str, name: str) -> bool:
    """True when variable ``name`` (``A:var`` or shared ``var``) changes ``bearing``."""
    return ":" not in name or name.split(":", 1)[0] == bearing


def _ends(v) -> tuple:
    """(least, largest) value a variable takes."""
    return (min(v.values), max(v.values)) if v.discrete else (v.low, v.high)


def _check_levers(study, system, variables: tuple, settings: EvaluationSettings) -> None:
    """Levers a bearing cannot take, refused at plan time per bearing (one line naming the
    study key and the rule): a preload at least as deep as the bearing's smallest radial
    clearance (the shim or lobe closes the film); lobes on a bearing with pads (a lobed bore
    is one ring: the pads' ends would cut the lobes); a shim width with lobes, or a width
    whose shims overlap (count × width > 360°); a preload count, offset or width on a
    bearing with no preload (they would change nothing)."""
    where = study.where("variables")
    for support in system.bearings:
        b, g = support.name, support.geometry
        build = g.build
        mine = [(k, v) for k, v in enumerate(variables) if _on(b, v.name)]
        by_var = {v.name.split(":")[-1]: (k, v) for k, v in mine}
        clearances = [_ends(v)[0] for _, v in mine
                      if v.name.split(":")[-1] == "radial_clearance_um"]
        c_low = min(clearances) if clearances else g.radial_clearance * 1e6
        held = build.bore if build is not None else None
        held_depth = (held.preload_depth if held is not None and held.kind in
                      ("shims", "lobes") and held.preload_depth is not None else None)
        if "preload_depth_um" in by_var:
            k, v = by_var["preload_depth_um"]
            deepest = _ends(v)[1]
            if deepest >= c_low:
                raise (where / k / ("values" if v.discrete else "high")).error(
                    deepest, f"a preload of {deepest:g} µm on bearing {b} is at least its "
                    f"smallest radial clearance ({c_low:g} µm): the shim or lobe closes the "
                    "film; keep the preload depth below the clearance")
        elif any(var in by_var for var in PRELOAD) and not held_depth:
            k, v = next(by_var[var] for var in PRELOAD if var in by_var)
            raise (where / k / "name").error(v.name, f"bearing {b} has no preload (no "
                                             "preload_depth_um variable, and its file has "
                                             "no shims or lobes by depth): this lever "
                                             "changes nothing")
        kind = settings.bore_kind if any(var in by_var for var in PRELOAD) else (
            held.kind if held is not None else "round")
        pads = (_ends(by_var["pads"][1])[1] if "pads" in by_var else
                len(build.pads) if build is not None else 0)
        if kind == "lobes" and pads > 1:
            k = by_var["pads"][0] if "pads" in by_var else next(
                k for var, (k, _) in by_var.items() if var in PRELOAD)
            raise (where / k / "name").error(variables[k].name, f"bearing {b} would have "
                                             f"lobes and {pads:g} pads: a lobed bore cannot "
                                             "take pads (use shims, or one top foil)")
        if "preload_width_deg" in by_var:
            k, v = by_var["preload_width_deg"]
            count = (_ends(by_var["preload_count"][1])[1] if "preload_count" in by_var
                     else settings.preload_count)
            if kind != "shims":
                raise (where / k / "name").error(v.name, f"a width is a shim's: bearing "
                                                 f"{b}'s preload is {kind}")
            if count * _ends(v)[1] > 360.0:
                raise (where / k / "high").error(_ends(v)[1], f"{count:g} shims of "
                                                 f"{_ends(v)[1]:g}° overlap (count × width "
                                                 "must be at most 360°)")


def plan_rotor_design(study, study_hash: str = "") -> RotorDesignPlan:
    """Validate a ``rotor_bearing_design`` study (:mod:`gfbopt.studies.rotor_design`) and
    build its plan — no solve."""
    from ..inputs.grid import Grid
    from ..inputs.rotor_limits import check_rotor_speeds
    from ..inputs.rotor_system import load_rotor

    s = study.spec
    try:
        system = load_rotor(study.directory / s["rotor"], running=True)   # clearance at speed
    except ParameterError as exc:
        raise study.where("rotor").error(str(s["rotor"]), f"{exc.name}: {exc.rule}") from None
    low, top = s["speed_range_rpm"]
    if not 0 < low < top:
        raise study.where("speed_range_rpm").error([low, top], "must be [lowest, top] with "
                                                   "0 < lowest < top speed [rpm]")
    high = s["search_high_rpm"] if s["search_high_rpm"] is not None else 1.25 * top
    if high < top:
        raise study.where("search_high_rpm").error(high, f"must be >= the top speed {top:g} "
                                                   "rpm")
    band = tuple(s["loss_factor_band"])
    if not 0.0 <= band[0] <= band[1] <= 1.0:
        raise study.where("loss_factor_band").error(list(band), "must be [low, high] with "
                                                    "0 <= low <= high <= 1")
    widest = max([min(b.geometry.radial_clearance for b in system.bearings) * 1e6]
                 + [x for v in s["variables"] if v["name"].endswith("radial_clearance_um")
                    for x in (v["values"] or [v["high"]]) if isinstance(x, (int, float))])
    from ..rotor.capacity import MIN_FILM_LIMIT_UM

    for key in ("min_film_um", "lift_off_film_um", "capacity_film_um"):
        if s[key] is not None and s[key] < MIN_FILM_LIMIT_UM:
            raise study.where(key).error(s[key], f"must be >= {MIN_FILM_LIMIT_UM:g} µm: a "
                                         "thinner film is below any real surface's roughness "
                                         "(is it in metres? the key is in µm)")
    if not s["min_film_um"] < widest:
        raise study.where("min_film_um").error(s["min_film_um"], f"must be below the radial "
                                               f"clearance ({widest:g} µm at the most)")
    try:
        check_rotor_speeds(system, (low, top, high), name="speed_range_rpm")
    except ParameterError as exc:
        raise study.where("speed_range_rpm").error(exc.value, exc.rule) from None
    if not s["variables"]:
        raise study.where("variables").error([], "must name at least one design variable")
    bearings = tuple(b.name for b in system.bearings)
    edges = _zone_edges(s["zone_edges_deg"], study.where("zone_edges_deg"))
    variables = _variables(s["variables"], study.where("variables"), bearings,
                           max(len(edges) - 1, 0))
    problem = _problem(s, study.where(), variables)
    r = s["robustness"]
    robustness = RobustnessSpec(_tolerances(r["tolerances"], study.where("robustness",
                                                                          "tolerances"),
                                            variables), r["samples"], r["seed"], r["designs"])
    q = s["search"]
    try:
        search = SearchSettings(q["method"], q["budget"], q["population"], q["startup"],
                                q["batch"], q["seed"], **{k: q[k] for k in REFINE_KEYS
                                                          if q.get(k) is not None})
    except ParameterError as exc:
        raise study.where("search", exc.name).error(exc.value, exc.rule) from None
    bore = s["bore"]
    bump_spec = None
    if any(v.name.split(":")[-1] == "compliance" for v in variables):
        from .spec import BumpDesignSpec

        g = system.bearings[0].geometry
        try:
            bump_spec = BumpDesignSpec(
                radial_clearance=g.radial_clearance,
                allowable_stress=(None if s["allowable_stress_mpa"] is None
                                  else s["allowable_stress_mpa"] * 1e6),
                design_pressure=s["design_pressure_bar"] * 1e5, gap=s["gap_mm"] * 1e-3,
                pitch_range=tuple(v * 1e-3 for v in s["pitch_range_mm"]),
                half_length_range=tuple(v * 1e-3 for v in s["half_length_range_mm"]),
                thickness_range=tuple(v * 1e-6 for v in s["thickness_range_um"]))
        except ParameterError as exc:
            raise study.where(exc.name).error(exc.value, exc.rule) from None
    common = dict(speed_low_rpm=float(low), top_speed_rpm=float(top),
                  search_high_rpm=float(high), loss_factor=band[0],
                  heaviest_load_factor=s["heaviest_load_factor"],
                  lift_off_film_um=s["lift_off_film_um"],
                  capacity_film_um=s["capacity_film_um"],
                  design_pressure_pa=s["design_pressure_bar"] * 1e5, gap_m=s["gap_mm"] * 1e-3,
                  bore_kind=bore["kind"], bore_width_deg=bore["width_deg"],
                  bore_offset_deg=bore["offset_deg"], preload_count=bore["count"],
                  pad_offset_deg=s["pad_offset_deg"], bump_spec=bump_spec,
                  zone_edges_deg=edges)
    if s["max_lift_off_speed_rpm"] is not None and s["lift_off_film_um"] is None:
        raise study.where("lift_off_film_um").error(None, "is needed by "
                                                    "max_lift_off_speed_rpm")
    if s["min_capacity_margin"] is not None and s["capacity_film_um"] is None:
        raise study.where("capacity_film_um").error(None, "is needed by min_capacity_margin")
    search_grid, default_grid = Grid.parse(s["search_grid"]), Grid.parse(s["grid"])
    if (default_grid.n_theta < search_grid.n_theta or default_grid.n_z < search_grid.n_z):
        raise study.where("grid").error(str(s["grid"]), f"must be at least as fine as "
                                        f"search_grid {s['search_grid']!r} in both directions: "
                                        "it re-evaluates the search's designs (grid honesty)")
    settings = EvaluationSettings(grid=search_grid, **common)
    default = EvaluationSettings(grid=default_grid, **common)
    _check_buildable(study, system, variables, settings)
    _check_levers(study, system, variables, settings)
    return RotorDesignPlan(system, problem, search, settings, default, band, s["goal"],
                           robustness, study_hash, s["regrid_designs"],
                           s["limit_cycle_revolutions"], Grid.parse(s["limit_cycle_grid"]),
                           s.get("what_it_would_take"))
