"""``gfbopt orbit --csv FILE``: the orbit table with its context ``FILE.csv.json`` (the
provenance of the --json output, the command line, the columns' units from the glossary),
and the JSON names the file (``csv``); a 2-revolution orbit at 24x8 (ε 0.4, Λ 1, S 1)."""
from __future__ import annotations

import json

import pandas as pd

from gfbopt.cli.csv_context import sidecar_path
from gfbopt.glossary import describe
from gfbopt.provenance import source_state
from tests.cli_inprocess import run_cli


def test_the_orbit_csv_has_its_context(tmp_path):
    argv = ["orbit", "--bearing-number", "1", "--eccentricity", "0.4", "--compliance", "1",
            "--grid", "24x8", "--mass", "1", "--revolutions", "2", "--json",
            "--csv", str(tmp_path / "orbit.csv")]
    out = run_cli(*argv)
    assert out.returncode == 0, out.stderr
    printed = json.loads(out.stdout)
    assert printed["csv"] == str(tmp_path / "orbit.csv")
    context = json.loads(sidecar_path(tmp_path / "orbit.csv").read_text())
    frame = pd.read_csv(tmp_path / "orbit.csv")
    assert len(frame) > 10 and list(frame.columns) == list(context["columns"])
    for column, entry in context["columns"].items():
        assert (entry["unit"], entry["meaning"]) == describe(column)
    prov = context["provenance"]
    assert prov["source_commit"] == source_state()["commit"]
    assert prov["options"]["command_line"] == ["gfbopt", *argv]
    assert prov["options"]["arguments"]["--mass"] == 1.0
    assert {k: v for k, v in prov.items() if k != "date"} == {
        k: v for k, v in printed["provenance"].items() if k != "date"}
