"""The studies of the bearing as built, end to end at a coarse grid: the onset speed against
the shim preload and the pad count, and the drag torque and power against speed and load.
Every column they write is in the glossary, and the physics comes out the way the
literature says (preload raises the onset; the power grows with speed, near Petroff's at a
light load)."""
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.glossary import describe
from gfbopt.studies import compute, study_from_dict

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"


ONSET = {"kind": "onset_as_built", "name": "t", "title": "t", "source": "test",
         "bearing": "bearings/ruscitto.toml", "grid": "24x8", "rotor_mass_kg": 2.0,
         "load_newton": 20.0, "speed_range_rpm": [8000.0, 32000.0],
         "preload_depths_um": [0.0, 8.0], "n_pads": [2.0]}


@pytest.mark.parametrize("over, key", [({"preload_depths_um": [0.0, 20.0]}, "preload_depths_um"),
                                       ({"n_pads": [1.5]}, "n_pads"),
                                       ({"speed_range_rpm": [9e3, 8e3]}, "speed_range_rpm")])
def test_onset_study_refuses_bad_levers_before_solving(over, key):
    with pytest.raises(ParameterError, match=key):
        study_from_dict({**ONSET, **over}, directory=PROBLEMS)


@pytest.mark.slow      # three onset searches: ≈ 30–50 s on a shared 2-core machine
def test_onset_against_preload_and_pads():
    """Preload 0 → 8 µm on three shims raises the onset (Kim & San Andrés 2008 measured a
    delayed onset with shimmed bearings); two pads (a second seam at 0°, on the load line)
    lower it (docs: problems/ruscitto_preload.toml).  24 × 8 grid: trends, not values."""
    loaded = study_from_dict(ONSET, directory=PROBLEMS)
    result = compute(loaded)
    table = result.tables["onset.csv"]
    for column in table.columns:
        describe(column)
    pre = table[table["variant"] == "preload"].set_index("preload_depth_um")
    assert (pre["onset_status"] == "onset").all()
    assert pre.loc[8.0, "onset_speed_rpm"] > 1.2 * pre.loc[0.0, "onset_speed_rpm"]
    pads = table[table["variant"] == "pads"].set_index("n_pads")
    assert pads.loc[2, "onset_speed_rpm"] < pre.loc[0.0, "onset_speed_rpm"]
    assert set(result.figures) == {"onset_preload.png", "onset_pads.png"}
    assert result.passed


def test_drag_and_power_against_speed_and_load():
    """Power rises with speed at each load; at a light load (5 N) the torque is within 10 %
    of Petroff's (a nearly concentric journal; the foil's deflection makes it differ)."""
    loaded = study_from_dict({
        "kind": "drag_power", "name": "t", "title": "t", "source": "test",
        "bearing": "bearings/ruscitto.toml", "grid": "36x10",
        "speeds_rpm": [10000.0, 30000.0], "loads_newton": [5.0, 50.0]}, directory=PROBLEMS)
    result = compute(loaded)
    table = result.tables["drag.csv"]
    for column in table.columns:
        describe(column)
    assert table["success"].all()
    for _, sub in table.groupby("load_newton"):
        assert sub.sort_values("speed_rpm")["power_loss_w"].is_monotonic_increasing
    light = table[table["load_newton"] == 5.0]
    assert ((light["torque_ratio"] - 1.0).abs() < 0.1).all()
    assert set(result.figures) == {"power_against_speed.png", "torque_against_load.png"}
