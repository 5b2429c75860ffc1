"""Glossary entries of the two-bearing analyses on the structure contract
(:mod:`gfbopt.rotor.structure`, :mod:`gfbopt.rotor.modes`): a shaft mode's shape."""

TERMS: dict[str, tuple[str, str]] = {
    "bending_share": ("-", "share of a shaft mode's squared whirl amplitude along the shaft "
                      "(dominant component, at its nodes) off the best straight line through "
                      "it; above 0.25 the mode is named 'bending n' (gfbopt.rotor.modes)"),
}
