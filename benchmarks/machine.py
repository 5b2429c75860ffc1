"""What machine and versions a benchmark ran on (shared by the benchmark scripts)."""
from __future__ import annotations

import datetime
import os
import platform

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
