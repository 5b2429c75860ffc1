"""The Craig–Bampton basis the two-bearing analyses use for a shaft (rotor/condensed.py)
against the full shaft of beam elements: natural frequencies on isotropic bearing springs."""
import numpy as np
import scipy.linalg as sla

from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.condensed import MODES, condensed
from gfbopt.rotor.shaft import shaft_structure

ROTOR = "problems/rotors/flexible_rotor.toml"
BEARINGS = (0.06, 0.30)       # the rotor file's bearing positions [m]
SPRING = 2e6                  # N/m at each bearing, x and y


def _frequencies_hz(structure) -> np.ndarray:
    k = structure.stiffness().copy()
    for z in BEARINGS:
        s = structure.station(z)
        k = k + SPRING * s.T @ s
    w2 = sla.eigh(k, structure.mass(), eigvals_only=True)
    return np.sqrt(np.abs(w2)) / (2 * np.pi)


def test_condensed_shaft_keeps_the_first_three_bending_pairs():
    """The first four roots are the rigid-body modes on the springs (close in the basis: the
    constraint modes span the rigid motion; measured 5e-6); the next six are the first three bending pairs.  Tolerance:
    16 held modes give 3.3e-4 (measured), 8 gave 4.9e-3 — the default must keep 5e-4."""
    shaft = shaft_structure(load_rotor(ROTOR))
    assert [b for b in BEARINGS] == [b.position for b in load_rotor(ROTOR).bearings]
    full = _frequencies_hz(shaft)
    reduced = _frequencies_hz(condensed(shaft, BEARINGS, modes=MODES))
    assert np.allclose(reduced[:4], full[:4], rtol=1e-5)      # measured 5e-6
    assert np.max(np.abs(reduced[4:10] / full[4:10] - 1)) < 5e-4
    assert full[4] > 800.0                       # a bending mode, not a rigid one
