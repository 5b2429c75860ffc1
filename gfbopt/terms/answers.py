"""Keys of the command line's and the API's answers (JSON, result objects) that are not a
table's column elsewhere in the glossary."""

TERMS = {
    "min_film_angle_deg": ("deg", "housing angle of the minimum film from the load line, in "
                           "the direction of rotation, in [0, 360)"),
    "mass_margin": ("-", "M_crit/M − 1 at this speed and load (> 0: stable; the rotor could be "
                    "this much heavier)"),
    "mode_whirl_ratio": ("-", "whirl ratio Ω/ω of the least-damped mode at the operating point"),
    "smallest_margin_speed_rpm": ("rpm", "speed at which the onset search's smallest_margin "
                                  "occurs"),
    "inertia_margin": ("-", "μ_c − 1 of a mode's threshold crossing at this speed (> 0: "
                       "stable)"),
    "radial_clearance_m": ("m", "radial clearance c of the bearing"),
    "solve_time_s": ("s", "wall time of the static solve"),
    "peak_speed_rpm": ("rpm", "speed of a station's largest imbalance-response amplitude"),
    "peak_amplitude_um": ("µm", "a station's largest imbalance-response amplitude (major "
                          "semi-axis of the 1× orbit)"),
    "largest_below_onset_um": ("µm", "a station's largest tabulated imbalance-response "
                               "amplitude below the first onset of whirl"),
    "largest_below_onset_rpm": ("rpm", "the speed of largest_below_onset_um"),
    "unstable_from_rpm": ("rpm", "the first onset of whirl, above which the imbalance "
                          "response is that of an unstable linear rotor"),
    "linear_critical_mass_kg": ("kg", "the linear (small-motion) critical rotor mass per "
                                "bearing M = M̄c W0/(c ω²)"),
    "time_step_rad": ("rad", "integration time step Δτ, in radians of shaft rotation"),
    "x_um": ("µm", "journal centre X along the static load, from the bearing centre"),
    "y_um": ("µm", "journal centre Y, 90° ahead of the load in the direction of rotation"),
    "error_of_approximation": ("-", "the half-mass rule's first onset over the two-bearing "
                               "rotor's, minus 1"),
}
