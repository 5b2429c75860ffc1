"""Run-ups and coast-downs of a heated rotor: each bearing at the running
condition of the instantaneous speed, quasi-steady in temperature, on the cold-c model
(gfbopt.transient.rotor_running / rotor_heated; the films' offset and viscosity ratio in
FusedFilms)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.running import running_case
from gfbopt.rotor.supports import COLD_FACTOR, COLD_GRID, resolve_rotor
from gfbopt.transient.rotor_analysis import rotor_orbit, rotor_ramp
from gfbopt.transient.rotor_running import (CLEARANCE_TOLERANCE, QUASI_STEADY,
                                            RunningSchedule, SpeedTable, solve_running_line)

ROOT = Path(__file__).resolve().parents[2]
HEATED = ROOT / "problems" / "rotors" / "blower_thermal.toml"
COLD = ROOT / "problems" / "rotors" / "blower.toml"
GRID = "24x8"
FIXED = dict(time_step=0.1, stages=4)        # the same steps on both paths


def journals(result) -> np.ndarray:
    return np.array([result.run.journal(0, k) for k in range(2)])       # [m]


def null_heat_rotor(tmp_path) -> Path:
    """The blower on the Ruscitto bearing with 1e15 W/K everywhere and a 1e-12 kg/m³
    journal: ambient film, no growth (as tests/verification/test_rotor_running.py)."""
    src = (ROOT / "problems" / "bearings" / "ruscitto_thermal.toml").read_text().replace(
        "density = 7850.0", "density = 1e-12")
    for key in ("journal_to_ambient = 0.5", "foil_to_sleeve = 5.0", "sleeve_to_ambient = 1.0"):
        assert key in src
        src = src.replace(key, key.split("=")[0] + "= 1e15")
    (tmp_path / "bearing.toml").write_text(src + "film_to_journal = 1e15\nfilm_to_foil = 1e15\n")
    rotor = tmp_path / "rotor.toml"
    rotor.write_text(COLD.read_text().replace("../bearings/ruscitto.toml", "bearing.toml"))
    return rotor


def test_a_heated_run_up_without_heat_or_growth_is_the_cold_run_up(tmp_path):
    """(i) Infinite conductances and no growth: c_run = c and μ = μ_ref at every speed of the
    line, and the run-up through the running line equals the cold one to 1e-12 (measured:
    identical, the offset 0 and the ratio 1 exactly)."""
    system = load_rotor(null_heat_rotor(tmp_path), running=True)
    hot = rotor_ramp(system, 10000.0, 14000.0, 400000.0, grid=GRID, linear_onset=False,
                     **FIXED)
    cold = rotor_ramp(load_rotor(COLD), 10000.0, 14000.0, 400000.0, grid=GRID,
                      linear_onset=False, **FIXED)
    a, b = journals(hot), journals(cold)
    assert a.shape == b.shape and hot.run.success and cold.run.success
    assert np.abs(a - b).max() <= 1e-12 * np.abs(b).max()
    d = hot.to_dict()
    assert d["clearance_model"] == QUASI_STEADY and d["running_end"] is None
    rows = d["running_line"]
    assert {r["bearing"] for r in rows} == {"A", "B"} and len(rows) == 2 * d["running_nodes"]
    for r in rows:
        assert r["running_clearance_um"] == pytest.approx(20.0, rel=1e-10)
        assert abs(r["film_temperature_c"] - 20.0) < 1e-9
    assert "running_line.csv" in hot.tables()


def test_a_heated_orbit_on_the_line_is_the_frozen_orbit_at_that_speed():
    """(ii) At 10,000 rpm (stable, from the equilibrium, imbalance only) the orbit on the
    cold-c model with the running line's one speed equals today's frozen orbit (the bearing
    at c_run and μ(T_f)): the same equations in two scalings, X = e/c against e/c_run, so
    they differ by the round-off of the scalings, amplified by 20 revolutions of stable
    dynamics: 1e-11 of the orbit (measured 3e-14)."""
    system = load_rotor(HEATED, running=True)
    line = rotor_orbit(system, 10000.0, 20.0, grid=GRID, running_path="line",
                       perturbation="none", **FIXED)
    frozen = rotor_orbit(system, 10000.0, 20.0, grid=GRID, perturbation="none", **FIXED)
    a, b = journals(line), journals(frozen)
    assert np.abs(a - b).max() <= 1e-11 * np.abs(b).max()
    d = line.to_dict()
    for row, eq_line, eq_frozen in zip(d["running_line"], line.equilibria, frozen.equilibria):
        ratio = row["running_clearance_um"] / 20.0                  # c_run/c, cold c 20 µm
        assert eq_line["eccentricity"] == pytest.approx(eq_frozen["eccentricity"] * ratio,
                                                        rel=1e-12)
        assert eq_line["min_film_thickness_um"] == pytest.approx(
            eq_frozen["min_film_thickness_um"], rel=1e-12)
    for name, point in frozen.to_dict()["running_condition"].items():
        row = next(r for r in d["running_line"] if r["bearing"] == name)
        assert row["running_clearance_um"] == pytest.approx(point["running_clearance_um"],
                                                            rel=1e-12)


def test_the_interpolated_line_is_the_fixed_point_between_its_speeds():
    """The PCHIP line against fixed points solved afresh at speeds that are not nodes: within
    2 × the refinement tolerance of the cold clearance (1e-3 c), and the midpoint misses the
    plan reports are within it."""
    grid = Grid.parse(GRID)
    system = load_rotor(HEATED, running=True)
    plan = solve_running_line(system, grid, 5000.0, 55000.0)
    assert plan.verdict is None and plan.end_rpm == 55000.0
    assert plan.errors["clearance_fraction"] <= CLEARANCE_TOLERANCE
    rotor = resolve_rotor(system, grid)
    for speed in (6234.0, 23456.0, 41111.0, 53777.0):
        for k, schedule in enumerate(plan.schedules):
            _, _, point, failed = running_case(rotor.running, k, rotor.cases[k],
                                               rotor.loads[k], speed, None, COLD_GRID,
                                               COLD_FACTOR)
            assert failed is None
            got = schedule.at(speed)["running_clearance_um"] * 1e-6
            assert abs(got - point.running_clearance) <= 2 * CLEARANCE_TOLERANCE * 20e-6


def test_a_run_up_into_a_runaway_ends_there_with_the_verdict():
    """Bearing B runs away near 59,000 rpm on 24×8: the run-up to 62,000 rpm is not raised;
    it ends at the last speed that runs, the failure bracketed to 1 %, and says so."""
    system = load_rotor(HEATED, running=True)
    result = rotor_ramp(system, 57000.0, 62000.0, 2.0e6, grid=GRID, linear_onset=False)
    d = result.to_dict()
    assert d["running_end"].startswith("thermal runaway at bearing B from ")
    assert d["requested_end_rpm"] == 62000.0
    limit = float(d["running_end"].split("from ")[1].split(" rpm")[0].replace(",", ""))
    assert d["end_speed_rpm"] < limit <= d["end_speed_rpm"] * 1.0102
    assert d["running_line"][-1]["speed_rpm"] == d["end_speed_rpm"]
    assert any("thermal runaway" in n for n in d["notes"])


def test_a_coast_down_from_a_speed_without_a_running_state_is_refused():
    system = load_rotor(HEATED, running=True)
    with pytest.raises(ParameterError, match="has no running state to start from"):
        rotor_ramp(system, 62000.0, 50000.0, 1.0e6, grid=GRID, linear_onset=False)


def test_the_speed_table_is_the_pchip_of_each_bearing_at_nodes_and_between():
    """At the nodes δ = (c − c_run)/c and μ_ref/μ exactly (to round-off); the scalar and the
    batch evaluations agree to round-off; clamped outside the line."""
    n = np.array([1000.0, 2000.0, 4000.0, 5000.0])
    a = RunningSchedule(n, 20e-6 * np.array([1.0, 0.99, 0.95, 0.9]),
                        np.array([1.0, 1.01, 1.05, 1.1]) * 3e-5, np.zeros(4), 20e-6, 3e-5, "A")
    b = RunningSchedule(n, 18e-6 * np.array([1.0, 0.98, 0.97, 0.96]),
                        np.array([1.0, 1.02, 1.03, 1.2]) * 3e-5, np.zeros(4), 18e-6, 3e-5, "B")
    table = SpeedTable([a, b], 5000.0)
    for j, speed in enumerate(n):
        delta, inverse = table.at(float(speed / 5000.0))
        assert delta == pytest.approx([1 - a.clearance_m[j] / 20e-6,
                                       1 - b.clearance_m[j] / 18e-6], abs=1e-15)
        assert inverse == pytest.approx([3e-5 / a.viscosity_pa_s[j],
                                         3e-5 / b.viscosity_pa_s[j]], rel=1e-14)
    r = np.array([0.1, 0.3, 0.55, 0.9, 1.2])
    d_all, i_all = table.at(r)
    for j, x in enumerate(r):
        d1, i1 = table.at(float(x))
        # the same cubic, evaluated as one dot product (a float) or by Horner (a batch)
        assert d_all[j] == pytest.approx(d1, rel=1e-13, abs=1e-16)
        assert i_all[j] == pytest.approx(i1, rel=1e-13)
    assert np.array_equal(table.at(0.1)[0], table.at(0.2)[0])          # clamped below


def test_a_run_up_into_a_centrifugal_closure_ends_below_it_with_the_verdict(tmp_path):
    """A [journal]-only bearing on a soft journal (E = 1e10 Pa: a test material) closes by
    centrifugal growth, u_c ∝ ω²: the run-up stops at the last speed that runs, the closure
    (running clearance at the 1 µm floor, gfbopt.thermal.running.closure_speeds' closed form)
    lies inside the reported 1 % bracket."""
    from gfbopt.thermal.running import closure_speeds

    src = (ROOT / "problems" / "bearings" / "ruscitto_thermal.toml").read_text()
    src = src[:src.index("\n[thermal]\n")].replace("youngs_modulus = 200e9",
                                                     "youngs_modulus = 1e10")
    (tmp_path / "bearing.toml").write_text(src)
    rotor = tmp_path / "rotor.toml"
    rotor.write_text(COLD.read_text().replace("../bearings/ruscitto.toml", "bearing.toml"))
    system = load_rotor(rotor, running=True)
    d = rotor_ramp(system, 30000.0, 50000.0, 2.0e6, grid=GRID, linear_onset=False).to_dict()
    assert d["running_end"].startswith("the journal reaches the foil at bearing A from ")
    assert d["thermal_models"] == {"A": "centrifugal growth", "B": "centrifugal growth"}
    limit = float(d["running_end"].split("from ")[1].split(" rpm")[0].replace(",", ""))
    spec = resolve_rotor(system, Grid.parse(GRID)).running.specs[0]
    close, _ = closure_speeds(spec, 40000.0, spec.centrifugal(40000.0 * np.pi / 30.0))
    # the line ends at the last speed that runs (the ramp itself may end below it, in
    # contact: end_speed_rpm is where it ended, end_cause why)
    line_end = max(r["speed_rpm"] for r in d["running_line"])
    assert d["end_speed_rpm"] <= line_end
    assert line_end < close <= limit + 0.5 <= 1.0101 * line_end  # N rounded
