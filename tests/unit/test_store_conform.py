"""The store's rows → Arrow conversion (gfbopt.doe.store._conform_table) gives exactly the
table the pandas route gave (DataFrame coercion, then Table.from_pandas), column types and
nulls included, for the value types a study writes and the odd ones it may."""
import math

import numpy as np
import pyarrow as pa
import pytest

from gfbopt.doe.store import _arrow_schema, _conform, _conform_table
from gfbopt.errors import ParameterError

SCHEMA = {"point": "int64", "x": "float64", "ok": "bool", "name": "string", "n": "int64"}


def _pandas_route(rows, schema):
    frame = _conform(rows, schema)
    return pa.Table.from_pandas(frame, schema=_arrow_schema(schema), preserve_index=False)


def _same(a: pa.Table, b: pa.Table) -> None:
    assert a.schema.remove_metadata() == b.schema.remove_metadata()
    da, db = a.to_pydict(), b.to_pydict()
    assert list(da) == list(db)
    for name in da:
        for u, v in zip(da[name], db[name], strict=True):
            same = (u is None and v is None) or u == v or (
                isinstance(u, float) and isinstance(v, float) and math.isnan(u) and math.isnan(v))
            assert same and type(u) is type(v), (name, u, v)


ROWS = [
    {"point": 1, "x": 1.5, "ok": True, "name": "a", "n": 3},
    {"point": 2, "x": float("nan"), "ok": None, "name": None},             # NaN → null
    {"point": 3, "x": np.float64(2.0), "ok": np.bool_(False), "name": "b", "n": np.int64(7)},
    {"point": 4},                                                           # all missing
    {"point": 5, "x": 4, "ok": False, "name": "", "n": None},              # int in float
    {"point": 6, "x": float("inf"), "ok": True, "name": "é ü", "n": -2},
    {"point": 7, "x": np.float32(0.1), "ok": True, "name": "c", "n": 0},
]


def test_direct_route_equals_the_pandas_route_on_a_study_s_values():
    _same(_conform_table(ROWS, SCHEMA), _pandas_route(ROWS, SCHEMA))


@pytest.mark.parametrize("odd", [
    {"point": 8, "x": "2.5"},                  # a number as text in a float column: 2.5
    {"point": 8, "x": "abc"},                  # text that is no number: null
    {"point": 8, "x": True},                   # a bool in a float column
    {"point": 8, "name": 12},                  # a number in a string column: "12"
    {"point": 8, "name": 1.5},
    {"point": 8, "n": 2.0},                    # a whole float in an int column
    {"point": 8, "x": 2 ** 60 + 1},            # an integer a double cannot hold exactly
])
def test_odd_values_take_the_pandas_route_and_agree(odd):
    rows = ROWS + [odd]
    _same(_conform_table(rows, SCHEMA), _pandas_route(rows, SCHEMA))


@pytest.mark.parametrize("odd, said", [({"ok": 1}, "bool-like"),    # beside a missing bool
                                       ({"n": 2.5}, "safely cast")])   # pyarrow would give 2
def test_a_value_pandas_refuses_is_refused_by_both(odd, said):
    """pandas' TypeError, by both routes (the store never wrote such a part before either)."""
    rows = ROWS + [{"point": 8, **odd}]
    for conform in (_pandas_route, _conform_table):
        with pytest.raises(TypeError, match=said):
            conform(rows, SCHEMA)


def test_a_column_outside_the_schema_is_refused_by_both():
    for conform in (_conform, _conform_table):
        with pytest.raises(ParameterError, match="'zz'|zz"):
            conform([{"point": 1, "zz": 2}], SCHEMA)


def test_the_direct_route_is_the_one_taken_for_plain_values(monkeypatch):
    """Plain values go through Table.from_pylist: no column by column, no DataFrame."""
    import gfbopt.doe.store as store

    called = []
    monkeypatch.setattr(store, "_by_column", lambda *a: called.append(a))
    table = _conform_table(ROWS * 100, SCHEMA)
    assert called == [] and table.num_rows == 700
    _conform_table(ROWS + [{"point": 8, "n": 2.5}], SCHEMA)      # 2.5 in an int column
    assert len(called) == 1


def test_by_column_route_equals_the_pandas_route():
    from gfbopt.doe.store import _by_column

    for odd in ({}, {"x": "2.5"}, {"name": 12}, {"n": 2.0}, {"x": True}):
        rows = ROWS + [{"point": 8, **odd}]
        _same(_by_column(rows, SCHEMA, _arrow_schema(SCHEMA)), _pandas_route(rows, SCHEMA))
