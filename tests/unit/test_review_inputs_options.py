"""A flag overrides only what it names (review defect 1): ``--foil rigid`` on a bearing file
that states ``film = "seam"`` keeps the file's seam, and a file's friction that the stated
foil cannot carry is refused in one line naming --foil and the file key (before: the whole
[model] table was dropped, the film went periodic and μ_f vanished silently)."""
import json
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import load_bearing
from gfbopt.inputs.options import ModelOptions, merge_options

from tests.cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]
RUSCITTO = ROOT / "problems/bearings/ruscitto.toml"
FRICTION = ROOT / "problems/bearings/ruscitto_friction.toml"
STABILITY = ("stability", "--rotor-mass-kg", "2", "--load-newton", "20", "--speed-rpm",
             "30000", "--grid", "24x8", "--json")


def test_foil_rigid_keeps_the_files_seam():
    resolved = merge_options(ModelOptions(foil="rigid"), load_bearing(RUSCITTO).options)
    assert (resolved.foil, resolved.film, resolved.seam_angle_deg) == ("rigid", "seam", 180.0)
    assert (resolved.deflection_law, resolved.loss_factor) == ("mean", 0.0)


def test_a_rigid_bearing_whose_film_nobody_states_is_periodic(tmp_path):
    path = tmp_path / "plain.toml"          # the Ruscitto bearing without its [model] table
    path.write_text(RUSCITTO.read_text().split("[model]")[0])
    resolved = merge_options(ModelOptions(foil="rigid"), load_bearing(path).options)
    assert (resolved.film, resolved.seam_angle_deg) == ("periodic", None)


def _critical_mass(*extra):
    out = run_cli(*STABILITY, "--bearing", str(RUSCITTO), "--foil", "rigid", *extra, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)["critical_mass_kg"]


def test_foil_rigid_answers_as_with_the_seam_stated():
    """The reviewer's numbers (24x8, 2 kg, 20 N, 30,000 rpm): M̄c = 4.519 (critical mass
    0.4578 kg) with the file's seam, 1.413 (0.1432 kg) with a periodic film; the flag alone
    gave the periodic answer and now gives the seam's to round-off."""
    alone, seam, periodic = (_critical_mass(), _critical_mass("--film", "seam"),
                             _critical_mass("--film", "periodic"))
    assert alone == pytest.approx(seam, rel=1e-12)
    assert seam == pytest.approx(0.4578, abs=5e-5) and periodic == pytest.approx(0.1432, abs=5e-5)


@pytest.mark.parametrize("command", ["static", "stability"])
@pytest.mark.parametrize("foil", ["rigid", "beam"])
def test_a_foil_that_cannot_carry_the_files_friction_is_refused(command, foil):
    args = (("static", "--load-newton", "20", "--speed-rpm", "30000", "--grid", "24x8")
            if command == "static" else STABILITY)
    out = run_cli(*args, "--bearing", str(FRICTION), "--foil", foil, cwd=ROOT)
    line = out.stderr.strip()
    assert out.returncode == 2 and len(line.splitlines()) == 1 and out.stdout == ""
    assert f"--foil = '{foil}'" in line and "model.friction_coefficient = 0.5" in line


def test_the_api_refuses_the_same_and_a_stated_override_is_kept():
    base = load_bearing(FRICTION).options
    with pytest.raises(ParameterError, match=r"^foil = 'rigid': .*model\.friction_coefficient"):
        merge_options(ModelOptions(foil="rigid"), base)
    # the file's own foil, or a bump option stated alongside, is not refused
    kept = merge_options(ModelOptions(foil="simple"), base)
    assert (kept.friction_coefficient, kept.friction_stiffness_ratio) == (0.5, 2.0)
    lossy = ModelOptions(film="seam", seam_angle_deg=180.0, foil="simple", loss_factor=0.2)
    with pytest.raises(ParameterError, match=r"model\.loss_factor = 0\.2: the rigid foil"):
        merge_options(ModelOptions(foil="rigid"), lossy)
    assert merge_options(ModelOptions(foil="rigid", loss_factor=0.0), lossy).loss_factor == 0.0
