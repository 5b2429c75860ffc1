"""The hardening bump (gfbopt.physics.hardening): load–deflection against its closed form."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from gfbopt.errors import ParameterError
from gfbopt.physics.hardening import (HardeningLaw, check_hardening_limit,
                                      hardened_deflection, hardened_reaction)

K0 = 1.2e12          # N/m³ (Heshmat 1/α of a typical bump, order of magnitude)
LIM = 450e-6         # m, the bump height


@pytest.mark.parametrize("n", [0.5, 1.0, 2.0, 3.5])
def test_load_deflection_against_integrated_stiffness(n):
    # the static curve Δp(δ) = ∫₀^δ k(u) du: adaptive quadrature of the law's own k(δ) vs the
    # closed form, to 1e-9 relative, up to 90 % of the bump height
    law = HardeningLaw(K0, LIM, n)
    for frac in (0.01, 0.3, 0.6, 0.9):
        d = frac * LIM
        numeric, err = quad(lambda u: float(law.tangent(u)), 0.0, d, epsabs=0, epsrel=1e-13)
        assert float(law.reaction(d)) == pytest.approx(numeric, rel=1e-9)
        # the inverse is the closed form of the same curve
        assert float(law.deflection(law.reaction(d))) == pytest.approx(d, rel=1e-9)


def test_small_deflections_are_linear_and_tension_is_linear():
    law = HardeningLaw(K0, LIM, 2.0)
    d = 1e-3 * LIM
    # Δp = k0 δ (1 + n δ/(2 δ_lim) + …): relative excess n δ/(2 δ_lim) = 1e-3
    assert float(law.reaction(d)) / (K0 * d) - 1 == pytest.approx(1e-3, rel=2e-3)
    assert float(law.reaction(-d)) == pytest.approx(-K0 * d, rel=1e-15)
    assert float(law.deflection(-K0 * d)) == pytest.approx(-d, rel=1e-15)


def test_hard_limit():
    law = HardeningLaw(K0, LIM, 1.0)
    # every finite load leaves the bump short of flat (n >= 1)
    assert float(law.deflection(30 * K0 * LIM)) == pytest.approx(LIM * (1 - math.exp(-30)),
                                                                 rel=1e-12)
    with pytest.raises(ParameterError, match="hard limit"):
        law.tangent(LIM)
    with pytest.raises(ParameterError, match="flattens"):
        hardened_deflection(3.0 * K0 * LIM, K0, LIM, 0.5)       # flat at 2 k0 δ_lim
    assert hardened_reaction(0.0, K0, LIM, 2.0) == 0.0


def test_limit_above_bump_height_refused():
    assert check_hardening_limit(LIM, LIM) == LIM
    with pytest.raises(ParameterError, match="bump height"):
        check_hardening_limit(1.01 * LIM, LIM)
    with pytest.raises(ParameterError, match="exponent"):
        HardeningLaw(K0, LIM, -1.0)
    with pytest.raises(ParameterError, match="limit"):
        HardeningLaw(K0, math.nan, 1.0)
    np.testing.assert_allclose(hardened_deflection(np.array([0.0, 1.0]), K0, LIM, 2.0)[0], 0.0)
