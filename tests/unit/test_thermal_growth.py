"""Centrifugal growth from the general Lamé solution against the closed forms; thermal growth;
Sutherland's law (DESIGN_NOTES "Clearance at speed: closed forms")."""
import math

import numpy as np
import pytest

from gfbopt.errors import ParameterError
from gfbopt.thermal.growth import (centrifugal_growth, hollow_disc_growth_closed_form,
                                   lame_constants, solid_disc_growth_closed_form,
                                   thermal_growth, thin_ring_growth)
from gfbopt.thermal.viscosity import sutherland_viscosity

STEEL = dict(density=7850.0, youngs_modulus=200e9, poisson_ratio=0.3)
B = 19.05e-3
OMEGA = 45_000 * 2 * math.pi / 60


def test_solid_disc_matches_closed_form_and_the_issue_number():
    u = centrifugal_growth(OMEGA, B, 0.0, **STEEL)
    closed = solid_disc_growth_closed_form(OMEGA, B, **STEEL)
    assert u == pytest.approx(closed, rel=1e-12)
    assert 0.9e-6 < u < 1.1e-6                # "about 1.0 µm"


@pytest.mark.parametrize("ratio", [0.05, 0.3, 0.5, 0.8, 0.95])
def test_hollow_disc_matches_closed_form(ratio):
    u = centrifugal_growth(OMEGA, B, ratio * B, **STEEL)
    closed = hollow_disc_growth_closed_form(OMEGA, B, ratio * B, **STEEL)
    assert u == pytest.approx(closed, rel=1e-12)


def test_free_surfaces_and_equilibrium_of_the_solved_constants():
    """The solved (A, B) leave both surfaces free and satisfy dσ_r/dr + (σ_r − σ_θ)/r
    + ρω²r = 0 (checked by finite differences of the stresses)."""
    a, b = 0.4 * B, B
    rho, e, nu = STEEL["density"], STEEL["youngs_modulus"], STEEL["poisson_ratio"]
    ca, cb = lame_constants(OMEGA, b, a, rho, e, nu)
    k = (1 - nu**2) * rho * OMEGA**2 / (8 * e)

    def stresses(r):
        du = ca - cb / r**2 - 3 * k * r**2
        ur = ca + cb / r**2 - k * r**2
        f = e / (1 - nu**2)
        return f * (du + nu * ur), f * (ur + nu * du)

    scale = rho * OMEGA**2 * b**2
    for r in (a, b):
        assert abs(stresses(r)[0]) < 1e-12 * scale
    r, h = 0.7 * b, 1e-6 * b
    dsr = (stresses(r + h)[0] - stresses(r - h)[0]) / (2 * h)
    sr, st = stresses(r)
    assert abs(dsr + (sr - st) / r + rho * OMEGA**2 * r) < 1e-6 * scale / b


def test_thin_ring_limit():
    # the closed form tends to the ring exactly (algebra), and the solved disc follows it
    # with the gap (3 + ν)(a² − b²)/(4 b²) of the closed form
    nu = STEEL["poisson_ratio"]
    ring = thin_ring_growth(OMEGA, B, STEEL["density"], STEEL["youngs_modulus"])
    assert hollow_disc_growth_closed_form(OMEGA, B, B, **STEEL) == pytest.approx(ring,
                                                                               rel=1e-12)
    for ratio in (1 - 1e-3, 1 - 1e-5):
        u = centrifugal_growth(OMEGA, B, ratio * B, **STEEL)
        gap = (3 + nu) * (ratio**2 - 1) / 4
        # the 2x2 system's conditioning grows like 1/(1 − a/b): 1e-16/1e-5 → 1e-11
        assert u / ring - 1 == pytest.approx(gap, abs=1e-10)
    assert 5.5e-6 < ring < 6.5e-6             # "about 6 µm"


def test_growth_scales_with_the_square_of_speed():
    u1 = centrifugal_growth(OMEGA, B, 0.3 * B, **STEEL)
    u2 = centrifugal_growth(2 * OMEGA, B, 0.3 * B, **STEEL)
    assert u2 / u1 == pytest.approx(4.0, rel=1e-12)
    assert centrifugal_growth(0.0, B, 0.0, **STEEL) == 0.0


def test_thermal_growth_issue_number():
    # 12e-6 × 40 × 19 mm ≈ 9 µm
    assert thermal_growth(12e-6, 19e-3, 40.0) == pytest.approx(9.12e-6, rel=1e-12)


@pytest.mark.parametrize("bad", [dict(inner_radius=B), dict(inner_radius=-1e-3),
                                 dict(poisson_ratio=0.5), dict(density=0.0)])
def test_bad_disc_refused(bad):
    args = dict(omega=OMEGA, outer_radius=B, inner_radius=0.0, **STEEL)
    args.update(bad)
    with pytest.raises(ParameterError):
        centrifugal_growth(**args)


def test_sutherland():
    mu = 1.85e-5
    assert sutherland_viscosity(300.0, mu, 300.0) == mu
    rise = sutherland_viscosity(340.0, mu, 300.0) / mu - 1
    assert rise == pytest.approx(0.0994, abs=5e-4)    # "+~10 % from 300 K to 340 K"
    # the U.S. Standard Atmosphere's own form β T^1.5/(T + S) at 288.15 K: 1.7894e-5 Pa s
    from gfbopt.thermal.viscosity import SUTHERLAND_AIR_BETA, SUTHERLAND_AIR_K
    t = 288.15
    beta_form = SUTHERLAND_AIR_BETA * t**1.5 / (t + SUTHERLAND_AIR_K)
    assert beta_form == pytest.approx(1.7894e-5, rel=1e-4)
    assert sutherland_viscosity(np.array([t, 400.0]), beta_form, t)[1] == pytest.approx(
        SUTHERLAND_AIR_BETA * 400.0**1.5 / (400.0 + SUTHERLAND_AIR_K), rel=1e-12)
