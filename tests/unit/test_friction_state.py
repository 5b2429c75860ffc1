"""The friction state law for transients (gfbopt.physics.friction_state) on a one-degree-of-
freedom self-excited oscillator, against the linear analysis (stuck) and the describing
function (slipping): m ẍ + c ẋ + k x + k_f (x − z) = 0, c < 0, slider z by the play operator."""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gfbopt.physics.friction import equivalent_stiffness, quadrature_stiffness
from gfbopt.physics.friction_state import (element_reaction, foil_deflection,
                                           slider_after_step, slip_displacement)

M, K, KAPPA = 1.0, 1.0, 1.0        # mass, bump stiffness (S = 1/K), element spring κ K
MU_Q = 1.0                         # μ_f q⁺: slip displacement X_s = μ q S/κ = 1


def _integrate(c, x0, t_end, steps_per_period):
    """RK4 on (x, v) for a batch of cases, the slider updated once per accepted step (each
    stage sees the element by the play operator from the step's starting z); returns
    (times, x history) (n_steps, n_cases)."""
    c = np.asarray(c, float)
    omega = math.sqrt((K + KAPPA * K) / M)
    dt = np.broadcast_to(2 * math.pi / omega / np.asarray(steps_per_period, float), c.shape)
    x = np.full(c.shape, float(x0))
    v = np.zeros(c.shape)
    z = np.zeros(c.shape)
    n = int(np.ceil(t_end / dt.min()))
    hist = np.empty((n, c.size))

    def acc(x, v):
        # the element at the stage's deflection: the play operator from the step's start z
        z_stage = slider_after_step(z, x, MU_Q, 1.0 / K, 1.0, KAPPA)
        return (-c * v - K * x - element_reaction(x, z_stage, 1.0 / K, KAPPA)) / M

    for i in range(n):
        k1x, k1v = v, acc(x, v)
        k2x, k2v = v + 0.5 * dt * k1v, acc(x + 0.5 * dt * k1x, v + 0.5 * dt * k1v)
        k3x, k3v = v + 0.5 * dt * k2v, acc(x + 0.5 * dt * k2x, v + 0.5 * dt * k2v)
        k4x, k4v = v + dt * k3v, acc(x + dt * k3x, v + dt * k3v)
        x = x + dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        v = v + dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        z = slider_after_step(z, x, MU_Q, 1.0 / K, 1.0, KAPPA)
        hist[i] = x
    return np.arange(1, n + 1)[:, None] * dt[None, :], hist


def _peaks(x):
    i = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1
    return i


def test_small_orbits_grow_at_the_stuck_rate():
    # below the slip amplitude the slider stays stuck: the linear system with the stuck
    # stiffness k + κk has the growth rate −c/(2m) = 0.01 exactly; the transient's peaks
    # give it within 2 % (measured 3e-5)
    t, x = _integrate([-0.02], 1e-3, 150.0, 200)
    p = _peaks(x[:, 0])
    assert x.max() < 0.1                                   # far below X_s = 1: stuck
    rate = np.polyfit(t[p, 0], np.log(x[p, 0]), 1)[0]
    assert rate == pytest.approx(0.01, rel=0.02)
    # and the whirl frequency is the stuck one, √((k + κk)/m)
    period = np.diff(t[p, 0]).mean()
    assert 2 * math.pi / period == pytest.approx(math.sqrt(2.0), rel=1e-3)


def test_limit_cycle_where_the_describing_function_restores_the_threshold():
    # above the stuck onset (c < 0) the orbit grows until the friction's equivalent damping
    # q(X)/ω(X) balances −c: the describing function's amplitude, against the transient's
    # settled one (within 5 %; measured 0.1 %), and the step halved (≤ 1 %; measured 3e-6)
    cases = [-0.1, -0.1, -0.05]
    t, x = _integrate(cases, 0.5, 400.0, [200, 400, 200])
    for j, c in enumerate(cases):
        p = _peaks(x[:, j])
        settled = x[p[-10:], j].mean()

        def balance(amp):
            keq = float(equivalent_stiffness(KAPPA * K, MU_Q / KAPPA, amp))
            q = float(quadrature_stiffness(KAPPA * K, MU_Q / KAPPA, amp))
            return c + q / math.sqrt((K + keq) / M)

        predicted = brentq(balance, 1.0 + 1e-9, 2.0)      # the stable (first) crossing
        assert settled == pytest.approx(predicted, rel=0.05)
        assert np.ptp(x[p[-10:], j]) < 1e-3 * settled      # settled, not still growing
    s200, s400 = (x[_peaks(x[:, j])[-10:], j].mean() for j in (0, 1))
    assert abs(s400 / s200 - 1) <= 0.01


def test_massless_foil_balance_stuck_and_slipping():
    s, mu, kappa = 0.8, 0.3, 2.0
    q = np.array([0.5, 0.5, 0.5, -0.2])
    z = np.array([0.3, 0.0, 0.6, 0.1])
    w, stuck = foil_deflection(q, z, s, mu, kappa)
    xs = slip_displacement(q, s, mu, kappa)
    np.testing.assert_allclose(xs, [0.06, 0.06, 0.06, 0.0])
    reaction = element_reaction(w, z, s, kappa)
    # the balance holds with the element's reaction clipped at μ q⁺
    np.testing.assert_allclose(w / s + np.clip(reaction, -mu * np.maximum(q, 0),
                                               mu * np.maximum(q, 0)), q, rtol=1e-14)
    np.testing.assert_array_equal(stuck, [True, False, False, False])
    # stuck: W = (S q + κ Z)/(1 + κ); slipping outward: W = S q (1 − μ); no load: W = S q
    assert w[0] == pytest.approx((s * 0.5 + kappa * 0.3) / (1 + kappa))
    assert w[1] == pytest.approx(s * 0.5 * (1 - mu))
    assert w[2] == pytest.approx(s * 0.5 * (1 + mu))
    assert w[3] == pytest.approx(s * -0.2)
    # after the step the slider sits within X_s of W (play operator)
    z_new = slider_after_step(z, w, q, s, mu, kappa)
    assert np.all(np.abs(w - z_new) <= xs + 1e-15)
    assert z_new[0] == z[0]
