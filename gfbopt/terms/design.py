"""Glossary entries of a bearing-pair design's decision: which limit binds
(``binding_limits.csv``, :mod:`gfbopt.design.decision`), what it would take
(``what_it_would_take.csv`` and its evaluations, :mod:`gfbopt.design.what_it_takes`) and the
answer's ``summary.json`` keys (:func:`gfbopt.studies.rotor_decision.answer`)."""

TERMS: dict[str, tuple[str, str]] = {
    # binding_limits.csv: one row per limit of the design study
    "limit_name": ("text", "the limited column of the evaluations (e.g. "
                   "min_film_lowest_speed_um)"),
    "limit_words": ("text", "the limit in words"),
    "limit_unit": ("text", "unit of the limit and of the values compared with it"),
    "limit_bound": ("text", "'lower' (the value must be ≥ the limit) or 'upper' (≤)"),
    "limit_value": ("(limit_unit)", "the limit as the study states it"),
    "designs_breaking": ("-", "evaluated designs (evaluation succeeded) that break this "
                         "limit, whatever else they break"),
    "designs_excluded_only_by_it": ("-", "evaluated designs that break this limit and meet "
                                    "every other one: relaxing it alone would admit them"),
    "chosen_value": ("(limit_unit)", "the chosen design's value of the limited quantity "
                     "(empty: no design meets every limit)"),
    "chosen_distance_to_limit": ("-", "the chosen design's distance to the limit over the "
                                 "limit's magnitude (≥ 0: met; −Constraint.violation)"),
    "active_at_chosen": ("flag", "the limit is active at the chosen design: its distance "
                         "to the limit is between 0 and the stated tolerance (2 %)"),
    "relaxed_first_onset_speed_rpm": ("rpm", "the best first onset of the evaluated designs "
                                      "that break this limit alone and beat the chosen "
                                      "design (empty: none)"),
    "relaxed_limit_value": ("(limit_unit)", "that design's value of the limited quantity: "
                            "the limit relaxed to it would admit that design"),
    "relaxed_breach": ("-", "by how much that design breaks the limit, over the limit's "
                       "magnitude (Constraint.violation > 0)"),
    "relaxed_point": ("text", "key of that design in evaluations.csv (point)"),
    # what_it_would_take.csv: one row per lever
    "lever": ("text", "a lever outside the design space: loss_factor, side_load_n or a "
              "design variable (A:… for one bearing)"),
    "lever_unit": ("text", "the lever's unit"),
    "lever_words": ("text", "the lever in words"),
    "lever_start": ("(lever_unit)", "the lever's value for the chosen design as it is (the "
                    "search's loss factor, 0 N of side load, the design's or the bearing's "
                    "as-built value)"),
    "lever_low": ("(lever_unit)", "lowest value the lever can physically take (the study's "
                  "bound)"),
    "lever_high": ("(lever_unit)", "highest value the lever can physically take"),
    "threshold_found": ("flag", "some value within the bounds makes the chosen design "
                        "stable to the top speed"),
    "threshold_value": ("(lever_unit)", "the value nearest the start at which the first onset "
                        "reaches the top speed (a scan from the start, then the Illinois method to "
                        "1e-5 of the bounds' span; empty: none within physical limits)"),
    "threshold_change": ("(lever_unit)", "threshold_value − lever_start"),
    "threshold_onset_speed_rpm": ("rpm", "first onset with the lever at threshold_value"),
    "threshold_meets_limits": ("flag", "the design with the lever at threshold_value meets "
                               "every limit of the study (a full evaluation)"),
    "at_bound_value": ("(lever_unit)", "the bound whose first onset is the higher (what the "
                       "lever reaches at its limit)"),
    "at_bound_onset_speed_rpm": ("rpm", "first onset with the lever at at_bound_value"),
    "lever_evaluations": ("-", "evaluations this lever's search used (answered from the "
                          "store on a resume included)"),
    # what_it_would_take_evaluations.csv (the store's rows)
    "lever_value": ("(lever_unit)", "the lever's value of this evaluation"),
    "onset_only": ("flag", "the evaluation computed the first onset only (the search); "
                   "false: every output (the answer's full evaluation)"),
    # summary.json keys of a design study's answer
    "best_first_onset_rpm": ("rpm", "summary.json: the best first onset of a design that "
                             "meets every limit (null: none)"),
    "chosen_design": ("text", "summary.json: the chosen design's variables and main outputs "
                      "(null: no design meets every limit)"),
    "limits": ("text", "summary.json: one entry per limit (the columns of "
                       "binding_limits.csv, without the limit_/chosen_ prefixes, and "
                       "relaxation_steps: [relaxed limit, first onset it allows, point] of "
                       "each relaxation that gains, least first)"),
    "active_limits": ("text", "summary.json: names of the limits active at the chosen design"),
    "what_it_would_take": ("text", "summary.json: one entry per lever (the columns of "
                           "what_it_would_take.csv); null when the chosen design is stable "
                           "to the top speed or the study names no lever"),
    "margin": ("text", "summary.json, a chosen design stable to the top speed: first onset "
               "[rpm], margin over the top speed [rpm] and relative, the worst case under "
               "the tolerances [rpm] and its relative margin; null otherwise"),
    "limit_cycle_revolutions": ("-", "revolutions of the top-speed orbit the study asked for "
                                "(the run stops earlier at contact: revolutions is what was "
                                "integrated)"),
    "consistency_checks_hold": ("flag", "summary.json: every internal consistency check of "
                                "the computation holds (not a verdict on the design)"),
}
