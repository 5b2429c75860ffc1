"""Bumps that rub in the rotor transient (gfbopt.transient.rotor_friction): each bearing's
sliders Z beside the rotor's state, moved by the play operator after each accepted step.

Friction 0 is today's rotor transient exactly; the fused friction films equal the one-bearing
kernels; a symmetric rotor (two identical bearings, no gyroscopics, CG midway, a side load at
the CG) whose cylindrical mode carries M̄ per bearing is the one-bearing problem exactly, so it
must reproduce the one-bearing friction orbit (gfbopt.transient.friction_orbit) and settle
where the rotor's describing function (gfbopt.rotor.friction_onset.settled_whirl) says; the
blower on rubbing bumps at its top speed, where the describing function finds no bounded
orbit inside the film, closes the film."""
import dataclasses
import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from gfbopt.errors import ParameterError
from gfbopt.inputs import Grid
from gfbopt.inputs.bearing_file import load_bearing
from gfbopt.inputs.rotor_system import load_rotor, rotor_from_dict
from gfbopt.rotor.system import without_gyroscopics
from gfbopt.transient.friction_foil import FrictionFoil
from gfbopt.transient.friction_orbit import friction_outcome, integrate_friction_orbits
from gfbopt.transient.rotor_analysis import rotor_orbit
from gfbopt.transient.rotor_friction import bearing_outcomes, initial_sliders, move_sliders
from gfbopt.transient.rotor_io import rotor_input
from gfbopt.transient.rotor_run import integrate_rotor
from gfbopt.transient.rotor_setup import (build_model, equilibrium_states,
                                          set_station_velocities)
from gfbopt.transient.rotor_system import RotorRightHandSide, runs

ROOT = Path(__file__).resolve().parents[2]
ROTORS = ROOT / "problems" / "rotors"
PLAIN = str(ROOT / "problems" / "bearings" / "ruscitto.toml")
GRID = Grid(24, 8)
SPEED, LOAD, CLEARANCE, MBAR = 15000.0, 60.0, 20e-6, 8.0


def _with_friction(system, mu):
    return replace(system, bearings=tuple(
        replace(b, options=replace(b.options, friction_coefficient=mu))
        for b in system.bearings))


def _kicked(model, batch=1, kick=1e-3):
    z = equilibrium_states(model, batch)
    v = kick / math.sqrt(2)
    return set_station_velocities(model, z, [[v, v], [v, v]])


def _zero_friction(model):
    """The same rotor model with a friction element of μ_f = 0 on every row of every bearing."""
    bearings = []
    for b in model.bearings:
        tm, sol = b.tm, b.tm.static
        x0 = sol.eccentricity * math.cos(sol.attitude_angle_rad)
        y0 = sol.eccentricity * math.sin(sol.attitude_angle_rad)
        w0 = (sol.film - (1.0 + tm.bore - x0 * tm.cos - y0 * tm.sin)[:, None])[:, 0].copy()
        friction = FrictionFoil(np.zeros(tm.shape[0]), 2.0, w0, "rows")
        bearings.append(replace(b, tm=dataclasses.replace(tm, friction=friction)))
    return replace(model, bearings=tuple(bearings))


@pytest.fixture(scope="module")
def blower():
    """The shipped blower on plain bumps, at 60,000 rpm, 24 × 8."""
    model, _ = build_model(rotor_input(load_rotor(ROTORS / "blower.toml")), 60000.0, GRID)
    return model


def test_zero_friction_is_todays_rotor_transient(blower):
    # a bearing file stating μ_f = 0 builds today's model (no sliders); μ_f = 0 forced on
    # every row through the friction path (fused rows and the one-bearing kernels) gives
    # today's orbits, films and step choices to 1e-12 (rk4 and rkc, 4 revolutions of the
    # blower above its onset at 60,000 rpm, imbalance on)
    zero = _with_friction(load_rotor(ROTORS / "blower_friction.toml"), 0.0)
    model, _ = build_model(rotor_input(zero), 60000.0, GRID)
    assert all(b.tm.friction is None for b in model.bearings)
    forced = _zero_friction(blower)
    duration = 2 * math.pi * 4
    for method in ("rk4", "rkc"):
        today = integrate_rotor(blower, runs(1), duration, _kicked(blower), method=method)
        assert today.sliders is None
        for fuse in (True, False):
            orig = RotorRightHandSide.__init__

            def init(self, *a, _fuse=fuse, **k):
                k["fuse"] = _fuse
                orig(self, *a, **k)

            RotorRightHandSide.__init__ = init
            try:
                new = integrate_rotor(forced, runs(1), duration, _kicked(forced),
                                      method=method)
            finally:
                RotorRightHandSide.__init__ = orig
            assert new.sliders is not None and new.tau.shape == today.tau.shape
            assert new.evaluations == today.evaluations and new.stages == today.stages
            np.testing.assert_allclose(new.q / CLEARANCE, today.q / CLEARANCE, rtol=0,
                                       atol=1e-12)
            np.testing.assert_allclose(new.min_film, today.min_film, rtol=0, atol=1e-12)


def test_fused_friction_films_equal_the_one_bearing_kernels():
    # a perturbed state of the blower on rubbing bumps (films ±2 %, sliders ±0.01 c), two
    # runs: the fused rows, the stacked and the bearing-by-bearing kernels give the same
    # right-hand side and the same sliders after a step (measured 1.6e-14 and 4e-16)
    model, _ = build_model(rotor_input(load_rotor(ROTORS / "blower_friction.toml")),
                           60000.0, GRID)
    rng = np.random.default_rng(3)
    z = _kicked(model, 2)
    z[:, :, :-9] *= 1 + 0.02 * rng.standard_normal(z[:, :, :-9].shape)
    start = initial_sliders(model, 2)
    sliders = tuple(s + 0.01 * rng.standard_normal(s.shape) for s in start)
    fused = RotorRightHandSide(model, runs(2), sliders=sliders)
    assert fused.fuse and fused.stack
    ref = fused(z)
    for stack in (True, False):
        kernel = RotorRightHandSide(model, runs(2), sliders=sliders, fuse=False, stack=stack)
        np.testing.assert_allclose(kernel(z), ref, rtol=0, atol=1e-12 * np.abs(ref).max())
        for a, b in zip(move_sliders(kernel, z), move_sliders(fused, z)):
            np.testing.assert_allclose(a, b, rtol=0, atol=1e-14)
    # the play operator moved some sliders and kept others (both branches exercised)
    moved = move_sliders(fused, z)
    changed = np.abs(moved[0] - sliders[0]) > 1e-15
    assert 0 < changed.sum() < changed.size
    # the films of a friction model need the sliders
    with pytest.raises(ParameterError, match="sliders"):
        RotorRightHandSide(model, runs(2))


def _symmetric_system(mu=0.05):
    """Two Ruscitto bearings with S = 1 (bump thickness solved for it), μ_f, κ = 2, 60 N
    each from a side load at the CG, no gravity, no gyroscopics; the cylindrical mode
    carries M̄ = (m/2) c ω²/W0 = 8 per bearing, the conical one I_t/(2 l²) c ω²/W0 = 1.6
    (below the stuck onset: it stays at rest).  At 15,000 rpm this is the one-bearing
    bounded case of tests/verification/test_friction_transient.py (M̄c 6.99 stuck)."""
    geometry = load_bearing(PLAIN)
    thickness = brentq(lambda t: replace(geometry, bump_thickness=t).compliance - 1.0,
                       40e-6, 300e-6, xtol=1e-16)
    omega = SPEED * math.pi / 30
    half = MBAR * LOAD / (CLEARANCE * omega ** 2)
    model = {"friction_coefficient": mu, "friction_stiffness_ratio": 2.0}
    system = rotor_from_dict({
        "rotor": {"mass": 2 * half, "transverse_inertia": 0.01, "polar_inertia": 0.001,
                  "gravity": 0.0},
        "side_loads": [{"force": 2 * LOAD, "direction_deg": 0.0, "position": 0.0}],
        "bearings": [{"file": PLAIN, "position": -0.05, "model": model},
                     {"file": PLAIN, "position": 0.05, "model": model}]})
    return replace(without_gyroscopics(system), bearings=tuple(
        replace(b, geometry=replace(b.geometry, bump_thickness=thickness))
        for b in system.bearings))


def _symmetric_runs(system):
    """(system, model, rotor run, one-bearing run) of a symmetric rotor: 80 revolutions, rkc
    at Δτ = 0.1 (both drivers), cylindrical kick 0.03 at both journals."""
    model, _ = build_model(rotor_input(system), SPEED, GRID)
    duration, kick = 2 * math.pi * 80, 0.03
    run = integrate_rotor(model, runs(1), duration, _kicked(model, kick=kick), method="rkc",
                          time_step=0.1)
    one = integrate_friction_orbits(model.bearings[0].tm, [MBAR], 80.0, kick=kick,
                                    method="rkc", time_step=0.1)
    return system, model, run, one


@pytest.fixture(scope="module")
def symmetric():
    """The symmetric rotor's two runs (:func:`_symmetric_runs`) on bare friction."""
    return _symmetric_runs(_symmetric_system())


def test_symmetric_rotor_reproduces_the_one_bearing_friction_orbit(symmetric):
    # the same equations in another arrangement (the rotor's matrices, both bearings' films
    # fused): the journal orbits agree to round-off (measured 6e-14 c over 80 revolutions;
    # asserted 1e-9 c), so the settled limit cycle is the one-bearing one at both bearings
    # (0.0530 c at γ = 0.3771; measured agreement 3e-14 relative, asserted 1e-9)
    _, model, run, one = symmetric
    assert model.bearings[0].tm.friction is not None and run.success and not run.contact[0]
    single = friction_outcome(one.orbit)
    assert single.kind == "settled limit cycle", single.verdict
    assert run.tau.shape == one.orbit.tau.shape
    for k in range(2):
        x, y = run.journal(0, k)
        np.testing.assert_allclose(x / CLEARANCE, one.orbit.x[0], rtol=0, atol=1e-9)
        np.testing.assert_allclose(y / CLEARANCE, one.orbit.y[0], rtol=0, atol=1e-9)
    for out in bearing_outcomes(run):
        assert out["kind"] == "settled limit cycle", out["verdict"]
        assert out["amplitude_um"] == pytest.approx(single.amplitude * CLEARANCE * 1e6,
                                                    rel=1e-9)
        assert out["whirl_ratio"] == pytest.approx(single.whirl_ratio, rel=1e-9)
        assert out["whirl_frequency_hz"] == pytest.approx(
            single.whirl_ratio * SPEED / 60.0, rel=1e-9)
        assert out["verdict"].startswith("settled limit cycle of 1.06 µm at 94.27 Hz")
    for a, b in zip(run.sliders, (one.slider, one.slider)):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-9)


@pytest.mark.slow
def test_symmetric_rotor_settles_where_the_describing_function_says(symmetric):
    # gfbopt.rotor.friction_onset.settled_whirl on the same rotor and grid: bounded whirl of
    # 1.108 µm at γ = 0.3766 (the one-bearing describing function's, to 1e-9 by its own
    # test); the transient settles 4.4 % below it (1.060 µm) at γ within 0.2 % — the
    # one-bearing transient's own agreement (its test: 5 %, 1 %)
    _settles_as_predicted(symmetric)


def _settles_as_predicted(symmetric):
    """Each bearing's settled orbit of the symmetric rotor's run within 5 % (amplitude) and
    1 % (whirl ratio) of the describing function's forward cylindrical prediction."""
    from gfbopt.rotor.friction_onset import settled_whirl
    from gfbopt.rotor.supports import resolve_rotor

    system, _, run, _ = symmetric
    predicted = settled_whirl(resolve_rotor(system, GRID), SPEED)
    assert predicted.bounded and predicted.label == "forward cylindrical"
    for out, amp in zip(bearing_outcomes(run), predicted.amplitude_um):
        assert out["amplitude_um"] == pytest.approx(amp, rel=0.05)
        assert out["whirl_ratio"] == pytest.approx(predicted.whirl_ratio, rel=0.01)


def test_blower_on_rubbing_bumps_closes_the_film_at_its_top_speed(capsys):
    # blower_friction at 60,000 rpm, 72 × 20: the describing function finds no bounded orbit
    # inside the film (tests/verification/test_rotor_friction_orbit.py); the transient's whirl
    # grows until bearing B's film closes, after 7.353 ms (7.77 ms on plain bumps; the fused
    # rows and the one-bearing kernels give the same step); asserted to ±1 %: the growing
    # orbit amplifies any change of a stick/slip decision
    system = load_rotor(ROTORS / "blower_friction.toml")
    result = rotor_orbit(system, 60000.0, 100, grid=Grid(72, 20), imbalance_scale=1.0)
    out = result.to_dict()
    assert out["contact"] and out["contact_bearing"] == "B"
    assert out["contact_time_s"] == pytest.approx(7.353e-3, rel=0.01)
    assert out["bump_friction"].startswith("bump friction μ_f = 0.5, κ = 2 at A; μ_f = 0.5, "
                                           "κ = 2 at B (sliders integrated")
    for b in out["bearings"]:
        assert b["friction_orbit_kind"] == "contact"
        assert b["friction_orbit_verdict"].startswith("contact after 7.3")
    assert any(n.startswith("Bumps that rub: bump friction") for n in out["notes"])


def test_command_line_states_the_model_and_the_outcome(capsys):
    from gfbopt.cli import main

    args = ["rotor", str(ROTORS / "blower_friction.toml"), "--orbit", "--speed-rpm", "60000",
            "--revolutions", "3", "--grid", "24x8"]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "bump friction μ_f = 0.5, κ = 2 at A; μ_f = 0.5, κ = 2 at B (sliders integrated" \
        in text
    assert "bearing A with friction: end of run" in text
    assert main(args + ["--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["bump_friction"].startswith("bump friction")
    assert [b["friction_orbit_kind"] for b in data["bearings"]] == ["end of run", "end of run"]


def test_refusals():
    system = load_rotor(ROTORS / "blower_friction.toml")
    model, _ = build_model(rotor_input(system), 60000.0, GRID)
    with pytest.raises(ParameterError, match="method = 'bdf'.*rk4 or rkc") as err:
        integrate_rotor(model, runs(1), 1.0, _kicked(model), method="bdf")
    assert "\n" not in str(err.value)
    # friction with η > 0: tests/unit/test_rotor_friction_damped.py (carried on the fused
    # rows, refused off them)
    with pytest.raises(ParameterError, match="sliders"):
        integrate_rotor(model, runs(2), 1.0, _kicked(model, 2),
                        sliders=initial_sliders(model, 1))
    plain, _ = build_model(rotor_input(load_rotor(ROTORS / "blower.toml")), 60000.0, GRID)
    with pytest.raises(ParameterError, match="no bump friction"):
        integrate_rotor(plain, runs(1), 1.0, _kicked(plain), sliders=initial_sliders(model, 1))


def test_each_run_keeps_its_own_sliders():
    # a batch of two blower runs on rubbing bumps (24 × 8, rkc at one fixed step), at the
    # rotor's mass and at twice it: each run of the batch equals that run alone — orbits and
    # sliders to 1e-12 (no slider of one run leaks into another's films)
    model, _ = build_model(rotor_input(load_rotor(ROTORS / "blower_friction.toml")),
                           60000.0, GRID)
    duration = 2 * math.pi * 3
    both = integrate_rotor(model, runs(2, inertia_scale=[1.0, 2.0]), duration,
                           _kicked(model, 2), method="rkc", time_step=0.1, stages=8)
    assert both.success and len(both.sliders) == 2
    for i, mu in enumerate((1.0, 2.0)):
        alone = integrate_rotor(model, runs(1, inertia_scale=mu), duration, _kicked(model),
                                method="rkc", time_step=0.1, stages=8)
        np.testing.assert_allclose(both.q[i] / CLEARANCE, alone.q[0] / CLEARANCE, rtol=0,
                                   atol=1e-12)
        for a, b in zip(both.sliders, alone.sliders):
            np.testing.assert_allclose(a[i], b[0], rtol=0, atol=1e-12)
    start = initial_sliders(model, 2)
    assert np.abs(both.sliders[1] - start[1]).max() > 1e-3


@pytest.mark.slow
def test_blower_just_above_its_onset_settles_on_rubbing_bumps():
    # blower_friction at 13,500 rpm (its stuck onset μ_c = 0.920, forward conical, 36 × 10),
    # no imbalance, 400 revolutions, 36 × 10 (≈ 12 s CPU): the whirl settles at 3.63 µm (A)
    # and 11.36 µm (B) at 0.494× — where the rotor's describing function, which holds the
    # film linear, finds no bounded orbit inside the film — while on plain bumps the film
    # closes (B, after ≈ 0.17 s at 72 × 20); amplitudes asserted to 2 % (the one-bearing
    # step study: halving the step moves a settled friction orbit by ≤ 0.5 %)
    grid = Grid(36, 10)
    out = rotor_orbit(load_rotor(ROTORS / "blower_friction.toml"), 13500.0, 400, grid=grid,
                      imbalance_scale=0.0).to_dict()
    assert not out["contact"] and out["success"]
    kinds = [b["friction_orbit_kind"] for b in out["bearings"]]
    assert kinds == ["settled limit cycle", "settled limit cycle"]
    amps = [b["friction_orbit_amplitude_um"] for b in out["bearings"]]
    assert amps == pytest.approx([3.63, 11.36], rel=0.02)
    for b in out["bearings"]:
        assert b["friction_orbit_whirl_ratio"] == pytest.approx(0.494, abs=0.003)
    bare = rotor_orbit(load_rotor(ROTORS / "blower.toml"), 13500.0, 400, grid=grid,
                       imbalance_scale=0.0).to_dict()
    assert bare["contact"] and bare["contact_bearing"] == "B"


def test_a_run_up_carries_the_sliders_and_states_no_limit_cycle():
    # the sliders do not depend on the bearing number, so a ramp (Λ following the speed in
    # the engine) carries them as an orbit does; its result names the model, and no
    # per-bearing limit cycle (a ramp has none)
    from gfbopt.transient.rotor_analysis import rotor_ramp

    result = rotor_ramp(load_rotor(ROTORS / "blower_friction.toml"), 8000.0, 12000.0,
                        100000.0, grid=GRID, linear_onset=False)
    out = result.to_dict()
    assert result.success and result.run.sliders is not None
    assert out["bump_friction"].startswith("bump friction μ_f = 0.5")
    assert all("friction_orbit_kind" not in b for b in out["bearings"])
    assert any("a ramp states no limit cycle" in n for n in out["notes"])
