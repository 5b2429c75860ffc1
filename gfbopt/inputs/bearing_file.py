"""Read a dimensional bearing description from a TOML file.

The file has a ``[bearing]`` table whose keys are the fields of
:class:`gfbopt.parameters.BearingGeometry`, all in SI units (m, Pa, Pa s)::

    [bearing]
    name = "Ruscitto et al. (1978) test bearing"
    radius = 19.05e-3            # m
    ...

An optional ``[model]`` table states the formulation the bearing is meant to be analysed with
(:class:`~gfbopt.inputs.options.ModelOptions`; defaults in
:func:`~gfbopt.inputs.options.resolve_model_options`)::

    [model]
    film = "seam"               # "periodic" | "seam"
    seam_angle_deg = 180.0      # top-foil welded end from the load line, [0, 360), or "max_film"
    foil = "simple"             # "rigid" | "simple" | "beam"
    deflection_law = "mean"     # "mean" | "local"
    loss_factor = 0.0           # structural loss factor η of the bumps [-]

Anything else (``source``, notes) is kept as metadata and not interpreted.
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
from .options import ModelOptions

_FIELDS = {f.name: f for f in dataclasses.fields(BearingGeometry)
           if f.name != "build"}          # the as-built tables are [bore], [[pads]], [[zones]]
_OPTIONAL = {name for name, f in _FIELDS.items()
             if f.default is not dataclasses.MISSING}


def read_toml(path: str | Path) -> dict:
    """Parse a TOML file; a missing or malformed file raises ParameterError."""
    path = Path(path)
    if not path.is_file():
        raise ParameterError("file", str(path), "must be an existing TOML file")
    try:
        return tomllib.loads(path.read_text())
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ParameterError("file", str(path), f"must be valid TOML ({exc})") from None


def bearing_from_dict(table: dict, where: str = "bearing") -> BearingGeometry:
    """A validated :class:`BearingGeometry` from a dict of SI values."""
    if not isinstance(table, dict):
        raise ParameterError(where, table, "must be a table of bearing quantities")
    unknown = sorted(set(table) - set(_FIELDS))
    if unknown:
        raise ParameterError(f"{where}.{unknown[0]}", table[unknown[0]],
                             f"is not a bearing quantity (known: {', '.join(_FIELDS)})")
    missing = [k for k in _FIELDS if k not in table and k not in _OPTIONAL]
    if missing:
        raise ParameterError(f"{where}.{missing[0]}", None, "is required but missing")
    for key, value in table.items():
        if key != "name" and (isinstance(value, bool) or not isinstance(value, (int, float))):
            raise ParameterError(f"{where}.{key}", value, "must be a number in SI units")
    return BearingGeometry(**table)


def load_bearing(path: str | Path) -> BearingGeometry:
    """The bearing described in the TOML file ``path`` (``[bearing]`` table, SI units)."""
    data = read_toml(path)
    if "bearing" not in data:
        raise ParameterError(f"{path}: [bearing]", None, "table is required but missing")
    geometry = bearing_from_dict(data["bearing"], where=f"{Path(path).name}: bearing")
    build = build_from_tables(data, where=Path(path).name)      # [bore], [[pads]], [[zones]]
    return geometry if build is None else dataclasses.replace(geometry, build=build)


def load_bearing_file(path: str | Path) -> tuple[BearingGeometry, ModelOptions]:
    """The bearing (``[bearing]``, SI) and the model options its ``[model]`` table states
    (options not stated are None; fill them with
    :func:`~gfbopt.inputs.options.resolve_model_options`)."""
    data = read_toml(path)
    geometry = load_bearing(path)
    name = Path(path).name
    options = (ModelOptions.from_table(data["model"], where=f"{name}: model")
               if "model" in data else ModelOptions())
    return geometry, options
