"""Thermal runaway and the running onset on the real film.

Runaway: a bearing that can shed little heat (conductances to ambient of 0.02 W/K, a sleeve
that does not grow) has a fixed point at low speed only.  The runaway speed the fixed point
brackets is checked against a brute-force scan of the true balance G(P) = P_drag(state(P)) − P
(one static solve per heat input P, up to the closing of the clearance): just below the
bracket G changes sign (a fixed point exists), just above it G stays positive (none)."""
import math
from pathlib import Path

import numpy as np
import pytest

from gfbopt.cli.running import running_onset, running_stability
from gfbopt.inputs import Grid, OperatingPoint, Rotor
from gfbopt.inputs.options import resolve_model_options
from gfbopt.static import SolverCache
from gfbopt.thermal.bearing import FilmCase, FilmDrag
from gfbopt.thermal.files import load_running_bearing
from gfbopt.thermal.running import MIN_RUNNING_CLEARANCE, _Balance, running_point, speed_line
from tests.cli_inprocess import run_cli

THERMAL = Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto_thermal.toml"
GRID = Grid.parse("24x8")


@pytest.fixture(scope="module")
def hot(tmp_path_factory):
    src = THERMAL.read_text()
    for old, new in (("journal_to_ambient = 0.5 ", "journal_to_ambient = 0.02"),
                     ("sleeve_to_ambient = 1.0 ", "sleeve_to_ambient = 0.02"),
                     ("sleeve_expansion_coefficient = 12e-6",
                      "sleeve_expansion_coefficient = 0.0")):
        assert old in src
        src = src.replace(old, new)
    path = tmp_path_factory.mktemp("hot") / "hot.toml"
    path.write_text(src)
    return path


def drag_for(bearing, load=20.0):
    return FilmDrag(FilmCase(bearing, resolve_model_options(bearing.options), GRID,
                             SolverCache(GRID), load))


def brute_force_balance(spec, drag, rpm, n=40):
    """G(P) = P_drag − P on n heat inputs up to the closing of the clearance."""
    t, omega, last, values = spec.thermal, rpm * math.pi / 30, None, []
    top = _Balance(spec, omega, lambda _: 1.0,
                   t.conductances(spec.radius, spec.length, spec.cold_clearance)).ceiling()
    for power in np.linspace(0.0, 0.995 * top, n):
        g = t.conductances(spec.radius, spec.length, spec.cold_clearance,
                           0.0 if last is None else last.leakage_flow(spec))
        balance = _Balance(spec, omega, lambda _: 1.0, g)
        c = balance.clearance(power)[0]
        assert c > MIN_RUNNING_CLEARANCE
        film = balance.temperatures(power)["film_k"]
        last = drag(rpm, c, spec.viscosity_at(film), film)
        values.append(last.power_w - power)
    return np.array(values)


def test_runaway_speed_agrees_with_a_brute_force_scan(hot):
    bearing, spec = load_running_bearing(hot)
    line = speed_line(spec, [2e3, 4e3, 8e3], drag_for(bearing))
    assert line.limit_kind == "runaway" and line.message.startswith("thermal runaway from")
    assert line.limit_rpm / line.limit_low_rpm - 1 <= 0.01
    below = brute_force_balance(spec, drag_for(bearing), 0.99 * line.limit_low_rpm)
    above = brute_force_balance(spec, drag_for(bearing), 1.01 * line.limit_rpm)
    assert below[0] > 0 and below.min() < 0          # a fixed point (two, in fact)
    assert above.min() > 0                           # none up to the closing clearance


def test_runaway_is_an_answer_of_gfbopt_stability(hot):
    result = run_cli("stability", "--bearing", hot, "--rotor-mass-kg", "1.5", "--load-newton",
                     "20", "--speed-rpm", "10000", "--grid", "24x8")
    assert result.returncode == 0, result.stderr
    # reported where it happens (bracketed from rest to ≤ 1 %), not at the speed asked
    import re

    found = re.search(r"thermal runaway from ([\d,]+) rpm \(bracketed in \[([\d,]+), "
                      r"([\d,]+)\] rpm", result.stdout)
    assert found, result.stdout
    limit, low, high = (float(g.replace(",", "")) for g in found.groups())
    assert limit == high and high / low - 1 <= 0.01 and high < 10000
    bearing, spec = load_running_bearing(hot)
    line = speed_line(spec, [2e3, 4e3, 8e3], drag_for(bearing))
    assert line.limit_low_rpm <= high * 1.0001 and low <= line.limit_rpm * 1.0001
    assert "running clearance" not in result.stdout          # no state after the runaway


def test_running_onset_zeroes_the_margin_at_its_own_running_condition():
    bearing, spec = load_running_bearing(THERMAL)
    cache = SolverCache(GRID)
    found = running_onset(bearing, spec, Rotor(1.5), 20.0, (8000.0, 40000.0), grid=GRID,
                          cache=cache)
    onset = found["onset_speed_rpm"]
    assert 8000 < onset < 40000 and onset != found["frozen_onset_speed_rpm"]
    result, point, warm = running_stability(bearing, spec, Rotor(1.5),
                                            OperatingPoint(onset, 20.0), grid=GRID,
                                            cache=cache)
    assert point.converged and warm.radial_clearance == point.running_clearance
    assert result.critical_mass_kg / 1.5 - 1 == pytest.approx(0.0, abs=1e-3)
    assert found["running"]["running_clearance_um"] == pytest.approx(
        point.running_clearance * 1e6, rel=1e-6)
    assert len(cache) <= 2               # the frozen onset's coarse guide and the 24x8 grid


def test_coarse_start_gives_the_same_running_point():
    """On a fine grid the fixed point's first solve starts from the coarse guide's
    equilibrium: the same running point as from a cold IPOPT start (to the fixed point's
    tolerance), every solve of it a Newton solve."""
    from gfbopt.cli.running import coarse_start

    bearing, spec = load_running_bearing(THERMAL)
    grid = Grid.parse("96x30")
    cache = SolverCache(grid)
    case = FilmCase(bearing, resolve_model_options(bearing.options), grid, cache, 20.0)
    start = coarse_start(grid, cache)
    assert start is not None and coarse_start(GRID, cache) is None
    warm, cold = FilmDrag(case, start=start), FilmDrag(case)
    a = running_point(spec, 30e3, warm)
    b = running_point(spec, 30e3, cold)
    assert a.running_clearance == pytest.approx(b.running_clearance, rel=1e-7)
    assert a.network.film_k == pytest.approx(b.network.film_k, abs=0.02)
    assert warm.last.solver == "newton"
