"""Glossary entries of the rotor's settled whirl with the bumps' Coulomb friction:
:mod:`gfbopt.rotor.friction_onset` (results/bumps_that_rub/rotor_settled_whirl.csv)."""

TERMS = {
    "settled_orbit_um": ("µm", "semi-major axis of the journal's whirl orbit at this bearing "
                         "where the bumps' friction (describing function) restores the "
                         "rotor's threshold, μ_c = 1 (nan: no bounded orbit inside the film; "
                         "0: stable for small orbits)"),
    "settled_whirl_hz": ("Hz", "whirl frequency of the settled orbit (describing function of "
                         "the bumps' friction)"),
    "settled_min_film_um": ("µm", "smallest static minimum film of the bearings less the "
                            "settled orbit's semi-major axis (the foil's own motion not "
                            "subtracted)"),
    "small_motion_inertia_scale": ("-", "μ_c of the rotor's first mode for small orbits, "
                                   "every loaded bump's friction slider stuck (< 1: the rotor "
                                   "whirls)"),
    "settled_inertia_scale": ("-", "μ_c of that mode at the settled orbit (unbounded: at the "
                              "orbit that fills the film)"),
    "film_share": ("-", "r = max over the bearings of the orbit's semi-major axis over the "
                   "equilibrium's minimum film"),
    "bounded": ("-", "True when the rotor settles on an orbit inside the film (or is stable "
                "for small orbits)"),
    "friction_verdict": ("text", "bounded whirl of A µm at B Hz, minimum film F µm; or no "
                         "bounded orbit inside the film; or stable for small orbits"),
    "friction_model": ("text", "the model that gave the settled-whirl answer"),
}
