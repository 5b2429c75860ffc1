"""One label per mode of a FLEXIBLE rotor in every output of one ``gfbopt rotor`` run: the text,
the JSON, the CSV files and the Campbell figure's legend (problems/rotors/flexible_rotor.toml,
20 Timoshenko elements, 24 × 8).

Each mode is one track of matched-whirl crossings along speed (gfbopt.rotor.mode_search), named
once; a Campbell track of the same mode (it loses its damping at that onset, or has the same
shape) carries that name and no other track does.  Before, the search by shape label gave the
two forward rigid-body modes "forward mixed" (one onset) plus "forward conical" and "forward
cylindrical" "unstable where its shape first appears", the bending modes' whirl was the
threshold's (near half the speed), and the diagram dropped the bending modes at low speeds.
The blower (rigid) keeps its onsets to 1e-9 of the numbers before the change."""
import contextlib
import io
import json
import math
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from gfbopt.cli import main
from gfbopt.cli import rotor as rotor_cli
from gfbopt.rotor.tracking import MIN_POINTS

ROOT = Path(__file__).resolve().parents[2]
ROTORS = ROOT / "problems" / "rotors"
SPEEDS = 8
HIGH = 60000.0


def _run(folder: Path, rotor: Path, *extra, low: float = 5000.0) -> dict:
    """One CLI run read as JSON, as text, as CSV and through the figures' legends."""
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
            code = main(["rotor", str(rotor), "--speed-range", f"{low:g}", f"{HIGH:g}",
                         "--grid", "24x8", "--json", "--csv", str(folder / "csv"), *extra])
    finally:
        mp.undo()
    assert code == 0
    out = {"json": json.loads(buffer.getvalue().splitlines()[0]), "text": printed[0],
           "modes": pd.read_csv(folder / "csv" / "modes.csv"),
           "scan": pd.read_csv(folder / "csv" / "threshold_scan.csv")}
    if legends:
        out["legend"] = legends["campbell.png"]
        out["campbell"] = pd.read_csv(folder / "csv" / "campbell.csv")
    return out


@pytest.fixture(scope="module")
def flexible(tmp_path_factory):
    folder = tmp_path_factory.mktemp("flexible_labels")
    return _run(folder, ROTORS / "flexible_rotor.toml", "--campbell", "--campbell-speeds",
                str(SPEEDS), "--plot", str(folder / "fig"))


def _finite(v) -> bool:
    return v is not None and math.isfinite(v)


def test_every_output_gives_each_mode_one_label(flexible):
    out, text, legend, table = (flexible[k] for k in ("json", "text", "legend", "campbell"))
    modes = out["modes"]
    labels = [m["label"] for m in modes]
    assert len(labels) == len(set(labels)), labels
    assert list(flexible["modes"]["label"]) == labels                  # modes.csv
    onsets = [m for m in modes if _finite(m["onset_speed_rpm"])]
    # both forward rigid-body modes have an onset of their own (one was "unstable where its
    # shape first appears" before), no mode is left without a bracket
    assert len(onsets) == 2
    assert not [m for m in modes if m["onset_status"] == "unstable where its shape first appears"]
    assert f"first to whirl: {out['first_mode']} from {out['onset_speed_rpm']:,.0f} rpm" in text
    # threshold_scan.csv: every crossing is one mode's, by its name (its shape class at that
    # speed apart, shape_label); at its onset the mode's crossing has μ_c = 1
    scan = flexible["scan"]
    assert "label" not in scan.columns and set(scan["track_label"]) <= set(labels)
    for m in onsets:
        at = scan[(scan["track_label"] == m["label"])
                  & np.isclose(scan["speed_rpm"], m["onset_speed_rpm"], rtol=1e-8, atol=0)]
        assert len(at) == 1 and at["inertia_scale"].iloc[0] == pytest.approx(1.0, abs=1e-5)
    for m in modes:                                                     # the text's lines
        shown = (f"{m['onset_speed_rpm']:,.0f} rpm" if _finite(m["onset_speed_rpm"])
                 else m["onset_status"])
        assert re.search(rf"^\s+{re.escape(m['label'])}\s+{re.escape(shown)},", text, re.M), m
    # Campbell: one name per track, no two alike, the same in the CSV, JSON, legend and text
    names = table.groupby("mode")["track_label"].agg(set)
    assert all(len(s) == 1 for s in names)
    csv_tracks = table.groupby("mode").first()
    json_tracks = {t["mode"]: t["label"] for t in out["campbell"]["tracks"]}
    assert json_tracks == csv_tracks["track_label"].to_dict()
    assert len(set(json_tracks.values())) == len(json_tracks)
    legend_tracks = {int(g.group(1)): g.group(2) for g in
                     (re.fullmatch(r"mode (\d+): (.+)", t) for t in legend) if g}
    assert legend_tracks == json_tracks
    line = text.split("tracks: ", 1)[1].splitlines()[0]
    for number, label in json_tracks.items():
        assert re.search(rf"(^|; ){number} {re.escape(label)}( \(damping|;|$)", line)
    # no track of one point (gfbopt.rotor.tracking.stitch): every legend entry is a line
    assert table.groupby("mode").size().min() >= MIN_POINTS
    speeds = sorted(table["speed_rpm"].unique())
    width = speeds[1] - speeds[0]
    for m in onsets:
        assert f"onset, {m['label']}: {m['onset_speed_rpm']:,.0f} rpm" in legend
        named = csv_tracks[csv_tracks["track_label"] == m["label"]]
        assert len(named) == 1, m["label"]                 # the track losing its damping there
        assert abs(named["track_zero_rpm"].iloc[0] - m["onset_speed_rpm"]) <= width
        # its whirl is its own: the track's damped natural frequency at the onset, within
        # the 5 % the naming allows (gfbopt.rotor.tracking.SAME_FREQUENCY)
        rows = table[table["track_label"] == m["label"]].sort_values("speed_rpm")
        f = float(np.interp(m["onset_speed_rpm"], rows["speed_rpm"],
                            rows["whirl_frequency_hz"]))
        assert m["whirl_frequency_hz"] == pytest.approx(f, rel=0.05)


def test_bending_modes_are_one_mode_in_the_list_and_the_diagram(flexible):
    out, table = flexible["json"], flexible["campbell"]
    limit = out["campbell"]["frequency_limit_hz"]
    assert limit == pytest.approx(3.0 * HIGH / 60.0)                  # the stated limit
    assert table["whirl_frequency_hz"].max() <= limit
    bending = [m for m in out["modes"] if " bending" in m["label"]]
    assert bending and all(m["onset_status"] == "stable over the range" for m in bending)
    for m in bending:
        # no whirl of its own in the range: the threshold's (a rotor μ_c times heavier,
        # near half the speed) is kept apart
        assert m["whirl_frequency_hz"] is None or not math.isfinite(m["whirl_frequency_hz"])
        assert 0 < m["threshold_whirl_frequency_hz"] < 0.6 * HIGH / 60.0
        assert "kind" not in m["shape"] and m["shape"]["shape_class"] == "bending"
    first = table[table["track_label"] == "forward bending 1"]
    # the first forward bending mode is a track of the diagram at every speed (the diagram
    # dropped it above 3x the speed before), at its own frequency, far above the threshold's
    assert len(first) == SPEEDS
    # (at the top speed, where the list reports it: 0.49x the speed at μ_c = 3.6 against
    # 902 Hz, measured)
    top = first.loc[first["speed_rpm"].idxmax(), "whirl_frequency_hz"]
    assert top > 1.5 * bending[0]["threshold_whirl_frequency_hz"]


def test_the_blower_keeps_its_onsets(tmp_path):
    """The rigid blower at 24 × 8: the onsets of main before the change (the search by
    label, commit 1ab0e8a), to 1e-9; its two forward modes, no third "forward mixed" (the low-speed
    shape of one of them, listed as a mode of its own before)."""
    out = _run(tmp_path, ROTORS / "blower.toml")["json"]
    found = {m["label"]: m["onset_speed_rpm"] for m in out["modes"]}
    assert found == {"forward conical": pytest.approx(12282.348178892993, rel=1e-9),
                     "forward cylindrical": pytest.approx(13079.731056007204, rel=1e-9)}
    assert all(m["shape"]["shape_class"] in ("conical", "cylindrical") for m in out["modes"])


def _same_names(run: dict) -> dict:
    """mode number → name, checked equal in campbell.csv, the JSON, the figure's legend and
    the text's "tracks:" line."""
    table, out, legend, text = run["campbell"], run["json"], run["legend"], run["text"]
    assert all(len(s) == 1 for s in table.groupby("mode")["track_label"].agg(set))
    csv_tracks = table.groupby("mode")["track_label"].first().to_dict()
    json_tracks = {t["mode"]: t["label"] for t in out["campbell"]["tracks"]}
    legend_tracks = {int(g.group(1)): g.group(2) for g in
                     (re.fullmatch(r"mode (\d+): (.+)", t) for t in legend) if g}
    assert csv_tracks == json_tracks == legend_tracks
    assert len(set(json_tracks.values())) == len(json_tracks)
    line = text.split("tracks: ", 1)[1].splitlines()[0]
    for number, label in json_tracks.items():
        assert re.search(rf"(^|; ){number} {re.escape(label)}( \(damping|;|$)", line)
    return json_tracks


def test_a_coarse_blower_diagram_has_no_track_of_one_point(tmp_path):
    """The blower at 24 × 8, 7 Campbell speeds over 4,000–60,000 rpm (steps of 9,333 rpm):
    before, the two forward modes on the half-speed line — log decrement 3.1 and 1.8 at
    4,000 rpm, −0.15 and −0.05 at 13,333 — each went on as a new track, leaving three tracks
    of one point (modes 1, 2 and 6 of 8: "forward mixed", "forward conical" at 4,000 rpm,
    "forward cylindrical" at 13,333 rpm, measured) in the CSV and the legend, and the onset
    labels on other tracks.  Now each of the two is one track over all 7 speeds, from
    31.8 and 32.9 Hz at 4,000 rpm to 226 and 296 Hz at 60,000 rpm (the 20-speed diagram's
    lines, results/rotor_blower), named by its onset; five tracks, one name each in every
    output."""
    run = _run(tmp_path, ROTORS / "blower.toml", "--campbell", "--campbell-speeds", "7",
               "--plot", str(tmp_path / "fig"), low=4000.0)
    table = run["campbell"]
    sizes = table.groupby("mode").size()
    assert sizes.min() >= MIN_POINTS and len(sizes) == 5
    names = _same_names(run)
    onsets = {m["label"] for m in run["json"]["modes"] if _finite(m["onset_speed_rpm"])}
    assert onsets == {"forward conical", "forward cylindrical"}
    for label in onsets:
        rows = table[table["track_label"] == label].sort_values("speed_rpm")
        assert len(rows) == 7, label
        assert rows["whirl_frequency_hz"].iloc[0] == pytest.approx(32.4, abs=0.7)
        assert rows["log_decrement"].iloc[0] > 1.5 and rows["log_decrement"].iloc[-1] < 0
    top = table[table["speed_rpm"] == table["speed_rpm"].max()]
    forward = sorted(top[top["track_label"].isin(onsets)]["whirl_frequency_hz"])
    assert forward == pytest.approx([226.4, 295.9], abs=0.5)
    assert sorted(names.values())[0].startswith("backward")
