"""The ``gfbopt`` command line: a thin layer over the Python API, one module per command.

=====================  =================================================================
module                 commands
=====================  =================================================================
:mod:`.static`         ``gfbopt static``
:mod:`.linear`         ``gfbopt linear``
:mod:`.stability`      ``gfbopt stability`` (SI: verdict, margin, onset speed, K and C)
:mod:`.transient`      ``gfbopt orbit``, ``gfbopt critical-mass``
:mod:`.design`         ``gfbopt design``
:mod:`.run`            ``gfbopt run``
:mod:`.rotor`          ``gfbopt rotor`` (two bearings: onset of each mode, Campbell, imbalance)
:mod:`.capacity`       ``gfbopt capacity`` (load capacity, lift-off speed)
:mod:`.export_ross`    ``gfbopt export-ross`` (each bearing's K, C table as a ROSS 3.x file)
:mod:`.formats`        ``gfbopt formats`` (file formats and study kinds, from the schemas)
:mod:`.common`         operating-point options, refusal of ignored options, JSON output
:mod:`.si`             a bearing file's [model] options merged with the command line
:mod:`.size`           the memory and time estimate of a command (gfbopt.guard)
:mod:`.csv_context`    the context file beside every CSV (provenance, column units)
:mod:`.flags`          each option by its flag as typed, in refusals and provenance
=====================  =================================================================

Bad input prints one line naming the parameter (by the flag as typed, :mod:`.flags`), its
value and the rule, and exits with status 2, before anything is solved (output paths that
cannot be written included, and a run whose estimated memory or time is above
``--max-memory-gb`` or ``--max-minutes``).  A solve
that does not converge (:class:`~gfbopt.errors.ConvergenceError`) exits with status 1 and says
why, with the solver's status and residual.  Every JSON output carries a ``provenance`` block
(version, source commit, options), and every CSV its context file ``FILE.csv.json`` with the
same block and its columns' units (:mod:`.csv_context`, docs/cli_outputs.md).
"""
from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path
from typing import Optional, Sequence

from ..errors import ConvergenceError, GfboptError, ParameterError
from ..version import __version__
from . import design, formats, linear, run, stability, static, transient
from . import rotor
from . import capacity, export_ross
from .common import Parser
from .csv_context import sidecar_path
from .flags import option_flags, refusal_line
from .size import GUARDED, add_limits, check_command

COMMANDS = (static, linear, stability, transient, design, run, rotor, formats)
COMMANDS += (capacity, export_ross)


def build_parser() -> Parser:
    parser = Parser(prog="gfbopt", description="Analysis and design of rotors (rigid, or "
                    "a flexible shaft) on bump-type gas foil bearings.")
    parser.add_argument("--version", action="version", version=f"gfbopt {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for module in COMMANDS:
        module.register(sub)
    for name in GUARDED:                  # one memory and time guard (gfbopt.guard)
        add_limits(sub.choices[name])
    for command in sub.choices.values():  # each option's flag as typed (CSV context, errors)
        command.set_defaults(option_flags=option_flags(command))
    return parser


def _limit_threads() -> None:
    """One BLAS thread for the whole command unless the user set one (:mod:`gfbopt.threads`,
    the mechanism the library's own calls use): gfbopt's linear algebra is many small sparse
    factorisations and dense solves, which multi-threaded BLAS slows 10–100× on small machines."""
    from ..threads import pin_threads

    pin_threads()


#: options naming a file or a folder a command writes (checked before anything is solved);
#: the folders (several files written in them) per command, the others name one file
OUTPUT_OPTIONS = ("csv", "plot", "figure", "results")
OUTPUT_FOLDERS = {"rotor": ("csv", "plot"), "run": ("results",)}


def _probe(folder: Path, key: str, value) -> None:
    """A file can really be created in ``folder`` (os.access says yes to root even where
    nothing can be written, e.g. /proc): a temporary file is created and removed."""
    try:
        handle, name = tempfile.mkstemp(prefix=".gfbopt-probe-", dir=folder)
    except OSError as exc:
        raise ParameterError(f"--{key}", value, f"cannot be written: nothing can be created "
                             f"in {str(folder)!r} ({exc.strerror or exc})") from None
    os.close(handle)
    os.unlink(name)


#: the file options that name a figure (its suffix gives the format)
FIGURE_OPTIONS = ("plot", "figure")


def _check_file(key: str, value) -> None:
    path = Path(value)
    parent = path.parent if str(path.parent) else Path(".")
    if path.is_dir():
        raise ParameterError(f"--{key}", value, "is a directory: give a file name")
    if key in FIGURE_OPTIONS:
        from ..plotting.core import figure_format

        try:
            figure_format(path)
        except ParameterError as exc:
            raise ParameterError(f"--{key}", value, exc.rule) from None
    if not parent.is_dir():
        raise ParameterError(f"--{key}", value, f"cannot be written: the folder "
                             f"{str(parent)!r} does not exist")
    if path.exists():            # overwritten, as save_figure and to_csv do: writable?
        try:
            with open(path, "ab"):
                pass
        except OSError as exc:
            raise ParameterError(f"--{key}", value, f"exists and cannot be overwritten "
                                 f"({exc.strerror or exc})") from None
    _probe(parent, key, value)
    if key == "csv":             # its context FILE.csv.json is written beside it (csv_context)
        side = sidecar_path(path)
        if side.is_dir():
            raise ParameterError(f"--{key}", value, f"cannot be written: its context file "
                                 f"{str(side)!r} is a directory")
        if side.exists():
            try:
                with open(side, "ab"):
                    pass
            except OSError as exc:
                raise ParameterError(f"--{key}", value, f"its context file {str(side)!r} "
                                     f"exists and cannot be overwritten "
                                     f"({exc.strerror or exc})") from None


def _check_folder(key: str, value) -> None:
    path = Path(value)
    if path.exists() and not path.is_dir():
        raise ParameterError(f"--{key}", value, "is a file, not a folder: give a folder "
                             "(several files are written in it) or remove the file")
    existing = path
    while not existing.exists():       # created with its parents: the first that exists
        existing = existing.parent if str(existing.parent) != str(existing) else Path(".")
    if not existing.is_dir():
        raise ParameterError(f"--{key}", value, f"cannot be created: {str(existing)!r} is a "
                             "file")
    _probe(existing, key, value)


def _check_bearing_names(args) -> None:
    """``gfbopt rotor --orbit/--run-up/--coast-down`` names files after the bearings
    (components_NAME.csv, waterfall_NAME.png): a name that cannot be part of a file name is
    refused before anything is solved (not sanitised: the files keep the names a user
    gave)."""
    from . import rotor_time

    if not (args.csv or args.plot) or not rotor_time.requested(args):
        return
    from ..inputs.rotor_system import load_rotor
    from ..guard import check_file_name_part

    for bearing in load_rotor(args.rotor_file, running=True).bearings:
        check_file_name_part(bearing.name, f"{args.rotor_file}: bearing name",
                             "--csv/--plot write components_NAME.csv and waterfall_NAME.png")


def check_outputs(args) -> None:
    """Every output path a command will write must be writable: refused in one line before
    anything is solved, not after (ParameterError).  An existing file is overwritten (the
    policy of :func:`gfbopt.plotting.core.save_figure` and of the CSV writers), so it must be
    writable; a folder is created with its parents where none exists."""
    folders = OUTPUT_FOLDERS.get(getattr(args, "command", None), ())
    for key in OUTPUT_OPTIONS:
        value = getattr(args, key, None)
        if value is None:
            continue
        if not str(value):
            raise ParameterError(f"--{key}", value, "is empty: give a file or folder name")
        (_check_folder if key in folders else _check_file)(key, value)
    if getattr(args, "command", None) == "rotor":
        _check_bearing_names(args)


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Run one command; exit status 0 done, 1 a solver that did not converge (the message
    says why, with its status and residual), 2 bad input (one line, before any solve),
    130 interrupted."""
    argv = list(sys.argv[1:] if argv is None else argv)
    args = build_parser().parse_args(argv)
    args.command_line = ("gfbopt", *map(str, argv))
    _limit_threads()
    try:
        check_outputs(args)
        check_command(args)
        return args.handler(args)
    except ConvergenceError as exc:
        print(f"gfbopt: error: the solver did not converge: {exc}", file=sys.stderr)
        return 1
    except ParameterError as exc:     # named by the flag as typed (gfbopt.cli.flags)
        print(f"gfbopt: error: {refusal_line(exc, args)}", file=sys.stderr)
        return 2
    except GfboptError as exc:
        print(f"gfbopt: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("gfbopt: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:          # e.g. `gfbopt … --json | head`: the reader left
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
