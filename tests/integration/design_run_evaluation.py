"""A cheap stand-in for gfbopt.design.rotor_objectives.evaluate_rotor_design, for tests of
the design run itself (tests/integration/test_design_run_safety.py).  Kept in a module of
its own with light imports: the pool's workers import it to run it."""
from __future__ import annotations

import os
import signal
from pathlib import Path

#: the test process's pid (a worker is any other process)
PARENT = "GFBOPT_TEST_DESIGN_PARENT"
#: evaluations after which every pool worker kills itself
DEATHS = "GFBOPT_TEST_DESIGN_DEATHS"


def cheap_evaluation(system, settings, cache=None, **design):
    """No design stable to 45,000 rpm: the onset falls with the clearance and rises with
    the loss factor; the power falls with the clearance (a front); the film at the lowest
    speed breaks the 1.5 µm limit below c = 16.7 µm.  Every call is logged (grid, η) when
    the environment names a log; with ``GFBOPT_TEST_DESIGN_DEATHS`` set, a pool worker
    (not the test's process) kills itself once that many evaluations were logged."""
    c = float(design["radial_clearance_um"])
    log = os.environ.get("GFBOPT_TEST_DESIGN_LOG")
    if log:
        with open(log, "a") as f:
            f.write(f"{settings.grid} {settings.loss_factor:g} {c!r}\n")
        limit = os.environ.get(DEATHS)
        if limit and str(os.getpid()) != os.environ.get(PARENT):
            if len(Path(log).read_text().splitlines()) > int(limit):
                os.kill(os.getpid(), signal.SIGKILL)
    onset = 12000.0 + 300.0 * (35.0 - c) + 4000.0 * settings.loss_factor
    return {"first_onset_speed_rpm": onset, "first_mode": "forward conical",
            "onset_status": "onset", "onset_whirl_frequency_hz": onset / 120.0,
            "stable_to_top_speed": onset >= settings.top_speed_rpm,
            "total_power_loss_w": 80.0 + 3.0 * (35.0 - c), "min_film_top_speed_um": 5.0,
            "min_film_lowest_speed_um": 0.15 * c - 1.0, "bump_stress_mpa": 100.0,
            "top_foil_sag_ratio": 0.1, "bump_closing_ratio": 0.5, "compliance_a": 1.0,
            "compliance_b": 1.0, "grid": str(settings.grid), "success": True,
            "message": "", "wall_time_s": 0.001}
