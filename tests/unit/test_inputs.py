"""Unit tests of the inputs and their conversions (gfbopt.parameters, gfbopt.bearing_file)."""
import math
from pathlib import Path

import pytest

from gfbopt import BearingGeometry, BearingModel, Grid, ParameterError
from gfbopt.inputs import load_bearing
from gfbopt.inputs.conversions import rpm_to_rad_per_s
from gfbopt.physics.bump import bump_compliance

REPO = Path(__file__).resolve().parents[2]
RUSCITTO_FILE = REPO / "problems" / "bearings" / "ruscitto.toml"

RUSCITTO = dict(radius=19.05e-3, length=38.1e-3, radial_clearance=20e-6,
                bump_pitch=4.572e-3, bump_half_length=1.778e-3, bump_thickness=101.6e-6,
                bump_youngs_modulus=214e9, top_foil_youngs_modulus=214e9, poisson_ratio=0.29,
                top_foil_thickness=101.6e-6, viscosity=2.98e-5, ambient_pressure=1e5)


def test_ruscitto_groups_match_hand_calculation():
    b = BearingGeometry(**RUSCITTO)
    # α = 2 s l0³ (1-ν²)/(E t³), worked by hand
    alpha = 2 * 4.572e-3 * 1.778e-3**3 * (1 - 0.29**2) / (214e9 * 101.6e-6**3)
    assert b.bump_compliance == pytest.approx(alpha, rel=1e-12)
    assert b.compliance == pytest.approx(1e5 * alpha / 20e-6, rel=1e-12)
    assert b.compliance == pytest.approx(1.05, abs=0.005)          # docs/PHYSICS.md: S ≈ 1.05
    omega = 45000 * 2 * math.pi / 60
    assert b.bearing_number(45000) == pytest.approx(
        6 * 2.98e-5 * omega * 19.05e-3**2 / (1e5 * 20e-6**2), rel=1e-12)
    assert b.bearing_number(45000) == pytest.approx(7.6, abs=0.05)  # docs/PHYSICS.md: Λ ≈ 7.6
    assert b.bearing_number(30000) == pytest.approx(5.1, abs=0.05)
    # C = E_t I_t c/(R⁴ L p_a), I_t = L t³/12 → C = E t³ c/(12 R⁴ p_a)
    assert b.top_foil_coefficient == pytest.approx(
        214e9 * 101.6e-6**3 * 20e-6 / (12 * 19.05e-3**4 * 1e5), rel=1e-12)
    assert b.length_ratio == pytest.approx(1.0)
    assert b.load_newton(b.nondimensional_load(100.0)) == pytest.approx(100.0, rel=1e-14)


def test_bearing_file_matches_reference_values():
    b = load_bearing(RUSCITTO_FILE)
    assert b == BearingGeometry(**RUSCITTO, name="Ruscitto et al. (1978)", options=b.options)
    assert b.options.film == "seam" and b.options.seam_angle_deg == 180.0   # its [model]


def test_rpm_conversion():
    assert rpm_to_rad_per_s(60.0) == pytest.approx(2 * math.pi)


@pytest.mark.parametrize("field, value, rule", [
    ("radius", 0.0, "must be >= 0.001 m"),
    ("length", -1.0, "must be >= 0.0001 m"),
    ("radial_clearance", -2e-5, "must be >= 1e-06 m"),
    ("radial_clearance", 1e-300, "must be >= 1e-06 m .below 1 µm"),
    ("bump_thickness", 5e-3, "must be < the half bump length"),
    ("bump_half_length", 3e-3, r"must satisfy 2 l0 <= s"),
    ("radial_clearance", 1e-3, "small against the radius"),
    ("viscosity", float("nan"), "finite"),
    ("poisson_ratio", 0.7, r"-1 < ν < 0.5"),
])
def test_bad_geometry_names_parameter_value_and_rule(field, value, rule):
    values = dict(RUSCITTO)
    values[field] = value
    with pytest.raises(ParameterError, match=rf"^{field} = .*{rule}"):
        BearingGeometry(**values)


@pytest.mark.parametrize("kwargs, match", [
    (dict(bearing_number=0.0), r"^bearing_number = 0.0: must be > 0"),
    (dict(bearing_number=1.0, compliance=-1.0), r"^compliance = -1.0: must be >= 0"),
    (dict(bearing_number=1.0, length_ratio=float("nan")), r"^length_ratio = nan: must be finite"),
    (dict(bearing_number=1.0, foil="elastic"), r"^foil = 'elastic': must be one of rigid"),
    (dict(bearing_number=1.0, film="open"), r"^film = 'open': must be one of periodic, seam"),
    (dict(bearing_number=1.0, foil="beam", deflection_law="local"), r"^deflection_law = 'local'"),
    (dict(bearing_number=1.0, subambient="cavitation"), r"^subambient = 'cavitation'"),
])
def test_bad_model_input(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        BearingModel(**kwargs)


@pytest.mark.parametrize("text, match", [
    ("7x20", r"grid n_theta = 7: must be >= 12"),
    ("72x3", r"grid n_z = 3: must be >= 4"),
    ("72x21", r"grid n_z = 21: must be even"),
    ("72-20", r"grid = '72-20': must be written NTHETAxNZ"),
    ("axb", r"must be written NTHETAxNZ"),
])
def test_bad_grid(text, match):
    with pytest.raises(ParameterError, match=match):
        Grid.parse(text)


def test_bad_bearing_files(tmp_path):
    missing = tmp_path / "missing.toml"
    missing.write_text("[bearing]\nradius = 0.02\n")
    with pytest.raises(ParameterError, match=r"missing.toml: bearing.length = None: is required"):
        load_bearing(missing)
    broken = tmp_path / "broken.toml"
    broken.write_text("[bearing\nradius = ")
    with pytest.raises(ParameterError, match=r"must be valid TOML"):
        load_bearing(broken)
    text = (RUSCITTO_FILE.read_text()
            .replace("radius = 19.05e-3", 'radius = "big"'))
    wrong = tmp_path / "wrong.toml"
    wrong.write_text(text)
    with pytest.raises(ParameterError, match=r"bearing.radius = 'big': must be a finite number"):
        load_bearing(wrong)
    with pytest.raises(ParameterError, match=r"must be an existing TOML file"):
        load_bearing(tmp_path / "nope.toml")


def test_bump_compliance_scales_as_monomial():
    base = bump_compliance(4e-3, 2e-3, 1e-4, 2e11, 0.3)
    assert bump_compliance(8e-3, 2e-3, 1e-4, 2e11, 0.3) == pytest.approx(2 * base)
    assert bump_compliance(4e-3, 4e-3, 1e-4, 2e11, 0.3) == pytest.approx(8 * base)
    assert bump_compliance(4e-3, 2e-3, 2e-4, 2e11, 0.3) == pytest.approx(base / 8)
