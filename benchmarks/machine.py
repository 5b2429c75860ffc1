"""What machine and versions a benchmark ran on (shared by the benchmark scripts)."""
from __future__ import annotations

import datetime
import json
import os
import platform
from pathlib import Path

import casadi
import numpy as np
import scipy

import gfbopt


def machine_info(**extra) -> dict:
    """Date, platform, CPU count, library versions and BLAS thread settings, plus ``extra``."""
    info = {
        "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
        "platform": platform.platform(),
        "processor": platform.processor() or platform.machine(),
        "cpu_count": os.cpu_count(),
        "python": platform.python_version(),
        "casadi": casadi.__version__,
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "gfbopt": gfbopt.__version__,
        # small sparse factorisations are sensitive to OpenBLAS threading: record it
        "thread_env": {k: os.environ.get(k) for k in ("OPENBLAS_NUM_THREADS",
                                                      "OMP_NUM_THREADS", "MKL_NUM_THREADS")},
    }
    info.update(extra)
    return info


def write_report(out: dict, path) -> Path:
    """Write a benchmark's results as JSON (creating the folder) and say where."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(out, indent=2, default=float))
    print(f"\nwrote {path}")
    return path


def tree_label(root) -> str:
    """A code tree as a reader can find it again: its commit (and "+ changes" when its tracked
    files differ from it), never a folder of this machine."""
    import subprocess

    def git(*args):
        return subprocess.run(["git", *args], cwd=str(root), capture_output=True,
                              text=True).stdout.strip()
    commit = git("rev-parse", "--short=12", "HEAD") or "unknown commit"
    dirty = bool(git("status", "--porcelain", "--untracked-files=no"))
    return f"gfbopt at {commit}" + (" + uncommitted changes" if dirty else "")

