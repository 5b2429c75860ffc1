"""The size of a command's run, estimated from its options before its handler starts
(:mod:`gfbopt.guard`): memory from ``--grid`` and the number of bearing models, time from the
grid × the solves, speeds (``--speed-range``, ``--campbell-speeds``) or time steps
(``--revolutions``, ``--time-step``, ``--run-up``, ``--rate``) it asks for.  Refused, one
line, when above ``--max-memory-gb`` or ``--max-minutes``; ``gfbopt run`` passes the two
limits on to the study runner, which estimates each study from its file."""
from __future__ import annotations

from .. import guard
from ..inputs.grid import DEFAULT_GRID, DEFAULT_MAX_MEMORY_GB, Grid
from .common import number

#: commands whose work the guard estimates (their parsers get the two limit options)
GUARDED = ("static", "linear", "stability", "orbit", "critical-mass", "rotor", "capacity",
           "export-ross", "run")
#: the rotor's bearings (a rigid rotor on two foil bearings)
ROTOR_BEARINGS = 2
#: imbalance-response speeds of ``gfbopt rotor`` (gfbopt.rotor.analyse.IMBALANCE_SPEEDS)
IMBALANCE_SPEEDS = 40
#: static solves of a capacity or lift-off search (marching by a factor, then Brent's method)
CAPACITY_SOLVES = 30


def add_limits(parser) -> None:
    """--max-memory-gb (when the command has none yet) and --max-minutes."""
    known = parser._option_string_actions
    if "--max-memory-gb" not in known:
        parser.add_argument("--max-memory-gb", type=number("max-memory-gb"),
                            default=DEFAULT_MAX_MEMORY_GB, help="refuse a run whose "
                            "estimated memory exceeds this [GB] (default "
                            f"{DEFAULT_MAX_MEMORY_GB:g}; the estimate is printed)")
    if "--max-minutes" not in known:
        parser.add_argument("--max-minutes", type=number("max-minutes"),
                            default=guard.DEFAULT_MAX_MINUTES, help="refuse a run whose "
                            "estimated computing time exceeds this [min] (default "
                            f"{guard.DEFAULT_MAX_MINUTES:g}; a rough estimate from the grid "
                            "and the number of solves, speeds or time steps)")


def limits(args) -> guard.Limits:
    """The two limits of the parsed options."""
    return guard.Limits(getattr(args, "max_memory_gb", DEFAULT_MAX_MEMORY_GB),
                        getattr(args, "max_minutes", guard.DEFAULT_MAX_MINUTES))


def _grid(args) -> Grid:
    text = getattr(args, "grid", None)
    return Grid.parse(text) if text is not None else DEFAULT_GRID


def check_command(args) -> None:
    """Refuse the command when its estimated memory or time is above the limits (before its
    handler; values the handler refuses anyway are left to it)."""
    command = getattr(args, "command", None)
    if command not in GUARDED or command == "run":
        return
    if command in ("orbit", "critical-mass"):      # their step count first (--max-steps)
        from .transient import check_run_length

        check_run_length(args)
    grid = _grid(args)
    check = limits(args)
    models = ROTOR_BEARINGS if command in ("rotor", "export-ross") else 1
    parts = [guard.grid_memory(grid, models=models)]
    if command == "rotor":
        parts += _rotor(args, grid)
    elif command == "orbit":
        revolutions, step = getattr(args, "revolutions", None), getattr(args, "time_step", None)
        if guard.positive(revolutions) and (step is None or guard.positive(step)):
            parts.append(guard.steps("--time-step" if step else "--revolutions",
                                     step or revolutions, guard.orbit_steps(revolutions, step),
                                     grid))
    elif command == "capacity":
        parts.append(guard.solves("--grid", str(grid), CAPACITY_SOLVES, grid))
    elif command == "export-ross":           # both bearings' tables: a speed's work each
        count = getattr(args, "speeds", None)
        if isinstance(count, int) and count > 0:
            parts.append(guard.speeds("--speeds", count, count, grid, ROTOR_BEARINGS,
                                      "table speeds"))
    else:
        parts.append(guard.solves("--grid", str(grid), 1, grid, "static solve"))
        ratios = getattr(args, "whirl_ratio", None) or getattr(args, "frequency_hz", None) or ()
        if ratios:
            parts.append(guard.speeds("--whirl-ratio" if command == "linear" else
                                      "--frequency-hz", len(ratios), len(ratios), grid,
                                      what="frequencies"))
        if command == "stability":
            parts += _scan(args, grid, 1)
    _top_speed(args)              # a range no model can run is refused as such, not as work
    guard.check(parts, check)


def _scan(args, grid: Grid, bearings: int) -> list:
    span = getattr(args, "speed_range", None)
    count = guard.scan_count(*span) if span else None
    if count is None:
        return []
    return [guard.speeds("--speed-range", list(span), count, grid, bearings,
                         "speeds of the onset scan")]


def _rotor(args, grid: Grid) -> list:
    from . import rotor_time

    b = ROTOR_BEARINGS
    if rotor_time.requested(args):
        profile = rotor_time.check_profile(args)       # its own rules first (direction, --force)
        step = getattr(args, "time_step", None)
        if step is not None and not guard.positive(step):
            return []
        if profile.kind == "orbit":
            count = guard.orbit_steps(profile.revolutions, step)
            option, value = ("--time-step", step) if step else ("--revolutions",
                                                                args.revolutions)
        else:
            count = guard.ramp_steps(profile.start_rpm, profile.end_rpm,
                                     profile.rate_rpm_per_s, step)
            option, value = (("--time-step", step) if step else
                             (f"--{profile.kind}", [profile.start_rpm, profile.end_rpm]))
        return [guard.steps(option, value, count, grid, b)]
    parts = _scan(args, grid, b)
    if not parts:
        return []
    if getattr(args, "campbell", False) and isinstance(args.campbell_speeds, int):
        parts.append(guard.speeds("--campbell-speeds", args.campbell_speeds,
                                  args.campbell_speeds, grid, b, "Campbell speeds"))
    if getattr(args, "imbalance_response", False):
        parts.append(guard.speeds("--imbalance-response", True, IMBALANCE_SPEEDS, grid, b,
                                  "imbalance-response speeds"))
    if getattr(args, "half_mass", False):
        parts += _scan(args, grid, b)
    return parts


def _top_speed(args) -> None:
    """A speed range beyond the model's limits (Λ at the top speed; for a rotor also the
    surface speed and Λ at the lowest speed, :func:`~gfbopt.inputs.rotor_limits.check_rotor_speeds`)
    refused before its cost is estimated and before the scan below it."""
    span = getattr(args, "speed_range", None)
    if not span or guard.scan_count(*span) is None:
        return
    if args.command == "rotor":
        from . import rotor_time

        if rotor_time.requested(args):
            return
        from ..inputs.rotor_system import load_rotor
        from ..rotor.analyse import check_speed_span

        check_speed_span(span, load_rotor(args.rotor_file, running=True), "--speed-range")
    elif args.command == "stability" and getattr(args, "bearing", None):
        from ..inputs import load_bearing

        guard.top_speed([(args.bearing, load_bearing(args.bearing, running=True))], span[1],
                        "--speed-range")
