"""Glossary entries of the flexible shaft and the ROSS export: the rotor file's
``[[shaft]]`` and ``[[disks]]`` keys (:mod:`gfbopt.inputs.shaft_file`) and the fields of
``gfbopt export-ross --json`` (:mod:`gfbopt.cli.export_ross`)."""

TERMS = {
    "outer_diameter": ("m", "outer diameter of a shaft element's hollow circular section"),
    "inner_diameter": ("m", "bore of a shaft element (0: solid)"),
    "density": ("kg/m³", "density of a shaft element's material"),
    "youngs_modulus": ("Pa", "Young's modulus E of a shaft element's material"),
    "poisson_ratio": ("-", "Poisson's ratio ν of a shaft element's material (shear modulus "
                      "E/(2(1 + ν)))"),
    "transverse_inertia": ("kg m²", "transverse (diametral) moment of inertia, about the "
                           "centre of gravity (rotor) or the disk's centre (disk)"),
    "polar_inertia": ("kg m²", "polar moment of inertia about the rotor axis"),
    "centre_of_gravity": ("m", "axial position of the rotor's centre of gravity (from the "
                          "shaft's first end with a shaft; 0 for a rigid rotor)"),
    "total_mass": ("kg", "mass of the whole rotor (with a shaft: its elements and disks)"),
    "node": ("-", "index of the shaft's finite-element node (from 0 at the first end)"),
    "speed_range_rpm": ("rpm", "lowest and highest speed of a coefficient table"),
    "speeds": ("-", "number of speeds of a coefficient table"),
    "frequency_range_hz": ("Hz", "lowest and highest whirl frequency of a coefficient table"),
    "frequencies": ("-", "number of whirl frequencies of a coefficient table"),
    "extrapolation": ("text", "what ROSS does outside a coefficient table's span (it "
                      "extrapolates linearly)"),
    "few_points": ("-", "True when an axis of the table has fewer than the 5 points ROSS "
                   "recommends"),
}
