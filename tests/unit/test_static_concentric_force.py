"""A concentric journal in a preloaded bore: the film force need not lie on the load line.

Before, ``static --eccentricity 0`` with shims reported ``load`` = −F_X (here negative: the
film pushed the journal at 70° from the load line), and IPOPT's ε ≈ −4e-48 printed as a
negative eccentricity.  The load carried at the centre is the force's magnitude, its direction
is stated, and the eccentricity is exactly 0 with no attitude angle.
"""
import math

import pytest

from gfbopt.inputs import BearingModel, Grid
from gfbopt.inputs.bore_si import BoreSpec, as_built
from gfbopt.static import solve_static

GRID = Grid(36, 10)


def _shimmed(**bore) -> BearingModel:
    spec = BoreSpec(kind="shims", count=3, preload_ratio=0.3, width_deg=60.0, **bore)
    return BearingModel(bearing_number=5.0, compliance=1.0, film="seam", seam_angle_deg=180.0,
                        as_built=as_built(spec))


@pytest.mark.parametrize("offset", [0.0, 40.0])
def test_concentric_journal_in_a_preloaded_bore_reports_the_force_magnitude(offset):
    sol = solve_static(_shimmed(offset_deg=offset), eccentricity=0.0, grid=GRID)
    fx, fy = sol.force
    assert sol.success
    assert math.copysign(1.0, sol.eccentricity) == 1.0 and sol.eccentricity == 0.0
    assert math.isnan(sol.attitude_angle_deg)
    # the shims push the journal off the load line: F_Y is not a round-off
    assert abs(fy) > 0.1 * abs(fx)
    assert sol.load == pytest.approx(math.hypot(fx, fy), rel=1e-12)
    assert sol.load > abs(fx)
    out = sol.to_dict()
    assert out["load"] == out["film_force"] == sol.load
    assert out["film_force_angle_deg"] == pytest.approx(
        math.degrees(math.atan2(fy, fx)) % 360.0, abs=1e-9)
    assert 0.0 <= out["film_force_angle_deg"] < 360.0


def test_an_equilibrium_reports_its_force_opposite_the_load():
    sol = solve_static(BearingModel(bearing_number=2.0, compliance=1.0), load=0.3, grid=GRID)
    assert sol.success and sol.eccentricity > 0
    assert sol.film_force == pytest.approx(0.3, rel=1e-6)
    assert sol.film_force_angle_deg == pytest.approx(180.0, abs=1e-4)
    assert sol.load == pytest.approx(-sol.force[0], rel=1e-12)


def test_a_round_bore_at_the_centre_has_no_force_and_no_direction():
    sol = solve_static(BearingModel(bearing_number=2.0, compliance=1.0), eccentricity=0.0,
                       grid=GRID)
    assert sol.eccentricity == 0.0 and sol.load == pytest.approx(0.0, abs=1e-12)
    assert math.isnan(sol.film_force_angle_deg) and math.isnan(sol.attitude_angle_deg)


def test_round_off_never_reads_as_a_negative_eccentricity_or_attitude():
    from dataclasses import replace

    sol = solve_static(BearingModel(bearing_number=2.0, compliance=1.0), load=0.3, grid=GRID)
    tilted = replace(sol, attitude_angle_rad=-1e-15)
    assert tilted.attitude_angle_deg == 0.0 and math.copysign(1, tilted.attitude_angle_deg) == 1
    assert replace(sol, attitude_angle_rad=-1e-3).attitude_angle_rad == -1e-3   # a real angle
    centred = replace(sol, eccentricity=-3.9e-48)
    assert centred.eccentricity == 0.0 and math.isnan(centred.attitude_angle_deg)
