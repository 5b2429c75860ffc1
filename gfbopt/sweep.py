"""Run many independent operating points, serially or on several processes.

IPOPT/MUMPS is not thread-safe, so parallel sweeps use processes (``spawn``): each worker
imports gfbopt afresh and builds its own solvers.  A point that raises is recorded as a row
with ``success = False`` and the error message; the sweep goes on and nothing computed is lost.
"""
from __future__ import annotations

import multiprocessing
import time
import traceback
from concurrent.futures import ProcessPoolExecutor
from typing import Callable, Sequence


def _guarded(function: Callable, point: dict) -> dict:
    t0 = time.perf_counter()
    try:
        row = dict(function(**point))
        row.setdefault("success", True)
    except Exception as exc:  # a failed point is data, not a crash of the sweep
        row = {"success": False, "message": f"{type(exc).__name__}: {exc}",
               "traceback": traceback.format_exc(limit=3)}
    row.setdefault("wall_time_s", time.perf_counter() - t0)
    return row


def run_points(function: Callable, points: Sequence[dict], workers: int = 1) -> list[dict]:
    """``function(**point)`` for every point, in order; ``workers`` > 1 uses processes.

    ``function`` must be importable at module level (it is pickled to the workers) and
    return a dict (one table row).
    """
    if workers <= 1 or len(points) <= 1:
        return [_guarded(function, p) for p in points]
    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(max_workers=workers, mp_context=context) as pool:
        futures = [pool.submit(_guarded, function, p) for p in points]
        return [f.result() for f in futures]
