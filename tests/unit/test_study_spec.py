"""Study files are validated before anything is solved: every mistake is one line naming the
file, the key's path and what was expected (gfbopt.studies.spec)."""
import time
from pathlib import Path

import pytest

from gfbopt import ParameterError, StaticSolver
from gfbopt.cli import main
from gfbopt.studies import SCHEMAS, load_study

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"

TABLE = """
name = "t"
kind = "static_table"
title = "a table"
source = "a source"
grid = "24x8"
references = ["yang"]

[model]
film = "periodic"

[[variants]]
label = "plain"
foil = "simple"

[[comparisons]]
variant = "plain"
reference = "yang"
tolerance = {load = 0.015, attitude_angle_deg = 0.5}

[[rows]]
bearing_number = 0.6
eccentricity = 0.2
published.yang = {load = 0.1806, attitude_angle_deg = 79.08}

[[rows]]
bearing_number = 3.0
eccentricity = 0.4
published.yang = {load = 1.523, attitude_angle_deg = 40.69}

[[rows]]
bearing_number = 3.0
eccentricity = 0.6
published.yang = {load = 2.8631, attitude_angle_deg = 30.04}
"""

TRANSIENT = """
kind = "transient_points"
title = "points"
source = "a source"
grid = "24x8"
[[points]]
label = "p"
eccentricity = 0.4
bearing_number = 2.0
"""


@pytest.fixture
def no_solver(monkeypatch):
    """Any attempt to build a static solver fails the test."""
    def refuse(*args, **kwargs):
        raise AssertionError("a solver was built before the study file was validated")
    monkeypatch.setattr(StaticSolver, "__init__", refuse)


def _write(tmp_path, text, name="x.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_the_valid_study_loads_without_building_a_solver(tmp_path, no_solver):
    t0 = time.perf_counter()
    loaded = load_study(_write(tmp_path, TABLE))
    assert time.perf_counter() - t0 < 1.0
    assert loaded.study.spec["variants"][0]["label"] == "plain"
    # defaults are filled in and stated
    assert loaded.study.spec["notes"] == [] and loaded.study.name == "t"


@pytest.mark.parametrize("old, new, match", [
    ('grid = "24x8"', 'gird = "72x20"',
     r"x\.toml: gird = '72x20': is not a key of a study of this kind \(did you mean 'grid'\?\)"),
    ('foil = "simple"', 'foil = "rigdi"',
     r"x\.toml: variants\[0\]\.foil = 'rigdi': must be one of rigid, simple, beam "
     r"\(did you mean 'rigid'\?\)"),
    ('bearing_number = 3.0\neccentricity = 0.6', 'bearing_number = 3.0\nepss = 0.6',
     r"x\.toml: rows\[2\]\.epss = 0\.6: is not a key of rows\[2\] \(did you mean "
     r"'eccentricity'\?\)"),
    ('tolerance = {load = 0.015', 'load_rell = 0.015\ntolerance = {load = 0.015',
     r"x\.toml: comparisons\[0\]\.load_rell = 0\.015: is not a key"),
    ('tolerance = {load = 0.015', 'tolerance = {load_rell = 0.015',
     r"x\.toml: comparisons\[0\]\.tolerance\.load_rell = 0\.015: no row publishes load_rell"),
    ('grid = "24x8"', 'grid = 72', r"x\.toml: grid = 72: must be a grid written NTHETAxNZ"),
    ('grid = "24x8"', 'grid = "24x7"', r"x\.toml: grid = '24x7': must be even"),
    ('eccentricity = 0.2', 'eccentricity = "0.2"',
     r"x\.toml: rows\[0\]\.eccentricity = '0\.2': must be a finite number"),
    ('eccentricity = 0.2\n', '', r"x\.toml: rows\[0\]\.eccentricity = None: is required"),
    ('film = "periodic"', 'film = "periodic"\ncompression_only = "yes"',
     r"x\.toml: model\.compression_only = 'yes': must be true or false"),
    ('title = "a table"\n', '', r"x\.toml: title = None: is required"),
    ('kind = "static_table"', 'kind = "static_tabel"',
     r"x\.toml: kind = 'static_tabel': must be one of .* \(did you mean 'static_table'\?\)"),
    ('reference = "yang"', 'reference = "yangg"',
     r"x\.toml: comparisons\[0\]\.reference = 'yangg': must be one of references: yang"),
    ('variant = "plain"', 'variant = "plane"',
     r"x\.toml: comparisons\[0\]\.variant = 'plane': must be one of the variants: plain"),
    ('foil = "simple"', 'foil = "rigid"\ncompliance = 1.0',
     r"x\.toml: rows\[0\]\.compliance = 1\.0: must be 0 with foil='rigid'"),
    ('bearing_number = 0.6', 'bearing_number = -0.6',
     r"x\.toml: rows\[0\]\.bearing_number = -0\.6: must be > 0"),
])
def test_a_mistake_is_one_line_naming_file_and_key(tmp_path, no_solver, old, new, match):
    assert old in TABLE
    with pytest.raises(ParameterError, match=match) as info:
        load_study(_write(tmp_path, TABLE.replace(old, new, 1)))
    assert "\n" not in str(info.value)


def test_a_misspelt_foil_is_caught_in_a_row_where_s_is_zero(tmp_path, no_solver):
    """A row with S = 0 is solved as the rigid bearing whatever its foil; the misspelling
    must still be reported, not silently replaced."""
    text = TABLE.replace("bearing_number = 0.6\n", 'bearing_number = 0.6\nfoil = "rigdi"\n')
    with pytest.raises(ParameterError, match=r"rows\[0\]\.foil = 'rigdi': must be one of"):
        load_study(_write(tmp_path, text))


@pytest.mark.parametrize("old, new, match", [
    ('grid = "24x8"', 'grid = "24x8"\ntolerance_nonlinear_linear = 0.01',
     r"tolerance_nonlinear_linear = 0\.01: is not a key .*did you mean "
     r"'nonlinear_linear_tolerance'"),
    ('grid = "24x8"', 'grid = "24x8"\nmethod = "rk5"',
     r"x\.toml: method = 'rk5': must be one of rk4"),
    ('grid = "24x8"', 'grid = "24x8"\nworkers = 2', r"x\.toml: workers = 2: is not a key"),
])
def test_transient_study_mistakes(tmp_path, no_solver, old, new, match):
    with pytest.raises(ParameterError, match=match):
        load_study(_write(tmp_path, TRANSIENT.replace(old, new, 1)))


def test_the_transient_search_defaults_to_rkc_from_the_linear_mode(tmp_path, no_solver):
    spec = load_study(_write(tmp_path, TRANSIENT)).study.spec
    assert spec["method"] == "rkc" and spec["start"] == "mode"
    assert spec["nonlinear_linear_tolerance"] == 0.01


def test_cli_validates_every_file_before_running_any(tmp_path, no_solver, capsys):
    good = _write(tmp_path, TABLE, "good.toml")
    bad = _write(tmp_path, TABLE.replace("eccentricity = 0.6", "epss = 0.6"), "bad.toml")
    status = main(["run", str(good), str(bad), "--results", str(tmp_path / "results")])
    assert status == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("gfbopt: error:") and "bad.toml: rows[2].epss" in err
    assert len(err.splitlines()) == 1
    assert not (tmp_path / "results").exists()


@pytest.mark.parametrize("path", sorted(PROBLEMS.glob("*.toml")), ids=lambda p: p.stem)
def test_every_study_in_problems_is_valid(path, no_solver):
    loaded = load_study(path)
    assert loaded.study.kind in SCHEMAS


def test_the_no_solver_guard_does_catch_a_build(no_solver):
    """The guard above is real: building any static solver fails while it is active."""
    from gfbopt import BearingModel, Grid, SolverCache

    with pytest.raises(AssertionError, match="a solver was built"):
        SolverCache()(BearingModel(bearing_number=1.0), Grid(24, 8))
