"""``gfbopt capacity``: load capacity at a speed, or lift-off speed at a load, for a
minimum-film limit (SI, per bearing)::

    gfbopt capacity --bearing FILE --speed-rpm N --min-film-um H            # largest load
    gfbopt capacity --bearing FILE --lift-off --load-newton F --min-film-um H [--max-speed-rpm N]

A thin layer over :func:`gfbopt.rotor.capacity.load_capacity` and
:func:`~gfbopt.rotor.capacity.lift_off_speed`.  ``--figure FILE`` draws the curve
(h_min against load or speed, the limit and the answer); ``--csv FILE`` writes it, with its
context ``FILE.json`` beside it (:mod:`.csv_context`).  The
formulation comes from the bearing file's ``[model]`` table and the options given here; the
bore, pads and zones from its ``[bore]``, ``[[pads]]`` and ``[[zones]]`` tables.  With
``[journal]``/``[thermal]`` every point of the search is at its own running condition
(:mod:`gfbopt.rotor.running_bearing`): the output names the clearance model and reports
running_clearance_um, centrifugal_growth_um, thermal_growth_um, film_temperature_c and
viscosity_pa_s at the answer, each CSV row carries its own running point (a row with no
running state, e.g. a thermal runaway, has NaN figures and its thermal_status), the CSV's
context names ``thermal_model`` and the figure's title says so.
"""
from __future__ import annotations

import math
import sys

from ..errors import ParameterError
from ..inputs.grid import DEFAULT_GRID
from .common import emit, number
from .csv_context import HELP as CSV_HELP, context_options, write_csv
from .si import seam_angle_text, stated_options


def register(subparsers) -> None:
    sub = subparsers.add_parser("capacity", help="load capacity at a speed, or lift-off "
                                "speed at a load, for a minimum-film limit (SI)")
    sub.add_argument("--bearing", required=True, help="bearing TOML file (SI)")
    sub.add_argument("--min-film-um", type=number("min-film-um"), required=True,
                     help="smallest minimum film allowed [µm]")
    sub.add_argument("--speed-rpm", type=number("speed-rpm"), default=None,
                     help="shaft speed of the load capacity [rpm]")
    sub.add_argument("--lift-off", action="store_true", help="find the lift-off speed of "
                     "--load-newton instead")
    sub.add_argument("--load-newton", type=number("load-newton"), default=None,
                     help="static load on one bearing [N] (with --lift-off)")
    sub.add_argument("--max-speed-rpm", type=number("max-speed-rpm"), default=None,
                     help="highest speed of the lift-off search [rpm] (default 100000)")
    sub.add_argument("--film", default=None, choices=("periodic", "seam"),
                     help="film convention (default: the file's, else a seam 180° from the "
                     "load)")
    sub.add_argument("--seam-angle", type=seam_angle_text, default=None,
                     help="top-foil welded end, degrees from the load line [0, 360)")
    sub.add_argument("--foil", default=None, choices=("rigid", "simple", "beam"),
                     help="foil model (default: the file's, else simple)")
    sub.add_argument("--deflection-law", default=None, choices=("mean", "local"),
                     help="foil deflection law (default: the file's, else mean)")
    sub.add_argument("--grid", default=str(DEFAULT_GRID),
                     help=f"NTHETAxNZ (default {DEFAULT_GRID})")
    sub.add_argument("--figure", default=None, help="draw the curve to this file (png, pdf)")
    sub.add_argument("--csv", default=None, help="write the curve to this CSV" + CSV_HELP)
    sub.add_argument("--json", action="store_true", help="print one JSON object")
    sub.set_defaults(handler=run)


def _check(args) -> None:
    """Contradictory input: one line, before anything is solved."""
    if args.lift_off:
        if args.load_newton is None:
            raise ParameterError("--load-newton", None, "is required with --lift-off")
        if args.speed_rpm is not None:
            raise ParameterError("--speed-rpm", args.speed_rpm, "is not used with --lift-off "
                                 "(the speed is the answer); give --max-speed-rpm to bound it")
    else:
        if args.speed_rpm is None:
            raise ParameterError("--speed-rpm", None, "is required for the load capacity (or "
                                 "give --lift-off --load-newton F)")
        if args.load_newton is not None:
            raise ParameterError("--load-newton", args.load_newton, "is used with --lift-off "
                                 "only (the load is the answer of the load capacity)")
        if args.max_speed_rpm is not None:
            raise ParameterError("--max-speed-rpm", args.max_speed_rpm, "is used with "
                                 "--lift-off only (it bounds the lift-off speed searched)")


def run(args) -> int:
    from ..inputs import Grid
    from ..inputs.options import merge_options
    from ..thermal.files import load_running_bearing
    from ..rotor.running_bearing import running_lift_off, running_load_capacity

    _check(args)
    grid = Grid.parse(args.grid)
    bearing, spec = load_running_bearing(args.bearing)   # [journal], [thermal] checked
    from ..inputs.rotor_limits import check_surface_speed

    check_surface_speed(bearing, [args.speed_rpm], "--speed-rpm")
    check_surface_speed(bearing, [args.max_speed_rpm], "--max-speed-rpm")
    options = merge_options(stated_options(args), bearing.options)
    if args.lift_off:
        extra = {} if args.max_speed_rpm is None else {"max_speed_rpm": args.max_speed_rpm}
        found = running_lift_off(bearing, spec, args.load_newton, args.min_film_um,
                                 options=options, grid=grid, **extra)
    else:
        found = running_load_capacity(bearing, spec, args.speed_rpm, args.min_film_um,
                                      options=options, grid=grid)
    result = _Found(found)
    out = {"bearing": bearing.name, **found}
    options = context_options(args, command="capacity", **out["conventions"])
    if args.csv:
        import pandas as pd

        write_csv(pd.DataFrame(result.curve), args.csv, options, float_format=None)
    if args.figure:
        from ..plotting.bearing import plot_capacity_curve
        from ..plotting.core import save_figure

        save_figure(plot_capacity_curve(out).figure, args.figure)
    emit(out, args.json, lambda: _report(out), options)
    if not result.success and "no lift-off" not in result.message:
        print(f"gfbopt: {result.message}", file=sys.stderr)
    return 0 if result.success or "no lift-off" in result.message else 1


class _Found:
    """success and message of the answer's dict."""

    def __init__(self, found: dict):
        self.success, self.message = bool(found["success"]), found.get("message") or ""
        self.curve = found["curve"]


def _report(out: dict) -> str:
    from ..model_text import built_words
    from .stability import running_lines

    conv = out["conventions"]
    lines = [f"gfbopt capacity — {out['bearing']}: {out['answer']}",
             f"  film: {conv['film_convention']}; foil {conv['foil']}, "
             f"{conv['deflection_law']} law; grid {conv['grid']}"]
    lines += running_lines(out["running"])
    built = built_words(conv)
    if built:
        lines.append(f"  as built: {built}")
    if out["success"] and out["curve"]:
        answered = math.isfinite(out.get("load_capacity_newton", out.get("lift_off_speed_rpm")))
        solved = f"({len(out['curve'])} equilibria solved, {out['wall_time_s']:.2f} s)"
        if math.isfinite(out["min_film_thickness_um"]):
            lines.append(f"  {'at the answer' if answered else 'at the load ceiling'}: "
                         f"h_min = {out['min_film_thickness_um']:.6g} µm {solved}")
        else:                                   # stopped where the running state is lost
            lines.append(f"  searched: {solved}")
    return "\n".join(lines)
