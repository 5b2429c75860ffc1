"""The rotor file's tables, declared once in :mod:`gfbopt.inputs.file_schema`'s language
(:class:`~gfbopt.inputs.file_schema.Field`, :class:`~gfbopt.inputs.file_schema.Table`,
:class:`~gfbopt.inputs.file_schema.FileFormat`), the same as the bearing file's: the validator
(:func:`gfbopt.inputs.rotor_system.rotor_from_dict`, with file_schema's checkers) and the user
documentation (``docs/formats/rotor_file.md``, :data:`ROTOR_FILE` rendered as every file
format is) read the same declarations.

Each field states its kind, unit, default and bounds (checked key by key, with did-you-mean
for a misspelt key); each table states the rules between its fields, which the objects it
builds enforce (:mod:`.rotor_system`, :mod:`.shaft_file`, :mod:`.rotor_limits`).  What the
rigid and the flexible rotor do differently is a rule too: with ``[[shaft]]`` elements the
``[rotor]`` table is optional and holds only :data:`SHAFT_ROTOR`'s keys, every position is
measured from the shaft's first end, and a side load's position is required.
"""
from __future__ import annotations

from dataclasses import replace

from .conversions import STANDARD_GRAVITY
from .file_schema import BEARING_FILE, MODEL, Field, FileFormat, Table

#: the [rotor] keys of a rigid rotor only (a rotor with a [[shaft]] takes its mass and
#: inertia from its elements and disks)
RIGID_ONLY = ("mass", "transverse_inertia", "polar_inertia")

_ANGLE = dict(low=-360.0, high=360.0, why="a direction: [-360, 360] degrees, a turn either way")
_FROM = "from the centre of gravity (signed); with a [[shaft]], from the shaft's first end"
_LARGE = ("a shaft element: above 0, at most 1 km; one in millimetres is caught by the "
          "rotor's limits")

ROTOR = Table("rotor", "the rigid rotor's mass and inertia, and gravity: required for a "
              "rigid rotor; with a [[shaft]] optional, and without mass or inertia", fields=(
    Field("name", "string", "text", "label in reports", default="rotor"),
    Field("mass", "number", "kg", "mass of the whole rotor (rigid rotor only)", positive=True),
    Field("transverse_inertia", "number", "kg m²", "transverse (diametral) moment of inertia "
          "about the centre of gravity (rigid rotor only)", positive=True),
    Field("polar_inertia", "number", "kg m²", "polar moment of inertia about the rotor axis, "
          "gyroscopic coupling I_p ω (rigid rotor only)", positive=True,
          why="every real rotor has a polar inertia"),
    Field("gravity_direction_deg", "number", "deg", "direction of gravity in the x–y plane, "
          "from +x in the direction of rotation (default: along +x, the load line of both "
          "bearings)", default=0.0, **_ANGLE),
    Field("gravity", "number", "m/s²", "gravitational acceleration (0: the rotor's weight is "
          "not a load)", default=STANDARD_GRAVITY, low=0.0),
), rules=(
    "required without a [[shaft]]; with one, mass, transverse_inertia and polar_inertia are "
    "refused (they come from the elements and disks)",
    "polar_inertia <= 2 × transverse_inertia (a rigid body's principal moments)",
    "transverse_inertia <= m ((50 D)² + (10 D)²/2) and polar_inertia <= m (10 D)² (D: the "
    "larger journal diameter; a rigid rotor only)",
    "m × 9.80665 m/s² at most both bearings' 100 p_a L D",
))

#: the [rotor] table of a rotor with a [[shaft]]
SHAFT_ROTOR = replace(ROTOR, fields=tuple(f for f in ROTOR.fields if f.name not in RIGID_ONLY))

BEARINGS = Table("bearings", "the two bearings the rotor runs in, each a bearing file placed "
                 "on the rotor", array=True, required=True, fields=(
    Field("file", "string", "path", "the bearing's TOML file ([bearing] in SI, optional "
          "[model]; bearing_file.md), relative to the rotor file"),
    Field("position", "number", "m", "axial position " + _FROM + ", on the shaft"),
    Field("name", "string", "text", "label of the bearing in reports (default A, B in file "
          "order)", default=None),
    Field("model", "table", "-", "this bearing's overrides of its file's [model] table: "
          "[bearings.model] (its keys below)", default=None, table=MODEL),
), rules=(
    "exactly two [[bearings]], at different positions and with different names",
    "a rigid rotor: within 50 D of the centre of gravity, and a span in [(L_A + L_B)/2, 50 D]",
    "each bearing's static share (weight and side loads) between 1e-4 p_a R² and "
    "100 p_a L D",
    "file names an existing bearing file",
))

#: ``[bearings.model]`` under a ``[[bearings]]``: that bearing's overrides of its file's
#: ``[model]`` table (checked against :data:`~gfbopt.inputs.file_schema.MODEL`)
BEARING_MODEL = replace(MODEL, name="bearings.model", doc="overrides of the bearing file's "
                        "[model] table for the [[bearings]] it follows (the same keys); "
                        "seam_angle_deg is measured from the direction of gravity (the "
                        "housing), see the conventions", required=False)

SIDE_LOADS = Table("side_loads", "static forces on the rotor besides its weight",
                   array=True, fields=(
    Field("force", "number", "N", "magnitude of the force", positive=True),
    Field("direction_deg", "number", "deg", "direction of the force in the x–y plane, from +x "
          "in the direction of rotation", **_ANGLE),
    Field("position", "number", "m", "axial position where it acts, " + _FROM, default=0.0),
), rules=("with a [[shaft]], position is required (m from the shaft's first end)",
          "a rigid rotor: position within 50 D of the centre of gravity"))

IMBALANCE = Table("imbalance", "imbalance planes (the imbalance response and the orbits)",
                  array=True, fields=(
    Field("amount_kg_m", "number", "kg m", "imbalance m e of the plane", default=None,
          positive=True),
    Field("amount_g_mm", "number", "g mm", "imbalance m e of the plane (1 g mm = 1e-6 kg m)",
          default=None, positive=True),
    Field("phase_deg", "number", "deg", "angular position of the heavy spot on the rotor, "
          "from the rotor's reference mark (along +x at t = 0) in the direction of rotation",
          default=0.0, **_ANGLE),
    Field("position", "number", "m", "axial position of the plane, " + _FROM),
    Field("name", "string", "text", "label of the plane (default plane 1, 2, …)", default=None),
), rules=("exactly one of amount_kg_m and amount_g_mm",
          "all planes together <= m c (c: the smaller radial clearance)",
          "a rigid rotor: position within 50 D of the centre of gravity"))

STATIONS = Table("stations", "named axial stations where the imbalance response is reported",
                 array=True, fields=(
    Field("name", "string", "text", "label of the station"),
    Field("position", "number", "m", "axial position of the station, " + _FROM),
), rules=("name unique, not a bearing's name",
          "a rigid rotor: position within 50 D of the centre of gravity"))

SHAFT = Table("shaft", "a flexible shaft: one table per Timoshenko beam element of hollow "
              "circular section, in order from the shaft's first end (gfbopt.rotor.shaft); "
              "a rigid rotor when absent", array=True, fields=(
    Field("length", "number", "m", "length of the element; each starts where the previous "
          "one ends", positive=True, high=1e3, why=_LARGE),
    Field("outer_diameter", "number", "m", "outer diameter of the element's section",
          positive=True, high=1e3, why=_LARGE),
    Field("inner_diameter", "number", "m", "bore of the element (0: solid)", default=0.0,
          low=0.0),
    Field("density", "number", "kg/m³", "density of the element's material", positive=True),
    Field("youngs_modulus", "number", "Pa", "Young's modulus E of the element's material",
          positive=True),
    Field("poisson_ratio", "number", "-", "Poisson's ratio ν of the material (shear modulus "
          "E/(2(1 + ν)), Cowper's shear coefficient)", default=0.3,
          why="-1 < ν < 0.5, an isotropic elastic material, is checked by the element"),
), rules=("inner_diameter < outer_diameter (a tube has a wall)",
          "-1 < poisson_ratio < 0.5",
          "outer_diameter <= the journal diameter 2R of a bearing the element runs in",
          "every position of the file (bearings, disks, imbalance planes, stations, side "
          "loads) on the shaft: 0 <= z <= L, from the first end"))

DISKS = Table("disks", "rigid disks on the shaft, lumped at their centre (a [[shaft]] needed)",
              array=True, fields=(
    Field("position", "number", "m", "axial position of the disk's centre, from the shaft's "
          "first end"),
    Field("mass", "number", "kg", "mass of the disk", positive=True),
    Field("transverse_inertia", "number", "kg m²", "transverse (diametral) moment of inertia "
          "about the disk's centre", default=0.0, low=0.0),
    Field("polar_inertia", "number", "kg m²", "polar moment of inertia about the axis",
          default=0.0, low=0.0),
    Field("name", "string", "text", "label of the disk (default disk 1, 2, …)", default=None),
), rules=("position on the shaft (0 <= z <= L)",
          "polar_inertia <= 2 × transverse_inertia (an axisymmetric body's principal "
          "moments)"))

#: the tables of a rotor file, in the order of the documentation
ROTOR_TABLES = (ROTOR, BEARINGS, BEARING_MODEL, SIDE_LOADS, IMBALANCE, STATIONS, SHAFT, DISKS)

ROTOR_EXAMPLE = """\
[rotor]
mass = 3.2                  # kg, whole rotor
transverse_inertia = 0.012  # kg m², about the centre of gravity
polar_inertia = 0.002       # kg m²

[[bearings]]
file = "../bearings/ruscitto.toml"   # relative to the rotor file
position = -0.035           # m, axial, from the centre of gravity

[[bearings]]
file = "../bearings/ruscitto.toml"
position = 0.065
[bearings.model]            # optional: this bearing's overrides of its file's [model]
loss_factor = 0.1

[[imbalance]]
amount_g_mm = 5.0
phase_deg = 0.0
position = 0.065
"""

ROTOR_DOC = """\
A rotor on two gas foil bearings, in SI units: a rigid body (`[rotor]`), or a flexible shaft \
of Timoshenko beam elements with disks (`[[shaft]]`, `[[disks]]`). Read by `gfbopt rotor \
ROTOR.toml`, `gfbopt.load_rotor` and the `rotor =` key of rotor design studies; \
`gfbopt rotor` exits with status 2 on a refusal.

Conventions:

* **Frame.** z along the rotor axis (positions from the centre of gravity, signed); x and y
  in the bearing plane, the shaft spinning from x towards y. Every angle (gravity, side
  loads, imbalance phase, a bearing's load direction) is measured from +x in the direction
  of rotation, in degrees. By default gravity acts along +x: x is "down".
* **Exactly two bearings** are supported; they must sit at different positions. The centre
  of gravity may lie outside the span (overhung rotor).
* **Static loads.** Each bearing's load (magnitude and direction) follows from the rotor's
  statics: weight at the centre of gravity plus the side loads, shared by force and moment
  balance. A bearing may be pushed away from gravity (an overhung rotor lifts the far
  bearing): its frame is rotated to its own load direction. A bearing that carries no load
  (its share exactly zero) is refused: the linear film model needs a loaded journal.
* **Seam angle.** A bearing's `seam_angle_deg` (bearing file or `[bearings.model]`) is
  measured from the direction of gravity: the top foil is fixed in the housing, which is
  installed with its seam relative to gravity. If the statics turn the bearing's load away
  from gravity by an angle α, its film sees the welded end at `seam_angle_deg − α` from its
  own load. `"max_film"` and a periodic film are unaffected.
* **Plausibility limits** (gfbopt.inputs.rotor_limits): a rigid rotor reaches at most 50
  journal diameters D from its centre of gravity (a shaft that long bends far below foil
  bearing speeds), its bearings do not overlap, its inertias are those of a body within that
  reach and wheels of radius up to 10 D, each bearing carries between 1e-4 p_a R² (else the
  rotor is unloaded) and 100 p_a L D, and the imbalance displaces the mass centre by at most
  the clearance. They catch positions in millimetres and inertias in kg cm²; a refusal names
  the key, the value and the limit.
* **Flexible shaft.** A rotor file with `[[shaft]]` elements describes a flexible shaft
  (Timoshenko beam elements, gfbopt.rotor.shaft) instead of a rigid body: its mass and
  inertia come from the elements and the `[[disks]]`, so its `[rotor]` table is optional and
  holds only `name`, `gravity` and `gravity_direction_deg` (`mass`, `transverse_inertia`,
  `polar_inertia` are refused there). The elements are given in order from the shaft's first
  end, each starting where the previous one ends. **Every position** (bearings, disks,
  imbalance planes, stations, side loads) is then measured along the axis from the shaft's
  first end and must lie on the shaft (0 <= z <= L); a side load's position is required. A
  node of the finite-element model is placed at every element end and at every such
  position (an element is split where one falls inside it). The statics take the weight at
  the shaft's centre of gravity (elements and disks); `[[disks]]` without `[[shaft]]` are
  refused. The rigid-rotor reach and span limits do not apply to a shaft (it bends).
  For example:

      [[shaft]]                 # one [[shaft]] table per element, from the first end
      length = 0.02             # m
      outer_diameter = 0.038    # m
      inner_diameter = 0.0      # m (optional)
      density = 7810.0          # kg/m³
      youngs_modulus = 211e9    # Pa
      poisson_ratio = 0.3       # - (optional)

      [[disks]]
      position = 0.35           # m from the shaft's first end
      mass = 1.2                # kg
      transverse_inertia = 8e-4 # kg m², about the disk's centre
      polar_inertia = 1.5e-3    # kg m²
* **Model options** not stated in `[bearings.model]` come from the bearing file's
  `[model]` table, then gfbopt's defaults (a seam 180° from the load, simple foil, axial-mean
  law, no structural damping)."""

#: the rotor file (``problems/rotors/*.toml``, ``gfbopt rotor ROTOR.toml``)
ROTOR_FILE = FileFormat("rotor file", ROTOR_DOC, top=BEARING_FILE.top, tables=ROTOR_TABLES,
                        example=ROTOR_EXAMPLE)

