"""A design study refuses, before any solve and in one line, what would silently change
nothing or mean something else (the reviewer's findings): a re-check grid coarser than the
search grid, --max-points (a design has a budget, not points), and a film limit that was
written in metres."""
import copy
import subprocess
import sys
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import read_toml
from gfbopt.studies import study_from_dict

ROOT = Path(__file__).resolve().parents[2]
FILE = ROOT / "problems" / "rotor_bearing_design.toml"
NAME = "problems/rotor_bearing_design.toml"


def _refusal(**top) -> str:
    data = copy.deepcopy(read_toml(FILE))
    data.update(top)
    with pytest.raises(ParameterError) as info:
        study_from_dict(data, name="t", file=NAME, directory=FILE.parent).plan
    text = str(info.value)
    assert "\n" not in text
    return text


@pytest.mark.parametrize("grid", ["12x4", "36x8", "24x10"])
def test_a_default_grid_coarser_than_the_search_grid_is_refused(grid):
    text = _refusal(grid=grid, search_grid="36x10")
    assert f"grid = '{grid}'" in text and "search_grid '36x10'" in text


def test_an_equal_or_finer_default_grid_plans():
    data = copy.deepcopy(read_toml(FILE))
    data.update(grid="36x10", search_grid="36x10")
    assert study_from_dict(data, name="t", file=NAME, directory=FILE.parent).plan is not None


@pytest.mark.parametrize("key", ["min_film_um", "lift_off_film_um", "capacity_film_um"])
def test_a_film_limit_in_metres_is_refused(key):
    text = _refusal(**{key: 1.5e-6})
    assert key in text and ">= 0.01 µm" in text


def test_max_points_on_a_design_study_is_refused_with_exit_2(tmp_path):
    run = subprocess.run([sys.executable, "-m", "gfbopt", "run", NAME, "--max-points", "3",
                          "--results", str(tmp_path)], cwd=ROOT, capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 2
    assert "--max-points = 3" in run.stderr and "no points to cap" in run.stderr
    assert not any(tmp_path.iterdir())
