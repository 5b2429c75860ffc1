"""A study's variant labels name what differs between its variants, in the words of the text
reports (gfbopt.model_text): the bumps' friction and hardening too, so two variants that
differ in μ_f or n never share a label."""
from pathlib import Path

from gfbopt.inputs import load_bearing
from gfbopt.studies.base import variant_titles

BEARING = Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto.toml"


def test_friction_and_hardening_are_named_when_they_differ():
    b = load_bearing(BEARING)
    titles = variant_titles({
        "plain": b.model(20000.0),
        "rubbing": b.model(20000.0, friction_coefficient=0.5, friction_stiffness_ratio=2.0),
        "hardened": b.model(20000.0, hardening_exponent=3.0, hardening_limit=0.8),
        "rigid": b.model(20000.0, foil="rigid")})
    assert titles["plain"] == f"simple foil, S = {b.compliance:.3g}"
    assert titles["rubbing"] == (f"simple foil, S = {b.compliance:.3g}, "
                                 "bump friction μ_f = 0.5 (κ = 2)")
    assert titles["hardened"] == (f"simple foil with hardening bumps (n = 3), "
                                  f"S = {b.compliance:.3g}")
    assert titles["rigid"] == "rigid bearing"
    assert len(set(titles.values())) == 4


def test_what_every_variant_shares_is_left_out():
    b = load_bearing(BEARING)
    titles = variant_titles({
        "soft": b.model(20000.0, friction_coefficient=0.5),
        "film": b.model(20000.0, friction_coefficient=0.5, film="seam", seam_angle_deg=180.0)})
    assert titles == {"soft": "periodic film", "film": "seam 180° from the load"}
