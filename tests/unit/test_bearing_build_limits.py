"""The bearing as built ([bore], [[pads]], [[zones]]) under the same rules as [bearing], with
bounded angles and counts, refused before any solve.

Before: zones with a bump thicker than its half length were solved although [bearing] refuses
it, a zone thickness of 1e-300 gave a ZeroDivisionError, zones on a rigid foil were dropped
silently, a shim offset of 1e300° made the shims vanish, 10⁶ lobes were solved on 36 rows
(aliased) and 100 pads ended in a CasADi assertion.
"""
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import load_bearing
from gfbopt.inputs.bore import AsBuilt, BoreProfile, check_grid_resolves
from tests.cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]
RUSCITTO = (ROOT / "problems" / "bearings" / "ruscitto.toml").read_text()
HALVES = ("[[zones]]\nstart_deg = 0.0\nend_deg = 180.0\n{}\n"
          "[[zones]]\nstart_deg = 180.0\nend_deg = 360.0\n")


def _file(tmp_path, extra, text=RUSCITTO):
    path = tmp_path / "b.toml"
    path.write_text(text.replace("[model]", extra + "\n[model]"))
    return path


@pytest.mark.parametrize("zone, key, words", [
    ("bump_thickness = 5e-3", "zones[1].bump_thickness", "must be < the half bump length"),
    ("bump_thickness = 1e-300", "zones[1].bump_thickness", "must be >= 1e-06 m"),
    ("bump_half_length = 4e-3", "zones[1].bump_half_length", "2 l0 <= s"),
    ("bump_pitch = 0.07", "zones[1].bump_pitch", "<= π R"),
    ("bump_thickness = 2e-6", "zones[1].bump_thickness", "compliance S"),
])
def test_zone_bumps_obey_the_bearings_rules(tmp_path, zone, key, words):
    # the same value in [bearing] is refused with the same rule
    with pytest.raises(ParameterError) as exc:
        load_bearing(_file(tmp_path, HALVES.format(zone)))
    assert key in exc.value.name and words in exc.value.rule
    name, value = zone.split(" = ")
    text = RUSCITTO.replace(f"{name} = ", f"{name} = {value}  #", 1)
    with pytest.raises(ParameterError) as same:
        load_bearing(_file(tmp_path, "", text=text))
    assert words in same.value.rule


def test_zones_within_the_rules_give_their_own_compliance(tmp_path):
    bearing = load_bearing(_file(tmp_path, HALVES.format("bump_thickness = 80e-6")))
    built = bearing.build.nondimensional(bearing)
    thin, own = (z.compliance for z in built.zones)
    # the thinner bump is softer (S ∝ 1/t_b³ in Heshmat's formula): (101.6/80)³ = 2.05
    assert own == pytest.approx(bearing.compliance, rel=1e-12)
    assert thin / own == pytest.approx((101.6 / 80.0) ** 3, rel=0.01)


def test_zones_on_a_rigid_foil_are_refused_not_dropped(tmp_path):
    text = RUSCITTO.replace('foil = "simple"', 'foil = "rigid"')
    with pytest.raises(ParameterError, match="rigid bearing has no top foil or bumps"):
        load_bearing(_file(tmp_path, HALVES.format("bump_thickness = 80e-6"), text=text))
    zoned = load_bearing(_file(tmp_path, HALVES.format("bump_thickness = 80e-6")))
    with pytest.raises(ParameterError, match="would be ignored"):
        zoned.model(30000.0, foil="rigid")


@pytest.mark.parametrize("extra, key, words", [
    ('[bore]\nkind = "shims"\ncount = 3\npreload_ratio = 0.2\nwidth_deg = 60.0\n'
     "offset_deg = 1e300\n", "bore.offset_deg", "<= 360 deg"),
    ('[bore]\nkind = "lobes"\ncount = 1000000\npreload_ratio = 0.2\n', "bore.count", "<= 12"),
    ("[[pads]]\nleading_end_deg = -1e300\narc_deg = 90.0\n", "pads[1].leading_end_deg",
     ">= -360"),
    (HALVES.format("").replace("start_deg = 180.0", "start_deg = 1e300"), "zones[2].start_deg",
     "<= 360"),
])
def test_angles_and_counts_are_bounded(tmp_path, extra, key, words):
    with pytest.raises(ParameterError) as exc:
        load_bearing(_file(tmp_path, extra))
    assert key in exc.value.name and words in exc.value.rule


def test_more_pads_than_the_limit_are_one_line_exit_2(tmp_path):
    pads = "".join(f"[[pads]]\nleading_end_deg = {3.6 * k!r}\narc_deg = 3.0\n"
                   for k in range(100))
    path = _file(tmp_path, pads, RUSCITTO.replace("seam_angle_deg = 180.0",
                                                  "seam_angle_deg = 0.0"))
    out = run_cli("static", "--bearing", path, "--speed-rpm", "30000", "--load-newton", "10",
                  "--grid", "36x10")
    assert out.returncode == 2 and out.stdout == ""
    assert out.stderr.count("\n") == 1 and "at most 12 top-foil pads" in out.stderr


def test_a_grid_too_coarse_for_the_lobes_is_refused():
    built = AsBuilt(BoreProfile("lobes", 12, 0.2))
    check_grid_resolves(built, 36)
    with pytest.raises(ParameterError, match=r"grid n_theta = 24: must be >= 3 × 12 = 36"):
        check_grid_resolves(built, 24)
    shims = AsBuilt(BoreProfile("shims", 3, 0.2, width=0.05))
    with pytest.raises(ParameterError, match="shim width 2.865°"):
        check_grid_resolves(shims, 72)
