"""The flexible shaft: Timoshenko beam elements with rigid disks, assembled into the structure
contract of :mod:`gfbopt.rotor.structure` (``kind = "shaft"``).

Nodes sit at every element end of the rotor file's ``[[shaft]]`` and at every position the
rotor names — bearings, disks, imbalance planes, stations, side loads: where such a position
falls inside an element, **a node is inserted** (the element is split in two of the same
section; an exact operation, the stiffness and mass of the pieces add up to the element's
own to round-off).  A position within :data:`SNAP` L of an existing node is that node.  Node
k has the degrees of freedom 4k … 4k + 3 = (x, y, ψx, ψy) (:mod:`gfbopt.rotor.beam_element`,
the sign convention of :mod:`gfbopt.rotor.rigid`), positions z_k from the shaft's first end.

``station(z)`` at a node picks that node's x and y; between nodes it interpolates with the
element's displacement shape functions (Timoshenko's interdependent interpolation, the cubic
Hermite polynomials in the Euler–Bernoulli limit), exact for the static beam.  The shaft has
no damping of its own (C = 0) and stands free: its four rigid-body modes have zero
frequency until bearings are added.
"""
from __future__ import annotations

import bisect
from dataclasses import dataclass, field

import numpy as np

from ..errors import ParameterError
from ..inputs.shaft_file import ShaftElement, ShaftModel, check_on_shaft
from .beam_element import disk_matrices, element_matrices, interpolation, plane_matrices
from .beam_element import section, shear_coefficient

#: a position within SNAP × the shaft's length of a node is that node [-]
SNAP = 1e-9
#: names of a node's degrees of freedom, in order
NODE_DOFS = ("x", "y", "psi_x", "psi_y")


@dataclass(frozen=True)
class ShaftStructure:
    """The shaft on its nodes: ``nodes`` [m from the first end] (increasing), ``elements``
    (one :class:`ShaftElement` between consecutive nodes), ``disks`` ((node, Disk) pairs),
    ``shear`` (False: Euler–Bernoulli elements, for checks), ``model`` (the rotor file's
    shaft).  Build it with :func:`build_shaft` or :func:`shaft_structure`."""

    nodes: tuple
    elements: tuple
    disks: tuple
    model: ShaftModel
    shear: bool = True
    kind: str = "shaft"
    _matrices: tuple = field(default=(), init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_matrices", _assemble(self))

    @property
    def size(self) -> int:
        return 4 * len(self.nodes)

    @property
    def dof_names(self) -> tuple:
        return tuple(f"{d}_{k}" for k in range(len(self.nodes)) for d in NODE_DOFS)

    @property
    def total_mass(self) -> float:
        return self.model.total_mass

    @property
    def centre_of_gravity(self) -> float:
        return self.model.centre_of_gravity

    def mass(self) -> np.ndarray:
        return self._matrices[0].copy()

    def gyroscopic(self) -> np.ndarray:
        return self._matrices[1].copy()

    def stiffness(self) -> np.ndarray:
        return self._matrices[2].copy()

    def damping(self) -> np.ndarray:
        return np.zeros((self.size, self.size))

    def node_index(self, position: float) -> int:
        """The node at ``position`` [m] (ParameterError if none within :data:`SNAP` L)."""
        k = _nearest(self.nodes, position)
        if abs(self.nodes[k] - position) > SNAP * self.nodes[-1]:
            raise ParameterError("position", position, f"is not a node of the shaft (nearest "
                                 f"node {self.nodes[k]:.6g} m)")
        return k

    def station(self, position: float) -> np.ndarray:
        """S(z), 2 × n: the axis's (x, y) at z [m from the first end] (module docstring)."""
        z = check_on_shaft(self.model, "position", float(position))
        s = np.zeros((2, self.size))
        k = _nearest(self.nodes, z)
        if abs(self.nodes[k] - z) <= SNAP * self.nodes[-1]:
            s[0, 4 * k], s[1, 4 * k + 1] = 1.0, 1.0
            return s
        e = min(max(bisect.bisect_right(self.nodes, z) - 1, 0), len(self.elements) - 1)
        el = self.elements[e]
        xi = (z - self.nodes[e]) / el.length
        s[:, 4 * e:4 * e + 8] = interpolation(xi, el.length, _phi(el, self.shear))
        return s


def _phi(el: ShaftElement, shear: bool) -> float:
    if not shear:
        return 0.0
    area, inertia = section(el.outer_diameter, el.inner_diameter)
    kappa = shear_coefficient(el.inner_diameter, el.outer_diameter, el.poisson_ratio)
    g_mod = el.youngs_modulus / (2.0 * (1.0 + el.poisson_ratio))
    return plane_matrices(el.length, area, inertia, el.density, el.youngs_modulus, g_mod,
                          kappa, shear)["phi"]


def _nearest(nodes: tuple, z: float) -> int:
    k = bisect.bisect_left(nodes, z)
    if k == len(nodes):
        return k - 1
    if k > 0 and z - nodes[k - 1] < nodes[k] - z:
        return k - 1
    return k


def _assemble(s: ShaftStructure) -> tuple:
    n = 4 * len(s.nodes)
    m, g, k = np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, n))
    for e, el in enumerate(s.elements):
        me, ge, ke = element_matrices(el.length, el.outer_diameter, el.inner_diameter,
                                      el.density, el.youngs_modulus, el.poisson_ratio,
                                      shear=s.shear)
        sl = slice(4 * e, 4 * e + 8)
        m[sl, sl] += me
        g[sl, sl] += ge
        k[sl, sl] += ke
    for node, disk in s.disks:
        md, gd = disk_matrices(disk.mass, disk.transverse_inertia, disk.polar_inertia)
        sl = slice(4 * node, 4 * node + 4)
        m[sl, sl] += md
        g[sl, sl] += gd
    return m, g, k


def build_shaft(model: ShaftModel, positions=(), shear: bool = True) -> ShaftStructure:
    """The shaft of ``model`` with a node at every element end, every disk and every one of
    ``positions`` [m from the first end] (each on the shaft: ParameterError otherwise); an
    element is split where a position falls inside it (module docstring)."""
    if not isinstance(model, ShaftModel):
        raise ParameterError("shaft", model, "must be a ShaftModel")
    length = model.length
    nodes = list(model.ends)
    wanted = [float(p) for p in positions] + [d.position for d in model.disks]
    for k, z in enumerate(wanted):
        check_on_shaft(model, f"position {k + 1}", z)
        near = _nearest(tuple(nodes), z)
        if abs(nodes[near] - z) > SNAP * length:
            bisect.insort(nodes, z)
    ends = model.ends
    elements = []
    for a, b in zip(nodes, nodes[1:]):
        owner = model.elements[min(bisect.bisect_right(ends, 0.5 * (a + b)) - 1,
                                   len(model.elements) - 1)]
        elements.append(ShaftElement(b - a, owner.outer_diameter, owner.density,
                                     owner.youngs_modulus, owner.inner_diameter,
                                     owner.poisson_ratio))
    nodes_t = tuple(nodes)
    disks = tuple((_nearest(nodes_t, d.position), d) for d in model.disks)
    return ShaftStructure(nodes_t, tuple(elements), disks, model, shear)


def rotor_positions(system) -> tuple:
    """Every axial position a rotor system names [m]: bearings, imbalance planes, stations,
    side loads (the disks are the shaft's own)."""
    out = [b.position for b in system.bearings]
    for key in ("imbalance", "stations", "side_loads"):
        out += [item.position for item in getattr(system, key)]
    return tuple(out)


def shaft_structure(system) -> ShaftStructure:
    """The :class:`ShaftStructure` of a :class:`~gfbopt.inputs.rotor_system.RotorSystem`
    with a shaft (``system.shaft``): nodes at every element end, disk and
    :func:`rotor_positions` position."""
    if getattr(system, "shaft", None) is None:
        raise ParameterError("shaft", None, "the rotor has no [[shaft]] (a rigid rotor: "
                             "gfbopt.rotor.structure.RigidStructure)")
    return build_shaft(system.shaft, rotor_positions(system))
