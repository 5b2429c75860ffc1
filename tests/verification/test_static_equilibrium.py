"""Static equilibrium: modes, options, conventions and failure reporting (published tables
are in tests/validation)."""
import math
from pathlib import Path

import numpy as np
import pytest

from gfbopt import (BearingModel, ConvergenceError, Grid, ParameterError, StaticSolver,
                    solve_static)
from gfbopt.inputs import load_bearing
from gfbopt.inputs import DEFAULT_GRID

def test_load_mode_inverts_eccentricity_mode(periodic_solver):
    model = BearingModel(bearing_number=2.0, compliance=1.0, foil="simple")
    forward = solve_static(model, eccentricity=0.8, solver=periodic_solver)
    back = solve_static(model, load=forward.load, solver=periodic_solver)
    assert back.success
    assert back.eccentricity == pytest.approx(0.8, abs=1e-8)
    assert back.attitude_angle_rad == pytest.approx(forward.attitude_angle_rad, abs=1e-8)


def test_compliant_bearing_runs_past_unit_eccentricity_from_cold(periodic_solver):
    """Heavy load on a compliant bearing: ε > 1 with H > 0 (Kim & San Andrés); cold start."""
    model = BearingModel(bearing_number=1.0, compliance=1.0, foil="simple")
    sol = solve_static(model, load=3.0, solver=periodic_solver)
    assert sol.success
    assert sol.eccentricity > 1.5
    assert 0 < sol.min_film < 0.5
    assert sol.film.min() > 0 and sol.pressure.min() > 0


@pytest.mark.parametrize("eps", [0.8, 0.9])
def test_rigid_bearing_cold_start_at_high_eccentricity(periodic_solver, eps):
    sol = solve_static(BearingModel(bearing_number=1.0, foil="rigid"), eccentricity=eps,
                       solver=periodic_solver)
    assert sol.success
    assert sol.min_film == pytest.approx(1 - eps, abs=1e-3)


def test_warm_start_needs_fewer_iterations(periodic_solver):
    model = BearingModel(bearing_number=3.0, compliance=0.5, foil="simple")
    cold = solve_static(model, eccentricity=0.6, solver=periodic_solver)
    warm = solve_static(model, eccentricity=0.61, solver=periodic_solver, initial=cold)
    assert warm.success and warm.iterations < cold.iterations


def test_seam_following_max_film_equals_a_fixed_seam_at_the_same_place():
    """A seam on the maximum-film line (θ_s = π + φ) and a seam fixed at that same angle
    from the load give the same equilibrium."""
    grid = Grid(36, 10)
    follow = BearingModel(bearing_number=2.0, compliance=1.0, film="seam")
    a = solve_static(follow, eccentricity=0.5, grid=grid)
    fixed = follow.replace(seam_angle_deg=math.degrees(math.pi + a.attitude_angle_rad))
    b = solve_static(fixed, eccentricity=0.5, grid=grid)
    assert b.load == pytest.approx(a.load, rel=1e-8)
    assert b.attitude_angle_rad == pytest.approx(a.attitude_angle_rad, abs=1e-8)


def test_seam_forces_ambient_pressure_at_the_foil_ends():
    sol = solve_static(BearingModel(bearing_number=2.0, compliance=1.0, film="seam",
                                    seam_angle_deg=200), eccentricity=0.5,
                       grid=Grid(36, 10))
    assert np.all(sol.pressure[0] == 1.0) and np.all(sol.pressure[-1] == 1.0)
    assert sol.theta_from_seam[0] == 0.0
    assert sol.theta_from_seam[-1] == pytest.approx(2 * math.pi)


def test_compression_only_keeps_the_foil_on_the_bumps():
    grid = Grid(36, 10)
    for foil in ("simple", "beam"):
        model = BearingModel(bearing_number=2.0, compliance=1.0, foil=foil,
                             top_foil_coefficient=0.1, film="seam", compression_only=True)
        sol = solve_static(model, eccentricity=0.6, grid=grid)
        free = solve_static(model.replace(compression_only=False), eccentricity=0.6, grid=grid)
        assert sol.success
        assert free.deflection.min() < -0.05          # the free foil is pulled in …
        if foil == "simple":
            assert sol.deflection.min() >= 0.0        # … the compression-only one is not
        else:
            # Where suction lifts the foil off the bumps only bending resists it: the
            # separated part is one run that ends at the free end (a lifted tail).
            lifted = np.flatnonzero(sol.deflection[:, 0] < -1e-9)
            assert lifted.size > 0
            assert lifted[-1] == sol.deflection.shape[0] - 1
            assert np.all(np.diff(lifted) == 1)


def test_beam_stiffer_top_foil_carries_more_load():
    """A stiffer top foil spreads the load: larger C approaches the rigid bearing."""
    grid = Grid(36, 10)
    loads = [solve_static(BearingModel(bearing_number=5.0, compliance=1.0, foil="beam",
                                       top_foil_coefficient=c, film="seam"),
                          eccentricity=0.3, grid=grid).load for c in (1e-4, 1.0, 1e3)]
    rigid = solve_static(BearingModel(bearing_number=5.0, foil="rigid", film="seam"),
                         eccentricity=0.3, grid=grid).load
    assert loads[0] < loads[1] < loads[2] < rigid * 1.001


def test_dimensional_ruscitto_point():
    """45,000 rpm, 100 N: the load in newtons round-trips and h_min is a few µm to tens."""
    geometry = load_bearing(Path(__file__).resolve().parents[2] / "problems/bearings/ruscitto.toml")
    model = geometry.model(45000.0, foil="simple")
    sol = solve_static(model, load=geometry.nondimensional_load(100.0))
    assert sol.success
    assert geometry.load_newton(sol.load) == pytest.approx(100.0, rel=1e-8)
    assert 5.0 < sol.min_film * geometry.radial_clearance * 1e6 < 30.0


def test_one_build_serves_many_operating_points(periodic_solver):
    """Λ, S and L/D are parameters: no rebuild between points with different values."""
    for lam, s, ld in ((0.5, 0.0, 0.5), (4.0, 2.0, 1.5)):
        sol = solve_static(BearingModel(bearing_number=lam, compliance=s, length_ratio=ld),
                           eccentricity=0.5, solver=periodic_solver)
        assert sol.success and sol.z[-1] == pytest.approx(ld)


def test_a_failed_solve_says_so():
    solver = StaticSolver(Grid(36, 10), ipopt_options={"ipopt.max_iter": 1})
    model = BearingModel(bearing_number=1.0, foil="rigid")
    sol = solve_static(model, eccentricity=0.8, solver=solver, continuation=False)
    assert not sol.success
    assert sol.status == "Maximum_Iterations_Exceeded"
    assert "IPOPT status Maximum_Iterations_Exceeded" in sol.message
    with pytest.raises(ConvergenceError, match=r"did not converge \(status: Maximum_Iter"):
        solve_static(model, eccentricity=0.8, solver=solver, continuation=False,
                     raise_on_failure=True)


@pytest.mark.parametrize("kwargs, match", [
    (dict(eccentricity=-0.1), r"^eccentricity = -0.1: must be >= 0"),
    (dict(eccentricity=1.0), r"^eccentricity = 1.0: must be < 1 for a rigid bearing"),
    (dict(eccentricity=float("nan")), r"^eccentricity = nan: must be finite"),
    (dict(load=-2.0), r"^load = -2.0: must be > 0"),
    (dict(), r"give exactly one of eccentricity or load"),
    (dict(eccentricity=0.3, load=1.0), r"give exactly one of eccentricity or load"),
])
def test_bad_targets(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        solve_static(BearingModel(bearing_number=1.0, foil="rigid"), **kwargs)


def test_solver_built_for_another_formulation_is_refused(periodic_solver):
    with pytest.raises(ParameterError, match=r"^solver = .*another formulation"):
        solve_static(BearingModel(bearing_number=1.0, film="seam"), eccentricity=0.3,
                     solver=periodic_solver)


def test_default_grid_is_144_by_36():
    assert DEFAULT_GRID == Grid(144, 36) == Grid()
