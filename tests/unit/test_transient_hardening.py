"""The hardening bump in the one-bearing transient (gfbopt.transient.hardening_recovery), and the
friction driver with the Kelvin–Voigt foil state (loss factor η > 0) beside the sliders.

The row balance against an independent root finder; the static equilibrium a fixed point of
the hardened transient; hardening off is today's law object; friction 0 with η > 0 is
integrate_orbits' damped answer."""
import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gfbopt.physics.foil_laws import foil_law
from gfbopt.physics.foil_recovery import row_mean_phi
from gfbopt.physics.hardening import hardened_foil_deflection, hardened_reaction_nd
from gfbopt.transient.friction_foil import FrictionFoil, friction_rows
from gfbopt.transient.friction_orbit import integrate_friction_orbits
from gfbopt.transient.hardening_recovery import (
    HardeningData,
    row_balance,
    transient_foil_law,
)
from gfbopt.transient.orbit import integrate_orbits
from gfbopt.transient.system import (
    RightHandSide,
    equilibrium_state,
    pressure_and_film,
    rigid_film,
    transient_model,
)
from tests.hardened_case import HARD, solved

_solved = solved


def _brent(phit, c, hr, s, n, lim, comp, kb, z, sb):
    """The root of f(ρ) = ρ + κ_b (W_h(ρ) − Z) − s_b q(W_h(ρ)) by bracketing (scipy)."""
    def f(rho):
        w = float(hardened_foil_deflection(rho, s, n, lim, comp))
        return rho + kb * (w - z) - sb * (phit / (hr + w) + c - 1.0)
    if hr <= 0:                       # the film closes where the bump's deflection is −H_r
        closes = float(hardened_reaction_nd(-hr, s, n, lim))
    else:
        closes = -1e3 if comp else -hr / s
    step = 1e-9 * (1.0 + abs(closes))
    while hr + float(hardened_foil_deflection(closes + step, s, n, lim, comp)) <= 0:
        step *= 10.0
    lo = closes + step
    assert f(lo) < 0
    hi = max(1.0, 2.0 * lo)
    while f(hi) < 0:
        hi *= 2
    return brentq(f, lo, hi, xtol=1e-15, rtol=1e-15, maxiter=500)


@pytest.mark.parametrize("comp", [False, True])
def test_row_balance_is_the_root_of_the_hardened_balance(comp):
    # random rows: rigid films from 1.5 down to −0.5 (the journal beyond the clearance, the
    # bump carrying it), light to heavy loads, stuck (κ_b, Z) and slipping (s_b = 1 ∓ μ)
    # branches; against brentq on the same f to 1e-12 (Newton's answer is at round-off)
    rng = np.random.default_rng(3)
    shape = (3, 40)
    hr = rng.uniform(-0.5, 1.5, shape)
    s = rng.uniform(0.2, 2.0, shape[1])
    hard = HardeningData(2.5, 1.2)
    c = 0.1
    phit = (np.maximum(hr, 0.05) + rng.uniform(0.3, 1.0, shape)) * rng.uniform(0.7, 3.0, shape)
    for kb, z, sb in ((0.0, 0.0, 1.0), (2.0 / s, rng.uniform(-0.2, 0.6, shape), 1.0),
                      (0.0, 0.0, rng.choice([0.7, 1.3], shape))):
        rho, w, a = row_balance(phit, c, hr, s, hard, comp, kb=kb, z=z, sb=sb)
        kbb, zb, sbb = (np.broadcast_to(v, shape) for v in (kb, z, sb))
        ref = np.array([[_brent(phit[i, j], c, hr[i, j], s[j], 2.5, 1.2, comp, kbb[i, j],
                                zb[i, j], sbb[i, j]) for j in range(shape[1])]
                        for i in range(shape[0])])
        np.testing.assert_allclose(rho, ref, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(w, hardened_foil_deflection(rho, s, 2.5, 1.2, comp),
                                   rtol=0, atol=1e-15)
        assert np.all(a > 0) and np.all(w < 1.2)


def test_hardening_off_is_todays_law_and_the_equilibrium_a_fixed_point():
    plain = _solved()
    assert transient_foil_law(plain.model, "transient") is foil_law(plain.model, "transient")
    sol = _solved(**HARD)
    tm = transient_model(sol)
    assert tm.law.name == "hardened" and tm.foil_data == HardeningData(3.0, 0.8)
    s = equilibrium_state(tm, 2)
    p, h = pressure_and_film(s.phi, s.x, s.y, tm)
    # the static solution's Φ recovers its P and H to round-off (measured 4e-16)
    np.testing.assert_allclose(p[1], sol.pressure, rtol=0, atol=1e-12)
    np.testing.assert_allclose(h[1, :, 0], sol.film[:, 0], rtol=0, atol=1e-12)
    # the right-hand side there is the static residual (IPOPT's; measured 4.3e-13, the
    # simple law's 3.6e-13), and the hardened film is stiffer than the linear bump's
    d = RightHandSide(tm, np.ones(2))(s)
    assert np.abs(d.phi).max() < 1e-10 and abs(d.u[0]) < 1e-12 and abs(d.v[0]) < 1e-12
    assert sol.eccentricity < plain.eccentricity - 0.01


def test_hardened_friction_rows_reduce_to_the_frictionless_and_balance_the_element():
    sol = _solved(friction_coefficient=0.3, friction_stiffness_ratio=2.0, **HARD)
    tm = transient_model(sol, friction=True)
    rng = np.random.default_rng(5)
    s = equilibrium_state(tm, 3)
    s.x += rng.normal(0, 0.05, 3)
    s.phi *= 1 + rng.normal(0, 0.05, s.phi.shape)
    hr = rigid_film(s.x, s.y, tm)
    z = tm.friction.equilibrium + rng.normal(0, 0.03, (3,) + tm.friction.equilibrium.shape)
    a, q, stuck = friction_rows(s.phi, hr, z, tm)
    w = a - hr
    S, mu, kappa = tm.compliance_rows, tm.friction.coefficient, 2.0
    bound = mu * np.maximum(q, 0.0)
    r = np.clip(kappa / S * (w - z), -bound, bound)
    np.testing.assert_allclose(hardened_reaction_nd(w, S, 3.0, 0.8) + r, q, atol=1e-11)
    loaded = q > 0
    assert 0 < (stuck & loaded).sum() < loaded.sum()       # both branches exercised
    # μ_f = 0 on every row: the hardened law's own recovery
    zero = dataclasses.replace(tm, friction=FrictionFoil(np.zeros(tm.shape[0]), 2.0,
                                                         tm.friction.equilibrium))
    free = dataclasses.replace(tm, friction=None)
    np.testing.assert_allclose(pressure_and_film(s.phi, s.x, s.y, zero, slider=z)[1],
                               pressure_and_film(s.phi, s.x, s.y, free)[1], rtol=0, atol=1e-13)
    phit, c = row_mean_phi(s.phi, hr, tm)
    np.testing.assert_allclose(q, phit / a + c - 1.0, atol=1e-14)


def test_zero_friction_with_a_loss_factor_is_integrate_orbits_damped_answer():
    # η = 0.3 (ν_ref 0.45 given: no linearisation), sliders with μ_f = 0 on every row: the
    # friction driver carries the Kelvin–Voigt state and equals integrate_orbits to 1e-12
    sol = _solved(loss_factor=0.3)
    tm = transient_model(sol, reference_whirl_ratio=0.45)
    w0 = tm.foil_state.equilibrium
    zero = dataclasses.replace(tm, friction=FrictionFoil(np.zeros(tm.shape[0]), 3.0, w0))
    for method, options in (("rk4", {}), ("rkc", {"time_step": 0.05})):
        today = integrate_orbits(tm, [3.0, 5.0], 2.0, method=method, **options)
        new = integrate_friction_orbits(zero, [3.0, 5.0], 2.0, method=method, **options).orbit
        assert new.tau.shape == today.tau.shape and new.time_step == today.time_step
        for a, b in ((new.x, today.x), (new.y, today.y), (new.min_film, today.min_film)):
            np.testing.assert_allclose(a, b, rtol=0, atol=1e-12)
        assert new.evaluations == today.evaluations


def test_friction_with_a_loss_factor_holds_the_equilibrium_and_damps_more():
    # μ_f = 0.3, κ = 2, η = 0.3: the equilibrium (sliders relaxed, W = W0) is a fixed point of
    # the damped friction model; the element's stuck spring stiffens the foundation, so a
    # kicked orbit differs from the frictionless damped one (the test can fail)
    sol = _solved(loss_factor=0.3, friction_coefficient=0.3, friction_stiffness_ratio=2.0)
    tm = transient_model(sol, friction=True, reference_whirl_ratio=0.45)
    s = equilibrium_state(tm, 1)
    rhs = RightHandSide(tm, np.ones(1))
    rhs.slider = np.broadcast_to(tm.friction.equilibrium, (1,) + tm.friction.equilibrium.shape)
    d = rhs(s)
    assert np.abs(d.w).max() < 1e-12 and np.abs(d.phi).max() < 1e-10
    run = integrate_friction_orbits(tm, [3.0], 2.0, kick=1e-3)
    free = integrate_orbits(dataclasses.replace(tm, friction=None), [3.0], 2.0, kick=1e-3)
    assert np.isfinite(run.orbit.x).all() and run.stuck[0, 2:].min() > 0.9
    assert np.abs(run.orbit.x - free.x).max() > 1e-6
    assert math.isfinite(run.orbit.min_film[0, -1])


@pytest.mark.parametrize("changes", [
    dict(loss_factor=0.3, **HARD),
    dict(friction_coefficient=0.3, friction_stiffness_ratio=2.0, **HARD),
    dict(loss_factor=0.3, friction_coefficient=0.3, friction_stiffness_ratio=2.0, **HARD),
    dict(compression_only=True, loss_factor=0.3, hardening_exponent=2.0, hardening_limit=0.6)])
def test_hardened_models_hold_their_static_equilibrium(changes):
    # with the Kelvin–Voigt state (τ_f W' + W = W_h(q)), the sliders, or both, and with bumps
    # that let go: the static solution is a fixed point of every hardened transient model (its
    # rates at IPOPT's residual, measured ≤ 1.1e-11), and a short kicked run stays finite
    sol = _solved(**changes)
    tm = transient_model(sol, friction=True, reference_whirl_ratio=0.45
                         if sol.model.loss_factor > 0 else None)
    assert tm.law.name == "hardened"
    s = equilibrium_state(tm, 1)
    rhs = RightHandSide(tm, np.ones(1))
    if tm.friction is not None:
        rhs.slider = tm.friction.equilibrium[None].copy()
    d = rhs(s)
    assert np.abs(d.phi).max() < 1e-9 and abs(d.u[0]) < 1e-12 and abs(d.v[0]) < 1e-12
    if tm.foil_state is not None:
        assert np.abs(d.w).max() < 1e-12
    run = integrate_friction_orbits(tm, [3.0], 1.0, kick=1e-3)
    assert np.isfinite(run.orbit.x).all() and run.orbit.success
