"""The kinds of :mod:`gfbopt.inputs.file_schema` that the study files need beside the bearing
and rotor files' (true or false, grids, a list of strings only, a list of tables, a table of
any names, pairs of labels), checked by :func:`check_study_kind`, which
:func:`gfbopt.inputs.file_schema.check_value` calls for them: one checker for every input
file.  Each refusal is one :class:`~gfbopt.errors.ParameterError` naming ``where`` (the file
and the key's path), the value and the rule.
"""
from __future__ import annotations

from dataclasses import replace

from ..errors import ParameterError

#: the allowed values of these kinds in words (:meth:`~gfbopt.inputs.file_schema.Field.rule`)
WORDS = {"flag": "true or false", "grid": 'a grid "NTHETAxNZ", e.g. "72x20"',
         "grids": "a list of grids", "string_list": "a list of strings",
         "tables": "a list of tables [[…]]", "mapping": "a table of name = value",
         "pairs": "a list of [label, label] pairs"}


def check_study_kind(f, value, where: str, check_value):
    """``value`` checked against the field ``f`` of one of :data:`WORDS`' kinds (a new,
    normalised value) or ParameterError naming ``where``; ``check_value``: file_schema's,
    for the items (passed in: this module does not import file_schema)."""
    def refuse(rule, v=value, at=where):
        return ParameterError(at, v, rule)
    kind = f.kind
    if kind == "flag":
        if not isinstance(value, bool):
            raise refuse("must be true or false")
        return value
    if kind == "grid":
        from .grid import Grid

        if not isinstance(value, str):
            raise refuse("must be a grid written NTHETAxNZ, e.g. \"72x20\"")
        try:
            Grid.parse(value)
        except ParameterError as exc:
            raise refuse(exc.rule) from None
        return value
    if kind == "mapping":
        if not isinstance(value, dict):
            raise refuse(f"must be a table ({f.doc})")
        return {name: check_value(f.values, v, f"{where}.{name}") for name, v in value.items()}
    if kind == "tables":
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            raise refuse(f"must be a list of tables ([[...]]) ({f.doc})")
        row = replace(f, kind="table")
        return [check_value(row, v, f"{where}[{k}]") for k, v in enumerate(value)]
    if not isinstance(value, list):                     # grids, string_list, pairs
        raise refuse(f"must be a list ({f.doc})")
    if f.length is not None and len(value) != f.length:
        raise refuse(f"must have {f.length} entries ({f.doc})")
    if kind == "pairs":
        for k, pair in enumerate(value):
            if (not isinstance(pair, list) or len(pair) != 2
                    or not all(isinstance(p, str) for p in pair)):
                raise refuse("must be a pair of variant labels", pair, f"{where}[{k}]")
        return [list(p) for p in value]
    item = replace(f, kind="grid" if kind == "grids" else "string", length=None)
    return [check_value(item, v, f"{where}[{k}]") for k, v in enumerate(value)]
