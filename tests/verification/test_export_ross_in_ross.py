"""A table file written by gfbopt (``gfbopt export-ross``, :func:`gfbopt.rotor.ross_bridge.
write_ross_table`) loads in ROSS 3.x with ``ross.BearingElement.load`` and gives back the same
coefficients.  Optional tier: skips with the reason when ROSS is not importable (ROSS 3 needs
Python >= 3.12; the default environment is 3.11).  Run under a venv with ROSS, e.g.
    .venv312/bin/python -m pytest -q tests/verification/test_export_ross_in_ross.py"""
import numpy as np
import pytest

from gfbopt.rotor.ross_bridge import NAMES, import_ross, ross_available, write_ross_table

_ROSS, _WHY = ross_available()
pytestmark = pytest.mark.skipif(not _ROSS, reason=_WHY)


def _tables():
    rng = np.random.default_rng(3)
    speed = np.linspace(1000.0, 6000.0, 6)
    freq = np.linspace(100.0, 3000.0, 7)
    base = np.add.outer(speed, freq)                  # smooth, as a bearing's tables are
    tables = {n: (1e3 if n[0] == "k" else 1e-1) * base * (1 + 0.01 * rng.normal(size=base.shape))
              for n in NAMES}
    return {**tables, "speed": speed, "frequency": freq}


@pytest.mark.parametrize("suffix", [".toml", ".json"])
def test_ross_loads_the_table_file(tmp_path, suffix):  # pragma: no cover - needs the extra
    ross = import_ross()
    tables = _tables()
    path = write_ross_table(tmp_path / f"bearing_A{suffix}", tables, 4, "A", 2e-5,
                            header=("gfbopt export-ross test",))
    element = ross.BearingElement.load(path)
    assert element.n == 4 and element.tag == "A"
    assert np.array_equal(element.speed, tables["speed"])
    assert np.array_equal(element.frequency, tables["frequency"])
    for name in NAMES:
        assert np.array_equal(np.asarray(getattr(element, name)), tables[name])
    # a tabulated point is returned as tabulated (PCHIP passes through the nodes)
    s, f = tables["speed"][2], tables["frequency"][5]
    k = element.K(f, speed=s)
    assert k[0, 1] == pytest.approx(tables["kxy"][2, 5], rel=1e-12)
    assert element.C(f, speed=s)[1, 0] == pytest.approx(tables["cyx"][2, 5], rel=1e-12)
