"""Bumps that rub: Coulomb friction in the foil-law registry and the linear analysis.

Friction 0 is today's foundation exactly; friction holds no static deflection; small orbits see
the stuck foundation; the describing function moves the onset with the orbit amplitude."""
import math
from pathlib import Path

import numpy as np
import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import load_bearing
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.options import resolve_model_options
from gfbopt.linear import coefficients, impedance, linear_threshold, linearise
from gfbopt.linear.friction_onset import onset_at_amplitude, settled_amplitude
from gfbopt.physics.foil_laws import foil_law
from gfbopt.static import solve_static

ROOT = Path(__file__).resolve().parents[2]
GRID = Grid(36, 10)
GAMMAS = (0.0, 0.3, 0.5, 0.9)


def _model(**changes):
    bearing = load_bearing(ROOT / "problems/bearings/ruscitto.toml")
    kw = resolve_model_options(bearing.options).model_kwargs()
    return bearing, bearing.model(30000.0, **kw).replace(**changes)


def _solved(**changes):
    bearing, model = _model(**changes)
    return solve_static(model, load=bearing.nondimensional_load(20.0), grid=GRID)


@pytest.mark.parametrize("law", ["mean", "local"])
def test_zero_friction_is_todays_foundation(law):
    # every static and linear answer of friction_coefficient = 0 (any κ) equals today's
    today = _solved(deflection_law=law)
    zero = _solved(deflection_law=law, friction_coefficient=0.0, friction_stiffness_ratio=7.0)
    assert zero.eccentricity == today.eccentricity
    assert zero.attitude_angle_deg == today.attitude_angle_deg
    np.testing.assert_array_equal(zero.pressure, today.pressure)
    np.testing.assert_array_equal(zero.film, today.film)
    lt, lz = linearise(today), linearise(zero)
    assert lz.friction is None
    a, b = linear_threshold(lt), linear_threshold(lz)
    assert b.critical_mass == pytest.approx(a.critical_mass, rel=1e-12)
    assert b.whirl_ratio == pytest.approx(a.whirl_ratio, rel=1e-12)
    ca, cb = coefficients(lt, GAMMAS), coefficients(lz, GAMMAS)
    np.testing.assert_allclose(cb.stiffness, ca.stiffness, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(cb.damping, ca.damping, rtol=1e-12, atol=1e-12)


def test_friction_holds_no_static_deflection_and_stiffens_small_orbits():
    bare = _solved()
    rub = _solved(friction_coefficient=0.2, friction_stiffness_ratio=1.0)
    np.testing.assert_array_equal(rub.pressure, bare.pressure)       # statics: today's
    lin_b, lin_r = linearise(bare), linearise(rub)
    units = lin_r.friction
    loaded = units.slip > 0
    # slip displacement X_s = μ q⁺ S/κ on every loaded θ row, none where q <= 0
    q = lin_r.compliance.unit_gauge
    np.testing.assert_allclose(units.slip[loaded], 0.2 * q[loaded] * lin_r.static.model.compliance)
    assert 0 < loaded.sum() < loaded.size
    # small orbits: stuck, k = 1 + κ on loaded rows, 1 elsewhere; no damping from friction
    k = lin_r.stiffness_factor(0.5j)
    np.testing.assert_array_equal(k, np.where(loaded, 2.0, 1.0))
    assert not lin_r.hysteretic
    # a stiffer foundation: the Ruscitto bearing's critical mass rises (3.518 -> 4.090 at
    # 36 x 10, 30,000 rpm, 20 N, seam at 180°)
    mb, mr = linear_threshold(lin_b).critical_mass, linear_threshold(lin_r).critical_mass
    assert mb == pytest.approx(3.518, rel=1e-3)
    assert mr == pytest.approx(4.090, rel=1e-3)
    # the zero-frequency stiffness is the stuck foundation's too
    kz = coefficients(lin_r, (0.0,)).stiffness[0]
    zs = impedance(lin_r, 1e-7j)
    np.testing.assert_allclose(kz, zs.real, rtol=1e-5, atol=1e-5 * abs(kz).max())


@pytest.mark.parametrize("law", ["mean", "local"])
def test_uniform_unit_factors_are_the_scalar_factor(law):
    # the per-unit path (column scaling) and the scalar path give the same impedance
    lin = linearise(_solved(deflection_law=law))
    n_units = lin.compliance.unit_columns.size
    for k in (1.7, 1.0 + 0.3j):
        z1 = impedance(lin, 0.45j, k)
        z2 = impedance(lin, 0.45j, np.full(n_units, k))
        np.testing.assert_allclose(z2, z1, rtol=1e-12, atol=1e-12 * abs(z1).max())


def test_onset_against_orbit_amplitude():
    bare = linear_threshold(linearise(_solved())).critical_mass
    lin = linearise(_solved(friction_coefficient=0.2))
    stuck = linear_threshold(lin).critical_mass
    tiny = onset_at_amplitude(lin, 1e-4)          # every unit below its slip amplitude
    assert tiny.stuck_fraction == 1.0 and tiny.converged
    assert tiny.critical_mass == pytest.approx(stuck, rel=1e-12)
    mid = onset_at_amplitude(lin, 0.3)
    assert mid.converged and 0 < mid.stuck_fraction < 1
    assert bare < mid.critical_mass < stuck
    # huge orbits: β ~ 1e-4, the element adds ~ (4/π) β κ: back to the bare bump
    huge = onset_at_amplitude(lin, 300.0)
    assert huge.stuck_fraction == 0.0
    assert huge.critical_mass == pytest.approx(bare, rel=1e-3)
    assert huge.critical_mass != bare


def test_settled_amplitude_verdicts():
    lin = linearise(_solved(friction_coefficient=0.2))
    stuck = linear_threshold(lin).critical_mass
    below = settled_amplitude(lin, 0.9 * stuck)
    assert below.bounded and below.amplitude == 0.0 and "stable for small orbits" in below.verdict
    # on this bearing the slipping bumps lose more stiffness than they gain damping: M̄c(A)
    # falls from the stuck value, so a rotor above it has no bounded orbit inside the film
    above = settled_amplitude(lin, 1.02 * stuck, samples=6)
    assert not above.bounded and math.isnan(above.amplitude)
    assert above.verdict.startswith("no bounded orbit inside the film")


def test_engines_that_do_not_carry_friction_refuse_it():
    _, model = _model(friction_coefficient=0.2)
    assert foil_law(model, "linear").name == "simple"
    with pytest.raises(ParameterError, match="friction_coefficient = 0.2: .*not by the "
                                             "transient engines"):
        foil_law(model, "transient")


def test_settled_orbit_where_friction_restores_the_threshold():
    # a softer foundation (S = 3, 15,000 rpm, μ_f = 0.5, κ = 2): slipping raises M̄c above the
    # stuck value (4.1429 -> 4.1488 at A = 0.109 c), so a rotor just above the stuck onset
    # settles on a bounded orbit where M̄c(A) = M̄ (found by bisection on log A)
    bearing, model = _model(compliance=3.0, friction_coefficient=0.5,
                            friction_stiffness_ratio=2.0)
    model = model.replace(bearing_number=model.bearing_number / 2.0)        # 15,000 rpm
    sol = solve_static(model, load=bearing.nondimensional_load(20.0), grid=GRID)
    lin = linearise(sol)
    stuck = linear_threshold(lin).critical_mass
    assert stuck == pytest.approx(4.1429, rel=1e-4)
    mass = 4.145
    orbit = settled_amplitude(lin, mass, samples=10, smallest=1e-2, xtol=1e-4)
    assert orbit.bounded and orbit.small_motion_mass == pytest.approx(stuck, rel=1e-12)
    assert 0.065 < orbit.amplitude < 0.11 < orbit.film_limit
    assert onset_at_amplitude(lin, orbit.amplitude).critical_mass >= mass
    assert onset_at_amplitude(lin, orbit.amplitude * (1 - 2e-4)).critical_mass < mass
    assert orbit.verdict.startswith("bounded whirl of A = ")


def test_stuck_bumps_are_a_stiffer_foundation_where_they_carry():
    # compression-only bumps act only where q > 0, and there every slider is loaded: stuck,
    # the foundation is k_b (1 + κ) on every acting bump, i.e. the scalar factor 1 + κ of
    # the bare bearing's linearisation (an independent path: no foil units)
    bare = linearise(_solved(compression_only=True))
    rub = linearise(_solved(compression_only=True, friction_coefficient=0.2,
                            friction_stiffness_ratio=1.5))
    acting = rub.compliance.unit_gain != 0
    assert np.array_equal(rub.friction.slip > 0, acting & (rub.compliance.unit_gauge > 0))
    for s in (0.3j, 0.5j, 0.8j):
        z_ref = impedance(bare, s, 2.5)
        np.testing.assert_allclose(impedance(rub, s), z_ref, rtol=1e-10,
                                   atol=1e-10 * abs(z_ref).max())
