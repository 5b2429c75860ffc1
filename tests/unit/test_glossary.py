"""One vocabulary: study-file keys, Python names and output columns share the glossary."""
import math

import pytest

from gfbopt.glossary import GLOSSARY, describe, deviation
from gfbopt.inputs import BearingModel
from gfbopt.studies.spec import FORMULATION, GROUPS


def test_model_keys_of_study_files_are_glossary_names_and_model_fields():
    fields = set(BearingModel.__dataclass_fields__)
    for key in (*GROUPS, *FORMULATION):
        assert key in GLOSSARY, key
        assert key in fields or key == "seam_angle_deg", key


def test_published_and_deviation_columns_are_described():
    assert describe("load_yang", ("yang",))[1].endswith("published (yang)")
    unit, meaning = describe("attitude_angle_deg_error_thesis", ("thesis",))
    assert unit == "deg" and "ours − published" in meaning
    unit, meaning = describe("load_error_yang", ("yang",))
    assert unit == "-" and "ours / published − 1" in meaning
    assert describe("kxy_N_per_m") == ("N/m", "stiffness K_XY (load frame: x along the load)")
    assert describe("zyx_ausman_im")[1].startswith("impedance Z_YX (imaginary part)")
    assert describe("load_error_grid_72x20")[1].startswith("relative load error of grid 72x20")


def test_an_unknown_column_is_an_error():
    with pytest.raises(KeyError, match="'epss' is not in the glossary"):
        describe("epss")


def test_deviation_is_relative_except_for_angles():
    assert deviation("load", 1.03, 1.0) == pytest.approx(0.03)
    assert deviation("attitude_angle_deg", 30.5, 30.0) == pytest.approx(0.5)
    assert math.isnan(deviation("load", 1.0, 0.0))


@pytest.mark.parametrize("column, unit", [
    ("first_onset_speed_rpm_search_grid", "rpm"), ("first_onset_speed_rpm_default_grid", "rpm"),
    ("total_power_loss_w_search_grid", "W"), ("total_power_loss_w_default_grid", "W"),
    ("min_film_lowest_speed_um_search_grid", "µm"), ("first_mode_default_grid", "text"),
    ("first_onset_speed_rpm_relative_change", "-")])
def test_a_grid_suffix_keeps_the_unit_of_the_quantity(column, unit):
    """default_grid_check.csv: a quantity computed on the search or the default grid has
    that quantity's unit (was "-" for every suffixed column)."""
    got, meaning = describe(column)
    assert got == unit
    base = column.rsplit("_search_grid", 1)[0].rsplit("_default_grid", 1)[0]
    if base in GLOSSARY and base != column:
        assert meaning.startswith(GLOSSARY[base][1])
