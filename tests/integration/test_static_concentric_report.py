"""``gfbopt static --eccentricity 0`` with a bore: the text says what the JSON says — the load
is the film force's magnitude and its direction is printed (no attitude angle); the
glossary names both columns."""
import json
import re
from pathlib import Path

from gfbopt.glossary import describe

from cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
SHIMS = '\n[bore]\nkind = "shims"\ncount = 3\npreload_depth = 5e-6\nwidth_deg = 60.0\n'


def test_concentric_text_gives_the_film_force_direction(tmp_path):
    bearing = tmp_path / "shims.toml"
    bearing.write_text((REPO / "problems/bearings/ruscitto.toml").read_text() + SHIMS)
    args = ("static", "--bearing", str(bearing), "--speed-rpm", "30000", "--eccentricity",
            "0", "--film", "seam", "--grid", "24x8")
    data = json.loads(run_cli(*args, "--json", cwd=REPO).stdout)
    text = run_cli(*args, cwd=REPO).stdout
    assert data["eccentricity"] == 0.0 and data["load"] == data["film_force"] > 0
    assert 0.0 < data["film_force_angle_deg"] < 360.0
    match = re.search(r"film force direction +([0-9.]+) deg from the load line", text)
    assert match and float(match.group(1)) == round(data["film_force_angle_deg"], 1)
    assert "attitude angle          none" in text and "nan" not in text


def test_glossary_names_the_film_force_columns():
    assert describe("film_force")[0] == "-" and "magnitude" in describe("film_force")[1]
    unit, meaning = describe("film_force_angle_deg")
    assert unit == "deg" and "direction of rotation" in meaning
