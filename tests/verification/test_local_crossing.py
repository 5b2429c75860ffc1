"""The onset search's local threshold (:func:`gfbopt.linear.crossings.local_crossing`): Newton's
method on the whirl ratio on a Krylov space of one LU, from the crossing at a neighbouring
speed, must land on the full threshold's crossing (:func:`gfbopt.linear.linear_threshold`,
whirl ratio to Brent's 1e-10) when the branch is the same.  Tolerances: the Krylov model is
converged to 1e-11 and the Newton iteration stops below a 1e-10 step, so mass and whirl agree
to ~1e-10 (measured 2e-11 at 144 × 36); 1e-9 leaves a margin.  The direct search (an LU per
step) stops at a 1e-4 step and is exact to about its square (≤ 1e-6 asserted; measured 1e-8)."""
from __future__ import annotations

from pathlib import Path

import pytest

from gfbopt import Grid, SolverCache
from gfbopt.inputs import Rotor, load_bearing_file
from gfbopt.linear import linear_threshold, linearise
from gfbopt.linear.crossings import direct_local_crossing, local_crossing
from gfbopt.rotor.analysis import equilibrium, resolve_case

REPO = Path(__file__).resolve().parents[2]
BEARING, OPTIONS = load_bearing_file(REPO / "problems" / "bearings" / "ruscitto.toml")


@pytest.mark.parametrize("options", [{}, dict(deflection_law="local", loss_factor=0.3)],
                         ids=["seam_180_mean", "local_eta_0.3"])
def test_local_crossing_equals_the_full_threshold_at_a_neighbouring_speed(options):
    grid = Grid(36, 10)
    case = resolve_case(BEARING, Rotor(2.0), 20.0, options=OPTIONS, grid=grid,
                        cache=SolverCache(grid), **options)
    lins = []
    for speed in (13000.0, 14000.0):          # 7.7 % apart: a scan step of the search
        sol = equilibrium(case, speed)
        lins.append(linearise(sol, case.cache(sol.model, grid)))
    start, full = (linear_threshold(lin) for lin in lins)
    assert start.whirl_ratio > 0 and full.whirl_ratio > 0
    root = start.critical_mass * start.whirl_ratio**2 * lins[0].load
    local = local_crossing(lins[1], start.whirl_ratio, root)
    assert local is not None and local.factorisations == 1
    assert local.mass == pytest.approx(full.critical_mass, rel=1e-9)
    assert local.whirl == pytest.approx(full.whirl_ratio, abs=1e-9)
    direct = direct_local_crossing(lins[1], start.whirl_ratio, root)
    assert direct.mass == pytest.approx(full.critical_mass, rel=1e-6)
    # the speed changed the threshold by far more than the tolerances above
    assert abs(full.critical_mass / start.critical_mass - 1) > 1e-3
