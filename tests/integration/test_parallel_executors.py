"""Executors (gfbopt.parallel): the serial and the process-pool executor give the same rows in
the same order, failed points become rows, and each worker builds a solver once per
formulation."""
import math
import os

import pytest

from gfbopt import BearingModel, Grid, analyses
from gfbopt.parallel import run_points

GRID = Grid(24, 8)
POINTS = [{"model": BearingModel(bearing_number=lam, compliance=s, foil=foil, film="seam"),
           "eccentricity": eps, "grid": GRID}
          for lam, s, foil in ((1.0, 0.0, "rigid"), (2.0, 1.0, "simple"))
          for eps in (0.2, 0.4)]


def _same(a, b):
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b


def _without_timing(rows):
    return [{k: v for k, v in r.items() if k != "wall_time_s"} for r in rows]


@pytest.fixture(scope="module")
def serial_rows():
    return run_points(analyses.linear_threshold_point, POINTS, workers=1,
                      tags=[{"k": k} for k in range(len(POINTS))])


def test_serial_and_process_pool_give_the_same_rows(serial_rows):
    pooled = run_points(analyses.linear_threshold_point, POINTS, workers=2,
                        tags=[{"k": k} for k in range(len(POINTS))])
    a, b = _without_timing(serial_rows), _without_timing(pooled)
    assert [r["k"] for r in b] == list(range(len(POINTS)))
    for ra, rb in zip(a, b):
        assert ra.keys() == rb.keys()
        assert all(_same(ra[k], rb[k]) for k in ra), (ra, rb)
    assert all(r["success"] for r in a) and all(1.0 < r["critical_mass"] < 10 for r in a)


def test_a_failed_point_is_a_row_and_the_sweep_goes_on():
    bad = dict(POINTS[0], eccentricity=-0.3)          # refused by solve_static (bad input)
    for workers in (1, 2):
        rows = run_points(analyses.static_point, [POINTS[0], bad, POINTS[1]], workers=workers,
                          tags=[{"label": "a"}, {"label": "b"}, {"label": "c"}])
        assert [r["label"] for r in rows] == ["a", "b", "c"]
        assert [r["success"] for r in rows] == [True, False, True]
        assert "eccentricity" in rows[1]["message"] and "ParameterError" in rows[1]["message"]
        assert rows[1]["wall_time_s"] >= 0 and rows[2]["load"] > 0


def test_a_function_may_return_several_rows_and_gets_the_cache():
    rows = run_points(analyses.impedance_point,
                      [{"model": BearingModel(bearing_number=1.0, foil="rigid"),
                        "eccentricity": 1e-3, "whirl_ratios": [0.0, 0.5], "grid": GRID}],
                      tags=[{"case": "x"}])
    assert [r["whirl_ratio"] for r in rows] == [0.0, 0.5]
    assert all(r["case"] == "x" and r["success"] for r in rows)


def test_workers_build_one_solver_per_formulation():
    """The transient maps used to build a CasADi solver per point; now each worker builds
    one per (grid, film, structure) and reuses it."""
    points = [{"model": POINTS[2]["model"], "eccentricity": e, "grid": GRID}
              for e in (0.1, 0.2, 0.3, 0.4, 0.5, 0.6)]
    rows = run_points(cache_report, points, workers=2)
    for pid in {r["pid"] for r in rows}:
        builds = [r["solvers"] for r in rows if r["pid"] == pid]
        assert builds[-1] == 1, builds           # one build served all of its points
    assert all(r["pid"] != os.getpid() for r in rows)


def cache_report(model, eccentricity, grid, cache):
    """A worker function reporting its process and the size of its solver cache."""
    row = analyses.static_point(model, eccentricity=eccentricity, grid=grid, cache=cache)
    return {**row, "pid": os.getpid(), "solvers": len(cache)}
