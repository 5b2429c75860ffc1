"""Run a ``gfbopt`` command inside the test process.

``python -m gfbopt ARGS`` is ``sys.exit(gfbopt.cli.main(ARGS))`` (gfbopt/__main__.py), so
calling ``main`` here with stdout and stderr captured checks the same exit status and the
same output, without the 1-2 s of interpreter start and imports that a subprocess pays per
call (most of the default suite's CLI tests are bad-input refusals that take milliseconds
once imported).  It is stricter than a subprocess in one way: an exception escaping ``main``
(a traceback) fails the test at once, and a warning is an error (filterwarnings = error).

The entry point itself (``python -m gfbopt``, ``--version``, provenance from an unrelated
folder, Ctrl-C/SIGTERM, killed workers) keeps its subprocess tests.
"""
from __future__ import annotations

import contextlib
import io
import os
import subprocess
from pathlib import Path
from typing import Optional

from gfbopt.cli import main


def run_cli(*args: str, cwd: Optional[Path] = None) -> subprocess.CompletedProcess:
    """``gfbopt *args`` run in this process from ``cwd``: a CompletedProcess with the exit
    status, stdout and stderr, as ``subprocess.run(..., capture_output=True, text=True)``."""
    out, err = io.StringIO(), io.StringIO()
    here = os.getcwd()
    try:
        if cwd is not None:
            os.chdir(cwd)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                code = main([str(a) for a in args])
            except SystemExit as exc:       # argparse: --version, --help, its own errors
                code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None
                                                                   else 1)
    finally:
        os.chdir(here)
    return subprocess.CompletedProcess(["gfbopt", *map(str, args)], code, out.getvalue(),
                                       err.getvalue())
