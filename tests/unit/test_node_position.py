"""A mode's node (gfbopt.rotor.modes, "Node"): ``node_position_m`` is where the mode's dominant
whirl |p(z)| is least along the rotor's axis as the structure moves it — along the shaft from
the shaft's own shape for a shaft (always on it), the rigid body's straight line otherwise,
with ``node_location`` saying where that is (a rigid rotor file gives the rotor no length).

Closed forms: a rigid axis p(z) = 2 (x₀ + z ψ) is least at −x₀/ψ; the conical mode of a
symmetric rigid rotor on identical bearings has its node at the centre of gravity; the second
bending mode of a uniform beam on two identical stiff supports at its ends is antisymmetric
about mid-span, its node there."""
import math

import numpy as np
import pytest
from scipy.linalg import eig, eigh

from gfbopt.inputs.shaft_file import ShaftElement, ShaftModel
from gfbopt.rotor.modes import BETWEEN, NO_NODE, ON_SHAFT, OUTSIDE, shape
from gfbopt.inputs.rotor_system import RotorBody
from gfbopt.rotor.rigid import gyroscopic_matrix, mass_matrix
from gfbopt.rotor.shaft import build_shaft

E, RHO, NU = 211e9, 7810.0, 0.3
BEARINGS = (-0.035, 0.065)


def _forward_line(x0: float, psi: float) -> np.ndarray:
    """q of a forward circular whirl whose axis is X(z) = x0 + z psi, Y = −i X (p = 2X)."""
    return np.array([x0, -1j * x0, psi, -1j * psi])


@pytest.mark.parametrize("x0, psi, where", [(0.004, 0.4, BETWEEN), (0.1, 0.4, OUTSIDE),
                                            (-0.02, 1.0, BETWEEN)])
def test_rigid_node_is_the_closed_form_of_its_line(x0, psi, where):
    out = shape(_forward_line(x0, psi), BEARINGS, ("A", "B"))
    assert out["node_position_m"] == pytest.approx(-x0 / psi, abs=1e-15)
    assert out["node_location"] == where
    assert out["node_relative_whirl"] == pytest.approx(0.0, abs=1e-12)


def test_a_translating_axis_has_no_node():
    """Before: inf (not JSON); now nan, said in words."""
    out = shape(_forward_line(0.01, 0.0), BEARINGS, ("A", "B"))
    assert math.isnan(out["node_position_m"]) and out["node_location"] == NO_NODE
    assert out["node_relative_whirl"] == 1.0


def test_symmetric_rigid_rotor_conical_mode_has_its_node_at_the_centre_of_gravity():
    """m = 3.2 kg, I_t = 0.012, I_p = 0.002 kg m² on identical isotropic springs and dampers
    at z = ±0.05 m (K = 2e6 N/m, C = 300 N s/m), 30,000 rpm: the quadratic eigenproblem's
    conical modes (the tilting ones) have p_c = 0 by symmetry, so the node is at z = 0 to
    rounding (1e-12 × the half span)."""
    a, k, c, omega = 0.05, 2e6, 300.0, 30000 * math.pi / 30
    body = RotorBody(3.2, 0.012, 0.002)
    m_mat, g_mat = mass_matrix(body), gyroscopic_matrix(body)
    kb, cb = np.zeros((4, 4)), np.zeros((4, 4))
    for z in (-a, a):
        s = np.array([[1, 0, z, 0], [0, 1, 0, z]], float)
        kb += k * s.T @ s
        cb += c * s.T @ s
    a_mat = np.block([[np.zeros((4, 4)), np.eye(4)], [-kb, -(cb + omega * g_mat)]])
    b_mat = np.block([[np.eye(4), np.zeros((4, 4))], [np.zeros((4, 4)), m_mat]])
    lam, vec = eig(a_mat, b_mat)
    conical = 0
    for j in np.flatnonzero(lam.imag > 0):
        q = vec[:4, j]
        out = shape(q, (-a, a), ("A", "B"))
        if out["shape_class"] != "conical":
            continue
        conical += 1
        assert abs(out["node_position_m"]) <= 1e-12 * a
        assert out["node_location"] == BETWEEN
    assert conical == 2                       # forward and backward


def test_second_bending_mode_of_a_supported_beam_has_its_node_at_mid_span():
    """A uniform 0.4 m steel shaft (20 mm, 20 elements) on identical springs at its ends,
    k = 1e3 × 48 E I/L³ (close to pinned: its second frequency is within 1 % of 4 × the
    first, π²·4 against π² of the pinned–pinned closed form); the second bending mode's
    shape is antisymmetric, so its least whirl on the shaft is at mid-span, 0.2 m, exactly a
    node (relative whirl at rounding) — and on the shaft, where the line through the two
    supports put it before (an antisymmetric mode's supports move in antiphase: the line's
    node is mid-span too, so the first bending mode checks the difference: the line through
    two supports moving in phase has no node, the shape's least is at a support)."""
    length, n, d = 0.4, 20, 0.02
    shaft = build_shaft(ShaftModel((ShaftElement(length / n, d, RHO, E, 0.0, NU),) * n))
    inertia = math.pi * d**4 / 64
    spring = 1e3 * 48 * E * inertia / length**3
    kmat = shaft.stiffness()
    for node in (0, n):
        kmat[4 * node, 4 * node] += spring
        kmat[4 * node + 1, 4 * node + 1] += spring
    w2, vec = eigh(kmat, shaft.mass())
    w = np.sqrt(w2)
    first, second = vec[:, 0], vec[:, 2]       # x and y planes: each frequency twice
    assert w[2] / w[0] == pytest.approx(4.0, rel=0.01)
    out = shape(second.astype(complex), (0.0, length), ("A", "B"), shaft)
    assert out["label"].endswith("bending 2")
    assert out["node_position_m"] == pytest.approx(length / 2, abs=1e-12 * length)
    assert out["node_location"] == ON_SHAFT
    assert out["node_relative_whirl"] < 1e-9
    one = shape(first.astype(complex), (0.0, length), ("A", "B"), shaft)
    assert one["label"].endswith("bending 1")
    assert 0.0 <= one["node_position_m"] <= length and one["node_location"] == ON_SHAFT
    assert min(one["node_position_m"], length - one["node_position_m"]) <= 1e-12
    assert 0 < one["node_relative_whirl"] < 1e-2       # the supports barely move


def test_flexible_rotor_node_lies_on_its_shaft():
    """The shipped flexible rotor's rigid-body-like modes on soft supports: whatever the
    shape, the node is on the 0.4 m shaft (the reviewer found 2.45 m from the bearing line)."""
    from pathlib import Path

    from gfbopt.inputs.rotor_system import load_rotor
    from gfbopt.rotor.shaft import shaft_structure

    root = Path(__file__).resolve().parents[2]
    system = load_rotor(root / "problems" / "rotors" / "flexible_rotor.toml")
    shaft = shaft_structure(system)
    positions = [b.position for b in system.bearings]
    kmat = shaft.stiffness()
    for z in positions:                        # soft isotropic supports, 1e6 N/m
        j = shaft.node_index(z)
        kmat[4 * j, 4 * j] += 1e6
        kmat[4 * j + 1, 4 * j + 1] += 1e6
    _, vec = eigh(kmat, shaft.mass())
    far = 0
    for j in range(0, 12, 2):
        q = vec[:, j].astype(complex)
        out = shape(q, positions, ("A", "B"), shaft)
        assert 0.0 <= out["node_position_m"] <= 0.4, out
        pa, pb = (shaft.station(z) @ q for z in positions)
        slope = (pb[0] - pa[0]) / (positions[1] - positions[0])
        line_node = positions[0] - pa[0] / slope if slope else math.inf
        far += not 0.0 <= line_node <= 0.4
    assert far >= 1             # the line through the bearings leaves the shaft for one mode
