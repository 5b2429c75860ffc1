"""``gfbopt rotor``: a rotor (rigid, or a flexible shaft) on two foil bearings — which mode whirls first, from what
speed, the Campbell diagram and the imbalance response.  A thin layer over
:func:`gfbopt.rotor.analyse.analyse_rotor`::

    gfbopt rotor ROTOR.toml --speed-range LOW HIGH [--speed-rpm N] [--campbell]
                 [--imbalance-response [--imbalance-plane G_MM PHASE_DEG POSITION_M … |
                 --imbalance-grade G]] [--half-mass] [--grid NTxNZ] [--json] [--csv DIR]
                 [--plot DIR]

The transient's options (:mod:`.rotor_time`) are refused without a transient, one line each
with what they set; ``--imbalance-plane``/``--imbalance-grade`` replace the file's imbalance
for ``--imbalance-response`` too (a grade's top speed is HIGH of ``--speed-range``).

The rotor file (docs/formats/rotor_file.md) is read and checked, with every bearing file,
before anything is solved.  JSON fields: ``onset_speed_rpm`` (first onset over all modes; null
with ``onset_reason`` when none in the range), ``first_mode``, ``onset_whirl_frequency_hz``,
``modes`` (one per mode, tracked along speed, :mod:`gfbopt.rotor.mode_search`: label, onset
speed, its own whirl frequency at the onset — null for a mode stable over the range, whose
threshold's is ``threshold_whirl_frequency_hz`` — and shape), ``bearing_loads_newton``,
``bearing_notes`` (a bearing pulled upwards, in one sentence), ``warnings`` (the statics'
plausibility flags: a film thinner than surface roughness, a load above the rule-of-thumb
capacity, each with its bearing and speed), ``campbell.tracks`` (every tracked mode's name:
one name per mode in the text, JSON, CSV and figures, :mod:`gfbopt.rotor.tracking`;
``campbell.frequency_limit_hz``: a shaft's modes are followed up to it),
``imbalance_response`` (``unstable_from_rpm``; each peak's ``above_first_onset``: the linear
response there is not physical), ``imbalance_planes``, ``conventions`` and ``provenance``.
``--csv DIR`` adds ``csv`` (the files written) and changes nothing else in the JSON; each CSV
has its context ``FILE.csv.json`` beside it (:mod:`.csv_context`).

Speed ranges: HIGH/LOW ≤ 1000, and speeds every bearing can run at (surface speed and bearing
number, :func:`gfbopt.rotor.analyse.check_speed_span`).
"""
from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

from ..errors import ParameterError
from ..inputs.grid import DEFAULT_GRID
from . import rotor_time
from .common import emit, integer, number
from .csv_context import HELP as CSV_HELP, context_options, write_csv
from ..model_text import built_words, model_words


def register(subparsers) -> None:
    sub = subparsers.add_parser("rotor", help="a rotor (rigid, or a flexible shaft) on two foil "
                                "bearings: onset of each mode, Campbell diagram, imbalance "
                                "response (SI)")
    sub.add_argument("rotor_file", metavar="ROTOR.toml", help="rotor file (SI; "
                     "docs/formats/rotor_file.md)")
    sub.add_argument("--speed-range", type=number("speed-range"), nargs=2, default=None,
                     metavar=("LOW", "HIGH"), help="speeds searched [rpm]")
    sub.add_argument("--speed-rpm", type=number("speed-rpm"), default=None,
                     help="also report the modes and each bearing's equilibrium at this speed "
                     "[rpm]")
    sub.add_argument("--campbell", action="store_true", help="Campbell diagram over the "
                     "range (full-system eigenvalues)")
    sub.add_argument("--campbell-speeds", type=integer("campbell-speeds"), default=20,
                     help="speeds of the Campbell diagram (default 20)")
    sub.add_argument("--imbalance-response", action="store_true",
                     help="linear imbalance response over the range (needs [[imbalance]])")
    sub.add_argument("--half-mass", action="store_true", help="also the per-bearing "
                     "approximation (each bearing alone with its share of mass and load)")
    sub.add_argument("--grid", default=str(DEFAULT_GRID),
                     help=f"NTHETAxNZ (default {DEFAULT_GRID})")
    sub.add_argument("--json", action="store_true", help="print one JSON object")
    sub.add_argument("--csv", default=None, metavar="DIR", help="write the tables as CSV "
                     "files in DIR (the JSON is the same with or without it, plus the list "
                     "'csv' of the files)" + CSV_HELP)
    sub.add_argument("--plot", default=None, metavar="DIR", help="write the figures (PNG) "
                     "in DIR")
    rotor_time.add_arguments(sub)      # --orbit, --run-up, --coast-down
    sub.set_defaults(handler=run)


def _check(args) -> None:
    if args.speed_range is None:
        raise ParameterError("--speed-range", None, "is required (or --orbit, --run-up, "
                             "--coast-down for a transient)")
    low, high = args.speed_range
    if not (math.isfinite(low) and math.isfinite(high) and 0 < low < high):
        raise ParameterError("--speed-range", args.speed_range,
                             "must be two speeds 0 < LOW < HIGH [rpm]")
    from ..rotor.analyse import check_speed_span

    check_speed_span(args.speed_range, name="--speed-range")
    if args.speed_rpm is not None and not args.speed_rpm > 0:
        raise ParameterError("--speed-rpm", args.speed_rpm, "must be > 0 [rpm]")
    if args.campbell_speeds < 2:
        raise ParameterError("--campbell-speeds", args.campbell_speeds, "must be >= 2")
    if not args.campbell and args.campbell_speeds != 20:
        raise ParameterError("--campbell-speeds", args.campbell_speeds, "needs --campbell")
    rotor_time.check_unused(args)
    if args.plot and not (args.campbell or args.imbalance_response or args.half_mass):
        raise ParameterError("--plot", args.plot, "needs --campbell, --imbalance-response or "
                             "--half-mass (there is no figure of the onsets alone)")


def run(args) -> int:
    from ..inputs import Grid
    from ..inputs.rotor_limits import check_rotor_speeds
    from ..inputs.rotor_system import load_rotor
    from ..rotor.analyse import analyse_rotor, check_speed_span

    if rotor_time.requested(args):
        return rotor_time.handle(args)
    _check(args)
    grid = Grid.parse(args.grid)
    system = load_rotor(args.rotor_file, running=True)    # [journal]/[thermal] read
    check_speed_span(args.speed_range, system, name="--speed-range")
    if args.speed_rpm is not None:
        check_rotor_speeds(system, [*args.speed_range, args.speed_rpm], name="--speed-rpm")
    planes = rotor_time.imbalance_planes(args, system, args.speed_range[1])
    if planes is not None:
        system = replace(system, imbalance=planes)
    if args.imbalance_response and not system.imbalance:
        raise ParameterError(f"{args.rotor_file}: imbalance", None, "--imbalance-response "
                             "needs an imbalance: an [[imbalance]] plane in the rotor file, "
                             "--imbalance-plane G_MM PHASE_DEG POSITION_M or "
                             "--imbalance-grade G")
    result = analyse_rotor(system, tuple(args.speed_range), speed_rpm=args.speed_rpm,
                           campbell=args.campbell, imbalance=args.imbalance_response,
                           half_mass=args.half_mass, grid=grid,
                           campbell_speeds=args.campbell_speeds,
                           show_progress=not args.json)
    out = {"rotor_file": args.rotor_file, "rotor": system.body.name, "grid": str(grid),
           **result.to_dict()}
    if args.imbalance_response:
        out["imbalance_planes"] = [
            {"name": p.name, "amount_g_mm": p.amount_kg_m * 1e6, "phase_deg": p.phase_deg,
             "position_m": p.position,
             "source": "rotor file" if planes is None else "command line"}
            for p in system.imbalance]
    # the conventions block of the JSON (each bearing's film, foil, friction, hardening and
    # clearance model) in the provenance too, so every CSV's context file names the model
    options = context_options(args, command="rotor", grid=str(grid),
                              rotor_file=args.rotor_file, conventions=out["conventions"])
    if args.csv:        # the JSON is the same with or without --csv, plus this list
        folder = Path(args.csv)
        folder.mkdir(parents=True, exist_ok=True)
        out["csv"] = [str(write_csv(frame, folder / f"{name}.csv", options))
                      for name, frame in result.tables().items()]
    if args.plot:
        out["figures"] = _figures(result, Path(args.plot), args.speed_range[1])
    emit(out, args.json, lambda: _report(out), options)
    return 0


def _figures(result, folder: Path, top: float) -> list:
    from ..plotting.core import save_figure
    from ..plotting.rotor import plot_campbell, plot_imbalance_response, plot_onsets

    folder.mkdir(parents=True, exist_ok=True)
    onsets = {m.label: m.onset_speed_rpm for m in result.onsets.modes}
    paths = []
    if result.campbell is not None and len(result.campbell.table):
        ax, _ = plot_campbell(result.campbell.table, onsets, top)
        paths.append(save_figure(ax.figure, folder / "campbell.png"))
    if result.imbalance is not None and len(result.imbalance.table):
        ax, _ = plot_imbalance_response(result.imbalance.table, result.imbalance.peaks,
                                        onsets, top,
                                        unstable_from_rpm=result.imbalance.unstable_from_rpm)
        paths.append(save_figure(ax.figure, folder / "imbalance_response.png"))
    if result.half_mass is not None:
        ax = plot_onsets([m.to_dict() for m in result.onsets.modes], result.half_mass, top)
        paths.append(save_figure(ax.figure, folder / "onsets.png"))
    return paths


def _report(out: dict) -> str:
    from ..rotor.mode_search import UNSTABLE_LOW

    loads = ", ".join(f"{b['bearing']} {b['load_newton']:.4g} N at "
                      f"{b['load_direction_deg']:.4g}°" for b in out["bearing_loads"])
    lines = [f"gfbopt rotor — {out['rotor']} ({out['rotor_file']}), grid {out['grid']}",
             f"  bearing loads: {loads}"]
    lines += [f"  {note}" for note in out["bearing_notes"]]
    for name, conv in out["conventions"]["bearings"].items():
        built = built_words(conv)
        lines.append(f"  bearing {name}: {conv['film_convention']}; "
                     f"{model_words(conv, law='law')}; {out['thermal_models'][name]}"
                     + (f"; as built: {built}" if built else ""))
    if _finite(out["onset_speed_rpm"]):
        lines.append(f"  first to whirl: {out['first_mode']} from "
                     f"{out['onset_speed_rpm']:,.0f} rpm at {out['onset_whirl_frequency_hz']:.4g}"
                     " Hz")
    else:
        low = [m["label"] for m in out["modes"] if m["onset_status"] == UNSTABLE_LOW]
        lines.append(f"  onset: none — {out['onset_reason']}" if not low else
                     f"  onset: none — unstable already at {out['speed_range_rpm'][0]:,.0f} "
                     f"rpm, the lowest speed, in {', '.join(low)}: the onset lies below the "
                     "range (why: under the mode)")
    for m in out["modes"]:
        speed = (f"{m['onset_speed_rpm']:,.0f} rpm" if math.isfinite(m["onset_speed_rpm"])
                 else m["onset_status"])
        whirl = (f"whirl {m['whirl_frequency_hz']:.4g} Hz" if _finite(m["whirl_frequency_hz"])
                 else f"least μ_c {m['smallest_inertia_margin'] + 1:.3g}")   # no whirl of its own
        lines.append(f"    {m['label']:<22} {speed:>28}, {whirl}, B/A phase "
                     f"{m['shape']['phase_b_from_a_deg']:+.0f}°")
        if m.get("note"):
            lines.append(f"      {m['note']}")
    lines += _running_lines(out)
    if out.get("at_speed"):
        lines += _at_speed_lines(out["at_speed"])
    for c in out["load_capacity_exceeded"]:
        if c.get("kind"):          # thermal runaway or closure at that speed
            lines.append(f"  {c['message']}")
            continue
        lines.append(f"  bearing {c['bearing']} over capacity at {c['speed_rpm']:,.0f} rpm: "
                     f"{c['message']}")
    if "half_mass_approximation" in out:
        h = out["half_mass_approximation"]
        lines.append(f"  per-bearing (half-mass) approximation: {h['onset_speed_rpm']:,.0f} rpm"
                     f" ({h['error_of_approximation']:+.1%} against the two-bearing onset)")
    if "imbalance_response" in out:
        lines += _imbalance_lines(out["imbalance_response"])
    if "campbell" in out and out["campbell"]["least_stable"]:
        ls = out["campbell"]["least_stable"]
        limit = out["campbell"].get("frequency_limit_hz")
        lines.append(f"  Campbell: {out['campbell']['modes']} modes over "
                     f"{out['campbell']['speeds']} speeds"
                     + (f" (every mode up to {limit:,.0f} Hz)" if _finite(limit) else "")
                     + f"; least stable {ls['track_label']} at "
                     f"{ls['speed_rpm']:,.0f} rpm (log decrement {ls['log_decrement']:.3g})")
        lines.append("    tracks: " + "; ".join(
            f"{t['mode']} {t['label']}" + (f" (damping through zero at "
                                           f"{t['track_zero_rpm']:,.0f} rpm)"
                                           if _finite(t["track_zero_rpm"]) else "")
            for t in out["campbell"]["tracks"]))
        lost = out["campbell"].get("dropped_roots") or []
        if lost:
            lines.append(f"    {len(lost)} root(s) found at one speed only, left out of the "
                         "diagram: " + "; ".join(
                             f"{d['whirl_frequency_hz']:,.1f} Hz at {d['speed_rpm']:,.0f} rpm "
                             f"({d['reason']})" for d in lost))
    for warning in out["warnings"]:
        lines.append(f"  warning: {warning}")
    for key in ("csv", "figures"):
        if key in out:
            lines.append(f"  {key}: {', '.join(out[key])}")
    return "\n".join(lines)


def _running_lines(out: dict) -> list:
    """Each heated bearing's running clearance, growths, film temperature and viscosity at
    the first onset."""
    lines = []
    for name, p in out.get("running_at_onset", {}).items():
        if not _finite(p.get("running_clearance_um")):
            continue
        temp = (f", film {p['film_temperature_c']:.4g} °C" if _finite(p.get(
            "film_temperature_c")) else "")
        lines.append(f"  bearing {name} at {p['speed_rpm']:,.0f} rpm: running clearance "
                     f"{p['running_clearance_um']:.4g} µm (cold {p['cold_clearance_um']:.4g}; "
                     f"centrifugal {p['centrifugal_growth_um']:.3g}, thermal "
                     f"{p['thermal_growth_um']:.3g} µm){temp}, μ {p['viscosity_pa_s']:.4g} Pa s")
    return lines


def _finite(value) -> bool:
    """A number of the JSON output is there (null, NaN and inf are not)."""
    return value is not None and math.isfinite(value)


def _imbalance_lines(ir: dict) -> list:
    """The text of the imbalance response: each station's peak, flagged when it lies above the
    first onset (not physical there), with the largest response below the onset."""
    lines = []
    for name, p in ir["peaks"].items():
        text = (f"  imbalance response peak at {name}: {p['peak_amplitude_um']:.3g} µm at "
                f"{p['peak_speed_rpm']:,.0f} rpm")
        if p["above_first_onset"]:
            text += " — where the rotor is unstable, not physical"
            if _finite(p["largest_below_onset_um"]):
                text += (f"; largest below the onset {p['largest_below_onset_um']:.3g} µm at "
                         f"{p['largest_below_onset_rpm']:,.0f} rpm")
        lines.append(text)
    if _finite(ir["unstable_from_rpm"]):
        lines.append(f"    above {ir['unstable_from_rpm']:,.0f} rpm the rotor is unstable: the "
                     "linear response there is not an orbit that would be observed (shaded in "
                     "the figure)")
    return lines


def _at_speed_lines(at: dict) -> list:
    """The text of ``--speed-rpm N`` (the JSON's ``at_speed``): each bearing's equilibrium
    (with its running clearance when heated), each mode's whirl and log decrement, and each
    mode's threshold (the inertia scale at which it is neutral)."""
    lines = [f"  at {at['speed_rpm']:,.0f} rpm (--speed-rpm):"]
    failed = at.get("load_capacity_exceeded")
    if "bearings" not in at:             # no equilibrium of the rotor there: say why, once
        why = (failed or {}).get("message") or "no equilibrium at this speed"
        lines.append(f"    no equilibrium: {why}")
        return lines
    for b in at["bearings"]:
        if not _finite(b.get("eccentricity")):      # thermal runaway or closure: no state
            lines.append(f"    bearing {b['bearing']}: no equilibrium "
                         f"({b.get('thermal_status') or 'not solved'})")
            continue
        text = (f"    bearing {b['bearing']}: load {b['load_newton']:.4g} N, ε = "
                f"{b['eccentricity']:.4f}, attitude {b['attitude_angle_deg']:.2f}°, minimum "
                f"film {b['min_film_thickness_um']:.3g} µm")
        if _finite(b.get("running_clearance_um")):
            text += (f"; running clearance {b['running_clearance_um']:.4g} µm (cold "
                     f"{b['cold_clearance_um']:.4g})")
            if _finite(b.get("film_temperature_c")):
                text += f", film {b['film_temperature_c']:.4g} °C"
        elif b.get("thermal_status") not in (None, "running"):
            text += f"; {b['thermal_status']}"
        if b.get("load_exceeds_capacity"):
            text += "; load above the rule-of-thumb capacity"
        lines.append(text)
    def name(row: dict) -> str:         # an onset-list mode's name, else the shape class
        return row.get("track_label") or f"({row['shape_label']})"

    unnamed = False
    for m in at["modes"]:
        if not _finite(m.get("log_decrement")):
            continue
        verdict = "unstable" if m["log_decrement"] < 0 else "stable"
        unnamed |= not m.get("track_label")
        lines.append(f"    mode {name(m):<22} whirl {m['whirl_frequency_hz']:.4g} Hz "
                     f"(ratio {m['whirl_ratio']:.3f}), log decrement "
                     f"{m['log_decrement']:+.3g}: {verdict}")
    for t in at.get("thresholds") or []:
        unnamed |= not t.get("track_label")
        lines.append(f"    threshold of {name(t)}: whirl {t['whirl_frequency_hz']:.4g}"
                     f" Hz (ratio {t['whirl_ratio']:.3f}) at {t['inertia_scale']:.3g} × the "
                     f"rotor's inertia (margin {t['inertia_margin']:+.1%})"
                     + (f"; {t['note']}" if t.get("note") else ""))
    if unnamed:
        lines.append("    (…): the shape class at this speed; no mode of the onset list has "
                     "that shape here (MAC < 0.8)")
    return lines
