"""One schema language for the input files: the rotor file is declared in
gfbopt.inputs.file_schema's Field/Table/FileFormat, as the bearing file is, and checked by
its checkers — every bound a field states is the bound the validator applies, every default
it states is the value the rotor gets, and a misspelt key anywhere gets "did you mean"."""
from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import rotor_schema
from gfbopt.inputs.conversions import STANDARD_GRAVITY
from gfbopt.inputs.file_schema import MODEL, REQUIRED, Field, FileFormat, Table
from gfbopt.inputs.rotor_schema import ROTOR_FILE
from gfbopt.inputs.rotor_system import rotor_from_dict

ROOT = Path(__file__).resolve().parents[2]
ROTORS = ROOT / "problems" / "rotors"
RIGID = tomllib.loads((ROTORS / "blower.toml").read_text())
FLEX = tomllib.loads((ROTORS / "flexible_rotor.toml").read_text())
#: a rigid rotor with one row of every array table a rigid rotor has
FULL = {**RIGID, "side_loads": [{"force": 5.0, "direction_deg": 90.0, "position": 0.02}]}


def _load(data):
    return rotor_from_dict(data, directory=ROTORS, where="r.toml")


def _tables():
    return {t.name: t for t in ROTOR_FILE.tables}


def test_the_rotor_file_is_declared_in_file_schemas_language_only():
    assert isinstance(ROTOR_FILE, FileFormat)
    assert all(isinstance(t, Table) for t in ROTOR_FILE.tables)
    assert all(isinstance(f, Field) for t in ROTOR_FILE.tables for f in t.fields)
    assert not hasattr(rotor_schema, "Key") and not hasattr(rotor_schema, "SCHEMA")
    # [bearings.model] is the bearing file's [model] table, key for key
    assert _tables()["bearings.model"].fields == MODEL.fields


def _rows_of(data, table):
    """(row dict, message prefix) of the first row of ``table`` in ``data``."""
    if table == "rotor":
        return data["rotor"], "r.toml: rotor."
    return data[table][0], f"r.toml: {table}[1]."


BOUNDED = [(t.name, f) for t in ROTOR_FILE.tables if t.name in ("rotor", "side_loads",
                                                                   "imbalance", "shaft", "disks")
           for f in t.fields if f.kind == "number" and (f.positive or f.low is not None
                                                        or f.high is not None)]


@pytest.mark.parametrize("table, f", BOUNDED, ids=[f"{t}.{f.name}" for t, f in BOUNDED])
def test_every_stated_bound_is_the_validators(table, f):
    """Just outside a field's bound: refused naming file, table row and key, with the bound
    the schema states; on the bound (or just inside a strict one) no refusal of that key."""
    base = copy.deepcopy(FLEX if table in ("shaft", "disks") else FULL)
    if table == "imbalance" and f.name == "amount_kg_m":
        base["imbalance"][0].pop("amount_g_mm")
    outside, edge = [], []
    if f.positive:
        outside.append(0.0)
    if f.low is not None:
        outside.append(f.low - max(1.0, abs(f.low)) * 1e-6)
        edge.append(f.low)
    if f.high is not None:
        outside.append(f.high * (1 + 1e-6))
        edge.append(f.high)
    for value in outside:
        data = copy.deepcopy(base)
        row, prefix = _rows_of(data, table)
        row[f.name] = value
        with pytest.raises(ParameterError) as err:
            _load(data)
        message = str(err.value)
        assert message.startswith(f"{prefix}{f.name} = ") and "\n" not in message, message
        assert ("must be > 0" if value == 0.0 and f.positive else "must be ") in message
    for value in edge:
        data = copy.deepcopy(base)
        row, prefix = _rows_of(data, table)
        row[f.name] = value
        try:
            _load(data)
        except ParameterError as exc:        # another rule (limits, statics) may refuse it
            assert not str(exc).startswith(f"{prefix}{f.name} = {value!r}: must be "), exc


def test_defaults_stated_by_the_schema_are_the_rotors():
    """A minimal rigid and a minimal flexible rotor get every stated default."""
    tables = _tables()
    rigid = _load({"rotor": {k: RIGID["rotor"][k] for k in rotor_schema.RIGID_ONLY},
                   "bearings": [{k: b[k] for k in ("file", "position")}
                                for b in RIGID["bearings"]],
                   "side_loads": [{"force": 5.0, "direction_deg": 90.0}],
                   "imbalance": [{"amount_g_mm": 2.0, "position": 0.065}]})
    assert rigid.body.name == tables["rotor"].field("name").default == "rotor"
    assert rigid.gravity == tables["rotor"].field("gravity").default == STANDARD_GRAVITY
    assert rigid.gravity_direction_deg == tables["rotor"].field("gravity_direction_deg").default
    assert rigid.side_loads[0].position == tables["side_loads"].field("position").default
    assert rigid.imbalance[0].phase_deg == tables["imbalance"].field("phase_deg").default
    assert [b.name for b in rigid.bearings] == ["A", "B"]
    assert rigid.imbalance[0].name == "plane 1"
    flex = copy.deepcopy(FLEX)
    for row in flex["shaft"]:
        row.pop("inner_diameter"), row.pop("poisson_ratio")
    flex["shaft"] = [{**row, "outer_diameter": 0.03} for row in flex["shaft"]]
    flex["disks"] = [{"position": d["position"], "mass": d["mass"]} for d in flex["disks"]]
    system = _load(flex)
    element = system.shaft.elements[0]
    assert element.inner_diameter == tables["shaft"].field("inner_diameter").default == 0.0
    assert element.poisson_ratio == tables["shaft"].field("poisson_ratio").default == 0.3
    disk = system.shaft.disks[0]
    assert (disk.transverse_inertia, disk.polar_inertia) == (0.0, 0.0)
    assert [d.name for d in system.shaft.disks] == ["disk 1", "disk 2"]
    for t in ROTOR_FILE.tables:                      # defaults obey their own fields' bounds
        for f in t.fields:
            if f.kind == "number" and f.default not in (REQUIRED, None):
                assert math.isfinite(f.default)


@pytest.mark.parametrize("where, misspelt, meant", [
    (None, "bearing", "bearings"), (None, "shafts", "shaft"), ("rotor", "masss", "mass"),
    ("bearings", "positon", "position"), ("bearings", "modle", "model"),
    ("side_loads", "forse", "force"), ("imbalance", "phase_dg", "phase_deg"),
    ("stations", "nme", "name"), ("shaft", "lenght", "length"),
    ("disks", "polar_inertai", "polar_inertia"), ("bearings.model", "lossfactor",
                                                  "loss_factor"),
])
def test_a_misspelt_key_anywhere_gets_did_you_mean(where, misspelt, meant):
    data = copy.deepcopy(FLEX if where in ("shaft", "disks") else
                         {**FULL, "stations": [{"name": "s", "position": 0.0}]})
    if where is None:
        data[misspelt] = data.pop(meant) if meant in data else 1.0
        key = f"r.toml: {misspelt}"
    elif where == "bearings.model":
        data["bearings"][1]["model"] = {misspelt: 0.1}
        key = f"r.toml: bearings[2].model.{misspelt}"
    else:
        row, prefix = _rows_of(data, where)
        row[misspelt] = row.pop(meant, 1.0)
        key = f"{prefix}{misspelt}"
    with pytest.raises(ParameterError) as err:
        _load(data)
    message = str(err.value)
    assert message.startswith(key) and f"(did you mean '{meant}'?)" in message, message
    assert "\n" not in message


def test_one_table_where_a_list_is_expected_is_one_row():
    data = copy.deepcopy(RIGID)
    data["imbalance"] = data["imbalance"][0]
    assert _load(data).imbalance == _load(RIGID).imbalance
    with pytest.raises(ParameterError, match=r"r.toml: stations = 3: must be a list of "
                       r"tables \(\[\[stations\]\]\)"):
        _load({**RIGID, "stations": 3})
