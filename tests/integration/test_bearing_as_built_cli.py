"""The bearing as built from files and the command line: the [bore], [[pads]], [[zones]]
tables, bad input (one line, exit 2, before any solve), ``gfbopt capacity`` (load capacity
and lift-off: monotone curves, h_min at the limit), and the torque columns of the outputs."""
import json
import math
import subprocess
from pathlib import Path

import pytest

from gfbopt import Grid
from gfbopt.errors import ParameterError
from gfbopt.inputs import load_bearing, load_bearing_file
from gfbopt.rotor.capacity import lift_off_speed, load_capacity

from cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
RUSCITTO = REPO / "problems/bearings/ruscitto.toml"
GRID = Grid(24, 8)        # trends and the limit, not converged values


def gfbopt(*args: str) -> subprocess.CompletedProcess:
    # in this process (tests/cli_inprocess.py: same main, exit status and output)
    return run_cli(*args, cwd=REPO)


def _file(tmp_path, extra: str) -> str:
    path = tmp_path / "bearing.toml"
    path.write_text(RUSCITTO.read_text() + "\n" + extra)
    return str(path)


SHIMS = """
[bore]
kind = "shims"
count = 3
preload_depth = 5e-6
width_deg = 60.0
"""


def test_file_tables_reach_the_model_and_every_output(tmp_path):
    """A shimmed, three-pad, two-zone bearing file: the model carries its preload over c,
    pads and zone compliances (S from the bump formula: thinner bumps, softer zone), and
    ``gfbopt static --json`` prints them with the torque and power."""
    text = SHIMS + "".join(f"""
[[pads]]
leading_end_deg = {a}
arc_deg = 120.0
""" for a in (60.0, 180.0, 300.0)) + """
[[zones]]
start_deg = 0.0
end_deg = 180.0
bump_thickness = 80e-6
[[zones]]
start_deg = 180.0
end_deg = 360.0
"""
    path = _file(tmp_path, text)
    geometry = load_bearing(path)
    model = geometry.model(45000, film="seam", seam_angle_deg=180.0)
    built = model.as_built
    assert built.bore.preload == pytest.approx(0.25, rel=1e-12)        # 5 µm / 20 µm
    assert [round(math.degrees(p.leading_end), 9) for p in built.pads] == [60, 180, 300]
    soft, stiff = (z.compliance for z in built.zones)
    assert soft == pytest.approx(geometry.compliance * (101.6 / 80.0) ** 3, rel=1e-12)
    assert stiff == pytest.approx(geometry.compliance, rel=1e-12)
    out = gfbopt("static", "--bearing", path, "--speed-rpm", "45000", "--load-newton", "20",
                 "--grid", "36x10", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["bore"] == "shims" and data["bore_preload_ratio"] == pytest.approx(0.25)
    assert data["pads_leading_end_deg"] == pytest.approx([60, 180, 300])
    assert len(data["zones_deg"]) == 2
    assert data["power_loss_w"] == pytest.approx(
        data["drag_torque_nm"] * 45000 * math.pi / 30, rel=1e-12)
    assert 0.5 < data["torque_ratio"] < 2.0


@pytest.mark.parametrize("extra, name, words", [
    ("[bore]\nkind = 'shims'\ncount = 3\npreload_depth = 20e-6\nwidth_deg = 60.0\n",
     "bore.preload_depth", "closes the film"),
    ("[bore]\nkind = 'lobes'\ncount = 3\npreload_ratio = 1.0\n", "bore.preload", "1 + B"),
    ("[bore]\nkind = 'shims'\ncount = 3\npreload_ratio = 0.2\nwidth_deg = -10.0\n",
     "bore.width_deg", "negative"),
    ("[[pads]]\nleading_end_deg = 180.0\narc_deg = 200.0\n[[pads]]\nleading_end_deg = 300.0\n"
     "arc_deg = 100.0\n", "pads", "overlapping pads"),
    ("[[pads]]\nleading_end_deg = 180.0\narc_deg = -5.0\n", "pads[1].arc_deg", "negative"),
    ("[[zones]]\nstart_deg = 0.0\nend_deg = 200.0\n[[zones]]\nstart_deg = 180.0\n"
     "end_deg = 360.0\n", "zones", "overlapping zones"),
    ("[[zones]]\nstart_deg = 0.0\nend_deg = 170.0\n[[zones]]\nstart_deg = 180.0\n"
     "end_deg = 360.0\n", "zones", "cover the bore"),
    ("[[zones]]\nstart_deg = 90.0\nend_deg = 10.0\n", "zones[1].end_deg", "negative"),
])
def test_bad_as_built_input_is_refused_before_solving(tmp_path, extra, name, words):
    """Each rule: one ParameterError naming the parameter, value and rule, raised while the
    file is read or the model built (before any solver exists)."""
    with pytest.raises(ParameterError) as err:
        load_bearing(_file(tmp_path, extra)).model(30000.0, film="seam", seam_angle_deg=180.0)
    assert name in str(err.value) and words in str(err.value), str(err.value)


@pytest.mark.parametrize("extra, name, words", [
    (SHIMS.replace("5e-6", "20e-6"), "bore.preload_depth", "20 µm >= clearance"),
    ("[bore]\nkind = 'shims'\ncount = 3\npreload_ratio = 0.2\nwidth_deg = -10.0\n",
     "bore.width_deg", "negative"),
    ("[[pads]]\nleading_end_deg = 180.0\narc_deg = 200.0\n[[pads]]\nleading_end_deg = 300.0\n"
     "arc_deg = 100.0\n", "pads", "overlapping pads"),
    ("[[pads]]\nleading_end_deg = 180.0\narc_deg = -5.0\n", "pads[1].arc_deg", "negative"),
    ("[[zones]]\nstart_deg = 0.0\nend_deg = 170.0\n[[zones]]\nstart_deg = 180.0\n"
     "end_deg = 360.0\n", "zones", "cover the bore"),
    ("[[zones]]\nstart_deg = 90.0\nend_deg = 10.0\n", "zones[1].end_deg", "negative")])
def test_bad_as_built_input_is_one_line_exit_2(tmp_path, extra, name, words):
    """From the command line: one line, exit 2, no traceback; [bore], [[pads]] and [[zones]]
    errors alike name the file, then the key."""
    out = gfbopt("static", "--bearing", _file(tmp_path, extra),
                 "--speed-rpm", "30000", "--load-newton", "20", "--grid", "36x10")
    assert out.returncode == 2, out.stderr
    line = out.stderr.strip()
    assert "\n" not in line and "Traceback" not in line
    assert line.startswith(f"gfbopt: error: bearing.toml: {name} = ") and words in line, line


def test_capacity_curve_monotone_and_on_the_limit():
    """Round bore, 30,000 rpm, 5 µm: along the load continuation h_min falls strictly and ε
    rises (physics: a heavier load pushes the journal out); the answer's h_min is the limit
    to 1e-6 relative (Brent to 1e-13); the power loss rises with the load there."""
    geometry, options = load_bearing_file(RUSCITTO)
    result = load_capacity(geometry, 30000.0, 5.0, options=options, grid=GRID)
    assert result.success, result.message
    assert result.min_film_thickness_um == pytest.approx(5.0, rel=1e-6)
    rows = sorted((r for r in result.curve if r["success"]), key=lambda r: r["load_newton"])
    films = [r["min_film_thickness_um"] for r in rows]
    eps = [r["eccentricity"] for r in rows]
    assert all(b < a for a, b in zip(films, films[1:]))
    assert all(b > a for a, b in zip(eps, eps[1:]))
    assert rows[0]["load_newton"] < result.to_dict()["load_capacity_newton"] < rows[-1][
        "load_newton"]


def test_lift_off_monotone_on_the_limit_and_no_lift_off():
    """Round bore, 20 N, 5 µm: h_min rises strictly with speed along the curve and equals
    the limit at the lift-off speed (≤ 1e-6 relative); a range that ends below it says
    "no lift-off below N rpm"."""
    geometry, options = load_bearing_file(RUSCITTO)
    result = lift_off_speed(geometry, 20.0, 5.0, options=options, grid=GRID)
    assert result.success, result.message
    assert result.min_film_thickness_um == pytest.approx(5.0, rel=1e-6)
    rows = sorted((r for r in result.curve if r["success"]), key=lambda r: r["speed_rpm"])
    films = [r["min_film_thickness_um"] for r in rows]
    assert all(b > a for a, b in zip(films, films[1:]))
    none = lift_off_speed(geometry, 20.0, 5.0, options=options, grid=GRID,
                          max_speed_rpm=0.5 * result.value)
    assert not none.success and math.isnan(none.value)
    assert none.answer.startswith(f"no lift-off below {0.5 * result.value:.6g} rpm")


def test_capacity_command_contract(tmp_path):
    figure = tmp_path / "lift.png"
    out = gfbopt("capacity", "--bearing", str(RUSCITTO), "--lift-off", "--load-newton", "20",
                 "--min-film-um", "5", "--grid", "24x8", "--json", "--figure", str(figure))
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    for key in ("lift_off_speed_rpm", "answer", "curve", "conventions", "provenance"):
        assert key in data
    assert figure.stat().st_size > 10_000


@pytest.mark.parametrize("args, name", [
    (["--min-film-um", "25", "--speed-rpm", "30000"], "--min-film-um"),
    (["--min-film-um", "5"], "--speed-rpm"),
    (["--min-film-um", "5", "--lift-off"], "--load-newton"),
    (["--min-film-um", "5", "--speed-rpm", "3e4", "--load-newton", "20"], "--load-newton")])
def test_capacity_command_bad_input(capsys, args, name):
    """In-process (the same main() as the console script): one line, exit 2."""
    from gfbopt.cli import main

    assert main(["capacity", "--bearing", str(RUSCITTO), "--grid", "24x8", *args]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"gfbopt: error: {name}") and "\n" not in err


def test_python_api_refuses_bad_preload_before_solving():
    geometry = load_bearing(RUSCITTO)
    from gfbopt.inputs.bore_si import BearingBuild, BoreSpec

    with pytest.raises(ParameterError, match="preload 25 µm >= clearance 20 µm"):
        geometry.__class__(**{**vars(geometry), "build": BearingBuild(
            BoreSpec("lobes", 3, preload_depth=25e-6))})
