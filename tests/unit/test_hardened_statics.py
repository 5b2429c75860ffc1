"""Statics with the hardening bump, to add as tests/unit/test_hardened_statics.py
with static_hardening.diff (the static build then passes the law's n and W_lim)."""
from pathlib import Path

import numpy as np
import pytest

from gfbopt.inputs import load_bearing
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.options import resolve_model_options
from gfbopt.linear import linear_threshold, linearise
from gfbopt.static import solve_static

ROOT = Path(__file__).resolve().parents[2]
GRID = Grid(36, 10)


def _case(**changes):
    bearing = load_bearing(ROOT / "problems/bearings/ruscitto.toml")
    kw = resolve_model_options(bearing.options).model_kwargs()
    return bearing.model(30000.0, **kw).replace(**changes), bearing.nondimensional_load(20.0)


def test_statics_use_the_hardened_stiffness_and_linear_its_tangent():
    simple, load = _case()
    s0 = solve_static(simple, load=load, grid=GRID)
    m0 = linear_threshold(linearise(s0)).critical_mass
    # a far limit is the linear bump: W = S q (1 − n S q/(2 W_lim) + …), ~1e-8 here
    far = solve_static(simple.replace(hardening_exponent=2.0, hardening_limit=1e8), load=load,
                       grid=GRID)
    assert far.eccentricity == pytest.approx(s0.eccentricity, rel=1e-7)
    model = simple.replace(hardening_exponent=3.0, hardening_limit=0.8)
    sol = solve_static(model, load=load, grid=GRID)
    lin = linearise(sol)
    # stiffer bumps: smaller eccentricity and (Ruscitto, 30 krpm, 20 N, 36 x 10) a higher onset
    assert sol.eccentricity < s0.eccentricity
    mc = linear_threshold(lin).critical_mass
    assert mc == pytest.approx(3.8384, rel=1e-4) and mc > m0
    # the tangent compliance the law names is exactly IPOPT's Jacobian entry
    rows, cols = lin.compliance.a.nonzero()
    np.testing.assert_allclose(np.asarray(lin.a[rows, cols]).ravel(),
                               np.asarray(lin.compliance.a[rows, cols]).ravel(), rtol=1e-12,
                               atol=1e-15)
