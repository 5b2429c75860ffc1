"""The one vocabulary of gfbopt's tables: every column name, its unit and its meaning.

Study files (``problems/*.toml``), Python keyword arguments and output columns use the same
names: ``bearing_number`` is Λ in a study file, in :class:`gfbopt.inputs.BearingModel` and in
``results/*/*.csv``.  The study reports document their columns from this table
(:func:`describe`), and a test checks that every column a study writes is described here.

Published values sit beside ours under the quantity's name followed by the reference's name
(``load_yang``, ``attitude_angle_deg_thesis``, ``crossover_thesis``); their deviation is
``<quantity>_error_<reference>``: relative (ours / published − 1) for every quantity except
angles (``*_deg``), whose deviation is ours − published in degrees (:func:`deviation`).
Conventions (frames, signs, non-dimensional groups): docs/PHYSICS.md.
"""
from __future__ import annotations

import math
import re

from .terms import TERMS

#: column → (unit, meaning).  "-" is non-dimensional; "text"/"flag" are not numbers.
GLOSSARY: dict[str, tuple[str, str]] = {
    # ---------------------------------------------------------------- labels
    "variant": ("text", "label of the model variant (formulation) within the study"),
    "label": ("text", "label of the operating point or case within the study; in a rotor's "
              "tables (modes, threshold scan) the mode's name, as track_label"),
    "against": ("text", "the variant whose curve is crossed"),
    "variable": ("text", "the swept input (a column name of this glossary)"),
    "where": ("text", "table or figure of the published source the value is read from"),
    "reference": ("text", "the published source a value comes from"),
    "masses": ("text", "'thesis': the thesis's rotor masses; 'scaled': the same fractions of "
               "our linear threshold"),
    "grid": ("text", "finite-difference grid, n_theta x n_z intervals"),
    # ---------------------------------------------------------------- model inputs
    "bearing_number": ("-", "bearing number Λ = 6 μ ω R² / (p_a c²)"),
    "compliance": ("-", "bump compliance coefficient S = p_a α / c (0: rigid bearing); c the "
                   "clearance analysed: a heated file's running one at one operating point, "
                   "its cold one where each point has its own (a rotor, a capacity curve)"),
    "length_ratio": ("-", "bearing length over diameter L/D"),
    "top_foil_coefficient": ("-", "top-foil bending coefficient C = E_t t_t³ c / (12 R⁴ p_a) "
                             "(beam foil only)"),
    "foil": ("text", "foil model: rigid, simple (elastic foundation) or beam (top foil on "
             "the bumps)"),
    "film": ("text", "periodic (no seam) or seam (P = 1 at the top-foil ends)"),
    "seam_angle_deg": ("deg", "welded end of the top foil from the load line, in the "
                       "direction of rotation ('max_film': on the maximum-film line)"),
    "deflection_law": ("text", "mean: W = S (P̄ − 1); local: W = S (P − 1)"),
    "subambient": ("text", "full: whole film pressure in the force; gumbel: gauge pressure "
                   "below ambient dropped"),
    "compression_only": ("flag", "the bumps cannot pull the top foil towards the journal"),
    # ---------------------------------------------------------------- operating point
    "eccentricity": ("-", "eccentricity ratio ε = e/c of the journal centre"),
    "load": ("-", "static load W̄ = W / (p_a R²)"),
    "load_newton": ("N", "static load W on the bearing"),
    "speed_rpm": ("rpm", "shaft speed"),
    # ---------------------------------------------------------------- static outputs
    "attitude_angle_deg": ("deg", "attitude angle φ: from the load line to the line of "
                           "centres, in the direction of rotation"),
    "film_force": ("-", "magnitude of the film force on the journal |F|/(p_a R²)"),
    "film_force_angle_deg": ("deg", "direction of the film force from the load line, in the "
                             "direction of rotation, in [0, 360) (180: opposing the load)"),
    "min_film": ("-", "minimum film thickness H_min = h_min / c"),
    "min_film_thickness_um": ("µm", "minimum film thickness h_min"),
    "min_film_angle_from_seam_deg": ("deg", "angle of the minimum film from the welded end of "
                                     "the top foil, in the direction of rotation"),
    "max_mean_pressure": ("-", "largest axially averaged pressure P̄ = p̄ / p_a"),
    "max_mean_pressure_angle_from_seam_deg": ("deg", "angle of the largest P̄ from the "
                                              "welded end"),
    "max_deflection": ("-", "largest top-foil deflection W = w / c"),
    "max_deflection_angle_from_seam_deg": ("deg", "angle of the largest deflection from the "
                                           "welded end"),
    # ---------------------------------------------------------------- profiles
    "angle_from_seam_deg": ("deg", "angle from the welded end of the top foil, in the "
                            "direction of rotation"),
    "theta_deg": ("deg", "angle from the load line, in the direction of rotation"),
    "mean_pressure": ("-", "axially averaged pressure P̄ = p̄ / p_a"),
    "deflection": ("-", "top-foil deflection W = w / c (positive away from the journal)"),
    "film_thickness": ("-", "film thickness H = h / c, smallest over the bearing length"),
    "midplane_pressure": ("-", "pressure P = p / p_a on the axial mid-plane"),
    # ---------------------------------------------------------------- grid convergence
    "case": ("text", "label of the case"),
    "n_theta": ("-", "grid intervals round the bearing"),
    "n_z": ("-", "grid intervals along the bearing"),
    "grid_spacing": ("-", "1 / n_theta"),
    "observed_order_load": ("-", "observed order of convergence of the load (three finest grids)"),
    "observed_order_attitude": ("-", "observed order of convergence of the attitude angle"),
    "load_extrapolated": ("-", "Richardson-extrapolated load W̄ (formal order 2)"),
    "attitude_angle_deg_extrapolated": ("deg", "Richardson-extrapolated attitude angle"),
    "default_grid": ("text", "the grid whose error is reported"),
    "default_grid_load_error": ("-", "relative load error of the default grid against the "
                                "extrapolated value"),
    "default_grid_attitude_error_deg": ("deg", "attitude error of the default grid against "
                                        "the extrapolated value"),
    # ---------------------------------------------------------------- stability
    "critical_mass": ("-", "critical rotor mass M̄ = M c ω² / W0 (M and W0 per bearing): "
                      "stable below, whirling above"),
    "whirl_ratio": ("-", "whirl frequency over shaft speed (at the threshold, or of the "
                    "excitation for coefficients)"),
    "stable_for_all_masses": ("flag", "no linear threshold: stable for every rotor mass"),
    "linear_critical_mass": ("-", "linear (small-motion) critical mass M̄"),
    "linear_whirl_ratio": ("-", "whirl ratio at the linear threshold"),
    "threshold_whirl_ratio": ("-", "whirl ratio at the linear threshold"),
    "critical_mass_kg": ("kg", "critical rotor mass per bearing M_crit = M̄c W0/(c ω²)"),
    "bracket_low": ("-", "largest rotor mass M̄ found stable by the transients"),
    "bracket_high": ("-", "smallest rotor mass M̄ found unstable by the transients"),
    "transients": ("-", "number of transient runs of the critical-mass search"),
    "rotor_revolutions": ("-", "shaft revolutions integrated in total by the search"),
    "nonlinear_over_linear": ("-", "transient critical mass over the linear one"),
    "static_success": ("flag", "the static equilibrium converged"),
    "crossover": ("-", "value of the swept variable where the critical-mass curves of "
                  "'variant' and 'against' cross (empty: they do not cross in the range)"),
    "critical_mass_published_over_ours": ("-", "published critical mass over our linear one"),
    # ---------------------------------------------------------------- orbits
    "tau": ("rad", "shaft rotation τ = ω t since the start of the run"),
    "x": ("-", "journal centre X/c, along the static load"),
    "y": ("-", "journal centre Y/c, 90° ahead of the load in the direction of rotation"),
    "mass": ("-", "rotor mass parameter M̄ = M c ω² / W0"),
    "mass_ratio": ("-", "rotor mass over the linear critical mass"),
    "mass_thesis": ("-", "the thesis's rotor mass this run corresponds to"),
    "verdict": ("text", "stable, unstable, limit cycle or contact (film below 0.02 c)"),
    "growth_rate": ("1/rad", "growth rate of the whirl per radian of shaft rotation "
                    "(> 0: unstable; inf: contact)"),
    "final_amplitude": ("-", "final orbit radius about the equilibrium, in clearances"),
    "contact_tau": ("rad", "shaft rotation τ = ω t at contact (empty: none)"),
    "amplitude_from_inside": ("-", "final orbit amplitude from a small initial displacement "
                              "[clearances]"),
    "amplitude_from_outside": ("-", "final orbit amplitude from a large initial displacement "
                               "[clearances]"),
    "verdict_from_inside": ("text", "verdict of the run from the small displacement"),
    "verdict_from_outside": ("text", "verdict of the run from the large displacement"),
    # ---------------------------------------------------------------- coefficients
    "frequency_hz": ("Hz", "excitation (whirl) frequency"),
    "impedance_error": ("-", "max |Z − Z_Ausman| / max |Z_Ausman| over the four entries"),
    # ---------------------------------------------------------------- diagnostics
    "success": ("flag", "the computation of this row converged"),
    "message": ("text", "why a computation did not converge (empty when it did)"),
    "status": ("text", "IPOPT's return status of the static solve"),
    "iterations": ("-", "IPOPT iterations of the static solve"),
    "residual": ("-", "largest residual of the discrete Reynolds equations, recomputed "
                 "after the solve"),
    "wall_time_s": ("s", "wall time of this row's computation"),
}

# Families of columns: (regular expression, unit, meaning with {groups}).
_PATTERNS: tuple = (
    (r"k([xy])([xy])_N_per_m", "N/m", "stiffness K_{0}{1} (load frame: x along the load)"),
    (r"c([xy])([xy])_Ns_per_m", "N s/m", "damping C_{0}{1} (load frame)"),
    (r"k([xy])([xy])", "-", "stiffness K̄_{0}{1} = K c / (p_a R²) (load frame)"),
    (r"c([xy])([xy])", "-", "damping C̄_{0}{1} = C c ω / (p_a R²) (load frame)"),
    (r"z([xy])([xy])_(re|im)", "-", "impedance Z_{0}{1} ({2} part), gfbopt"),
    (r"z([xy])([xy])_ausman_(re|im)", "-", "impedance Z_{0}{1} ({2} part), Ausman's closed form"),
    (r"load_error_grid_(\d+x\d+)", "-", "relative load error of grid {0} against the "
     "extrapolated value"),
)

_PART = {"re": "real", "im": "imaginary"}


def deviation(quantity: str, ours: float, published: float) -> float:
    """Deviation of ``ours`` from ``published``: ours − published for an angle (``*_deg``),
    ours / published − 1 otherwise (the rule behind every ``<quantity>_error_<reference>``
    column and every tolerance on a published comparison)."""
    if quantity.endswith("_deg"):
        return ours - published
    if published == 0 or not math.isfinite(published):
        return math.nan
    return ours / published - 1.0


def describe(column: str, references: tuple = ()) -> tuple[str, str]:
    """(unit, meaning) of ``column``; ``references`` are the names of published sources,
    so that ``load_yang`` reads "load W̄ … published by yang".  KeyError if unknown."""
    if column in GLOSSARY:
        return GLOSSARY[column]
    for ref in references:
        for quantity in GLOSSARY:
            if column == f"{quantity}_{ref}":
                unit, meaning = GLOSSARY[quantity]
                return unit, f"{meaning} — published ({ref})"
            if column == f"{quantity}_error_{ref}":
                unit = "deg" if quantity.endswith("_deg") else "-"
                kind = "ours − published" if unit == "deg" else "ours / published − 1"
                return unit, f"deviation of {quantity} from {ref}: {kind}"
        if column == f"verdicts_{ref}":
            return "text", f"verdicts published ({ref})"
    bearing = re.fullmatch(r"([A-Z]):(\w+)", column)     # a design variable per bearing
    if bearing:
        unit, meaning = describe(bearing.group(2), references)
        return unit, f"{meaning}, of bearing {bearing.group(1)}"
    for suffix, where in _SUFFIXES:
        base = column[:-len(suffix)] if column.endswith(suffix) else ""
        if base:
            unit, meaning = describe(base, references)
            return unit, f"{meaning}, {where}"
    for pattern, unit, meaning in _PATTERNS:
        match = re.fullmatch(pattern, column)
        if match:
            groups = [_PART.get(g, g.upper() if len(g) == 1 else g) for g in match.groups()]
            return unit, meaning.format(*groups)
    raise KeyError(f"column {column!r} is not in the glossary (gfbopt/glossary.py)")


# ---------------------------------------------------------------- design of experiments
# Columns of sampled studies (gfbopt.studies.doe); added without overriding an entry that
# another family of studies defines.
for _name, _entry in {
    "point": ("-", "index of the point in the study's sample plan (the key of a row)"),
    "worker": ("text", "host:pid of the process that computed the row"),
    "bump_pitch": ("m", "bump pitch s"),
    "bump_thickness": ("m", "bump foil thickness t_b"),
    "bump_half_length": ("m", "half bump length l0"),
    "radial_clearance": ("m", "radial clearance c"),
    "bump_youngs_modulus": ("Pa", "Young's modulus of the bump foil E_b"),
    "top_foil_thickness": ("m", "top foil thickness t_t"),
    "length": ("m", "bearing length L"),
    "radius": ("m", "journal radius R"),
    "loss_factor": ("-", "structural loss factor η of the bump foundation"),
    "rotor_mass_kg": ("kg", "rotor mass per bearing M"),
    "speed_low_rpm": ("rpm", "low end of the speed range searched for the onset"),
    "speed_high_rpm": ("rpm", "high end of the speed range searched for the onset"),
    "onset_speed_rpm": ("rpm", "onset speed of whirl: lowest speed in the range at which the "
                        "rotor is linearly unstable (empty: none in the range)"),
    "whirl_frequency_hz": ("Hz", "whirl frequency Ω/2π: at the onset of instability in an "
                           "onset's row; of the mode (a Campbell row, a stability point's "
                           "least-damped mode) or of the threshold crossing (a threshold-scan "
                           "row) at the row's speed"),
    "stable_over_range": ("flag", "stable at every speed of the range searched"),
    "unstable_at_lower_end": ("flag", "already unstable at the lowest speed searched"),
    "smallest_margin": ("-", "smallest M_crit/M − 1 of the onset search, over its speeds up "
                        "to the first scan speed above the onset (all of them when it finds "
                        "none)"),
    "evaluations": ("-", "linear-threshold computations of the onset search"),
    "output": ("text", "the study output whose sensitivity is given"),
    "input": ("text", "the sampled input"),
    "S1": ("-", "first-order Sobol index (share of the output variance due to this input alone)"),
    "S1_conf": ("-", "95 % bootstrap half-width of S1"),
    "ST": ("-", "total Sobol index (share of the variance involving this input)"),
    "ST_conf": ("-", "95 % bootstrap half-width of ST"),
}.items():
    GLOSSARY.setdefault(_name, _entry)


# ---------------------------------------------------------------- stability studies
# Columns of gfbopt.studies.stability (onset_conventions, loss_factor_map); added without
# overriding an entry that another family of studies defines.
for _name, _entry in {
    "convention": ("text", "film convention: periodic (no seam), max_film (seam on the "
                   "maximum-film line) or seam_<deg> (welded end at that housing angle from "
                   "the load line)"),
    "onset_status": ("text", "how the onset search ended: onset (found in the range), "
                     "unstable at every mass (M̄c = 0 at the lowest speed), unstable at the "
                     "lowest speed, unstable where its shape first appears (a rotor's mode "
                     "first found inside the range), stable over the range, load exceeds "
                     "capacity, failed"),
    "critical_mass_kg_at_low_speed": ("kg", "critical rotor mass per bearing at the lowest "
                                      "speed of the range (0: unstable at every mass)"),
    "loss_factor": ("-", "structural loss factor η of the bump foundation"),
    "onset_speed_rpm": ("rpm", "onset speed of whirl: lowest speed in the range at which the "
                        "rotor is linearly unstable (empty: none in the range)"),
    "evaluations": ("-", "linear-threshold computations of the onset search"),
    "load_exceeds_capacity": ("flag", "the static load continuation stopped short of the "
                              "load with the film closing: the bearing cannot carry it"),
}.items():
    GLOSSARY.setdefault(_name, _entry)


# ---------------------------------------------------------------- bump design for stability
# Columns of gfbopt.studies.design (pitch_design); added without overriding other families.
for _name, _entry in {
    "loss_factor": ("-", "structural loss factor η of the bump foundation"),
    "onset_speed_rpm": ("rpm", "onset speed of whirl on the rotor's mass–speed line (the high "
                        "end of the range when stable over it, the low end when unstable there)"),
    "stable_over_range": ("flag", "stable at every speed of the range searched"),
    "unstable_at_lower_end": ("flag", "already unstable at the lowest speed searched"),
    "best_compliance": ("-", "compliance S with the latest onset of whirl for this law and η"),
    "best_onset_speed_rpm": ("rpm", "onset speed of whirl at the best S"),
    "band_low": ("-", "lowest S whose onset speed is within 2 % of the best"),
    "band_high": ("-", "highest S whose onset speed is within 2 % of the best"),
    "decided_by_bound": ("text", "'low'/'high' when the best S sits on the stiffest/softest "
                         "bump foil the limits allow (the limit decides), empty otherwise"),
    "baseline_compliance": ("-", "S of the bearing's original bump foil"),
    "baseline_onset_speed_rpm": ("rpm", "onset speed of whirl with the original bump foil"),
    "feasible": ("flag", "the design meets every limit: the minimum film at the film-check "
                 "speed, and a bump foil with a whole number of bumps realises S"),
    "meets_film_limit": ("flag", "the minimum film meets the limit at the film-check speed "
                         "(the search ranks S among these; the design then picks a realisable "
                         "S within 2 % of the best onset)"),
    "onset_whirl_frequency_hz": ("Hz", "whirl frequency at the onset of instability"),
    "mass_margin_at_check_speed": ("-", "M_crit/M − 1 at the film-check speed"),
    "bump_pitch_mm": ("mm", "bump pitch s of the least-stress bump foil realising S"),
    "half_bump_length_mm": ("mm", "half bump length l0 of that foil"),
    "bump_thickness_mm": ("mm", "bump foil thickness t_b of that foil"),
    "bump_stress_mpa": ("MPa", "bump bending stress σ_b = 3 Δp s l0 / t_b² at the design "
                        "pressure"),
    "number_of_bumps": ("-", "whole number of bumps round the bearing, 2πR/s"),
    "binding_limits": ("text", "limits that bind at the least-stress geometry"),
    "geometry_message": ("text", "why no bump foil realises this S (empty when one does)"),
    "objective": ("text", "quantity the geometric program minimised"),
    "pitch": ("m", "bump pitch s"),
    "half_length": ("m", "half bump length l0"),
    "thickness": ("m", "bump foil thickness t_b"),
    "top_foil_thickness": ("m", "top foil thickness t_t"),
    "bump_compliance": ("m³/N", "bump compliance per unit area α = 2 s l0³ (1 − ν²)/(E t_b³)"),
    "bump_stress": ("Pa", "bump bending stress σ_b at the design pressure"),
    "bump_deflection": ("m", "bump deflection Δp α at the design pressure"),
    "top_foil_sag": ("m", "top-foil sag between bumps at the design pressure"),
    "top_foil_stress": ("Pa", "top-foil bending stress between bumps"),
    "solver": ("text", "conic solver cvxpy used for the geometric program"),
    "solves": ("-", "geometric programs solved"),
}.items():
    GLOSSARY.setdefault(_name, _entry)


# ---------------------------------------------------------------- rotor on two bearings
# Columns of gfbopt.rotor (gfbopt rotor, the rotor_two_bearings study); added without
# overriding an entry that another family defines.
for _name, _entry in {
    "bearing": ("text", "name of the bearing of the rotor (A, B, …)"),
    "station": ("text", "axial station of the rotor: a bearing or a named station"),
    "position_m": ("m", "axial position along the rotor in its frame (conventions.frame): a "
                   "rigid body's from its centre of gravity, a shaft's from its first end"),
    "mode": ("-", "number of the mode tracked over speed in the Campbell diagram"),
    "track_label": ("text", "the mode's name, the same in the text, JSON, CSV and figures: the "
                    "label of the matched-whirl onset at which the track loses its damping, or "
                    "of the onset-list mode of the same shape (MAC ≥ 0.8), else its shape "
                    "class; ' (2)', ' (3)' when another track has that name (gfbopt.rotor."
                    "tracking); in threshold_scan.csv the mode the crossing belongs to; at "
                    "--speed-rpm the onset-list mode of the same shape (null: none)"),
    "shape_label": ("text", "shape class of the tracked mode at this speed: forward/backward, "
                    "cylindrical/conical/mixed; it may change along a track, whose name is "
                    "track_label"),
    "track_zero_rpm": ("rpm", "where the tracked mode's log decrement falls through zero, "
                       "interpolated between the diagram's speeds (empty: it does not)"),
    "note": ("text", "why the mode is unstable for every inertia scale (μ_c = 0: the "
             "massless journal whirls), else empty"),
    "inertia_scale": ("-", "μ_c: the rotor whirls in this mode when its inertias are μ_c "
                      "times the real ones (> 1 stable)"),
    "smallest_inertia_margin": ("-", "least μ_c − 1 of the mode over the speeds scanned"),
    "log_decrement": ("-", "logarithmic decrement per whirl cycle (> 0 stable)"),
    "damping_ratio": ("-", "damping ratio ζ = −Re s/|s| of the mode"),
    "growth_rate_per_s": ("1/s", "growth rate of the mode (> 0 unstable)"),
    "reference_whirl_ratio": ("-", "ν_ref of the Kelvin–Voigt foil states (empty: η = 0)"),
    "node_position_m": ("m", "axial position (the rotor file's) where the mode's dominant "
                        "whirl is least along the rotor's axis: a shaft's from its shape "
                        "along the shaft (always on it); the rigid body's where its straight "
                        "axis whirls least, which may lie off the rotor (node_location says "
                        "where); empty when the axis translates (no node)"),
    "phase_b_from_a_deg": ("deg", "phase of the dominant whirl at bearing B from bearing A "
                           "(0 cylindrical, ±180 conical)"),
    "amplitude_um": ("µm", "synchronous amplitude: major semi-axis of the 1× orbit ellipse, "
                     "(|X̂ + iŶ| + |X̂ − iŶ|)/2, the forward plus the backward radius (the "
                     "rotor transient's sync_amplitude_um)"),
    "amplitude_x_um": ("µm", "amplitude of x (x = Re(X e^{iωt}))"),
    "amplitude_y_um": ("µm", "amplitude of y"),
    "phase_x_deg": ("deg", "phase of x against the rotor's reference mark"),
    "phase_y_deg": ("deg", "phase of y against the rotor's reference mark"),
    "forward_radius_um": ("µm", "radius of the orbit's forward circular component"),
    "backward_radius_um": ("µm", "radius of the orbit's backward circular component"),
    "mass_share_kg": ("kg", "the bearing's share of the rotor mass in the half-mass rule"),
    "answer": ("text", "the one-bearing onset search's answer in words"),
}.items():
    GLOSSARY.setdefault(_name, _entry)
_PATTERNS = _PATTERNS + (
    (r"(forward|backward)_radius_(.+)", "-", "{0} whirl radius of the mode at bearing {1}, "
     "over the largest radius"),
    (r"phase_deg_(.+)", "deg", "phase of the mode's dominant whirl at bearing {0} from "
     "bearing A"),
)


# ---------------------------------------------------------------- rotor bearing-pair design
# Columns of gfbopt.studies.rotor_design; added without overriding others.
for _name, _entry in {
    "first_onset_speed_rpm": ("rpm", "first onset of whirl over all modes of the rotor (the "
                              "end of the search when every mode is stable there)"),
    "first_mode": ("text", "the mode that whirls first"),
    "onset_status": ("text", "onset, stable over the range, or unstable at the lowest speed"),
    "onset_whirl_frequency_hz": ("Hz", "whirl frequency at the first onset"),
    "stable_to_top_speed": ("-", "every mode stable up to the top speed"),
    "total_power_loss_w": ("W", "power lost in both bearings' films at the top speed"),
    "min_film_top_speed_um": ("µm", "smaller minimum film of the two bearings at the top "
                              "speed"),
    "min_film_lowest_speed_um": ("µm", "smaller minimum film of the two bearings at the "
                                 "lowest speed under the heaviest load"),
    "capacity_margin": ("-", "smaller load capacity over static load of the two bearings"),
    "bump_stress_mpa": ("MPa", "largest bump bending stress at the design pressure"),
    "top_foil_sag_ratio": ("-", "largest top-foil sag between bumps over the clearance"),
    "bump_closing_ratio": ("-", "(2 l0 + gap)/s: a bump closes within its pitch when ≤ 1"),
    "compliance_a": ("-", "compliance S of bearing A"),
    "compliance_b": ("-", "compliance S of bearing B"),
    "evaluation": ("-", "order in which the optimiser first asked for the design"),
    "batch": ("-", "generation (NSGA-II) or proposal batch (Bayesian) of the design"),
    "feasible": ("-", "the design succeeded and meets every limit"),
    "radial_clearance_um": ("µm", "radial clearance c"),
    "length_mm": ("mm", "bearing length L"),
    "bump_pitch_mm": ("mm", "bump pitch s"),
    "bump_half_length_mm": ("mm", "half bump length l0"),
    "bump_thickness_um": ("µm", "bump foil thickness t_b"),
    "preload_count": ("-", "number of shims or lobes"),
    "pads": ("-", "number of top-foil pads"),
    "nominal_onset_speed_rpm": ("rpm", "first onset of the design as searched (at the "
                                "search's loss factor, the band's low end)"),
    "loss_factor_low": ("-", "low end of the uncertain loss-factor band η"),
    "loss_factor_high": ("-", "high end of the uncertain loss-factor band η"),
    "band_low_onset_speed_rpm": ("rpm", "first onset of the design at the band's low "
                                 "loss factor"),
    "band_high_onset_speed_rpm": ("rpm", "first onset of the design at the band's high "
                                  "loss factor"),
    "worst_loss_factor": ("-", "the band's end where the design's first onset is lower: "
                          "the loss factor of the tolerance check"),
    "worst_onset_speed_rpm": ("rpm", "lowest first onset over the design and its tolerance "
                              "samples, at the worst loss factor"),
    "p05_onset_speed_rpm": ("rpm", "5th percentile of the first onset over the design and "
                            "its tolerance samples, at the worst loss factor"),
    "stable_to_top_fraction": ("-", "fraction of the design and its tolerance samples "
                               "stable to the top speed, at the worst loss factor"),
    "samples": ("-", "evaluations of the tolerance check: the design and its tolerance "
                "samples"),
    "failed_samples": ("-", "of those, evaluations that failed"),
    "first_mode_default_grid": ("text", "the mode that whirls first, on the default grid"),
    "onset_status_default_grid": ("text", "onset status on the default grid"),
    "feasible_default_grid": ("-", "the design meets every limit on the default grid"),
    "limit_cycle_um": ("µm", "subsynchronous whirl limit cycle at the bearing (largest "
                       "distance from the orbit's centre)"),
    "settled": ("-", "the limit cycle changed by ≤ 1 % over the last whirl periods"),
}.items():
    GLOSSARY.setdefault(_name, _entry)
_PATTERNS = _PATTERNS + (
    (r"(.+)_relative_change", "-", "{0}: default grid over search grid − 1"),
)
#: suffixes naming where a column's quantity was computed: the column has the unit and
#: meaning of the quantity it suffixes (``first_onset_speed_rpm_search_grid``: rpm)
_SUFFIXES = (("_search_grid", "on the search grid"), ("_default_grid", "on the default grid"))


# ---------------------------------------------------------------- rotor transients
# Columns of rotor transients (gfbopt.transient.rotor_result, study kind rotor_run_up);
# per-bearing columns carry the bearing's name (x_A_um, min_film_B_um, …).
for _name, _entry in {
    "time_s": ("s", "time since the start of the run"),
    "shaft_angle_deg": ("deg", "shaft angle since the start of the run (the imbalance phase "
                        "origin)"),
    "sync_amplitude_um": ("µm", "synchronous amplitude: major semi-axis of the order-tracked "
                          "1× orbit ellipse over the window, (|X̂ + iŶ| + |X̂ − iŶ|)/2 (the "
                          "linear imbalance response's amplitude_um); of an orbit, over its "
                          "last window, ending at the record's end"),
    "sync_amplitude_x_um": ("µm", "order-tracked 1× amplitude of the journal's x (along "
                            "gravity), zero to peak"),
    "sync_phase_x_deg": ("deg", "phase of that 1× component: x peaks when the shaft angle is "
                         "minus this"),
    "sync_amplitude_y_um": ("µm", "order-tracked 1× amplitude of the journal's y, zero to "
                            "peak"),
    "sync_phase_y_deg": ("deg", "phase of the 1× component of y"),
    "sub_amplitude_um": ("µm", "largest subsynchronous spectral peak (a local maximum inside "
                         "0.05–0.95 × shaft speed), 1× removed, zero to peak (empty: no peak "
                         "inside the band)"),
    "sub_frequency_hz": ("Hz", "frequency of that peak (positive: forward whirl; empty: no "
                         "peak)"),
    "sub_whirl_ratio": ("-", "that frequency over the shaft frequency, inside 0.05–0.95 "
                        "(empty: no peak)"),
    "quantity": ("text", "what the row reports"),
    "value": ("-", "its value, in the unit named by the quantity"),
}.items():
    GLOSSARY.setdefault(_name, _entry)
_PATTERNS += (
    (r"x_(\w+)_um", "µm", "journal centre x at bearing {0} (global frame, along gravity, "
     "from the bearing centre)"),
    (r"y_(\w+)_um", "µm", "journal centre y at bearing {0} (90° ahead of gravity)"),
    (r"min_film_(\w+)_um", "µm", "smallest film at bearing {0} since the previous sample"),
    (r"running_clearance_um_(\w+)", "µm", "running radial clearance at bearing {0}"),
    (r"film_temperature_c_(\w+)", "°C", "mean film temperature at bearing {0}"),
    (r"viscosity_pa_s_(\w+)", "Pa s", "gas viscosity at the film temperature at bearing {0}"),
)
for _name, _entry in TERMS.items():
    if _name in GLOSSARY:
        raise ValueError(f"glossary: {_name!r} is defined twice (gfbopt/terms and here)")
    GLOSSARY[_name] = _entry
