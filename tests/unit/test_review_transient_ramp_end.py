"""A ramp cut short says where it ended; a ramp that cannot run is refused before any work.

blower_thermal run up 10,000 → 40,000 rpm at 20,000 rpm/s on 24 × 8 closes bearing B's film
at 15,528 rpm, t = 0.2764 s (≈ 4 s to compute).  Before, its JSON said end_speed_rpm 40,000
and duration_s 1.5 (the asked end; the glossary defines end_speed_rpm as where the ramp
ended) and the figures were titled '10,000 → 40,000 rpm' without the contact marked.

A rotor whose bearings state [journal]/[thermal] and bump friction was refused only after
the running line had been solved and the progress line printed, naming 'rotor'.

The contact numbers are the run's own (rkc, deterministic); rel 1e-3 allows another BLAS's
round-off, not another contact step (one sample ≈ 0.2 rad ≈ 2e-5 s here).  The identities
(end = contact, duration = contact time) are exact: the same floats."""
from __future__ import annotations

from pathlib import Path

import matplotlib
import pytest

from gfbopt.glossary import GLOSSARY
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.transient.rotor_analysis import rotor_ramp

matplotlib.use("Agg")
ROOT = Path(__file__).resolve().parents[2]
ROTORS = ROOT / "problems" / "rotors"


@pytest.fixture(scope="module")
def cut_short():
    system = load_rotor(ROTORS / "blower_thermal.toml", running=True)
    return rotor_ramp(system, 10000.0, 40000.0, 20000.0, grid=Grid(24, 8))


def test_the_json_says_where_the_ramp_ended_and_what_was_asked(cut_short):
    d = cut_short.to_dict()
    assert d["contact"] and d["contact_bearing"] == "B"
    assert d["contact_speed_rpm"] == pytest.approx(15528.0, rel=1e-3)
    assert d["contact_time_s"] == pytest.approx(0.2764, rel=1e-3)
    assert d["end_speed_rpm"] == d["contact_speed_rpm"]
    assert d["duration_s"] == d["contact_time_s"]
    # shaft revolutions to there: the mean speed times the time, (10,000 + 15,528)/2/60 · t
    assert d["revolutions"] == pytest.approx(
        (10000.0 + d["end_speed_rpm"]) / 2 / 60 * d["duration_s"], rel=1e-9)
    assert d["revolutions"] == pytest.approx(d["revolutions_integrated"], rel=1e-6)
    assert d["requested_end_rpm"] == 40000.0 and d["requested_duration_s"] == 1.5
    assert d["end_cause"] == "contact at bearing B"
    for key in ("end_speed_rpm", "duration_s", "requested_end_rpm", "requested_duration_s",
                "end_cause"):
        assert key in GLOSSARY, key
    words = cut_short.run_words()
    assert words == ("run-up 10,000 → 15,528 rpm at 20,000 rpm/s (asked → 40,000 rpm; "
                     "contact at bearing B at 15,528 rpm, t = 0.2764 s)")


def test_a_ramp_that_reaches_its_end_states_it_as_asked():
    system = load_rotor(ROTORS / "blower.toml")
    result = rotor_ramp(system, 8000.0, 9000.0, 100000.0, grid=Grid(24, 8),
                        linear_onset=False)
    d = result.to_dict()
    assert not d["contact"] and d["success"]
    assert d["end_speed_rpm"] == d["requested_end_rpm"] == 9000.0
    assert d["duration_s"] == d["requested_duration_s"] == pytest.approx(0.01, rel=1e-12)
    assert d["end_cause"] is None
    assert result.run_words() == "run-up 8,000 → 9,000 rpm at 100,000 rpm/s"


def test_the_figures_mark_the_contact_and_title_what_was_run(cut_short, tmp_path):
    import matplotlib.pyplot as plt

    from gfbopt.cli import rotor_time

    opened = []
    real = plt.Figure.savefig

    def keep(fig, *args, **kwargs):
        opened.append(fig)
        return real(fig, *args, **kwargs)

    plt.Figure.savefig = keep
    try:
        rotor_time._figures(cut_short, tmp_path)
    finally:
        plt.Figure.savefig = real
    assert {p.name for p in tmp_path.iterdir()} >= {"components.png", "waterfall_B.png",
                                                    "waterfall_A.png", "orbits.png"}
    label = "contact at B, 15,528 rpm, t = 0.2764 s"
    speed = cut_short.contacts[0]["contact_speed_rpm"]
    marked = 0
    for fig in opened:
        title = " ".join(t.get_text() for ax in fig.axes for t in (ax.title,))
        assert "10,000 → 15,528 rpm" in title and "asked → 40,000 rpm" in title, title
        assert "→ 40,000 rpm at" not in title
        for ax in fig.axes:
            for line in ax.get_lines():
                if line.get_label() == label:
                    marked += 1
                    data = line.get_ydata() if "Waterfall" in title else line.get_xdata()
                    assert all(v == speed for v in data)
                    assert label in [t.get_text() for t in ax.get_legend().get_texts()]
            if "Waterfall" in title and ax.get_ylabel() == "shaft speed [rpm]":
                assert ax.get_ylim()[1] >= speed
    # the two waterfalls and both panels of the components figure
    assert marked == 4
    plt.close("all")


def test_friction_on_the_running_line_is_refused_before_any_work(tmp_path, capsys):
    """blower_thermal's bearing file with friction_coefficient = 0.5 in its [model] table
    (helperH's combo case): one line naming the flag and the file keys, exit 2, nothing
    printed before it (the progress line used to come first)."""
    from gfbopt.cli import main

    source = ROOT / "problems" / "bearings" / "ruscitto_thermal.toml"
    text = source.read_text()
    assert text.count("\n[model]\n") == 1 and "friction_coefficient" not in text
    (tmp_path / "tf.toml").write_text(text.replace("\n[model]\n", "\n[model]\n"
                                                   "friction_coefficient = 0.5\n"))
    rotor = (ROTORS / "blower_thermal.toml").read_text()
    assert rotor.count('file = "../bearings/ruscitto_thermal.toml"') == 2
    (tmp_path / "rotor.toml").write_text(rotor.replace("../bearings/ruscitto_thermal.toml",
                                                       "tf.toml"))
    code = main(["rotor", str(tmp_path / "rotor.toml"), "--run-up", "10000", "20000",
                 "--rate", "20000", "--grid", "24x8"])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    line, = err.strip().splitlines()                  # no progress line: no work done
    assert line.startswith("gfbopt: error: --run-up = '10000 20000': bearing A (")
    assert line.count("tf.toml) friction_coefficient = 0.5") == 2 and "bearing B (" in line
    assert "with [journal]/[thermal]" in line and "(--orbit)" in line
