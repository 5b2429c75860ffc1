"""A design variable of one bearing (``A:radial_clearance_um``) is described from its
quantity's glossary entry and names the bearing (the reviewer found the main job's README
listing these columns as 'not yet described')."""
import pytest

from gfbopt.glossary import GLOSSARY, describe


@pytest.mark.parametrize("column", ["radial_clearance_um", "preload_depth_um", "length_mm"])
def test_a_bearings_design_variable_is_its_quantity_of_that_bearing(column):
    unit, meaning = GLOSSARY[column]
    assert describe(f"B:{column}") == (unit, f"{meaning}, of bearing B")


def test_an_unknown_quantity_of_a_bearing_is_still_unknown():
    with pytest.raises(KeyError):
        describe("A:not_a_quantity")
