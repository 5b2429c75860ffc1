"""Read a bearing file: the bearing in SI units and the formulation it is analysed with.

The file format (every key, unit, default and rule) is :data:`~gfbopt.inputs.file_schema.
BEARING_FILE`, documented for users in ``docs/formats/bearing_file.md`` (generated from it)::

    [bearing]
    name = "Ruscitto et al. (1978) test bearing"
    radius = 19.05e-3            # m
    ...

    [model]                     # optional
    film = "seam"               # "periodic" | "seam"
    seam_angle_deg = 180.0      # top-foil welded end from the load line, [0, 360), or "max_film"
    foil = "simple"             # "rigid" | "simple" | "beam"
    deflection_law = "mean"     # "mean" | "local"
    loss_factor = 0.0           # structural loss factor η of the bumps [-]

    [journal]                   # optional: the journal's centrifugal growth
    [thermal]                   # optional: the lumped heat balance (needs [journal])

(:mod:`gfbopt.inputs.thermal_tables`; read by :func:`gfbopt.thermal.files.load_running_bearing`
on the routes of :data:`RUNNING_ROUTES`; :func:`load_bearing` refuses them on every other
route rather than answer with the cold clearance.)

The file is checked as strictly as a study file, before anything is built: an unknown table or
key (``[modle]``) is refused with "did you mean", and a geometry that cannot be built (a bump
thicker than its half length, 2 l0 > s, a clearance of 1e-300 m) is refused with the rule.

One resolution of the ``[model]`` table for every route: :func:`load_bearing` returns the
:class:`~gfbopt.inputs.BearingGeometry` carrying the file's options (``geometry.options``), and
:func:`gfbopt.rotor.stability` / :func:`gfbopt.rotor.onset_speed` use them unless told
otherwise, exactly as ``gfbopt stability --bearing FILE`` and studies naming the file do
(:func:`~gfbopt.inputs.options.merge_options`: stated options over the file's, then the
defaults).
"""
from __future__ import annotations

import dataclasses
from pathlib import Path

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

from ..errors import ParameterError
from .bearing import BearingGeometry
from .bore_si import build_from_tables
from .file_schema import BEARING, BEARING_FILE, check_file, check_table
from .options import ModelOptions
from .thermal_tables import RUNNING_EXAMPLE, RUNNING_TABLES

#: the study kinds (``gfbopt run``) that read [journal] and [thermal]: each point at its
#: running condition (gfbopt.studies.base.load_running_geometry); other kinds refuse the file
RUNNING_STUDY_KINDS = ("onset_conventions", "onset_as_built", "loss_factor_map", "load_sweep",
                       "linear_coefficients", "drag_power", "pitch_design")
#: the commands that read [journal] and [thermal]; other routes refuse a file stating them
RUNNING_ROUTES = ("`gfbopt stability`, `gfbopt capacity`, `gfbopt static`, `gfbopt linear`, "
                  "`gfbopt orbit` and `gfbopt critical-mass` (gfbopt.thermal.files), "
                  "gfbopt.api's stability, "
                  "onset_speed, load_capacity and lift_off_speed given the file's path, the "
                  "analyses of `gfbopt rotor` (load_rotor(..., running=True)) and the study "
                  "kinds " + ", ".join(f"`{k}`" for k in RUNNING_STUDY_KINDS)
                  + " (`gfbopt run`)")
#: the bearing file with the clearance at speed's ``[journal]`` and ``[thermal]`` tables
#: (:mod:`gfbopt.inputs.thermal_tables`); the file every route checks against
BEARING_FILE_RUNNING = dataclasses.replace(
    BEARING_FILE, tables=BEARING_FILE.tables + RUNNING_TABLES,
    example=BEARING_FILE.example + RUNNING_EXAMPLE,
    doc=BEARING_FILE.doc + "  The optional `[journal]` and `[thermal]` tables give the "
    "clearance at speed (centrifugal and thermal growth, Sutherland's viscosity, a lumped "
    f"heat balance), read by {RUNNING_ROUTES}; a file with neither keeps the isothermal, "
    "cold-clearance answers.")

#: largest TOML file read [bytes] (a bearing or study file is a few kB)
MAX_FILE_BYTES = 1_000_000


def read_toml(path: str | Path) -> dict:
    """Parse a TOML file; a missing, huge, deeply nested or malformed file raises
    ParameterError (one line)."""
    path = Path(path)
    try:
        if not path.is_file():
            raise ParameterError("file", str(path), "must be an existing TOML file")
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise ParameterError("file", str(path), f"is {size} bytes: an input file must be "
                                 f"at most {MAX_FILE_BYTES} bytes")
        text = path.read_text()
    except OSError as exc:
        raise ParameterError("file", str(path), f"cannot be read ({exc.strerror})") from None
    except UnicodeDecodeError:
        raise ParameterError("file", str(path), "must be UTF-8 text") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError("file", str(path), f"must be valid TOML ({exc})") from None
    except RecursionError:
        raise ParameterError("file", str(path), "must be valid TOML (nested too deeply)") \
            from None


def bearing_from_dict(table: dict, where: str = "bearing",
                      options: ModelOptions = ModelOptions()) -> BearingGeometry:
    """A validated :class:`BearingGeometry` from a dict of SI values (the ``[bearing]``
    table), carrying ``options``."""
    checked = check_table(table, BEARING, where)
    try:
        return BearingGeometry(**checked, options=options)
    except ParameterError as exc:
        raise ParameterError(f"{where}.{exc.name}", exc.value, exc.rule) from None


def read_bearing_file(path: str | Path) -> dict:
    """The file checked against :data:`BEARING_FILE_RUNNING`: {table or
    key: checked value} (defaults not filled).  ParameterError names the file and key."""
    name = Path(path).name
    return check_file(read_toml(path), BEARING_FILE_RUNNING, name)


def load_bearing_public(path: str | Path) -> BearingGeometry:
    """The bearing described in the TOML file ``path`` (``gfbopt.load_bearing``): as
    :func:`load_bearing`, without its ``running`` switch — a file stating ``[journal]`` or
    ``[thermal]`` is refused in one line: its answers need the running condition, which
    ``gfbopt.stability``, ``onset_speed``, ``load_capacity`` and ``lift_off_speed`` apply when
    given the file's path (a geometry loaded past the refusal would answer with the cold
    clearance, silently)."""
    return load_bearing(path)


def load_bearing(path: str | Path, running: bool = False) -> BearingGeometry:
    """The bearing described in the TOML file ``path`` (``[bearing]``, SI units), carrying
    the options of its ``[model]`` table (``.options``; nothing stated when there is none)
    and the bearing as built (``.build``: ``[bore]``, ``[[pads]]``, ``[[zones]]``).

    A file stating ``[journal]`` or ``[thermal]`` is refused unless ``running`` (the routes
    of :data:`RUNNING_ROUTES`, through :func:`gfbopt.thermal.files.load_running_bearing`):
    any other route would answer silently with the cold clearance."""
    name = Path(path).name
    data = read_toml(path)
    tables = check_file(data, BEARING_FILE_RUNNING, name)      # every table and key checked
    for table in RUNNING_TABLES:
        if table.name in tables and not running:
            raise ParameterError(f"{name}: [{table.name}]", "…", "is read by "
                                 f"{RUNNING_ROUTES} only in this version: this route would "
                                 "use the cold clearance and a constant viscosity (use those "
                                 "commands, or a file without the table)")
    options = _options(tables.get("model"), name)
    build = build_from_tables(data, where=name)                # [bore], [[pads]], [[zones]]
    bearing = bearing_from_dict(tables["bearing"], where=f"{name}: bearing", options=options)
    if build is not None:
        try:                          # the bore, pads and zones checked against the bearing
            bearing = dataclasses.replace(bearing, build=build)
        except ParameterError as exc:
            raise ParameterError(f"{name}: {exc.name}", exc.value, exc.rule) from None
    try:                              # the combination, on a model of this bearing
        from .options import resolve_model_options

        bearing.model(1000.0, **resolve_model_options(options).model_kwargs())
    except ParameterError as exc:
        raise ParameterError(f"{name}: model.{exc.name}", exc.value, exc.rule) from None
    return bearing


def load_bearing_file(path: str | Path) -> tuple[BearingGeometry, ModelOptions]:
    """(the bearing, the options its ``[model]`` table states) — options not stated are None;
    fill them with :func:`~gfbopt.inputs.options.merge_options`.  The same options are
    ``bearing.options``."""
    bearing = load_bearing(path)
    return bearing, bearing.options


def _options(table, name: str) -> ModelOptions:
    if table is None:
        return ModelOptions()
    try:
        options = ModelOptions(**table)
        from .options import resolve_model_options

        resolve_model_options(options)          # contradictions refused now, with the file
        return options
    except ParameterError as exc:
        raise ParameterError(f"{name}: model.{exc.name}", exc.value, exc.rule) from None


#: the fields of [bearing] (for callers that list them)
FIELDS = tuple(f.name for f in dataclasses.fields(BearingGeometry)
               if f.name not in ("options", "build"))
