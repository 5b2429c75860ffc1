"""The CSV files of the command line: ``--csv`` changes no answer of the JSON (it adds the
list ``csv`` of the files written), and every CSV has its context ``FILE.csv.json`` beside it
(gfbopt version, source commit, the command line and options as typed, the columns' units
from the glossary — the block of the command's ``--json``), the CSV itself a plain table
``pandas.read_csv`` reads with no options.  Grids 36x10/24x8 on the 3.2 kg blower: the
answers here are compared between two runs of the same command, not against the physics."""
from __future__ import annotations

import json
import math
from pathlib import Path

import pandas as pd
import pytest

from gfbopt.cli import main
from gfbopt.cli.csv_context import sidecar_path
from gfbopt.glossary import describe
from gfbopt.provenance import source_state
from gfbopt.version import __version__
from tests.cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
BLOWER = str(REPO / "problems" / "rotors" / "blower.toml")
RUSCITTO = str(REPO / "problems" / "bearings" / "ruscitto.toml")
#: a rotor run with every table: modes, scan, equilibria, Campbell, imbalance, half-mass
ROTOR = ("rotor", BLOWER, "--speed-range", "10000", "60000", "--grid", "36x10", "--campbell",
         "--campbell-speeds", "3", "--imbalance-response", "--half-mass", "--speed-rpm",
         "30000", "--json")
ORBIT = ("rotor", BLOWER, "--orbit", "--speed-rpm", "30000", "--revolutions", "2", "--grid",
         "24x8", "--json")
#: fields that time the run (differ between any two runs)
TIMES = ("wall_time_s",)


def _json(*args) -> dict:
    out = run_cli(*args)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def _same(a, b, where="") -> None:
    """a == b, numbers to 1e-9 relative (two runs of one command: the same solves)."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and set(a) == set(b), (where, set(a) ^ set(b))
        for key in a:
            _same(a[key], b[key], f"{where}/{key}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), where
        for k, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{where}[{k}]")
    elif isinstance(a, float) and isinstance(b, float):
        assert b == pytest.approx(a, rel=1e-9, abs=1e-300), where
    else:
        assert a == b, where


def _check_provenance(without: dict, with_csv: dict, folder: Path) -> None:
    """The provenance blocks differ only where the command lines do: the date, the line as
    typed and --csv."""
    p, q = without["provenance"], with_csv["provenance"]
    assert p["options"]["arguments"]["--csv"] is None
    assert q["options"]["arguments"]["--csv"] == str(folder)
    assert q["options"]["command_line"] == p["options"]["command_line"] + ["--csv", str(folder)]
    for block in (p, q):
        block.pop("date")
        block["options"].pop("command_line")
        block["options"]["arguments"].pop("--csv")
    assert p == q


@pytest.mark.parametrize("command", [ROTOR, ORBIT], ids=["linear", "orbit"])
def test_the_rotor_json_is_the_same_with_csv_but_for_the_list_of_files(tmp_path, command):
    """Before, --csv replaced the JSON's scan and equilibria by a file name ('scan.csv', a
    file never written: it is threshold_scan.csv) and the imbalance table by
    'imbalance_response.csv'; the transient route did not list its files."""
    without = _json(*command)
    with_csv = _json(*command, "--csv", tmp_path)
    written = with_csv.pop("csv")
    assert sorted(written) == sorted(str(p) for p in tmp_path.glob("*.csv"))
    assert len(written) == (6 if command is ROTOR else 3)
    _check_provenance(without, with_csv, tmp_path)
    for key in TIMES:
        assert without.pop(key) > 0 and with_csv.pop(key) > 0
    _same(without, with_csv)
    if command is ROTOR:          # the answers the CSV holds are in the JSON too
        assert isinstance(with_csv["scan"], list) and len(with_csv["scan"]) > 0
        assert isinstance(with_csv["imbalance_response"]["table"], list)
        scan = pd.read_csv(tmp_path / "threshold_scan.csv")
        assert len(scan) == len(with_csv["scan"])
        assert scan["speed_rpm"].tolist() == pytest.approx(
            [r["speed_rpm"] for r in with_csv["scan"]], rel=1e-8)


def _check_context(csv: Path, printed: dict, argv: list) -> dict:
    """``csv`` has its context beside it: the same provenance as the --json output (but the
    date), the command line as typed, every column in the glossary with its unit."""
    side = sidecar_path(csv)
    assert side.name == csv.name + ".json" and side.is_file(), csv
    context = json.loads(side.read_text())
    frame = pd.read_csv(csv)                       # no options: a plain one-header table
    assert len(frame) > 0 and list(frame.columns) == list(context["columns"])
    assert context["file"] == csv.name and context["read_with"] == "pandas.read_csv(path)"
    for column, entry in context["columns"].items():
        assert (entry["unit"], entry["meaning"]) == describe(column), column   # the glossary
    prov = context["provenance"]
    assert prov["gfbopt_version"] == __version__
    assert prov["source_commit"] == source_state()["commit"]
    assert prov["options"]["command_line"] == ["gfbopt", *map(str, argv)]
    assert "SI units" in prov["conventions"]
    same = {k: v for k, v in printed["provenance"].items() if k != "date"}
    assert {k: v for k, v in prov.items() if k != "date"} == same
    return context


def test_every_rotor_csv_has_its_context(tmp_path):
    argv = [*ROTOR, "--csv", tmp_path]
    printed = _json(*argv)
    for name in printed["csv"]:
        context = _check_context(Path(name), printed, argv)
        assert context["provenance"]["options"]["arguments"]["--grid"] == "36x10"
        assert context["provenance"]["options"]["rotor_file"] == BLOWER
    argv = [*ORBIT, "--csv", tmp_path / "orbit"]
    printed = _json(*argv)
    for name in printed["csv"]:
        context = _check_context(Path(name), printed, argv)
        assert context["provenance"]["options"]["arguments"]["--revolutions"] == 2.0


def test_stability_and_capacity_csvs_have_their_context(tmp_path):
    argv = ["stability", "--bearing", RUSCITTO, "--rotor-mass-kg", "1.5", "--speed-rpm",
            "30000", "--grid", "36x10", "--json", "--csv", tmp_path / "kc.csv"]
    printed = _json(*argv)
    context = _check_context(tmp_path / "kc.csv", printed, argv)
    assert context["columns"]["kxy_N_per_m"]["unit"] == "N/m"
    assert context["provenance"]["options"]["film_convention"] == printed["conventions"][
        "film_convention"]
    argv = ["capacity", "--bearing", RUSCITTO, "--speed-rpm", "30000", "--min-film-um", "5",
            "--grid", "36x10", "--json", "--csv", tmp_path / "curve.csv"]
    printed = _json(*argv)
    context = _check_context(tmp_path / "curve.csv", printed, argv)
    assert context["columns"]["min_film_thickness_um"]["unit"] == "µm"
    curve = pd.read_csv(tmp_path / "curve.csv")
    assert len(curve) == len(printed["curve"])
    assert math.isfinite(printed["load_capacity_newton"])


def test_export_ross_files_have_their_context(tmp_path):
    argv = ["export-ross", BLOWER, "--speed-range", "10000", "60000", "--speeds", "2",
            "--frequencies", "2", "--grid", "24x8", "--out", tmp_path, "--json"]
    printed = _json(*argv)
    assert [Path(f["file"]).name for f in printed["files"]] == ["bearing_A.toml",
                                                               "bearing_B.toml"]
    for entry in printed["files"]:
        path = Path(entry["file"])
        context = json.loads(sidecar_path(path).read_text())
        assert context["read_with"] == "ross.BearingElement.load(path)"
        assert "columns" not in context                  # ROSS's own keys, not gfbopt's
        assert context["provenance"]["options"]["command_line"] == ["gfbopt",
                                                                    *map(str, argv)]
        header = path.read_text().splitlines()[1]         # the TOML names the commit too
        state = source_state()
        assert header.startswith(f"# source commit {state['commit'] or state['source']}")


@pytest.mark.parametrize("command", ["rotor", "stability", "capacity"])
def test_the_help_of_every_csv_option_names_its_context(command, capsys):
    with pytest.raises(SystemExit):
        main([command, "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "FILE.csv.json" in text and "docs/cli_outputs.md" in text


def test_the_docs_page_names_every_command_that_writes_a_csv():
    page = (REPO / "docs" / "cli_outputs.md").read_text()
    for command in ("gfbopt rotor", "gfbopt stability", "gfbopt capacity", "gfbopt orbit",
                    "gfbopt export-ross", "FILE.csv.json", "pandas.read_csv"):
        assert command in page, command


def test_a_context_file_that_cannot_be_written_is_refused_before_solving(tmp_path):
    (tmp_path / "kc.csv.json").mkdir()
    out = run_cli("stability", "--bearing", RUSCITTO, "--rotor-mass-kg", "1.5", "--speed-rpm",
                  "30000", "--csv", tmp_path / "kc.csv")
    assert out.returncode == 2 and out.stdout == ""
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"gfbopt: error: --csv = "
                                                   f"'{tmp_path / 'kc.csv'}'")
    assert "its context file" in lines[0] and "is a directory" in lines[0]
    assert not (tmp_path / "kc.csv").exists()
