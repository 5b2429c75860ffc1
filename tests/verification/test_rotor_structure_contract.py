"""Every two-bearing analysis on the structure contract (gfbopt.rotor.structure), for any n:

* the blower rotor's answers (onsets of every mode, crossings, Campbell rows, imbalance
  response) are those of the 4 × 4 rigid-body code before the contract, to 1e-9
  (tests/verification/rotor_structure_reference.json, made by rotor_structure_reference.py
  from commit 0c7535c; the crossings at 32,000 and 48,000 rpm hold two forward modes 1e-4 apart in γ, which a coarser scan misses);
* the same rigid body written as a generic structure in other coordinates (the axis's
  displacement at the two bearings, n = 4, not RigidStructure, so through the n-DOF
  arithmetic: stations, mass-weighted MAC, station-read labels) gives the same answers to
  1e-9 (the eigenvalues ν are invariant under the change of coordinates; only rounding
  differs);
* a rigid body with a flexible bending pair (n = 6, condensed by Craig–Bampton on the
  bearing stations) that is very stiff gives the rigid rotor's onsets to 1e-4 (its
  flexibility enters as 1/k_b: 1e-6 here), and a soft one runs end to end."""
import json
import math
import sys
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
import pytest

from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.campbell import system_modes
from gfbopt.rotor.condensed import condensed
from gfbopt.rotor.diagrams import campbell_diagram, synchronous_response
from gfbopt.rotor.modes import mode_label, shape
from gfbopt.rotor.rigid import transformations
from gfbopt.rotor.structure import RigidStructure, Structure
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine, rotor_onsets

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from rotor_structure_reference import (CROSSING_SPEEDS, GRID, RANGE, ROTOR,  # noqa: E402
                                       answers, close)


@dataclass(frozen=True)
class BearingCoordinates:
    """The rigid body with q = (x_A, y_A, x_B, y_B): the axis's displacement at the two
    bearings z_A, z_B [m]; x(z) = (1 − t) x_A + t x_B, t = (z − z_A)/(z_B − z_A)."""

    body: object
    z_a: float
    z_b: float
    kind: str = "generic"

    @property
    def size(self):
        return 4

    @property
    def dof_names(self):
        return ("x_A", "y_A", "x_B", "y_B")

    @property
    def total_mass(self):
        return self.body.mass

    @property
    def centre_of_gravity(self):
        return 0.0

    def _p(self):                     # q_rigid = P q
        return np.vstack([self.station(0.0), np.array([[-1, 0, 1, 0], [0, -1, 0, 1]])
                          / (self.z_b - self.z_a)])

    def mass(self):
        p = self._p()
        return p.T @ RigidStructure(self.body).mass() @ p

    def gyroscopic(self):
        p = self._p()
        return p.T @ RigidStructure(self.body).gyroscopic() @ p

    def stiffness(self):
        return np.zeros((4, 4))

    def damping(self):
        return np.zeros((4, 4))

    def station(self, z):
        t = (z - self.z_a) / (self.z_b - self.z_a)
        return np.array([[1 - t, 0, t, 0], [0, 1 - t, 0, t]], dtype=float)


@dataclass(frozen=True)
class WithBending:
    """The rigid body plus one bending pair (b_x, b_y) of shape φ(z) = u² − 1/3,
    u = (z − z_c)/h, modal mass m_b and stiffness k_b: q = (x, y, ψx, ψy, b_x, b_y)."""

    body: object
    k_b: float
    m_b: float = 0.3
    z_c: float = 0.015
    h: float = 0.09
    kind: str = "shaft"

    def phi(self, z):
        return ((z - self.z_c) / self.h) ** 2 - 1.0 / 3.0

    @property
    def shape_positions(self):
        return tuple(np.linspace(self.z_c - self.h, self.z_c + self.h, 31))

    @property
    def size(self):
        return 6

    @property
    def dof_names(self):
        return ("x", "y", "psi_x", "psi_y", "b_x", "b_y")

    @property
    def total_mass(self):
        return self.body.mass

    @property
    def centre_of_gravity(self):
        return 0.0

    def mass(self):
        b = self.body
        return np.diag([b.mass, b.mass, b.transverse_inertia, b.transverse_inertia,
                        self.m_b, self.m_b])

    def gyroscopic(self):
        g = np.zeros((6, 6))
        g[:4, :4] = RigidStructure(self.body).gyroscopic()
        return g

    def stiffness(self):
        return np.diag([0, 0, 0, 0, self.k_b, self.k_b]).astype(float)

    def damping(self):
        return np.zeros((6, 6))

    def station(self, z):
        f = self.phi(z)
        return np.array([[1, 0, z, 0, f, 0], [0, 1, 0, z, 0, f]], dtype=float)


@pytest.fixture(scope="module")
def blower():
    system = load_rotor(ROTOR)
    return system, resolve_rotor(system, GRID)


def _on(rotor, structure):
    return replace(rotor, structure=structure,
                   transforms=transformations(rotor.system, rotor.loads, structure))


def _onsets(system, rotor):
    return rotor_onsets(system, RANGE, grid=GRID, line=SpeedLine(rotor), show_progress=False,
                        coarse_grid=None)


def test_blower_answers_unchanged_by_the_contract():
    """Onsets of every mode, crossings, Campbell rows and imbalance response to 1e-9."""
    reference = json.loads((HERE / "rotor_structure_reference.json").read_text())
    now = json.loads(json.dumps(answers(), default=float))
    assert close(reference, now, 1e-9) == []
    assert [m["label"] for m in now["modes"]][:2] == ["forward conical", "forward cylindrical"]


def test_generic_structure_of_the_rigid_body_gives_its_answers(blower):
    """Bearing coordinates through the n-DOF code: onsets, crossings and labels to 1e-9."""
    system, rotor = blower
    generic = _on(rotor, BearingCoordinates(system.body, *rotor.positions))
    assert not isinstance(generic.structure, RigidStructure)
    assert isinstance(generic.structure, Structure)
    a, b = _onsets(system, rotor), _onsets(system, generic)
    assert [m.label for m in a.modes] == [m.label for m in b.modes]
    for x, y in zip(a.modes, b.modes):
        assert x.status == y.status
        if math.isfinite(x.onset_speed_rpm):
            assert y.onset_speed_rpm == pytest.approx(x.onset_speed_rpm, rel=1e-9)
            assert y.whirl_frequency_hz == pytest.approx(x.whirl_frequency_hz, rel=1e-9)
    ra, rb = SpeedLine(rotor, local=False), SpeedLine(generic, local=False)
    for speed in CROSSING_SPEEDS:
        ca, cb = ra.crossings(speed), rb.crossings(speed)
        assert [c.label for c in ca] == [c.label for c in cb]
        for x, y in zip(ca, cb):
            assert y.inertia_scale == pytest.approx(x.inertia_scale, rel=1e-9)
            assert y.whirl_ratio == pytest.approx(x.whirl_ratio, rel=1e-9)
    # the full system's modes and the imbalance response through the stations
    sa, sb = ra.states(12000.0), rb.states(12000.0)
    ma, mb = system_modes(rotor, sa), system_modes(generic, sb)
    assert [m.label for m in ma] == [m.label for m in mb]
    np.testing.assert_allclose([m.eigenvalue for m in mb], [m.eigenvalue for m in ma],
                               rtol=1e-9)
    xa, xb = synchronous_response(ra, 12000.0), synchronous_response(rb, 12000.0)
    for name in xa:
        np.testing.assert_allclose(xb[name], xa[name], rtol=1e-9)


def test_a_stiff_bending_pair_gives_the_rigid_rotors_onsets(blower):
    """k_b = 1e12 N/m (10⁶ × the bearings'): every rigid-body mode's onset and whirl
    frequency within 1e-4 (measured 2e-10); the bending pair's own crossings (μ_c ~ 1e7:
    they would whirl only on a rotor ten million times heavier) are not reported
    (matched_whirl.SHAFT_SCALE_LIMIT)."""
    system, rotor = blower
    stiff = _on(rotor, condensed(WithBending(system.body, 1e12), rotor.positions))
    assert stiff.structure.size == 6
    a, b = _onsets(system, rotor), _onsets(system, stiff)
    rigid = {m.label: m for m in a.modes}
    flexible = {m.label: m for m in b.modes}
    assert set(rigid) <= set(flexible)
    for label, x in rigid.items():
        y = flexible[label]
        assert x.status == y.status
        if math.isfinite(x.onset_speed_rpm):
            assert y.onset_speed_rpm == pytest.approx(x.onset_speed_rpm, rel=1e-4)
            assert y.whirl_frequency_hz == pytest.approx(x.whirl_frequency_hz, rel=1e-4)
    # the bending pair's own crossings (μ_c ~ 1e7) are beyond SHAFT_SCALE_LIMIT: not reported
    assert sorted(flexible) == sorted(rigid)


def test_a_soft_bending_pair_runs_end_to_end_with_bending_named(blower):
    """k_b giving a bending mode near 250 Hz: the onsets of every mode and a Campbell diagram
    run; the bending mode is named 'forward/backward bending 1' by its shape."""
    system, rotor = blower
    soft = _on(rotor, condensed(WithBending(system.body, 0.3 * (2 * math.pi * 250) ** 2),
                                rotor.positions))
    result = _onsets(system, soft)
    assert result.modes and math.isfinite(result.onset_speed_rpm)
    line = SpeedLine(soft)
    camp = campbell_diagram(line, (8000.0, 14000.0), show_progress=False,
                            onsets=result.modes)
    labels = set(camp.table["shape_label"])
    assert {"forward bending 1", "backward bending 1"} & labels
    assert labels <= {mode_label(d, k, o) for d in ("forward", "backward")
                      for k, o in (("cylindrical", 0), ("conical", 0), ("mixed", 0),
                                   ("bending", 1), ("bending", 2))}


def test_bending_labels_from_the_shape():
    """A pure bending shape (forward circle, φ = u² − 1/3: two nodes off its line) is
    'forward bending 1'; a cubic (three nodes) 'bending 2'; rigid motion is never bending."""
    body = load_rotor(ROTOR).body
    s = WithBending(body, 1e8)
    positions = (-0.035, 0.065)
    assert shape(np.array([0, 0, 0, 0, 1, -1j]), positions, "AB", s)["label"] == \
        "forward bending 1"
    assert shape(np.array([0, 0, 0, 0, 1, 1j]), positions, "AB", s)["label"] == \
        "backward bending 1"
    assert shape(np.array([1, -1j, 0, 0, 0, 0]), positions, "AB", s)["label"] == \
        "forward cylindrical"
    assert shape(np.array([0, 0, 1, -1j, 0, 0]), positions, "AB", s)["label"] == \
        "forward conical"

    @dataclass(frozen=True)
    class Cubic(WithBending):
        def phi(self, z):
            u = (z - self.z_c) / self.h
            return u**3 - 0.6 * u

    assert shape(np.array([0, 0, 0, 0, 1, -1j]), positions, "AB", Cubic(body, 1e8))[
        "label"] == "forward bending 2"
