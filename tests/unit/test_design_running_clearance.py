"""The design with bearings at their clearance at speed (issue 28/30): the rotor transient
refuses a rotor read with its [journal]/[thermal] tables (it would run cold), and the design's
top-speed orbit runs the rotor frozen at the top speed's running condition — each bearing's
running clearance and viscosity there, the tables gone."""
from __future__ import annotations

from pathlib import Path

import pytest

from gfbopt.design.robustness import frozen_at_running_condition
from gfbopt.errors import ParameterError
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.transient.rotor_analysis import rotor_orbit

ROOT = Path(__file__).resolve().parents[2]
HEATED = ROOT / "problems" / "rotors" / "blower_thermal.toml"


def test_the_rotor_transient_refuses_a_rotor_read_with_its_heat_balance():
    system = load_rotor(HEATED, running=True)
    with pytest.raises(ParameterError, match="does not carry the heat balance"):
        rotor_orbit(system, 30000.0, 1.0, grid="24x8")


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
