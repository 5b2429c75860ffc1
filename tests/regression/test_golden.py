"""Regression tier: gfbopt against its own golden outputs (coarse grids).

The golden file was written by ``tests/regression/make_golden.py`` before the package was
restructured, so these tests show that moving code changed no number beyond round-off.
Tolerances: IPOPT converges the static residual to 1e-10 and every result is recomputed from
the solution, so a pure refactoring moves static and linear numbers by ≲ 1e-9 (relative);
the RK4 transient is deterministic and moves only by floating-point reordering (≲ 1e-9 after
two revolutions of an unstable orbit).  A 1e-7 relative tolerance is far above that noise and
far below any physical change (the smallest model change, one grid refinement, moves loads by
~1e-3).
"""
import json
import math
from pathlib import Path

import numpy as np
import pytest

from make_golden import STATIC_CASES, compute  # noqa: E402  (tests/regression on sys.path)

GOLDEN = json.loads((Path(__file__).parent / "golden.json").read_text())
REL = 1e-7


@pytest.fixture(scope="module")
def fresh():
    return compute()


def _close(a, b, rel=REL, abs_=1e-10):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return np.allclose(a, b, rtol=rel, atol=abs_, equal_nan=True)


@pytest.mark.parametrize("case", sorted(STATIC_CASES))
def test_static_unchanged(fresh, case):
    for key, value in GOLDEN["static"][case].items():
        assert _close(fresh["static"][case][key], value), (case, key)


@pytest.mark.parametrize("case", sorted(GOLDEN["linear"]))
def test_linear_unchanged(fresh, case):
    g, f = GOLDEN["linear"][case], fresh["linear"][case]
    assert _close(f["stiffness"], g["stiffness"], abs_=1e-9), case
    assert _close(f["damping"], g["damping"], abs_=1e-9), case
    assert math.isclose(f["critical_mass"], g["critical_mass"], rel_tol=REL)
    assert math.isclose(f["whirl_ratio"], g["whirl_ratio"], rel_tol=REL)


@pytest.mark.parametrize("case", sorted(GOLDEN["transient"]))
def test_transient_unchanged(fresh, case):
    for key, value in GOLDEN["transient"][case].items():
        assert _close(fresh["transient"][case][key], value, abs_=1e-9), (case, key)
