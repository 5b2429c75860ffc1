"""A bearing as built whose lobes, shims or pads are finer than the grid is refused where
its model meets the grid (one line, exit 2, before any solve), by every path to a build:
``solver_for``, the solver cache and the command line."""
from pathlib import Path

import pytest

from gfbopt import Grid, SolverCache, solver_for
from gfbopt.errors import ParameterError
from gfbopt.inputs import load_bearing_file

from cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
RUSCITTO = REPO / "problems/bearings/ruscitto.toml"
LOBES = '\n[bore]\nkind = "lobes"\ncount = 10\npreload_depth = 5e-6\n'


@pytest.fixture
def lobed(tmp_path):
    path = tmp_path / "lobed.toml"
    path.write_text(RUSCITTO.read_text() + LOBES)
    return path


def test_ten_lobes_on_24_rows_are_refused(lobed):
    geometry, options = load_bearing_file(lobed)
    model = geometry.model(30000.0, **options.model_kwargs())
    with pytest.raises(ParameterError, match=r"grid n_theta = 24: must be >= 3 × 10 = 30"):
        solver_for(model, Grid(24, 8))
    with pytest.raises(ParameterError, match="grid n_theta"):
        SolverCache(Grid(24, 8))(model)
    assert solver_for(model, Grid(30, 4)).key[0] == Grid(30, 4)     # 3 rows a lobe: built


def test_the_command_refuses_before_solving(lobed):
    out = run_cli("static", "--bearing", str(lobed), "--speed-rpm", "30000", "--load-newton",
                  "20", "--grid", "24x8", cwd=REPO)
    assert out.returncode == 2 and out.stdout == ""
    err = out.stderr.strip()
    assert err.startswith("gfbopt: error: --grid n_theta = 24") and "\n" not in err
