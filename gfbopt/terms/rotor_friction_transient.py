"""Glossary entries of the rotor transient with the bumps' Coulomb friction (sliders
integrated): :mod:`gfbopt.transient.rotor_friction`, the ``gfbopt rotor --orbit`` JSON of a
rotor whose bearing files state ``friction_coefficient`` > 0 (per bearing unless stated)."""

TERMS = {
    "bump_friction": ("text", "the friction model the rotor transient integrated: μ_f and κ "
                      "at each bearing, the sliders moved by the play operator after each "
                      "accepted step (whole run)"),
    "friction_orbit_kind": ("text", "how a constant-speed run ended at this bearing: "
                            "'settled limit cycle', 'contact' or 'end of run'"),
    "friction_orbit_amplitude_um": ("µm", "semi-major axis of the whirl's first harmonic at "
                                    "this journal over the last 6 whirl periods (the 1× of "
                                    "an imbalance removed); the describing function's "
                                    "orbit amplitude"),
    "friction_orbit_previous_amplitude_um": ("µm", "the same over the 6 whirl periods before "
                                             "(settled: within 1e-3 of the last)"),
    "friction_orbit_whirl_frequency_hz": ("Hz", "whirl frequency of that first harmonic "
                                          "(mean period between upward zero crossings)"),
    "friction_orbit_whirl_ratio": ("-", "that whirl frequency over the shaft speed"),
    "friction_orbit_verdict": ("text", "settled limit cycle of A µm at F Hz; or contact "
                               "after T ms; or end of run, growing/decaying, with the last "
                               "amplitude and its change"),
}
