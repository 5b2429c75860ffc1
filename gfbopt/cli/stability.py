"""``gfbopt stability``: is my rotor stable, with what margin, from what speed — in SI units.

A thin layer over :func:`gfbopt.rotor.stability`, :func:`gfbopt.rotor.onset_speed` and
:func:`gfbopt.rotor.coefficient_table`::

    gfbopt stability --bearing FILE.toml --rotor-mass-kg M [--load-newton F] --speed-rpm N
                     [--loss-factor η] [--onset | --speed-range A B] [film and foil options]
                     [--csv FILE] [--json]

M and F are per bearing; without ``--load-newton`` the load is the rotor's weight M g (a
horizontal rigid rotor).  ``--onset`` searches (N/4, 2N); ``--speed-range`` sets the range.
``--csv`` writes K [N/m] and C [N s/m] against excitation frequency [Hz] at the operating point,
one row per frequency, including the threshold whirl frequency ("matched whirl").
Formulation options not given come from the bearing file's ``[model]`` table, else the
defaults (:mod:`gfbopt.cli.si`); every output states the conventions used.

A bearing file with ``[journal]`` and/or ``[thermal]`` is analysed at the running condition
(:mod:`gfbopt.thermal`: centrifugal and thermal growth, Sutherland's viscosity, the lumped
heat balance solved to a fixed point): the operating point at the running clearance of its
speed, the onset by :func:`gfbopt.rotor.running_bearing.running_onset`.  Every output names the
model (``thermal_model``: "isothermal, cold clearance", "centrifugal growth" or "heat
balance + growth") and reports running_clearance_um, centrifugal_growth_um,
thermal_growth_um, film_temperature_c and viscosity_pa_s (gfbopt/terms/thermal.py); a
thermal runaway or a closed clearance is the answer, not an error.
"""
from __future__ import annotations

import sys

from ..errors import ParameterError
from .common import add_grid, emit, number
from .csv_context import HELP as CSV_HELP, context_options, write_context
from ..model_text import built_words, model_words
from .si import seam_angle_text, stated_options

#: --onset without --speed-range searches (N/4, 2N) around the operating speed N [rpm]
ONSET_RANGE = (0.25, 2.0)


def register(subparsers) -> None:
    sub = subparsers.add_parser("stability", help="is the rotor stable, with what margin, "
                                "from what speed (SI units)")
    sub.add_argument("--bearing", required=True, help="bearing TOML file (SI; optional "
                     "[model] table)")
    sub.add_argument("--rotor-mass-kg", type=number("rotor-mass-kg"), default=None,
                     help="rotor mass carried by one bearing [kg]")
    sub.add_argument("--mass", type=number("mass"), default=None,
                     help="the rotor as M̄ = M c ω²/W0 at --speed-rpm instead (needs "
                     "--load-newton; not with --rotor-mass-kg)")
    sub.add_argument("--load-newton", type=number("load-newton"), default=None,
                     help="static load on one bearing [N] (default: the rotor's weight M g)")
    sub.add_argument("--speed-rpm", type=number("speed-rpm"), default=None,
                     help="shaft speed of the operating point [rpm]")
    sub.add_argument("--loss-factor", type=number("loss-factor"), default=None,
                     help="structural loss factor η of the bumps, 0–1 (default 0, or the file's)")
    onset = sub.add_mutually_exclusive_group()
    onset.add_argument("--onset", action="store_true", help="also find the onset speed of "
                       f"whirl in ({ONSET_RANGE[0]:g} N, {ONSET_RANGE[1]:g} N)")
    onset.add_argument("--speed-range", type=number("speed-range"), nargs=2, default=None,
                       metavar=("LOW", "HIGH"), help="find the onset speed in this range [rpm]")
    sub.add_argument("--film", default=None, choices=("periodic", "seam"),
                     help="film convention (default: the file's, else a seam 180° from the "
                     "load)")
    sub.add_argument("--seam-angle", type=seam_angle_text, default=None,
                     help="top-foil welded end, degrees from the load line in the direction "
                     "of rotation [0, 360), or max_film")
    sub.add_argument("--foil", default=None, choices=("rigid", "simple", "beam"),
                     help="foil model (default: the file's, else simple)")
    sub.add_argument("--deflection-law", default=None, choices=("mean", "local"),
                     help="mean: W = S(P̄ − 1); local: W = S(P − 1) (default: the file's, else "
                     "mean)")
    sub.add_argument("--frequency-hz", type=number("frequency-hz"), nargs="+", default=None,
                     help="excitation frequencies of the K, C table [Hz] (default: 0.1 … 1.0 "
                     "times the shaft frequency, plus the matched whirl)")
    sub.add_argument("--csv", default=None, help="write K [N/m], C [N s/m] against frequency "
                     "to this CSV (columns kxx_N_per_m … cyy_Ns_per_m, gfbopt.glossary)"
                     + CSV_HELP)
    add_grid(sub)
    sub.add_argument("--json", action="store_true", help="print one JSON object (the same "
                     "fields whatever the flags; null when not computed)")
    sub.set_defaults(handler=run)


def _check(args) -> None:
    """Bad or contradictory input: one line, before anything is built or solved."""
    if args.rotor_mass_kg is not None and args.mass is not None:
        raise ParameterError("--mass", args.mass, "contradicts --rotor-mass-kg: give the rotor "
                             "either in kg or as the non-dimensional M̄, not both")
    if args.rotor_mass_kg is None and args.mass is None:
        raise ParameterError("--rotor-mass-kg", None, "is required (rotor mass per bearing)")
    for option, value in (("--rotor-mass-kg", args.rotor_mass_kg), ("--mass", args.mass),
                          ("--load-newton", args.load_newton), ("--speed-rpm", args.speed_rpm)):
        if value is not None and not value > 0:
            raise ParameterError(option, value, "must be > 0")
    if args.loss_factor is not None and args.loss_factor < 0:
        raise ParameterError("--loss-factor", args.loss_factor, "must be >= 0 (a negative loss "
                             "factor would feed energy into the rotor)")
    if args.mass is not None and (args.load_newton is None or args.speed_rpm is None):
        raise ParameterError("--mass", args.mass, "needs --load-newton and --speed-rpm (with "
                             "the load taken as the weight M g, M̄ = c ω²/g does not depend "
                             "on M)")
    if args.speed_rpm is None and args.speed_range is None:
        raise ParameterError("--speed-rpm", None, "is required (or give --speed-range)")
    if args.onset and args.speed_rpm is None:
        raise ParameterError("--onset", True, "needs --speed-rpm (it searches around it)")
    if args.speed_rpm is None and (args.csv or args.frequency_hz):
        raise ParameterError("--csv/--frequency-hz", args.csv or args.frequency_hz,
                             "need --speed-rpm (the coefficients belong to an operating point)")
    if args.speed_range is not None:
        low, high = args.speed_range
        if not 0 < low < high:
            raise ParameterError("--speed-range", args.speed_range,
                                 "must be two speeds 0 < LOW < HIGH [rpm]")


def _provenance_options(args, grid, options, out: dict) -> dict:
    """The options of the provenance block of --json and of the CSV's context file: the
    formulation (friction and hardening when stated), the clearance model and, once the
    operating point is solved, its running clearance."""
    running = {k: out.get(k) for k in RUNNING_FIELDS[:-1]}
    return context_options(args, command="stability", grid=str(grid), **options.to_dict(),
                           **running)


#: the fields of the operating-point answer (StabilityResult.to_dict without conventions)
POINT_FIELDS = (
    "stable", "verdict", "critical_mass_kg", "mass_margin", "whirl_frequency_hz",
    "growth_rate_per_s", "log_decrement", "threshold_whirl_frequency_hz", "eccentricity",
    "attitude_angle_deg", "min_film_thickness_um", "bearing_number", "load", "mass",
    "critical_mass", "threshold_whirl_ratio", "mode_whirl_ratio", "growth_rate", "speed_rpm",
    "load_newton", "wall_time_s")
#: one JSON schema for ``gfbopt stability --json``, whatever the flags: every field present,
#: null when not computed (the operating point without --speed-rpm, the onset without
#: --onset/--speed-range, the CSV path without --csv)
#: the clearance at speed's fields (gfbopt.thermal.running.RunningPoint.to_dict), present
#: whatever the model: the running point of the operating point (null without --speed-rpm)
RUNNING_FIELDS = ("thermal_model", "running_clearance_um", "centrifugal_growth_um",
                  "thermal_growth_um", "film_temperature_c", "viscosity_pa_s", "running")
SCHEMA = ("bearing", "rotor_mass_kg", "grid", "conventions", *POINT_FIELDS, "coefficients",
          "csv", "onset", "onset_speed_rpm", "onset_whirl_frequency_hz", *RUNNING_FIELDS,
          "success", "message", "warnings")


def _span(args) -> tuple:
    """The onset search range [rpm]: --speed-range, or (N/4, 2N) around --speed-rpm."""
    return (tuple(args.speed_range) if args.speed_range is not None
            else tuple(f * args.speed_rpm for f in ONSET_RANGE))


def run(args) -> int:
    from ..inputs import Rotor
    from ..inputs.conversions import mass_from_parameter, rpm_to_rad_per_s
    from ..inputs.options import merge_options
    from ..progress import progress
    from ..rotor import coefficient_table, onset_speed
    from ..rotor.analysis import resolve_case
    from ..rotor.onset import check_speed_range
    from ..static import SolverCache
    from ..thermal.files import load_running_bearing
    from ..rotor.running_bearing import running_onset
    from ..thermal.running import ISOTHERMAL
    from .common import grid_of

    _check(args)
    grid = grid_of(args)
    bearing, spec = load_running_bearing(args.bearing)      # [journal], [thermal] checked
    from ..inputs.rotor_limits import check_surface_speed

    check_surface_speed(bearing, [args.speed_rpm], "--speed-rpm")
    check_surface_speed(bearing, list(args.speed_range or ()), "--speed-range")
    options = merge_options(stated_options(args), bearing.options)
    if args.mass is not None and spec.model_name != ISOTHERMAL:
        raise ParameterError("--mass", args.mass, "a bearing file with [journal]/[thermal] "
                             "runs at the clearance of its running condition, so M̄ = M c ω²/W0 "
                             "names no rotor before that is solved: give --rotor-mass-kg")
    if args.mass is not None:      # M = M̄ W0/(c ω²): the same rotor, in kg
        mass = mass_from_parameter(args.mass, bearing.radial_clearance,
                                   rpm_to_rad_per_s(args.speed_rpm), args.load_newton)
    else:
        mass = args.rotor_mass_kg
    rotor = Rotor(mass)
    cache = SolverCache(grid)
    common = dict(options=options, grid=grid, cache=cache)
    out = dict.fromkeys(SCHEMA)
    out.update(bearing=bearing.name, rotor_mass_kg=mass, grid=str(grid),
               load_newton=args.load_newton,        # as typed; the operating point's below
               conventions=options.to_dict(), warnings=[], thermal_model=spec.model_name)
    result = table = onset = None
    wants_onset = args.onset or args.speed_range is not None
    resolve_case(bearing, rotor, args.load_newton, **common)    # bad input: before any solve
    if wants_onset:
        check_speed_range(_span(args))
    # the operating point's two steps have a status of their own; the onset search reports its
    # own progress (one line per speed when stderr is not a terminal).  A bar is closed on
    # success only: an error is one line of its own, with no status after it
    if args.speed_rpm is not None:
        bar = progress(total=2, desc="stability", unit="step")
        bar.set_postfix_str(f"operating point {args.speed_rpm:.6g} rpm")
        result, point, warm = _operating_point(bearing, spec, rotor, args, common)
        out.update(_running_fields(point))
        if result is None:                         # thermal runaway or a closed clearance
            out.update(verdict=point.status, speed_rpm=args.speed_rpm)
            out["warnings"].append(point.message)
            bar.close()
        else:
            answer = result.to_dict()
            out.update({k: answer[k] for k in POINT_FIELDS},
                       conventions=result.conventions,
                       warnings=list(result.warnings))
            bar.update(1)
            bar.set_postfix_str("K and C against frequency")
            table = coefficient_table(result.linearisation, warm, args.speed_rpm,
                                      args.frequency_hz, result.threshold_whirl_ratio)
            out["coefficients"] = table.to_dict()
            if args.csv:
                from ..rotor.coefficients import COLUMNS

                write_context(table.write_csv(args.csv), COLUMNS,
                              _provenance_options(args, grid, options, out))
                out["csv"] = str(args.csv)
            bar.update(1)
            bar.close()
    if wants_onset:
        span = _span(args)
        if spec.model_name == ISOTHERMAL:
            onset = onset_speed(bearing, rotor, args.load_newton, span, **common,
                                progress=True)
            found = onset.to_dict()
        else:
            # searched from the range's geometric mean whatever --speed-rpm (one answer:
            # the study rows and gfbopt.api search from there too)
            found = running_onset(bearing, spec, rotor, args.load_newton, span,
                                  progress=True, **common)
            onset = _Answered(found)
        out["onset"] = {k: v for k, v in found.items() if k != "conventions"}
        out["onset_speed_rpm"] = found["onset_speed_rpm"]
        out["onset_whirl_frequency_hz"] = found.get("whirl_frequency_hz")
        if result is None and "conventions" in found:
            out["conventions"] = found["conventions"]
        if args.speed_rpm is None and found.get("running"):    # the onset's running point
            d = found["running"]
            out.update({k: d[k] for k in RUNNING_FIELDS[:-1]}, running=d)
    done = [r for r in (result, onset) if r is not None]
    success = all(r.success for r in done)
    out["success"] = success
    out["message"] = "; ".join(r.message for r in done if r.message)
    emit(out, args.json, lambda: _report(out, result, onset, table, args.csv),
         _provenance_options(args, grid, options, out))
    if not success:
        print("gfbopt: the stability analysis did not complete: "
              f"{(result and result.message) or (onset and onset.message)}", file=sys.stderr)
        return 1
    return 0


class _Answered:
    """The running onset's dict seen as a result (success, message, answer)."""

    def __init__(self, found: dict):
        self.success = bool(found.get("success", True))
        self.message = found.get("message") or ""
        self.answer = found.get("answer", "")


def _operating_point(bearing, spec, rotor, args, common):
    """(StabilityResult or None, RunningPoint, the bearing analysed): at the running
    condition when the file states [journal]/[thermal], else today's analysis exactly."""
    from ..inputs import OperatingPoint
    from ..rotor.running_bearing import running_stability

    return running_stability(bearing, spec, rotor,
                             OperatingPoint(args.speed_rpm, args.load_newton), **common)


def _running_fields(point) -> dict:
    """The clearance at speed's top-level fields of the answer (RUNNING_FIELDS)."""
    d = point.to_dict()
    return {"thermal_model": d["thermal_model"],
            **{k: d[k] for k in RUNNING_FIELDS[1:-1]}, "running": d}


def running_lines(d: dict) -> list:
    """The text lines of a running point's dict (RunningPoint.to_dict)."""
    import math

    def finite(key):
        return d.get(key) is not None and math.isfinite(d[key])

    if not finite("running_clearance_um"):          # runaway or closure: no state to show
        return [f"  clearance model: {d['thermal_model']}; no running state at "
                f"{d['speed_rpm']:,.0f} rpm ({d['thermal_status']}; cold clearance "
                f"{d['cold_clearance_um']:.4g} µm)", f"  {d['thermal_message']}"]
    lines = [f"  clearance model: {d['thermal_model']}; running clearance "
             f"{d['running_clearance_um']:.4g} µm (cold {d['cold_clearance_um']:.4g}, "
             f"centrifugal growth {d['centrifugal_growth_um']:.3g}, thermal growth "
             f"{d['thermal_growth_um']:.3g} µm)"]
    if finite("film_temperature_c"):
        lines.append(f"  heat balance: film {d['film_temperature_c']:.1f} °C, journal "
                     f"{d['journal_temperature_c']:.1f} °C, sleeve "
                     f"{d['sleeve_temperature_c']:.1f} °C; drag {d['heat_generated_w']:.3g} W; "
                     f"μ = {d['viscosity_pa_s']:.4g} Pa s "
                     f"({d['thermal_static_solves']} static solves)")
    if d["thermal_message"]:
        lines.append(f"  {d['thermal_message']}")
    return lines


def _report(out, result, onset, table, csv) -> str:
    conv = out["conventions"]
    lines = [f"gfbopt stability — {out['bearing']}, rotor {out['rotor_mass_kg']:.4g} kg per "
             f"bearing, grid {out['grid']}",
             f"  conventions: {conv['film_convention']}; {model_words(conv)}"]
    built = built_words(conv)
    if built:
        lines.append(f"  as built: {built}")
    if out.get("running"):
        lines += running_lines(out["running"])
    else:
        lines.append(f"  clearance model: {out['thermal_model']}")
    if result is not None:
        r = result
        lines += [
            f"  operating point: {r.speed_rpm:.6g} rpm, load {r.load_newton:.4g} N "
            f"({r.conventions['load_source']})",
            f"  equilibrium: ε = {r.eccentricity:.4f}, attitude {r.attitude_angle_deg:.2f}°, "
            f"minimum film {r.min_film_thickness_um:.2f} µm",
            f"  Λ = {r.bearing_number:.4g}, W̄0 = {r.load_parameter:.4g}, M̄ = {r.mass_parameter:.4g}"
            f", M̄c = {r.critical_mass_parameter:.4g}",
            f"  verdict: {r.verdict.upper()} — critical mass {r.critical_mass_kg:.4g} kg, "
            f"mass margin {r.mass_margin:+.1%}",
            f"  least-damped mode: whirl {r.whirl_frequency_hz:.4g} Hz, growth rate "
            f"{r.growth_rate_per_s:.4g} 1/s, log decrement {r.log_decrement:.4g}",
            f"  threshold whirl (matched whirl for K, C): "
            f"{r.threshold_whirl_frequency_hz:.4g} Hz (γ = {r.threshold_whirl_ratio:.3f})"]
        if r.message:
            lines.append(f"  note: {r.message}")
        if csv:
            lines.append(f"  K [N/m], C [N s/m] against frequency written to {csv} "
                         f"({len(table.table)} rows; frame: {table.frame})")
    if onset is not None:
        lines.append(f"  onset: {onset.answer}")
    shown = (out.get("running") or {}).get("thermal_message")    # printed above already
    lines += [f"  WARNING: {w}" for w in out["warnings"] if w != shown]
    return "\n".join(lines)
