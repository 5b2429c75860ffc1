"""A preload-depth lever of [what_it_would_take] stops at the bearing's radial clearance: a
shim as deep as the clearance closes the film (the reviewer found the scan run to 16 µm on a
15 µm clearance, its failure reported as 'the evaluation failed at 16' under 'physical
limits [0, 16]')."""
import math

from gfbopt.design.lever_runs import answers_text, clearance_bound, LeverAnswer
from gfbopt.design.what_it_takes import Lever
from gfbopt.inputs.rotor_system import load_rotor

ROTOR = load_rotor("problems/rotors/blower.toml")


def test_preload_lever_is_bounded_by_its_bearings_clearance():
    design = {"A:radial_clearance_um": 15.0, "B:radial_clearance_um": 19.3}
    lever, note = clearance_bound(Lever("A:preload_depth_um", "µm", "A's preload", 0.0, 16.0),
                                  ROTOR, design, None)
    assert lever.high == 15.0 and lever.low == 0.0
    assert "bearing A's radial clearance 15 µm" in note and "16 µm" in note
    both, note = clearance_bound(Lever("preload_depth_um", "µm", "preload", 0.0, 30.0),
                                 ROTOR, design, None)
    assert both.high == 15.0 and "bearing A" in note      # the smaller of the two


def test_levers_inside_the_clearance_and_other_levers_are_untouched():
    design = {"A:radial_clearance_um": 15.0, "B:radial_clearance_um": 19.3}
    inside = Lever("B:preload_depth_um", "µm", "B's preload", 0.0, 16.0)
    assert clearance_bound(inside, ROTOR, design, None) == (inside, "")
    eta = Lever("loss_factor", "-", "loss factor", 0.0, 0.6)
    assert clearance_bound(eta, ROTOR, design, None) == (eta, "")


def test_the_answer_text_states_the_bound_and_why():
    a = LeverAnswer("A:preload_depth_um", "µm", "A's preload", 5.65, 0.0, 15.0, False,
                    math.nan, math.nan, math.nan, None, math.nan, 12.66, 25000.0, 9,
                    "bounded by bearing A's radial clearance 15 µm (the study's bound 16 µm "
                    "is deeper: a preload as deep as the clearance closes the film); the "
                    "evaluation failed at 15")
    text = answers_text([a], 45000.0, 19892.0)
    assert "[0, 15]" in text and "closes the film" in text and "12.66" in text
