"""The reviewer's text-report defects (gfbopt/cli): ``rotor --speed-rpm N`` prints its at-speed
section; the model's bump friction and hardening are named in stability, rotor and static
reports and in the orbit figure (with a labelled radial axis); ``orbit --bearing`` prints the
minimum film in µm and 'not measured' where its JSON has null.  Grids 24x8: the texts are
checked against the same run's JSON numbers (formatted as printed), not against physics."""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from tests.cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
B = REPO / "problems" / "bearings"
R = REPO / "problems" / "rotors"
FRICTION = str(B / "ruscitto_friction.toml")


def _hardened(tmp_path) -> str:
    """ruscitto.toml with hardening bumps: [model] bump_height 20 µm, n = 3."""
    text = (B / "ruscitto.toml").read_text()
    assert text.rstrip().splitlines()[-1].startswith("loss_factor")     # [model] is last
    path = tmp_path / "hardened.toml"
    path.write_text(text + "bump_height = 20e-6\nhardening_exponent = 3\n")
    return str(path)


def _ok(*args):
    out = run_cli(*args)
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_rotor_speed_rpm_prints_the_at_speed_section():
    """45,000 rpm on the heated blower: bearing A's running clearance (16.68 µm, the JSON's
    16.6776 to 4 digits) and every mode's whirl are in the text, as in at_speed."""
    args = ("rotor", str(R / "blower_thermal.toml"), "--speed-range", "10000", "50000",
            "--grid", "24x8", "--speed-rpm", "45000")
    text = _ok(*args)
    at = json.loads(_ok(*args, "--json"))["at_speed"]
    a = next(b for b in at["bearings"] if b["bearing"] == "A")
    assert a["running_clearance_um"] == pytest.approx(16.68, abs=0.005)
    assert "at 45,000 rpm (--speed-rpm):" in text
    assert f"running clearance {a['running_clearance_um']:.4g} µm" in text
    assert "running clearance 16.68 µm" in text
    for m in at["modes"]:              # the onset list's name, else "(shape class)"
        name = m["track_label"] or f"({m['shape_label']})"
        assert f"mode {name:<22} whirl {m['whirl_frequency_hz']:.4g} Hz" in text
    for t in at["thresholds"]:
        name = t["track_label"] or f"({t['shape_label']})"
        assert f"threshold of {name}: whirl {t['whirl_frequency_hz']:.4g}" in text


def test_flexible_rotor_at_30000_rpm_in_the_text():
    text = _ok("rotor", str(R / "flexible_rotor.toml"), "--speed-range", "10000", "50000",
               "--grid", "24x8", "--speed-rpm", "30000")
    assert "at 30,000 rpm (--speed-rpm):" in text
    assert text.count("    bearing ") == 2          # each bearing's equilibrium at 30,000 rpm


def test_stability_conventions_name_the_bump_friction():
    text = _ok("stability", "--bearing", FRICTION, "--rotor-mass-kg", "2", "--load-newton",
               "20", "--speed-rpm", "30000", "--grid", "24x8")
    line = next(l for l in text.splitlines() if l.startswith("  conventions:"))
    assert line.endswith("simple foil, mean deflection law, loss factor 0, bump friction "
                         "μ_f = 0.5 (κ = 2)")


def test_rotor_bearing_lines_name_the_bump_friction():
    text = _ok("rotor", str(R / "blower_friction.toml"), "--speed-range", "10000", "40000",
               "--grid", "24x8")
    lines = [l for l in text.splitlines() if l.startswith("  bearing A:")
             or l.startswith("  bearing B:")]
    assert len(lines) == 2
    assert all("loss factor 0, bump friction μ_f = 0.5 (κ = 2)" in l for l in lines)


def test_static_names_the_hardening_bumps(tmp_path):
    path = _hardened(tmp_path)
    args = ("static", "--bearing", path, "--speed-rpm", "30000", "--load-newton", "20",
            "--grid", "24x8")
    data = json.loads(_ok(*args, "--json"))
    assert data["foil_law"] == "hardened" and data["hardening_exponent"] == 3.0
    head = _ok(*args).splitlines()[0]
    assert head == "gfbopt static — simple foil with hardening bumps (n = 3), seam film, grid 24x8"


def test_static_names_the_bump_friction():
    head = _ok("static", "--bearing", FRICTION, "--speed-rpm", "30000", "--load-newton", "20",
               "--grid", "24x8").splitlines()[0]
    assert "bump friction μ_f = 0.5 (κ = 2)" in head


ORBIT = ("orbit", "--bearing", FRICTION, "--load-newton", "20", "--speed-rpm", "30000",
         "--rotor-mass-kg", "2", "--revolutions", "30", "--grid", "24x8")


def test_orbit_figure_names_friction_and_the_radial_axis(tmp_path, monkeypatch):
    """The figure's title names μ_f, its radial axis ε = e/c [-]."""
    import gfbopt.plotting as plotting

    seen = {}
    real = plotting.plot_orbits

    def spy(*a, **k):
        ax = real(*a, **k)
        seen["title"], seen["ylabel"] = ax.get_title(), ax.get_ylabel()
        return ax
    monkeypatch.setattr(plotting, "plot_orbits", spy)
    _ok(*ORBIT, "--plot", str(tmp_path / "orb.png"))
    assert (tmp_path / "orb.png").stat().st_size > 0
    assert "bump friction μ_f = 0.5 (κ = 2)" in seen["title"]
    assert seen["ylabel"] == "eccentricity ε = e/c [-]"


def test_orbit_text_in_micrometres_and_not_measured():
    """The 2 kg rotor touches (verdict contact): growth rate and whirl ratio are null in the
    JSON and 'not measured' in the text; the minimum film is h/c × c in µm (c = 20 µm)."""
    data = json.loads(_ok(*ORBIT, "--json"))
    assert data["verdict"] == "contact"
    assert data["growth_rate"] is None and data["whirl_ratio"] is None
    text = _ok(*ORBIT)
    assert "growth rate not measured, whirl ratio not measured" in text
    assert "inf" not in text and "nan" not in text
    film_um = data["min_film"] * data["radial_clearance_m"] * 1e6
    assert math.isfinite(film_um)
    assert f"min film {film_um:.4g} µm" in text


@pytest.mark.parametrize("args", [
    ("static", "--bearing", str(B / "ruscitto.toml"), "--load-newton", "20", "--speed-rpm",
     "30000", "--grid", "24x8"),
    ("rotor", str(R / "blower.toml"), "--speed-range", "5000", "20000", "--grid", "24x8")])
def test_a_text_report_ends_with_what_made_it(args):
    from gfbopt.provenance import source_state
    from gfbopt.version import __version__

    last = _ok(*args).rstrip("\n").splitlines()[-1]
    state = source_state()
    assert last.startswith(f"  gfbopt {__version__}, ")
    if state["commit"]:
        assert f"commit {state['commit'][:8]}" in last
