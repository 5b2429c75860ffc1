"""A bearing as built (shims, pads, bump zones) is named in one phrase by every text report that
answers for it (gfbopt.model_text.built_words): static, linear's friction, stability, capacity
and the rotor's bearing lines — never a Python repr ("pads None, zones None")."""
from pathlib import Path

import pytest

from gfbopt.model_text import built_words
from tests.cli_inprocess import run_cli

RUSCITTO = Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto.toml"
SHIMS = "\n[bore]\nkind = \"shims\"\ncount = 3\npreload_depth = 8e-6\nwidth_deg = 60.0\n"
ZONES = ("\n[[zones]]\nstart_deg = 0.0\nend_deg = 180.0\nfriction_coefficient = 0.3\n"
         "\n[[zones]]\nstart_deg = 180.0\nend_deg = 360.0\nfriction_coefficient = 0.0\n")
POINT = ("--speed-rpm", "30000", "--grid", "24x8")


@pytest.fixture()
def files(tmp_path):
    out = {}
    for name, extra in (("shims", SHIMS), ("zones", ZONES)):
        path = tmp_path / f"{name}.toml"
        path.write_text(RUSCITTO.read_text() + extra)
        out[name] = path
    return out


def test_the_phrase():
    assert built_words({"bore": "round", "zones": None, "pads_leading_end_deg": None}) == ""
    assert built_words({"bore": "shims", "bore_count": 3, "bore_preload_depth_m": 8e-6,
                        "bore_width_deg": 60.0}) == "3 shims, preload 8 µm, 60° wide"
    assert built_words({"bore": "shims", "bore_count": 3, "bore_preload_ratio": 0.4}) == \
        "3 shims, preload 0.4 c"
    assert built_words({"pads_leading_end_deg": [0.0, 120.0, 240.0]}) == "pads at 0, 120, 240°"
    assert built_words({"zones": [{"start_deg": 0.0, "end_deg": 180.0,
                                   "friction_coefficient": 0.3}]}) == \
        "bump zones 0–180° (friction coefficient 0.3)"


@pytest.mark.parametrize("command, extra", [
    ("capacity", ("--min-film-um", "5")),
    ("stability", ("--rotor-mass-kg", "2", "--load-newton", "20")),
    ("static", ("--load-newton", "20")),
])
def test_every_report_names_the_bearing_as_built(files, command, extra):
    for name, words in (("shims", "as built: 3 shims, preload "),
                        ("zones", "as built: bump zones 0–180° (friction coefficient 0.3), "
                                  "180–360°")):
        cli = run_cli(command, "--bearing", files[name], *POINT, *extra)
        assert cli.returncode == 0, cli.stderr
        assert words in cli.stdout, cli.stdout
        assert "None" not in cli.stdout and "{'" not in cli.stdout


def test_linear_names_the_bumps_friction():
    friction = RUSCITTO.parent / "ruscitto_friction.toml"
    cli = run_cli("linear", "--bearing", friction, "--load-newton", "20", *POINT)
    assert cli.returncode == 0, cli.stderr
    assert "bump friction μ_f = 0.5 (κ = 2)" in cli.stdout.splitlines()[0]
