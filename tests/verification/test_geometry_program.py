"""The bump-foil geometric program against closed forms and independent re-evaluation.

The formulas are typed in again here (not imported from gfbopt.physics.bump) so that a slip
in the package cannot confirm itself.  Tolerances: Clarabel solves the GP to ~1e-8 in the
logarithms of the variables, so optimal values are compared at rel 1e-6 and constraints
re-checked at rel 1e-6; the compliance is asked within 0.1 % (the brief) and holds to 1e-6.
"""
import math
import re

import pytest
from scipy.optimize import brentq

from gfbopt.design import BumpDesignSpec, compliance_range, design_bump_foil
from gfbopt.errors import ParameterError

E, NU, PA, C, DP, GAP = 214e9, 0.29, 101325.0, 32e-6, 1e5, 0.2e-3
E_PLATE = E / (1 - NU**2)
SOLVER_REL = 1e-6


def compliance(s, l0, t, c=C, pa=PA):
    """S = p_a α / c, α = 2 s l0³ (1 − ν²)/(E t³) (Heshmat 1983)."""
    return pa * 2 * s * l0**3 / (E_PLATE * t**3) / c


def stress(s, l0, t, dp=DP):
    """σ_b = 3 Δp s l0 / t²."""
    return 3 * dp * s * l0 / t**2


def stress_at_compliance(target, s, l0, c=C, pa=PA):
    """σ_b = 3 Δp (c E' S/(2 p_a))^{2/3} s^{1/3} / l0 (DESIGN_NOTES)."""
    return 3 * DP * (c * E_PLATE * target / (2 * pa)) ** (2 / 3) * s ** (1 / 3) / l0


def example_spec(**changes):
    """The DESIGN_NOTES example: c = 32 µm, Inconel X-750 (E = 214 GPa, ν = 0.29), Δp = 1 bar,
    s ∈ [2, 6] mm, l0 ∈ [0.5, 3] mm, t_b ∈ [50, 200] µm, gap 0.2 mm (the spec defaults)."""
    base = {"radial_clearance": C, "design_pressure": DP, "pitch_range": (2e-3, 6e-3),
            "half_length_range": (0.5e-3, 3e-3), "thickness_range": (50e-6, 200e-6),
            "gap": GAP}
    base.update(changes)
    return BumpDesignSpec(**base)


# (a) ----------------------------------------------------------------------------------
def test_returned_geometry_meets_every_constraint_when_re_evaluated():
    spec = example_spec(radius=19.05e-3, top_foil_thickness_range=(40e-6, 150e-6),
                        sag_limit=0.2, flattening_limit=0.5, bump_height=0.5e-3)
    d = design_bump_foil(spec, 0.664)
    assert d.success and d.status == "optimal"
    s, l0, t, top = d.pitch, d.half_length, d.thickness, d.top_foil_thickness
    rel = SOLVER_REL
    assert compliance(s, l0, t) == pytest.approx(0.664, rel=1e-3)  # the brief: within 0.1 %
    assert compliance(s, l0, t) == pytest.approx(0.664, rel=rel)   # what it achieves
    assert 2e-3 * (1 - rel) <= s <= 6e-3 * (1 + rel)
    assert 0.5e-3 * (1 - rel) <= l0 <= 3e-3 * (1 + rel)
    assert 50e-6 * (1 - rel) <= t <= 200e-6 * (1 + rel)
    assert 40e-6 * (1 - rel) <= top <= 150e-6 * (1 + rel)
    assert 2 * l0 + GAP <= s * (1 + rel)
    assert stress(s, l0, t) <= 310e6 * (1 + rel)  # Inconel X-750 default allowable
    sag = DP * s**4 * (1 - NU**2) / (32 * E * top**3)
    assert sag <= 0.2 * C * (1 + rel)
    assert DP * s**2 / (2 * top**2) <= 310e6 * (1 + rel)
    deflection = DP * compliance(s, l0, t) * C / PA  # Δp α
    assert deflection <= 0.5 * 0.5e-3
    # the reported numbers are the formulas evaluated on the returned geometry
    assert d.compliance == pytest.approx(compliance(s, l0, t), rel=1e-12)
    assert d.bump_stress == pytest.approx(stress(s, l0, t), rel=1e-12)
    assert d.top_foil_sag == pytest.approx(sag, rel=1e-12)
    assert d.bump_deflection == pytest.approx(deflection, rel=1e-12)
    # whole number of bumps, and the thinnest top foil meeting the sag limit (which binds)
    assert d.number_of_bumps == 20
    assert s == pytest.approx(2 * math.pi * 19.05e-3 / 20, rel=1e-12)
    assert top == pytest.approx((DP * s**4 * (1 - NU**2) / (32 * E * 0.2 * C)) ** (1 / 3),
                                rel=1e-12)
    assert "top-foil sag <= limit" in d.binding_constraints
    assert "no bump flattening" not in d.binding_constraints


# (b) ----------------------------------------------------------------------------------
def test_minimum_stress_matches_the_closed_form_on_the_closing_line():
    # At fixed S, σ_b ∝ s^{1/3}/l0: the longest bump that closes, l0 = (s − gap)/2, and then
    # s^{1/3}/(s − gap) falls with s, so s = s_max: both "pitch <= 6 mm" and the closing bind.
    target = 0.664
    d = design_bump_foil(example_spec(), target)
    assert d.success
    assert d.pitch == pytest.approx(6e-3, rel=SOLVER_REL)
    assert d.half_length == pytest.approx((6e-3 - GAP) / 2, rel=SOLVER_REL)
    assert d.bump_stress == pytest.approx(stress_at_compliance(target, 6e-3, 2.9e-3),
                                          rel=SOLVER_REL)
    assert set(d.binding_constraints) == {"pitch <= 6 mm", "bump closes within pitch"}
    assert d.solves == 5  # 2 + 2 range GPs and the design: catches a silent slowdown
    # the GP's own geometry satisfies the closed form identically
    assert d.bump_stress == pytest.approx(
        stress_at_compliance(d.compliance, d.pitch, d.half_length), rel=1e-12)


def test_minimum_stress_with_the_half_length_capped_moves_the_pitch_to_the_closing_line():
    # l0 ≤ 2 mm: l0 = 2 mm, then σ_b ∝ s^{1/3} wants the least pitch that still closes the
    # bump, s = 2 l0 + gap = 4.2 mm.
    target = 0.3
    d = design_bump_foil(example_spec(half_length_range=(0.5e-3, 2e-3)), target)
    assert d.pitch == pytest.approx(4.2e-3, rel=SOLVER_REL)
    assert d.half_length == pytest.approx(2e-3, rel=SOLVER_REL)
    assert d.bump_stress == pytest.approx(stress_at_compliance(target, 4.2e-3, 2e-3),
                                          rel=SOLVER_REL)
    assert set(d.binding_constraints) == {"half length <= 2 mm", "bump closes within pitch"}


def test_band_target_takes_the_cheaper_end():
    # σ_b ∝ S^{2/3} at the same geometry family: the least stress is at the lower end.
    d = design_bump_foil(example_spec(), (0.5, 0.8))
    assert d.compliance == pytest.approx(0.5, rel=SOLVER_REL)
    assert d.bump_stress == pytest.approx(stress_at_compliance(0.5, 6e-3, 2.9e-3),
                                          rel=SOLVER_REL)
    assert "compliance >= lower target" in d.binding_constraints


def least_pitch_reaching(target, t_min=50e-6):
    """Least pitch at which S = target is reachable: l0 = (s − gap)/2, t = t_min."""
    return brentq(lambda s: compliance(s, (s - GAP) / 2, t_min) - target, 1e-3, 6e-3,
                  xtol=1e-15, rtol=1e-14)


def test_least_pitch_objective_breaks_ties_by_stress():
    target = 0.664
    # without a binding stress limit the least pitch is where the thinnest, longest closing
    # bump just reaches S; at that pitch the geometry is unique
    d = design_bump_foil(example_spec(objective="pitch", allowable_stress=2e9), target)
    s = least_pitch_reaching(target)
    assert d.pitch == pytest.approx(s, rel=SOLVER_REL)
    assert d.half_length == pytest.approx((s - GAP) / 2, rel=1e-5)
    assert d.thickness == pytest.approx(50e-6, rel=1e-5)
    # with the 310 MPa default the stress binds first: the least pitch has
    # σ_b(S, s, (s − gap)/2) = 310 MPa, and among the geometries with that pitch the least
    # stress is the longest closing bump
    d = design_bump_foil(example_spec(objective="pitch"), target)
    s = brentq(lambda p: stress_at_compliance(target, p, (p - GAP) / 2) - 310e6, 1e-3, 6e-3,
               xtol=1e-15, rtol=1e-14)
    assert d.pitch == pytest.approx(s, rel=SOLVER_REL)
    assert d.half_length == pytest.approx((s - GAP) / 2, rel=1e-5)
    assert set(d.binding_constraints) == {"bump closes within pitch",
                                          "bump stress <= allowable"}


def test_compliance_ranges_match_closed_forms():
    spec = example_spec()
    low, high = compliance_range(spec, limits=False)
    # least S: thickest foil, shortest bump, least pitch; greatest: the opposite, closing
    assert low == pytest.approx(compliance(2e-3, 0.5e-3, 200e-6), rel=SOLVER_REL)
    assert high == pytest.approx(compliance(6e-3, 2.9e-3, 50e-6), rel=SOLVER_REL)
    low, high = compliance_range(spec)  # with the 310 MPa stress limit
    # σ_b(S) at s = 6 mm, l0 = 2.9 mm equals the allowable at S_max = (σ l0/(3Δp s^{1/3}))^{3/2}
    # · 2 p_a/(c E')
    s_max = ((310e6 * 2.9e-3 / (3 * DP * 6e-3 ** (1 / 3))) ** 1.5 * 2 * PA / (C * E_PLATE))
    assert high == pytest.approx(s_max, rel=SOLVER_REL)
    assert low == pytest.approx(compliance(2e-3, 0.5e-3, 200e-6), rel=SOLVER_REL)


# (c) ----------------------------------------------------------------------------------
def test_design_notes_example():
    # DESIGN_NOTES: S = 0.664 → s = 6.0 mm, l0 = 2.9 mm, t_b ≈ 181 µm, σ_b ≈ 160 MPa.
    # With p_a = 101325 Pa (the default) the GP gives t_b = 181.4 µm and σ_b = 158.6 MPa;
    # with p_a = 1e5 Pa, 180.6 µm and 160.0 MPa.  S = 0.664 is the Ruscitto geometry at
    # c = 32 µm with p_a = 101325 Pa, whose stress is 236 MPa per bar.
    d = design_bump_foil(example_spec(), 0.664)
    assert d.pitch * 1e3 == pytest.approx(6.0, rel=SOLVER_REL)
    assert d.half_length * 1e3 == pytest.approx(2.9, rel=SOLVER_REL)
    assert d.thickness * 1e6 == pytest.approx(181.44, abs=0.01)
    assert d.bump_stress / 1e6 == pytest.approx(158.56, abs=0.01)
    assert d.bump_stress / 1e6 == pytest.approx(160, rel=0.01)  # "≈ 160 MPa" holds to 1 %
    d1 = design_bump_foil(example_spec(ambient_pressure=1e5), 0.664)
    assert d1.thickness * 1e6 == pytest.approx(180.65, abs=0.01)
    assert d1.bump_stress / 1e6 == pytest.approx(159.96, abs=0.01)
    assert compliance(4.572e-3, 1.778e-3, 101.6e-6) == pytest.approx(0.664, abs=5e-4)
    assert stress(4.572e-3, 1.778e-3, 101.6e-6) / 1e6 == pytest.approx(236.25, abs=0.01)


# (d) ----------------------------------------------------------------------------------
def test_too_low_allowable_stress_is_diagnosed_with_the_amount_to_move():
    d = design_bump_foil(example_spec(allowable_stress=140e6), 0.664)
    assert not d.success and d.status == "infeasible"
    assert math.isnan(d.pitch) and d.binding_constraints == ()
    least = stress_at_compliance(0.664, 6e-3, 2.9e-3)  # 158.56 MPa, the best any geometry does
    (move,) = d.relaxations
    assert move.limit == "allowable stress"
    assert move.required * 1e6 == pytest.approx(least, rel=SOLVER_REL)
    assert move.factor == pytest.approx(least / 140e6, rel=SOLVER_REL)
    assert "allowable stress must rise by 13.3 % (to 158.6 MPa)" in d.message
    # and the range that the present limits allow is reported (at S_max = 0.551 the foil is
    # 193 µm thick, inside its range, so the closed form of test_compliance_ranges holds)
    assert d.compliance_range[1] == pytest.approx(
        (140e6 * 2.9e-3 / (3 * DP * 6e-3 ** (1 / 3))) ** 1.5 * 2 * PA / (C * E_PLATE),
        rel=SOLVER_REL)


def test_too_tight_sag_limit_is_diagnosed_with_the_amount_to_move():
    # With a generous stress limit only the sag binds: the least sag is the thickest top foil
    # at the least pitch that still reaches S (thinnest, longest closing bump).
    target, kappa = 0.664, 0.002  # sag <= 64 nm; the least possible is 126 nm
    spec = example_spec(allowable_stress=2e9, top_foil_thickness_range=(40e-6, 150e-6),
                        sag_limit=kappa)
    d = design_bump_foil(spec, target)
    assert not d.success
    s = least_pitch_reaching(target)
    least_sag = DP * s**4 * (1 - NU**2) / (32 * E * 150e-6**3)
    (move,) = d.relaxations
    assert move.limit == "top-foil sag limit κ_c"
    assert move.required == pytest.approx(least_sag / C, rel=1e-5)
    assert move.factor == pytest.approx(least_sag / (kappa * C), rel=1e-5)
    assert re.search(r"top-foil sag limit κ_c must rise by [\d.]+ % \(to 0\.\d+\)", d.message)


# (e) ----------------------------------------------------------------------------------
@pytest.mark.parametrize("changes, message", [
    ({"radial_clearance": -1e-6}, "radial_clearance = -1e-06: must be finite and > 0"),
    ({"pitch_range": (6e-3, 2e-3)}, "pitch_range = (0.006, 0.002): low must be < high"),
    ({"thickness_range": (50e-6,)}, "thickness_range = (5e-05,): must be a pair (low, high)"),
    ({"half_length_range": (3e-3, 4e-3)},
     "2 x shortest half length + gap = 6.2 mm exceeds the largest pitch 6 mm: no bump closes"),
    ({"material": "steel"},
     "material = 'steel': unknown material; known: inconel-x750, inconel-x750-538c"),
    ({"sag_limit": 0.1}, "sag_limit = 0.1: needs top_foil_thickness_range"),
    ({"objective": "mass"}, "objective = 'mass': must be one of stress, pitch"),
    ({"poisson_ratio": 0.6}, "poisson_ratio = 0.6: must lie in (-1, 0.5)"),
    ({"flattening_limit": 0.5}, "flattening_limit = 0.5: needs bump_height too"),
    ({"gap": -1e-4}, "gap = -0.0001: must be finite and >= 0"),
    ({"radius": 1.114e-3, "pitch_range": (4e-3, 6e-3)},
     "radius = 0.001114: no whole number of bumps N gives a pitch 2πR/N within [4 mm, 6 mm]"),
])
def test_bad_specification_raises_a_one_line_parameter_error(changes, message):
    with pytest.raises(ParameterError, match=re.escape(message)):
        example_spec(**changes)


@pytest.mark.parametrize("target, message", [
    (50.0, ("target compliance S = 50.0: outside the achievable range [0.000847, 31.73] "
            "under these limits (pitch, half-length and thickness ranges")),
    (-1.0, "target compliance S = -1.0: must be finite and > 0"),
    ((0.8, 0.5), "target compliance band = (0.8, 0.5): low must be < high"),
    ((40.0, 50.0), "target compliance band = (40.0, 50.0): outside the achievable range"),
])
def test_bad_target_raises_a_one_line_parameter_error(target, message):
    with pytest.raises(ParameterError, match=re.escape(message)):
        design_bump_foil(example_spec(), target)


# (f) ----------------------------------------------------------------------------------
def test_whole_number_of_bumps_fixes_the_pitch_and_re_solves():
    # l0 ≤ 2.5 mm, s ≤ 7 mm: the continuous optimum is s = 2·2.5 + 0.2 = 5.2 mm, i.e.
    # N = 2π·19.05/5.2 = 23.02 bumps.  N = 23 (s = 5.204 mm, l0 = 2.5 mm, the closing slack)
    # beats N = 24 (s = 4.987 mm, l0 = (s − gap)/2): σ_b ∝ s^{1/3}/l0.
    radius, target = 19.05e-3, 0.5
    spec = example_spec(radius=radius, pitch_range=(2e-3, 7e-3),
                        half_length_range=(0.5e-3, 2.5e-3))
    d = design_bump_foil(spec, target)
    assert d.success and isinstance(d.number_of_bumps, int) and d.number_of_bumps == 23
    assert d.pitch == pytest.approx(2 * math.pi * radius / 23, rel=1e-12)
    assert d.half_length == pytest.approx(2.5e-3, rel=SOLVER_REL)
    assert d.bump_stress == pytest.approx(stress_at_compliance(target, d.pitch, 2.5e-3),
                                          rel=SOLVER_REL)
    s24 = 2 * math.pi * radius / 24
    assert d.bump_stress < stress_at_compliance(target, s24, (s24 - GAP) / 2)
    assert compliance(d.pitch, d.half_length, d.thickness) == pytest.approx(target, rel=1e-6)
    assert "N = 23 bumps" in d.message and d.solves == 7  # 4 range GPs, 1 + 2 designs
