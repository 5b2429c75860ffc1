"""The study runners end to end on coarse grids (paper resolution: `gfbopt run`)."""
import json
import math

import pandas as pd
import pytest

from gfbopt import ParameterError, analyses
from gfbopt.glossary import describe
from gfbopt.studies import compute, run_study, study_from_dict

LINEAR_MAP = """
name = "tiny_linear_map"
kind = "linear_map"
title = "test"
source = "a test"
grid = "24x8"
crossover_pairs = [["S1", "rigid"]]
published = "published.toml"
whirl_ratio_range = [0.3, 0.6]
[sweep]
variable = "eccentricity"
values = [0.1, 0.6]
[fixed]
bearing_number = 1.0
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

PUBLISHED = """
reference = "thesis"
source = "a thesis"
[curves]
rigid = {foil = "rigid"}
S1 = {foil = "simple", compliance = 1.0}
[[crossovers]]
where = "Fig 3.12"
variable = "eccentricity"
bearing_number = 1.0
variant = "S1"
against = "rigid"
crossover = 0.45
tolerance = 0.02
[[critical_masses]]
label = "simple"
where = "Fig 3.10"
curve = "S1"
eccentricity = 0.4
bearing_number = 2.0
critical_mass = 20.9
tolerance = 0.05
"""

TRANSIENT_MAP = LINEAR_MAP.replace('kind = "linear_map"', 'kind = "transient_map"').replace(
    'name = "tiny_linear_map"', 'name = "tiny_transient_map"').replace(
    'whirl_ratio_range = [0.3, 0.6]\n', 'method = "rk4"\n')


@pytest.mark.parametrize("text, name, workers", [(LINEAR_MAP, "tiny_linear_map", 1),
                                                 (TRANSIENT_MAP, "tiny_transient_map", 2)])
def test_map_studies_write_tables_crossovers_and_summaries(tmp_path, text, name, workers):
    (tmp_path / "published.toml").write_text(PUBLISHED)
    problem = tmp_path / f"{name}.toml"
    problem.write_text(text)
    result = run_study(problem, results_root=tmp_path / "results", workers=workers)
    assert result.passed, result.checks
    folder = tmp_path / "results" / name
    table = pd.read_csv(folder / "map.csv")
    assert len(table) == 4 and table["success"].all()
    # with the thesis's seam, the foil bearing beats the rigid one at small eccentricity and
    # not at large (results/linear_map_eps)
    small = table[table["eccentricity"] == 0.1].set_index("variant")["critical_mass"]
    large = table[table["eccentricity"] == 0.6].set_index("variant")["critical_mass"]
    assert small["S1"] > small["rigid"] and large["S1"] < large["rigid"]
    crossovers = pd.read_csv(folder / "crossovers.csv")
    assert 0.1 < crossovers.loc[0, "crossover"] < 0.6
    assert crossovers.loc[0, "crossover_thesis"] == 0.45
    meta = json.loads((folder / "summary.json").read_text())
    assert meta["consistency_checks_hold"] and meta["agrees_with_reference"] in ("yes", "no")
    prov = meta["provenance"]
    assert prov["options"]["grid"] == "24x8" and "source_commit" in prov
    assert prov["options"]["variants"]["S1"]["foil"] == "simple"
    assert prov["options"]["variants"]["S1"]["film"] == "seam"
    assert (folder / "critical_mass.png").is_file() and (folder / "README.md").is_file()
    index = (tmp_path / "results" / "index.md").read_text()
    assert "| consistency checks hold | agrees with the published reference |" in index
    assert f"[{name}]" in index
    if name == "tiny_linear_map":          # thresholds beside the published critical mass
        points = pd.read_csv(folder / "published_points.csv")
        assert list(points["critical_mass_thesis"]) == [20.9] and points.loc[0, "label"] == "simple"
    if name == "tiny_transient_map":
        assert prov["options"]["method"] == "rk4"
        assert (table["nonlinear_over_linear"] - 1).abs().max() < 0.01


def test_every_output_column_is_in_the_glossary(tmp_path):
    (tmp_path / "published.toml").write_text(PUBLISHED)
    loaded = study_from_dict(_toml(LINEAR_MAP), file="tiny.toml", directory=tmp_path)
    result = compute(loaded)
    for name, table in result.tables.items():
        for column in table.columns:
            unit, meaning = describe(column, ("thesis",))
            assert unit and meaning, (name, column)


def test_a_published_curve_must_be_the_variant_of_the_same_label(tmp_path):
    (tmp_path / "published.toml").write_text(PUBLISHED.replace(
        'S1 = {foil = "simple", compliance = 1.0}', 'S1 = {foil = "simple", compliance = 2.0}'))
    with pytest.raises(ParameterError, match=r"tiny\.toml: variants = 'S1': is not the bearing "
                       r"of curve 'S1' in published\.toml"):
        study_from_dict(_toml(LINEAR_MAP), file="tiny.toml", directory=tmp_path)
    (tmp_path / "published.toml").write_text(PUBLISHED.replace('curve = "S1"', 'curve = "S3"'))
    with pytest.raises(ParameterError, match=r"published\.toml: critical_masses\[0\]\.curve = "
                       r"'S3': must be one of the curves: rigid, S1"):
        study_from_dict(_toml(LINEAR_MAP), file="tiny.toml", directory=tmp_path)


def test_a_failed_point_is_recorded_and_the_study_completes(monkeypatch):
    real = analyses.linear_threshold_point

    def flaky(model, *, eccentricity=None, **kwargs):
        if eccentricity == 0.6 and model.foil == "simple":
            raise RuntimeError("solver crashed")
        return real(model, eccentricity=eccentricity, **kwargs)

    monkeypatch.setattr(analyses, "linear_threshold_point", flaky)
    no_published = _toml(LINEAR_MAP)
    del no_published["published"]
    result = compute(study_from_dict(no_published, file="tiny.toml"), workers=1)
    table = result.tables["map.csv"]
    failed = table[~table["success"]]
    assert len(table) == 4 and len(failed) == 1
    assert failed.iloc[0]["variant"] == "S1" and failed.iloc[0]["eccentricity"] == 0.6
    assert "RuntimeError: solver crashed" in failed.iloc[0]["message"]
    assert math.isnan(failed.iloc[0]["critical_mass"])
    assert not result.passed            # the convergence check reports it


def test_static_table_compares_with_published_columns():
    study = {"kind": "static_table", "title": "t", "source": "s", "grid": "36x10",
             "references": ["yang"], "model": {"film": "periodic"},
             "comparisons": [{"reference": "yang", "tolerance": {"load": 0.03,
                                                                 "attitude_angle_deg": 1.0}}],
             "rows": [{"bearing_number": 3.0, "eccentricity": 0.6,
                       "published": {"yang": {"load": 2.8631, "attitude_angle_deg": 30.04}}}]}
    result = compute(study_from_dict(study, name="mini"))
    table = result.tables["table.csv"]
    assert list(table["load_yang"]) == [2.8631]
    assert table.loc[0, "load_error_yang"] == pytest.approx(table.loc[0, "load"] / 2.8631 - 1)
    assert result.agreement == "yes" and result.passed
    assert result.options["variants"]["default"]["foil"] == "rigid"


def _toml(text):
    import tomllib

    return tomllib.loads(text)
