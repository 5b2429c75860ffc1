"""A rotor on two foil bearings, described in SI units: the rotor file and its dataclasses.

The rotor is a rigid body (the ``[rotor]`` table below) or a flexible shaft of beam elements
with disks (``[[shaft]]`` and ``[[disks]]``, :mod:`gfbopt.inputs.shaft_file`; the
finite-element model is :mod:`gfbopt.rotor.shaft`).  With a shaft every position is measured
from the shaft's first end, the ``[rotor]`` table is optional and gives only ``name``,
``gravity`` and ``gravity_direction_deg``, and :attr:`RotorSystem.body` is the rigid body of
the same mass and inertia (about the centre of gravity, :attr:`RotorSystem.
centre_of_gravity` from the first end).

A rotor file is a TOML file (keys below are a contract;
:data:`gfbopt.inputs.rotor_schema.ROTOR_FILE` declares them all in
:mod:`gfbopt.inputs.file_schema`'s language, the validator below checks them against it and
``docs/formats/rotor_file.md`` is generated from it)::

    [rotor]
    name = "blower"             # optional label
    mass = 3.2                  # kg, whole rotor
    transverse_inertia = 0.012  # kg m², about the centre of gravity
    polar_inertia = 0.002       # kg m²
    gravity_direction_deg = 0.0 # optional: direction of gravity in the x–y plane [deg]
    gravity = 9.80665           # optional: m/s² (0: no weight, side loads only)

    [[bearings]]                # exactly two
    file = "bearings/ruscitto.toml"   # relative to the rotor file
    position = -0.035           # m, axial, from the centre of gravity
    name = "A"                  # optional (default A, B in file order)
    [bearings.model]            # optional: overrides of the bearing file's [model] table
    loss_factor = 0.1

    [[side_loads]]              # optional static forces on the rotor
    force = 10.0                # N, > 0
    direction_deg = 90.0        # in the x–y plane [deg]
    position = 0.0              # m, axial, from the centre of gravity

    [[imbalance]]               # optional imbalance planes
    amount_g_mm = 5.0           # or amount_kg_m (exactly one of the two)
    phase_deg = 0.0             # angular position on the rotor [deg]
    position = 0.12             # m, axial, from the centre of gravity

    [[stations]]                # optional named axial stations for the imbalance response
    name = "impeller"
    position = 0.12             # m

Frame (the same as the bearings', :mod:`gfbopt.static`): z along the rotor axis, positions
measured from the centre of gravity; x and y in the plane of the bearings, the shaft spinning
from x towards y (a right-handed frame x, y, z with spin +ω about z).  Every angle in the x–y
plane (gravity, side loads, imbalance phase, each bearing's load direction) is measured from +x
in the direction of rotation, in degrees at this edge.  By default gravity acts along +x
(``gravity_direction_deg = 0``): x is then "down", the load line of both bearings of a
horizontal rotor.

Bad input raises one :class:`~gfbopt.errors.ParameterError` naming the file, the key, the value
and the rule, before anything is solved; so does a rotor no machine can be (positions in
millimetres, inertias beyond the mass's reach, an unloaded bearing, an imbalance displacing the
mass centre beyond the clearance: :mod:`gfbopt.inputs.rotor_limits`).  A centre of gravity
outside the bearing span (overhung rotor) and a bearing pushed away from gravity by the
statics are legal (:mod:`gfbopt.rotor.rigid` rotates that bearing's frame).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Optional, Union

from ..errors import ParameterError
from .bearing import BearingGeometry
from .bearing_file import load_bearing, load_bearing_file, read_bearing_file, read_toml
from .thermal_tables import RUNNING_TABLES
from .checks import check_angle_deg, check_finite, check_nonnegative, check_positive
from .conversions import STANDARD_GRAVITY
from .file_schema import REQUIRED, Table, check_file
from .options import ModelOptions
from .rotor_limits import check_rotor_limits
from .rotor_schema import IMBALANCE, ROTOR, ROTOR_FILE, SHAFT_ROTOR, SIDE_LOADS
from .shaft_file import ShaftModel, shaft_from_file, shaft_refuses_rigid_keys

#: the number of bearings a rotor file must give (the rigid-rotor model has two supports)
BEARING_COUNT = 2


# ------------------------------------------------------------------ dataclasses
@dataclass(frozen=True)
class RotorBody:
    """The rigid rotor's inertia.

    mass [kg] > 0; transverse_inertia I_t [kg m²] > 0 about the centre of gravity;
    polar_inertia I_p [kg m²], 0 ≤ I_p ≤ 2 I_t (the rotor file requires > 0; the Python API
    accepts 0 for idealised checks without gyroscopic coupling); name.
    """

    mass: float
    transverse_inertia: float
    polar_inertia: float
    name: str = "rotor"

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass", check_positive("mass", self.mass))
        object.__setattr__(self, "transverse_inertia",
                           check_positive("transverse_inertia", self.transverse_inertia))
        ip = check_nonnegative("polar_inertia", self.polar_inertia)
        if ip > 2.0 * self.transverse_inertia * (1 + 1e-12):
            raise ParameterError("polar_inertia", self.polar_inertia,
                                 f"must be <= 2 × transverse_inertia = "
                                 f"{2 * self.transverse_inertia:.6g} kg m² (a rigid body's "
                                 "principal moments obey I_p <= I_t + I_t)")
        object.__setattr__(self, "polar_inertia", ip)


@dataclass(frozen=True)
class BearingSupport:
    """One bearing of the rotor: its geometry (from its bearing file), where it sits, and the
    formulation it is analysed with.

    name; position [m] from the centre of gravity (signed, along z); geometry (SI);
    options : the bearing file's ``[model]`` table with the rotor file's ``[bearings.model]``
    over it (options not stated stay None: filled by
    :func:`~gfbopt.inputs.options.resolve_model_options`); file : the bearing file used
    (None when built in Python).  A stated seam angle is measured from the direction of
    gravity, i.e. fixed in the housing (:mod:`gfbopt.rotor.rigid`).
    running_tables : the bearing file's checked ``[journal]`` and ``[thermal]`` tables
    (((table, ((key, value), ...)), ...); () when it states neither: the isothermal,
    cold-clearance bearing), read only by ``load_rotor(path, running=True)`` (the linear
    rotor analyses, :mod:`gfbopt.rotor.running`); :meth:`tables` gives them as dicts.
    """

    name: str
    position: float
    geometry: BearingGeometry
    options: ModelOptions = field(default_factory=ModelOptions)
    file: Optional[str] = None
    running_tables: tuple = ()

    def tables(self) -> dict:
        """{"journal": {...}, "thermal": {...}} of the tables stated (empty: neither)."""
        return {name: dict(items) for name, items in self.running_tables}

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", check_finite("position", self.position))
        if not isinstance(self.geometry, BearingGeometry):
            raise ParameterError("geometry", self.geometry, "must be a BearingGeometry (SI)")
        if not isinstance(self.options, ModelOptions):
            raise ParameterError("options", self.options, "must be ModelOptions")


@dataclass(frozen=True)
class SideLoad:
    """A static force on the rotor: force [N] > 0, direction_deg [deg] in the x–y plane from
    +x in the direction of rotation, position [m] from the centre of gravity."""

    force: float
    direction_deg: float
    position: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "force", check_positive("force", self.force))
        object.__setattr__(self, "direction_deg",
                           check_angle_deg("direction_deg", self.direction_deg))
        object.__setattr__(self, "position", check_finite("position", self.position))

    @property
    def vector(self) -> tuple[float, float]:
        """(F_x, F_y) [N]."""
        a = math.radians(self.direction_deg)
        return self.force * math.cos(a), self.force * math.sin(a)


@dataclass(frozen=True)
class ImbalancePlane:
    """An imbalance: amount m e [kg m] > 0, phase_deg of the heavy spot on the rotor (from its
    reference mark, along +x at t = 0, in the direction of rotation) [deg], position [m]."""

    amount_kg_m: float
    position: float
    phase_deg: float = 0.0
    name: str = "plane"

    def __post_init__(self) -> None:
        object.__setattr__(self, "amount_kg_m", check_positive("amount_kg_m", self.amount_kg_m))
        object.__setattr__(self, "position", check_finite("position", self.position))
        object.__setattr__(self, "phase_deg", check_angle_deg("phase_deg", self.phase_deg))


@dataclass(frozen=True)
class Station:
    """A named axial station [m from the centre of gravity] for the imbalance response."""

    name: str
    position: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", check_finite("position", self.position))


@dataclass(frozen=True)
class RotorSystem:
    """A rotor on two bearings, with its static loads and imbalance (SI).

    body : inertia; bearings : exactly two :class:`BearingSupport` at different positions;
    side_loads, imbalance, stations : tuples (may be empty); gravity [m/s²] ≥ 0 and
    gravity_direction_deg [deg]; source : the rotor file (None when built in Python);
    shaft : None (a rigid rotor, positions from its centre of gravity) or a
    :class:`~gfbopt.inputs.shaft_file.ShaftModel` (a flexible shaft: positions from its first
    end, each on the shaft; ``body`` may be None and is then the shaft's rigid-body
    equivalent, :func:`shaft_body`; a body given must be that one).
    """

    body: Optional[RotorBody]
    bearings: tuple
    side_loads: tuple = ()
    imbalance: tuple = ()
    stations: tuple = ()
    gravity: float = STANDARD_GRAVITY
    gravity_direction_deg: float = 0.0
    source: Optional[str] = None
    shaft: Optional[ShaftModel] = None

    def __post_init__(self) -> None:
        where = f"{self.source}: " if self.source else ""
        if self.shaft is not None:
            object.__setattr__(self, "body", _shaft_body(self.shaft, self.body, where))
        if not isinstance(self.body, RotorBody):
            raise ParameterError(f"{where}rotor", self.body, "must be a RotorBody")
        bearings = tuple(self.bearings)
        if len(bearings) != BEARING_COUNT:
            raise ParameterError(f"{where}bearings", f"{len(bearings)} bearing(s)",
                                 "exactly two bearings are supported (a rigid rotor on two "
                                 "supports)")
        if bearings[0].position == bearings[1].position:
            raise ParameterError(f"{where}bearings[2].position", bearings[1].position,
                                 "must differ from bearings[1].position (two bearings at the "
                                 "same position cannot resist a tilt)")
        if bearings[0].name == bearings[1].name:
            raise ParameterError(f"{where}bearings[2].name", bearings[1].name,
                                 "must differ from the other bearing's name")
        object.__setattr__(self, "bearings", bearings)
        for key in ("side_loads", "imbalance", "stations"):
            object.__setattr__(self, key, tuple(getattr(self, key)))
        names = {b.name for b in bearings}
        for k, s in enumerate(self.stations, 1):
            if s.name in names:
                raise ParameterError(f"{where}stations[{k}].name", s.name,
                                     "must be unique (not a bearing's or another station's)")
            names.add(s.name)
        object.__setattr__(self, "gravity", check_nonnegative("gravity", self.gravity))
        object.__setattr__(self, "gravity_direction_deg",
                           check_angle_deg("gravity_direction_deg", self.gravity_direction_deg))
        check_rotor_limits(self, where)

    def static_shares(self) -> tuple:
        """Each bearing's static load vector (W_x, W_y) [N] from force and moment balance of
        the weight (at the centre of gravity) and the side loads about the bearings
        (:func:`gfbopt.rotor.rigid.bearing_loads` adds directions and frames)."""
        fx, fy = self.weight_vector
        mx, my = self.centre_of_gravity * fx, self.centre_of_gravity * fy
        for load in self.side_loads:
            vx, vy = load.vector
            fx, fy, mx, my = fx + vx, fy + vy, mx + load.position * vx, my + load.position * vy
        za, zb = (b.position for b in self.bearings)
        return (((zb * fx - mx) / (zb - za), (zb * fy - my) / (zb - za)),
                ((mx - za * fx) / (zb - za), (my - za * fy) / (zb - za)))

    @property
    def weight_vector(self) -> tuple[float, float]:
        """(W_x, W_y) = m g (cos, sin)(gravity direction) [N]."""
        a = math.radians(self.gravity_direction_deg)
        w = self.body.mass * self.gravity
        return w * math.cos(a), w * math.sin(a)

    @property
    def centre_of_gravity(self) -> float:
        """Axial position of the centre of gravity [m] in the frame of the positions: 0 for a
        rigid rotor (positions from the CG), the shaft's (elements and disks) from its first
        end with a shaft."""
        return 0.0 if self.shaft is None else self.shaft.centre_of_gravity

    @property
    def total_mass(self) -> float:
        """[kg] (the body's; with a shaft, elements and disks)."""
        return self.body.mass

    @property
    def span(self) -> float:
        """Distance between the bearings [m]."""
        return abs(self.bearings[1].position - self.bearings[0].position)

    def station_positions(self) -> dict:
        """name → axial position [m]: both bearings, then the named stations."""
        out = {b.name: b.position for b in self.bearings}
        out.update({s.name: s.position for s in self.stations})
        return out


# ------------------------------------------------------------------ the file
def load_rotor(path: Union[str, Path], running: bool = False) -> RotorSystem:
    """The rotor described in the rotor file ``path``, validated before anything is solved
    (every bearing file read and checked too).  ParameterError names the file and key.

    ``running``: read each bearing file's ``[journal]`` and ``[thermal]`` tables (kept on
    :attr:`BearingSupport.running_tables`) — the linear rotor analyses (``gfbopt rotor``'s
    onsets, Campbell, imbalance response) run each bearing at its running clearance; every
    other route (False) refuses a bearing file stating them, as
    :func:`~gfbopt.inputs.bearing_file.load_bearing` does, rather than answer with the cold
    clearance."""
    path = Path(path)
    return rotor_from_dict(read_toml(path), directory=path.parent, where=str(path),
                           running=running)


def rotor_from_dict(data: dict, directory: Union[str, Path] = ".",
                    where: str = "<rotor>", running: bool = False) -> RotorSystem:
    """A :class:`RotorSystem` from the tables of a rotor file (``directory``: where bearing
    files are looked up; ``where`` names the source in errors).

    Every key is checked against :data:`~gfbopt.inputs.rotor_schema.ROTOR_FILE` by
    :mod:`~gfbopt.inputs.file_schema`'s checkers (unknown keys and tables with did-you-mean,
    missing, wrong type, non-finite, out of bounds); the rules between keys and tables that
    the schema states in words are enforced here and by the objects built (rows are
    numbered from 1 in the messages: ``bearings[2].position``)."""
    directory = Path(directory)
    if not isinstance(data, dict):
        raise ParameterError(where, data, "must be a table")
    rows = {k: [v] if k in _ARRAYS and isinstance(v, dict) else v for k, v in data.items()}
    flexible = bool(rows.get("shaft"))
    if flexible:                   # the rigid-only keys named as such, not as unknown keys
        shaft_refuses_rigid_keys(data, where)
    elif rows.get("disks"):
        shaft_from_file([], rows["disks"], where)          # refused: disks need a shaft
    file = check_file(rows, _SHAFT_FILE if flexible else _RIGID_FILE, where, first_row=1)
    shaft = shaft_from_file(file.get("shaft", []), file.get("disks", []), where)
    if shaft is None and "rotor" not in file:
        raise ParameterError(f"{where}: [rotor]", None, "table is required but missing (a "
                             "rigid rotor's mass and inertia; or give [[shaft]] elements)")
    rotor = _filled(file.get("rotor", {}), ROTOR if shaft is None else SHAFT_ROTOR)
    if shaft is None:
        body = _build(RotorBody, f"{where}: rotor", mass=rotor["mass"],
                      transverse_inertia=rotor["transverse_inertia"],
                      polar_inertia=rotor["polar_inertia"], name=rotor["name"])
    else:
        body = shaft_body(shaft, rotor["name"])
    bearing_rows = file.get("bearings", [])
    if len(bearing_rows) != BEARING_COUNT:
        raise ParameterError(f"{where}: bearings", f"{len(bearing_rows)} [[bearings]] table(s)",
                             "exactly two bearings are supported (a rigid rotor on two "
                             "supports)")
    bearings = [_bearing(row, k, directory, where, running)
                for k, row in enumerate(bearing_rows, 1)]
    loads = [_build(SideLoad, f"{where}: side_loads[{k}]", **_filled(row, SIDE_LOADS))
             for k, row in enumerate(file.get("side_loads", []), 1)]
    planes = [_plane(row, k, where) for k, row in enumerate(file.get("imbalance", []), 1)]
    stations = [_build(Station, f"{where}: stations[{k}]", **row)
                for k, row in enumerate(file.get("stations", []), 1)]
    return RotorSystem(body, tuple(bearings), tuple(loads), tuple(planes), tuple(stations),
                       gravity=rotor["gravity"],
                       gravity_direction_deg=rotor["gravity_direction_deg"], source=where,
                       shaft=shaft)


def shaft_body(shaft: ShaftModel, name: str = "rotor") -> RotorBody:
    """The rigid body of a shaft's mass and inertia (about its centre of gravity)."""
    return RotorBody(shaft.total_mass, shaft.transverse_inertia, shaft.polar_inertia, name)


def _shaft_body(shaft, body, where: str) -> RotorBody:
    """The shaft's rigid-body equivalent; a body given must be it (to 1e-9)."""
    if not isinstance(shaft, ShaftModel):
        raise ParameterError(f"{where}shaft", shaft, "must be a ShaftModel or None")
    own = shaft_body(shaft, body.name if isinstance(body, RotorBody) else "rotor")
    if body is None:
        return own
    if not isinstance(body, RotorBody) or not all(
            math.isclose(getattr(body, k), getattr(own, k), rel_tol=1e-9)
            for k in ("mass", "transverse_inertia", "polar_inertia")):
        raise ParameterError(f"{where}rotor", body, "must be None or the shaft's own rigid "
                             f"body (mass {own.mass:.6g} kg, I_t {own.transverse_inertia:.6g}, "
                             f"I_p {own.polar_inertia:.6g} kg m²): a shaft's inertia comes "
                             "from its elements and disks")
    return body


# ------------------------------------------------------------------ checking, with file_schema
#: the rotor file as checked: the rules "[rotor] required without a [[shaft]]" and "two
#: [[bearings]]" are the builder's (with their own messages), and with a [[shaft]] the
#: [rotor] table has no mass or inertia and a side load's position is required
_RIGID_FILE = replace(ROTOR_FILE, tables=tuple(replace(t, required=False)
                                               for t in ROTOR_FILE.tables if "." not in t.name))
_SHAFT_FILE = replace(_RIGID_FILE, tables=tuple(
    replace(SHAFT_ROTOR, required=False) if t.name == "rotor" else
    replace(t, fields=tuple(replace(f, default=REQUIRED) if f.name == "position" else f
                            for f in t.fields)) if t.name == "side_loads" else t
    for t in _RIGID_FILE.tables))
_ARRAYS = tuple(t.name for t in ROTOR_FILE.tables if t.array)


def _filled(checked: dict, table: Table) -> dict:
    """A checked table with the defaults of the keys it does not state (None: no default)."""
    out = dict(checked)
    for f in table.fields:
        if f.name not in out and not f.required and f.default is not None:
            out[f.name] = f.default
    return out


def _build(cls, where: str, *args, **kwargs):
    """cls(...) with a ParameterError renamed to ``where.key``."""
    try:
        return cls(*args, **kwargs)
    except ParameterError as exc:
        raise ParameterError(f"{where}.{exc.name}", exc.value, exc.rule) from None


def _bearing(table: dict, k: int, directory: Path, where: str,
             running: bool = False) -> BearingSupport:
    here = f"{where}: bearings[{k}]"
    file = directory / table["file"]
    if not file.is_file():
        raise ParameterError(f"{here}.file", table["file"],
                             f"must name an existing bearing file (looked for {file})")
    tables: tuple = ()
    if running:
        geometry = load_bearing(file, running=True)
        options = geometry.options
        checked = read_bearing_file(file)
        tables = tuple((t.name, tuple(sorted(checked[t.name].items())))
                       for t in RUNNING_TABLES if t.name in checked)
    else:
        geometry, options = load_bearing_file(file)
    if "model" in table:
        options = ModelOptions(**table["model"]).over(options)
    return _build(BearingSupport, here, name=table.get("name", "AB"[k - 1]),
                  position=table["position"], geometry=geometry, options=options,
                  file=str(file), running_tables=tables)


def _plane(table: dict, k: int, where: str) -> ImbalancePlane:
    here = f"{where}: imbalance[{k}]"
    table = _filled(table, IMBALANCE)
    stated = [key for key in ("amount_kg_m", "amount_g_mm") if key in table]
    if not stated:
        raise ParameterError(f"{here}.amount_kg_m", None, "is required: give the imbalance "
                             "as amount_kg_m [kg m] or amount_g_mm [g mm]")
    if len(stated) == 2:
        raise ParameterError(f"{here}.amount_g_mm", table["amount_g_mm"],
                             "contradicts amount_kg_m: give one of the two")
    amount = table.get("amount_kg_m", table.get("amount_g_mm", 0.0) * 1e-6)
    return _build(ImbalancePlane, here, amount_kg_m=amount, position=table["position"],
                  phase_deg=table["phase_deg"], name=table.get("name", f"plane {k}"))
