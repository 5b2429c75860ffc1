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
:mod:`.formats`        ``gfbopt formats`` (file formats and study kinds, from the schemas)
:mod:`.common`         operating-point options, refusal of ignored options, JSON output
:mod:`.si`             a bearing file's [model] options merged with the command line
=====================  =================================================================

Bad input prints one line naming the parameter, its value and the rule, and exits with
status 2, before anything is solved (output paths that cannot be written included).  A solve
that does not converge (:class:`~gfbopt.errors.ConvergenceError`) exits with status 1 and says
why, with the solver's status and residual.  Every JSON output carries a ``provenance`` block (version, source commit, options).
"""
from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Optional, Sequence

from ..errors import ConvergenceError, GfboptError, ParameterError
from ..version import __version__
from . import design, formats, linear, run, stability, static, transient
from . import rotor
from . import capacity
from .common import Parser

COMMANDS = (static, linear, stability, transient, design, run, rotor, formats)
COMMANDS += (capacity,)


def build_parser() -> Parser:
    parser = Parser(prog="gfbopt", description="Analysis and design of rigid rotors on "
                    "bump-type gas foil bearings.")
    parser.add_argument("--version", action="version", version=f"gfbopt {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for module in COMMANDS:
        module.register(sub)
    return parser


def _limit_threads() -> None:
    """One BLAS thread unless the user set one: gfbopt's linear algebra is many small sparse
    factorisations, which multi-threaded BLAS slows 10–100× on small machines."""
    if not any(os.environ.get(v) for v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS",
                                           "MKL_NUM_THREADS")):
        from threadpoolctl import threadpool_limits

        threadpool_limits(1)


#: options naming a file a command writes (checked before anything is solved)
OUTPUT_OPTIONS = ("csv", "plot")


def check_outputs(args) -> None:
    """Every output path a command will write must be writable: refused in one line before
    anything is solved, not after (ParameterError)."""
    for key in OUTPUT_OPTIONS:
        value = getattr(args, key, None)
        if value is None:
            continue
        path = Path(value)
        parent = path.parent if str(path.parent) else Path(".")
        if path.is_dir():
            raise ParameterError(f"--{key}", value, "is a directory: give a file name")
        if not parent.is_dir():
            raise ParameterError(f"--{key}", value, f"cannot be written: the folder "
                                 f"{str(parent)!r} does not exist")
        if not os.access(parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
            raise ParameterError(f"--{key}", value, "cannot be written (permission denied)")


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Run one command; exit status 0 done, 1 a solver that did not converge (the message
    says why, with its status and residual), 2 bad input (one line, before any solve),
    130 interrupted."""
    args = build_parser().parse_args(argv)
    _limit_threads()
    try:
        check_outputs(args)
        return args.handler(args)
    except ConvergenceError as exc:
        print(f"gfbopt: error: the solver did not converge: {exc}", file=sys.stderr)
        return 1
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
