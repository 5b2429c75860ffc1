"""The Campbell diagram's modes against a dense eigen-decomposition of the whole linearised
system (rotor states and both bearings' film and foil states; scipy.linalg.eig on the pencil
at a coarse grid, 24 × 8, where it is a few hundred states): every mode the diagram reports
is an eigenvalue of the pencil to 1e-9, and the pencil's other eigenvalues with much rotor
motion are the film-coupled ones docs/rotor.md states the diagram does not follow (one
eigenvalue per root of the rotor's frozen-coefficient estimate is followed; the stability
answer is the matched-whirl onset's, every crossing of every branch)."""
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sla

from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.campbell import MAX_WHIRL, FullSystem, system_modes
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine

ROTORS = Path(__file__).resolve().parents[2] / "problems" / "rotors"
GRID = Grid(24, 8)


def _dense(name: str, speed: float):
    rotor = resolve_rotor(load_rotor(ROTORS / name), GRID)
    states = SpeedLine(rotor).states(speed)
    full = FullSystem(rotor, states)
    values, vectors = sla.eig(full.j.toarray(), full.e.toarray())
    keep = np.isfinite(values) & (values.imag > 0) & (values.imag < 2 * MAX_WHIRL)
    dense = [(complex(values[k]), full.rotor_share(vectors[:, k])) for k in np.flatnonzero(keep)]
    return system_modes(rotor, states), dense


@pytest.mark.parametrize("name, speed, extra", [
    # the film-coupled eigenvalues (whirl ratio, rotor share) beside the diagram's modes
    ("blower.toml", 12000.0, [(0.9956, 0.628), (1.3715, 0.588)]),
    ("flexible_rotor.toml", 6000.0, [(0.4840, 0.758), (1.6030, 0.683)]),
])
def test_the_diagrams_modes_are_eigenvalues_of_the_whole_system(name, speed, extra):
    modes, dense = _dense(name, speed)
    assert len(modes) == 4
    for m in modes:                  # each an eigenvalue of the pencil, with its rotor share
        s, share = min(dense, key=lambda d: abs(d[0] - m.eigenvalue))
        assert abs(s - m.eigenvalue) <= 1e-9 * abs(s)
        assert m.rotor_share == pytest.approx(share, abs=1e-6)
    found = [m.eigenvalue for m in modes]
    others = [(s, share) for s, share in dense
              if min(abs(s - f) for f in found) > 1e-6 * abs(s)]
    strong = sorted((round(s.imag, 4), round(share, 3)) for s, share in others
                    if share >= 0.55 and s.imag < MAX_WHIRL)
    assert strong == [pytest.approx(e, abs=2e-4) for e in extra]
    # every one of them decays: the diagram's stability picture is not missing a growing mode
    assert all(s.real < 0 for s, _ in others if s.imag < MAX_WHIRL)
