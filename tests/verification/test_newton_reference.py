"""The hand-written sparse Newton reference (tests/verification/newton_reference.py) against gfbopt.

(a) its analytic Jacobian equals central finite differences of gfbopt's residual;
(b) its equilibrium equals gfbopt's CasADi/IPOPT equilibrium for the rigid periodic bearing.
"""
import importlib.util
from pathlib import Path

import numpy as np
import pytest

from gfbopt import BearingModel, Grid, solve_static
from gfbopt import discretisation as disc

_PATH = Path(__file__).resolve().parent / "newton_reference.py"
_SPEC = importlib.util.spec_from_file_location("newton_reference", _PATH)
newton_reference = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(newton_reference)


@pytest.mark.parametrize("bearing_number, eccentricity", [(0.6, 0.4), (3.0, 0.8)])
def test_analytic_jacobian_matches_finite_differences(bearing_number, eccentricity):
    error = newton_reference.jacobian_check(bearing_number, eccentricity, length_ratio=1.0,
                                            grid=Grid(24, 8))
    assert error < 1e-6


def test_jacobian_sparsity_is_five_point():
    st = disc.make_stencil(Grid(24, 8), periodic=True)
    dz = st.axial_spacing(1.0)
    h = newton_reference.film_thickness(st, 0.5)
    jac = newton_reference.jacobian(np.ones(st.n_unknown), h, st, 1.0, dz)
    assert jac.shape == (st.n_unknown, st.n_unknown)
    assert np.diff(jac.indptr).max() <= 5


@pytest.mark.parametrize("bearing_number, eccentricity", [(0.6, 0.4), (3.0, 0.6)])
def test_newton_equals_ipopt_equilibrium(bearing_number, eccentricity):
    grid = Grid(36, 10)
    ref = newton_reference.solve_rigid_newton(bearing_number, eccentricity, 1.0, grid)
    assert ref["converged"]
    assert ref["iterations"] <= 10
    sol = solve_static(BearingModel(bearing_number=bearing_number, foil="rigid",
                                    length_ratio=1.0), eccentricity=eccentricity, grid=grid)
    assert sol.success
    assert sol.load == pytest.approx(ref["load"], rel=1e-8)
    assert sol.attitude_angle_deg == pytest.approx(ref["attitude_angle_deg"],
                                                             abs=1e-6)
    assert np.abs(sol.pressure - ref["pressure"]).max() < 1e-8
