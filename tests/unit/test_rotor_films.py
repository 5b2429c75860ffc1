"""The rotor transient's fused film evaluation (gfbopt.transient.rotor_films) equals the
one-bearing kernels to round-off.

On random states (films, foil states, rotor positions and velocities, a batch of runs at
different speeds, ramps and inertias) the right-hand side with every film evaluated at once
is compared with (a) the same system through the one-bearing kernels bearing by bearing
(``fuse=False``, the engine as it was) and (b) a reference written here from the one-bearing
functions (pressure_and_film, flux_residual, film_force, the foil state's rate): every film
and foil entry to 1e-12 of the block's largest, the rotor's rows likewise, the smallest film
and the largest foil deflection to 1e-13.  Variants: undamped and damped axial-mean law,
seamed and periodic film, compression-only bumps, a rigid bore.  A short run-up integrated
both ways keeps its record to 1e-9 of the clearance.
"""
import dataclasses
import math

import numpy as np
import pytest

from gfbopt.inputs import Grid, load_bearing
from gfbopt.physics.foil_laws import RigidLaw
from gfbopt.static import SolverCache
from gfbopt.transient.rotor_films import fusable
from gfbopt.transient.rotor_run import integrate_rotor
from gfbopt.transient.rotor_setup import (RotorBearing, RotorInput, build_model,
                                          equilibrium_states, static_force_of)
from gfbopt.transient.rotor_system import RotorRightHandSide, layout, rigid_rotor_matrices, runs
from gfbopt.transient.system import film_force, flux_residual, pressure_and_film

BEARING = load_bearing("problems/bearings/ruscitto.toml")
GRID = Grid.parse("24x8")
G = 9.80665


def rotor(loss_factor=0.0, film="seam", **options):
    """An asymmetric rotor (CG 30 mm from mid-span, I_p > 0): the bearings carry different
    loads, so their films, and with damping their τ_f, differ."""
    m, g = rigid_rotor_matrices(3.2, 0.012, 0.002)
    opts = {"film": film, "loss_factor": loss_factor, **options}
    if film == "seam":
        opts["seam_angle_deg"] = 180.0
    bearings = (RotorBearing(BEARING, -0.08, opts, "A"), RotorBearing(BEARING, 0.02, opts, "B"))
    return RotorInput(m, g, bearings, static_force_of([(3.2 * G, 0.0, 0.0)]), ())


@pytest.fixture(scope="module")
def cache():
    return SolverCache(GRID)


def variant(name, cache):
    if name == "rigid":
        model, _ = build_model(rotor(), 30_000.0, GRID, cache=cache)
        films = tuple(dataclasses.replace(b, tm=dataclasses.replace(b.tm, law=RigidLaw()))
                      for b in model.bearings)
        return dataclasses.replace(model, bearings=films)
    kw = {"undamped": {}, "damped": {"loss_factor": 0.3},
          "periodic": {"film": "periodic", "loss_factor": 0.3},
          "periodic_undamped": {"film": "periodic"},
          "compression_only": {"compression_only": True}}[name]
    model, _ = build_model(rotor(**kw), 30_000.0, GRID, cache=cache)
    return model


def random_states(model, batch, rng):
    z = equilibrium_states(model, batch)
    lay = layout(model)
    for k in range(len(model.bearings)):
        phi = lay.phi_of(z, k)
        phi *= 1.0 + 0.1 * rng.standard_normal(phi.shape)
        w = lay.foil_of(z, k)
        if w is not None:
            w += 0.05 * rng.standard_normal(w.shape)
    r = lay.rotor_of(z)
    r[:, :8] += 0.1 * rng.standard_normal((batch, 8))
    r[:, 8] = rng.uniform(0.0, 5.0, batch)
    return z


def reference_films(rhs, z):
    """dΦ/dτ, dW/dτ and the forces of every bearing from the one-bearing functions."""
    lay, model = rhs.layout, rhs.model
    xy = rhs.journals(z)
    speed = rhs.runs.speed_at(lay.rotor_of(z)[:, 8])
    out = []
    for k, b in enumerate(model.bearings):
        tm, w = b.tm, lay.foil_of(z, k)
        p, h = pressure_and_film(lay.phi_of(z, k), xy[:, k, 0], xy[:, k, 1], tm, deflection=w)
        lam = (rhs.base_lambda[k] * speed)[:, None, None]
        dphi = flux_residual(p, h, dataclasses.replace(tm, bearing_number=lam))
        dw = None if w is None else tm.foil_state.rate(p, w, tm) * rhs.foil_factor[k]
        out.append((dphi / rhs.film_divisor[k], dw, np.stack(film_force(p, tm), axis=1)))
    return out


def close(a, b, tol=1e-12):
    scale = max(np.max(np.abs(b)), 1e-300)
    return np.max(np.abs(a - b)) / scale < tol


@pytest.mark.parametrize("name", ["undamped", "damped", "periodic", "periodic_undamped",
                                  "compression_only", "rigid"])
def test_fused_films_equal_the_one_bearing_kernels_on_random_states(name, cache):
    model = variant(name, cache)
    assert fusable(model)
    rng = np.random.default_rng(7)
    batch = runs(3, speed=[0.4, 1.0, 1.7], ramp=[0.0, 0.02, -0.01], inertia_scale=[1, 2, 0.5])
    z = random_states(model, 3, rng)
    fused = RotorRightHandSide(model, batch, track_deflection=True)
    kernels = RotorRightHandSide(model, batch, track_deflection=True, fuse=False)
    assert fused.fused is not None and kernels.fused is None
    a, b = fused(z), kernels(z)
    lay = fused.layout
    ref = reference_films(fused, z)
    for k in range(len(model.bearings)):
        assert close(lay.phi_of(a, k), lay.phi_of(b, k))
        assert close(lay.phi_of(a, k), ref[k][0])
        if ref[k][1] is not None:
            assert close(lay.foil_of(a, k), lay.foil_of(b, k))
            assert close(lay.foil_of(a, k), ref[k][1])
    assert close(lay.rotor_of(a), lay.rotor_of(b))
    assert np.array_equal(a[:, :, lay.filled:-9], b[:, :, lay.filled:-9])   # padding: 0
    np.testing.assert_allclose(fused.min_film, kernels.min_film, rtol=0, atol=1e-13)
    np.testing.assert_allclose(fused.max_deflection, kernels.max_deflection, rtol=0,
                               atol=1e-13)
    # the flux is not trivially small: a wrong stencil entry would show
    assert np.max(np.abs(lay.phi_of(a, 0))) > 1e-2
    # a second evaluation (the kernel's buffers reused) at another state is as exact
    z2 = random_states(model, 3, rng)
    assert close(fused(z2)[:, :, :lay.filled], kernels(z2)[:, :, :lay.filled])


def test_a_run_up_integrated_with_fused_films_keeps_its_record(cache, monkeypatch):
    """A short ramp (rkc, speed-following step, damped films, imbalance-free, kicked): the
    record of the fused right-hand side against the one-bearing kernels'."""
    model = variant("damped", cache)
    z0 = equilibrium_states(model, 1)
    layout(model).rotor_of(z0)[:, 4:6] += 1e-3
    batch = runs(1, speed=0.5, ramp=0.5 / (2 * math.pi * 20))
    fused = integrate_rotor(model, batch, 2 * math.pi * 20, z0.copy())
    import gfbopt.transient.rotor_system as rs
    monkeypatch.setattr(rs, "fusable", lambda model: False)
    kernels = integrate_rotor(model, batch, 2 * math.pi * 20, z0.copy())
    assert fused.success and kernels.success
    assert fused.evaluations == kernels.evaluations
    np.testing.assert_array_equal(fused.tau, kernels.tau)
    c = model.clearance_ref
    assert np.max(np.abs(fused.q - kernels.q)) < 1e-9 * c
    assert np.max(np.abs(fused.q[0, :, 0] - fused.q[0, 0, 0])) > 1e-3 * c    # it moved
    np.testing.assert_allclose(fused.run_min_film, kernels.run_min_film, rtol=1e-9)
