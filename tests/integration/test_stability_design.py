"""Stability-driven bump design end to end on a coarse grid (numbers checked independently)."""

import pytest

from gfbopt import Grid, load_bearing
from gfbopt.design.spec import BumpDesignSpec
from gfbopt.design.stability_design import (StabilityDesignSpec, bearing_with_compliance,
                                            design_for_stability)
from gfbopt.errors import ParameterError
from gfbopt.inputs.options import ModelOptions
from gfbopt.inputs.rotor import Rotor
from gfbopt.physics import bump
from pathlib import Path

RUSCITTO = Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto.toml"


def _spec(**kw):
    b = load_bearing(RUSCITTO)
    base = dict(bearing=b, rotor=Rotor(2.0), load_newton=20.0, speed_range_rpm=(5000, 45000),
                min_film_thickness_m=3e-6,
                geometry=BumpDesignSpec(radial_clearance=b.radial_clearance,
                                        pitch_range=(3e-3, 6e-3),
                                        half_length_range=(1e-3, 2.5e-3),
                                        thickness_range=(50e-6, 150e-6)),
                options=ModelOptions(film="seam", seam_angle_deg=180.0, foil="simple"),
                grid=Grid(24, 8), loss_factors=(0.0,), deflection_laws=("mean",), n_scan=4)
    base.update(kw)
    return StabilityDesignSpec(**base)


def test_bearing_with_compliance_changes_only_the_bump_thickness():
    b = load_bearing(RUSCITTO)
    c = bearing_with_compliance(b, 0.5)
    assert c.compliance == pytest.approx(0.5, rel=1e-12)
    assert (c.bump_pitch, c.bump_half_length) == (b.bump_pitch, b.bump_half_length)


def test_design_recommends_a_geometry_that_meets_its_band_and_is_confirmed():
    result = design_for_stability(_spec())
    assert result.success, result.message
    rec = result.recommended
    geo = rec["geometry"]
    # re-evaluate the geometry independently with the plain formulas
    b = load_bearing(RUSCITTO)
    alpha = bump.bump_compliance(geo["pitch"], geo["half_length"], geo["thickness"],
                                 b.bump_youngs_modulus, b.poisson_ratio)
    s = bump.compliance_coefficient(alpha, b.ambient_pressure, b.radial_clearance)
    low, high = rec["band"]
    assert low * (1 - 1e-5) <= s <= high * (1 + 1e-5)
    assert 3e-3 * (1 - 1e-6) <= geo["pitch"] <= 6e-3 * (1 + 1e-6)
    # the axial-mean law favours the stiffest admissible bump (optimum on the lower bound)
    assert result.optima.loc[0, "decided_by_bound"] == "low"
    assert rec["onset_speed_rpm"] >= result.optima.loc[0, "baseline_onset_speed_rpm"]
    conf = result.confirmation
    assert conf["success"], conf["message"]
    # nonlinear = linear threshold to the search tolerance (0.5 %)
    assert conf["nonlinear_over_linear"] == pytest.approx(1.0, abs=0.005)


@pytest.mark.parametrize("kw, match", [
    (dict(speed_range_rpm=(45000, 5000)), "speed_range_rpm"),
    (dict(min_film_thickness_m=30e-6), "must be below the radial clearance"),
    (dict(loss_factors=(-0.1,)), r"loss_factors = -0.1: must lie in \[0, 1\]"),
    (dict(deflection_laws=("pointwise",)), "must be 'mean' or 'local'"),
])
def test_bad_design_specs(kw, match):
    with pytest.raises(ParameterError, match=match):
        _spec(**kw)
