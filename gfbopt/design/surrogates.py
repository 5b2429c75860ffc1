"""Cheap analytic problems with known answers, to test and time the design optimiser.

Each is a module-level function returning one row (picklable, so the process pool and Dask
can run it), with two optional keywords for the tests: ``delay_s`` (sleep, to stand in for
an expensive evaluation) and ``log_path`` (append one line per call, to count evaluations
across a killed and resumed run).

=====================  =================================================================
function               known answer
=====================  =================================================================
:func:`zdt1`           Zitzler–Deb–Thiele ZDT1 (Evol. Comput. 8(2) (2000) 173–195) in 3
                       variables: front f2 = 1 − √f1, f1 ∈ [0, 1], at x1 = x2 = 0
:func:`quarter_circle` min (x, y) subject to x² + y² ≥ 1: front on the unit arc
:func:`hartmann3`      Hartmann-3 (Dixon & Szegö 1978), maximised: 3.86278 at
                       (0.114614, 0.555649, 0.852547), three other local maxima
:func:`pinched_bowl`   min (x − 0.8)² + (y − 0.8)² subject to x + y ≤ 1: 0.18 at (0.5, 0.5)
:func:`tilted_valley`  min of a valley 10× narrower across than along, tilted 45° to the
                       axes: 1 at (0.3, 0.6), inside the unit square (no constraint active)
:func:`leaning_wall`   max x + 2y + z/2 subject to x² + 2y² ≤ 0.5 and z ≤ 0.7 in [0, 1]³:
                       on both limits, at x = y = 1/√6, z = 0.7
=====================  =================================================================
"""
from __future__ import annotations

import math
import os
import time
from typing import Optional

import numpy as np

#: Hartmann-3: optimum and its location
HARTMANN3_MAX = 3.86278
HARTMANN3_ARGMAX = (0.114614, 0.555649, 0.852547)
_A = np.array([[3.0, 10, 30], [0.1, 10, 35], [3.0, 10, 30], [0.1, 10, 35]])
_P = 1e-4 * np.array([[3689, 1170, 2673], [4699, 4387, 7470], [1091, 8732, 5547],
                      [381, 5743, 8828]])
_C = np.array([1.0, 1.2, 3.0, 3.2])


def _side(delay_s: float, log_path: Optional[str], **design) -> None:
    if delay_s:
        time.sleep(delay_s)
    if log_path:
        text = " ".join(f"{k}={float(v).hex()}" for k, v in sorted(design.items()))
        with open(log_path, "a") as f:            # one short line: atomic append on POSIX
            f.write(f"{os.getpid()} {text}\n")


def zdt1(x0: float, x1: float, x2: float, delay_s: float = 0.0,
         log_path: Optional[str] = None) -> dict:
    """ZDT1 in three variables on [0, 1]³ (both objectives minimised)."""
    _side(delay_s, log_path, x0=x0, x1=x1, x2=x2)
    g = 1.0 + 9.0 * (x1 + x2) / 2.0
    return {"f1": x0, "f2": g * (1.0 - math.sqrt(x0 / g))}


def zdt1_front(n: int = 2001) -> np.ndarray:
    """The true ZDT1 front, densely sampled (n × 2)."""
    f1 = np.linspace(0.0, 1.0, n)
    return np.column_stack([f1, 1.0 - np.sqrt(f1)])


#: exact hypervolume of the ZDT1 front up to the reference point (1.1, 1.1):
#: ∫₀¹ (1.1 − (1 − √f1)) df1 + 0.1 × 1.1 = 0.1 + 2/3 + 0.11
ZDT1_HYPERVOLUME = 0.1 + 2.0 / 3.0 + 0.11


def quarter_circle(x: float, y: float, delay_s: float = 0.0,
                   log_path: Optional[str] = None) -> dict:
    """Objectives x and y (minimised), constraint ``radius_squared`` = x² + y² ≥ 1."""
    _side(delay_s, log_path, x=x, y=y)
    return {"f1": x, "f2": y, "radius_squared": x * x + y * y}


def hartmann3(x0: float, x1: float, x2: float, delay_s: float = 0.0,
              log_path: Optional[str] = None) -> dict:
    """Hartmann-3 as ``merit`` (to maximise)."""
    _side(delay_s, log_path, x0=x0, x1=x1, x2=x2)
    x = np.array([x0, x1, x2])
    return {"merit": float(np.sum(_C * np.exp(-np.sum(_A * (x - _P) ** 2, axis=1))))}


def pinched_bowl(x: float, y: float, delay_s: float = 0.0,
                 log_path: Optional[str] = None) -> dict:
    """``f`` = (x − 0.8)² + (y − 0.8)² (minimised) with ``sum_xy`` = x + y ≤ 1."""
    _side(delay_s, log_path, x=x, y=y)
    return {"f": (x - 0.8) ** 2 + (y - 0.8) ** 2, "sum_xy": x + y}


def failing_half(x: float, y: float) -> dict:
    """``f`` = (x − 0.3)² + (y − 0.6)², but the evaluation raises for x > 0.7 (a solver that
    fails in part of the space)."""
    if x > 0.7:
        raise RuntimeError("no convergence (planted failure)")
    return {"f": (x - 0.3) ** 2 + (y - 0.6) ** 2}


def tilted_valley(x: float, y: float, delay_s: float = 0.0,
                  log_path: Optional[str] = None) -> dict:
    """``f`` = 1 + (u + v)² + 10 (u − v)² with u = x − 0.3, v = y − 0.6 (minimised): 1 at
    (0.3, 0.6); the valley runs at 45° to both axes, so a search along the axes alone
    creeps down it."""
    _side(delay_s, log_path, x=x, y=y)
    u, v = x - 0.3, y - 0.6
    return {"f": 1.0 + (u + v) ** 2 + 10.0 * (u - v) ** 2}


#: the optimum of :func:`leaning_wall`: on x² + 2y² = 1/2 the Lagrange condition
#: (1, 2) = λ (2x, 4y) gives y = x, 3x² = 1/2; z at its bound 0.7
LEANING_WALL_ARGMAX = (math.sqrt(1.0 / 6.0), math.sqrt(1.0 / 6.0), 0.7)


def leaning_wall(x: float, y: float, z: float, delay_s: float = 0.0,
                 log_path: Optional[str] = None) -> dict:
    """``merit`` = x + 2y + z/2 (maximised) with ``ellipse`` = x² + 2y² ≤ 0.5 and ``z``
    ≤ 0.7 (a second, axis-parallel limit): both limits active at the optimum
    :data:`LEANING_WALL_ARGMAX`, the first curved and oblique to the axes."""
    _side(delay_s, log_path, x=x, y=y, z=z)
    return {"merit": x + 2.0 * y + 0.5 * z, "ellipse": x * x + 2.0 * y * y, "zc": z}
