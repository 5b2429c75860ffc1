"""The typed study specification: one schema per study kind, checked before any solving.

A study file is a TOML table.  Its keys are the Python names of :mod:`gfbopt.glossary`
(``bearing_number``, ``compliance``, ``eccentricity``, ``length_ratio``,
``seam_angle_deg``, …), the same names as the columns the study writes.  :func:`validate`
checks the whole file against the schema of its ``kind``: an unknown or missing key, a value
of the wrong type or an unknown value raises one :class:`~gfbopt.errors.ParameterError`
naming the file, the key's path and what was expected, e.g.
``problems/x.toml: rows[2].epss = 0.3: is not a key of rows (did you mean 'eccentricity'?…)``.
The result is a new dict with every optional key present (its default filled in).

Tolerances are spelt ``<what>_tolerance`` everywhere; a comparison with a published value
is a ``tolerance = {quantity = value}`` table whose values are relative, except for angles
(``*_deg``), which are in degrees (:func:`gfbopt.glossary.deviation`).
"""
from __future__ import annotations

import difflib
import math
from dataclasses import dataclass
from typing import Any, Optional

from ..errors import ParameterError
from ..inputs import (
    DEFAULT_GRID,
    DEFLECTION_LAWS,
    FILM_MODELS,
    FOIL_MODELS,
    SUBAMBIENT_TREATMENTS,
    Grid,
)

REQUIRED = object()
#: default of a model key: when absent it is inherited (from ``[model]``, then from
#: :class:`~gfbopt.inputs.BearingModel`'s own defaults), so it is not filled in
UNSET = object()


@dataclass(frozen=True)
class Key:
    """One key of a study file.

    kind : number, integer, string, flag, grid, seam_angle, numbers, strings, grids, pairs,
        table (``keys`` is its schema), tables (a list of such tables) or mapping (any
        names, each value checked against ``values``)
    doc : meaning and unit (shown in errors)
    default : :data:`REQUIRED` for a required key
    choices : allowed values (a callable returning them is evaluated when checking)
    minimum : smallest allowed number; ``positive`` → must be > 0; maximum : largest
    length : exact length of a list
    """

    kind: str
    doc: str
    default: Any = REQUIRED
    choices: Any = ()
    keys: Optional[dict] = None
    values: Optional["Key"] = None
    minimum: Optional[float] = None
    positive: bool = False
    length: Optional[int] = None
    maximum: Optional[float] = None


def req(kind: str, doc: str, **kw) -> Key:
    """A required key."""
    return Key(kind, doc, **kw)


def opt(kind: str, default, doc: str, **kw) -> Key:
    """An optional key and its default."""
    return Key(kind, doc, default=default, **kw)


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
        keys[name] = Key(keys[name].kind, keys[name].doc, REQUIRED, keys[name].choices,
                         minimum=keys[name].minimum, positive=keys[name].positive)
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


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _check_scalar(key: Key, value, where: Where):
    kind = key.kind
    if kind in ("number", "integer"):
        if kind == "integer" and not (isinstance(value, int) and not isinstance(value, bool)):
            raise where.error(value, f"must be an integer ({key.doc})")
        if not _is_number(value):
            raise where.error(value, f"must be a number ({key.doc})")
        try:
            value = float(value) if kind == "number" else value
            finite = kind == "integer" or math.isfinite(value)
        except OverflowError:
            finite = False
        if not finite:
            raise where.error(value, "must be finite")
        if key.positive and value <= 0:
            raise where.error(value, f"must be > 0 ({key.doc})")
        if key.minimum is not None and value < key.minimum:
            raise where.error(value, f"must be >= {key.minimum:g} ({key.doc})")
        if key.maximum is not None and value > key.maximum:
            raise where.error(value, f"must be <= {key.maximum:g} ({key.doc})")
        return value
    if kind == "flag":
        if not isinstance(value, bool):
            raise where.error(value, "must be true or false")
        return value
    if kind == "string":
        if not isinstance(value, str):
            raise where.error(value, f"must be a string ({key.doc})")
        choices = key.choices() if callable(key.choices) else key.choices
        if choices and value not in choices:
            raise where.error(value, f"must be one of {', '.join(choices)}" + _hint(value,
                                                                                  choices))
        return value
    if kind == "grid":
        if not isinstance(value, str):
            raise where.error(value, "must be a grid written NTHETAxNZ, e.g. \"72x20\"")
        try:
            Grid.parse(value)
        except ParameterError as exc:
            raise where.error(value, exc.rule) from None
        return value
    if kind == "seam_angle":
        if value == "max_film":
            return value
        if not _is_number(value) or not 0.0 <= value < 360.0:
            raise where.error(value, "must be an angle in [0, 360) degrees or \"max_film\"")
        return float(value)
    raise AssertionError(kind)


#: symbols and older spellings → the glossary name (for "did you mean …?")
ALIASES = {"eps": "eccentricity", "epsilon": "eccentricity", "Lambda": "bearing_number",
           "S": "compliance", "C": "top_foil_coefficient", "L_over_D": "length_ratio",
           "attitude_deg": "attitude_angle_deg", "min_film_um": "min_film_thickness_um",
           "tolerance_nonlinear_linear": "nonlinear_linear_tolerance",
           "tolerance": "critical_mass_tolerance", "eps0": "eccentricity",
           "thesis_orbits": "orbits"}


def _hint(name: str, known) -> str:
    """" (did you mean 'x'?)" for a misspelt or old-vocabulary ``name``, or ""."""
    known = list(known)
    name = str(name)
    for alias, target in ALIASES.items():
        near = name == alias or (name.startswith(alias) and len(name) - len(alias) <= 2
                                 and len(alias) > 2)
        if near and target in known:
            return f" (did you mean '{target}'?)"
    close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
    return f" (did you mean '{close[0]}'?)" if close else ""


def check_value(key: Key, value, where: Where):
    """``value`` checked against ``key`` (a new, normalised value) or ParameterError."""
    kind = key.kind
    if kind in ("numbers", "strings", "grids", "pairs"):
        if not isinstance(value, list):
            raise where.error(value, f"must be a list ({key.doc})")
        if key.length is not None and len(value) != key.length:
            raise where.error(value, f"must have {key.length} entries ({key.doc})")
        if kind == "pairs":
            for k, pair in enumerate(value):
                if (not isinstance(pair, list) or len(pair) != 2
                        or not all(isinstance(p, str) for p in pair)):
                    raise (where / k).error(pair, "must be a pair of variant labels")
            return [list(p) for p in value]
        item = Key({"numbers": "number", "strings": "string", "grids": "grid"}[kind], key.doc,
                   choices=key.choices, minimum=key.minimum, positive=key.positive)
        return [_check_scalar(item, v, where / k) for k, v in enumerate(value)]
    if kind == "table":
        if not isinstance(value, dict):
            raise where.error(value, f"must be a table ({key.doc})")
        return check_table(value, key.keys, where)
    if kind == "tables":
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            raise where.error(value, f"must be a list of tables ([[...]]) ({key.doc})")
        return [check_table(v, key.keys, where / k) for k, v in enumerate(value)]
    if kind == "mapping":
        if not isinstance(value, dict):
            raise where.error(value, f"must be a table ({key.doc})")
        return {name: check_value(key.values, v, where / name) for name, v in value.items()}
    return _check_scalar(key, value, where)


def check_table(data: dict, schema: dict, where: Where) -> dict:
    """A table checked key by key against ``schema``; defaults filled in."""
    out = {}
    for name, value in data.items():
        if name not in schema:
            context = where.path or "a study of this kind"
            raise (where / name).error(value, f"is not a key of {context}{_hint(name, schema)}"
                                       f" (known: {', '.join(schema)})")
        out[name] = check_value(schema[name], value, where / name)
    for name, key in schema.items():
        if name not in out:
            if key.default is REQUIRED:
                raise (where / name).error(None, f"is required ({key.doc})")
            if key.default is not UNSET:
                out[name] = _copy(key.default)
    return out


def _copy(value):
    if isinstance(value, list):
        return [_copy(v) for v in value]
    if isinstance(value, dict):
        return {k: _copy(v) for k, v in value.items()}
    return value


def validate(data: dict, file: str) -> dict:
    """The study ``data`` (parsed TOML) of ``file`` checked against the schema of its kind.

    Returns a new dict with every key of the schema (defaults filled in); raises one
    ParameterError naming ``file`` and the key otherwise.
    """
    top = Where(file)
    kind = data.get("kind")
    if kind not in SCHEMAS:
        raise (top / "kind").error(kind, f"must be one of {', '.join(SCHEMAS)}"
                                   + _hint(kind, tuple(SCHEMAS)))
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

