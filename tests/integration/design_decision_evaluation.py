"""A planted stand-in for gfbopt.design.rotor_objectives.evaluate_rotor_design, for the
decision of a design run (tests/integration/test_design_decision.py): the first onset

    N₁ = 12,000 + 300 (35 − c) + 100,000 η + 150 F + 1,000 (m − 3.2) + offset   [rpm]

(c the radial clearance [µm], η the loss factor, F the static side loads' sum [N], m the
rotor's mass [kg], offset from GFBOPT_TEST_ONSET_OFFSET, default 0), capped at the end
of the onset search; the
start-up film 0.15 c − 1 [µm] (the 1.5 µm limit binds at c = 16.667 µm, where the onset is
highest among the designs that meet it).  Every call is logged (η, F, c) when
GFBOPT_TEST_DESIGN_LOG names a log; with GFBOPT_TEST_STOP_AFTER_LEVERS = k, the call after
k lever-search calls raises KeyboardInterrupt (a run killed in that stage)."""
from __future__ import annotations

import os
from pathlib import Path


def planted_evaluation(system, settings, cache=None, near_onset_rpm=None, onset_only=False,
                       **design):
    c = float(design["radial_clearance_um"])
    force = sum(load.force for load in system.side_loads)
    log = os.environ.get("GFBOPT_TEST_DESIGN_LOG")
    if log:
        with open(log, "a") as f:
            f.write(f"{settings.grid} {settings.loss_factor!r} {force!r} {c!r} "
                    f"{int(onset_only)}\n")
        stop = os.environ.get("GFBOPT_TEST_STOP_AFTER_LEVERS")
        if stop and len([x for x in Path(log).read_text().splitlines()
                         if _levered(x)]) > int(stop):
            raise KeyboardInterrupt("planted: the run is killed in its lever searches")
    onset = (12000.0 + 300.0 * (35.0 - c) + 100000.0 * settings.loss_factor + 150.0 * force
             + 1000.0 * (system.body.mass - 3.2)
             + float(os.environ.get("GFBOPT_TEST_ONSET_OFFSET", "0")))
    status = "onset"
    if onset >= settings.search_high_rpm:
        onset, status = settings.search_high_rpm, "stable over the range"
    row = {"first_onset_speed_rpm": onset, "first_mode": "forward conical",
           "onset_status": status, "onset_whirl_frequency_hz": onset / 120.0,
           "stable_to_top_speed": onset >= settings.top_speed_rpm, "grid": str(settings.grid),
           "success": True, "message": "", "wall_time_s": 0.001}
    if not onset_only:
        row.update({"total_power_loss_w": 80.0 + 3.0 * (35.0 - c),
                    "min_film_top_speed_um": 5.0, "min_film_lowest_speed_um": 0.15 * c - 1.0,
                    "bump_stress_mpa": 100.0, "top_foil_sag_ratio": 0.1,
                    "bump_closing_ratio": 0.5, "compliance_a": 1.0, "compliance_b": 1.0})
    return row


def _levered(line: str) -> bool:
    """A logged call of a lever search: a loss factor other than the band's ends (0,
    0.2) or a side load."""
    _, eta, force, *_ = line.split()
    return float(eta) not in (0.0, 0.2) or float(force) > 0.0
