"""The size of a study, estimated from its validated file before it is planned or run
(:mod:`gfbopt.guard`): the memory of the models at its largest grid, the arrays its search
allocates, and the time of its solves, speeds, evaluations and time steps.

:func:`study_work` gives the parts of every kind: the rotor kinds count their speeds
(``speed_range_rpm``, ``campbell_speeds``, ``imbalance_speeds``), designs (``budget``,
``robustness.samples`` × ``robustness.designs``, ``regrid_designs``) and time steps
(``start_rpm``/``end_rpm``/``rate_rpm_per_s``, ``time_step``, ``*_revolutions``); the others
their points: the product of the lengths of their lists (rows, cases, variants, speeds,
loads, values …), each a static solve, plus the time steps of their orbits
(``revolutions``).  The estimates are rough; they refuse, in one line naming the key, runs
of hours or of more memory than a machine has.
"""
from __future__ import annotations

import math
from typing import Iterator

from .. import guard
from ..inputs.grid import DEFAULT_GRID, Grid

#: evaluations of one lever of a design's [what_it_would_take], about (as
#: gfbopt.studies.rotor_design.LEVER_EVALUATIONS: the scan each way, the refinement, the answer)
LEVER_EVALUATIONS = 2 * 4 + 8 + 1
#: kinds on a rotor: two bearing models at each grid
ROTOR_KINDS = ("rotor_two_bearings", "rotor_run_up", "rotor_bearing_design")
#: lists that are not points of a study (labels, references, notes, published numbers)
NOT_POINTS = ("notes", "references", "trends", "comparisons", "crossover_pairs", "kicks",
              "speed_range_rpm", "speed_range", "whirl_ratio_range", "pitch_range_mm",
              "half_length_range_mm", "thickness_range_um", "top_foil_thickness_range_um",
              "loss_factor_band", "zone_edges_deg", "tolerances", "variables")


def _grids(data, path: str = "") -> Iterator[tuple]:
    """(key path, grid text) of every grid in the study (keys named *grid*, lists *grids*)."""
    if isinstance(data, dict):
        for key, value in data.items():
            where = f"{path}.{key}" if path else str(key)
            if "grid" in str(key) and isinstance(value, str):
                yield where, value
            elif "grid" in str(key) and isinstance(value, list):
                yield from ((f"{where}[{k}]", v) for k, v in enumerate(value)
                            if isinstance(v, str))
            else:
                yield from _grids(value, where)
    elif isinstance(data, list):
        for k, value in enumerate(data):
            yield from _grids(value, f"{path}[{k}]")


def study_work(spec: dict, where: str = "") -> list:
    """The :class:`~gfbopt.guard.Work` parts of a validated study ``spec`` (key names
    prefixed by ``where``, the file)."""
    prefix = f"{where}: " if where else ""
    kind = spec.get("kind")
    models = 2 if kind in ROTOR_KINDS else 1
    parts = []
    for key, text in _grids(spec):
        parts.append(guard.grid_memory(Grid.parse(text), f"{prefix}{key}", models))
    grid = Grid.parse(spec["grid"]) if isinstance(spec.get("grid"), str) else DEFAULT_GRID
    if kind == "rotor_two_bearings":
        parts += _rotor(spec, grid, prefix)
    elif kind == "rotor_run_up":
        parts += _run_up(spec, grid, prefix)
    elif kind == "rotor_bearing_design":
        parts += _design(spec, grid, prefix)
    else:
        parts += _points(spec, grid, prefix)
    return parts


def _scan(spec: dict, grid: Grid, key: str, prefix: str, high=None) -> list:
    low, top = spec[key]
    count = guard.scan_count(low, high or top)
    return [] if count is None else [guard.speeds(f"{prefix}{key}", spec[key], count, grid, 2,
                                                  "speeds of the onset scan")]


def _rotor(spec: dict, grid: Grid, prefix: str) -> list:
    parts = _scan(spec, grid, "speed_range_rpm", prefix)
    for key in ("campbell_speeds", "imbalance_speeds"):
        parts.append(guard.speeds(f"{prefix}{key}", spec[key], spec[key], grid, 2,
                                  key.replace("_", " ")))
    return parts


def _run_up(spec: dict, grid: Grid, prefix: str) -> list:
    step = spec.get("time_step")
    count = guard.ramp_steps(spec["start_rpm"], spec["end_rpm"], spec["rate_rpm_per_s"], step)
    parts = [guard.steps(f"{prefix}{'time_step' if step else 'rate_rpm_per_s'}",
                         step or spec["rate_rpm_per_s"], count, grid, 2, "run-up time steps")]
    orbits = (("top_speed_revolutions", 1), ("cycle_revolutions",
                                             len(spec.get("cycle_speed_ratios") or ())))
    for key, times in orbits:
        parts.append(guard.steps(f"{prefix}{key}", spec[key],
                                 times * guard.orbit_steps(spec[key], step), grid, 2,
                                 "orbit time steps"))
    return parts


def _design(spec: dict, grid: Grid, prefix: str) -> list:
    search, robust = spec["search"], spec["robustness"]
    coarse = Grid.parse(spec["search_grid"])
    square = "population" if search["method"] in ("nsga2", "nsga2_refine") else "budget"
    n = search[square]
    parts = [guard.Work(f"{prefix}search.{square}", n, memory_bytes=guard.SORT_BYTES_PER_PAIR
                        * float(n) ** 2, how=f"a {n:,} × {n:,} matrix of designs "
                        f"({guard.SORT_BYTES_PER_PAIR:g} bytes each)"),
             guard.designs(f"{prefix}search.budget", search["budget"], search["budget"],
                           coarse)]
    band = spec.get("loss_factor_band") or [0.0, 0.0]
    ends = len(set(band) - {band[0]})           # the band's other end, checked per design
    checked = (robust["samples"] if robust.get("tolerances") else 0) + ends
    parts.append(guard.designs(f"{prefix}robustness.samples", robust["samples"],
                               checked * robust["designs"], coarse,
                               f"robustness designs ({robust['designs']} × {checked})"))
    parts.append(guard.designs(f"{prefix}regrid_designs", spec["regrid_designs"],
                               spec["regrid_designs"], grid))
    levers = len(spec.get("what_it_would_take") or {})
    if levers:              # each lever: its scan each way, the refinement, the answer
        parts.append(guard.designs(f"{prefix}what_it_would_take", levers,
                                   levers * LEVER_EVALUATIONS, coarse,
                                   f"designs ({levers} levers × {LEVER_EVALUATIONS})"))
    revolutions = spec.get("limit_cycle_revolutions") or 0.0
    if revolutions > 0:
        parts.append(guard.steps(f"{prefix}limit_cycle_revolutions", revolutions,
                                 guard.orbit_steps(revolutions, None),
                                 Grid.parse(spec["limit_cycle_grid"]), 2, "orbit time steps"))
    return parts


def _points(spec: dict, grid: Grid, prefix: str) -> list:
    """Static solves: the product of the study's list lengths (its points), and the time
    steps of its orbits when it has ``revolutions``."""
    factors = list(_lists(spec))
    if not factors:
        return []
    count = math.prod(len(v) for _, v in factors)
    driver, longest = max(factors, key=lambda f: len(f[1]))
    product = " × ".join(f"{key} {len(v):,}" for key, v in factors)
    parts = [guard.solves(f"{prefix}{driver}", len(longest), count, grid,
                          f"points ({product}), each a static solve,")]
    revolutions = spec.get("revolutions")
    if guard.positive(revolutions):
        parts.append(guard.steps(f"{prefix}revolutions", revolutions,
                                 count * guard.orbit_steps(revolutions, None), grid, 1,
                                 "orbit time steps"))
    return parts


def _lists(data, path: str = "") -> Iterator[tuple]:
    """(key path, list) of every list of points in ``data`` (not inside a list's tables)."""
    for key, value in data.items():
        if key in NOT_POINTS or "grid" in key:
            continue
        where = f"{path}.{key}" if path else key
        if isinstance(value, list) and value:
            yield where, value
        elif isinstance(value, dict):
            yield from _lists(value, where)



#: kinds that name files after the rotor's bearings (components_NAME.csv, waterfall_NAME.png)
NAMES_FILES = ("rotor_run_up",)


def check_file_names(spec: dict, directory, where: str) -> None:
    """Refuse, before the estimate and the plan, what no run of a rotor study can mean: a
    speed range no bearing of the rotor can run at (the rotor's speed rule,
    :func:`gfbopt.inputs.rotor_limits.check_rotor_speeds`: refused as such, not as too much
    work), and a bearing name that cannot be part of the file names the study writes after
    it (:func:`gfbopt.guard.check_file_name_part`)."""
    if spec.get("kind") not in ROTOR_KINDS or not isinstance(spec.get("rotor"), str):
        return
    from pathlib import Path

    from ..inputs.rotor_limits import check_rotor_speeds
    from ..inputs.rotor_system import load_rotor

    path = Path(directory) / spec["rotor"]
    if not path.is_file():                  # the plan names the key (rotor = ...) and the file
        return
    system = load_rotor(path, running=True)      # names and speeds only: any rotor file
    span = spec.get("speed_range_rpm")
    if isinstance(span, (list, tuple)) and len(span) == 2:
        check_rotor_speeds(system, span, f"{where}: speed_range_rpm")
    if spec.get("kind") not in NAMES_FILES:
        return
    for bearing in system.bearings:
        guard.check_file_name_part(bearing.name, f"{where}: rotor {spec['rotor']}: bearing "
                                   "name", "the study writes components_NAME.csv and "
                                   "waterfall_NAME.png")
