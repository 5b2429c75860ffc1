"""Glossary entries of the bearing-pair design's preload levers (gfbopt.design.rotor_objectives
DESIGN_VARIABLES), columns of a design study's tables when a study varies them."""

TERMS = {
    "preload_offset_deg": ("deg", "centre of the first shim or lobe from the load line "
                           "(a design variable)"),
    "preload_width_deg": ("deg", "angular width of each shim (a design variable, shims "
                          "only)"),
}
