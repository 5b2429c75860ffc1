"""The bearing as built: bore profile, pads, bump zones and the drag torque.

Exact checks:
* a zero preload, one pad at the present seam and uniform zones are today's bearing: the same
  numbers to round-off (the golden outputs of tests/regression pin today's bearing itself);
* concentric round bore: torque = Petroff's exactly (P ≡ 1, H ≡ 1 on any grid: the quadrature
  of 1/H is exact, so the "grid error" is round-off, order ∞); near-concentric the ratio is
  1 + O(ε²);
* rigid bore at ε = 0.5: the Couette part equals 1/√(1 − ε²) to the periodic trapezoid rule's
  geometric convergence (ρ^−N, ρ = (1 + √(1 − ε²))/ε = 3.73: below 1e-12 at N = 36), and the
  total converges at second order under refinement (the pressure part is a midpoint rule on
  second-order pressures);
* a rigid three-lobe bearing: gfbopt's film force at a fixed journal position equals an
  independent sparse-Newton solve of the same discrete equations, and its grid error is
  second order (Richardson on three grids);
* a preloaded bearing's linear threshold equals its nonlinear (transient) critical mass.
"""
import math

import numpy as np
import pytest
import scipy.sparse.linalg as spla

from gfbopt import BearingModel, Grid, solve_static
from gfbopt import discretisation as disc
from gfbopt.analyses import critical_mass_point
from gfbopt.inputs.bore import AsBuilt, BoreProfile, Pad, Zone
from gfbopt.linear import linear_threshold, linearise
from gfbopt.static import SolverCache, solver_key

import newton_reference as ref   # tests/verification on sys.path

GRID = Grid(36, 10)
SEAM = math.pi
THREE_SHIMS = BoreProfile("shims", 3, 0.25, math.radians(60.0))


def _base(**kw):
    return BearingModel(**{**dict(bearing_number=2.0, compliance=1.0, film="seam",
                                  seam_angle_deg=math.degrees(SEAM)), **kw})


@pytest.mark.parametrize("kw", [dict(), dict(deflection_law="local"),
                                dict(foil="beam", top_foil_coefficient=1.0),
                                dict(film="periodic", seam_angle_deg=None),
                                dict(compression_only=True, subambient="gumbel")])
def test_trivial_as_built_is_todays_bearing(kw):
    """Zero preload (shims and lobes), one pad spanning the bore at the seam and uniform
    zones give today's numbers: the same build (solver key) and the load, attitude, torque and
    linear threshold to 1e-12 (IPOPT from identical starts; only the parameter layout
    differs)."""
    today = _base(**kw)
    zones = (Zone(0.0, 2.0, 1.0), Zone(2.0, 2 * math.pi, 1.0))
    pads = (Pad(SEAM, 2 * math.pi),) if today.film == "seam" else ()
    variants = [AsBuilt(BoreProfile("shims", 3, 0.0, 1.0)), AsBuilt(BoreProfile("lobes", 3)),
                AsBuilt(zones=zones), AsBuilt(pads=pads)]
    cache = SolverCache(GRID)
    ref_sol = solve_static(today, eccentricity=0.5, solver=cache(today))
    for built in variants:
        model = today.replace(as_built=built)
        assert solver_key(model, GRID) == solver_key(today, GRID)
        sol = solve_static(model, eccentricity=0.5, solver=cache(model))
        for key in ("load", "attitude_angle_deg", "torque_ratio", "min_film"):
            assert getattr(sol, key) == pytest.approx(getattr(ref_sol, key), rel=1e-12), key
    # the dynamics too (one variant: the linear model is the static Jacobian's)
    ref_thr = linear_threshold(linearise(ref_sol, cache(today)), samples=8)
    thr = linear_threshold(linearise(sol, cache(model)), samples=8)
    assert thr.critical_mass == pytest.approx(ref_thr.critical_mass, rel=1e-10)


def test_concentric_round_bore_torque_is_petroff():
    """ε = 0: exactly Petroff (H ≡ 1, no pressure); ε = 0.01: 1 + O(ε²) — the Couette part
    1/√(1 − ε²) ≈ 1 + 5e-5, the pressure part O(ε²) too (≤ 1e-3 allows either)."""
    model = BearingModel(bearing_number=2.0, foil="rigid")
    sol = solve_static(model, eccentricity=0.0, grid=GRID)
    assert sol.torque_ratio == pytest.approx(1.0, abs=1e-14)
    near = [solve_static(model, eccentricity=e, grid=GRID).torque_ratio - 1 for e in (0.01, 0.02)]
    assert abs(near[0]) < 1e-3
    assert near[1] / near[0] == pytest.approx(4.0, rel=0.02)        # quadratic in ε


def test_couette_part_closed_form_and_total_converges():
    """Rigid, periodic, ε = 0.5: Couette part 1/√(1 − ε²) to 1e-12 on every grid (periodic
    trapezoid rule, geometric convergence); the total torque converges at order 2 ± 0.3."""
    model = BearingModel(bearing_number=2.0, foil="rigid")
    exact = 1.0 / math.sqrt(1.0 - 0.25)
    totals = []
    for grid in (Grid(24, 8), Grid(48, 16), Grid(96, 32)):
        sol = solve_static(model, eccentricity=0.5, grid=grid)
        assert sol.couette_torque_ratio == pytest.approx(exact, rel=1e-12)
        totals.append(sol.torque_ratio)
    order = math.log2((totals[1] - totals[0]) / (totals[2] - totals[1]))
    assert order == pytest.approx(2.0, abs=0.3)
    assert totals[2] > exact            # the pressure-gradient part adds drag here


def test_three_lobe_force_matches_independent_newton_and_is_second_order():
    """Rigid three-lobe bore (preload 0.3), periodic film, journal fixed at (X, Y) =
    (0.3, 0.1): gfbopt's film force equals a hand-written sparse Newton on the same grid
    (1e-9: both converge the residual to ≤ 1e-10), and the load converges at order 2 ± 0.3
    on 24 × 8, 48 × 16, 96 × 32; the coarse grid is within its Richardson error estimate
    (×1.5) of the extrapolated value."""
    lobes = AsBuilt(BoreProfile("lobes", 3, 0.3, offset=math.radians(20.0)))
    model = BearingModel(bearing_number=3.0, foil="rigid", as_built=lobes)
    ecc, phi = math.hypot(0.3, 0.1), math.atan2(0.1, 0.3)
    # independent check on one grid
    st = disc.make_stencil(GRID, periodic=True)
    dz = st.axial_spacing(1.0)
    theta = st.psi                          # periodic film with a bore: origin on the load line
    h = np.repeat(1.0 + lobes.bore_rows(theta) - 0.3 * np.cos(theta) - 0.1 * np.sin(theta),
                  st.n_z_nodes)
    p = np.ones(st.n_unknown)
    for _ in range(30):
        r = ref.residual(p, h, st, 3.0, dz)
        if np.abs(r).max() < 1e-11:
            break
        p = p + spla.splu(ref.jacobian(p, h, st, 3.0, dz)).solve(-r)
    fx, fy = ref.forces(p, st, dz)
    sol = solve_static(model, eccentricity=ecc, attitude_angle_deg=math.degrees(phi), grid=GRID)
    assert sol.success
    assert sol.force[0] == pytest.approx(fx, rel=1e-9)
    assert sol.force[1] == pytest.approx(fy, rel=1e-9)
    # grid convergence of the load
    loads = [solve_static(model, eccentricity=ecc, attitude_angle_deg=math.degrees(phi),
                          grid=g).force[0]
             for g in (Grid(24, 8), Grid(48, 16), Grid(96, 32))]
    order = math.log2((loads[1] - loads[0]) / (loads[2] - loads[1]))
    assert order == pytest.approx(2.0, abs=0.3)
    extrapolated = loads[2] + (loads[2] - loads[1]) / 3.0
    estimate = abs(loads[0] - loads[1]) * 4.0 / 3.0
    assert abs(loads[0] - extrapolated) <= 1.5 * estimate


def test_preload_and_zones_change_no_build():
    """A new preload value or zone change is a parameter of the build: one solver serves all
    (the cache holds one build), and the answers differ (the parameters act)."""
    cache = SolverCache(GRID)
    loads = []
    for built in (AsBuilt(THREE_SHIMS), AsBuilt(BoreProfile("shims", 3, 0.1, 1.0)),
                  AsBuilt(BoreProfile("lobes", 4, 0.2)),
                  AsBuilt(zones=(Zone(0, math.pi, 0.5), Zone(math.pi, 2 * math.pi, 1.5)))):
        model = _base(as_built=built)
        loads.append(solve_static(model, eccentricity=0.5, solver=cache(model)).load)
    assert len(cache) == 1
    assert len({round(v, 6) for v in loads}) == len(loads)


def test_zones_reach_the_film():
    """A softer half where the film is thin: at the same load the journal sits further out
    (ε grows) than with the uniform mean S, and the uniform bearing is bracketed by the all-
    soft and all-stiff ones."""
    load = 0.6
    eps = {}
    for name, zones in (("soft_loaded", (Zone(-math.pi / 2, math.pi / 2, 1.5),
                                         Zone(math.pi / 2, 3 * math.pi / 2, 0.5))),
                        ("stiff_loaded", (Zone(-math.pi / 2, math.pi / 2, 0.5),
                                          Zone(math.pi / 2, 3 * math.pi / 2, 1.5)))):
        sol = solve_static(_base(as_built=AsBuilt(zones=zones)), load=load, grid=GRID)
        assert sol.success
        eps[name] = sol.eccentricity
    uniform = solve_static(_base(), load=load, grid=GRID).eccentricity
    assert eps["stiff_loaded"] < uniform < eps["soft_loaded"]


def test_pads_hold_ambient_at_each_seam():
    """Three pads: P = 1 on each pad's leading-end row, and the load falls against one pad at
    the same ε (the film is broken twice more)."""
    pads = tuple(Pad(SEAM + k * 2 * math.pi / 3, 2 * math.pi / 3) for k in range(3))
    model = _base(as_built=AsBuilt(pads=pads))
    sol = solve_static(model, eccentricity=0.5, grid=GRID)
    assert sol.success
    for k in range(3):
        row = k * GRID.n_theta // 3
        np.testing.assert_array_equal(sol.pressure[row], 1.0)
    assert sol.load < solve_static(_base(), eccentricity=0.5, grid=GRID).load


def test_preloaded_linear_threshold_equals_nonlinear_critical_mass():
    """Three shims (preload 0.25 c), simple foundation, seam 180° from the load: the transient
    (RKC, from the linear mode) critical mass equals the linear one to ≤ 1 % (the search's
    bracket is ±0.5 %; docs/PHYSICS.md §8 measured ~1e-4 for round bores)."""
    model = _base(as_built=AsBuilt(THREE_SHIMS))
    row = critical_mass_point(model, load=0.5, grid=GRID, tolerance=0.005)
    assert row["success"], row["message"]
    assert row["nonlinear_over_linear"] == pytest.approx(1.0, abs=0.01)


def test_first_order_bore_pressure_is_ausmans_for_a_cosine_bore():
    """A bore B = ε cos θ is the eccentricity's own film: the first-order bore pressure (the
    cold start of a preloaded bearing) equals Ausman's to round-off, on a periodic and on a
    seamed grid (which repeats its first row)."""
    from gfbopt.physics.bore import first_order_bore_pressure
    from gfbopt.physics.closed_forms import first_order_pressure

    z = np.linspace(-1.0, 1.0, 11)
    theta = 2 * math.pi * np.arange(36) / 36
    ausman = first_order_pressure(BearingModel(bearing_number=2.0), z, theta, 0.01) - 1.0
    ours = first_order_bore_pressure(0.01 * np.cos(theta), z, 2.0, 1.0, periodic=True)
    np.testing.assert_allclose(ours, ausman, atol=1e-15)
    seamed = first_order_bore_pressure(np.append(0.01 * np.cos(theta), 0.01), z, 2.0, 1.0,
                                       periodic=False)
    np.testing.assert_allclose(seamed[:-1], ausman, atol=1e-15)


@pytest.mark.parametrize("built", [
    AsBuilt(THREE_SHIMS),
    AsBuilt(pads=tuple(Pad(SEAM + k * 2 * math.pi / 3, 2 * math.pi / 3) for k in range(3))),
    AsBuilt(BoreProfile("lobes", 3, 0.2), zones=(Zone(0, math.pi, 0.5),
                                                 Zone(math.pi, 2 * math.pi, 1.5)))])
@pytest.mark.parametrize("law", [dict(), dict(deflection_law="local"),
                                 dict(loss_factor=0.3)])
def test_as_built_equilibrium_is_a_transient_fixed_point(built, law):
    """The transient engine sees the same film as the static model: at the equilibrium the
    right-hand side vanishes (film 1e-10: IPOPT's residual tolerance scaled by 1/(2Λ); journal
    to round-off), with the Kelvin–Voigt foil state at rest too when η > 0."""
    from gfbopt.transient import transient_model
    from gfbopt.transient.system import RightHandSide, equilibrium_state

    sol = solve_static(_base(as_built=built, **law), load=0.5, grid=GRID)
    assert sol.success
    tm = transient_model(sol)
    rate = RightHandSide(tm, np.array([1.0]))(equilibrium_state(tm, 1))
    assert np.abs(rate.phi).max() < 1e-10
    assert abs(rate.u[0]) < 1e-13 and abs(rate.v[0]) < 1e-13
    if rate.w is not None:
        assert np.abs(rate.w).max() < 1e-12


def test_zones_damped_local_law_nonlinear_equals_linear():
    """Bump zones under the local law with a loss factor η = 0.3: the transient (Kelvin–Voigt
    state, τ_f = η/ν_ref) critical mass equals the linear hysteretic one to ≤ 1 %
    (docs/PHYSICS.md §7: they share the impedance at the threshold whirl)."""
    zones = (Zone(-math.pi / 2, math.pi / 2, 0.7), Zone(math.pi / 2, 3 * math.pi / 2, 1.3))
    model = _base(as_built=AsBuilt(zones=zones), deflection_law="local", loss_factor=0.3)
    row = critical_mass_point(model, load=0.5, grid=GRID, tolerance=0.005)
    assert row["success"], row["message"]
    assert row["nonlinear_over_linear"] == pytest.approx(1.0, abs=0.01)


def test_python_api_in_degrees():
    """The public constructor takes degrees (as files and the command line do) and gives the
    same bearing as the radian internals; a depth without a clearance is refused."""
    from gfbopt.errors import ParameterError
    from gfbopt.inputs.bore_si import BoreSpec, PadSpec, as_built

    built = as_built(BoreSpec("shims", 3, preload_ratio=0.25, width_deg=60.0),
                     pads=[PadSpec(180.0, 120.0), PadSpec(300.0, 120.0), PadSpec(60.0, 120.0)],
                     zones=[(0.0, 180.0, 0.5), (180.0, 360.0, 1.5)])
    assert built.bore == THREE_SHIMS
    assert built.describe()["pads_leading_end_deg"] == [60.0, 180.0, 300.0]
    with pytest.raises(ParameterError, match="preload_ratio"):
        as_built(BoreSpec("lobes", 3, preload_depth=5e-6))
