"""Glossary entries of the rotor transient's tables (merged into :data:`gfbopt.glossary.GLOSSARY`)."""

TERMS: dict[str, tuple[str, str]] = {
    "speed_over_linear_onset": ("-", "shaft speed over the rotor's linear onset speed"),
    "contact": ("flag", "the run ended in contact (film ≤ 0.02 c or foil travel exhausted)"),
    "contact_time_s": ("s", "time of contact since the start of the run (empty: none)"),
    "limit_cycle_status": ("text", "subsynchronous whirl at a constant speed: 'limit cycle' "
                           "(settled), 'growing', 'decaying', or 'none' (no subsynchronous "
                           "peak of at least the threshold and 5× the band's noise floor: "
                           "the other limit_cycle_ columns are empty)"),
    "limit_cycle_amplitude_um": ("µm", "subsynchronous whirl at a constant speed, measured "
                                 "as limit_cycle_measure says: largest distance of the orbit "
                                 "(1× removed) from its centre over the last window of 10 "
                                 "whirl periods; or, bumps that rub, the semi-major axis of "
                                 "the whirl's first harmonic over the last 6 "
                                 "(friction_orbit_amplitude_um, the same number) (empty: "
                                 "limit_cycle_status none)"),
    "limit_cycle_measure": ("text", "the one measure of an orbit's limit cycle, its amplitude "
                            "and settled test: 'largest distance' (10 whirl periods against "
                            "the 10 before, settled within 1 %) or 'first harmonic' (a rotor "
                            "whose bumps rub: 6 periods against 6, within 1e-3, the "
                            "describing function's amplitude; limit_cycle_status and "
                            "friction_orbit_kind are then one verdict)"),
    "limit_cycle_frequency_hz": ("Hz", "frequency of that whirl (positive: forward; empty: "
                                 "none)"),
    "limit_cycle_whirl_ratio": ("-", "that frequency over the shaft frequency, inside "
                                "0.05–0.95 (empty: none)"),
    "limit_cycle_settled": ("flag", "the whirl amplitude changed by ≤ the settle tolerance "
                            "(1 %, or 1e-3 with limit_cycle_measure 'first harmonic') "
                            "between the last two windows (empty: no whirl)"),
    "limit_cycle_change": ("-", "relative change of the whirl amplitude between the last two "
                           "windows (empty: no whirl)"),
    "min_film_um": ("µm", "smallest film thickness over the run (0: the film closed)"),
    "revolutions": ("-", "shaft revolutions integrated"),
}
