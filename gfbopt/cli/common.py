"""Shared pieces of the sub-commands: the operating-point options, the rules that refuse
options which would be ignored, JSON output with provenance, and progress."""
from __future__ import annotations

import argparse
import json
import math
import re
import sys
from dataclasses import dataclass
from typing import Callable, Optional


from ..errors import ParameterError
from ..inputs import DEFAULT_GRID, BearingGeometry, BearingModel, Grid
from ..inputs.grid import DEFAULT_MAX_MEMORY_GB, check_grid_budget
from ..provenance import jsonable as _jsonable, provenance
from .si import fill_model_options, seam_angle_text


#: a negative number, also in scientific notation (-30e-6): a value, never an option
NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


class Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line and exit 2 (no traceback), naming the
    option by its flag once (``--grid = 'abc': …``, not ``argument --grid: grid = …``)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # argparse takes "-30e-6" for an option ("expected one argument"): a number it is
        self._negative_number_matcher = NEGATIVE_NUMBER

    def error(self, message: str) -> None:
        head, sep, rest = message.partition(": ")
        if sep and head.startswith("argument ") and rest.startswith(head[9:] + " = "):
            message = rest                      # the type's own message names the flag
        self.exit(2, f"gfbopt: error: {message}\n")


def number(name: str) -> Callable[[str], float]:
    """argparse type: a finite float, with the option's flag ``--name`` in the error."""
    name = f"--{name}"

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} = {text!r}: must be a number") from None
        if not math.isfinite(value):         # inf is a number, just not a finite one
            raise argparse.ArgumentTypeError(f"{name} = {text!r}: must be finite" + (
                " (not NaN)" if math.isnan(value) else ""))
        return value
    return parse


def integer(name: str, minimum: Optional[int] = None) -> Callable[[str], int]:
    """argparse type: an integer (``minimum`` or more when given), with the option's flag
    ``--name`` in the error — the form of :func:`number` (``--name = 'abc': must be an
    integer``), never argparse's own ``invalid int value``."""
    name = f"--{name}"

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} = {text!r}: must be an integer") \
                from None
        if minimum is not None and value < minimum:
            raise argparse.ArgumentTypeError(f"{name} = {value}: must be >= {minimum}")
        return value
    return parse


def add_operating_point(sub: argparse.ArgumentParser) -> None:
    """Options that define the bearing, its formulation and the operating point."""
    target = sub.add_mutually_exclusive_group()
    target.add_argument("--eccentricity", type=number("eccentricity"), help="ε = e/c [-]")
    target.add_argument("--load", type=number("load"), help="W/(p_a R²) [-]")
    target.add_argument("--load-newton", type=number("load-newton"), help="static load per "
                        "bearing [N] (with --bearing and --speed-rpm)")
    sub.add_argument("--bearing-number", type=number("bearing-number"), help="Λ [-]")
    sub.add_argument("--compliance", type=number("compliance"), default=None, help="S [-]")
    sub.add_argument("--length-ratio", type=number("length-ratio"), default=None,
                     help="L/D [-] (default 1; taken from the file with --bearing)")
    sub.add_argument("--top-foil-coefficient", type=number("top-foil-coefficient"),
                     default=None, help="C [-] (beam foil only)")
    sub.add_argument("--bearing", help="bearing TOML file (dimensional input, SI)")
    sub.add_argument("--speed-rpm", type=number("speed-rpm"), help="shaft speed [rpm] "
                     "(with --bearing)")
    sub.add_argument("--foil", default=None, choices=("rigid", "simple", "beam"),
                     help="foil model (default: simple, or rigid when S = 0)")
    sub.add_argument("--film", default=None, choices=("periodic", "seam"),
                     help="periodic: full 360° film; seam: P = 1 at the top-foil ends "
                     "(default: periodic; with --bearing, the file's [model] table, else a "
                     "seam 180° from the load — gfbopt.cli.si)")
    sub.add_argument("--seam-angle", type=seam_angle_text, default=None,
                     help="welded end of the top foil, degrees from the load line in the "
                     "direction of rotation, or max_film (the maximum-film line; the default "
                     "without --bearing); seam film, or the beam's welded end with a "
                     "periodic film")
    sub.add_argument("--deflection-law", default=None, choices=("mean", "local"),
                     help="mean: W = S(P̄ − 1); local: W = S(P − 1) (simple foil only; "
                     "default mean, or the bearing file's)")
    sub.add_argument("--subambient", default="full", choices=("full", "gumbel"),
                     help="full film force, or Gümbel: sub-ambient pressure dropped")
    sub.add_argument("--compression-only", action="store_true",
                     help="bumps cannot pull the foil inward (W >= 0)")
    add_grid(sub)
    sub.add_argument("--json", action="store_true", help="print one JSON object")


def add_grid(sub: argparse.ArgumentParser) -> None:
    """--grid and the memory limit that refuses a grid too large to build."""
    sub.add_argument("--grid", default=str(DEFAULT_GRID),
                     help=f"NTHETAxNZ (default {DEFAULT_GRID})")
    sub.add_argument("--max-memory-gb", type=number("max-memory-gb"),
                     default=DEFAULT_MAX_MEMORY_GB, help="refuse a grid whose estimated "
                     f"memory exceeds this [GB] (default {DEFAULT_MAX_MEMORY_GB:g}; the "
                     "estimate is printed)")


def grid_of(args) -> Grid:
    """The grid of --grid, refused (one line, nothing built) when its estimated memory exceeds
    --max-memory-gb."""
    limit = args.max_memory_gb
    if not limit > 0:
        raise ParameterError("--max-memory-gb", limit, "must be > 0")
    return check_grid_budget(Grid.parse(args.grid), limit)


@dataclass(frozen=True)
class OperatingPoint:
    """What the operating-point options describe (non-dimensional model and target)."""

    model: BearingModel
    grid: Grid
    eccentricity: Optional[float] = None
    load: Optional[float] = None
    geometry: Optional[BearingGeometry] = None
    speed_rpm: Optional[float] = None
    load_newton: Optional[float] = None


def _refuse(option: str, value, reason: str) -> None:
    raise ParameterError(option, value, reason)


def _refuse_ignored_options(args) -> None:
    """Options that the chosen mode would ignore are refused, with the reason (one line)."""
    dimensional = args.bearing is not None
    if dimensional:
        for option, value in (("--length-ratio", args.length_ratio),
                              ("--compliance", args.compliance),
                              ("--bearing-number", args.bearing_number)):
            if value is not None:
                _refuse(option, value, "is taken from the bearing file (--bearing); do not "
                        "also give it")
        if args.speed_rpm is None:
            _refuse("--speed-rpm", None, "is required with --bearing")
    else:
        if args.speed_rpm is not None:
            _refuse("--speed-rpm", args.speed_rpm, "needs --bearing FILE.toml (a speed in rpm "
                    "means nothing without the bearing's dimensions); give --bearing-number")
        if args.load_newton is not None:
            _refuse("--load-newton", args.load_newton, "needs --bearing FILE.toml and "
                    "--speed-rpm")
        if args.bearing_number is None:
            _refuse("--bearing-number", None, "is required (or give --bearing)")
    foil = args.foil
    if foil == "rigid":
        if args.compliance not in (None, 0.0):
            _refuse("--compliance", args.compliance, "is not used with --foil rigid (a rigid "
                    "bearing has no bump foundation)")
        if args.compression_only:
            _refuse("--compression-only", True, "is not used with --foil rigid (no bumps)")
        if args.deflection_law != "mean":
            _refuse("--deflection-law", args.deflection_law, "is not used with --foil rigid")
    if args.top_foil_coefficient is not None and foil != "beam":
        _refuse("--top-foil-coefficient", args.top_foil_coefficient, "is used by the beam "
                "foil only; add --foil beam")
    if args.seam_angle is not None:
        if args.film == "periodic" and foil != "beam":
            _refuse("--seam-angle", args.seam_angle, "is not used with a periodic film (no "
                    "seam) unless the beam foil needs its welded end; add --film seam")
        if not 0.0 <= args.seam_angle < 360.0:
            _refuse("--seam-angle", args.seam_angle, "must lie in [0, 360) degrees")


def operating_point(args) -> OperatingPoint:
    """The model and target (eccentricity or load) from the parsed options."""
    resolved = fill_model_options(args)   # the bearing file's [model] table and the defaults
    _refuse_ignored_options(args)
    common = dict(film=args.film, deflection_law=args.deflection_law,
                  subambient=args.subambient, compression_only=args.compression_only,
                  seam_angle_deg=args.seam_angle,
                  loss_factor=args.loss_factor)
    if args.bearing is not None:            # the bumps' friction and hardening, as stated
        common.update(resolved.bump_kwargs())
    grid = grid_of(args)
    extra: dict = {}
    if args.bearing is not None:
        from ..inputs import load_bearing

        geometry = load_bearing(args.bearing)
        from ..inputs.rotor_limits import check_surface_speed

        check_surface_speed(geometry, [args.speed_rpm], "--speed-rpm")
        model = geometry.model(args.speed_rpm, foil=args.foil or "simple", **common)
        if args.top_foil_coefficient is not None:
            model = model.replace(top_foil_coefficient=args.top_foil_coefficient)
        extra.update(geometry=geometry, speed_rpm=args.speed_rpm)
        if args.load_newton is not None:
            extra.update(load=geometry.nondimensional_load(args.load_newton),
                         load_newton=args.load_newton)
    else:
        compliance = 0.0 if args.compliance is None else args.compliance
        foil = args.foil or ("rigid" if compliance == 0.0 else "simple")
        model = BearingModel(bearing_number=args.bearing_number, compliance=compliance,
                             length_ratio=1.0 if args.length_ratio is None else args.length_ratio,
                             foil=foil, top_foil_coefficient=args.top_foil_coefficient or 0.0,
                             **common)
    if args.eccentricity is not None:
        extra["eccentricity"] = args.eccentricity
    elif args.load is not None:
        extra["load"] = args.load
    if "eccentricity" not in extra and "load" not in extra:
        _refuse("--eccentricity/--load", None, "give one of them" + (
            " (or --load-newton)" if args.bearing is not None else ""))
    return OperatingPoint(model=model, grid=grid, **extra)


def describe(op: OperatingPoint, **more) -> dict:
    """Inputs and conventions of an operating point, for every output."""
    out = {**op.model.groups(), **op.model.options(), "grid": str(op.grid)}
    if op.geometry is not None:
        out.update(bearing=op.geometry.name, speed_rpm=op.speed_rpm,
                   radial_clearance_m=op.geometry.radial_clearance)
    out.update(more)
    return out


def emit(out: dict, as_json: bool, report: Callable[[], str], options: dict) -> None:
    """Print ``out`` as one JSON object (with provenance), or the readable ``report()`` with
    what made it as its last line (gfbopt's version and source commit; the JSON's
    ``provenance`` has the options and the date too)."""
    if as_json:
        payload = {**out, "provenance": provenance(**options)}
        print(json.dumps(_jsonable(payload)))
    else:
        print(report() + "\n" + made_by())


def made_by() -> str:
    """'  gfbopt 0.3.0, commit 1b9f1878 (+ uncommitted changes)': the last line of a text
    report."""
    from ..provenance import source_state
    from ..version import __version__

    state = source_state()
    where = (f"commit {state['commit'][:8]}" + (" + uncommitted changes" if state["dirty"]
                                                 else "")
             if state["commit"] else state["source"])
    return f"  gfbopt {__version__}, {where}"


class FractionProgress:
    """A ``progress(fraction)`` callback (0 … 1, what the transient engines report) shown by
    :func:`gfbopt.progress.progress`: a tqdm bar with an ETA on a terminal, a status line to
    stderr every 10 s otherwise (stdout, and so ``--json``, is untouched).  Use as a context
    manager: the last line is written when the work completes (not after an error, which is
    one line of its own)."""

    def __init__(self, label: str):
        from ..progress import progress

        self._bar = progress(total=100, desc=label, unit="%")

    def __call__(self, fraction: float) -> None:
        done = min(100, max(0, int(100 * fraction)))
        if done > self._bar.n:
            self._bar.update(done - self._bar.n)

    def __enter__(self) -> "FractionProgress":
        return self

    def __exit__(self, kind, *exc) -> None:
        if kind is None:             # an error is one line of its own: no status after it
            self._bar.close()


def progress_bar(label: str, enabled: bool = True):
    """The 0.2 hand-drawn bar, kept for ``gfbopt run`` (gfbopt/cli/run.py) until it moves to
    :class:`FractionProgress`: a one-line bar on a terminal; nothing when stderr is not a TTY
    or when ``enabled`` is False."""
    if not enabled or not sys.stderr.isatty():
        return None

    def show(fraction: float) -> None:
        n = int(30 * fraction)
        sys.stderr.write(f"\r{label} [{'#' * n}{'.' * (30 - n)}] {100 * fraction:5.1f} %")
        if fraction >= 1.0:
            sys.stderr.write("\n")
        sys.stderr.flush()
    return show
