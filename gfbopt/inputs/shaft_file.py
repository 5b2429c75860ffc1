"""A flexible shaft in SI units: its beam elements and disks, as the rotor file gives them
(``[[shaft]]`` and ``[[disks]]``, declared by :data:`gfbopt.inputs.rotor_schema.SHAFT` and
:data:`~gfbopt.inputs.rotor_schema.DISKS` in :mod:`gfbopt.inputs.file_schema`'s language).

The shaft is a chain of hollow circular elements given in order from its first end; element
k spans [z_k, z_k + l_k], so consecutive elements join by construction and the shaft has no
gap (a non-positive length is refused).  Every axial position of a rotor with a shaft —
bearings, disks, imbalance planes, stations, side loads — is measured along the axis from
the shaft's first end (z = 0) and must lie on the shaft, 0 <= z <= L.  A disk is rigid and
lumped at its position (mass, transverse and polar inertia about its own centre); its mass
is added to the shaft's (give the shaft under the disk as shaft elements or not at all).

:class:`ShaftModel` also gives the rigid-body properties of the whole (exact for the
elements, uniform tubes): total mass, centre of gravity (from the first end), transverse
inertia about the centre of gravity and polar inertia — the statics of two bearings needs
the first two; :func:`gfbopt.inputs.rotor_system.shaft_body` is the rigid rotor of the same
inertia.
The finite-element model (:mod:`gfbopt.rotor.shaft`) reproduces them exactly in its
rigid-body motions.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import ParameterError
from .checks import check_finite, check_nonnegative, check_positive
from .rotor_schema import DISKS, RIGID_ONLY, SHAFT

#: default Poisson ratio of a shaft element (steel) [-]
DEFAULT_POISSON = 0.3
#: relative tolerance of "on the shaft" (a position within 1e-9 L past an end is the end)
ON_SHAFT = 1e-9


@dataclass(frozen=True)
class ShaftElement:
    """One hollow circular beam element: length [m] > 0, outer_diameter [m] > 0,
    inner_diameter [m] in [0, outer_diameter), density [kg/m³] > 0, youngs_modulus [Pa] > 0,
    poisson_ratio [-] in (−1, 0.5)."""

    length: float
    outer_diameter: float
    density: float
    youngs_modulus: float
    inner_diameter: float = 0.0
    poisson_ratio: float = DEFAULT_POISSON

    def __post_init__(self) -> None:
        for key in ("length", "outer_diameter", "density", "youngs_modulus"):
            object.__setattr__(self, key, check_positive(key, getattr(self, key)))
        inner = check_nonnegative("inner_diameter", self.inner_diameter)
        if not inner < self.outer_diameter:
            raise ParameterError("inner_diameter", self.inner_diameter, f"must be < "
                                 f"outer_diameter = {self.outer_diameter:g} m (a tube has a "
                                 "wall)")
        object.__setattr__(self, "inner_diameter", inner)
        nu = check_finite("poisson_ratio", self.poisson_ratio)
        if not -1.0 < nu < 0.5:
            raise ParameterError("poisson_ratio", self.poisson_ratio,
                                 "must be in (-1, 0.5) (an isotropic elastic material)")
        object.__setattr__(self, "poisson_ratio", nu)

    @property
    def mass(self) -> float:
        """ρ A l [kg]."""
        return self.density * math.pi / 4.0 * (self.outer_diameter**2
                                               - self.inner_diameter**2) * self.length

    @property
    def polar_inertia(self) -> float:
        """m (d_o² + d_i²)/8 [kg m²]."""
        return self.mass * (self.outer_diameter**2 + self.inner_diameter**2) / 8.0

    @property
    def own_transverse_inertia(self) -> float:
        """m ((d_o² + d_i²)/16 + l²/12) about the element's own centre [kg m²]."""
        return self.mass * ((self.outer_diameter**2 + self.inner_diameter**2) / 16.0
                            + self.length**2 / 12.0)


@dataclass(frozen=True)
class Disk:
    """A rigid disk: position [m from the shaft's first end], mass [kg] > 0,
    transverse_inertia I_t [kg m²] >= 0 about its centre, polar_inertia I_p [kg m²] in
    [0, 2 I_t] (any axisymmetric body: I_p = ∫r² dm <= 2 ∫(z² + r²/2) dm); name."""

    position: float
    mass: float
    transverse_inertia: float = 0.0
    polar_inertia: float = 0.0
    name: str = "disk"

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", check_finite("position", self.position))
        object.__setattr__(self, "mass", check_positive("mass", self.mass))
        it = check_nonnegative("transverse_inertia", self.transverse_inertia)
        ip = check_nonnegative("polar_inertia", self.polar_inertia)
        if ip > 2.0 * it * (1 + 1e-12):
            raise ParameterError("polar_inertia", self.polar_inertia, f"must be <= 2 × "
                                 f"transverse_inertia = {2 * it:.6g} kg m² (an axisymmetric "
                                 "body's principal moments)")
        object.__setattr__(self, "transverse_inertia", it)
        object.__setattr__(self, "polar_inertia", ip)


@dataclass(frozen=True)
class ShaftModel:
    """The shaft's elements (in order from the first end, at least one) and its disks (each
    on the shaft)."""

    elements: tuple
    disks: tuple = ()

    def __post_init__(self) -> None:
        elements, disks = tuple(self.elements), tuple(self.disks)
        if not elements:
            raise ParameterError("shaft", "0 elements", "needs at least one [[shaft]] element")
        for k, e in enumerate(elements, 1):
            if not isinstance(e, ShaftElement):
                raise ParameterError(f"shaft[{k}]", e, "must be a ShaftElement")
        object.__setattr__(self, "elements", elements)
        for k, d in enumerate(disks, 1):
            if not isinstance(d, Disk):
                raise ParameterError(f"disks[{k}]", d, "must be a Disk")
            check_on_shaft(self, f"disks[{k}].position", d.position)
        object.__setattr__(self, "disks", disks)

    @property
    def ends(self) -> tuple:
        """The element ends [m from the first end]: 0, l_1, l_1 + l_2, …, L."""
        z, out = 0.0, [0.0]
        for e in self.elements:
            z += e.length
            out.append(z)
        return tuple(out)

    @property
    def length(self) -> float:
        return self.ends[-1]

    @property
    def total_mass(self) -> float:
        """Elements and disks [kg]."""
        return sum(e.mass for e in self.elements) + sum(d.mass for d in self.disks)

    @property
    def centre_of_gravity(self) -> float:
        """[m from the first end]."""
        ends = self.ends
        moment = sum(e.mass * 0.5 * (a + b) for e, a, b in zip(self.elements, ends, ends[1:]))
        moment += sum(d.mass * d.position for d in self.disks)
        return moment / self.total_mass

    @property
    def transverse_inertia(self) -> float:
        """About the centre of gravity [kg m²] (each part's own plus m d²)."""
        zg, ends = self.centre_of_gravity, self.ends
        out = sum(e.own_transverse_inertia + e.mass * (0.5 * (a + b) - zg) ** 2
                  for e, a, b in zip(self.elements, ends, ends[1:]))
        return out + sum(d.transverse_inertia + d.mass * (d.position - zg) ** 2
                         for d in self.disks)

    @property
    def polar_inertia(self) -> float:
        """[kg m²]."""
        return sum(e.polar_inertia for e in self.elements) + sum(d.polar_inertia
                                                                 for d in self.disks)


def check_on_shaft(model: ShaftModel, key: str, position: float) -> float:
    """``position`` if it lies on the shaft (0 <= z <= L within :data:`ON_SHAFT` L), else
    ParameterError naming ``key``."""
    length = model.length
    if not -ON_SHAFT * length <= position <= length * (1 + ON_SHAFT):
        raise ParameterError(key, position, f"must lie on the shaft, 0 <= z <= {length:.6g} m "
                             "(positions are measured along the axis from the shaft's first "
                             "end when the rotor has a [[shaft]])")
    return position


def shaft_from_rows(shaft_rows: list, disk_rows: list, where: str) -> ShaftModel:
    """The :class:`ShaftModel` of a rotor file's ``[[shaft]]`` and ``[[disks]]`` rows, each
    already checked key by key against :data:`~.rotor_schema.SHAFT` / :data:`~.rotor_schema.
    DISKS`; the rules between keys are the built objects' own (ParameterError naming the row
    and key)."""
    elements = [_named(ShaftElement, f"{where}: shaft[{k}]", _filled(row, SHAFT))
                for k, row in enumerate(shaft_rows, 1)]
    if not elements:
        raise ParameterError(f"{where}: shaft", "0 elements", "needs at least one [[shaft]] "
                             "element")
    bare = ShaftModel(tuple(elements))
    disks = []
    for k, row in enumerate(disk_rows, 1):
        here = f"{where}: disks[{k}]"
        disk = _named(Disk, here, {"name": f"disk {k}", **_filled(row, DISKS)})
        check_on_shaft(bare, f"{here}.position", disk.position)
        disks.append(disk)
    return ShaftModel(tuple(elements), tuple(disks))


def shaft_from_file(shaft_rows: list, disk_rows: list, where: str):
    """The rotor file's :class:`ShaftModel` from its checked rows (None without
    ``[[shaft]]``; ``[[disks]]`` need one)."""
    if not shaft_rows:
        if disk_rows:
            raise ParameterError(f"{where}: disks", f"{len(disk_rows)} [[disks]] table(s)",
                                 "need a [[shaft]] to sit on (a rigid rotor's inertia is its "
                                 "[rotor] table)")
        return None
    return shaft_from_rows(shaft_rows, disk_rows, where)


def shaft_refuses_rigid_keys(data: dict, where: str) -> None:
    """A shaft's ``[rotor]`` table gives no mass or inertia (refused naming the key)."""
    if isinstance(data.get("rotor"), dict):
        for key in RIGID_ONLY:
            if key in data["rotor"]:
                raise ParameterError(f"{where}: rotor.{key}", data["rotor"][key],
                                     "is refused with a [[shaft]]: the rotor's mass and "
                                     "inertia come from its [[shaft]] elements and [[disks]]")


def _filled(row: dict, table) -> dict:
    out = dict(row)
    for f in table.fields:
        if f.name not in out and not f.required and f.default is not None:
            out[f.name] = f.default
    return out


def _named(cls, where: str, kwargs: dict):
    try:
        return cls(**kwargs)
    except ParameterError as exc:
        raise ParameterError(f"{where}.{exc.name}", exc.value, exc.rule) from None


def check_positions_on_shaft(model: ShaftModel, groups, prefix: str = "") -> None:
    """Every position of ``groups`` ((table, items), …) on the shaft (:func:`check_on_shaft`,
    the key named ``prefix + table[k].position``)."""
    for name, items in groups:
        for k, item in enumerate(items, 1):
            check_on_shaft(model, f"{prefix}{name}[{k}].position", item.position)
