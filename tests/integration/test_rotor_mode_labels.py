"""One name per mode in every output of ``gfbopt rotor``: the text, the JSON, the CSV files and
the Campbell figure's legend of one run give each mode the same label, and no two Campbell
tracks share one (gfbopt.rotor.tracking.name_tracks).

The rotor is the blower of problems/rotors/blower.toml made heavier (5 kg, inertias scaled
with the mass): its forward conical and forward cylindrical onsets fall into one interval of
the Campbell diagram at nearly the same frequency, where the tracks' names used to be taken
from the last onset matched (both tracks "forward cylindrical", none "forward conical")."""
import contextlib
import io
import json
import math
import re
from pathlib import Path

import pandas as pd
import pytest

from gfbopt.cli import main
from gfbopt.cli import rotor as rotor_cli

ROOT = Path(__file__).resolve().parents[2]
MASS = 5.0


def heavy_rotor(folder: Path, mass: float = MASS) -> Path:
    """blower.toml with ``mass`` [kg] and its inertias scaled by the same factor."""
    text = (ROOT / "problems" / "rotors" / "blower.toml").read_text()
    scale = mass / 3.2
    text = text.replace("mass = 3.2 ", f"mass = {mass:g} ")
    text = text.replace("transverse_inertia = 0.012", f"transverse_inertia = {0.012 * scale:.6g}")
    text = text.replace("polar_inertia = 0.002", f"polar_inertia = {0.002 * scale:.6g}")
    text = text.replace("../bearings/", f"{(ROOT / 'problems' / 'bearings').as_posix()}/")
    path = folder / "heavy.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("labels")
    rotor = heavy_rotor(folder)
    legends, printed = {}, []
    original_emit = rotor_cli.emit

    def emit_both(out, as_json, report, options):       # one run, read as JSON and as text
        original_emit(out, True, report, options)
        printed.append(report())

    def keep_legend(fig, path, *args, **kwargs):
        legends[Path(path).name] = [t.get_text() for ax in fig.axes
                                    if ax.get_legend() is not None
                                    for t in ax.get_legend().get_texts()]
        return str(path)

    mp = pytest.MonkeyPatch()
    mp.setattr(rotor_cli, "emit", emit_both)
    mp.setattr("gfbopt.plotting.core.save_figure", keep_legend)
    buffer = io.StringIO()
    try:
        with contextlib.redirect_stdout(buffer):
            code = main(["rotor", str(rotor), "--speed-range", "5000", "30000", "--campbell",
                         "--campbell-speeds", "10", "--grid", "24x8", "--json",
                         "--csv", str(folder / "csv"), "--plot", str(folder / "fig")])
    finally:
        mp.undo()
    assert code == 0
    out = json.loads(buffer.getvalue().splitlines()[0])
    return {"json": out, "text": printed[0], "legend": legends["campbell.png"],
            "campbell": pd.read_csv(folder / "csv" / "campbell.csv"),
            "modes": pd.read_csv(folder / "csv" / "modes.csv")}


def test_no_two_tracks_share_a_label(run):
    names = run["campbell"].groupby("mode")["track_label"].agg(set)
    assert all(len(s) == 1 for s in names), "one name per track in campbell.csv"
    labels = [next(iter(s)) for s in names]
    assert len(labels) == len(set(labels)), labels
    assert "label" not in run["campbell"].columns      # the row's shape is `shape_label`
    assert set(run["campbell"]["shape_label"]) <= {
        f"{d} {k}" for d in ("forward", "backward") for k in ("cylindrical", "conical", "mixed")}


def test_each_mode_has_one_label_in_text_json_csv_and_legend(run):
    out, text, legend, table = run["json"], run["text"], run["legend"], run["campbell"]
    onsets = [m for m in out["modes"] if m["onset_speed_rpm"] is not None
              and math.isfinite(m["onset_speed_rpm"])]
    assert {m["label"] for m in onsets} == {"forward conical", "forward cylindrical"}
    assert list(run["modes"]["label"]) == [m["label"] for m in out["modes"]]
    assert f"first to whirl: {out['first_mode']} from {out['onset_speed_rpm']:,.0f} rpm" in text
    speeds = sorted(table["speed_rpm"].unique())
    width = speeds[1] - speeds[0]
    csv_tracks = table.groupby("mode").first()
    json_tracks = {t["mode"]: t["label"] for t in out["campbell"]["tracks"]}
    assert json_tracks == csv_tracks["track_label"].to_dict()
    legend_tracks = {int(m.group(1)): m.group(2) for m in
                     (re.fullmatch(r"mode (\d+): (.+)", t) for t in legend) if m}
    assert legend_tracks == json_tracks
    text_tracks = text.split("tracks: ", 1)[1].splitlines()[0]
    for number, label in json_tracks.items():
        assert re.search(rf"(^|; ){number} {re.escape(label)}( \(damping|;|$)", text_tracks)
    for m in onsets:
        # the text's line of the mode, the figure's onset line and one track, all one name
        assert re.search(rf"^\s+{re.escape(m['label'])}\s+{m['onset_speed_rpm']:,.0f} rpm",
                         text, re.M)
        assert f"onset, {m['label']}: {m['onset_speed_rpm']:,.0f} rpm" in legend
        named = csv_tracks[csv_tracks["track_label"] == m["label"]]
        assert len(named) == 1
        # that track is the one losing its damping at this onset
        assert abs(named["track_zero_rpm"].iloc[0] - m["onset_speed_rpm"]) <= width
    first = [m for m in onsets if m["label"] == out["first_mode"]][0]
    zeros = csv_tracks["track_zero_rpm"].dropna().sort_values()
    assert csv_tracks.loc[zeros.index[0], "track_label"] == first["label"]
