"""The stability study kinds (onset_conventions, loss_factor_map) on tiny grids: validation
before any solve, end-to-end runs, the nonlinear confirmation against the linear threshold."""
import json
import math
from pathlib import Path

import pytest

from gfbopt import ParameterError
from gfbopt.glossary import describe
from gfbopt.studies import load_study, run_study, study_from_dict
from gfbopt.studies.stability import ONSET, OVERLOAD, STABLE, UNSTABLE_ALL, UNSTABLE_LOW

ROOT = Path(__file__).resolve().parents[2]
BEARINGS = ROOT / "problems"
STATUSES = {ONSET, UNSTABLE_ALL, UNSTABLE_LOW, STABLE, OVERLOAD}


def conventions(**over) -> dict:
    return {"kind": "onset_conventions", "title": "t", "source": "a test", "grid": "24x8",
            "bearing": "bearings/ruscitto.toml", "rotor_mass_kg": 2.0, "load_newton": 20.0,
            "speed_range_rpm": [3000.0, 60000.0], "seam_angles_deg": [60.0, 180.0],
            "fine_grid_onset_rpm": {"periodic": 8840.0, "seam_180": 13080.0},
            "fine_grid_tolerance": 0.03, **over}


def loss_factor(**over) -> dict:
    return {"kind": "loss_factor_map", "title": "t", "source": "a test", "grid": "24x8",
            "loss_factors": [0.0, 0.5], "compliances": [1.0, 3.0],
            "cases": [{"label": "L2", "bearing_number": 2.0, "eccentricity": 0.4}],
            "onset": {"bearing": "bearings/ruscitto.toml", "rotor_mass_kg": 2.0,
                      "load_newton": 20.0, "speed_range_rpm": [5000.0, 60000.0]},
            "onset_compliances": [1.0],
            "confirmations": [{"case": "L2", "deflection_law": "mean", "compliance": 1.0,
                               "loss_factor": 0.3}], **over}


def plan(data: dict):
    return study_from_dict(data, name="tiny", file="tiny.toml", directory=BEARINGS)


@pytest.mark.parametrize("data, pattern", [
    (conventions(seam_angle_deg=[0.0]), (r"tiny\.toml: seam_angle_deg = \[0\.0\]: is not a "
                                         r"key .*did you mean 'seam_angles_deg'")),
    (conventions(rotor_mass=2.0), (r"rotor_mass = 2\.0: is not a key .*did you mean "
                                   r"'rotor_mass_kg'")),
    (conventions(seam_angles_deg=[400.0]), (r"seam_angles_deg\[0\] = 400\.0: must lie in "
                                            r"\[0, 360\)")),
    (conventions(fine_grid_onset_rpm={"seam_90": 1.0}), r"fine_grid_onset_rpm\.seam_90"),
    (conventions(speed_range_rpm=[6000.0, 3000.0]), r"speed_range_rpm"),
    (loss_factor(loss_factor=[0.1]), (r"loss_factor = \[0\.1\]: is not a key .*did you "
                                      r"mean 'loss_factors'")),
    (loss_factor(compliances=[0.0, 1.0]), r"compliances\[0\] = 0\.0: must be > 0"),
    (loss_factor(cases=[{"label": "L2", "bearing_number": 2.0, "eccentricty": 0.4}]),
     r"cases\[0\]\.eccentricty = 0\.4: is not a key .*did you mean 'eccentricity'"),
    (loss_factor(confirmations=[{"case": "L3", "deflection_law": "mean", "compliance": 1.0,
                                 "loss_factor": 0.3}]),
     r"confirmations\[0\]\.case = 'L3': is not a case"),
    (loss_factor(deflection_laws=["mean", "locale"]), r"deflection_laws\[1\] = 'locale'"),
])
def test_misspelt_or_wrong_keys_are_one_line_errors_before_solving(data, pattern,
                                                                     monkeypatch):
    import gfbopt.studies.stability as family

    def no_solve(*args, **kwargs):
        raise AssertionError("solved before the study was validated")

    monkeypatch.setattr(family, "run_points", no_solve)
    with pytest.raises(ParameterError, match=pattern) as info:
        plan(data)
    assert "\n" not in str(info.value)


def test_shipped_study_files_validate():
    for name in ("ruscitto_conventions", "loss_factor"):
        loaded = load_study(ROOT / "problems" / f"{name}.toml")
        assert loaded.study.name == name


def test_onset_conventions_end_to_end(tmp_path):
    result = run_study(plan(conventions()), tmp_path, workers=1)
    table = result.tables["onset.csv"]
    assert list(table["convention"]) == ["periodic", "max_film", "seam_60", "seam_180"]
    assert set(table["onset_status"]) <= STATUSES
    by = table.set_index("convention")
    # the convention matters: periodic < max-film seam < welded end opposite the load
    assert 8000 < by.loc["periodic", "onset_speed_rpm"] < 10000
    assert (by.loc["periodic", "onset_speed_rpm"] < by.loc["max_film", "onset_speed_rpm"]
            < by.loc["seam_180", "onset_speed_rpm"])
    # a welded end inside the loaded arc: no onset, said so (not a silent NaN)
    assert by.loc["seam_60", "onset_status"] != ONSET
    assert result.passed, result.checks
    out = tmp_path / "tiny"
    assert (out / "onset_speed.png").stat().st_size > 0
    summary = json.loads((out / "summary.json").read_text())
    assert any("How much the convention matters" in n for n in summary["notes"])
    for column in table.columns:
        describe(column)


def test_loss_factor_map_end_to_end_and_transient_confirmation(tmp_path):
    result = run_study(plan(loss_factor()), tmp_path, workers=1)
    cm = result.tables["critical_mass.csv"]
    assert set(cm["deflection_law"]) == {"rigid", "mean", "local"}
    assert len(cm) == 1 + 2 * 2 * 2 and cm["success"].all()
    # at fixed load, structural damping raises the critical mass of a compliant bearing
    mean = cm[cm["deflection_law"] == "mean"].set_index(["compliance", "loss_factor"])
    assert mean.loc[(3.0, 0.5), "critical_mass"] > mean.loc[(3.0, 0.0), "critical_mass"]
    onset = result.tables["onset.csv"]
    assert set(onset["onset_status"]) <= STATUSES and len(onset) == 1 + 2 * 2
    conf = result.tables["confirmation.csv"]
    assert conf["success"].all()
    assert abs(conf["nonlinear_over_linear"].iloc[0] - 1) < 0.01
    assert result.passed, result.checks
    assert any("rigid bearing" in n for n in result.notes)
    for name in ("critical_mass.png", "onset_speed.png"):
        assert (tmp_path / "tiny" / name).stat().st_size > 0
    for table in result.tables.values():
        for column in table.columns:
            describe(column)


def test_a_case_needs_exactly_one_of_eccentricity_and_load():
    with pytest.raises(ParameterError, match=r"cases\[0\].*give one of eccentricity"):
        plan(loss_factor(cases=[{"label": "L2", "bearing_number": 2.0}]))
    assert math.isfinite(plan(loss_factor(cases=[{"label": "L2", "bearing_number": 2.0,
                                                  "load": 0.6}])).plan["cases"][0]["case"][
                                                      "load"])
