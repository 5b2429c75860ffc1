"""Bearings at their clearance at speed in the rotor transient and the design (issues 28/30):
a constant-speed orbit of a rotor read with its [journal]/[thermal] tables runs at that speed's
running condition (each bearing's running clearance and viscosity there, the tables gone; the
design's top-speed orbit is one); a run-up follows each bearing's running line
(tests/unit/test_rotor_heated_rampup.py)."""
from __future__ import annotations

from pathlib import Path

import pytest

from gfbopt.rotor.supports import frozen_at_running_condition
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.transient.rotor_analysis import rotor_orbit, rotor_ramp

ROOT = Path(__file__).resolve().parents[2]
HEATED = ROOT / "problems" / "rotors" / "blower_thermal.toml"


def test_a_run_up_of_a_heated_rotor_follows_its_line_an_orbit_holds_its_speeds_condition():
    system = load_rotor(HEATED, running=True)
    ramp = rotor_ramp(system, 5000.0, 30000.0, 5.0e6, grid="24x8", linear_onset=False)
    assert ramp.to_dict()["clearance_model"].startswith("heat balance + growth, quasi-steady")
    orbit = rotor_orbit(system, 30000.0, 2.0, grid="24x8").to_dict()
    _, running = frozen_at_running_condition(system, 30000.0, Grid.parse("24x8"))
    assert orbit["clearance_model"].startswith("heat balance + growth, frozen")
    assert orbit["running_condition"] == running["bearings"]


def test_frozen_rotor_carries_each_bearings_running_clearance_at_the_speed():
    system = load_rotor(HEATED, running=True)
    frozen, running = frozen_at_running_condition(system, 30000.0, Grid.parse("24x8"))
    assert "failure" not in running and running["speed_rpm"] == 30000.0
    for cold, warm in zip(system.bearings, frozen.bearings):
        point = running["bearings"][cold.name]
        assert warm.running_tables == () and cold.running_tables
        assert warm.geometry.radial_clearance == pytest.approx(
            point["running_clearance_um"] * 1e-6, rel=1e-12)
        # the journal grows and heats at 30,000 rpm: the clearance closes, the gas thickens
        assert warm.geometry.radial_clearance < cold.geometry.radial_clearance
        assert warm.geometry.viscosity > cold.geometry.viscosity
