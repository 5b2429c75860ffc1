"""Bump-foil formulas (gfbopt.physics.bump): hand values, the Ruscitto bearing, identities
between them, an independent beam solution for the top-foil sag, and agreement on floats,
numpy arrays and cvxpy expressions (the geometric program evaluates the same functions)."""
import math

import cvxpy as cp
import numpy as np
import pytest

from gfbopt.physics import bump

# Ruscitto, McCormick & Gray 1978, NASA CR-135368 — the bump-foil test bearing as listed in the
# thesis (Mohan, IIT Guwahati, 2010), Table 3.3; problems/bearings/ruscitto.toml holds the same
# values.  SI units.
RUSCITTO = {"radius": 19.05e-3, "radial_clearance": 20e-6, "top_foil_thickness": 101.6e-6,
            "bump_thickness": 101.6e-6, "pitch": 4.572e-3, "half_length": 1.778e-3,
            "youngs_modulus": 214e9, "poisson_ratio": 0.29, "ambient_pressure": 1.0e5}


def ruscitto_alpha():
    r = RUSCITTO
    return bump.bump_compliance(r["pitch"], r["half_length"], r["bump_thickness"],
                                r["youngs_modulus"], r["poisson_ratio"])


def test_ruscitto_compliance_matches_hand_value_and_physics_md():
    r = RUSCITTO
    alpha = ruscitto_alpha()
    # α = 2 s l0³ (1 − ν²)/(E t_b³), worked by hand: 2·4.572e-3·(1.778e-3)³·0.9159
    # / (214e9·(101.6e-6)³) = 2.0975e-10 m³/N
    assert alpha == pytest.approx(2 * 4.572e-3 * 1.778e-3**3 * (1 - 0.29**2)
                                  / (214e9 * 101.6e-6**3), rel=1e-14)
    assert alpha == pytest.approx(2.0975e-10, rel=1e-4)
    s = bump.compliance_coefficient(alpha, r["ambient_pressure"], r["radial_clearance"])
    assert s == pytest.approx(1e5 * alpha / 20e-6, rel=1e-14)
    assert s == pytest.approx(1.05, abs=0.005)  # docs/PHYSICS.md: S ≈ 1.05 for this bearing
    # Heshmat's stiffness per unit area K = E t_b³ / (2 s l0³ (1 − ν²)) = 1/α
    assert bump.bump_stiffness_per_area(alpha) == pytest.approx(
        214e9 * 101.6e-6**3 / (2 * 4.572e-3 * 1.778e-3**3 * (1 - 0.29**2)), rel=1e-14)


def test_ruscitto_stress_deflection_and_bump_count():
    r = RUSCITTO
    # DESIGN_NOTES: the Ruscitto geometry carries 236 MPa per bar: 3·1e5·4.572e-3·1.778e-3
    # / (101.6e-6)² = 236.25 MPa
    sigma = bump.bump_bending_stress(1e5, r["pitch"], r["half_length"], r["bump_thickness"])
    assert sigma == pytest.approx(236.25e6, rel=1e-6)
    assert bump.bump_deflection(1e5, ruscitto_alpha()) == pytest.approx(
        1e5 * ruscitto_alpha(), rel=1e-14)
    # 2π · 19.05 / 4.572 = 26.18 bumps round the bearing
    assert bump.number_of_bumps(r["radius"], r["pitch"]) == pytest.approx(26.180, abs=5e-4)


def test_stress_closed_form_at_fixed_compliance_equals_direct_formula():
    e, nu, pa, c, dp = 214e9, 0.29, 101325.0, 32e-6, 1e5
    for pitch, half, thick in [(4.572e-3, 1.778e-3, 101.6e-6), (6e-3, 2.9e-3, 181e-6),
                               (2e-3, 0.5e-3, 50e-6)]:
        s = bump.compliance_coefficient(bump.bump_compliance(pitch, half, thick, e, nu), pa, c)
        direct = bump.bump_bending_stress(dp, pitch, half, thick)
        closed = bump.stress_at_fixed_compliance(dp, s, pitch, half, c, pa, e, nu)
        assert closed == pytest.approx(direct, rel=1e-12)
        # and σ_b = (3/2) E' t_b δ / l0², δ = Δp α (DESIGN_NOTES)
        delta = bump.bump_deflection(dp, bump.bump_compliance(pitch, half, thick, e, nu))
        assert 1.5 * e / (1 - nu**2) * thick * delta / half**2 == pytest.approx(direct, rel=1e-12)


def clamped_strip_by_finite_differences(span, pressure, rigidity, n=400):
    """Mid-span deflection and end moment of a strip clamped at both ends under uniform
    pressure: D w'''' = q, w = w' = 0 at x = 0 and x = span, second-order differences with
    mirrored ghost nodes.  Independent of the closed forms under test."""
    h = span / n
    m = n - 1  # interior unknowns w_1 .. w_{n-1}
    a = np.zeros((m, m))
    for i in range(m):
        for offset, coef in ((-2, 1.0), (-1, -4.0), (0, 6.0), (1, -4.0), (2, 1.0)):
            j = i + offset
            if 0 <= j < m:
                a[i, j] += coef
    a[0, 0] += 1.0    # w_{-1} = w_1 (zero slope at x = 0), w_0 = 0
    a[-1, -1] += 1.0  # the same at x = span
    w = np.linalg.solve(a / h**4, np.full(m, pressure / rigidity))
    end_moment = rigidity * 2.0 * w[0] / h**2  # D w''(0) with w_0 = 0, w_{-1} = w_1
    return w[m // 2], end_moment


def test_top_foil_sag_and_stress_match_a_clamped_strip_solved_numerically():
    e, nu, dp, span, t = 214e9, 0.29, 1e5, 4.572e-3, 101.6e-6
    rigidity = e * t**3 / (12 * (1 - nu**2))  # plate rigidity per unit width [N m]
    sag = bump.top_foil_sag(dp, span, t, e, nu)
    errors = []
    for n in (200, 400):
        sag_fd, moment_fd = clamped_strip_by_finite_differences(span, dp, rigidity, n)
        errors.append(abs(sag_fd / sag - 1))
    # second-order differences: 400 intervals leave 5e-5 on the sag, 6e-6 on the moment, and
    # halving the step divides the sag error by 4 (it converges to the closed form)
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.01)
    assert sag == pytest.approx(sag_fd, rel=1e-4)
    assert bump.top_foil_stress(dp, span, t) == pytest.approx(6 * moment_fd / t**2, rel=1e-4)


FUNCTIONS = {
    # name: (function, arguments in the order of the signature; None marks a design variable)
    "bump_compliance": (bump.bump_compliance, ("pitch", "half_length", "thickness", 214e9, 0.29)),
    "bump_bending_stress": (bump.bump_bending_stress,
                            (1e5, "pitch", "half_length", "thickness")),
    "top_foil_sag": (bump.top_foil_sag, (1e5, "pitch", "top", 214e9, 0.29)),
    "top_foil_stress": (bump.top_foil_stress, (1e5, "pitch", "top")),
    "number_of_bumps": (bump.number_of_bumps, (19.05e-3, "pitch")),
    "stress_at_fixed_compliance": (bump.stress_at_fixed_compliance,
                                   (1e5, "compliance", "pitch", "half_length", 32e-6, 101325.0,
                                    214e9, 0.29)),
}
POINTS = {"pitch": [4.572e-3, 6e-3, 2e-3], "half_length": [1.778e-3, 2.9e-3, 0.5e-3],
          "thickness": [101.6e-6, 181e-6, 50e-6], "top": [101.6e-6, 80e-6, 150e-6],
          "compliance": [1.05, 0.664, 0.1]}


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_floats_arrays_and_cvxpy_expressions_agree(name):
    function, signature = FUNCTIONS[name]
    arrays = {k: np.array(v) for k, v in POINTS.items()}
    on_arrays = function(*[arrays[a] if isinstance(a, str) else a for a in signature])
    variables = {k: cp.Variable(pos=True) for k in POINTS}
    expression = function(*[variables[a] if isinstance(a, str) else a for a in signature])
    # every quantity is a monomial: log-log affine, usable on either side of a GP constraint
    assert expression.is_log_log_affine()
    for i in range(3):
        on_floats = function(*[POINTS[a][i] if isinstance(a, str) else a for a in signature])
        assert isinstance(on_floats, float)
        for key, var in variables.items():
            var.value = POINTS[key][i]
        assert on_arrays[i] == pytest.approx(on_floats, rel=1e-14)
        assert float(expression.value) == pytest.approx(on_floats, rel=1e-12)


def test_compliance_and_stiffness_of_expressions_are_monomials():
    alpha = bump.bump_compliance(cp.Variable(pos=True), cp.Variable(pos=True),
                                 cp.Variable(pos=True), 214e9, 0.29)
    for expr in (bump.compliance_coefficient(alpha, 101325.0, 32e-6),
                 bump.bump_stiffness_per_area(alpha), bump.bump_deflection(1e5, alpha)):
        assert expr.is_log_log_affine()
    assert bump.bump_stiffness_per_area(2.0) == 0.5
    assert math.isclose(bump.compliance_coefficient(2e-10, 1e5, 20e-6), 1.0)


def test_formulas_also_evaluate_on_casadi_symbols():
    # gfbopt.physics promises numpy and CasADi alike; the bump formulas use only * / **
    import casadi as ca

    x = ca.SX.sym("x", 3)
    expression = bump.bump_compliance(x[0], x[1], x[2], 214e9, 0.29)
    f = ca.Function("alpha", [x], [expression])
    point = [4.572e-3, 1.778e-3, 101.6e-6]
    assert float(f(point)) == pytest.approx(ruscitto_alpha(), rel=1e-14)
