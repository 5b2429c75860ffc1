"""The flexible shaft of the example rotor file against the same shaft assembled by ROSS 3.x
(:func:`gfbopt.rotor.ross_bridge.ross_shaft_rotor`): free–free and supported (stiff pins at
the bearings) natural frequencies, and the gyroscopic matrices, from ROSS's own assembled
matrices on its lateral degrees of freedom (x, y, α, β; its axial and torsional ones do not
couple at rest).  The issue asks 0.1 %; the two codes use the same element (Timoshenko,
Cowper's κ), so the check asks 1e-6 (measured: see the commit).  Optional tier: skips with
the reason when ROSS is not importable (ROSS 3 needs Python >= 3.12)."""
from pathlib import Path

import numpy as np
import pytest
from scipy.linalg import eigh

from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.ross_bridge import (ROSS_LATERAL, RossStructure, ross_available,
                                      ross_shaft_rotor)
from gfbopt.rotor.shaft import shaft_structure
from gfbopt.rotor.structure import Structure

ROOT = Path(__file__).resolve().parents[2]
_ROSS, _WHY = ross_available()
pytestmark = pytest.mark.skipif(not _ROSS, reason=_WHY)
#: a stiff pin [N/m]: 1e4 × the shaft's lateral stiffness scale, the same in both models
PIN = 1e12
BAND = 1e-6


def _both():
    system = load_rotor(ROOT / "problems" / "rotors" / "flexible_rotor.toml")
    ours = shaft_structure(system)
    rotor = ross_shaft_rotor(ours)
    lateral = [6 * k + j for k in range(len(ours.nodes)) for j in ROSS_LATERAL]
    pick = np.ix_(lateral, lateral)
    theirs = (np.asarray(rotor.M(0.0))[pick], np.asarray(rotor.K(0.0))[pick],
              np.asarray(rotor.G())[pick])
    nodes = [ours.node_index(b.position) for b in system.bearings]
    return ours, theirs, nodes


def _frequencies(m, k, pins=(), count=8):
    k = k.copy()
    for node in pins:
        k[4 * node, 4 * node] += PIN
        k[4 * node + 1, 4 * node + 1] += PIN
    return np.sqrt(np.abs(eigh(k, m, eigvals_only=True)))[:count]


def test_free_free_and_pinned_frequencies_match_ross():  # pragma: no cover - needs the extra
    ours, (m, k, _), nodes = _both()
    mine = _frequencies(ours.mass(), ours.stiffness())
    ross = _frequencies(m, k)
    assert np.all(mine[:4] < 1e-3 * mine[4]) and np.all(ross[:4] < 1e-3 * ross[4])
    assert np.allclose(mine[4:], ross[4:], rtol=BAND, atol=0)     # the bending modes
    mine = _frequencies(ours.mass(), ours.stiffness(), nodes)
    ross = _frequencies(m, k, nodes)
    assert np.allclose(mine, ross, rtol=BAND, atol=0)


def test_gyroscopic_split_matches_ross():  # pragma: no cover - needs the extra
    """Forward and backward whirl of the pinned shaft at 30,000 rpm (state space)."""
    ours, (m, k, g), nodes = _both()
    omega = 30000.0 * np.pi / 30

    def whirl(mm, kk, gg):
        kk = kk.copy()
        for node in nodes:
            kk[4 * node, 4 * node] += PIN
            kk[4 * node + 1, 4 * node + 1] += PIN
        n = mm.shape[0]
        a = np.block([[np.zeros((n, n)), np.eye(n)],
                      [-np.linalg.solve(mm, kk), -np.linalg.solve(mm, omega * gg)]])
        lam = np.linalg.eigvals(a)
        return np.sort(lam.imag[lam.imag > 1.0])[:8]

    assert np.allclose(whirl(ours.mass(), ours.stiffness(), ours.gyroscopic()),
                       whirl(m, k, g), rtol=BAND, atol=0)


def test_a_ross_shaft_taken_in_is_gfbopts_matrix_for_matrix():  # pragma: no cover - extra
    """ROSS's assembled shaft as a gfbopt Structure (ψx = β, ψy = −α): M, G, K equal
    gfbopt's own element for element (measured 1.4e-16, 1.2e-16, 3.7e-16 of the largest
    entry: the same element, and the same gyroscopic sign), C = 0, mass, CG and stations."""
    system = load_rotor(ROOT / "problems" / "rotors" / "flexible_rotor.toml")
    ours = shaft_structure(system)
    theirs = RossStructure(ross_shaft_rotor(ours))
    assert isinstance(theirs, Structure) and theirs.dof_names == ours.dof_names
    for name in ("mass", "gyroscopic", "stiffness"):
        a, b = getattr(ours, name)(), getattr(theirs, name)()
        assert np.abs(a - b).max() <= 1e-12 * np.abs(a).max(), name
    assert not theirs.damping().any()
    assert theirs.total_mass == pytest.approx(ours.total_mass, rel=1e-12)
    assert theirs.centre_of_gravity == pytest.approx(ours.centre_of_gravity, rel=1e-12)
    for z in (0.06, 0.123, 0.4):
        assert np.allclose(theirs.station(z), ours.station(z), rtol=0, atol=1e-12)
