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
:mod:`.common`         operating-point options, refusal of ignored options, JSON output
:mod:`.si`             a bearing file's [model] options merged with the command line
=====================  =================================================================

Bad input prints one line naming the parameter, its value and the rule, and exits with
status 2, before anything is solved.  A solve that does not converge exits with status 1 and
says why.  Every JSON output carries a ``provenance`` block (version, source commit, options).
"""
from __future__ import annotations

import os
import sys
from typing import Optional, Sequence

from ..errors import GfboptError
from ..version import __version__
from . import design, linear, run, stability, static, transient
from . import rotor
from . import capacity
from .common import Parser

COMMANDS = (static, linear, stability, transient, design, run, rotor)
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


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = build_parser().parse_args(argv)
    _limit_threads()
    try:
        return args.handler(args)
    except GfboptError as exc:
        print(f"gfbopt: error: {exc}", file=sys.stderr)
        return 2
