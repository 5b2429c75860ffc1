"""Flexible rotors through ROSS: each gfbopt bearing's frequency-dependent K and C in the form
ROSS's ``BearingElement`` takes.

ROSS (ross-rotordynamics, an optional extra: ``pip install -e ".[ross]"``; ROSS 3.x needs
Python ≥ 3.12, the core of gfbopt stays on Python ≥ 3.10) takes bearing coefficients as tables
over speed and excitation frequency (``speed`` × ``frequency``, rad/s, PCHIP between points,
linear extrapolation outside: keep the table wide).  A gas bearing's coefficients must be taken
at the whirl frequency (matched whirl, ``run_modal(speed, matched_whirl=True)``): ROSS's
default, the running speed, misses the foil bearing's subsynchronous instability
(shared design notes, "ROSS 3.x").

:func:`bearing_tables` gives, for one bearing of a gfbopt rotor, the tables kxx … cyy [N/m,
N s/m] in the rotor's x–y frame (x along gravity by default; ROSS's x and y are the same
plane), from Z_k(iΩ) rotated out of the bearing's load frame: K = Re(R Z Rᵀ), C = Im(R Z Rᵀ)/Ω.
:func:`bearing_element` builds the ROSS element (ROSS imported only there).  The same signs as
ROSS: the bearing force on the shaft is −K u − C u̇.

:func:`write_ross_table` writes one bearing's tables in ROSS 3.x's own file format, the file
``BearingElement.save_coefficient_table`` writes and ``BearingElement.load`` reads (ROSS 3.1,
``ross/bearing_seal_element.py``; ``ross.utils.load_data``: TOML through the ``toml``
package, or JSON by the ``.json`` suffix): one table ``[BearingElement_<tag>]`` — ROSS's load
takes the file's first table — holding ``n`` (the node), ``tag``, ``speed`` and
``frequency`` (the axes, rad/s, strictly increasing), every coefficient of the element's
signature as an n_speed × n_frequency nested list (kxx … cyy from :func:`bearing_tables`;
kzz, czz and the added masses mxx … mzz zero) and ``radial_clearance`` [m].  Written with
the standard library only (ROSS need not be installed).  :func:`ross_shaft_rotor` assembles
a gfbopt flexible shaft (:mod:`gfbopt.rotor.shaft`) in ROSS, element for element.
"""
from __future__ import annotations

import json
import math
import os
import re
import sys
import warnings
from pathlib import Path
from typing import Sequence

import numpy as np

from ..errors import ParameterError
from ..inputs.conversions import rpm_to_rad_per_s
from .rigid import rotation
from .system import SpeedLine

#: the coefficient names of ROSS's BearingElement
NAMES = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")


def bearing_tables(line: SpeedLine, bearing: int, speeds_rpm: Sequence[float],
                   frequencies_hz: Sequence[float]) -> dict:
    """{'speed': ω [rad/s] (n_s,), 'frequency': Ω [rad/s] (n_f,), kxx … cyy: (n_s, n_f)}
    for bearing number ``bearing`` (0 or 1) of the rotor on ``line``."""
    if bearing not in (0, 1):
        raise ParameterError("bearing", bearing, "must be 0 or 1 (the rotor's two bearings)")
    freqs = np.asarray(frequencies_hz, dtype=float)
    if freqs.size == 0 or not np.all(np.isfinite(freqs) & (freqs > 0)):
        raise ParameterError("frequencies_hz", list(freqs), "must be finite and > 0 [Hz]")
    speeds = [float(s) for s in speeds_rpm]
    out = {n: np.zeros((len(speeds), freqs.size)) for n in NAMES}
    rot = rotation(line.rotor.loads[bearing].direction_rad)
    for i, speed in enumerate(speeds):
        states = line.states(speed)
        if not states.ok:
            raise ParameterError("speeds_rpm", speed, "a bearing's load exceeds its capacity "
                                 "here: " + states.failure["message"])
        omega = rpm_to_rad_per_s(speed)
        st = states.states[bearing]
        for j, f in enumerate(freqs):
            big = 2 * np.pi * f
            z = rot @ st.impedance(big / omega) @ rot.T
            for k, (p, q) in enumerate(((0, 0), (0, 1), (1, 0), (1, 1))):
                out[NAMES[k]][i, j] = z[p, q].real
                out[NAMES[4 + k]][i, j] = z[p, q].imag / big
    out["speed"] = np.array([rpm_to_rad_per_s(s) for s in speeds])
    out["frequency"] = 2 * np.pi * freqs
    return out


def import_ross():
    """The ``ross`` module, imported quietly: its import prints a REFPROP banner on file
    descriptor 1 from C code (which would corrupt JSON output) and raises a UserWarning from
    ccp (an error under pytest's ``filterwarnings = error``); both are silenced for the import
    only.  ParameterError (with the reason of :func:`ross_available`) when it is missing."""
    ok, why = ross_available()
    if not ok:
        raise ParameterError("ross", None, why)
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 1)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                import ross
    finally:
        os.dup2(saved, 1)
        os.close(saved)
    return ross


def bearing_element(node: int, tables: dict, **kwargs):
    """A ROSS ``BearingElement`` at ``node`` from :func:`bearing_tables` (needs ROSS ≥ 3.0,
    which takes speed × frequency tables)."""
    ross = import_ross()
    return ross.BearingElement(node, **{n: tables[n] for n in NAMES},
                               speed=tables["speed"], frequency=tables["frequency"], **kwargs)


#: Young's modulus of the "rigid" shaft of :func:`ross_rotor` [Pa] (10⁴ × steel: its first
#: bending mode lies far above the rigid-body modes) and its density [kg/m³] (its mass,
#: ~1e-5 kg, is negligible against the disk's)
RIGID_MODULUS = 2.1e15
MASSLESS_DENSITY = 1.0


def ross_rotor(line: SpeedLine, speeds_rpm: Sequence[float], frequencies_hz: Sequence[float],
               shaft_modulus: float = RIGID_MODULUS, shaft_diameter: float = 0.02):
    """A ROSS shaft-and-disk rotor of the gfbopt rotor on ``line``: nodes at the two bearings
    and the centre of gravity, one disk at the CG with the rotor's m, I_t and I_p, a
    massless shaft (modulus ``shaft_modulus`` [Pa], outer diameter [m]: rigid by default, a
    steel modulus makes it flexible), and at each bearing node a :func:`bearing_element` on
    the bearing's speed × frequency tables (:func:`bearing_tables`)."""
    ross = import_ross()
    system = line.rotor.system
    positions = sorted({b.position for b in system.bearings} | {0.0})
    material = ross.Material(name="gfbopt_shaft", rho=MASSLESS_DENSITY, E=shaft_modulus,
                             G_s=shaft_modulus / 2.6)
    shaft = [ross.ShaftElement(L=b - a, idl=0.0, odl=shaft_diameter, material=material, n=k)
             for k, (a, b) in enumerate(zip(positions, positions[1:]))]
    body = system.body
    disk = ross.DiskElement(n=positions.index(0.0), m=body.mass, Id=body.transverse_inertia,
                            Ip=body.polar_inertia)
    bearings = [bearing_element(positions.index(b.position),
                                bearing_tables(line, k, speeds_rpm, frequencies_hz))
                for k, b in enumerate(system.bearings)]
    return ross.Rotor(shaft, [disk], bearings)


def ross_shaft_rotor(structure, bearing_elements=()):
    """The ROSS rotor of a gfbopt :class:`~gfbopt.rotor.shaft.ShaftStructure`: one ROSS
    ``ShaftElement`` per gfbopt element on the same nodes (Timoshenko: shear, rotary inertia,
    gyroscopic; Cowper's κ, ROSS's default), one ``DiskElement`` per disk, and the given
    ROSS bearing elements (e.g. :func:`bearing_element` at the bearings' nodes).  ROSS's
    node k is gfbopt's node k; its degrees of freedom per node are (x, y, z, α, β, θ)."""
    ross = import_ross()
    materials = {}
    elements = []
    for k, el in enumerate(structure.elements):
        key = (el.density, el.youngs_modulus, el.poisson_ratio)
        if key not in materials:
            materials[key] = ross.Material(name=f"gfbopt_{len(materials)}", rho=el.density,
                                           E=el.youngs_modulus, Poisson=el.poisson_ratio)
        elements.append(ross.ShaftElement(L=el.length, idl=el.inner_diameter,
                                          odl=el.outer_diameter, material=materials[key], n=k,
                                          shear_effects=structure.shear, rotary_inertia=True,
                                          gyroscopic=True))
    disks = [ross.DiskElement(n=node, m=d.mass, Id=d.transverse_inertia, Ip=d.polar_inertia)
             for node, d in structure.disks]
    return ross.Rotor(elements, disks, list(bearing_elements))


#: ROSS's lateral degrees of freedom among the six of a node (x, y, α, β of x, y, z, α, β, θ)
ROSS_LATERAL = (0, 1, 3, 4)


def ross_lateral_map(nodes: int) -> np.ndarray:
    """P (4 nodes × 6 nodes): gfbopt's q = (x, y, ψx, ψy) per node from ROSS's (x, y, z, α,
    β, θ): ψx = dx/dz = β (a rotation about y), ψy = dy/dz = −α (a rotation about x)."""
    p = np.zeros((4 * nodes, 6 * nodes))
    for k in range(nodes):
        p[4 * k, 6 * k] = p[4 * k + 1, 6 * k + 1] = p[4 * k + 2, 6 * k + 4] = 1.0
        p[4 * k + 3, 6 * k + 3] = -1.0
    return p


class RossStructure:
    """A shaft assembled by ROSS (a ``ross.Rotor`` of shaft elements and disks, without
    bearings), taken in as a :class:`~gfbopt.rotor.structure.Structure` (``kind = "shaft"``):
    its lateral M, G (per rad/s), K and C at rest, mapped to gfbopt's degrees of freedom by
    :func:`ross_lateral_map` (M_g = P M Pᵀ, …); positions from ROSS's first node; station(z)
    at a node picks x, y, between nodes the element's Timoshenko interpolation (its Φ);
    total mass and centre of gravity ROSS's.  ROSS's bearings are left out: gfbopt adds its
    own at their stations."""

    kind = "shaft"

    def __init__(self, rotor):
        self.rotor = rotor
        self.nodes = tuple(float(z) for z in rotor.nodes_pos)
        p = ross_lateral_map(len(self.nodes))
        self._m = p @ np.asarray(rotor.M(0.0)) @ p.T
        self._g = p @ np.asarray(rotor.G()) @ p.T
        self._k = p @ np.asarray(rotor.K(0.0)) @ p.T
        self._c = p @ np.asarray(rotor.C(0.0)) @ p.T
        self._elements = sorted(rotor.shaft_elements, key=lambda e: e.n)

    size = property(lambda self: 4 * len(self.nodes))
    total_mass = property(lambda self: float(self.rotor.m))
    centre_of_gravity = property(lambda self: float(self.rotor.CG))

    @property
    def dof_names(self) -> tuple:
        return tuple(f"{d}_{k}" for k in range(len(self.nodes))
                     for d in ("x", "y", "psi_x", "psi_y"))

    def mass(self) -> np.ndarray:
        return self._m.copy()

    def gyroscopic(self) -> np.ndarray:
        return self._g.copy()

    def stiffness(self) -> np.ndarray:
        return self._k.copy()

    def damping(self) -> np.ndarray:
        return self._c.copy()

    def station(self, position: float) -> np.ndarray:
        from .beam_element import interpolation

        z, tol = float(position), 1e-9 * self.nodes[-1]
        if not self.nodes[0] - tol <= z <= self.nodes[-1] + tol:
            raise ParameterError("position", position, f"must lie on the ROSS shaft, "
                                 f"{self.nodes[0]:g} <= z <= {self.nodes[-1]:g} m")
        s = np.zeros((2, self.size))
        k = int(np.argmin(np.abs(np.array(self.nodes) - z)))
        if abs(self.nodes[k] - z) <= tol:
            s[0, 4 * k], s[1, 4 * k + 1] = 1.0, 1.0
            return s
        e = int(np.searchsorted(self.nodes, z)) - 1
        el = self._elements[e]
        s[:, 4 * e:4 * e + 8] = interpolation((z - self.nodes[e]) / el.L, el.L, el.phi)
        return s


def ross_modes(rotor, speed_rpm: float, num_modes: int = 8) -> list:
    """ROSS's matched-whirl modes at ``speed_rpm`` (``run_modal(speed, matched_whirl=True)``;
    its warnings, e.g. a whirl frequency that did not converge, are kept): dicts of
    whirl_frequency_hz, log_decrement, whirl ('Forward', 'Backward', 'Mixed')."""
    omega = rpm_to_rad_per_s(speed_rpm)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        modal = rotor.run_modal(omega, num_modes=num_modes, matched_whirl=True)
    notes = sorted({str(w.message) for w in caught})
    return [{"whirl_frequency_hz": float(wd / (2 * np.pi)), "log_decrement": float(ld),
             "whirl": str(direction), "warnings": notes}
            for wd, ld, direction in zip(modal.wd, modal.log_dec, modal.whirl_direction())]


def ross_available() -> tuple[bool, str]:
    """(importable, reason) for the optional ROSS extra."""
    try:
        import importlib.util

        import importlib.metadata

        if importlib.util.find_spec("ross") is None:
            return False, ("ROSS is not installed (optional extra: pip install -e \".[ross]\","
                           " ross-rotordynamics >= 3.0 needs Python >= 3.12)")
        version = importlib.metadata.version("ross-rotordynamics")
    except (ImportError, ValueError) as exc:  # pragma: no cover
        return False, f"ROSS cannot be located ({exc})"
    if int(version.split(".")[0]) < 3:
        return False, (f"ROSS {version} is installed; the speed x frequency bearing tables "
                       "and matched whirl need ross-rotordynamics >= 3.0 (Python >= 3.12)")
    return True, ""


#: the coefficients of ROSS's BearingElement that gfbopt's tables leave at zero (axial, and
#: the added masses)
ZERO_COEFFICIENTS = ("kzz", "czz", "mxx", "myy", "mxy", "myx", "mzz")
#: ROSS's least recommended number of points per table axis (MIN_RECOMMENDED_AXIS_POINTS)
ROSS_MIN_AXIS_POINTS = 5


def ross_table_data(tables: dict, node: int, tag: str,
                    radial_clearance: float | None = None) -> dict:
    """{f"BearingElement_{tag}": {...}}: the content of a ROSS coefficient-table file
    (module docstring) from :func:`bearing_tables`; ParameterError on a non-finite value or
    an axis that does not increase."""
    speed, freq = (np.asarray(tables[k], dtype=float) for k in ("speed", "frequency"))
    for key, axis in (("speed", speed), ("frequency", freq)):
        if axis.ndim != 1 or axis.size == 0 or not np.all(np.isfinite(axis)) or (
                axis.size > 1 and not np.all(np.diff(axis) > 0)):
            raise ParameterError(key, list(np.ravel(axis)), "must be finite and strictly "
                                 "increasing [rad/s] (ROSS's table axes)")
    shape = (speed.size, freq.size)
    body = {"n": int(node), "tag": str(tag), "speed": speed.tolist(),
            "frequency": freq.tolist()}
    for name in NAMES:
        values = np.asarray(tables[name], dtype=float)
        if values.shape != shape or not np.all(np.isfinite(values)):
            raise ParameterError(name, values.shape, f"must be a finite {shape[0]} × "
                                 f"{shape[1]} table (speed × frequency)")
        body[name] = values.tolist()
    for name in ZERO_COEFFICIENTS:
        body[name] = np.zeros(shape).tolist()
    if radial_clearance is not None:
        body["radial_clearance"] = float(radial_clearance)
    return {f"BearingElement_{tag}": dict(sorted(body.items()))}


def write_ross_table(path, tables: dict, node: int, tag: str,
                     radial_clearance: float | None = None, header: Sequence[str] = ()) -> Path:
    """Write :func:`ross_table_data` to ``path``: JSON for a ``.json`` suffix (as ROSS
    decides), TOML otherwise, with ``header`` lines as TOML comments (ignored by readers)."""
    path = Path(path)
    data = ross_table_data(tables, node, tag, radial_clearance)
    if path.suffix.lower() == ".json":
        path.write_text(json.dumps(data, indent=2) + "\n")
        return path
    lines = [f"# {h}" for h in header]
    for section, body in data.items():
        lines.append(f"[{_toml_key(section)}]")
        lines += [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in body.items()]
    path.write_text("\n".join(lines) + "\n")
    return path


def _toml_key(key: str) -> str:
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else json.dumps(key)


def _toml_value(value) -> str:
    if isinstance(value, str):
        return json.dumps(value)          # a JSON string is a TOML basic string
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ParameterError("value", value, "must be finite")
        return repr(value)                # shortest round-trip form, valid TOML
    return "[" + ", ".join(_toml_value(v) for v in value) + "]"
