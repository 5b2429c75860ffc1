"""A bearing file's ``[journal]`` and ``[thermal]`` tables, read into the clearance at
speed's :class:`~gfbopt.thermal.running.RunningSpec` (the tables' schema:
:mod:`gfbopt.inputs.thermal_tables`; the file format:
:data:`gfbopt.inputs.bearing_file.BEARING_FILE_RUNNING`)."""
from __future__ import annotations

from pathlib import Path

from ..errors import ParameterError
from ..inputs.bearing_file import BEARING_FILE_RUNNING, load_bearing, read_toml
from ..inputs.file_schema import check_file
from .network import JournalMaterial, ThermalNetwork
from .running import RunningSpec


def running_spec(tables: dict, bearing, where: str = "bearing file") -> RunningSpec:
    """The RunningSpec of ``bearing`` (a BearingGeometry) from a checked file's ``tables``
    ({name: checked dict}); ParameterError names ``where`` and the key."""
    journal = tables.get("journal")
    thermal = tables.get("thermal")
    try:
        return RunningSpec(bearing.radius, bearing.length, bearing.radial_clearance,
                           bearing.viscosity, bearing.ambient_pressure,
                           None if journal is None else JournalMaterial(**journal),
                           None if thermal is None else ThermalNetwork(**thermal))
    except ParameterError as exc:
        raise ParameterError(f"{where}: {exc.name}", exc.value, exc.rule) from None


def load_running_bearing(path):
    """(the bearing, its RunningSpec) of the file ``path``: the ``[journal]`` and
    ``[thermal]`` tables checked against the bearing (inner radius, temperatures,
    conductances, a path to ambient) before any solve; a file with neither gives the
    isothermal, cold-clearance spec."""
    name = Path(path).name
    bearing = load_bearing(path, running=True)
    tables = check_file(read_toml(path), BEARING_FILE_RUNNING, name)
    return bearing, running_spec(tables, bearing, where=name)
