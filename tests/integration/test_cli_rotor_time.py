"""``gfbopt rotor ROTOR.toml --orbit | --run-up | --coast-down``: bad input is one line and
exit 2 before any solve; a run that hits contact says where and when and keeps its record;
a run-up's JSON and CSV carry the waterfall components, the appearance speed and the linear
onset."""
import json
import math
from pathlib import Path

import pandas as pd
import pytest

from gfbopt.cli import main
from gfbopt.glossary import describe
from gfbopt.inputs import Grid
from gfbopt.inputs.rotor_system import load_rotor

ROTOR = "problems/rotors/blower.toml"


@pytest.fixture
def no_solve(monkeypatch):
    """Fail the test if a transient model is built (i.e. something is solved)."""
    import gfbopt.transient.rotor_analysis as api

    def refuse(*a, **k):
        raise AssertionError("a model was built: bad input must be refused before")
    monkeypatch.setattr(api, "build_model", refuse)


@pytest.mark.parametrize("options, says", [
    (["--run-up", "5000", "60000", "--rate", "0"], "--rate"),
    (["--run-up", "5000", "60000", "--rate", "-100"], "--rate"),
    (["--run-up", "60000", "5000", "--rate", "1000"], "must end above its start"),
    (["--coast-down", "5000", "60000", "--rate", "1000"], "must end below its start"),
    (["--orbit", "--speed-rpm", "30000", "--revolutions", "100000"], "--force"),
    (["--run-up", "5000", "60000", "--rate", "10"], "--force"),
    (["--orbit", "--speed-rpm", "30000"], "--revolutions"),
    (["--orbit", "--speed-rpm", "30000", "--revolutions", "5", "--rate", "10"], "--rate"),
    (["--orbit", "--speed-rpm", "30000", "--revolutions", "5", "--method", "rk4",
      "--stages", "4"], "--stages"),
    (["--orbit", "--speed-rpm", "30000", "--revolutions", "5", "--imbalance-plane", "0", "0",
      "0.01"], "amount"),
])
def test_bad_input_is_one_line_and_exit_2_before_any_solve(options, says, no_solve, capsys):
    assert main(["rotor", ROTOR, *options]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and says in err, err


def test_an_imbalance_without_a_plane_is_refused(tmp_path, capsys, no_solve):
    bearings = (Path(ROTOR).parent.parent / "bearings").resolve()
    text = Path(ROTOR).read_text().replace("position = 0.065\n\n[[stations]]",
                                           "\n[[stations]]")
    assert text.count("position = 0.065") == 1          # the plane's position is gone
    bad = tmp_path / "rotor.toml"
    bad.write_text(text.replace('file = "../bearings/', f'file = "{bearings}/'))
    assert main(["rotor", str(bad), "--orbit", "--speed-rpm", "3e4", "--revolutions",
                 "5"]) == 2
    err = capsys.readouterr().err.strip()
    assert "imbalance" in err and "position" in err and len(err.splitlines()) == 1
    with pytest.raises(SystemExit) as exc:          # a plane needs its 3 numbers on the CLI
        main(["rotor", ROTOR, "--orbit", "--imbalance-plane", "1.0", "0"])
    assert exc.value.code == 2


def test_contact_is_a_result_with_time_speed_and_bearing_and_the_record_is_kept():
    from gfbopt.transient.rotor_analysis import rotor_orbit

    system = load_rotor(ROTOR)
    # 30,000 rpm is far above this rotor's onset: the kicked whirl grows into the film
    result = rotor_orbit(system, 30_000, 20, grid=Grid.parse("36x10"), imbalance_scale=0.0,
                         kick=0.02)
    d = result.to_dict()
    assert result.success and d["contact"] and d["contact_kind"] == "film"
    assert d["contact_bearing"] in ("A", "B") and d["contact_speed_rpm"] == 30_000
    assert 0 < d["contact_time_s"] < 20 * 60 / 30_000
    frame = result.orbit_frame()
    kept = frame[frame["time_s"] <= d["contact_time_s"] + 1e-12]
    assert len(kept) > 50 and kept.notna().all().all()      # the record up to contact
    assert frame["time_s"].max() == pytest.approx(d["contact_time_s"])
    # the run's smallest film is the contact film (≤ 0.02 c = 0.4 µm), at that bearing
    low = [b for b in d["bearings"] if b["bearing"] == d["contact_bearing"]][0]
    assert low["min_film_um"] <= 0.02 * 20.0 + 1e-9
    assert low["min_film_time_s"] == pytest.approx(d["contact_time_s"])
    # a whirl into contact has no settled synchronous response to report
    assert all(b.get("sync_amplitude_um") is None for b in d["bearings"])


def test_run_up_json_and_csv(tmp_path, capsys):
    out = tmp_path / "csv"
    code = main(["rotor", ROTOR, "--run-up", "5000", "9000", "--rate", "100000", "--grid",
                 "24x8", "--imbalance-grade", "2.5", "--json", "--csv", str(out)])
    assert code == 0
    d = json.loads(capsys.readouterr().out)
    assert d["run"] == "run-up" and d["rate_rpm_per_s"] == 100_000
    assert d["revolutions"] == pytest.approx(7000 / 60 * 0.04)
    assert "linear_onset_speed_rpm" in d and "subsync_appearance_rpm" in d
    assert d["provenance"]["gfbopt_version"] and d["provenance"]["options"]["method"] == "rkc"
    assert [b["bearing"] for b in d["bearings"]] == ["A", "B"]
    for b in d["bearings"]:
        assert 0 < b["min_film_um"] < 20.0 and b["peak_amplitude_um"] > 0
        # the ramp's 1× peak is the largest synchronous amplitude of its components table
        comp = pd.read_csv(out / f"components_{b['bearing']}.csv")
        k = comp["sync_amplitude_um"].idxmax()
        assert b["peak_amplitude_um"] == pytest.approx(comp["sync_amplitude_um"][k], rel=1e-7)
        assert b["peak_speed_rpm"] == pytest.approx(comp["speed_rpm"][k], rel=1e-7)
    for name in ("orbit.csv", "components_A.csv", "components_B.csv"):
        table = pd.read_csv(out / name)
        for column in table.columns:
            describe(column)                     # every column is in the glossary
    comp = pd.read_csv(out / "components_A.csv")
    assert comp["speed_rpm"].is_monotonic_increasing
    assert comp["speed_rpm"].iloc[0] > 5000 and comp["speed_rpm"].iloc[-1] < 9000


def test_coast_down_slows_the_film_and_the_imbalance_with_it():
    """A coast-down: the speed falls linearly at the rate, the 1× tracking follows it, and
    the film's Λ follows the speed in the engine (no rebuild): the run starts at the start
    speed's equilibrium and ends near the end speed's (the journal sinks as Λ falls)."""
    from gfbopt.transient.rotor_analysis import rotor_ramp

    system = load_rotor(ROTOR)
    grid = Grid.parse("24x8")
    result = rotor_ramp(system, 9000, 6000, 75_000, grid=grid, linear_onset=False)
    assert result.success and not result.run.contact.any()
    speed = result.run.speed_rpm(0)
    assert speed[0] == pytest.approx(9000) and speed[-1] == pytest.approx(6000, abs=1.0)
    assert (speed.max() - speed.min()) == pytest.approx(3000, abs=1.0)
    comp = result.tables()["components_A.csv"]
    assert comp["speed_rpm"].is_monotonic_decreasing
    # the journal at bearing A sinks along gravity as the film's speed (Λ) falls
    x, _ = result.run.journal(0, 0)
    start_eps = result.equilibria[0]["eccentricity"]
    assert x[-1] > x[0] and x[0] == pytest.approx(start_eps * math.cos(math.radians(
        result.equilibria[0]["attitude_angle_deg"])) * 20e-6, rel=1e-9)
