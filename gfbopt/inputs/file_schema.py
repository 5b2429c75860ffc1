"""The declarative schema of gfbopt's input files: one object per file format, read by the
validator and by the generator of the user documentation (``docs/formats/``, written by
:mod:`gfbopt.file_formats`), so that the two cannot drift.

A :class:`FileFormat` is a list of top-level :class:`Field` s and of :class:`Table` s; a table
is a list of fields (``array=True``: a list of tables, ``[[name]]`` in TOML).  Each field
states its kind, unit, default, allowed values or bounds and meaning; each table may state
rules between its fields (enforced by the object it builds, documented here).

:func:`check_file` refuses an unknown top-level key or table and an unknown key in a table
with "did you mean …?", a missing required one, a wrong type, a non-finite number and a
number out of its bounds — one :class:`~gfbopt.errors.ParameterError` naming the file, the
key, the value and the rule.

Adding a table to the bearing file (e.g. ``[bore]``, ``[[pads]]``, ``[[zones]]``) is one entry:
define ``Table("bore", "…", fields=(Field(...), ...))`` next to the code that builds it and add
it to :data:`BEARING_TABLES` below; the validator then accepts and checks it and the generated
docs describe it.  Its builder reads the checked table from
:func:`gfbopt.inputs.bearing_file.read_bearing_file`'s ``tables``.
"""
from __future__ import annotations

import copy
import difflib
import math
from dataclasses import dataclass, replace
from typing import Any, Optional

from ..errors import ParameterError
from .bearing_example import BEARING_EXAMPLE
from .bore import BORE_KINDS, END_RANGE_DEG, MAX_FEATURES, MAX_ZONES, START_RANGE_DEG
from .checks import FRICTION_COEFFICIENT_BELOW, WHY_FRICTION
from .model import (DEFLECTION_LAWS, FILM_MODELS, FOIL_MODELS, MAX_HARDENING_EXPONENT,
                    MIN_HARDENING_EXPONENT)

#: default of a required field
REQUIRED = object()
#: default of a field that is not stated and not filled in, even in a table that fills in
#: defaults (``Table.fill``; a study's model keys, inherited from ``[model]``)
UNSET = object()
#: field kinds: a finite number, a string, a string out of ``choices``, an angle in
#: degrees [0, 360) or "max_film", a string or a list of strings, a sub-table (the field's
#: ``table``, e.g. ``[bearings.model]``); and the study files' (:mod:`.schema_kinds`): an
#: int kept int ("count"), true or false, a grid and grids, a list of strings only, a list
#: of tables, a table of any names (each value checked against ``values``), label pairs
KINDS = ("number", "integer", "numbers", "string", "choice", "seam_angle", "strings", "text",
         "table", "count", "flag", "grid", "grids", "string_list", "tables", "mapping",
         "pairs")


@dataclass(frozen=True)
class Field:
    """One key of a file or table.

    name, kind (:data:`KINDS`), unit ("m", "Pa", "deg", "-", "text"), doc (meaning);
    default (:data:`REQUIRED`: must be given; None: not stated); choices (kind "choice");
    low / high: inclusive bounds of a number, or ``positive`` for > 0; below: an exclusive
    upper bound; off: one value allowed outside the bounds, meaning "off" (e.g. 0 of an
    exponent whose other values lie in [1, 10]); why: the reason of the bounds (shown in
    refusals and docs); table: the :class:`Table` a field of kind "table"
    or "tables" is checked against; length: the exact length of a list; values: the
    :class:`Field` every value of a "mapping" is checked against.  ``choices`` of a
    "string" (or of the items of a list) restrict it too, and may be a callable returning
    them (evaluated when checking).
    """

    name: str
    kind: str
    unit: str
    doc: str
    default: Any = REQUIRED
    choices: tuple = ()
    low: Optional[float] = None
    high: Optional[float] = None
    positive: bool = False
    why: str = ""
    below: Optional[float] = None
    off: Optional[float] = None
    table: Any = None
    length: Optional[int] = None
    values: Any = None

    @property
    def required(self) -> bool:
        return self.default is REQUIRED

    @property
    def minimum(self) -> Optional[float]:
        """``low`` (the study schemas' spelling)."""
        return self.low

    @property
    def maximum(self) -> Optional[float]:
        """``high`` (the study schemas' spelling)."""
        return self.high

    @property
    def keys(self) -> Optional[dict]:
        """{name: field} of the table of a "table" or "tables" field, else None."""
        return None if self.table is None else {f.name: f for f in self.table.fields}

    def options(self) -> tuple:
        """The allowed values (``choices``, called if it is a callable)."""
        return tuple(self.choices() if callable(self.choices) else self.choices)

    def rule(self) -> str:
        """The allowed values in words."""
        if self.kind == "choice" or (self.kind == "string" and self.choices):
            return "one of " + ", ".join(f'"{c}"' for c in self.options())
        if self.kind in _STUDY_KINDS:
            from .schema_kinds import WORDS

            return WORDS[self.kind]
        if self.kind == "seam_angle":
            return 'degrees in [0, 360), or "max_film"'
        if self.kind in ("string", "text"):
            return "a string"
        if self.kind == "strings":
            return "a string or a list of strings"
        if self.kind == "numbers":
            return "a list of finite numbers"
        if self.kind == "table":
            return f"a table of [{self.table.name}]'s keys"
        parts = []
        if self.positive:
            parts.append("> 0")
        if self.low is not None:
            parts.append(f">= {self.low:g}")
        if self.high is not None:
            parts.append(f"<= {self.high:g}")
        if self.below is not None:
            parts.append(f"< {self.below:g}")
        noun = "a whole number" if self.kind in ("integer", "count") else "a finite number"
        off = "" if self.off is None else f" {self.off:g} (off) or"
        return noun + (f",{off} {' and '.join(parts)}" if parts else "")


@dataclass(frozen=True)
class Table:
    """A TOML table ``[name]`` (or ``[[name]]`` with ``array=True``) of a file format.

    rules : constraints between fields, in words (enforced by the object the table builds).
    fill : the checked table has every field whose default is neither :data:`REQUIRED` nor
        :data:`UNSET` (a copy of the default filled in; the study files' tables).
    aliases : (old spelling or symbol, field name) pairs suggested for an unknown key.
    by_path : a refusal of an unknown key names the table by its path in the file
        (``rows[2]``, the text after the last ": " of ``where``), not by ``[name]``.
    """

    name: str
    doc: str
    fields: tuple
    required: bool = False
    array: bool = False
    rules: tuple = ()
    fill: bool = False
    aliases: tuple = ()
    by_path: bool = False

    def field(self, name: str) -> Field:
        return {f.name: f for f in self.fields}[name]


@dataclass(frozen=True)
class FileFormat:
    """A whole input file: top-level fields, tables and a complete example."""

    name: str
    doc: str
    top: tuple
    tables: tuple
    example: str

    def table(self, name: str) -> Table:
        return {t.name: t for t in self.tables}[name]


def did_you_mean(name: str, known, aliases=()) -> str:
    """" (did you mean 'x'?)" for a misspelt ``name``, or "".  ``aliases``: (alias, name)
    pairs; ``name`` equal to an alias (or the alias and at most two characters more) of a
    known name suggests that name first."""
    known = list(known)
    name = str(name)
    for alias, target in aliases:
        near = name == alias or (name.startswith(alias) and len(name) - len(alias) <= 2
                                 and len(alias) > 2)
        if near and target in known:
            return f" (did you mean '{target}'?)"
    close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
    return f" (did you mean '{close[0]}'?)" if close else ""


def check_value(f: Field, value, where: str):
    """``value`` checked against field ``f`` (normalised: numbers as float) or
    ParameterError naming ``where``."""
    def refuse(rule):
        return ParameterError(where, value, rule)
    if f.kind in ("string", "text"):
        if not isinstance(value, str):
            raise refuse(f"must be a string ({f.doc})")
        options = f.options()
        if options and value not in options:
            raise refuse(f"must be one of {', '.join(options)}" + did_you_mean(value, options))
        return value
    if f.kind in _STUDY_KINDS:
        from .schema_kinds import check_study_kind

        return check_study_kind(f, value, where, check_value)
    if f.kind == "strings":
        items = [value] if isinstance(value, str) else value
        if not isinstance(items, list) or not all(isinstance(v, str) for v in items):
            raise refuse("must be a string or a list of strings")
        return value
    if f.kind == "choice":
        if not isinstance(value, str) or value not in f.choices:
            raise refuse(f"must be {f.rule()}" + did_you_mean(value, f.choices))
        return value
    if f.kind == "table":
        return check_table(value, f.table, where)
    if f.kind == "seam_angle" and value == "max_film":
        return value
    if f.kind == "numbers":
        if not isinstance(value, list):
            raise refuse(f"must be {f.rule()} ({f.doc})")
        if f.length is not None and len(value) != f.length:
            raise refuse(f"must have {f.length} entries ({f.doc})")
        item = replace(f, kind="number", length=None)
        return [check_value(item, v, f"{where}[{k}]") for k, v in enumerate(value)]
    if f.kind in ("integer", "count") and (isinstance(value, bool)
                                           or not isinstance(value, int)):
        raise refuse(f"must be {f.rule()} ({f.doc})")
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise refuse(f"must be {f.rule()} ({f.doc}" + (f" [{f.unit}])" if f.unit not in
                                                        ("-", "text") else ")"))
    try:
        number = float(value)
    except OverflowError:               # an integer beyond the float range
        number = math.inf
    if not math.isfinite(number):
        raise refuse("must be finite (not NaN or infinite)")
    if f.kind == "seam_angle":
        if not 0.0 <= number < 360.0:
            raise refuse("must lie in [0, 360) degrees from the load line in the direction "
                         "of rotation, or be \"max_film\"")
        return number
    why = f" ({f.why})" if f.why else ""
    if f.off is not None and number == f.off:
        return number
    if f.positive and number <= 0:
        raise refuse(f"must be > 0{why}")
    unit = "" if f.unit in ("-", "text") else f" {f.unit}"
    off = "" if f.off is None else f"{f.off:g} (off) or "
    if f.low is not None and number < f.low:
        raise refuse(f"must be {off}>= {f.low:g}{unit}{why}")
    if f.high is not None and number > f.high:
        raise refuse(f"must be {off}<= {f.high:g}{unit}{why}")
    if f.below is not None and number >= f.below:
        raise refuse(f"must be < {f.below:g}{unit}{why}")
    return value if f.kind == "count" else number


#: the kinds checked by :mod:`.schema_kinds` (the study files' lists, tables and flags)
_STUDY_KINDS = ("flag", "grid", "grids", "string_list", "tables", "mapping", "pairs")


def check_fields(data: dict, fields: tuple, where: str, what: str, *,
                 prefix: Optional[str] = None, fill: bool = False, aliases=()) -> dict:
    """The keys of ``data`` checked against ``fields``: unknown keys refused (did you mean,
    with ``aliases``), required keys demanded; returns the stated keys, checked, and with
    ``fill`` the defaults of the others (:class:`Table`'s ``fill``).  ``prefix``: what
    precedes a key's name in a refusal (default ``where.``)."""
    if not isinstance(data, dict):
        raise ParameterError(where, data, f"must be a table ({what})")
    schema = {f.name: f for f in fields}
    if prefix is None:
        prefix = f"{where}." if where else ""
    for name in data:
        if name not in schema:
            raise ParameterError(f"{prefix}{name}", data[name], f"is not a key of {what}"
                                 f"{did_you_mean(name, schema, aliases)} (known: "
                                 f"{', '.join(schema)})")
    for f in fields:
        if f.required and f.name not in data:
            raise ParameterError(f"{prefix}{f.name}", None, f"is required ({f.doc})")
    out = {name: check_value(schema[name], value, f"{prefix}{name}")
           for name, value in data.items()}
    if fill:
        out.update((f.name, copy.deepcopy(f.default)) for f in fields if f.name not in out
                   and f.default is not REQUIRED and f.default is not UNSET)
    return out


def check_table(data, table: Table, where: str, prefix: Optional[str] = None) -> dict:
    """One table (a dict) checked against ``table``; see :func:`check_fields`."""
    what = where.rsplit(": ", 1)[-1] if table.by_path else f"[{table.name}]"
    return check_fields(data, table.fields, where, what, prefix=prefix,
                        fill=table.fill, aliases=table.aliases)


def check_file(data: dict, fmt: FileFormat, where: str, first_row: int = 1) -> dict:
    """A parsed file checked against ``fmt``: top-level keys and tables (unknown ones refused
    with did-you-mean), each table key by key.  Returns {name: checked value}, a list of
    checked tables for ``array`` tables (rows named ``name[k]`` from ``first_row``: every
    file counts its tables from 1, the first ``[[zones]]`` being ``zones[1]``)."""
    top = {f.name: f for f in fmt.top}
    tables = {t.name: t for t in fmt.tables}
    known = [*top, *tables]
    out = {}
    for name, value in data.items():
        if name in tables:
            t = tables[name]
            if t.array:
                if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
                    raise ParameterError(f"{where}: {name}", value,
                                         f"must be a list of tables ([[{name}]])")
                out[name] = [check_table(v, t, f"{where}: {name}[{k}]")
                             for k, v in enumerate(value, first_row)]
            else:
                out[name] = check_table(value, t, f"{where}: {name}")
        elif name in top:
            out[name] = check_value(top[name], value, f"{where}: {name}")
        else:
            kind = "table" if isinstance(value, dict) else "key"
            raise ParameterError(f"{where}: {name}", "…" if kind == "table" else value,
                                 f"is not a {kind} of a {fmt.name}{did_you_mean(name, known)}"
                                 f" (known: {', '.join(known)})")
    for t in fmt.tables:
        if t.required and t.name not in data:
            raise ParameterError(f"{where}: [{t.name}]", None,
                                 f"table is required but missing ({t.doc})")
    return out


# ------------------------------------------------------------------ the bearing file
_WHY_SIZE = "a journal bearing of 1 mm to 1 m radius"
_WHY_MODULUS = "a metal foil: 1 MPa to 10 TPa"
_WHY_TURN = "a turn either way from the load line"

#: the ``[bearing]`` table: the bearing in SI units (:class:`~gfbopt.inputs.BearingGeometry`)
BEARING = Table("bearing", "the bearing's dimensions and materials, SI units", required=True,
                fields=(
    Field("name", "string", "text", "label used in reports", default="bearing"),
    Field("radius", "number", "m", "journal (bearing) radius R", low=1e-3, high=1.0,
          why=_WHY_SIZE),
    Field("length", "number", "m", "axial length L", low=1e-4,
          why="0.05 <= L/D <= 10 is checked with the radius"),
    Field("radial_clearance", "number", "m", "radial clearance c", low=1e-6,
          why="below 1 µm the gas film is no longer a continuum; c/R <= 0.01 is checked with "
              "the radius"),
    Field("bump_pitch", "number", "m", "bump pitch s", low=1e-5,
          why="2 l0 <= s and s <= π R are checked with the other dimensions"),
    Field("bump_half_length", "number", "m", "half bump length l0", low=1e-6),
    Field("bump_thickness", "number", "m", "bump foil thickness t_b", low=1e-6,
          why="t_b < l0 is checked with the half length"),
    Field("bump_youngs_modulus", "number", "Pa", "Young's modulus of the bump foil E_b",
          low=1e6, high=1e13, why=_WHY_MODULUS),
    Field("top_foil_youngs_modulus", "number", "Pa", "Young's modulus of the top foil E_t",
          low=1e6, high=1e13, why=_WHY_MODULUS),
    Field("poisson_ratio", "number", "-", "Poisson's ratio ν of the bump foil", low=-0.999,
          high=0.499, why="an isotropic solid has -1 < ν < 0.5"),
    Field("top_foil_thickness", "number", "m", "top foil thickness t_t", low=1e-6,
          why="t_t <= R/10 is checked with the radius"),
    Field("viscosity", "number", "Pa s", "gas dynamic viscosity μ", low=1e-7, high=1.0,
          why="gases: about 1e-6 to 1e-4 Pa s"),
    Field("ambient_pressure", "number", "Pa", "ambient pressure p_a", default=101325.0,
          low=100.0, high=1e8, why="100 Pa to 1000 bar"),
), rules=(
    "c/R <= 0.01 (the thin-film Reynolds equation needs a clearance small against the radius)",
    "0.05 <= L/D <= 10",
    "2 l0 <= s (a bump spans 2 l0 and must fit in its pitch)",
    "t_b < l0 (each half bump is a slender beam in Heshmat's compliance formula)",
    "s <= π R (at least two bumps round the bearing)",
    "t_t <= R/10 (a thin top foil)",
    "the compliance S = p_a α/c <= 1000 and the top-foil coefficient C <= 10^4 (the "
    "non-dimensional model's bounds)",
))

#: the bumps' Coulomb friction (:mod:`gfbopt.physics.friction`) and hardening
#: (:mod:`gfbopt.physics.hardening`) in ``[model]``
BUMP_FIELDS = (
    Field("friction_coefficient", "number", "-", "Coulomb friction coefficient μ_f of the "
          "slider beside each bump (spring–slider element; slip force per unit area μ_f "
          "times the local gauge pressure); default 0: no friction", default=None, low=0.0,
          below=FRICTION_COEFFICIENT_BELOW, why=WHY_FRICTION),
    Field("friction_stiffness_ratio", "number", "-", "stiffness of the friction element's "
          "spring over the bump's, κ = k_f/k_b (the stuck foundation is k_b (1 + κ)); "
          "default 1", default=None, positive=True, high=1e3, why="k_f/k_b"),
    Field("bump_height", "number", "m", "bump height h_b, the hard limit of the hardening "
          "bump", default=None, positive=True, high=1e-2, why="a bump foil: below 1 cm"),
    Field("hardening_limit", "number", "m", "deflection δ_lim at which the hardening bump "
          "k0/(1 − δ/δ_lim)^n is flat; <= bump_height; default bump_height", default=None,
          positive=True),
    Field("hardening_exponent", "number", "-", "exponent n of the hardening bump "
          "k0/(1 − δ/δ_lim)^n; default 0: off (the linear bump)", default=None, off=0.0,
          low=MIN_HARDENING_EXPONENT, high=MAX_HARDENING_EXPONENT, why="n < 1 flattens the "
          "bump at a finite load; n = 1–3 covers a gentle to an abrupt stiffening"),
)

#: the optional ``[model]`` table: the formulation the bearing is analysed with
#: (:class:`~gfbopt.inputs.options.ModelOptions`); what it does not state takes the defaults
#: of :func:`~gfbopt.inputs.options.resolve_model_options`
MODEL = Table("model", "the formulation the bearing is analysed with by every route (command "
              "line, Python API, studies); options not stated take gfbopt's defaults, and an "
              "option given on the command line or as a keyword argument wins", fields=(
    Field("film", "choice", "text", "film convention: periodic (full 360° film, no seam) or "
          "seam (the top foil's ends open to ambient)", default=None, choices=FILM_MODELS),
    Field("seam_angle_deg", "seam_angle", "deg", "welded end of the top foil from the load "
          "line in the direction of rotation, or \"max_film\" (the seam on the maximum-film "
          "line, the thesis's convention); default 180 with a seam", default=None),
    Field("foil", "choice", "text", "foil model: rigid (plain gas bearing), simple (elastic "
          "foundation W = S(P − 1)), beam (1D top foil on the bumps); default simple",
          default=None, choices=FOIL_MODELS),
    Field("deflection_law", "choice", "text", "mean: W = S(P̄ − 1) (axially averaged "
          "pressure); local: W = S(P − 1) (simple foil only); default mean", default=None,
          choices=DEFLECTION_LAWS),
    Field("loss_factor", "number", "-", "structural loss factor η of the bumps; default 0",
          default=None, low=0.0, high=1.0, why="a fraction: 0.2 means 20 %"),
    *BUMP_FIELDS,
), rules=(
    "friction_coefficient > 0 needs a bump foundation of foil 'simple' (refused with foil "
    "'rigid' or S = 0: no bumps to rub; and with foil 'beam': its foundation has no "
    "per-unit friction element yet)",
    "hardening_limit <= bump_height (the bump height is the hard limit); hardening_exponent "
    "> 0 needs bump_height, foil 'simple' and deflection_law 'mean' (the 'hardened' law)",
))

#: the bearing as built (helper "bore", :mod:`gfbopt.inputs.bore_si`, which builds them and
#: checks the rules between their keys): a bore profile, top-foil pads and bump zones
BORE = Table("bore", "the bore profile (shims, lobes or a measured table) that preloads the "
             "bearing; a round bore when absent", fields=(
    Field("kind", "choice", "text", "bore profile", choices=BORE_KINDS),
    Field("count", "integer", "-", "number of shims or lobes (shims, lobes)", default=None,
          low=1, high=MAX_FEATURES, why="more are a surface finish, not a preload profile"),
    Field("preload_depth", "number", "m", "preload: depth of the shims or lobes (or "
          "preload_ratio)", default=None, positive=True),
    Field("preload_ratio", "number", "-", "preload over the radial clearance (or "
          "preload_depth)", default=None),
    Field("width_deg", "number", "deg", "shim width (shims: required)", default=None,
          positive=True, why="negative or zero shim width"),
    Field("offset_deg", "number", "deg", "centre of the first shim or lobe from the load "
          "line", default=None, low=START_RANGE_DEG[0], high=START_RANGE_DEG[1],
          why=_WHY_TURN),
    Field("angle_deg", "numbers", "deg", "angles of a measured bore (kind table), in [0, 360)",
          default=None),
    Field("clearance_change", "numbers", "m", "change of the radial clearance at those angles "
          "(kind table)", default=None)),
    rules=(f"shims and lobes: 1 <= count <= {MAX_FEATURES} and exactly one of preload_depth, "
           "preload_ratio",
           "preload_depth < radial_clearance (the film must stay open with the journal "
           "concentric)"))
PADS = Table("pads", "one table per top foil (pad): a segmented bearing; one 360° top foil "
             "when absent", array=True, fields=(
    Field("leading_end_deg", "number", "deg", "welded (leading) end from the load line",
          low=START_RANGE_DEG[0], high=START_RANGE_DEG[1], why=_WHY_TURN),
    Field("arc_deg", "number", "deg", "arc of the pad", positive=True,
          why="negative or zero pad width")),
    rules=("pads need a seamed film; with a seam stated, it sits on a pad's leading end",
           f"at most {MAX_FEATURES} pads; a rigid foil has none"))
ZONES = Table("zones", "bump zones with their own bump geometry, covering 360° once; a "
              "uniform foundation when absent", array=True, fields=(
    Field("start_deg", "number", "deg", "start of the zone from the load line",
          low=START_RANGE_DEG[0], high=START_RANGE_DEG[1], why=_WHY_TURN),
    Field("end_deg", "number", "deg", "end of the zone (> start; above 360 through 0°)",
          low=END_RANGE_DEG[0], high=END_RANGE_DEG[1]),
    *(replace(BEARING.field(key), doc=f"{BEARING.field(key).doc} (default: [bearing]'s)",
              default=None) for key in ("bump_pitch", "bump_half_length", "bump_thickness")),
    replace(BUMP_FIELDS[0], doc="Coulomb friction coefficient μ_f of this zone's bumps "
            "(default: [model]'s)")),
    rules=(f"at most {MAX_ZONES} zones; each zone's bumps obey [bearing]'s rules (2 l0 <= s, "
           "t_b < l0, s <= π R, S <= 1000); zones need a bump foil (not foil 'rigid')",))

#: the tables of a bearing file; adding a table is one entry here (module docstring)
BEARING_TABLES = (BEARING, MODEL, BORE, PADS, ZONES)


#: the bearing file (``problems/bearings/*.toml``, ``--bearing FILE``)
BEARING_FILE = FileFormat(
    "bearing file",
    "A bump-type gas foil journal bearing in SI units, and optionally the formulation it is "
    "analysed with.  Read by `gfbopt.load_bearing`, `--bearing FILE` of the commands, and "
    "the `bearing =` key of study files; the same file gives the same answer by every route.",
    top=(Field("source", "string", "text", "citation of where the dimensions come from",
               default=None),
         Field("notes", "strings", "text", "free notes (not interpreted)", default=None)),
    tables=BEARING_TABLES, example=BEARING_EXAMPLE)
