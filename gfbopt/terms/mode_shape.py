"""Glossary entries of a rotor mode's identity and shape (:mod:`gfbopt.rotor.mode_search`,
:mod:`gfbopt.rotor.modes`, :mod:`gfbopt.rotor.diagrams`): the shape class of a mode, the
threshold's whirl of a mode stable over the range, and the Campbell diagram's frequency
limit."""

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
    "frequency_limit_hz": ("Hz", "a Campbell diagram of a flexible shaft follows every mode "
                           "whose damped natural frequency is below this, at every speed "
                           "(default 3 times the highest speed; bending modes included); "
                           "null for a rigid rotor, whose four modes are all followed"),
}
