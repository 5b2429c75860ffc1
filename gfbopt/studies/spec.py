"""The typed study specification: one schema per study kind, checked before any solving.

A study file is a TOML table.  Its keys are the Python names of :mod:`gfbopt.glossary`
(``bearing_number``, ``compliance``, ``eccentricity``, ``length_ratio``,
``seam_angle_deg``, …), the same names as the columns the study writes.  :func:`validate`
checks the whole file against the schema of its ``kind``: an unknown or missing key, a value
of the wrong type or an unknown value raises one :class:`~gfbopt.errors.ParameterError`
naming the file, the key's path and what was expected, e.g.
``problems/x.toml: rows[2].epss = 0.3: is not a key of rows[2] (did you mean
'eccentricity'?…)``.  The result is a new dict with every optional key present (its default
filled in).

The schemas are written in the language of every input file, :mod:`gfbopt.inputs.file_schema`:
:func:`req` and :func:`opt` build its :class:`~gfbopt.inputs.file_schema.Field` s (a
``table``/``tables`` key's ``keys`` a :class:`~gfbopt.inputs.file_schema.Table` that fills in
defaults and suggests the glossary's :data:`ALIASES`), and :func:`validate`,
:func:`check_table` and :func:`check_value` are file_schema's checker
(:func:`~gfbopt.inputs.file_schema.check_fields`), so the study, bearing and rotor files are
refused in the same words and ``docs/formats/`` is generated from the same objects.

Tolerances are spelt ``<what>_tolerance`` everywhere; a comparison with a published value
is a ``tolerance = {quantity = value}`` table whose values are relative, except for angles
(``*_deg``), which are in degrees (:func:`gfbopt.glossary.deviation`).
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Optional

from ..errors import ParameterError
from ..inputs import (
    DEFAULT_GRID,
    DEFLECTION_LAWS,
    FILM_MODELS,
    FOIL_MODELS,
    SUBAMBIENT_TREATMENTS,
)
from ..inputs.file_schema import (
    REQUIRED,
    UNSET,
    Field,
    Table,
    check_fields,
    did_you_mean,
)
from ..inputs.file_schema import check_value as check_field

#: symbols and older spellings → the glossary name (for "did you mean …?")
ALIASES = {"eps": "eccentricity", "epsilon": "eccentricity", "Lambda": "bearing_number",
           "S": "compliance", "C": "top_foil_coefficient", "L_over_D": "length_ratio",
           "attitude_deg": "attitude_angle_deg", "min_film_um": "min_film_thickness_um",
           "tolerance_nonlinear_linear": "nonlinear_linear_tolerance",
           "tolerance": "critical_mass_tolerance", "eps0": "eccentricity",
           "thesis_orbits": "orbits"}
_ALIAS_PAIRS = tuple(ALIASES.items())
#: a study kind's spelling → file_schema's kind, where they differ (a study's integer stays
#: an int; its list of strings is a list, not a bare string)
_KINDS = {"integer": "count", "strings": "string_list"}


def _key(kind: str, doc: str, default, *, choices=(), keys: Optional[dict] = None,
         values: Optional[Field] = None, minimum: Optional[float] = None,
         positive: bool = False, length: Optional[int] = None,
         maximum: Optional[float] = None) -> Field:
    """One key of a study file as a :class:`~gfbopt.inputs.file_schema.Field` (named when
    it is placed in a table: :func:`_fields`).

    kind : number, integer, string, flag, grid, seam_angle, numbers, strings, grids, pairs,
        table (``keys`` is its schema), tables (a list of such tables) or mapping (any
        names, each value checked against ``values``)
    doc : meaning and unit (shown in errors)
    default : :data:`REQUIRED` for a required key; :data:`UNSET`: not filled in
    choices : allowed values (a callable returning them is evaluated when checking)
    minimum : smallest allowed number; ``positive`` → must be > 0; maximum : largest
    length : exact length of a list
    """
    return Field("", _KINDS.get(kind, kind), "-", doc, default=default, choices=choices,
                 low=minimum, high=maximum, positive=positive, why=doc, length=length,
                 values=values, table=None if keys is None else _table("", doc, keys))


def req(kind: str, doc: str, **kw) -> Field:
    """A required key (:func:`_key`)."""
    return _key(kind, doc, REQUIRED, **kw)


def opt(kind: str, default, doc: str, **kw) -> Field:
    """An optional key and its default (:func:`_key`)."""
    return _key(kind, doc, default, **kw)


def _named(name: str, key: Field) -> Field:
    """``key`` placed under ``name`` (its table and a mapping's values named after it)."""
    return replace(key, name=name,
                   table=None if key.table is None else replace(key.table, name=name),
                   values=None if key.values is None else _named(f"{name}.NAME", key.values))


def _fields(schema: dict) -> tuple:
    """The named fields of a schema {name: key}."""
    return tuple(_named(name, key) for name, key in schema.items())


def _table(name: str, doc: str, schema: dict) -> Table:
    """A study table: defaults filled in, the glossary's aliases suggested."""
    return Table(name, doc, _fields(schema), fill=True, aliases=_ALIAS_PAIRS, by_path=True)


# ----------------------------------------------------------------- shared key groups
def _transient_methods() -> tuple:
    from ..transient import METHODS

    return tuple(METHODS)


#: the formulation of a model (what a dimensional bearing file does not fix)
FORMULATION = {
    "foil": opt("string", UNSET, "foil model (default simple)", choices=FOIL_MODELS),
    "film": opt("string", UNSET, "film: periodic (default) or seam", choices=FILM_MODELS),
    "seam_angle_deg": opt("seam_angle", UNSET, "welded end from the load line [deg], or "
                          "'max_film' (default)"),
    "deflection_law": opt("string", UNSET, "foil deflection law (default mean)",
                          choices=DEFLECTION_LAWS),
    "subambient": opt("string", UNSET, "force from sub-ambient pressure (default full)",
                      choices=SUBAMBIENT_TREATMENTS),
    "compression_only": opt("flag", UNSET, "bumps act in compression only (default false)"),
}
#: the non-dimensional groups of a model (a point may require some)
GROUPS = {
    "bearing_number": opt("number", UNSET, "bearing number Λ [-]", positive=True),
    "compliance": opt("number", UNSET, "compliance S [-] (default 0)", minimum=0.0),
    "length_ratio": opt("number", UNSET, "L/D [-] (default 1)", positive=True),
    "top_foil_coefficient": opt("number", UNSET, "top-foil coefficient C [-] (default 0)",
                                minimum=0.0),
}
MODEL = {**GROUPS, **FORMULATION}
VARIANT = {"label": req("string", "label of the variant"), **MODEL}
#: the formulation of a study on a bearing file: what is not stated comes from the file's
#: [model] table, then gfbopt's defaults (gfbopt.analyses.bearing_model, the CLI's resolution)
DIMENSIONAL_FORMULATION = {
    **FORMULATION,
    "foil": opt("string", UNSET, "foil model (default: the bearing file's, else simple)",
                choices=FOIL_MODELS),
    "film": opt("string", UNSET, "film (default: the bearing file's, else seam)",
                choices=FILM_MODELS),
    "seam_angle_deg": opt("seam_angle", UNSET, "welded end from the load line [deg], or "
                          "'max_film' (default: the bearing file's, else 180)"),
    "deflection_law": opt("string", UNSET, "foil deflection law (default: the bearing "
                          "file's, else mean)", choices=DEFLECTION_LAWS)}
DIMENSIONAL_VARIANT = {"label": req("string", "label of the variant"),
                       **DIMENSIONAL_FORMULATION}

COMMON = {
    "name": opt("string", None, "study name (default: the file name)"),
    "kind": req("string", "study kind"),
    "title": req("string", "title, for bearing engineers"),
    "source": opt("string", UNSET, "full citation of the source, with table or figure "
                  "(required of a shipped study: a file in gfbopt's problems/ folder)"),
    "notes": opt("strings", [], "notes printed in the report"),
}
GRID = {"grid": opt("grid", str(DEFAULT_GRID), "finite-difference grid NTHETAxNZ")}
METHOD = {"method": opt("string", "rk4", "transient integration method",
                        choices=_transient_methods)}


def _point(required=("eccentricity", "bearing_number"), **extra) -> dict:
    """Keys of an operating point: the model's groups and formulation, ε, a label."""
    keys = {**MODEL, "eccentricity": opt("number", UNSET, "eccentricity ratio ε [-]",
                                         minimum=0.0), **extra}
    for name in required:
        keys[name] = replace(keys[name], default=REQUIRED)
    return keys


COMPARISON = {
    "variant": opt("string", "default", "variant compared"),
    "reference": req("string", "published source compared with (a key of `published`)"),
    "tolerance": req("mapping", "largest deviation per quantity: relative, or degrees for "
                     "*_deg", values=req("number", "tolerance", minimum=0.0)),
}
PUBLISHED_VALUES = req("mapping", "published quantities (glossary names)",
                       values=req("number", "published value"))
STABILITY = {
    "sweep": req("table", "the swept variable", keys={
        "variable": req("string", "swept input", choices=("eccentricity", "bearing_number")),
        "values": req("numbers", "its values")}),
    "fixed": req("table", "the inputs held fixed", keys={
        "eccentricity": opt("number", UNSET, "ε [-]", minimum=0.0),
        "bearing_number": opt("number", UNSET, "Λ [-]", positive=True),
        "length_ratio": opt("number", 1.0, "L/D [-]", positive=True)}),
    "model": opt("table", {}, "formulation shared by the variants", keys=FORMULATION),
    "variants": req("tables", "model variants", keys=VARIANT),
    "crossover_pairs": opt("pairs", [], "[variant, against] pairs whose crossing is sought"),
    "published": opt("string", None, "file of published stability results (problems/"
                     "published/*.toml), relative to the study file"),
}
TRANSIENT_SEARCH = {
    "critical_mass_tolerance": opt("number", 0.005, "relative bracket of the transient "
                                   "critical-mass search", positive=True),
    "revolutions": opt("number", None, "shaft revolutions per transient (default: one "
                       "whirl period from the least-stable linear mode)", positive=True),
    "start": opt("string", "mode", "start of each transient: the least-stable linear mode "
                 "shape, or a small kick", choices=("mode", "kick")),
    "nonlinear_linear_tolerance": opt("number", 0.01, "largest |nonlinear/linear − 1| of "
                                      "the critical mass", minimum=0.0),
    "method": opt("string", "rkc", "transient integration method (rkc: stabilised "
                  "Runge-Kutta-Chebyshev, ~13x faster than rk4 at equal accuracy)",
                  choices=_transient_methods),
}

SCHEMAS: dict[str, dict] = {
    "static_table": {**GRID,
        "references": req("strings", "names of the published sources of the rows"),
        "model": opt("table", {}, "formulation shared by the variants", keys=MODEL),
        "variants": opt("tables", [{"label": "default"}], "model variants", keys=VARIANT),
        "comparisons": opt("tables", [], "comparisons with the published rows",
                           keys=COMPARISON),
        "rows": req("tables", "operating points", keys=_point(
            published=opt("mapping", {}, "published values per source",
                          values=PUBLISHED_VALUES)))},
    "profile": {**GRID,
        "point": req("table", "the operating point", keys={
            "bearing_number": req("number", "Λ [-]", positive=True),
            "eccentricity": req("number", "ε [-]", minimum=0.0),
            "compliance": opt("number", 0.0, "S [-]", minimum=0.0),
            "length_ratio": opt("number", 1.0, "L/D [-]", positive=True),
            "top_foil_coefficient": opt("number", 0.0, "C [-]", minimum=0.0)}),
        "model": opt("table", {}, "formulation shared by the variants", keys=FORMULATION),
        "variants": req("tables", "model variants", keys={"label": req("string", "label"),
                                                          **FORMULATION}),
        "published": opt("mapping", {}, "published peak values per source",
                         values=PUBLISHED_VALUES),
        "comparisons": opt("tables", [], "comparisons with the published values",
                           keys=COMPARISON)},
    "grid_convergence": {
        "grids": req("grids", "grids refined by 2, coarsest first"),
        "default_grid": opt("grid", str(DEFAULT_GRID), "grid whose error is reported"),
        "also_report": opt("grids", [], "further grids whose error is reported"),
        "order_tolerance": req("number", "largest |observed order − 2|", minimum=0.0),
        "default_grid_load_tolerance": req("number", "largest relative load error of the "
                                           "default grid", minimum=0.0),
        "cases": req("tables", "cases", keys=_point(label=req("string", "label")))},
    "concentric_impedance": {**GRID,
        "eccentricity": req("number", "small eccentricity ε [-]", positive=True),
        "whirl_ratios": req("numbers", "whirl ratios γ [-]"),
        "impedance_tolerance": req("number", "largest max|Z − Z_Ausman| / max|Z_Ausman|",
                                   minimum=0.0),
        "cases": req("tables", "bearings", keys={
            "bearing_number": req("number", "Λ [-]", positive=True),
            "length_ratio": opt("number", 1.0, "L/D [-]", positive=True)})},
    "load_sweep": {**GRID,
        "bearing": req("string", "bearing file (SI), relative to the study file"),
        "speeds_rpm": req("numbers", "shaft speeds [rpm]"),
        "loads_newton": req("numbers", "static loads [N], increasing"),
        "trends": opt("strings", [], "monotone trends checked",
                      choices=("min_film_thickness_decreases_with_load",
                               "eccentricity_increases_with_load")),
        "model": opt("table", {}, "formulation shared by the variants (over the bearing "
                     "file's [model])", keys=DIMENSIONAL_FORMULATION),
        "variants": req("tables", "model variants", keys=DIMENSIONAL_VARIANT)},
    "linear_coefficients": {**GRID,
        "bearing": req("string", "bearing file (SI), relative to the study file"),
        "speeds_rpm": req("numbers", "shaft speeds [rpm]"),
        "loads_newton": req("numbers", "static loads [N]"),
        "whirl_ratios": req("numbers", "excitation frequency over shaft speed [-]"),
        "model": opt("table", {}, "formulation shared by the variants (over the bearing "
                     "file's [model])", keys=DIMENSIONAL_FORMULATION),
        "variants": req("tables", "model variants", keys=DIMENSIONAL_VARIANT)},
    "linear_map": {**GRID, **STABILITY,
        "trends": opt("strings", [], "monotone trends checked",
                      choices=("critical_mass_increases_with_eccentricity",)),
        "whirl_ratio_range": opt("numbers", None, "[low, high] of the threshold whirl ratio",
                                 length=2)},
    "transient_map": {**GRID, **STABILITY, **TRANSIENT_SEARCH},
    "transient_points": {**GRID, **TRANSIENT_SEARCH,
        "model": opt("table", {}, "formulation shared by the points", keys=MODEL),
        "points": req("tables", "operating points", keys=_point(label=req("string", "label")))},
    "orbits": {**GRID, **METHOD,
        "revolutions": req("number", "shaft revolutions per orbit", positive=True),
        "kick": req("number", "initial journal speed from the equilibrium [-]", positive=True),
        "model": opt("table", {}, "formulation shared by the cases", keys=FORMULATION),
        "published": req("string", "file of published stability results whose "
                         "critical_masses give the cases (masses and verdicts)")},
    "bifurcation": {**GRID,
        "eccentricity": req("number", "ε [-]", positive=True),
        "revolutions": req("number", "shaft revolutions per run", positive=True),
        "mass_ratios": req("numbers", "rotor masses over the linear critical mass"),
        "kicks": opt("numbers", [0.05, 0.6], "initial displacements inside and outside the "
                     "cycle [clearances]", length=2),
        "cycle_tolerance": opt("number", 0.05, "largest relative difference of the cycles "
                               "reached from inside and outside", minimum=0.0),
        "allowed_without_cycle": opt("integer", 0, "masses allowed without an established "
                                     "cycle or contact", minimum=0),
        "model": req("table", "the bearing", keys=_point(required=("bearing_number",)))},
}
#: the kinds of this module; families of kinds in their own modules (e.g. :mod:`.design`)
#: add their schemas to SCHEMAS through :func:`gfbopt.studies.runner.register`
KINDS = tuple(SCHEMAS)

#: a file of published stability results (problems/published/*.toml): one copy of the
#: numbers, named by the studies that compare with them
PUBLISHED_DATA = {
    "reference": req("string", "name of the source in output columns (e.g. thesis)"),
    "source": req("string", "full citation"),
    "notes": opt("strings", [], "how the values were read and why the tolerances"),
    "curves": req("mapping", "label → model of each published curve",
                  values=req("table", "model", keys=MODEL)),
    "crossovers": opt("tables", [], "where two critical-mass curves cross", keys={
        "where": req("string", "table or figure"),
        "variable": req("string", "swept input", choices=("eccentricity", "bearing_number")),
        "eccentricity": opt("number", UNSET, "fixed ε [-]", minimum=0.0),
        "bearing_number": opt("number", UNSET, "fixed Λ [-]", positive=True),
        "variant": req("string", "curve (a key of curves)"),
        "against": req("string", "crossed curve (a key of curves)"),
        "crossover": req("number", "value of the swept input at the crossing"),
        "tolerance": req("number", "largest deviation, in the swept input", minimum=0.0)}),
    "critical_masses": opt("tables", [], "published critical masses", keys={
        "label": req("string", "short label"), "where": req("string", "table or figure"),
        "curve": req("string", "model (a key of curves)"),
        "eccentricity": req("number", "ε [-]", minimum=0.0),
        "bearing_number": req("number", "Λ [-]", positive=True),
        "critical_mass": req("number", "critical mass M̄ [-]", positive=True),
        "tolerance": req("number", "largest relative deviation", minimum=0.0),
        "masses": opt("numbers", [], "rotor masses M̄ of published orbits"),
        "verdicts": opt("strings", [], "published verdict of each orbit",
                        choices=("stable", "critical", "unstable"))}),
}


# ----------------------------------------------------------------------- checking
@dataclass(frozen=True)
class Where:
    """Where a value sits: the file and the path of keys, for one-line errors."""

    file: str
    path: str = ""

    def __truediv__(self, key) -> "Where":
        if isinstance(key, int):
            return Where(self.file, f"{self.path}[{key}]")
        return Where(self.file, f"{self.path}.{key}" if self.path else str(key))

    def error(self, value, rule: str) -> ParameterError:
        return ParameterError(f"{self.file}: {self.path}", value, rule)


def _at(where: Where) -> str:
    return f"{where.file}: {where.path}"


def check_value(key: Field, value, where: Where):
    """``value`` checked against ``key`` (a new, normalised value) or ParameterError
    (:func:`gfbopt.inputs.file_schema.check_value`, the one checker of input files)."""
    return check_field(key, value, _at(where))


def check_table(data: dict, schema: dict, where: Where) -> dict:
    """A table checked key by key against ``schema`` {name: key}; defaults filled in."""
    prefix = f"{_at(where)}." if where.path else f"{where.file}: "
    return check_fields(data, _fields(schema), _at(where), where.path or "a study of this "
                        "kind", prefix=prefix, fill=True, aliases=_ALIAS_PAIRS)


def validate(data: dict, file: str) -> dict:
    """The study ``data`` (parsed TOML) of ``file`` checked against the schema of its kind.

    Returns a new dict with every key of the schema (defaults filled in); raises one
    ParameterError naming ``file`` and the key otherwise.
    """
    top = Where(file)
    kind = data.get("kind") if isinstance(data, dict) else None
    if not isinstance(kind, str) or kind not in SCHEMAS:
        raise (top / "kind").error(kind, f"must be one of {', '.join(SCHEMAS)}"
                                   + did_you_mean(kind, tuple(SCHEMAS), _ALIAS_PAIRS))
    out = check_table(data, {**COMMON, **SCHEMAS[kind]}, top)
    if "source" not in out:
        if shipped(file):
            raise (top / "source").error(None, "is required of a study shipped in gfbopt's "
                                         "problems/ folder (the full citation of the "
                                         "source, with table or figure)")
        out["source"] = USER_SOURCE
    return out


#: the ``source`` of a user's study that cites none
USER_SOURCE = "none cited (a user's own study)"


def shipped(file: str) -> bool:
    """True for a study file that gfbopt ships: one inside the ``problems/`` folder beside
    the ``gfbopt`` package (the checkout's; an installed wheel ships none), found by its
    resolved path, so a copy anywhere else is the user's own study."""
    from pathlib import Path

    path = Path(file)
    if not path.is_file():
        return False
    problems = Path(__file__).resolve().parents[2] / "problems"
    return problems in path.resolve().parents


def describe_schema(kind: str) -> list[tuple[str, str, str]]:
    """(key, "required" or "default: …", meaning) of the top-level keys of ``kind``."""
    rows = []
    for name, key in {**COMMON, **SCHEMAS[kind]}.items():
        state = ("required" if key.default is REQUIRED else "optional"
                 if key.default in (UNSET, None) else f"default: {key.default!r}")
        rows.append((name, state, key.doc))
    return rows

