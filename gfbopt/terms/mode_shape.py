"""Glossary entries of a rotor mode's identity and shape (:mod:`gfbopt.rotor.mode_search`,
:mod:`gfbopt.rotor.modes`, :mod:`gfbopt.rotor.diagrams`): the shape class of a mode, the
threshold's whirl of a mode stable over the range, where its node lies, and the Campbell
diagram's frequency limit and the roots it left out."""

TERMS = {
    "shape_class": ("text", "the mode's shape class where its shape is read: cylindrical, "
                    "conical or mixed (rigid-body motion, by the phase of the whirl at the two "
                    "bearings) or bending (a shaft bending off the straight line); formerly the "
                    "key 'kind', which in the outputs says why a speed was skipped"),
    "threshold_whirl_frequency_hz": ("Hz", "a mode stable over the range (no onset): the "
                                     "whirl frequency of its matched-whirl threshold at its "
                                     "least μ_c, i.e. of a rotor μ_c times heavier whirling "
                                     "in that mode — not the mode's own frequency (that is "
                                     "the Campbell diagram's); null for a mode with an onset, "
                                     "whose own whirl there is whirl_frequency_hz"),
    "node_location": ("text", "where node_position_m lies: 'on the shaft' (a shaft's node, "
                      "read from its shape along the shaft), 'between the bearings' or "
                      "'outside the bearings (it may be off the rotor)' (the rigid body's: "
                      "its rotor file gives it no length), 'none (the axis translates)' "
                      "(no node; node_position_m empty)"),
    "node_relative_whirl": ("-", "the mode's dominant whirl at node_position_m over its "
                            "largest at the stations read (the bearings; a shaft's shape "
                            "stations): 0 at a true node, near 1 where the least whirl is no "
                            "node (a shaft's cylindrical mode is least at an end)"),
    "dropped_roots": ("text", "Campbell diagram: the roots found at one speed only that "
                      "continue no track, left out of the table and the figure, each with "
                      "its speed, frequency, log decrement, shape label and reason "
                      "(gfbopt.rotor.tracking.stitch)"),
    "frequency_limit_hz": ("Hz", "a Campbell diagram of a flexible shaft follows every mode "
                           "whose damped natural frequency is below this, at every speed "
                           "(default 3 times the highest speed; bending modes included); "
                           "null for a rigid rotor, whose four modes are all followed"),
}
