"""The rotor transient on the structure contract (gfbopt.rotor.structure): a rotor of any
size integrates.

* The generic n-degree-of-freedom path (least-squares equilibrium, stations from the
  structure, journals S(z) q) run on the rigid body is the rigid path to round-off (the
  rigid path itself is unchanged bit for bit: the rigid body keeps its own arithmetic).
* problems/rotors/flexible_rotor.toml (20 Timoshenko elements, condensed on its bearing
  stations with 8 held modes: 12 degrees of freedom) at 20,000 rpm, 36 × 10: its static
  equilibrium (the shaft's deflection under gravity and the films) is a rest point of the
  transient, and a kicked run of 3 revolutions stays in its film with the explicit step
  under T/30 of the structure's highest kept mode (the step rule's rotor period includes
  the shaft's stiffness); and its imbalance response is the rotor analyses' linear
  synchronous response on the same condensed shaft, to 2 %.
"""
import math
from pathlib import Path

import numpy as np
import pytest

from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.structure import RigidStructure, is_rigid
from gfbopt.static import SolverCache
from gfbopt.transient.rotor_io import rotor_input
from gfbopt.transient.rotor_run import integrate_rotor
from gfbopt.transient.rotor_setup import (build_model, equilibrium_states, gravity_force,
                                          set_station_velocities)
from gfbopt.transient.rotor_system import RotorRightHandSide, runs

ROOT = Path(__file__).resolve().parents[2]
GRID = Grid(36, 10)


class _Generic:
    """The rigid body seen through the contract only (not recognised as rigid)."""

    kind = "generic"

    def __init__(self, body):
        self._rigid = RigidStructure(body)

    def __getattr__(self, name):
        return getattr(self._rigid, name)


@pytest.fixture(scope="module")
def blower():
    system = load_rotor(ROOT / "problems/rotors/blower.toml")
    return system, rotor_input(system)


def test_the_generic_path_on_the_rigid_body_is_the_rigid_path(blower):
    system, rigid_input = blower
    generic = _Generic(system.body)
    assert not is_rigid(generic)
    q_s = gravity_force(generic, system.weight_vector,
                        [(*load.vector, load.position) for load in system.side_loads])
    np.testing.assert_allclose(q_s, rigid_input.static_force, rtol=0, atol=1e-12)
    generic_input = type(rigid_input)(rigid_input.mass_matrix, rigid_input.gyroscopic,
                                      rigid_input.bearings, rigid_input.static_force,
                                      rigid_input.imbalance, rigid_input.description,
                                      generic, q_s)
    cache = SolverCache(GRID)
    a, _ = build_model(rigid_input, 30_000.0, GRID, cache=cache)
    b, _ = build_model(generic_input, 30_000.0, GRID, cache=cache)
    assert a.rigid and not b.rigid
    za = set_station_velocities(a, equilibrium_states(a, 1), [[1e-3, 0.0], [0.0, 1e-3]])
    zb = set_station_velocities(b, equilibrium_states(b, 1), [[1e-3, 0.0], [0.0, 1e-3]])
    np.testing.assert_allclose(zb, za, rtol=0, atol=1e-13)
    ra, rb = (integrate_rotor(m, runs(1, ramp=1e-3), 2 * math.pi, z.copy())
              for m, z in ((a, za), (b, zb)))
    assert ra.evaluations == rb.evaluations and ra.success and rb.success
    scale = np.abs(ra.q).max()
    np.testing.assert_allclose(rb.q, ra.q, rtol=0, atol=1e-10 * scale)
    for k in range(2):
        np.testing.assert_allclose(rb.journal(0, k), ra.journal(0, k), rtol=0,
                                   atol=1e-10 * scale)


@pytest.fixture(scope="module")
def flexible():
    system = load_rotor(ROOT / "problems/rotors/flexible_rotor.toml")
    rotor = rotor_input(system, imbalance=())
    model, _ = build_model(rotor, 20_000.0, GRID, cache=SolverCache(GRID))
    return rotor, model


def test_a_flexible_shaft_rests_at_its_static_equilibrium(flexible):
    rotor, model = flexible
    assert rotor.structure.size == 4 + rotor.structure.modes_kept and not model.rigid
    z = equilibrium_states(model, 1)
    rhs = RotorRightHandSide(model, runs(1))
    n = model.dofs
    tail = rhs(z)[0, 0, rhs.layout.rotor:]
    films = np.abs(rhs.from_local @ rhs.accel).max()     # one unit of film force, q̃''
    assert np.abs(tail[n:2 * n]).max() < 1e-9 * films
    deflection = z[0, 0, rhs.layout.rotor + 4:rhs.layout.rotor + n]     # held modes η
    assert np.abs(deflection).max() > 1e-4      # gravity does bend the shaft (η ≠ 0)


def test_a_kicked_flexible_rotor_runs_in_its_film_at_the_structures_step(flexible):
    _, model = flexible
    z = set_station_velocities(model, equilibrium_states(model, 1),
                               [[1e-3, 1e-3], [1e-3, 1e-3]])
    run = integrate_rotor(model, runs(1), 2 * math.pi * 3, z)
    assert run.success and not run.contact.any()
    assert run.q.shape[2] == model.dofs and np.all(np.isfinite(run.q))
    highest = math.sqrt(np.linalg.eigvals(np.linalg.solve(model.mass_matrix,
                                                          model.stiffness)).real.max())
    rate = highest / model.reference_speed
    assert run.time_step * rate <= 2 * math.pi / 30
    # RKC's own growth of an undamped held mode over the run: at most 10 %
    steps = 2 * math.pi * 3 / run.time_step
    assert steps * (rate * run.time_step) ** 4 / 8 <= math.log(1.1) * (1 + 1e-9)
    for k in range(2):
        x, y = run.journal(0, k)
        c = model.bearings[k].clearance
        assert 0 < np.ptp(x) < 0.1 * c and 0 < np.ptp(y) < 0.1 * c
    assert run.run_min_film.min() > 0.3


def test_a_flexible_rotors_imbalance_response_is_the_linear_synchronous_response():
    """The flexible rotor at 8,000 rpm (below its onset) with the file's 2 g mm on the
    overhung impeller, 16 revolutions from the static equilibrium: the 1× fit over the last
    8 at both bearings against the rotor analyses' linear response on the same condensed
    shaft (gfbopt.rotor.diagrams.synchronous_response, each bearing's synchronous
    impedance, 36 × 10).  RK4: it damps the undamped held modes' imaginary axis (RKC would
    need its growth cap's short step, rotor_steps.growth_step, over 16 revolutions).
    Tolerance 2 % of the complex amplitude, the rigid rotor's test's:
    bearing B's response is ≈ 10 % of its clearance (the film's nonlinearity ~1 %);
    measured 0.07–0.09 % at A, 0.3–0.94 % at B."""
    from gfbopt.rotor.diagrams import synchronous_response
    from gfbopt.rotor.supports import resolve_rotor
    from gfbopt.rotor.system import SpeedLine
    from gfbopt.transient.spectra import synchronous_fit

    speed, revs = 8_000.0, 16
    system = load_rotor(ROOT / "problems/rotors/flexible_rotor.toml")
    cache = SolverCache(GRID)
    model, _ = build_model(rotor_input(system), speed, GRID, cache=cache)
    linear = synchronous_response(SpeedLine(resolve_rotor(system, GRID, cache)), speed)
    run = integrate_rotor(model, runs(1), 2 * math.pi * revs, equilibrium_states(model, 1),
                          method="rk4")
    assert run.success and not run.contact[0]
    last = run.tau >= 2 * math.pi * (revs - 8)
    t, angle = run.time_s[last], run.shaft_angle(0)[last]
    for k, b in enumerate(model.bearings):
        x, y = run.journal(0, k)
        measured = np.array([synchronous_fit(t, x[last], angle)[0],
                             synchronous_fit(t, y[last], angle)[0]])
        expected = np.asarray(linear[b.label])
        assert abs(expected[0]) < 0.15 * b.clearance          # the near-linear regime
        error = np.abs(measured - expected) / np.abs(expected)
        assert np.all(error <= 0.02), (b.label, measured, expected, error)


def test_the_growth_cap_keeps_rkcs_amplification_of_an_undamped_mode_within_10_percent():
    """rotor_steps.growth_step on an undamped oscillator of 40 rad per rad of τ over 50 rad:
    RKC with 2 stages (its largest amplification) grows it by at most 10 %, and by more than
    5 % (the cap is not needlessly short); at the T/30 step instead it grows ≈ 10-fold."""
    from types import SimpleNamespace

    from gfbopt.transient.rkc import rkc_step
    from gfbopt.transient.rotor_steps import GROWTH, growth_step

    rate, duration = 40.0, 50.0
    rotation = np.array([[0.0, rate], [-rate, 0.0]])

    def grown(dt):
        z = np.array([[1.0, 0.0]])
        for _ in range(int(round(duration / dt))):
            z = rkc_step(lambda y: y @ rotation.T, z, dt, 2)
        return float(np.linalg.norm(z))

    dt = growth_step(SimpleNamespace(structure_rate=rate), duration)
    assert GROWTH == 1.1 and 1.05 < grown(dt) <= 1.1 * (1 + 1e-6)
    assert grown(2 * math.pi / rate / 30) > 5
    assert growth_step(SimpleNamespace(structure_rate=0.0), duration) == math.inf
