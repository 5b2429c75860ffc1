"""What ``gfbopt rotor`` says about its own limits: the imbalance response above the first
onset is marked as not physical (JSON, text, figure); a bearing pulled upwards by the rotor's
geometry is said in one plain sentence; the transient's options are refused where unused and
the imbalance options are used by ``--imbalance-response``; films thinner than a real
surface are warned of (the statics' plausibility flags), and speed ranges the model cannot
mean are refused before any solve.  Small grids (24 × 8) and narrow ranges."""
import json
import math
import re
from pathlib import Path

import pandas as pd
import pytest
from cli_inprocess import run_cli

from gfbopt.errors import ParameterError
from gfbopt.inputs.rotor_system import load_rotor

ROOT = Path(__file__).resolve().parents[2]
BLOWER = ROOT / "problems" / "rotors" / "blower.toml"
BEARINGS = (ROOT / "problems" / "bearings").as_posix()


def _rotor(tmp_path, name: str, edit) -> Path:
    text = edit(BLOWER.read_text().replace("../bearings/", f"{BEARINGS}/"))
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.fixture
def no_solve(monkeypatch):
    """Fail the test if the rotor analysis starts (bad input must be refused before)."""
    import gfbopt.rotor.analyse as api

    def refuse(*a, **k):
        raise AssertionError("the analysis started: bad input must be refused before")
    monkeypatch.setattr(api, "analyse_rotor", refuse)


# ------------------------------------------------------------ imbalance above the onset
def test_the_figure_shades_the_unstable_range_and_marks_its_peaks_apart():
    from gfbopt.plotting.rotor import plot_imbalance_response

    speeds = [1000.0 * k for k in range(1, 11)]
    rows = [{"speed_rpm": s, "station": st, "amplitude_um": a * s, "phase_x_deg": -s / 100}
            for st, a in (("A", 1e-4), ("B", 2e-4)) for s in speeds]
    peaks = {"A": {"peak_speed_rpm": 3000.0, "peak_amplitude_um": 0.3},
             "B": {"peak_speed_rpm": 8000.0, "peak_amplitude_um": 1.6}}
    ax_a, ax_p = plot_imbalance_response(pd.DataFrame(rows), peaks, {"forward conical": 5000.0},
                                         10000.0, unstable_from_rpm=5000.0)
    spans = [p for p in ax_a.patches if p.get_label().startswith("unstable above 5,000 rpm")]
    assert len(spans) == 1
    assert spans[0].get_x() == pytest.approx(5000.0)               # to the axis' end
    assert spans[0].get_x() + spans[0].get_width() >= 10000.0
    markers = {ln.get_label(): ln for ln in ax_a.lines if ln.get_marker() == "v"}
    above = [ln for lab, ln in markers.items() if lab.startswith("peak B")][0]
    below = [ln for lab, ln in markers.items() if lab.startswith("peak A")][0]
    assert "not physical" in above.get_label() and above.get_markerfacecolor() == "none"
    assert "not physical" not in below.get_label() and below.get_markerfacecolor() != "none"
    # above the onset each curve is thin and dashed
    dashed = [ln for ln in ax_a.lines if ln.get_linestyle() == "--"]
    assert len(dashed) == 2 and all(min(ln.get_xdata()) <= 5000.0 for ln in dashed)


def test_peaks_above_the_onset_are_flagged_in_json_and_text():
    args = ["rotor", BLOWER, "--speed-range", "5000", "25000", "--imbalance-response",
            "--grid", "24x8"]
    out = json.loads(run_cli(*args, "--json").stdout)
    ir, onset = out["imbalance_response"], out["onset_speed_rpm"]
    assert 5000 < onset < 25000 and ir["unstable_from_rpm"] == onset
    assert f"above {onset:,.0f} rpm, where the rotor is unstable" in ir["note"]
    assert "not physical" in ir["note"]
    assert ir["peaks"]
    for p in ir["peaks"].values():
        assert p["above_first_onset"] == (p["peak_speed_rpm"] >= onset)
        assert p["largest_below_onset_rpm"] < onset
        assert p["largest_below_onset_um"] <= p["peak_amplitude_um"]
    assert any(p["above_first_onset"] for p in ir["peaks"].values())   # the blower's are
    text = run_cli(*args).stdout
    for name, p in ir["peaks"].items():
        line = [ln for ln in text.splitlines() if f"peak at {name}:" in ln][0]
        assert ("where the rotor is unstable, not physical" in line) == p["above_first_onset"]
    assert f"above {onset:,.0f} rpm the rotor is unstable: the linear response there" in text


# ------------------------------------------------------------ a bearing pulled upwards
def test_a_bearing_pulled_upwards_is_said_plainly(tmp_path):
    one_side = _rotor(tmp_path, "one_side.toml", lambda t: t.replace(
        "position = -0.035 ", "position = 0.02 ").replace(
        "position = 0.065            # m\n", "position = 0.08\n"))
    args = ["rotor", one_side, "--speed-range", "5000", "6000", "--grid", "24x8"]
    out = json.loads(run_cli(*args, "--json").stdout)
    b = [x for x in out["bearing_loads"] if x["bearing"] == "B"][0]
    assert b["load_from_gravity_deg"] == pytest.approx(180.0)
    assert out["conventions"]["bearings"]["B"]["seam_angle_deg"] == pytest.approx(0.0)
    text = run_cli(*args).stdout
    said = (f"bearing B is pulled upwards: its load is {b['load_newton']:.4g} N at 180° from "
            "gravity (both bearings lie on one side of the centre of gravity), and its seam is "
            "now in the loaded arc")
    assert said in text and said in out["bearing_notes"][0]
    # the mode it makes whirl at every speed: one short line, its reason once, under the mode
    low = [m for m in out["modes"] if m["onset_status"] == "unstable at the lowest speed"]
    onset_line = [ln for ln in text.splitlines() if "onset: none" in ln][0]
    assert low and onset_line == (f"  onset: none — unstable already at 5,000 rpm, the lowest "
                                  f"speed, in {low[0]['label']}: the onset lies below the "
                                  "range (why: under the mode)")
    assert text.count(low[0]["note"]) == 1
    assert len(out["bearing_notes"]) == 1                  # A is loaded downwards
    plain = run_cli("rotor", BLOWER, "--speed-range", "5000", "6000", "--grid", "24x8")
    assert "pulled upwards" not in plain.stdout


# ------------------------------------------------------------ options refused where unused
@pytest.mark.parametrize("option", [
    ["--revolutions", "5"], ["--rate", "100"], ["--method", "rk4"], ["--method", "rkc"],
    ["--time-step", "0.1"], ["--stages", "4"], ["--perturbation", "conical"],
    ["--kick", "0.01"], ["--reference-whirl-ratio", "0.5"], ["--foil-travel-um", "10"],
    ["--window-revolutions", "10"], ["--subsync-threshold-um", "1"], ["--force"],
])
@pytest.mark.parametrize("analysis", [["--imbalance-response"], ["--campbell"], []])
def test_transient_options_are_refused_without_a_transient(option, analysis, no_solve):
    r = run_cli("rotor", BLOWER, "--speed-range", "5000", "6000", *analysis, *option)
    err = r.stderr.strip()
    assert r.returncode == 2 and len(err.splitlines()) == 1, err
    assert err.startswith(f"gfbopt: error: {option[0]} ") and "--orbit" in err, err


@pytest.mark.parametrize("option", [["--imbalance-plane", "2", "0", "0.065"],
                                    ["--imbalance-grade", "2.5"]])
def test_imbalance_options_need_the_imbalance_response(option, no_solve):
    r = run_cli("rotor", BLOWER, "--speed-range", "5000", "6000", "--campbell", *option)
    err = r.stderr.strip()
    assert r.returncode == 2 and len(err.splitlines()) == 1
    assert err.startswith(f"gfbopt: error: {option[0]} ") and "--imbalance-response" in err


def test_the_imbalance_response_uses_a_plane_from_the_command_line(tmp_path):
    """A rotor file without [[imbalance]]: the plane given on the command line is used; the
    response is linear in the amount, so twice the file's amount at the same plane doubles
    every amplitude of the blower's own response."""
    bare = _rotor(tmp_path, "bare.toml", lambda t: re.sub(
        r"\[\[imbalance\]\].*?position = 0\.065\n", "", t, flags=re.S))
    assert not load_rotor(bare).imbalance
    args = ["--speed-range", "5000", "8000", "--imbalance-response", "--grid", "24x8", "--json"]
    refused = run_cli("rotor", bare, *args)
    assert refused.returncode == 2 and "--imbalance-plane" in refused.stderr
    given = run_cli("rotor", bare, *args, "--imbalance-plane", "4", "0", "0.065")
    own = run_cli("rotor", BLOWER, *args)
    assert given.returncode == 0 and own.returncode == 0
    a, b = json.loads(given.stdout), json.loads(own.stdout)
    assert a["imbalance_planes"] == [{"name": "plane 1", "amount_g_mm": pytest.approx(4.0),
                                      "phase_deg": 0.0, "position_m": 0.065,
                                      "source": "command line"}]
    assert b["imbalance_planes"][0]["source"] == "rotor file"
    for station, p in b["imbalance_response"]["peaks"].items():
        q = a["imbalance_response"]["peaks"][station]
        assert q["peak_amplitude_um"] == pytest.approx(2.0 * p["peak_amplitude_um"], rel=1e-6)
        assert q["peak_speed_rpm"] == pytest.approx(p["peak_speed_rpm"], rel=1e-6)
    graded = json.loads(run_cli("rotor", bare, *args, "--imbalance-grade", "2.5").stdout)
    total = sum(p["amount_g_mm"] for p in graded["imbalance_planes"])
    omega = 8000 * 2 * math.pi / 60                 # U = m G/ω at HIGH of --speed-range
    assert total == pytest.approx(3.2 * 2.5e-3 / omega * 1e6, rel=1e-12)


# ------------------------------------------------------------ films and speed ranges
def test_a_film_thinner_than_a_real_surface_is_warned_of():
    args = ["rotor", BLOWER, "--speed-range", "300", "3000", "--grid", "24x8"]
    out = json.loads(run_cli(*args, "--json").stdout)
    film = {e["bearing"]: e["min_film_thickness_um"] for e in out["equilibria"]
            if e.get("speed_rpm") == 300 and "min_film_thickness_um" in e}
    assert film["A"] < 5.0
    said = f"bearing A at 300 rpm: minimum film h_min = {film['A']:.3g} µm is below 5 µm"
    assert any(w.startswith(said) for w in out["warnings"]), out["warnings"]
    assert said in run_cli(*args).stdout
    fine = json.loads(run_cli("rotor", BLOWER, "--speed-range", "20000", "30000", "--grid",
                              "24x8", "--json").stdout)
    assert not any("minimum film" in w for w in fine["warnings"])


@pytest.mark.parametrize("speeds, says", [
    (["10", "60000"], "HIGH/LOW = 6e+03 exceeds 1000"),
    (["5000", "600000"], "journal surface at 1.2e+03 m/s, above 1000 m/s"),
    (["1e-5", "1e-3"], "bearing number Λ = 1.7e-09, below 1e-06"),
])
def test_meaningless_speed_ranges_are_refused_before_any_solve(speeds, says, no_solve):
    r = run_cli("rotor", BLOWER, "--speed-range", *speeds)
    err = r.stderr.strip()
    assert r.returncode == 2 and len(err.splitlines()) == 1 and says in err, err
    assert err.startswith("gfbopt: error: --speed-range ")


@pytest.mark.parametrize("speeds", [(1e-300, 1e300), (1.0, 1e12), (10.0, 60000.0),
                                    (1e-5, 1e-3)])
def test_the_api_refuses_them_too(speeds):
    from gfbopt.rotor.analyse import analyse_rotor

    with pytest.raises(ParameterError, match="speed_range"):
        analyse_rotor(load_rotor(BLOWER), speeds)
