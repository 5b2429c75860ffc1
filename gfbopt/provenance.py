"""What made a result: gfbopt version, the commit of the gfbopt source, date, libraries.

The commit is that of the directory gfbopt was imported from — never of the directory the
user happens to run in (their own project, a results folder).  When gfbopt is installed from
a wheel rather than a git checkout the commit is ``None`` and ``source`` says so.
"""
from __future__ import annotations

import datetime as _dt
import functools
import math
import platform
import subprocess
from pathlib import Path

from .version import __version__

#: One line every output carries about units and frames (docs/PHYSICS.md states them in full).
CONVENTIONS = ("SI units (m, Pa, N, kg, s) at the edges, speeds in rpm; non-dimensional groups "
               "Λ = 6μωR²/(p_a c²), S = p_a α/c, W̄ = W/(p_a R²), M̄ = M c ω²/W0 with M the rotor "
               "mass and W0 the static load per bearing; X along the static load, angles from "
               "the load line in the direction of rotation, degrees in outputs (docs/PHYSICS.md)")

_PACKAGE_DIR = Path(__file__).resolve().parent


def _git(*args: str) -> str:
    out = subprocess.run(["git", "-C", str(_PACKAGE_DIR), *args], capture_output=True,
                         text=True, timeout=10, check=False)
    if out.returncode != 0:
        raise OSError(out.stderr.strip())
    return out.stdout.strip()


@functools.lru_cache(maxsize=1)
def source_state() -> dict:
    """{'commit': sha or None, 'dirty': bool or None, 'source': description} of gfbopt itself.

    ``dirty`` is True when the gfbopt checkout has uncommitted changes to tracked files.
    Generated outputs (``results/``, ``runs/``) are not source: a run that rewrites the shipped
    results does not make its own provenance dirty.
    """
    try:
        top = Path(_git("rev-parse", "--show-toplevel"))
        if not (top / "gfbopt" / "version.py").is_file() or _PACKAGE_DIR != top / "gfbopt":
            raise OSError("gfbopt is not the package of this repository")
        commit = _git("rev-parse", "HEAD")
        dirty = bool(_git("status", "--porcelain", "--untracked-files=no", "--",
                          ":(top,exclude)results", ":(top,exclude)runs"))
        # the checkout's folder is this machine's business, not the result's: the commit names it
        return {"commit": commit, "dirty": dirty, "source": "git checkout"}
    except (OSError, subprocess.SubprocessError):
        return {"commit": None, "dirty": None,
                "source": "installed package (not a git checkout)"}


def jsonable(value):
    """``value`` made JSON-safe for every output: numpy scalars → Python numbers, non-finite
    floats → null, keys → strings, tuples → lists (recursively)."""
    import numpy as np

    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def provenance(**options) -> dict:
    """The provenance block of an output: version, source commit and dirty flag, date,
    platform and library versions, the conventions, and the ``options`` given (physics
    options, grid, method, …)."""
    import casadi
    import numpy
    import scipy

    state = source_state()
    return {"gfbopt_version": __version__, "source_commit": state["commit"],
            "source_dirty": state["dirty"], "source": state["source"],
            "date": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
            "python": platform.python_version(), "numpy": numpy.__version__,
            "scipy": scipy.__version__, "casadi": casadi.__version__,
            "conventions": CONVENTIONS, "options": options}
