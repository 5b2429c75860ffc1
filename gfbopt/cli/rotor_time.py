"""The rotor in time: ``gfbopt rotor ROTOR.toml --orbit | --run-up A B | --coast-down A B``.

::

    gfbopt rotor rotor.toml --orbit --speed-rpm 45000 --revolutions 200 --grid 72x20
    gfbopt rotor rotor.toml --run-up 5000 60000 --rate 20000 --imbalance-grade 2.5 --plot out/
    gfbopt rotor rotor.toml --coast-down 60000 5000 --rate 20000 --json --csv out/

One transient of the whole rotor (rigid, or a condensed shaft) on the films of both bearings
(:mod:`gfbopt.transient.rotor_analysis`): orbits at both journals [µm], the limit cycle at a
constant speed, or the waterfall, 1× and subsynchronous components of a run-up/coast-down
with the speed where the subsynchronous line appears beside the linear onset; the smallest
film with its time, speed and bearing, and contact when it happens (the record up to there
is kept).  Progress: a bar with an ETA on a terminal, a periodic status line otherwise.

The ``gfbopt rotor`` command (:mod:`gfbopt.cli.rotor`) owns the rotor file and the
shared options ``--speed-rpm``, ``--grid``, ``--json``, ``--csv DIR``, ``--plot DIR``; this
module adds the transient's options (:func:`add_arguments`) and runs them (:func:`handle`)
when :func:`requested` says one of ``--orbit/--run-up/--coast-down`` was given.
"""
from __future__ import annotations

import math
from pathlib import Path

from .common import number
from .csv_context import context_options, write_csv

#: defaults of --kick [clearances per rad] and --window-revolutions [revolutions]
KICK, WINDOW_REVOLUTIONS = 1e-3, 20.0
#: a ramp spans at least this many shaft revolutions (--rate: faster is a step in speed, not
#: a run-up); an --orbit at least one revolution (its whirl and 1× need a period)
MIN_RUN_REVOLUTIONS = 2.0
#: an explicit --window-revolutions: at least a revolution (a shorter spectrum cannot tell
#: the 1× from a subsynchronous line) and at most this share of the run (a ramp keeps 10
#: windows, an orbit 2: the share the default is cut to)
WINDOW_SHARE = {"orbit": 0.5, "run-up": 0.1, "coast-down": 0.1}
#: smallest --foil-travel-um [µm]: 10 nm, a hundredth of a foil's surface roughness
MIN_FOIL_TRAVEL_UM = 0.01
#: the transient's options, with what each sets: refused without --orbit/--run-up/
#: --coast-down (:func:`check_unused`)
TRANSIENT_ONLY = {
    "revolutions": ("--revolutions", "the length of an --orbit"),
    "rate": ("--rate", "the speed ramp of a --run-up/--coast-down"),
    "method": ("--method", "the time integration of a transient"),
    "time_step": ("--time-step", "the time step of a transient"),
    "stages": ("--stages", "the RKC stages of a transient"),
    "perturbation": ("--perturbation", "the starting kick of a transient"),
    "kick": ("--kick", "the starting kick of a transient"),
    "reference_whirl_ratio": ("--reference-whirl-ratio", "the damped foil of a transient"),
    "foil_travel_um": ("--foil-travel-um", "the contact check of a transient"),
    "window_revolutions": ("--window-revolutions", "the waterfall windows of a transient "
                           "(an orbit's synchronous amplitude is its last window's)"),
    "subsync_threshold_um": ("--subsync-threshold-um", "the subsynchronous threshold of a "
                             "run-up's waterfall and an orbit's whirl"),
    "force": ("--force", "the revolution limit of a transient"),
}
#: the imbalance options: used by a transient and by --imbalance-response
IMBALANCE_OPTIONS = {"imbalance_grade": "--imbalance-grade",
                     "imbalance_plane": "--imbalance-plane"}

METHOD_HELP = ("integration method: rkc (default; damped Runge–Kutta–Chebyshev, stages from "
               "the stiffness bound, step from accuracy) or rk4 (the reference)")


def add_arguments(parser) -> None:
    """The transient's options on the rotor command's parser (not the shared ones)."""
    g = parser.add_argument_group("rotor transient (orbit, run-up, coast-down)")
    mode = g.add_mutually_exclusive_group()
    mode.add_argument("--orbit", action="store_true", help="orbit at a constant --speed-rpm "
                      "for --revolutions, from the equilibrium (perturbed by --perturbation)")
    mode.add_argument("--run-up", nargs=2, type=number("run-up"), metavar=("A", "B"),
                      default=None, help="run up from A to B rpm at --rate")
    mode.add_argument("--coast-down", nargs=2, type=number("coast-down"), metavar=("A", "B"),
                      default=None, help="coast down from A to B rpm at --rate")
    g.add_argument("--revolutions", type=number("revolutions"), default=None,
                   help="shaft revolutions of an --orbit")
    g.add_argument("--rate", type=number("rate"), default=None,
                   help="speed ramp rate [rpm/s] of a run-up or coast-down (> 0)")
    g.add_argument("--method", default=None, choices=("rkc", "rk4"), help=METHOD_HELP)
    g.add_argument("--time-step", type=number("time-step"), default=None,
                   help="Δτ [rad of rotation at the top speed] (default: from accuracy for "
                   "rkc, 0.9 × the stability limit for rk4)")
    g.add_argument("--stages", type=number("stages"), default=None,
                   help="RKC stages (rkc only; default: the fewest that are stable)")
    g.add_argument("--perturbation", default=None, choices=("none", "cylindrical", "conical"),
                   help="starting kick of both journals (default: cylindrical for an orbit, "
                   "none for a ramp)")
    g.add_argument("--kick", type=number("kick"), default=None,
                   help=f"journal speed of the kick [clearances per rad] (default {KICK:g})")
    g.add_argument("--imbalance-grade", type=number("imbalance-grade"), default=None,
                   help="balance grade G [mm/s] (ISO 21940-11): U = m G/ω_max (ω_max the "
                   "transient's top speed, or HIGH of --speed-range with --imbalance-response) "
                   "split over two planes at the bearings by their static load shares, phase "
                   "0 (replaces the file's imbalance; also for --imbalance-response)")
    g.add_argument("--imbalance-plane", nargs=3, action="append", type=number("imbalance-plane"),
                   metavar=("G_MM", "PHASE_DEG", "POSITION_M"), default=None,
                   help="an imbalance plane: amount [g mm], phase [deg], axial position [m] "
                   "as in the rotor file (from the CG of a rigid rotor, from the shaft's first "
                   "end with [[shaft]]) (repeat; replaces the file's imbalance; also for "
                   "--imbalance-response)")
    g.add_argument("--reference-whirl-ratio", type=number("reference-whirl-ratio"),
                   default=None, help="ν_ref of a damped foil (η > 0; default each bearing's "
                   "linear threshold whirl ratio)")
    g.add_argument("--foil-travel-um", type=number("foil-travel-um"), default=None,
                   help="bump travel [µm] before the foil is exhausted (contact); default: "
                   "not checked")
    g.add_argument("--window-revolutions", type=number("window-revolutions"), default=None,
                   help="waterfall window [revolutions at the mean speed; at most 1/10 of "
                   "a ramp, 1/2 of an orbit, whose synchronous amplitude is its last "
                   f"window's] (default {WINDOW_REVOLUTIONS:g})")
    g.add_argument("--subsync-threshold-um", type=number("subsync-threshold-um"), default=None,
                   help="amplitude [µm] from which the subsynchronous line counts as present "
                   "(a ramp's appearance; an orbit's whirl, below it 'no subsynchronous "
                   "whirl') (default 2 %% of the clearance)")
    g.add_argument("--force", action="store_true", help="run more than the revolution limit "
                   "(gfbopt.transient.rotor_analysis.MAX_REVOLUTIONS)")


def add_shared_arguments(parser) -> None:
    """The rotor command's own options, for using this module without it (tests)."""
    parser.add_argument("rotor", help="rotor file (TOML)")
    parser.add_argument("--speed-rpm", type=number("speed-rpm"), default=None)
    parser.add_argument("--grid", default="72x20")
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--csv", default=None)
    parser.add_argument("--plot", default=None)


def requested(args) -> bool:
    """True when a transient was asked for."""
    return bool(getattr(args, "orbit", False) or getattr(args, "run_up", None)
                or getattr(args, "coast_down", None))


def check_unused(args) -> None:
    """Refuse, one line each, the transient's options on a run without a transient, and the
    imbalance options without --imbalance-response (ParameterError, before any solve)."""
    from ..errors import ParameterError

    for key, (option, sets) in TRANSIENT_ONLY.items():
        value = getattr(args, key, None)
        if value is not None and value is not False:
            raise ParameterError(option, value, f"sets {sets}: it is used only with --orbit, "
                                 "--run-up or --coast-down")
    if not getattr(args, "imbalance_response", False):
        for key, option in IMBALANCE_OPTIONS.items():
            value = getattr(args, key, None)
            if value is not None:
                raise ParameterError(option, value, "is used only by --imbalance-response "
                                     "or a transient (--orbit, --run-up, --coast-down)")


def _rotor_path(args) -> str:
    for name in ("rotor", "rotor_file", "file", "path"):
        value = getattr(args, name, None)
        if isinstance(value, (str, Path)):
            return str(value)
    from ..errors import ParameterError

    raise ParameterError("ROTOR.toml", None, "a rotor file is required")


#: the speed ramp's names (gfbopt.transient.rotor_analysis.ramp_profile) → the metavars
#: of --run-up/--coast-down A B
RAMP_ENDS = {"start_rpm": "A", "end_rpm": "B"}
#: the rotor command's options that a transient does not use (refused, not ignored)
NOT_USED = {"speed_range": "--speed-range", "campbell": "--campbell",
            "imbalance_response": "--imbalance-response", "half_mass": "--half-mass"}


def check_profile(args):
    """The speed profile from the options (ParameterError before anything is solved)."""
    from ..errors import ParameterError
    from ..transient.rotor_analysis import orbit_profile, ramp_profile

    for key, option in NOT_USED.items():
        value = getattr(args, key, None)
        if value:
            raise ParameterError(option, value, "is not used by --orbit/--run-up/--coast-down "
                                 "(a transient); run it separately")
    if getattr(args, "campbell_speeds", 20) != 20:
        raise ParameterError("--campbell-speeds", args.campbell_speeds, "needs --campbell")

    if args.orbit:
        if args.speed_rpm is None:
            raise ParameterError("--speed-rpm", None, "is required with --orbit")
        if args.revolutions is None:
            raise ParameterError("--revolutions", None, "is required with --orbit")
        if args.rate is not None:
            raise ParameterError("--rate", args.rate, "is used by --run-up/--coast-down only")
        if not args.revolutions >= 1.0:
            raise ParameterError("--revolutions", args.revolutions, "must be >= 1 (an orbit of "
                                 "at least one shaft revolution)")
        return _check_numbers(args, orbit_profile(args.speed_rpm, args.revolutions,
                                                  args.force))
    kind = "run-up" if args.run_up else "coast-down"
    start, end = args.run_up or args.coast_down
    if args.rate is None:
        raise ParameterError("--rate", None, f"is required with --{kind} (rpm/s, > 0)")
    if args.rate <= 0:
        raise ParameterError("--rate", args.rate, "must be > 0 rpm/s (the direction comes "
                             "from --run-up or --coast-down)")
    if args.revolutions is not None:
        raise ParameterError("--revolutions", args.revolutions, f"is used by --orbit only "
                             f"(a {kind}'s length follows from its speeds and rate)")
    if args.speed_rpm is not None:
        raise ParameterError("--speed-rpm", args.speed_rpm, f"is used by --orbit only (the "
                             f"{kind} gives its speeds)")
    try:                 # the ramp's own names (start_rpm, end_rpm) are A and B of --KIND
        profile = ramp_profile(start, end, args.rate, kind, args.force)
    except ParameterError as exc:
        if exc.name not in RAMP_ENDS:
            raise
        raise ParameterError(f"--{kind}", [start, end], f"{RAMP_ENDS[exc.name]} = "
                             f"{exc.value:g}: {exc.rule}") from None
    if not profile.revolutions >= MIN_RUN_REVOLUTIONS:
        raise ParameterError("--rate", args.rate, f"ramps {start:g} → {end:g} rpm in "
                             f"{profile.revolutions:.3g} shaft revolutions, fewer than "
                             f"{MIN_RUN_REVOLUTIONS:g} (a step in speed, not a {kind}): at most "
                             f"{args.rate * profile.revolutions / MIN_RUN_REVOLUTIONS:.6g} "
                             "rpm/s")
    return _check_numbers(args, profile)


def _check_numbers(args, profile):
    """--time-step, --kick, --stages, --window-revolutions and --foil-travel-um within what
    they can mean (the bounds of ``gfbopt transient``'s options; module constants)."""
    from types import SimpleNamespace

    from ..errors import ParameterError
    from .transient import MAX_STAGES, check_run_length

    check_run_length(SimpleNamespace(time_step=args.time_step, kick=args.kick))
    stages = args.stages
    if stages is not None and not (math.isfinite(stages) and float(stages).is_integer()
                                   and 2 <= stages <= MAX_STAGES):
        raise ParameterError("--stages", stages, f"must be an integer in [2, {MAX_STAGES}]")
    window = args.window_revolutions
    if window is not None:
        most = WINDOW_SHARE[profile.kind] * profile.revolutions
        if not 1.0 <= window <= most:
            room = (f"must lie in [1, {most:.4g}]" if most >= 1.0 else
                    "has no room here (leave the default)")
            raise ParameterError("--window-revolutions", window, f"{room}: a window of at least "
                                 f"one revolution and at most {WINDOW_SHARE[profile.kind]:g} of "
                                 f"the {profile.kind}'s {profile.revolutions:.4g} revolutions")
    for option, value, means in (
            ("--reference-whirl-ratio", args.reference_whirl_ratio, "a whirl ratio ν_ref"),
            ("--subsync-threshold-um", args.subsync_threshold_um, "an amplitude [µm]")):
        if value is not None and not value > 0:
            raise ParameterError(option, value, f"must be > 0 ({means})")
    travel = args.foil_travel_um
    if travel is not None and not travel >= MIN_FOIL_TRAVEL_UM:
        raise ParameterError("--foil-travel-um", travel, f"must be >= {MIN_FOIL_TRAVEL_UM:g} µm "
                             "(a bump travel below a hundredth of a foil's roughness is none)")
    return profile


def _check_planes(system, planes: tuple) -> None:
    """The rotor file's rule for a plane's position (gfbopt.inputs.rotor_limits), refused by
    the option that gave the plane: ``--imbalance-plane[2] position = 5.0: …``."""
    from dataclasses import replace

    from ..errors import ParameterError

    try:                     # the rotor system checks its limits itself as it is replaced
        replace(system, imbalance=planes)
    except ParameterError as exc:
        name = (exc.name if isinstance(exc.name, str) else "").rsplit(": ", 1)[-1]
        if name.startswith("imbalance["):
            k = name[len("imbalance["):].split("]", 1)[0]
            raise ParameterError(f"--imbalance-plane[{k}] position", exc.value,
                                 exc.rule) from None
        raise


def imbalance_planes(args, system, top_rpm: float):
    """The imbalance planes the options ask for (None: the file's); a balance grade is
    turned into an amount with the top speed ``top_rpm`` [rpm]."""
    from ..errors import ParameterError
    from ..inputs.rotor_system import ImbalancePlane
    from ..rotor.rigid import bearing_loads
    from ..transient.rotor_setup import iso_g_imbalance

    if args.imbalance_grade is not None and args.imbalance_plane:
        raise ParameterError("--imbalance-grade", args.imbalance_grade, "give either a grade "
                             "or --imbalance-plane entries, not both")
    if args.imbalance_plane:
        planes = []
        for k, (amount, phase, position) in enumerate(args.imbalance_plane):
            if not amount > 0:
                raise ParameterError(f"--imbalance-plane[{k + 1}] amount", amount,
                                     "must be > 0 g mm")
            planes.append(ImbalancePlane(amount * 1e-6, position, phase, f"plane {k + 1}"))
        _check_planes(system, tuple(planes))
        return tuple(planes)
    if args.imbalance_grade is None:
        return None
    total = iso_g_imbalance(args.imbalance_grade, system.body.mass, top_rpm)
    loads = bearing_loads(system)
    share = [w.magnitude for w in loads]
    return tuple(ImbalancePlane(total * s / sum(share), b.position, 0.0, f"at {b.name}")
                 for s, b in zip(share, system.bearings))


def handle(args) -> int:
    """Run the transient the options ask for; 0 on success (contact is a result), 1 when the
    integration failed."""
    from dataclasses import replace

    from ..errors import ParameterError
    from ..inputs import Grid
    from ..inputs.rotor_system import load_rotor
    from ..progress import progress
    from ..transient.rotor_analysis import check_running_friction, progress_units, run_profile

    profile = check_profile(args)
    method = args.method or "rkc"
    if args.stages is not None and method != "rkc":
        raise ParameterError("--stages", args.stages, "applies to --method rkc only")
    grid = Grid.parse(args.grid)
    system = load_rotor(_rotor_path(args), running=True)   # an orbit holds its speed's condition
    if profile.kind != "orbit":     # refused before any work (the running line, progress)
        flag = "--run-up" if args.run_up else "--coast-down"
        check_running_friction(system, profile, name=flag,
                               value=" ".join(f"{v:g}" for v in (args.run_up or args.coast_down)))
    if args.reference_whirl_ratio is not None and not any(
            (b.options.loss_factor or 0.0) > 0 for b in system.bearings):
        raise ParameterError("--reference-whirl-ratio", args.reference_whirl_ratio, "is used "
                             "only with structural damping: no bearing of the rotor file "
                             "states loss_factor > 0 (as gfbopt orbit without --loss-factor)")
    planes = imbalance_planes(args, system, profile.top_rpm)
    if planes is not None:
        system = replace(system, imbalance=planes)
    perturbation = args.perturbation or ("cylindrical" if profile.kind == "orbit" else "none")
    scale = 1.0 if system.imbalance else 0.0
    total, unit = progress_units(profile)
    with progress(total=total, desc=f"rotor {profile.kind}", unit=unit) as bar:
        result = run_profile(
            system, profile, grid=grid, method=method, perturbation=perturbation,
            kick=KICK if args.kick is None else args.kick, imbalance_scale=scale,
            time_step=args.time_step,
            stages=None if args.stages is None else int(args.stages),
            reference_whirl_ratio=args.reference_whirl_ratio,
            foil_travel_m=None if args.foil_travel_um is None else args.foil_travel_um * 1e-6,
            progress=bar, system=system,
            window_revolutions=(WINDOW_REVOLUTIONS if args.window_revolutions is None
                                else args.window_revolutions),
            subsync_threshold_um=args.subsync_threshold_um)
    out = result.to_dict()
    options = _context(args, system, grid, profile, result.settings)
    if args.csv:        # the JSON is the same with or without --csv, plus this list
        folder = Path(args.csv)
        folder.mkdir(parents=True, exist_ok=True)
        out["csv"] = [str(write_csv(table, folder / name, options, float_format="%.8g"))
                      for name, table in result.tables().items()]
    if args.plot:
        _figures(result, Path(args.plot))
    _emit(out, args.json, options, result)
    return 0 if result.success else 1


#: the settings of a run (gfbopt.transient.rotor_analysis.run_profile) that are its options;
#: the rest (the running line, its fixed points, solves and misses, where a ramp ended) are
#: results, in the JSON and the tables, not in the provenance
RUN_OPTIONS = ("method", "perturbation", "kick", "reference_whirl_ratio", "contact_film",
               "foil_travel_m", "sample_every_rad", "max_step_rad", "running_step_rpm")
#: the settings that state the model (into the conventions block, beside each bearing's)
MODEL_SETTINGS = ("clearance_model", "running_interpolation", "bump_friction")


def _context(args, system, grid, profile, settings: dict) -> dict:
    """The provenance options of the JSON and of every CSV's context file, built as
    ``gfbopt rotor --speed-range`` builds them (:mod:`gfbopt.cli.rotor`): the command, the
    rotor file, the grid, the run's options as asked and the conventions block (each
    bearing's film, foil, friction, hardening and thermal model)."""
    from ..rotor.supports import resolve_rotor

    conventions = resolve_rotor(system, grid).conventions()
    conventions.update({k: settings[k] for k in MODEL_SETTINGS if k in settings})
    asked = {"speed_profile": profile.to_dict(), "time_step": args.time_step,
             "stages": None if args.stages is None else int(args.stages),
             "window_revolutions": (WINDOW_REVOLUTIONS if args.window_revolutions is None
                                    else args.window_revolutions),
             "subsync_threshold_um": args.subsync_threshold_um,
             **{k: settings[k] for k in RUN_OPTIONS if k in settings}}
    return context_options(args, command="rotor", rotor_file=_rotor_path(args),
                           grid=str(grid), **asked, conventions=conventions)


def _figures(result, folder: Path) -> None:
    from ..plotting import save_figure
    from ..plotting.waterfall import plot_components, plot_journal_orbits, plot_waterfall

    folder.mkdir(parents=True, exist_ok=True)
    p = result.profile
    what = result.run_words()
    contact = result.contacts[0] if result.contacts[0]["contact"] else None
    c_um = result.run.model.bearings[0].clearance * 1e6
    ax = plot_journal_orbits(result.orbit_frame(), result.names, clearance_um=c_um,
                             title=f"Journal orbits, {what}")
    save_figure(ax.figure, folder / "orbits.png")
    if p.kind == "orbit":
        return
    lin = result.onset.get("linear_onset_speed_rpm", math.nan)
    tables = {}
    for k, name in enumerate(result.names):
        w = result.waterfalls[0][k]
        ax = plot_waterfall(w, bearing=name, linear_onset_rpm=lin,
                            appearance_rpm=result.onset.get(f"subsync_appearance_{name}_rpm",
                                                            math.nan),
                            contact=contact, title=f"Waterfall at bearing {name}, {what}")
        save_figure(ax.figure, folder / f"waterfall_{name}.png")
        if w.time_s.size:
            tables[name] = w.table()
    if tables:
        axes = plot_components(tables, linear_onset_rpm=lin,
                               threshold_um=result.onset.get("subsync_threshold_um", math.nan),
                               contact=contact, title=f"1× and subsynchronous components, {what}")
        save_figure(axes[0].figure, folder / "components.png")


def _rpm(value) -> str:
    """A speed for the text report ('none' for a missing one: JSON null / NaN)."""
    return "none in the record" if value is None or value != value else f"{value:,.0f} rpm"


def _whirl(b: dict, whirl_words) -> str:
    """An orbit's whirl in words; an unsettled one whose change over the last window was not
    measured (null) says so instead of a number."""
    if (b.get("limit_cycle_status") in (None, "none") or b.get("limit_cycle_settled")
            or b.get("limit_cycle_change") is not None):
        return whirl_words(b)
    return whirl_words({**b, "limit_cycle_settled": True})[:-1] + ", not settled)"


def _emit(out: dict, as_json: bool, options: dict, result) -> None:
    import json

    from ..provenance import jsonable, provenance
    from ..transient.rotor_result import whirl_words

    if as_json:
        print(json.dumps(jsonable({**out, "provenance": provenance(**options)})))
        return
    p = result.profile
    lines = [f"gfbopt rotor — {result.run_words()}, {out['revolutions_integrated']:.1f} "
             f"revolutions ({out['method']}, grid {out['grid']}) in "
             f"{out['wall_time_s']:.1f} s"]
    for b in out["bearings"]:
        text = (f"  bearing {b['bearing']}: load {b['load_newton']:.4g} N, min film "
                f"{b['min_film_um']:.3g} µm at {b['min_film_speed_rpm']:,.0f} rpm "
                f"(t = {b['min_film_time_s']:.4g} s)")
        if b.get("sync_amplitude_um") is not None:
            text += f"; 1× {b['sync_amplitude_um']:.3g} µm (last window)"
        if b.get("peak_amplitude_um") is not None:
            text += (f"; 1× peak {b['peak_amplitude_um']:.3g} µm at "
                     f"{b['peak_speed_rpm']:,.0f} rpm")
        if "limit_cycle_status" in b and "friction_orbit_verdict" not in b:
            text += "; " + _whirl(b, whirl_words)      # bumps that rub: their line below
        lines.append(text)
    if out.get("bump_friction"):
        lines.append(f"  {out['bump_friction']}")
        for b in out["bearings"]:
            if "friction_orbit_verdict" in b:
                lines.append(f"  bearing {b['bearing']} with friction: "
                             f"{b['friction_orbit_verdict']}")   # = its limit_cycle_status
    if out.get("clearance_model"):
        lines.append(f"  clearance model: {out['clearance_model']}")
    for name in dict.fromkeys(r["bearing"] for r in out.get("running_line", [])):
        rows = [r for r in out["running_line"] if r["bearing"] == name]
        a, b = rows[0], rows[-1]
        lines.append(f"  bearing {name} running line ({len(rows)} speeds, running_line.csv): "
                     f"{a['running_clearance_um']:.4g} µm, {a['film_temperature_c']:.4g} °C, "
                     f"{a['viscosity_pa_s']:.4g} Pa s at {a['speed_rpm']:,.0f} rpm → "
                     f"{b['running_clearance_um']:.4g} µm, {b['film_temperature_c']:.4g} °C, "
                     f"{b['viscosity_pa_s']:.4g} Pa s at {b['speed_rpm']:,.0f} rpm")
    if out.get("running_end"):
        lines.append(f"  RAMP ENDS at {p.end_rpm:,.0f} rpm (asked "
                     f"{out['requested_end_rpm']:,.0f}): {out['running_end']}")
    if p.kind != "orbit":
        lines.append(f"  subsynchronous line (≥ {out['subsync_threshold_um']:.3g} µm) appears "
                     f"at {_rpm(out['subsync_appearance_rpm'])}; linear onset "
                     f"{_rpm(out['linear_onset_speed_rpm'])} ({out['linear_onset_source']})")
    if out["contact"]:
        lines.append(f"  CONTACT ({out['contact_kind']}) at bearing {out['contact_bearing']}, "
                     f"{out['contact_speed_rpm']:,.0f} rpm, t = {out['contact_time_s']:.4g} s; "
                     "the record up to there is kept")
    if not out["success"]:
        lines.append(f"  ** FAILED: {out['message']}")
    if out.get("csv"):
        lines.append(f"  csv: {', '.join(out['csv'])}")
    print("\n".join(lines))
