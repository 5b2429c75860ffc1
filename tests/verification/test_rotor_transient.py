"""The rotor transient (gfbopt.transient.rotor_*) against the one-bearing engine and the
linear analysis.

* Symmetric rotor (CG midway, I_p = 0), cylindrical motion: both journals see the same film
  and the tilt stays exactly zero, so the rotor transient is the one-bearing engine with half
  the mass and half the load — operation for operation but for the order of the rotor
  sums; the orbits agree to round-off (1e-12 of the clearance; measured ≲ 1e-15).
* Just above / below each mode's linear threshold the growth rate and whirl of the
  transient are the linear characteristic root's (gfbopt.linear).
* Small imbalance below the onset: the settled 1× response at both bearings is the rotor
  issue's linear synchronous response (gfbopt.rotor.diagrams).
* A supercritical limit cycle grows as the square root of the distance past the onset
  (slow tier).
"""
import math

import numpy as np
import pytest

from gfbopt.inputs import Grid, load_bearing
from gfbopt.linear import characteristic_root, linear_threshold, linearise
from gfbopt.rotor.rigid import station_matrix
from gfbopt.static import SolverCache
from gfbopt.transient import fit_growth_rate, integrate_orbits
from gfbopt.transient.rotor_run import integrate_rotor
from gfbopt.transient.rotor_setup import (RotorBearing, RotorInput, build_model,
                                          equilibrium_states, set_station_velocities, static_force_of)
from gfbopt.transient.rotor_system import rigid_rotor_matrices, runs
from gfbopt.transient.spectra import synchronous_fit

BEARING = load_bearing("problems/bearings/ruscitto.toml")
OPTIONS = {"film": "seam", "seam_angle_deg": 180.0}
GRID = Grid.parse("36x10")
G = 9.80665


def symmetric_rotor(mass=3.2, inertia=0.012, polar=0.0, half_span=0.05, imbalance=(),
                    loss_factor=0.0):
    m, g = rigid_rotor_matrices(mass, inertia, polar)
    options = {**OPTIONS, "loss_factor": loss_factor}
    bearings = (RotorBearing(BEARING, -half_span, options, "A"),
                RotorBearing(BEARING, half_span, options, "B"))
    return RotorInput(m, g, bearings, static_force_of([(mass * G, 0.0, 0.0)]), imbalance)


@pytest.fixture(scope="module")
def cache():
    return SolverCache(GRID)


@pytest.mark.parametrize("method, loss_factor", [
    ("rkc", 0.0), pytest.param("rk4", 0.0, marks=pytest.mark.slow),
    pytest.param("rkc", 0.2, marks=pytest.mark.slow)])
def test_symmetric_rotor_is_the_one_bearing_engine_in_cylindrical_whirl(method, loss_factor,
                                                                       cache):
    """Also with a loss factor: both films then carry their Kelvin–Voigt foil states, the
    same states as the one-bearing engine's (its ν_ref, the bearing's threshold whirl)."""
    speed = 30_000.0
    rotor = symmetric_rotor(loss_factor=loss_factor)
    model, sols = build_model(rotor, speed, GRID, cache=cache)
    tm = model.bearings[0].tm
    assert (tm.foil_state is not None) == (loss_factor > 0)
    assert sols[0].load == sols[1].load
    omega = speed * math.pi / 30
    mbar = (3.2 / 2) * BEARING.radial_clearance * omega ** 2 / (3.2 * G / 2)
    step = {"rkc": {"time_step": 0.1, "stages": 6}, "rk4": {"time_step": 0.01}}[method]
    revs = 4.0 if method == "rkc" else 1.5
    one = integrate_orbits(tm, [mbar], revs, kick=1e-3, method=method, **step)
    z = equilibrium_states(model, 1)
    v = 1e-3 / math.sqrt(2)
    z = set_station_velocities(model, z, [[v, v], [v, v]])
    run = integrate_rotor(model, runs(1), 2 * math.pi * revs, z, method=method, **step)
    assert run.success and one.success
    assert run.tau.shape == one.tau.shape
    np.testing.assert_array_equal(run.tau, one.tau)
    c = BEARING.radial_clearance
    for k in range(2):
        x, y = run.journal(0, k)
        # round-off: the rotor's sums (2 p_a R² F + m g)/(m c ω²) against the one-bearing
        # (F + W̄0)/(M̄ W̄0) differ in the last bits only; 1e-12 c leaves 1000× margin
        assert np.max(np.abs(x / c - one.x[0])) < 1e-12
        assert np.max(np.abs(y / c - one.y[0])) < 1e-12
    # the tilt stays at round-off (the equilibrium's 4 × 4 solve leaves ~1e-22 rad)
    assert np.max(np.abs(run.q[0, :, 2:])) * 0.05 / c < 1e-13
    assert np.max(np.abs(one.x[0] - one.x[0, 0])) > 1e-4   # and the orbit moved


def test_growth_rate_and_whirl_at_each_modes_linear_onset(cache):
    """Symmetric rotor, I_p = 0, 20,000 rpm: the cylindrical mode is the one-bearing problem
    with mass m/2, the conical one with mass I_t/(2a²), both at the bearing's load (the
    rotor issue's reduction).  Rotor inertias scaled to 3 % above and below each mode's
    linear threshold (loads unchanged), each kicked in its own shape.

    Tolerances: the matrix-pencil fit after one settling revolution resolves σ to ~1e-5 per
    rad and RKC at Δτ = 0.1 is within 3e-6 of RK4 (benchmarks/bench_integrators.py), while
    σ itself is ≈ 1e-3 here, so 2 % on σ; the whirl ratio to 1 % (fit error ~1e-4).
    """
    speed, delta = 20_000.0, 0.03
    rotor = symmetric_rotor()
    model, sols = build_model(rotor, speed, GRID, cache=cache)
    lin = linearise(sols[0], cache(sols[0].model, GRID))
    thr = linear_threshold(lin)
    omega = speed * math.pi / 30
    w0 = 3.2 * G / 2                                   # load per bearing [N]
    per_unit = BEARING.radial_clearance * omega ** 2 / w0
    equivalent = {"cylindrical": 3.2 / 2, "conical": 0.012 / (2 * 0.05 ** 2)}   # kg
    cases = [(mode, sign) for mode in equivalent for sign in (+1, -1)]
    mu = np.array([thr.critical_mass / (equivalent[m] * per_unit) * (1 + s * delta)
                   for m, s in cases])
    v = 1e-3 / math.sqrt(2)
    velocities = np.array([[[v, v], [v, v]] if m == "cylindrical" else [[v, v], [-v, -v]]
                           for m, _ in cases])
    z = set_station_velocities(model, equilibrium_states(model, len(cases)), velocities)
    run = integrate_rotor(model, runs(len(cases), inertia_scale=mu), 2 * math.pi * 6, z)
    assert run.success
    c = BEARING.radial_clearance
    late = run.tau >= 2 * math.pi
    for b, (mode, sign) in enumerate(cases):
        x, y = run.journal(b, 1)                       # bearing B (z = +a)
        dx, dy = (x - x[0]) / c, (y - y[0]) / c
        sigma, gamma = fit_growth_rate(run.tau[late], dx[late], dy[late])
        mbar = mu[b] * equivalent[mode] * per_unit
        root = characteristic_root(lin, mbar, 1j * thr.whirl_ratio)
        assert np.sign(sigma) == sign                  # grows above, decays below
        assert abs(sigma / root.real - 1) <= 0.02, (mode, sign, sigma, root)
        assert abs(gamma / root.imag - 1) <= 0.01, (mode, sign, gamma, root)
        xa, _ = run.journal(b, 0)
        same = np.sign(np.dot(xa - xa[0], x - x[0]))   # the mode's shape is kept
        assert same == (1 if mode == "cylindrical" else -1)


def _study_system(speed_note="", amount_kg_m=2e-7, polar=0.002):
    """The rotor issue's example rotor (3.2 kg, CG 35/65 mm from the bearings, I_t 0.012,
    I_p 0.002 kg m², two Ruscitto bearings) with one imbalance plane at the impeller end."""
    from gfbopt.inputs.options import ModelOptions
    from gfbopt.inputs.rotor_system import (BearingSupport, ImbalancePlane, RotorBody,
                                            RotorSystem)

    opts = ModelOptions(film="seam", seam_angle_deg=180.0, foil="simple",
                        deflection_law="mean", loss_factor=0.0)
    return RotorSystem(RotorBody(3.2, 0.012, polar),
                       (BearingSupport("A", -0.035, BEARING, opts),
                        BearingSupport("B", 0.065, BEARING, opts)),
                       imbalance=(ImbalancePlane(amount_kg_m, 0.09, 30.0),))


def test_small_imbalance_below_onset_gives_the_linear_synchronous_response(cache):
    """Asymmetric rotor with gyroscopics at 8,000 rpm (below its onset, ≈ 12,000 rpm: the
    transient decays) and 0.2 g mm of imbalance 90 mm from the CG at 30°: the response is
    ≈ 1 % of the clearance, so the film's nonlinearity moves the 1× response by ~(0.01)²,
    and the tracked 1× fit over the last 8 of 16 revolutions carries the decaying transient
    at ≲ 1e-3 (the run starts on the linear response).  The linear response is the rotor
    issue's (gfbopt.rotor.diagrams.synchronous_response: D(iω) q̂ = Q̂ with each bearing's
    synchronous impedance, on the same grid).  Tolerance 2 % of the complex amplitude
    (amplitude and phase: 2 % ≈ 1.1°), the issue's; the RKC step's phase error at 63 steps
    per revolution is ~1e-3 (measured agreement 0.03–0.12 %)."""
    from gfbopt.rotor.diagrams import synchronous_response
    from gfbopt.rotor.supports import resolve_rotor
    from gfbopt.rotor.system import SpeedLine
    from gfbopt.transient.rotor_io import rotor_input

    speed = 8_000.0
    system = _study_system()
    rotor = rotor_input(system)
    model, sols = build_model(rotor, speed, GRID, cache=cache)
    linear = synchronous_response(SpeedLine(resolve_rotor(system, GRID, cache)), speed)
    stations = np.vstack([station_matrix(b.position) for b in model.bearings])
    q_hat = np.linalg.solve(stations, np.concatenate([linear[b.label]
                                                      for b in model.bearings]))
    z = equilibrium_states(model, 1)
    tail = z[0, 0, -9:]
    c = model.clearance_ref
    tail[:4] += q_hat.real / c                       # start on the linear response
    tail[4:8] += (1j * q_hat).real / c
    revs = 16
    run = integrate_rotor(model, runs(1), 2 * math.pi * revs, z)
    assert run.success and not run.contact[0]
    last = run.tau >= 2 * math.pi * (revs - 8)
    t, angle = run.time_s[last], run.shaft_angle(0)[last]
    for k, b in enumerate(model.bearings):
        x, y = run.journal(0, k)
        measured = np.array([synchronous_fit(t, x[last], angle)[0],
                             synchronous_fit(t, y[last], angle)[0]])
        expected = linear[b.label]
        assert abs(expected[0]) < 0.05 * c              # small: the linear regime
        error = np.abs(measured - expected) / np.abs(expected)
        assert np.all(error <= 0.02), (b.label, measured, expected, error)


@pytest.mark.slow
def test_supercritical_limit_cycle_grows_as_the_square_root_of_the_distance_past_onset():
    """Symmetric rotor, I_p = 0, I_t = 0.004 kg m² (conical equivalent mass I_t/(2a²) =
    0.8 kg against m/2 = 1.6 kg: the conical mode stays stable where the cylindrical one
    whirls, so round-off cannot seed a conical whirl), 20,000 rpm, 24 × 8 grid (the linear
    threshold on the same grid): inertias 1, 2 and 4 % above the cylindrical onset in one
    batch, from a small cylindrical kick, 1,800 revolutions (≥ 8 e-folds of the slowest,
    1 %, whose e-fold is ≈ 214 revolutions).  A supercritical Hopf bifurcation has
    A² = c1 δ (1 + k δ + …), so the log–log slope of A against δ is 0.5 + ½ kδ/(1 + kδ); the
    one-bearing bifurcation study (results/bifurcation) has k ≈ 12, a slope ≈ 0.6 at these δ
    at worst, so 0.5 ± 0.1 admits the next order while a subcritical jump or a linear law
    (slope 1) fails.  Settled: the whirl amplitude changes by ≤ 1 % between its last two
    10-period windows (the default criterion; the largest-distance amplitude of a window
    carries a ≈ 0.5 % ripple from residual beats — measured 0.63 % at 2 % after 1,800
    revolutions — and a 1 % error at one δ moves the slope by ≤ 0.015).  Measured in
    development (1,500 revolutions): 3.47 µm at 1 % and 4.92 µm at 2 % (ratio 1.418 against
    √2 = 1.414)."""
    from gfbopt.transient.spectra import limit_cycle

    grid = Grid.parse("24x8")
    cache = SolverCache(grid)
    speed = 20_000.0
    model, sols = build_model(symmetric_rotor(inertia=0.004), speed, grid, cache=cache)
    lin = linearise(sols[0], cache(sols[0].model, grid))
    thr = linear_threshold(lin)
    omega = speed * math.pi / 30
    mu_c = thr.critical_mass / (1.6 * BEARING.radial_clearance * omega ** 2 / (3.2 * G / 2))
    deltas = np.array([0.01, 0.02, 0.04])
    v = 0.01 / math.sqrt(2)
    z = set_station_velocities(model, equilibrium_states(model, 3), [[v, v], [v, v]])
    run = integrate_rotor(model, runs(3, inertia_scale=mu_c * (1 + deltas)),
                          2 * math.pi * 1800, z, sample_every=0.4)
    assert run.success and not run.contact.any()
    amps = []
    for b in range(3):
        x, y = run.journal(b, 0)
        lc = limit_cycle(run.time_s, x * 1e6, y * 1e6, run.shaft_angle(b), speed / 60,
                         periods=10, tolerance=0.01)
        assert lc.settled, (deltas[b], lc)
        assert abs(lc.whirl_ratio / thr.whirl_ratio - 1) < 0.02
        amps.append(lc.amplitude_um)
    slope = np.polyfit(np.log(deltas), np.log(amps), 1)[0]
    assert abs(slope - 0.5) <= 0.1, (amps, slope)


def test_side_load_and_a_bearing_pushed_away_from_gravity_start_in_equilibrium(cache):
    """Overhung CG (both bearings on one side of it) plus a side load: bearing B is pushed
    away from gravity (its load points ≈ 180° from it).  The engine's statics give the rotor
    module's bearing loads and directions (to round-off), and the packed equilibrium is a
    fixed point of the rotor's right-hand side: accelerations ≤ 1e-9 of gravity's (the
    static solves' force residual), films still to ≤ 1e-8 per rad."""
    from gfbopt.inputs.options import ModelOptions
    from gfbopt.inputs.rotor_system import BearingSupport, RotorBody, RotorSystem, SideLoad
    from gfbopt.rotor.rigid import bearing_loads
    from gfbopt.transient.rotor_io import frame_check, rotor_input
    from gfbopt.transient.rotor_system import RotorRightHandSide

    opts = ModelOptions(film="seam", seam_angle_deg=180.0, foil="simple",
                        deflection_law="mean", loss_factor=0.0)
    system = RotorSystem(RotorBody(3.2, 0.012, 0.002),
                         (BearingSupport("A", 0.03, BEARING, opts),
                          BearingSupport("B", 0.09, BEARING, opts)),
                         side_loads=(SideLoad(15.0, 90.0, 0.12),))
    loads = bearing_loads(system)
    assert abs(loads[1].away_from_gravity_deg) > 90            # B is pushed upwards
    rotor = rotor_input(system)
    assert frame_check(rotor, system) < 1e-9
    model, sols = build_model(rotor, 30_000.0, GRID, cache=cache)
    for film, load in zip(model.bearings, loads):
        assert math.degrees(film.frame_angle) == pytest.approx(load.direction_deg, abs=1e-9)
    rhs = RotorRightHandSide(model, runs(1))
    d = rhs(equilibrium_states(model, 1))
    lay = rhs.layout
    g_scale = 9.80665 / (model.clearance_ref * model.reference_speed ** 2)
    assert np.max(np.abs(lay.rotor_of(d)[:, 4:8])) < 1e-9 * g_scale * 10
    assert np.max(np.abs(lay.phi_of(d, 0))) < 1e-8 and np.max(np.abs(lay.phi_of(d, 1))) < 1e-8


def test_a_ramps_speed_following_step_keeps_the_answer_and_a_uniform_record(cache):
    """A run-up's rkc step follows the speed (rotor_run: Δτ = min(0.2 rad of shaft rotation
    at the current speed, T_rotor/30, T_film/4), samples Hermite-interpolated onto a uniform
    grid).  Against the same ramp at a constant step 4–6× finer (Δτ = 0.05, the old kind of
    record, one sample every 4 steps): the tracked 1× response over the last 4 top-speed
    revolutions at both bearings within 1 % of the complex amplitude (RKC's phase error at
    0.2 rad per step is ~3e-4 per rad, benchmarks/bench_integrators.py; measured 0.02–0.2 %),
    the smallest film within 1e-4 of itself; the record is uniform in time (every interval
    the sample spacing to 1e-9, but a shorter last one) and the speed-following step costs
    fewer evaluations."""
    from gfbopt.inputs.rotor_system import load_rotor
    from gfbopt.transient.rotor_analysis import ramp_profile, run_profile

    system = load_rotor("problems/rotors/blower.toml")
    profile = ramp_profile(5_000.0, 11_000.0, 50_000.0)
    kw = {"grid": GRID, "perturbation": "none", "linear_onset": False, "cache": cache}
    follow = run_profile(system, profile, **kw).run
    fine = run_profile(system, profile, time_step=0.05, **kw).run
    assert follow.success and fine.success
    assert follow.options["step_rule"].startswith("follows the speed")
    assert fine.options["step_rule"] == "constant"
    assert follow.evaluations < 0.7 * fine.evaluations
    gaps = np.diff(follow.tau)
    assert np.all(np.abs(gaps[:-1] - 0.2) < 1e-9) and 0 < gaps[-1] <= 0.2 + 1e-9
    np.testing.assert_allclose(follow.tau[:-1], fine.tau[:-1], rtol=0, atol=1e-9)
    for k in range(2):
        amps = []
        for run in (follow, fine):
            x, y = run.journal(0, k)
            last = run.tau >= run.tau[-1] - 2 * math.pi * 4
            t, angle = run.time_s[last], run.shaft_angle(0)[last]
            amps.append(np.array([synchronous_fit(t, x[last], angle)[0],
                                  synchronous_fit(t, y[last], angle)[0]]))
        error = np.abs(amps[0] - amps[1]) / np.abs(amps[1])
        assert np.all(error <= 0.01), (k, amps, error)
        assert abs(follow.run_min_film[0, k] / fine.run_min_film[0, k] - 1) < 1e-4
