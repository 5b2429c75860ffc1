"""The least-stable mode is the least-damped root over all rigid-body roots.

Reference: every finite eigenvalue of the linearised semi-discrete system (pressure and foil
states + rigid rotor), from a dense generalised eigenvalue computation of the pencil (J, E) —
no shift, no impedance, no root finding.  On 0.2.0 ``least_stable_mode`` searched only near
the threshold whirl ratio: at 5,000 rpm (Ruscitto, 2 kg, 20 N) it reported the half-frequency
root (γ ≈ 0.49, log decrement 2.7 here) while a root at γ ≈ 2.9 has log decrement 1.1.

Grid 24 x 8 (246 states: the dense computation takes a second).  Tolerance 1e-8 relative: both
are eigenvalues of the same matrices, by shift-invert Arnoldi (tolerance 1e-12) and by QZ.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp

from gfbopt.inputs import Grid, load_bearing
from gfbopt.inputs.rotor import OperatingPoint, Rotor
from gfbopt.linear import least_stable_mode
from gfbopt.linear.least_stable import MODE_BAND, damping_ratio
from gfbopt.rotor import stability
from gfbopt.rotor.analysis import resolve_case, threshold_at

ROOT = Path(__file__).resolve().parents[2]
BEARING = load_bearing(ROOT / "problems" / "bearings" / "ruscitto.toml")
GRID = Grid(24, 8)


def dense_roots(lin, mass: float) -> np.ndarray:
    """Every finite eigenvalue s of s E v = J v with whirl ratio |Im s| in MODE_BAND; with
    structural damping each half plane with its own foundation (sign of Im s)."""
    m = mass * lin.load
    n = lin.size
    roots = []
    for sign in ((1, -1) if lin.loss_factor > 0 else (1,)):
        a, b = lin.system(sign * 1j)
        jac = sp.bmat([[-a, sp.csc_matrix(-lin.c_xi), sp.csc_matrix((n, 2))],
                       [sp.csc_matrix((2, n)), None, sp.identity(2)],
                       [sp.csc_matrix(lin.force), sp.csc_matrix((2, 2)), None]]).toarray()
        e = sp.block_diag([b, sp.identity(2), m * sp.identity(2)]).toarray()
        w = sla.eig(jac, e, right=False)
        w = w[np.isfinite(w) & (np.abs(w) < 1e6)]
        roots += list(w[(np.sign(w.imag) == sign) & (np.abs(w.imag) > MODE_BAND[0])
                        & (np.abs(w.imag) <= MODE_BAND[1])])
    return np.array(roots)


@pytest.mark.parametrize("speed_rpm, loss_factor", [(5000, 0.0), (15000, 0.0), (45000, 0.0),
                                                   (5000, 0.3)])
def test_least_stable_mode_is_the_least_damped_of_all_roots(speed_rpm, loss_factor):
    case = resolve_case(BEARING, Rotor(2.0), 20.0, grid=GRID, loss_factor=loss_factor)
    _, lin, thr = threshold_at(case, speed_rpm)
    mass = case.mass_parameter(speed_rpm)
    roots = dense_roots(lin, mass)
    expected = min(roots, key=damping_ratio)
    mode = least_stable_mode(lin, mass, thr)
    assert mode.real == pytest.approx(expected.real, rel=1e-8, abs=1e-10)
    assert mode.imag == pytest.approx(abs(expected.imag), rel=1e-8)
    # no root of the dense spectrum is less damped than the one reported
    assert damping_ratio(mode) <= min(damping_ratio(r) for r in roots) + 1e-10


def test_low_speed_reports_the_high_frequency_root():
    """The defect as reported: at 5,000 rpm the least-damped root whirls well above the
    threshold whirl ratio (≈ 0.45), and the SI result reports its log decrement."""
    result = stability(BEARING, Rotor(2.0), OperatingPoint(5000, 20.0), grid=GRID)
    assert result.stable
    assert result.mode_whirl_ratio > 2.0 > 1.0 > result.threshold_whirl_ratio
    delta = -2 * math.pi * result.growth_rate / result.mode_whirl_ratio
    assert result.log_decrement == pytest.approx(delta, rel=1e-12)
    case = resolve_case(BEARING, Rotor(2.0), 20.0, grid=GRID)
    _, lin, _ = threshold_at(case, 5000)
    half = [r for r in dense_roots(lin, case.mass_parameter(5000)) if abs(r.imag) < 1.0]
    half_delta = min(-2 * math.pi * r.real / r.imag for r in half)
    assert result.log_decrement < half_delta       # the half-frequency root is more damped


SLOW = pytest.mark.slow          # a new static build each (~5-15 s under load): two by default


@pytest.mark.parametrize("model, load, speed_rpm", [
    ('film = "periodic"', 20.0, 30000),
    pytest.param('foil = "beam"', 20.0, 15000, marks=SLOW),
    pytest.param('deflection_law = "local"', 50.0, 10000, marks=SLOW),
    ('film = "seam"\nseam_angle_deg = 90.0', 20.0, 45000),
    pytest.param('foil = "rigid"', 10.0, 20000, marks=SLOW),
    pytest.param("loss_factor = 0.2", 80.0, 8000, marks=SLOW)])
def test_krylov_search_equals_the_dense_spectrum_and_the_reference(model, load, speed_rpm,
                                                                   tmp_path):
    """The default search (one LU and one Krylov space, roots of its reduced model) gives the
    least-damped root of the dense spectrum and of the reference search (three shift-invert
    Arnoldi searches of the full system) over other films, foils, laws and loads: the same
    eigenvalue, so 1e-8 relative as above."""
    text = (ROOT / "problems" / "bearings" / "ruscitto.toml").read_text().split("[model]")[0]
    path = tmp_path / "bearing.toml"
    path.write_text(text + f"[model]\n{model}\n")
    case = resolve_case(load_bearing(path), Rotor(2.0), load, grid=GRID)
    _, lin, thr = threshold_at(case, speed_rpm)
    mass = case.mass_parameter(speed_rpm)
    expected = min(dense_roots(lin, mass), key=damping_ratio)
    for method in ("krylov", "eigs"):
        mode = least_stable_mode(lin, mass, thr, method=method)
        assert mode.real == pytest.approx(expected.real, rel=1e-8, abs=1e-10), method
        assert mode.imag == pytest.approx(abs(expected.imag), rel=1e-8), method
