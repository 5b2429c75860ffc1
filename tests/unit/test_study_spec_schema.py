"""Study files are declared and checked in file_schema's one language (gfbopt.inputs.file_schema):
every key of every study kind is a file_schema Field, spec's checking is file_schema's checker,
and the kinds the study files added to file_schema behave as stated (the bearing and rotor
files' kinds unchanged)."""
import dataclasses
import tomllib
from pathlib import Path

import pytest

import gfbopt.inputs.file_schema as fs
from gfbopt import ParameterError
from gfbopt.inputs.file_schema import BORE, REQUIRED, UNSET, Field, Table
from gfbopt.studies import SCHEMAS, spec
from gfbopt.studies.spec import COMMON, PUBLISHED_DATA, Where, opt, req, validate

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "problems"
DOC = ROOT / "docs" / "formats" / "study_file.md"


def _walk(schema: dict, prefix=""):
    """(path, field) of every key of a study schema, nested tables and mappings included."""
    for name, key in schema.items():
        path = f"{prefix}{name}"
        yield path, key
        if key.kind in ("table", "tables") and key.keys:
            yield from _walk(key.keys, f"{path}[]." if key.kind == "tables" else f"{path}.")
        if key.kind == "mapping" and key.values is not None and key.values.keys:
            yield from _walk(key.values.keys, f"{path}.NAME.")


def test_every_study_key_is_a_file_schema_field_and_spec_has_no_key_class():
    assert not hasattr(spec, "Key")
    schemas = {"common": COMMON, "published": PUBLISHED_DATA, **SCHEMAS}
    count = 0
    for kind, schema in schemas.items():
        for path, key in _walk(schema):
            count += 1
            assert type(key) is Field, (kind, path)
            assert key.kind in fs.KINDS, (kind, path, key.kind)
            if key.table is not None:
                assert type(key.table) is Table and key.table.fill and key.table.by_path
    assert count > 400          # 27 shipped kinds' keys: the walk reached the nested tables


def test_the_generated_page_documents_every_key_of_every_kind():
    text = DOC.read_text()
    for kind, schema in SCHEMAS.items():
        assert f"### {kind}" in text
        for path, _ in _walk(schema):
            assert f"| `{path}` |" in text, (kind, path)


def test_validate_checks_every_key_with_file_schemas_checker(monkeypatch):
    seen = []
    real = fs.check_value

    def counting(f, value, where):
        seen.append(where)
        return real(f, value, where)
    monkeypatch.setattr(fs, "check_value", counting)
    file = PROBLEMS / "thesis_table_3_1.toml"
    data = tomllib.loads(file.read_text())
    out = validate(data, str(file))
    assert f"{file}: grid" in seen and f"{file}: rows[0].bearing_number" in seen
    assert len(seen) >= len(data)
    assert out["rows"][0]["bearing_number"] == data["rows"][0]["bearing_number"]


# ------------------------------------------------------------ the kinds study files added
def _refusal(f, value, where="f.toml: k"):
    with pytest.raises(ParameterError) as info:
        fs.check_value(f, value, where)
    return str(info.value)


def test_count_keeps_an_int_and_integer_still_gives_a_float():
    count = Field("n", "count", "-", "points", low=1)
    assert fs.check_value(count, 3, "k") == 3 and type(fs.check_value(count, 3, "k")) is int
    assert _refusal(count, 2.5) == "f.toml: k = 2.5: must be a whole number, >= 1 (points)"
    assert "must be a whole number" in _refusal(count, True)
    assert _refusal(count, 0) == "f.toml: k = 0: must be >= 1"
    bore_count = BORE.field("count")                     # the bearing file's, unchanged
    assert type(fs.check_value(bore_count, 3, "k")) is float


def test_a_string_list_is_a_list_only_and_strings_still_takes_one_string():
    names = Field("notes", "string_list", "-", "notes", default=[], choices=("a", "b"))
    assert fs.check_value(names, ["a", "b"], "k") == ["a", "b"]
    assert _refusal(names, "a") == "f.toml: k = 'a': must be a list (notes)"
    assert _refusal(names, ["a", "bb"]) == ("f.toml: k[1] = 'bb': must be one of a, b "
                                            "(did you mean 'b'?)")
    assert fs.check_value(Field("notes", "strings", "text", "free notes"), "x", "k") == "x"


def test_choices_of_a_string_may_be_a_callable():
    method = Field("method", "string", "-", "integration method",
                   choices=lambda: ("rk4", "rkc", "bdf"))
    assert fs.check_value(method, "rkc", "k") == "rkc"
    assert _refusal(method, "bdff") == ("f.toml: k = 'bdff': must be one of rk4, rkc, bdf "
                                        "(did you mean 'bdf'?)")
    assert method.rule() == 'one of "rk4", "rkc", "bdf"'


def test_numbers_check_their_length_and_their_items_bounds():
    pair = Field("kicks", "numbers", "-", "kicks", positive=True, length=2, why="kicks")
    assert fs.check_value(pair, [1, 2.5], "k") == [1.0, 2.5]
    assert _refusal(pair, [1.0]) == "f.toml: k = [1.0]: must have 2 entries (kicks)"
    assert _refusal(pair, [1.0, -1.0]) == "f.toml: k[1] = -1.0: must be > 0 (kicks)"
    plain = BORE.field("angle_deg")                      # no bounds: any finite numbers
    assert fs.check_value(plain, [-1e9, 5], "k") == [-1e9, 5.0]


def test_flag_grid_pairs_mapping_and_tables():
    assert _refusal(Field("f", "flag", "-", "x"), "yes") == ("f.toml: k = 'yes': must be "
                                                             "true or false")
    grid = Field("grid", "grid", "-", "grid")
    assert fs.check_value(grid, "24x8", "k") == "24x8"
    assert "must be even" in _refusal(grid, "24x7")
    pairs = Field("p", "pairs", "-", "pairs")
    assert fs.check_value(pairs, [["a", "b"]], "k") == [["a", "b"]]
    assert _refusal(pairs, [["a", 1]]) == ("f.toml: k[0] = ['a', 1]: must be a pair of "
                                           "variant labels")
    tol = Field("tolerance", "mapping", "-", "tolerances",
                values=Field("v", "number", "-", "tolerance", low=0.0, why="tolerance"))
    assert fs.check_value(tol, {"load": 1}, "k") == {"load": 1.0}
    assert _refusal(tol, {"load": -1}) == "f.toml: k.load = -1: must be >= 0 (tolerance)"
    rows = Field("rows", "tables", "-", "rows", table=Table("rows", "rows", (
        Field("x", "number", "-", "x"),), by_path=True))
    assert _refusal(rows, [{"x": 1}, {"y": 1}]) == ("f.toml: k[1].y = 1: is not a key of k[1] "
                                                    "(known: x)")
    assert _refusal(rows, {"x": 1}).startswith("f.toml: k = {'x': 1}: must be a list of tables")


def test_a_filling_table_fills_every_default_but_unset_and_copies_them():
    table = Table("t", "t", (Field("a", "numbers", "-", "a", default=[1.0]),
                             Field("b", "number", "-", "b", default=UNSET),
                             Field("c", "number", "-", "c"),
                             Field("d", "string", "-", "d", default=None)), fill=True)
    out = fs.check_table({"c": 2}, table, "f.toml: t")
    assert out == {"c": 2.0, "a": [1.0], "d": None}
    out["a"].append(5.0)
    assert table.field("a").default == [1.0]
    assert fs.check_table({"c": 2}, dataclasses.replace(table, fill=False),
                          "f.toml: t") == {"c": 2.0}          # the bearing files' way
    assert table.field("c").default is REQUIRED


def test_aliases_suggest_the_glossary_name():
    assert fs.did_you_mean("eps", ["eccentricity"]) == ""
    assert fs.did_you_mean("eps", ["eccentricity"], (("eps", "eccentricity"),)) == \
        " (did you mean 'eccentricity'?)"
    where = Where("x.toml")
    with pytest.raises(ParameterError, match=r"^x\.toml: Lambda = 2: is not a key of a study "
                                             r"of this kind \(did you mean 'bearing_number'"):
        spec.check_table({"Lambda": 2}, {"bearing_number": req("number", "Λ")}, where)


def test_req_and_opt_build_fields_with_the_study_spellings():
    k = opt("integer", 3, "seed", minimum=0)
    assert (k.kind, k.default, k.low, k.minimum, k.unit) == ("count", 3, 0, 0, "-")
    t = req("table", "fixed", keys={"eps": opt("number", 0.0, "ε"), "n": req("strings", "n")})
    assert t.required and t.keys["eps"].name == "eps" and t.keys["n"].kind == "string_list"


@pytest.mark.parametrize("kind", [[], {}, 3, None])
def test_a_kind_that_is_not_a_name_is_one_refusal(kind):
    with pytest.raises(ParameterError, match=r"^x\.toml: kind = .*: must be one of "):
        validate({"kind": kind, "title": "t"}, "x.toml")
