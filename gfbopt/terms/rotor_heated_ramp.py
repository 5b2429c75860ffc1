"""Glossary entries of a rotor's run-up or coast-down (where it ended, what was asked) and of
a heated rotor's (gfbopt.transient.rotor_running, rotor_heated; the clearance at speed): the running line
each bearing follows, quasi-steady in temperature.
Merged into :data:`gfbopt.glossary.GLOSSARY` once listed in :data:`gfbopt.terms._PARTS`.  The
per-speed columns of ``running_line`` (running_clearance_um, film_temperature_c,
viscosity_pa_s) are gfbopt/terms/thermal.py's."""

TERMS: dict[str, tuple[str, str]] = {
    "clearance_model": ("text", "the clearance and viscosity model of a rotor transient: "
                        "quasi-steady running line (ramps) or frozen at one speed's running "
                        "condition (orbits)"),
    "running_condition": ("-", "bearing → its running point (running clearance, growths, "
                          "temperatures, viscosity) held through a constant-speed orbit"),
    "running_line": ("-", "per bearing and solved speed: speed_rpm, running_clearance_um, "
                     "film_temperature_c, viscosity_pa_s of the line a ramp follows"),
    "running_nodes": ("count", "speeds at which the running line was solved (after "
                      "refinement)"),
    "running_interpolation": ("text", "how the running line is interpolated in speed (PCHIP: "
                              "monotone piecewise cubic)"),
    "running_interpolation_error": ("-", "the largest miss of the cubic at a solved midpoint "
                                    "of an accepted interval: clearance_um, "
                                    "clearance_fraction (of the cold clearance), "
                                    "viscosity_relative; refinements (halvings)"),
    "running_fixed_points": ("count", "fixed points of the heat balance solved for the line "
                             "(both bearings, refinement and bracketing included)"),
    "running_static_solves": ("count", "static solves of those fixed points"),
    "running_end": ("text", "why the ramp ends before its requested end (thermal runaway or "
                    "closure, bracketed to 1 %), null when it does not"),
    "requested_end_rpm": ("rpm", "the end speed asked for (end_speed_rpm: where the ramp "
                          "ended)"),
    "end_speed_rpm": ("rpm", "where the ramp ended: its requested end, or the speed where "
                      "contact, the integration's stop or the running line's end "
                      "(end_cause) cut it short"),
    "duration_s": ("s", "simulated time of the run, to where it ended (a ramp cut short: "
                   "to its contact or stop)"),
    "requested_duration_s": ("s", "the ramp's duration asked for: |requested_end_rpm − "
                             "start_speed_rpm| / rate_rpm_per_s"),
    "end_cause": ("text", "why a ramp ended before requested_end_rpm: 'contact at bearing "
                  "B', 'the integration stopped' or 'the running line ends (running_end)'; "
                  "null when it reached it"),
    "running_step_rpm": ("rpm", "the coarsest spacing of the running line's speeds"),
}
