"""The study runners end to end on coarse grids (the paper-resolution runs are `gfbopt run`)."""
import json

import pandas as pd
import pytest

from gfbopt.studies import run_study

LINEAR_MAP = """
name = "tiny_linear_map"
kind = "linear_map"
title = "test"
grid = "24x8"
crossover_pairs = [["S1", "rigid"]]
published_crossovers = [{variant = "S1", against = "rigid", crossover_thesis = 0.45}]
checks = [{kind = "whirl_ratio_range"}]
[sweep]
variable = "eps"
values = [0.1, 0.6]
[fixed]
Lambda = 1.0
[model]
film = "seam"
[[variants]]
label = "rigid"
foil = "rigid"
[[variants]]
label = "S1"
foil = "simple"
compliance = 1.0
"""

TRANSIENT_MAP = LINEAR_MAP.replace('kind = "linear_map"', 'kind = "transient_map"').replace(
    'name = "tiny_linear_map"', 'name = "tiny_transient_map"\nworkers = 1').replace(
    'checks = [{kind = "whirl_ratio_range"}]\n', '')


@pytest.mark.parametrize("text, name", [(LINEAR_MAP, "tiny_linear_map"),
                                        (TRANSIENT_MAP, "tiny_transient_map")])
def test_map_studies_write_tables_crossovers_and_summaries(tmp_path, text, name):
    problem = tmp_path / f"{name}.toml"
    problem.write_text(text)
    summary = run_study(problem, results_root=tmp_path / "results")
    assert summary.passed, summary.report()
    folder = tmp_path / "results" / name
    table = pd.read_csv(folder / "map.csv")
    assert len(table) == 4 and table["success"].all()
    # with the thesis's seam, the foil bearing beats the rigid one at small eccentricity and
    # not at large (results/linear_map_eps)
    small = table[table["eps"] == 0.1].set_index("variant")["critical_mass"]
    large = table[table["eps"] == 0.6].set_index("variant")["critical_mass"]
    assert small["S1"] > small["rigid"] and large["S1"] < large["rigid"]
    crossovers = pd.read_csv(folder / "crossovers.csv")
    assert 0.1 < crossovers.loc[0, "crossover"] < 0.6
    assert crossovers.loc[0, "crossover_thesis"] == 0.45
    meta = json.loads((folder / "summary.json").read_text())
    assert meta["passed"] and meta["grid"] == "24x8" and "git_commit" in meta
    assert (folder / "critical_mass.png").is_file()


def test_a_failed_point_is_recorded_and_the_sweep_goes_on():
    from gfbopt.sweep import run_points

    rows = run_points(_maybe_fail, [{"x": 1.0}, {"x": -1.0}, {"x": 3.0}])
    assert [r["success"] for r in rows] == [True, False, True]
    assert rows[2]["y"] == 6.0 and "x must be positive" in rows[1]["message"]


def _maybe_fail(x):
    if x < 0:
        raise ValueError("x must be positive")
    return {"y": 2 * x}
