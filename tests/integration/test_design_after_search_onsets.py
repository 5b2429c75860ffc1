"""The bearing-pair design's stages after the search (default-grid check, loss-factor band,
tolerance samples) refine each first onset from a known one instead of scanning from the
lowest speed (gfbopt.design.rotor_objectives.first_onset with ``near``): the same onset as
the full scan, on a fraction of its speeds; the fine grid's cold film check from the coarse
grid's equilibrium (Newton) is IPOPT's state.  Blower rotor, shim preload, 36x10 (the main
job's search grid) and 72x20."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from gfbopt.design.rotor_objectives import (ONSET_TOLERANCE, EvaluationSettings, _lowest,
                                            apply_design, evaluate_rotor_design,
                                            first_onset)
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.options import ModelOptions
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine
from gfbopt.static import SolverCache

ROOT = Path(__file__).resolve().parents[2]
SYSTEM = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
#: the main job's chosen design and a tolerance sample of it (± 1 µm)
NOMINAL = {"radial_clearance_um": 18.903591605040464, "preload_depth_um": 5.046874970770284}
SAMPLE = {"radial_clearance_um": 19.6, "preload_depth_um": 4.3}


def _settings(grid: str = "36x10", eta: float = 0.0) -> EvaluationSettings:
    return EvaluationSettings(4000.0, 45000.0, 56250.0, Grid.parse(grid), loss_factor=eta,
                              heaviest_load_factor=2.0)


def _line(design: dict, settings: EvaluationSettings, cache) -> SpeedLine:
    designed, _ = apply_design(SYSTEM, design, settings)
    return SpeedLine(resolve_rotor(designed, settings.grid, cache,
                                   ModelOptions(loss_factor=settings.loss_factor)))


def _exact(line: SpeedLine, row: dict) -> float:
    """The root of the least μ_c − 1 to 1e-9 in the full scan's bracket."""
    from gfbopt.rotor.system import scan_speeds

    speeds = scan_speeds(4000.0, 56250.0)
    k = next(j for j, s in enumerate(speeds) if s >= row["first_onset_speed_rpm"])

    def margin(speed):
        c = _lowest(line, speed)
        return (c.inertia_scale - 1.0) / (c.inertia_scale + 1.0)
    return brentq(margin, speeds[k - 1], speeds[k], xtol=1e-9 * speeds[k], rtol=1e-12)


@pytest.mark.parametrize("design, eta", [(SAMPLE, 0.0), (NOMINAL, 0.2)],
                         ids=["tolerance sample", "other end of the band"])
def test_onset_from_a_nearby_onset_is_the_full_scans_on_fewer_speeds(design, eta):
    """From the nominal's onset at η = 0: the sample's onset (7 % lower) and the nominal's at
    η = 0.2 (4 % higher) are the roots of the full scan's bracket to 1e-5 (the search's
    Brent stops at ONSET_TOLERANCE, so it agrees to that), with the same mode and whirl
    frequency, on at most 5 speeds where the scan from the lowest speed needs at least 9."""
    cache = SolverCache(Grid.parse("36x10"))
    near = first_onset(_line(NOMINAL, _settings(), cache), _settings())["first_onset_speed_rpm"]
    settings = _settings(eta=eta)
    full_line, near_line = _line(design, settings, cache), _line(design, settings, cache)
    full = first_onset(full_line, settings)
    found = first_onset(near_line, settings, near)
    assert abs(found["first_onset_speed_rpm"] / near - 1.0) > 0.03      # a real shift
    assert found["onset_status"] == full["onset_status"] == "onset"
    assert found["first_mode"] == full["first_mode"]
    assert found["first_onset_speed_rpm"] == pytest.approx(_exact(full_line, full), rel=1e-5)
    assert found["first_onset_speed_rpm"] == pytest.approx(full["first_onset_speed_rpm"],
                                                           rel=ONSET_TOLERANCE)
    assert found["onset_whirl_frequency_hz"] == pytest.approx(
        full["onset_whirl_frequency_hz"], rel=1e-3)
    assert len(near_line.speeds_solved) <= 5 < 9 <= len(full_line.speeds_solved)


def test_a_near_onset_that_does_not_bracket_falls_back_to_the_full_scan():
    """A 'nearby' onset far from this design's (8,000 rpm, two scan intervals below its
    onset): its first secant step leaves the intervals next to it and the scan from the lowest speed
    gives the search's own answer."""
    cache = SolverCache(Grid.parse("36x10"))
    settings = _settings()
    full = first_onset(_line(NOMINAL, settings, cache), settings)
    found = first_onset(_line(NOMINAL, settings, cache), settings, 8000.0)
    assert found["first_onset_speed_rpm"] == pytest.approx(full["first_onset_speed_rpm"],
                                                           rel=1e-9)
    assert found["first_mode"] == full["first_mode"]


def test_onset_only_rows_and_the_evaluation_keywords():
    """``evaluate_rotor_design`` takes the nearby onset and ``onset_only`` (the tolerance
    check's rows: the onset, no power or film) without reading them as design variables."""
    settings = _settings()
    nominal = evaluate_rotor_design(SYSTEM, settings, None, **NOMINAL)
    row = evaluate_rotor_design(SYSTEM, settings, None, onset_only=True,
                                near_onset_rpm=nominal["first_onset_speed_rpm"], **SAMPLE)
    assert row["success"], row["message"]
    assert "total_power_loss_w" not in row and "min_film_lowest_speed_um" not in row
    assert 0.9 * nominal["first_onset_speed_rpm"] < row["first_onset_speed_rpm"] \
        < nominal["first_onset_speed_rpm"]


def test_fine_grid_cold_film_check_is_newton_from_the_coarse_grid_and_ipopt_s_state():
    """The film at the lowest speed under twice the load on 72x20 (4× the cells of the
    36x10 cold grid): solved by the Newton fast path from the coarse equilibrium, the same
    state as IPOPT's cold solve to 1e-10."""
    from gfbopt.design.rotor_objectives import _static
    from gfbopt.static import solve_static

    settings = _settings("72x20")
    cache = SolverCache(settings.grid)
    case = _line(NOMINAL, settings, cache).rotor.cases[1]
    load = 2.0 * case.load_newton
    sol = _static(case, 4000.0, load, settings.grid, cache)
    model = case.model(4000.0)
    ipopt = solve_static(model, load=case.bearing.nondimensional_load(load),
                         solver=cache(model, settings.grid), continuation=True)
    assert sol.success and ipopt.success and sol.solver == "newton" != ipopt.solver
    assert np.max(np.abs(sol.state - ipopt.state)) <= 1e-10


def test_tolerance_figures_are_the_full_scans_on_fewer_speeds(monkeypatch):
    """The tolerance check of the nominal design (2 samples at 36x10, band [0, 0.2]) against
    the same figures from full-scan evaluations of the same samples: the band's ends, the
    worst case and the 5th percentile to the search's ONSET_TOLERANCE (the refinement from
    the nominal is to 1e-5, the full scan's Brent to 1e-3), the same worst end; its 3
    evaluations solve at most 5 speeds each (the full scan: 11)."""
    from gfbopt.design.problem import DesignProblem, Objective, Variable
    from gfbopt.design.robustness import robustness, tolerance_sample

    solved = []
    states = SpeedLine.states

    def counted(line, speed):
        if speed not in line.speeds_solved:
            solved.append(speed)
        return states(line, speed)

    settings = _settings()
    problem = DesignProblem((Variable("radial_clearance_um", 15.0, 35.0),
                             Variable("preload_depth_um", 0.0, 12.0)),
                            (Objective("first_onset_speed_rpm", "max"),))
    row = {"point": "p0", **NOMINAL, **evaluate_rotor_design(SYSTEM, settings, None,
                                                             **NOMINAL)}
    tolerances = {"radial_clearance_um": 1.0, "preload_depth_um": 1.0}
    monkeypatch.setattr(SpeedLine, "states", counted)
    out = robustness(SYSTEM, settings, [row], tolerances, (0.0, 0.2), 2, 0, problem).iloc[0]
    monkeypatch.undo()
    assert len(solved) <= 3 * 5
    high = evaluate_rotor_design(SYSTEM, dataclasses.replace(settings, loss_factor=0.2),
                                 None, **NOMINAL)["first_onset_speed_rpm"]
    onsets = [row["first_onset_speed_rpm"]] + [
        evaluate_rotor_design(SYSTEM, settings, None, **d)["first_onset_speed_rpm"]
        for d in tolerance_sample(NOMINAL, tolerances, 2, 0)]
    assert out["worst_loss_factor"] == 0.0 and out["failed_samples"] == 0
    assert out["band_high_onset_speed_rpm"] == pytest.approx(high, rel=ONSET_TOLERANCE)
    assert out["worst_onset_speed_rpm"] == pytest.approx(min(onsets), rel=ONSET_TOLERANCE)
    assert out["p05_onset_speed_rpm"] == pytest.approx(np.percentile(onsets, 5),
                                                       rel=ONSET_TOLERANCE)
