"""The spring–slider (Jenkins) element against its closed forms (gfbopt.physics.friction)."""
import math

import numpy as np
import pytest

from gfbopt.errors import ParameterError
from gfbopt.physics.friction import (JenkinsElement, describing_function, dissipated_energy,
                                     equivalent_stiffness, harmonic_cycle,
                                     quadrature_stiffness, slider_update)

K, FS = 2.5e6, 3.0           # N/m, N: x_s = 1.2 µm


@pytest.mark.parametrize("amplitude", [0.5e-6, 1.2e-6, 1.5e-6, 2.4e-6, 4.0e-6, 30e-6])
def test_cycle_matches_closed_forms(amplitude):
    # Integrated cycle (time-stepped play operator, Fourier coefficients by quadrature) vs
    # E = 4 F_s (X − x_s), k_eq = (k/π)(ψ − ½ sin 2ψ), q = (4k/π) β (1 − β); stuck when β ≥ 1.
    el = JenkinsElement(K, FS)
    cyc = harmonic_cycle(el, amplitude, samples=2000)
    xs = FS / K
    beta = xs / amplitude
    if beta >= 1:
        e, keq, q = 0.0, K, 0.0
    else:
        psi = math.acos(1 - 2 * beta)
        e = 4 * FS * (amplitude - xs)
        keq = K / math.pi * (psi - 0.5 * math.sin(2 * psi))
        q = 4 * K / math.pi * beta * (1 - beta)
    assert cyc.energy == pytest.approx(e, rel=1e-6, abs=1e-6 * FS * xs)
    assert cyc.stiffness == pytest.approx(keq, rel=1e-6)
    assert cyc.quadrature == pytest.approx(q, rel=1e-6, abs=1e-6 * K)
    # the closed-form functions of the module agree with the same formulas
    assert float(equivalent_stiffness(K, xs, amplitude)) == pytest.approx(keq, rel=1e-12)
    assert float(quadrature_stiffness(K, xs, amplitude)) == pytest.approx(q, abs=1e-9 * K)
    assert dissipated_energy(FS, K, amplitude) == pytest.approx(e, rel=1e-12, abs=1e-30)
    assert cyc.quadrature == pytest.approx(cyc.energy / (math.pi * amplitude**2), rel=1e-12,
                                           abs=1e-9 * K)


def test_slipping_cycle_converges_with_steps():
    # the only quadrature error is the step where slip starts (a kink): it falls with the step
    el = JenkinsElement(K, FS)
    exact = K / math.pi * (math.acos(1 - 2 * 0.5) - 0.5 * math.sin(2 * math.acos(0.0)))
    errs = [abs(harmonic_cycle(el, 2.4e-6, samples=n).stiffness - exact) / K
            for n in (202, 402)]
    assert errs[1] < errs[0] / 4 or errs[1] < 1e-12


def test_play_operator_stick_and_slip():
    assert slider_update(0.0, 0.5, 1.0) == 0.0          # inside the band: stuck
    assert slider_update(0.0, 3.0, 1.0) == 2.0          # slides, spring stretched by x_s
    assert slider_update(2.0, -1.0, 1.0) == 0.0         # reversed past the band
    np.testing.assert_array_equal(slider_update(np.zeros(2), np.array([3.0, -3.0]), 1.0),
                                  [2.0, -2.0])


def test_describing_function_limits():
    xs = 1.0
    assert describing_function(K, xs, 1.0) == pytest.approx(K)          # β = 1: stuck limit
    assert describing_function(K, xs, 1e9) == pytest.approx(0.0, abs=1e-3 * K)
    z = describing_function(K, xs, 2.0, sign=-1)                         # β = ½
    assert z.real == pytest.approx(K / 2)                                # ψ = π/2
    assert z.imag == pytest.approx(-K / math.pi)


def test_bad_element():
    with pytest.raises(ParameterError, match="slip_force"):
        JenkinsElement(K, -1.0)
    with pytest.raises(ParameterError, match="stiffness"):
        JenkinsElement(float("nan"), 1.0)
    with pytest.raises(ParameterError, match="samples"):
        harmonic_cycle(JenkinsElement(K, FS), 1e-6, samples=7)
