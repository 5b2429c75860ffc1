"""Glossary entries of the two-bearing rotor at its bearings' running condition
(gfbopt.rotor.running; merged into :data:`gfbopt.glossary.GLOSSARY` once listed in
:data:`gfbopt.terms._PARTS`).  The per-bearing columns of the Campbell and imbalance tables
(``running_clearance_um_A``, ``film_temperature_c_A``, ``viscosity_pa_s_A``) are the
quantities of gfbopt/terms/thermal.py at the bearing named by the suffix."""

TERMS: dict[str, tuple[str, str]] = {
    "thermal_models": ("text", "bearing → the clearance model each bearing was analysed "
                       "with ('isothermal, cold clearance', 'centrifugal growth' or 'heat "
                       "balance + growth')"),
    "running_at_onset": ("-", "bearing → its running condition (running clearance, growths, "
                         "temperatures, viscosity, heat flows) at the rotor's first onset "
                         "speed"),
    "thermal_limits": ("-", "per bearing whose running condition fails at a speed solved: "
                       "the speed it fails from, bracketed to 1 %"),
    "running_cost": ("-", "the fixed points' cost over the analysis: fixed_points, "
                     "static_solves, static_solves_per_point, max_static_solves"),
    "fixed_points": ("count", "running conditions solved (one per bearing and speed, all "
                     "grids)"),
    "static_solves": ("count", "static solves of the fixed points (the equilibria of the "
                      "analysis not counted)"),
    "static_solves_per_point": ("-", "static_solves / fixed_points"),
    "max_static_solves": ("count", "the largest number of static solves of one fixed point"),
    "limit_rpm": ("rpm", "the speed from which the bearing's running condition fails "
                  "(thermal runaway or closure)"),
    "last_running_rpm": ("rpm", "the highest of the analysis's own speeds below limit_rpm at "
                         "which the bearing's running condition was solved (limit_rpm is "
                         "bracketed between it and first_failing_rpm)"),
    "first_failing_rpm": ("rpm", "the lowest of the analysis's own speeds at which the "
                          "bearing's running condition failed"),
    "kind": ("text", "why a speed was skipped: 'thermal runaway' or 'closure' (a load beyond "
             "capacity has no kind)"),
}
