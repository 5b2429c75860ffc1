"""One guard on the size of a run: memory and computing time estimated from the work count,
checked before anything is built or solved, for every command and every study.

A run is split into :class:`Work` parts, each driven by one option or study key (the grid,
``--campbell-speeds``, ``--time-step``, ``budget``, ``samples`` …).  A part's memory is that
of the models it builds at its grid (:func:`gfbopt.inputs.grid.grid_estimate`: 70 MB plus
10 kB per node and model) or of the arrays it allocates; its time is its count of solves,
speeds, evaluations or time steps × the grid's nodes × a cost per node measured on this
project's reference machine (constants below).  :func:`check` refuses a run whose peak
memory exceeds ``--max-memory-gb`` or whose summed time exceeds ``--max-minutes``, with one
line naming the option or key that drives the estimate, its value, the estimate and the
option that raises the limit (:class:`~gfbopt.errors.ParameterError`, exit 2).

The estimates are rough (a factor of a few either way: warm starts, convergence and the
machine differ); they exist to refuse at once runs that would take hours or more memory than
the machine has, not to predict a run's length.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Iterable, Optional

from .errors import ParameterError
from .inputs.grid import (BASE_MEMORY_BYTES, DEFAULT_MAX_MEMORY_GB, MEMORY_PER_NODE_BYTES,
                          SOLVE_SECONDS_PER_NODE, Grid)

#: default largest estimated computing time of one command or study [min]; ``--max-minutes``
#: (``max_minutes=`` in Python) raises it
DEFAULT_MAX_MINUTES = 60.0
#: time of one speed of an onset scan, Campbell diagram or imbalance response, per bearing:
#: a part independent of the grid [s] and a part per grid node [s].  Measured on the blower
#: rotor (8,000–12,000 rpm, Campbell diagrams of 3 and 13 speeds, the difference over 10):
#: 1.45 s per speed at 12x4 (a coarse grid's statics and tracking take longer, not shorter),
#: 0.18 s at 24x8, 0.37 s at 36x10 (4.5e-4 s per node and bearing); onset scans 1.6e-4 s per
#: node and bearing at 36x10.  The node part was 2e-4 s alone, which let 100,000 Campbell
#: speeds at 12x4 through as 43 min (they take about 40 h).
SPEED_SECONDS_PER_BEARING = 0.75
SPEED_SECONDS_PER_NODE = 5e-4
#: time of one transient time step per bearing and grid node [s] (measured 4.5e-6 s: blower
#: rotor orbit, 40 revolutions at 13,000 rpm, rkc, Δτ = 0.1, 36x10)
STEP_SECONDS_PER_NODE = 5e-6
#: the default time step of an orbit and of a ramp [rad] (gfbopt.cli.transient,
#: gfbopt.transient.rotor_analysis.RAMP_MAX_STEP): the fewest steps a run can take
ORBIT_STEP, RAMP_STEP = 0.1, 0.2
#: geometric ratio of the speeds of an onset scan (gfbopt.rotor.onset.SCAN_RATIO)
SCAN_RATIO = 1.25
#: CPU time of one bearing-pair design evaluation at 36x10 (the blower's first onset of every
#: mode over its search range, the film and the drag: 1.03 s measured, rounded up to 1.5 s),
#: and the exponent of its growth with the grid's nodes (36x10 1.03 s, 72x20 1.84 s, 144x36
#: 5.28 s CPU: ≈ nodes^0.6).  A speed-by-speed estimate (:func:`speeds`) overstated the main
#: job 100–150× (57 min for a run of 44 s CPU): a design's onset search evaluates few speeds.
DESIGN_SECONDS_36X10 = 1.5
DESIGN_GRID_EXPONENT = 0.6
#: bytes per pair of designs of NSGA-II's non-dominated sorting (a population² matrix)
SORT_BYTES_PER_PAIR = 8.0


@dataclass(frozen=True)
class Work:
    """One part of a run: the option or key that drives it, its value, and its estimated
    peak memory [bytes] and time [s], with how they were estimated (``how``)."""

    option: str
    value: object
    memory_bytes: float = 0.0
    seconds: float = 0.0
    how: str = ""
    basis: str = ""


@dataclass(frozen=True)
class Limits:
    """The largest estimated memory [GB] and time [min], and the options that raise them."""

    max_memory_gb: float = DEFAULT_MAX_MEMORY_GB
    max_minutes: float = DEFAULT_MAX_MINUTES
    memory_option: str = "--max-memory-gb"
    time_option: str = "--max-minutes"

    def __post_init__(self) -> None:
        for option, value in ((self.memory_option, self.max_memory_gb),
                              (self.time_option, self.max_minutes)):
            if not (isinstance(value, (int, float)) and value > 0 and math.isfinite(value)):
                raise ParameterError(option, value, "must be > 0")


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.3g} s"
    if seconds < 7200:
        return f"{seconds / 60:.3g} min"
    if seconds < 3.15e7:
        return f"{seconds / 3600:.3g} h"
    return f"{seconds / 3.15e7:.3g} years"


def check(parts: Iterable[Work], limits: Optional[Limits] = None) -> list:
    """``parts`` unless the peak memory (the largest part's) exceeds ``limits.max_memory_gb``
    or the summed time exceeds ``limits.max_minutes``: then ParameterError naming the part
    that contributes most, its value, the estimate and the option that raises the limit."""
    parts = [p for p in parts if p is not None]
    limits = limits or Limits()
    heavy = max(parts, key=lambda p: p.memory_bytes, default=None)
    if heavy is not None and heavy.memory_bytes > limits.max_memory_gb * 1e9:
        raise ParameterError(heavy.option, heavy.value, (
            f"{heavy.how}: estimated {heavy.memory_bytes / 1e9:.3g} GB of memory"
            f"{f' ({heavy.basis})' if heavy.basis else ''}, above the "
            f"limit of {limits.max_memory_gb:g} GB: make it smaller or raise "
            f"{limits.memory_option}"))
    total = sum(p.seconds for p in parts)
    if total > limits.max_minutes * 60:
        slow = max(parts, key=lambda p: p.seconds)
        rest = (f" (of {_duration(total)} in all)" if total > 1.05 * slow.seconds else "")
        raise ParameterError(slow.option, slow.value, (
            f"{slow.how}: estimated {_duration(slow.seconds)} of computing{rest}, a rough "
            f"estimate above the limit of {limits.max_minutes:g} min: make it smaller or "
            f"raise {limits.time_option}"))
    return parts


# ------------------------------------------------------------------------- the pieces
def nodes(grid: Grid) -> int:
    """Grid nodes (the count of :func:`gfbopt.inputs.grid.grid_estimate`)."""
    return (grid.n_theta + 1) * (grid.n_z + 1)


def grid_memory(grid: Grid, option: str = "grid", models: int = 1) -> Work:
    """The memory of ``models`` bearing models built at ``grid``."""
    n = nodes(grid)
    many = f" × {models} bearing models" if models > 1 else ""
    return Work(option, str(grid), BASE_MEMORY_BYTES + models * MEMORY_PER_NODE_BYTES * n,
                how=f"{n:,} nodes{many}", basis=f"{MEMORY_PER_NODE_BYTES / 1e3:g} kB per "
                "node and model, measured up to 288x72")


def solves(option: str, value, count: float, grid: Grid, what: str = "static solves") -> Work:
    """``count`` cold static solves at ``grid`` (1 ms per node, gfbopt.inputs.grid)."""
    return Work(option, value, seconds=count * SOLVE_SECONDS_PER_NODE * nodes(grid),
                how=f"{count:,.6g} {what} at {grid} ({SOLVE_SECONDS_PER_NODE * 1e3:g} ms per "
                "node each)")


def speeds(option: str, value, count: float, grid: Grid, bearings: int = 1,
           what: str = "speeds") -> Work:
    """``count`` speeds of a scan, Campbell diagram or response, ``bearings`` at each."""
    per = (SPEED_SECONDS_PER_BEARING + SPEED_SECONDS_PER_NODE * nodes(grid)) * bearings
    return Work(option, value, seconds=count * per,
                how=f"{count:,.6g} {what} × {bearings} bearing(s) at {grid} "
                f"({per:.2g} s each)")


def designs(option: str, value, count: float, grid: Grid, what: str = "designs") -> Work:
    """``count`` bearing-pair design evaluations at ``grid`` (:data:`DESIGN_SECONDS_36X10`)."""
    per = DESIGN_SECONDS_36X10 * (nodes(grid) / nodes(Grid(36, 10))) ** DESIGN_GRID_EXPONENT
    return Work(option, value, seconds=count * per,
                how=f"{count:,.6g} {what} at {grid} ({per:.2g} s each)")


def steps(option: str, value, count: float, grid: Grid, bearings: int = 1,
          what: str = "time steps") -> Work:
    """``count`` transient time steps, ``bearings`` films each."""
    per = STEP_SECONDS_PER_NODE * nodes(grid) * bearings
    return Work(option, value, seconds=count * per,
                how=f"{count:.3g} {what} × {bearings} bearing film(s) at {grid} "
                f"({per:.2g} s each)")


def scan_count(low, high) -> Optional[int]:
    """Speeds of an onset scan over [low, high] rpm (ratio 1.25), None when not a range."""
    try:
        low, high = float(low), float(high)
    except (TypeError, ValueError):
        return None
    if not (math.isfinite(low) and math.isfinite(high) and 0 < low < high):
        return None
    span = math.log(high) - math.log(low)       # not log(high/low): 1e300/1e-300 overflows
    return max(2, math.ceil(span / math.log(SCAN_RATIO) - 1e-9) + 1)


def orbit_steps(revolutions: float, time_step: Optional[float]) -> float:
    """Time steps of ``revolutions`` at a constant speed (step in rad of rotation)."""
    return revolutions * 2 * math.pi / (time_step or ORBIT_STEP)


def ramp_steps(start_rpm: float, end_rpm: float, rate: float,
               time_step: Optional[float]) -> float:
    """Time steps of a linear ramp (step in rad of rotation at the top speed)."""
    duration = abs(end_rpm - start_rpm) / rate
    return max(start_rpm, end_rpm) / 60 * duration * 2 * math.pi / (time_step or RAMP_STEP)


def positive(value) -> bool:
    """A finite number > 0 (what a count or a step must be to be estimated)."""
    return (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value) and value > 0)


def top_speed(geometries, high_rpm: float, option: str) -> None:
    """Refuse a top speed at which a bearing's Λ is beyond the model's limit at once (the
    scan would otherwise solve every lower speed first)."""
    from .inputs.model import MAX_BEARING_NUMBER

    for name, geometry in geometries:
        value = geometry.bearing_number(high_rpm)
        if value > MAX_BEARING_NUMBER:
            raise ParameterError(option, high_rpm, (
                f"at the top speed bearing {name} has Λ = {value:.3g}, above the model's "
                f"limit of {MAX_BEARING_NUMBER:g} (real gas bearings run below Λ ≈ 100): "
                "give a lower top speed"))


#: characters no file name may hold (a path separator, NUL, control characters)
UNSAFE_IN_FILE_NAME = re.compile(r"[/\\\x00-\x1f\x7f]")


def check_file_name_part(name, where: str, writes: str) -> str:
    """``name`` if it can be part of a file name (``writes`` says which files are named
    after it), else ParameterError: refused, not sanitised, so that the files carry the name
    the user gave."""
    if (not isinstance(name, str) or not name.strip() or name in (".", "..")
            or UNSAFE_IN_FILE_NAME.search(name) or len(name.encode()) > 200):
        raise ParameterError(where, name, f"cannot be part of a file name ({writes}): no '/', "
                             "'\\', control characters, '.' or '..', at most 200 bytes")
    return name
