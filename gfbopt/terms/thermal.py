"""Glossary entries of the clearance at speed (gfbopt.thermal; merged into
:data:`gfbopt.glossary.GLOSSARY` once listed in :data:`gfbopt.terms._PARTS`)."""

TERMS: dict[str, tuple[str, str]] = {
    "thermal_model": ("text", "the clearance model used: 'isothermal, cold clearance', "
                      "'centrifugal growth' ([journal]) or 'heat balance + growth' "
                      "([thermal])"),
    "thermal_status": ("text", "the running condition: 'running' (fixed point found), "
                       "'runaway' (no fixed point, or the clearance closes with the heat "
                       "balance) or 'closure' (the journal reaches the foil by its "
                       "centrifugal growth)"),
    "thermal_message": ("text", "why there is no running condition (empty when there is)"),
    "cold_clearance_um": ("µm", "radial clearance as stated, at the reference temperature "
                          "and at rest"),
    "running_clearance_um": ("µm", "radial clearance at speed and temperature: cold − "
                             "centrifugal growth − thermal growth; null when there is no running state (thermal runaway or closure)"),
    "centrifugal_growth_um": ("µm", "the journal's radial growth at speed (Lamé, plane "
                              "stress, free surfaces)"),
    "thermal_growth_um": ("µm", "net thermal closing of the clearance: journal growth − "
                          "sleeve bore growth (α r ΔT each); null when there is no running state (thermal runaway or closure)"),
    "journal_thermal_growth_um": ("µm", "the journal's thermal growth α_j R (T_j − T_ref)"),
    "sleeve_thermal_growth_um": ("µm", "the sleeve bore's thermal growth α_s (R + c)(T_s − "
                                 "T_ref)"),
    "viscosity_pa_s": ("Pa s", "gas viscosity at the mean film temperature (Sutherland; the "
                       "stated one without [thermal]); null when there is no running state (thermal runaway or closure)"),
    "film_temperature_c": ("°C", "mean film temperature of the lumped heat balance (empty "
                           "without [thermal]); null when there is no running state (thermal runaway or closure)"),
    "journal_temperature_c": ("°C", "journal temperature of the lumped heat balance"),
    "foil_temperature_c": ("°C", "top foil and bump temperature of the lumped heat balance"),
    "sleeve_temperature_c": ("°C", "sleeve (bearing housing bore) temperature of the lumped "
                             "heat balance"),
    "cooling_outlet_temperature_c": ("°C", "cooling flow temperature leaving the bump "
                                     "channels"),
    "heat_generated_w": ("W", "heat generated in the film: its drag power at the running "
                         "condition"),
    "heat_to_shaft_w": ("W", "heat leaving through the journal to the shaft and ambient"),
    "heat_to_housing_w": ("W", "heat leaving through the foil, bumps and sleeve to the "
                          "ambient"),
    "heat_to_cooling_w": ("W", "heat taken by the cooling flow, ṁ c_p (T_out − T_in)"),
    "heat_to_side_leakage_w": ("W", "heat carried by the film's side leakage, ṁ_l c_p (T_f "
                               "− T_a)"),
    "side_leakage_kg_s": ("kg/s", "mass flow leaving the film at its two ends"),
    "thermal_static_solves": ("-", "static solves the fixed point of the running condition "
                              "took"),
    "thermal_evaluations": ("-", "running-condition stability evaluations of the onset's "
                            "secant search"),
    "frozen_onset_speed_rpm": ("rpm", "onset of the bearing frozen at the running condition "
                               "of the guess speed (the running onset's first step)"),
    "frozen_at_rpm": ("rpm", "the guess speed whose running condition was frozen"),
    "thermal_limit_rpm": ("rpm", "first speed with no running condition (thermal runaway or "
                          "closure), bracketed to 0.5 %"),
    "thermal_limit_kind": ("text", "'runaway' or 'closure' at thermal_limit_rpm"),
}
