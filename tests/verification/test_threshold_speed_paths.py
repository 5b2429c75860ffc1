"""The fast threshold search (Krylov model on one LU, crossings checked on the exact impedance)
against the exhaustive reference scan (one LU per impedance evaluation).

gfbopt/linear/threshold.py: both methods scan the same whirl ratios, follow the same branches
and refine the same brackets; the fast one must give the same critical mass and whirl ratio
(≤ 1e-9 relative here; 1e-12 typical) on every kind of case — rigid, simple, local and beam
foils, periodic and seam films, structural damping, several crossing branches (the least
stable must win), unstable for every mass (M̄c = 0) and stable for every mass — with 2–4
factorisations instead of ~32, and must fall back to direct solves wherever its Krylov model
is not trusted.
"""
import math

import numpy as np
import pytest

from gfbopt import BearingModel, Grid, ParameterError, solve_static
from gfbopt.linear import impedance, linear_threshold, linearise, semi_discrete_eigenvalues
from gfbopt.linear import crossings
from gfbopt.linear.crossings import Cost, krylov_crossings, mass_roots, scan_crossings
from gfbopt.linear.krylov import ShiftedImpedance
from gfbopt.linear.threshold import _bordered_eigenvalues

GRID = Grid(36, 10)
REL = 1e-9

#: name -> (eccentricity, or ("load", W̄0), model)
CASES = {
    "rigid": (0.4, BearingModel(bearing_number=2.0, foil="rigid")),
    "simple": (0.4, BearingModel(bearing_number=2.0, compliance=1.0)),
    "local": (0.4, BearingModel(bearing_number=2.0, compliance=1.0, deflection_law="local")),
    "beam_seam_200": (0.4, BearingModel(bearing_number=5.0, compliance=1.0, foil="beam",
                                        film="seam", top_foil_coefficient=1.0,
                                        seam_angle_deg=200)),
    "beam_seam_max_film": (0.3, BearingModel(bearing_number=5.0, compliance=1.0, foil="beam",
                                             film="seam", top_foil_coefficient=1.0)),
    "simple_eta": (0.4, BearingModel(bearing_number=2.0, compliance=1.0, loss_factor=0.3)),
    "local_eta_co_seam": (0.4, BearingModel(bearing_number=2.0, compliance=1.0,
                                            deflection_law="local", compression_only=True,
                                            film="seam", seam_angle_deg=180.0,
                                            loss_factor=0.3)),
    # two crossings, the larger on a low-whirl branch (γ ≈ 0.14)
    "low_whirl_branch": (0.8, BearingModel(bearing_number=10.0, foil="rigid",
                                           length_ratio=0.5)),
    # seven crossings on several branches; the least stable is at γ ≈ 1.08
    "seven_crossings": (0.8, BearingModel(bearing_number=40.0, foil="rigid", film="seam",
                                          length_ratio=1.5, seam_angle_deg=90)),
    # welded end inside the loaded arc: the massless journal is unstable, M̄c = 0
    "unstable_every_mass": (("load", 0.55), BearingModel(
        bearing_number=3.4, compliance=1.05, film="seam", seam_angle_deg=90)),
    # three crossings and still unstable for every mass
    "unstable_with_crossings": (0.8, BearingModel(bearing_number=40.0, foil="rigid",
                                                  length_ratio=0.5)),
    # a jump of the branch function taken for a crossing (below), and unstable anyway
    "unstable_branch_jump": (0.5, BearingModel(bearing_number=10.0, compliance=5.0,
                                               length_ratio=1.5)),
    # no crossing on (0.02, 1.2), and stable: M̄c = ∞
    "stable_every_mass": (0.9, BearingModel(bearing_number=1.0, foil="rigid")),
}


def _lin(name, grid=GRID):
    where, model = CASES[name]
    if isinstance(where, tuple):
        sol = solve_static(model, load=where[1], grid=grid)
    else:
        sol = solve_static(model, eccentricity=where, grid=grid)
    assert sol.success
    return linearise(sol)


def _same(a, b):
    """Critical masses or whirl ratios equal to REL (relative), inf/nan/0 alike."""
    if not (math.isfinite(a) and a != 0):
        return (a == b) or (math.isnan(a) and math.isnan(b))
    return abs(a - b) <= REL * abs(a)


@pytest.fixture(scope="module", params=list(CASES))
def pair(request):
    lin = _lin(request.param)
    return request.param, lin, linear_threshold(lin, method="scan"), linear_threshold(lin)


def test_fast_path_equals_the_reference_scan(pair):
    name, _, ref, fast = pair
    assert (ref.method, fast.method) == ("scan", "krylov")
    assert _same(ref.critical_mass, fast.critical_mass), (name, ref, fast)
    assert _same(ref.whirl_ratio, fast.whirl_ratio), (name, ref, fast)
    assert ref.stable_for_all_masses == fast.stable_for_all_masses
    assert (ref.message == "") == (fast.message == "")
    assert np.sign(ref.probe_growth_rate) == np.sign(fast.probe_growth_rate)
    assert ref.probe_growth_rate == pytest.approx(fast.probe_growth_rate, rel=1e-8, abs=1e-12)
    # the fast path: one LU for the Krylov model, one for the check (reused by the probe;
    # three at a jump of the branch function), or the probe's own when nothing crosses; the
    # reference: one per evaluation
    assert fast.factorisations <= 4 and ref.factorisations >= 25
    assert ref.factorisations == ref.evaluations + 1


def test_kinds_of_answer_are_covered(pair):
    """The case list really holds the special answers it is meant to."""
    name, lin, ref, _ = pair
    if name.startswith("unstable"):
        assert ref.critical_mass == 0.0 and ref.probe_growth_rate > 0
    elif name == "stable_every_mass":
        assert ref.stable_for_all_masses and math.isinf(ref.critical_mass)
    else:
        assert 0 < ref.critical_mass < math.inf


@pytest.mark.parametrize("name, count, whirl", [("low_whirl_branch", 2, (0.05, 0.3)),
                                                ("seven_crossings", 7, (1.0, 1.2))])
def test_least_stable_crossing_wins_among_several_branches(name, count, whirl):
    """Every crossing of the reference, and the threshold is the smallest of them (on the
    γ ≈ 1.08 branch for seven_crossings, not the half-frequency one)."""
    lin = _lin(name)
    found = scan_crossings(lin, np.linspace(0.02, 1.2, 24), Cost())
    assert len(found) == count
    assert any(whirl[0] < c.whirl < whirl[1] for c in found)
    best = min(found, key=lambda c: c.mass)
    fast = linear_threshold(lin)
    assert _same(best.mass, fast.critical_mass) and _same(best.whirl, fast.whirl_ratio)
    if name == "seven_crossings":
        assert 1.0 < fast.whirl_ratio < 1.2


def test_a_jump_of_the_branch_function_is_reported_as_the_reference_reports_it():
    """Λ = 10, S = 5, L/D = 1.5, periodic film: near γ = 0.47 the two roots swap places as the
    one nearer the branch's value, Im u of the followed root jumps from −0.73 to +0.048, and
    Brent's method reports the jump as a crossing (M̄ = 9.08) although no root is real there.
    The fast search reports the same point (its exact sign test) with 3 LUs for the check,
    where Brent's method on the exact impedance bisects the jump with ~45."""
    lin = _lin("unstable_branch_jump")
    gammas = np.linspace(0.02, 1.2, 24)
    ref = scan_crossings(lin, gammas, Cost())
    cost = Cost()
    fast = krylov_crossings(lin, gammas, cost)
    assert len(ref) == len(fast) == 1
    assert fast[0].mass == pytest.approx(ref[0].mass, rel=1e-8)
    assert fast[0].whirl == pytest.approx(ref[0].whirl, abs=3e-10)
    assert np.abs(mass_roots(impedance(lin, 1j * fast[0].whirl)).imag).min() > 0.01
    assert cost.factorisations == 4


def test_narrow_whirl_window_as_in_the_onset_search():
    """The onset search refines with 8 whirl ratios in ±0.1 around the threshold."""
    lin = _lin("simple")
    options = {"whirl_range": (0.38, 0.6), "samples": 8}
    ref = linear_threshold(lin, method="scan", **options)
    fast = linear_threshold(lin, **options)
    assert _same(ref.critical_mass, fast.critical_mass)
    assert _same(ref.whirl_ratio, fast.whirl_ratio)


@pytest.mark.parametrize("name", ["simple_eta", "beam_seam_200"])
def test_krylov_model_equals_direct_impedance(name):
    """Z(iγ) from the Krylov space equals the direct solve to 1e-10 at every scan point once
    converged (with η > 0 the forward-whirl foundation k(1 + iη) is used)."""
    lin = _lin(name)
    gammas = np.linspace(0.02, 1.2, 24)
    model = ShiftedImpedance(lin, (0.02, 1.2))
    assert model.converge(gammas).all() and model.blocks < 30
    for g in gammas:
        z, residual = model.evaluate(g)
        exact = impedance(lin, 1j * g)
        assert residual <= 1e-11
        np.testing.assert_allclose(z, exact, rtol=0, atol=1e-10 * np.abs(exact).max())


def test_unconverged_krylov_points_are_solved_directly(monkeypatch):
    """With the Krylov space capped at 18 block steps (26 needed here) only the middle half of
    the scan converges: the other scan points are solved directly, their brackets refined on
    the exact impedance, and the answer is the reference's."""
    lin = _lin("seven_crossings")
    ref = linear_threshold(lin, method="scan")

    class Capped(ShiftedImpedance):
        def __init__(self, lin, whirl_range):
            super().__init__(lin, whirl_range, max_blocks=18)

    monkeypatch.setattr(crossings, "ShiftedImpedance", Capped)
    fast = linear_threshold(lin)
    assert 12 < fast.factorisations < ref.factorisations - 12
    assert _same(ref.critical_mass, fast.critical_mass)
    assert _same(ref.whirl_ratio, fast.whirl_ratio)


def test_singular_shift_falls_back_to_the_reference(monkeypatch):
    lin = _lin("simple")
    ref = linear_threshold(lin, method="scan")

    def singular(*args, **kwargs):
        raise RuntimeError("Factor is exactly singular")

    monkeypatch.setattr(crossings, "ShiftedImpedance", singular)
    fast = linear_threshold(lin)
    assert fast.factorisations == ref.factorisations - 1       # the probe reuses an LU
    assert _same(ref.critical_mass, fast.critical_mass)
    assert _same(ref.whirl_ratio, fast.whirl_ratio)


@pytest.mark.parametrize("error", [1e-7, 1e-2])
def test_an_inaccurate_model_is_caught_by_the_exact_check(monkeypatch, error):
    """A Krylov model whose Z is off by a phase ``error`` (its residual still says converged)
    moves the crossing: the exact check rejects it, and Newton steps or Brent's method on the
    exact impedance give the reference answer."""
    lin = _lin("simple")
    ref = linear_threshold(lin, method="scan")
    evaluate = ShiftedImpedance.evaluate

    def wrong(self, gamma, blocks=None):
        z, residual = evaluate(self, gamma, blocks)
        return z * (1 + 1j * error), residual

    monkeypatch.setattr(ShiftedImpedance, "evaluate", wrong)
    fast = linear_threshold(lin)
    assert fast.factorisations > 2
    assert _same(ref.critical_mass, fast.critical_mass)
    assert _same(ref.whirl_ratio, fast.whirl_ratio)


@pytest.mark.parametrize("name", ["simple", "simple_eta"])
def test_bordered_eigenvalues_equal_the_semi_discrete_ones(name):
    """The probe's shift-invert operator by block elimination of the rotor (one LU of
    A + iγB) gives the eigenvalues of the bordered descriptor system (its own LU)."""
    lin = _lin(name)
    gamma, mass = 0.48, 1.5
    direct = crossings.DirectImpedance(lin, Cost())
    ours = _bordered_eigenvalues(lin, mass, 1j * gamma, *direct.factorise(gamma), count=6)
    theirs = semi_discrete_eigenvalues(lin, mass, 1j * gamma, count=6)
    def nearest(ev):                    # forward whirl, as the probe (and with η > 0 the
        ev = ev[ev.imag > 0.02]         # foundation of Im s > 0 only)
        return ev[np.argsort(np.abs(ev - 1j * gamma))][:2]

    np.testing.assert_allclose(nearest(ours), nearest(theirs), rtol=0, atol=1e-9)


def test_bad_threshold_input():
    lin = _lin("rigid")
    with pytest.raises(ParameterError, match=r"^whirl_range = \(0.0, 1.0\): must be finite "
                                             r"with 0 < low < high$"):
        linear_threshold(lin, whirl_range=(0.0, 1.0))
    with pytest.raises(ParameterError, match=r"^whirl_range = \(0.6, 0.3\)"):
        linear_threshold(lin, whirl_range=(0.6, 0.3))
    with pytest.raises(ParameterError, match=r"^whirl_range = 'ab': must be two whirl ratios"):
        linear_threshold(lin, whirl_range="ab")
    with pytest.raises(ParameterError, match=r"^samples = 1: must be an integer >= 2$"):
        linear_threshold(lin, samples=1)
    with pytest.raises(ParameterError, match=r"^samples = 2.5"):
        linear_threshold(lin, samples=2.5)
    with pytest.raises(ParameterError, match=r"^method = 'fast': must be one of: krylov, scan"):
        linear_threshold(lin, method="fast")
