"""Friction per bump zone ([[zones]] friction_coefficient)."""
from pathlib import Path

import numpy as np
import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import load_bearing
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.options import merge_options, ModelOptions
from gfbopt.linear import linear_threshold, linearise
from gfbopt.static import solve_static

ROOT = Path(__file__).resolve().parents[2]
BEARING = (ROOT / "problems/bearings/ruscitto.toml").read_text()
GRID = Grid(36, 10)


def _threshold(tmp_path, text):
    path = tmp_path / "zones.toml"
    path.write_text(BEARING + text)
    bearing = load_bearing(path)
    model = bearing.model(30000.0, **merge_options(ModelOptions(), bearing.options)
                          .model_kwargs())
    sol = solve_static(model, load=bearing.nondimensional_load(20.0), grid=GRID)
    lin = linearise(sol)
    return lin, linear_threshold(lin).critical_mass


def test_zone_friction(tmp_path):
    zones = '\n[[zones]]\nstart_deg = 0.0\nend_deg = 180.0\n{a}\n[[zones]]\nstart_deg = 180.0' \
            '\nend_deg = 360.0\n{b}\n'
    model_mu = "friction_coefficient = 0.2\n"
    # every zone at the [model]'s coefficient is the uniform friction exactly
    uniform = _threshold(tmp_path, model_mu)[1]
    same = _threshold(tmp_path, model_mu + zones.format(a="friction_coefficient = 0.2", b=""))[1]
    assert same == uniform
    # friction in the first half only: the loaded rows there slip-limited, none elsewhere
    lin, half = _threshold(tmp_path, zones.format(a="friction_coefficient = 0.2", b=""))
    bare = _threshold(tmp_path, "")[1]
    mu = np.atleast_1d(lin.friction.coefficient)
    assert set(np.round(mu, 12)) == {0.0, 0.2}
    assert np.all(lin.friction.slip[mu == 0] == 0)
    # between the bare bump and friction everywhere (Ruscitto, 30 krpm, 20 N, 36 x 10: 3.518 <
    # 3.966 < 4.090); the other half carries less load, so less stuck stiffness (3.634)
    assert bare < half < uniform
    assert half == pytest.approx(3.9665, rel=1e-4)
    other = _threshold(tmp_path, zones.format(a="", b="friction_coefficient = 0.2"))[1]
    assert bare < other < half
    with pytest.raises(ParameterError, match=r"zones\[1\]\.friction_coefficient = -0\.1: "
                                             "must be >= 0"):
        _threshold(tmp_path, zones.format(a="friction_coefficient = -0.1", b=""))
