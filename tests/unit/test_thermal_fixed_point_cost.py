"""The fixed point's cost and its root search: at most 3 static solves per operating point
(alone and along a speed line, up to 1 % below the thermal runaway at 60,625 rpm), and the
vectorised root search gives the scalar loop's answer exactly."""
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from gfbopt.inputs import Grid
from gfbopt.inputs.options import resolve_model_options
from gfbopt.static import SolverCache
from gfbopt.thermal.balance import N_SAMPLES, Balance
from gfbopt.thermal.bearing import FilmCase, FilmDrag
from gfbopt.thermal.files import load_running_bearing
from gfbopt.thermal.running import running_point, speed_line

THERMAL = Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto_thermal.toml"
GRID = Grid.parse("24x8")
SPEEDS = (10e3, 20e3, 30e3, 40e3, 50e3, 60e3)


@pytest.fixture(scope="module")
def case():
    bearing, spec = load_running_bearing(THERMAL)
    film = FilmCase(bearing, resolve_model_options(bearing.options), GRID, SolverCache(GRID),
                    20.0)
    return spec, film


def test_at_most_three_static_solves_per_point(case):
    spec, film = case
    for speed in SPEEDS:
        point = running_point(spec, speed, FilmDrag(film))
        assert point.converged and point.static_solves <= 3, speed
        n = point.network
        assert abs(n.heat_out_w - n.power_w) <= 1e-9 * max(n.power_w, 1.0)
    line = speed_line(spec, SPEEDS, FilmDrag(film))
    assert not math.isfinite(line.limit_rpm)
    assert [p.static_solves for p in line.points] <= [3] * len(SPEEDS)
    assert max(p.static_solves for p in line.points) <= 3
    # seeded and alone agree to the fixed point's tolerance (0.01 K of film temperature)
    alone = running_point(spec, 60e3, FilmDrag(film))
    assert abs(line.points[-1].network.film_k - alone.network.film_k) < 0.01


def _scalar_lowest_root(b: Balance):
    """The root search as a plain loop over the same samples (the reference): the root on
    the first sign change, or None when no sample is positive."""
    top, _ = b.top()
    grid = top * np.linspace(0.0, 1.0, N_SAMPLES + 1)[:-1]
    grid = np.append(grid, top * (1.0 - 1e-12))
    values = [b.residual(float(p)) for p in grid]
    k = next((i for i, v in enumerate(values) if v > 0), None)
    if k is None:
        return None, max(values)
    return brentq(b.residual, grid[k - 1], grid[k], xtol=1e-300, rtol=1e-15,
                  maxiter=200), None


@pytest.mark.parametrize("rpm, slope", [(30e3, 0.0), (60e3, -0.05), (60e3, 0.02)])
def test_vectorised_root_search_is_the_scalar_loop(case, rpm, slope):
    """Same samples, same bracket, same Brent: the roots agree to 1e-13 (the samples'
    values differ from the scalar ones by rounding only, ≤ 1e-12 of the drag), and a
    balance with no root (τ rising with Λ at 60,000 rpm) has none either way."""
    spec, _ = case
    t, omega = spec.thermal, rpm * math.pi / 30
    g = t.conductances(spec.radius, spec.length, spec.cold_clearance, 1e-6)
    b = Balance(spec, omega, lambda x: np.maximum(0.9 + slope * (x - 3.0), 1e-3), g)
    power, closest = b.lowest_root()
    reference, best = _scalar_lowest_root(b)
    if reference is None:
        assert power is None and best < 0 and b.residual(closest) < 0
        return
    assert power == pytest.approx(reference, rel=1e-13)
    assert abs(b.residual(power)) <= 1e-9 * power
    grid = np.linspace(0.0, 2.0 * power, 9)
    np.testing.assert_allclose(b.residual(grid), [b.residual(float(p)) for p in grid],
                               rtol=0, atol=1e-12 * power)
