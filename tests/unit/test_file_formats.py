"""The user documentation of the input files is generated from the validators' schemas:
docs/formats/ must be what the schemas generate now."""
from __future__ import annotations

import dataclasses
import tomllib

import pytest

from gfbopt import cli
from gfbopt.errors import ParameterError
from gfbopt.file_formats import DOCS, PAGES, render_format, stale_pages
from gfbopt.inputs import BearingGeometry
from gfbopt.inputs.file_schema import BEARING, BEARING_FILE, MODEL, Field, FileFormat, Table
from gfbopt.inputs.options import OPTION_NAMES


def test_docs_formats_are_not_stale():
    """Fails when a schema changed without `python -m gfbopt.file_formats` (regenerate)."""
    assert stale_pages() == [], "run: python -m gfbopt.file_formats"


def test_bearing_schema_is_the_validator_schema():
    """The documented [bearing] keys are exactly BearingGeometry's, [model]'s exactly
    ModelOptions's: the docs cannot describe a key the validator does not read."""
    geometry = {f.name for f in dataclasses.fields(BearingGeometry)} - {"options", "build"}
    assert {f.name for f in BEARING.fields} == geometry
    assert tuple(f.name for f in MODEL.fields) == OPTION_NAMES
    page = (DOCS / "bearing_file.md").read_text()
    for f in (*BEARING.fields, *MODEL.fields):
        assert f"| `{f.name}` |" in page


def test_adding_a_table_is_one_entry():
    """The hook for new tables ([bore], [[pads]]): a FileFormat with one more Table renders
    it with its keys; the validator of that format accepts and checks it."""
    from gfbopt.inputs.file_schema import check_file

    pads = Table("washers", "thrust washers", fields=(Field("arc_deg", "number", "deg", "pad arc",
                                                        positive=True),), array=True)
    fmt = FileFormat(BEARING_FILE.name, BEARING_FILE.doc, BEARING_FILE.top,
                     (*BEARING_FILE.tables, pads), BEARING_FILE.example)
    assert "## `[[washers]]` (optional)" in render_format(fmt)
    assert "`arc_deg`" in render_format(fmt)
    data = {**tomllib.loads(BEARING_FILE.example), "washers": [{"arc_deg": 60}]}
    assert check_file(data, fmt, "x.toml")["washers"] == [{"arc_deg": 60.0}]
    with pytest.raises(ParameterError, match=r"x.toml: washers\[1\].arc = 60: is not a key "
                       r"of \[washers\] \(did you mean 'arc_deg'\?\)"):
        check_file({**data, "washers": [{"arc": 60}]}, fmt, "x.toml")
    with pytest.raises(ParameterError, match=r"x.toml: washers = .*is not a key of a bearing "
                       r"file \(known: source, notes, bearing, model, bore, pads, zones\)"):
        check_file(data, BEARING_FILE, "x.toml")


def test_formats_command_prints_the_pages(capsys):
    assert cli.main(["formats"]) == 0
    listing = capsys.readouterr().out
    assert "bearing_file" in listing and "sweep" in listing
    assert cli.main(["formats", "bearing_file"]) == 0
    assert capsys.readouterr().out.strip() == PAGES["bearing_file.md"]().strip()
    assert cli.main(["formats", "--kinds"]) == 0
    assert "onset_conventions" in capsys.readouterr().out.split()
    assert cli.main(["formats", "bearing_fil"]) == 2
    assert "did you mean 'bearing_file'" in capsys.readouterr().err
