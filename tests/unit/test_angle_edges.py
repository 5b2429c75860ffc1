"""Angles at the Python edge are degrees: a static solution's and the
linear coefficients' angles are ``*_deg``; radians survive only in fields named ``*_rad``; the
0.2 radian names (``attitude_angle``, ``seam_angle``, ``min_film_angle``) are refused with the
conversion, so ``attitude_angle=1.0`` can never silently mean 57.3°.

Grid 24 x 8: the checks are about names and units, not accuracy; the comparisons are of one
solution with itself (degrees = math.degrees(radians) exactly, 1e-12 for float round trips).
"""
from __future__ import annotations

import math

import pytest

from gfbopt import BearingModel, solve_static
from gfbopt.errors import ParameterError
from gfbopt.inputs import Grid
from gfbopt.linear import coefficients, linearise

GRID = Grid(24, 8)


@pytest.fixture(scope="module")
def solution():
    model = BearingModel(bearing_number=2.0, compliance=1.0, foil="simple", film="seam",
                         seam_angle_deg=180.0)
    sol = solve_static(model, load=0.5, grid=GRID)
    assert sol.success, sol.message
    return sol


def test_static_solution_angles_are_degrees(solution):
    assert solution.attitude_angle_deg == math.degrees(solution.attitude_angle_rad)
    assert 0.0 < solution.attitude_angle_deg < 90.0            # a foil bearing leads the load
    assert solution.seam_angle_deg == pytest.approx(180.0, abs=1e-12)
    assert solution.min_film_angle_deg == pytest.approx(
        math.degrees(solution.min_film_angle_rad) % 360.0, abs=1e-12)
    assert solution.to_dict()["attitude_angle_deg"] == solution.attitude_angle_deg
    # the minimum film lies near the line of centres (θ = φ for a rigid bore), to a grid cell
    assert abs(solution.min_film_angle_deg - solution.attitude_angle_deg) < 360.0 / 24 * 3


@pytest.mark.parametrize("name", ["attitude_angle", "seam_angle", "min_film_angle"])
def test_old_radian_names_are_refused_with_the_replacement(solution, name):
    with pytest.raises(AttributeError, match=rf"{name}_deg.*{name}_rad"):
        getattr(solution, name)
    assert not hasattr(solution.model, "seam_angle")          # BearingModel: seam_angle_rad


def test_solve_static_takes_the_position_in_degrees(solution):
    model = solution.model
    fixed = solve_static(model, eccentricity=solution.eccentricity,
                         attitude_angle_deg=solution.attitude_angle_deg, grid=GRID)
    assert fixed.attitude_angle_deg == pytest.approx(solution.attitude_angle_deg, abs=1e-9)
    # the equilibrium position gives back the equilibrium load (force along the load line)
    assert fixed.load == pytest.approx(solution.load, rel=1e-6)
    with pytest.raises(ParameterError, match=r"^attitude_angle = 1.0: is no longer accepted.*"
                                             r"attitude_angle_deg=57.2958"):
        solve_static(model, eccentricity=0.3, attitude_angle=1.0, grid=GRID)


def test_coefficients_attitude_angle_in_degrees(solution):
    k = coefficients(linearise(solution), [0.5])
    assert k.attitude_angle_deg == pytest.approx(solution.attitude_angle_deg, abs=1e-12)
    with pytest.raises(AttributeError, match="attitude_angle_deg"):
        k.attitude_angle
