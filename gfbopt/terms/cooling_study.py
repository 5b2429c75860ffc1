"""Glossary entries of the blower rotor's study over the cooling flow
(benchmarks/study_blower_cooling.py → results/blower_cooling/; merged into
:data:`gfbopt.glossary.GLOSSARY` once listed in :data:`gfbopt.terms._PARTS`)."""

TERMS: dict[str, tuple[str, str]] = {
    "cooling_mass_flow_kg_s": ("kg/s", "cooling flow ṁ through each bearing's bump channels "
                               "([thermal] cooling_mass_flow; empty for a variant without "
                               "the heat balance)"),
}
