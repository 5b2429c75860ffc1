"""The engineer's question in SI: the Ruscitto bearing, 2 kg and 20 N per bearing.

For each film convention: the verdict and margin at 10,000 and 45,000 rpm and the onset speed,
with the arithmetic cross-checked against the non-dimensional path (M̄ = M c ω²/W0 both ways,
and the threshold recomputed from a BearingModel at the onset speed).  Grid 72 × 20 (within
0.5 % of the default grid's loads up to ε ≈ 0.6; here ε = 0.2–0.5).  Pinned values were
measured on this grid; they are regression values of the model, with tolerances (0.5 %) far
above round-off and far below any change of physics or convention (the conventions differ by
25–80 %).
"""
import math
from pathlib import Path

import pytest

from gfbopt import Grid, ParameterError, SolverCache, solve_static
from gfbopt.inputs import ModelOptions, OperatingPoint, Rotor, load_bearing_file
from gfbopt.inputs.conversions import mass_parameter, rpm_to_rad_per_s
from gfbopt.linear import coefficients, linear_threshold, linearise
from gfbopt.rotor import LoadCapacityError, coefficient_table, onset_speed, stability
from gfbopt.rotor.coefficients import COLUMNS

RUSCITTO = Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto.toml"
BEARING, FILE_OPTIONS = load_bearing_file(RUSCITTO)
GRID = Grid(72, 20)
ROTOR = Rotor(2.0)
LOAD = 20.0
C = 20e-6

#: convention → (options, M̄c at 45,000 rpm, M̄c at 10,000 rpm, onset [rpm], onset whirl [Hz]),
#: measured on 72 × 20
CONVENTIONS = {
    "periodic": (dict(film="periodic"), 0.6353, 1.5963, 8856.5, 72.16),
    "max_film": (dict(film="seam", seam_angle_deg="max_film"), 3.3241, 2.9150, 11570.4, 95.76),
    "seam_180": ({}, 3.3100, 3.9090, 13098.5, 109.6),          # the file's [model] table
}


@pytest.fixture(scope="module")
def cache():
    return SolverCache(GRID)


def _run(cache, name, speed):
    return stability(BEARING, ROTOR, OperatingPoint(speed, LOAD), grid=GRID, cache=cache,
                     options=FILE_OPTIONS, **CONVENTIONS[name][0])


@pytest.fixture(scope="module")
def onsets(cache):
    return {name: onset_speed(BEARING, ROTOR, LOAD, (5000, 20000), grid=GRID, cache=cache,
                              options=FILE_OPTIONS, **CONVENTIONS[name][0])
            for name in CONVENTIONS}


@pytest.mark.parametrize("name", list(CONVENTIONS))
def test_verdict_and_margin_at_45000_rpm(cache, name):
    """M̄ = 2 kg × 20 µm × ω²/20 N = 44.41 at 45,000 rpm (docs/PHYSICS.md §2), far above every
    convention's threshold: unstable, with the margin and critical mass following from M̄c by
    the conversions, worked here by hand; the least-stable mode grows (δ < 0)."""
    r = _run(cache, name, 45000)
    omega = 45000 * 2 * math.pi / 60
    assert r.mass_parameter == pytest.approx(2.0 * C * omega**2 / LOAD, rel=1e-12)
    assert r.critical_mass_parameter == pytest.approx(CONVENTIONS[name][1], rel=5e-3)
    assert r.critical_mass_kg == pytest.approx(r.critical_mass_parameter * LOAD / (C * omega**2),
                                               rel=1e-12)
    assert r.mass_margin == pytest.approx(r.critical_mass_kg / 2.0 - 1, rel=1e-12)
    assert not r.stable and r.verdict == "unstable" and r.success
    assert r.growth_rate_per_s > 0 and r.log_decrement < 0
    assert r.growth_rate_per_s == pytest.approx(r.growth_rate * omega, rel=1e-12)
    assert r.whirl_frequency_hz == pytest.approx(r.mode_whirl_ratio * omega / (2 * math.pi))
    assert r.threshold_whirl_frequency_hz == pytest.approx(
        r.threshold_whirl_ratio * omega / (2 * math.pi), rel=1e-12)
    assert 0.45 < r.threshold_whirl_ratio < 0.55
    assert r.min_film_thickness_um == pytest.approx(r.linearisation.static.min_film * 20,
                                                    rel=1e-12)
    assert r.bearing_number == pytest.approx(7.64, abs=0.01)


def test_the_convention_decides_the_verdict_at_10000_rpm(cache):
    """M̄ = 2.19 at 10,000 rpm: the periodic film (M̄c = 1.60) says unstable, both seams
    (2.92 on the maximum-film line, 3.91 with the welded end opposite the load) say stable,
    with a decaying least-stable mode (δ > 0) — the convention matters as much as the physics."""
    results = {name: _run(cache, name, 10000) for name in CONVENTIONS}
    for name, r in results.items():
        assert r.critical_mass_parameter == pytest.approx(CONVENTIONS[name][2], rel=5e-3)
        assert r.stable == (r.mass_parameter < r.critical_mass_parameter)
        assert (r.growth_rate < 0) == r.stable and (r.log_decrement > 0) == r.stable
    assert not results["periodic"].stable
    assert results["max_film"].stable and results["seam_180"].stable
    assert results["seam_180"].mass_margin == pytest.approx(3.9090 / 2.1926 - 1, rel=5e-3)
    assert results["seam_180"].conventions["seam_angle_deg"] == 180.0


@pytest.mark.parametrize("name", list(CONVENTIONS))
def test_onset_speed_cross_checked_on_the_nondimensional_path(onsets, name):
    """At the onset speed N*, a BearingModel built there and solved at W̄0 = 20 N/(p_a R²)
    gives M̄c(Λ(N*)) equal to the rotor's M̄ = M c ω*²/W0 (to 2e-3: Brent's tolerance of 1e-4
    in speed is 2e-4 in M̄); the whirl frequency is γc ω*/(2π)."""
    o = onsets[name]
    expected_speed, expected_hz = CONVENTIONS[name][3:]
    assert o.success and not o.stable_over_range and not o.unstable_at_lower_end
    assert o.onset_speed_rpm == pytest.approx(expected_speed, rel=5e-3)
    assert o.whirl_frequency_hz == pytest.approx(expected_hz, rel=5e-3)
    omega = rpm_to_rad_per_s(o.onset_speed_rpm)
    kwargs = dict(film="seam", seam_angle_deg=180.0, foil="simple")
    if name == "periodic":
        kwargs.update(film="periodic", seam_angle_deg=None)
    elif name == "max_film":
        kwargs.update(seam_angle_deg=None)
    model = BEARING.model(o.onset_speed_rpm, **kwargs)
    sol = solve_static(model, load=BEARING.nondimensional_load(LOAD), grid=GRID)
    thr = linear_threshold(linearise(sol))
    mbar = mass_parameter(2.0, C, omega, LOAD)
    assert mbar == pytest.approx(thr.critical_mass, rel=2e-3)
    assert o.whirl_frequency_hz == pytest.approx(thr.whirl_ratio * omega / (2 * math.pi),
                                                 rel=2e-3)


def test_onset_depends_on_the_convention(onsets):
    """DESIGN_NOTES: the periodic film puts the onset near 10,000 rpm and the seam on the
    maximum-film line moves it by about 30 % (measured +31 %); the welded end opposite the
    load moves it by +48 %."""
    speeds = {name: o.onset_speed_rpm for name, o in onsets.items()}
    assert 8000 < speeds["periodic"] < 10000
    assert speeds["max_film"] / speeds["periodic"] - 1 == pytest.approx(0.306, abs=0.02)
    assert speeds["seam_180"] / speeds["periodic"] - 1 == pytest.approx(0.479, abs=0.02)


def test_loss_factor_raises_the_onset_speed(cache, onsets):
    """η = 0.3 on the default convention: onset 13,536 rpm against 13,099 (+3.3 %)."""
    damped = onset_speed(BEARING, ROTOR, LOAD, (5000, 20000), grid=GRID, cache=cache,
                         options=FILE_OPTIONS, loss_factor=0.3)
    ratio = damped.onset_speed_rpm / onsets["seam_180"].onset_speed_rpm
    assert 1.02 < ratio < 1.05
    assert damped.conventions["loss_factor"] == 0.3


def test_stable_over_the_range_and_unstable_at_the_low_end_are_answers(cache):
    light = onset_speed(BEARING, Rotor(0.05), LOAD, (5000, 20000), grid=GRID, cache=cache,
                        options=FILE_OPTIONS)
    assert light.stable_over_range and math.isnan(light.onset_speed_rpm)
    assert light.smallest_margin > 0 and light.smallest_margin_speed_rpm == pytest.approx(20000)
    assert light.answer.startswith("stable over the whole range 5000–20000 rpm")
    assert light.evaluations == 8                      # ratio ≤ 1.25: 4^(1/7) = 1.219
    heavy = onset_speed(BEARING, ROTOR, LOAD, (20000, 40000), grid=GRID, cache=cache,
                        options=FILE_OPTIONS)
    assert heavy.unstable_at_lower_end and heavy.evaluations == 1
    assert heavy.answer.startswith("unstable already at 20000 rpm")


def test_load_defaults_to_the_rotor_weight(cache):
    r = stability(BEARING, ROTOR, OperatingPoint(45000), grid=GRID, cache=cache)
    assert r.load_newton == pytest.approx(2.0 * 9.80665, rel=1e-15)
    assert "M g" in r.conventions["load_source"]
    assert r.conventions["film"] == "seam" and r.conventions["seam_angle_deg"] == 180.0


def test_coefficients_in_si(cache):
    """K = K̄ p_a R²/c and C = C̄ p_a R²/(c ω) at f = γ ω/(2π); the matched whirl row is in the
    table; with η > 0 a zero frequency is refused (its hysteretic damping is unbounded)."""
    r = _run(cache, "seam_180", 45000)
    table = coefficient_table(r.linearisation, BEARING, 45000,
                              matched_whirl_ratio=r.threshold_whirl_ratio)
    assert tuple(table.table.columns[:9]) == COLUMNS
    omega = rpm_to_rad_per_s(45000)
    row = table.table.iloc[(table.table.whirl_ratio - 0.5).abs().argmin()]
    nd = coefficients(r.linearisation, [row.whirl_ratio])
    scale = 1e5 * 19.05e-3**2 / C
    assert row.kxy_N_per_m == pytest.approx(nd.stiffness[0, 0, 1] * scale, rel=1e-12)
    assert row.cyx_Ns_per_m == pytest.approx(nd.damping[0, 1, 0] * scale / omega, rel=1e-12)
    assert row.frequency_hz == pytest.approx(row.whirl_ratio * omega / (2 * math.pi))
    assert table.threshold_whirl_frequency_hz == pytest.approx(r.threshold_whirl_frequency_hz)
    assert (table.table.frequency_hz - table.threshold_whirl_frequency_hz).abs().min() < 1e-9
    with pytest.raises(ParameterError, match=r"^frequency_hz = 0.0: must be finite and > 0"):
        coefficient_table(r.linearisation, BEARING, 45000, [0.0, 100.0])


@pytest.mark.parametrize("kwargs, match", [
    (dict(loss_factor=-0.1), r"^loss_factor = -0.1: must be >= 0"),
    (dict(foil="rigid", loss_factor=0.2), r"^loss_factor = 0.2: must be 0 with foil='rigid'"),
    (dict(seam_angle_deg=360.0), r"^seam_angle_deg = 360.0: must lie in \[0, 360\) degrees"),
    (dict(seam_angle=3.0), r"^seam_angle = 3.0: is no longer accepted.*seam_angle_deg=171.887"),
    (dict(film="periodic", seam_angle_deg=57.0), r"^seam_angle_deg = 57.0: .*periodic film"),
])
def test_bad_options_are_refused_before_any_build(kwargs, match):
    cache = SolverCache(GRID)
    with pytest.raises(ParameterError, match=match):
        stability(BEARING, ROTOR, OperatingPoint(45000, LOAD), grid=GRID, cache=cache, **kwargs)
    assert len(cache) == 0


def test_bad_speed_range():
    with pytest.raises(ParameterError, match=r"^speed_range = \(2000, 1000\): must be increasing"):
        onset_speed(BEARING, ROTOR, LOAD, (2000, 1000))
    with pytest.raises(ParameterError, match=r"^speed_range low = -1.0: must be > 0"):
        onset_speed(BEARING, ROTOR, LOAD, (-1, 1000))


def test_load_beyond_capacity_says_so_with_the_largest_load():
    """2000 N at 45,000 rpm has no equilibrium (the film closes); the error names the largest
    load that converged by continuation (36 × 10: 1000 N; 72 × 20: 1609 N)."""
    grid = Grid(36, 10)
    with pytest.raises(LoadCapacityError, match=r"^load_newton = 2000.0: load exceeds the load "
                       r"capacity at this speed \(45000 rpm\): the largest load that converged "
                       r"is \d+ N"):
        stability(BEARING, ROTOR, OperatingPoint(45000, 2000.0), grid=grid,
                  options=ModelOptions())


@pytest.mark.slow
def test_ruscitto_answers_on_the_default_grid():
    """Paper resolution (144 × 36): the same answers within 1 % of the 72 × 20 values."""
    grid = Grid(144, 36)
    cache = SolverCache(grid)
    for name, (kwargs, mc45, _, speed, hz) in CONVENTIONS.items():
        r = stability(BEARING, ROTOR, OperatingPoint(45000, LOAD), grid=grid, cache=cache,
                      options=FILE_OPTIONS, **kwargs)
        assert r.critical_mass_parameter == pytest.approx(mc45, rel=0.01)
        o = onset_speed(BEARING, ROTOR, LOAD, (5000, 20000), grid=grid, cache=cache,
                        options=FILE_OPTIONS, **kwargs)
        assert o.onset_speed_rpm == pytest.approx(speed, rel=0.01)
        assert o.whirl_frequency_hz == pytest.approx(hz, rel=0.01)
