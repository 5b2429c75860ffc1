"""SI inputs of the stability analysis: conversions, rotor and operating point, model options
(film conventions and their default), the bearing file's [model] table."""
import math
from pathlib import Path

import pytest

from gfbopt import BearingModel, ParameterError
from gfbopt.inputs import (MAX_FILM, ModelOptions, OperatingPoint, Rotor, load_bearing,
                           load_bearing_file, resolve_model_options)
from gfbopt.inputs import conversions as cv
from gfbopt.inputs.options import DEFAULT_SEAM_ANGLE_DEG

RUSCITTO_FILE = Path(__file__).resolve().parents[2] / "problems" / "bearings" / "ruscitto.toml"

OMEGA_45K = 45000 * 2 * math.pi / 60


def test_mass_parameter_worked_example_and_round_trip():
    """docs/PHYSICS.md §2: 2 kg per bearing, c = 20 µm, 20 N, 45,000 rpm gives M̄ = 44.4 (and 2.19
    at 10,000 rpm); kg → M̄ → kg is the identity to round-off."""
    mbar = cv.mass_parameter(2.0, 20e-6, OMEGA_45K, 20.0)
    assert mbar == pytest.approx(2 * 20e-6 * OMEGA_45K**2 / 20, rel=1e-15)
    assert mbar == pytest.approx(44.4, abs=0.05)
    assert cv.mass_parameter(2.0, 20e-6, cv.rpm_to_rad_per_s(10000), 20.0) == pytest.approx(
        2.19, abs=0.005)
    assert cv.mass_from_parameter(mbar, 20e-6, OMEGA_45K, 20.0) == pytest.approx(2.0, rel=1e-14)


def test_dynamic_scales_and_mode_quantities():
    """docs/PHYSICS.md §2: p_a R²/(c ω) = 385 N s/m at 45,000 rpm for the Ruscitto bearing; the
    whirl ratio ↔ frequency, growth rate and log decrement conversions."""
    assert cv.damping_scale(1e5, 19.05e-3, 20e-6, OMEGA_45K) == pytest.approx(385, abs=0.5)
    assert cv.damping_scale(1e5, 19.05e-3, 20e-6, OMEGA_45K) * OMEGA_45K == pytest.approx(
        cv.stiffness_scale(1e5, 19.05e-3, 20e-6), rel=1e-14)
    f = cv.whirl_frequency_hz(0.5, OMEGA_45K)
    assert f == pytest.approx(375.0, rel=1e-12)                 # half of 750 Hz
    assert cv.whirl_ratio_from_frequency(f, OMEGA_45K) == pytest.approx(0.5, rel=1e-14)
    assert cv.growth_rate_per_second(0.01, OMEGA_45K) == pytest.approx(47.124, rel=1e-4)
    # δ = −2πσ/γ: one whirl period at γ multiplies the amplitude by exp(2πσ/γ)
    assert cv.logarithmic_decrement(-0.01, 0.5) == pytest.approx(0.04 * math.pi, rel=1e-14)
    assert cv.film_thickness_um(0.75, 20e-6) == pytest.approx(15.0, rel=1e-14)
    assert cv.rotor_weight_newton(2.0) == pytest.approx(19.6133, rel=1e-12)


def test_rotor_and_operating_point():
    rotor = Rotor(2.0)
    point = OperatingPoint(45000.0)
    assert point.load_on(rotor) == pytest.approx(2.0 * 9.80665, rel=1e-15)
    assert "M g" in point.load_source()
    assert OperatingPoint(45000.0, 20.0).load_on(rotor) == 20.0


@pytest.mark.parametrize("make, match", [
    (lambda: Rotor(0.0), r"^mass_kg = 0.0: must be > 0"),
    (lambda: Rotor(-2.0), r"^mass_kg = -2.0: must be > 0"),
    (lambda: Rotor(float("nan")), r"^mass_kg = nan: must be finite"),
    (lambda: OperatingPoint(0.0, 20.0), r"^speed_rpm = 0.0: must be > 0"),
    (lambda: OperatingPoint(1000.0, -5.0), r"^load_newton = -5.0: must be > 0"),
    (lambda: OperatingPoint(1000.0, 0.0), r"^load_newton = 0.0: must be > 0"),
])
def test_bad_rotor_input(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


@pytest.mark.parametrize("kwargs, match", [
    (dict(bearing_number=2.0, compliance=1.0, loss_factor=-0.1),
     r"^loss_factor = -0.1: must be >= 0"),
    (dict(bearing_number=2.0, compliance=1.0, loss_factor=20.0),
     r"^loss_factor = 20.0: must be <= 1 \(a fraction"),
    (dict(bearing_number=2.0, foil="rigid", loss_factor=0.2),
     r"^loss_factor = 0.2: must be 0 with foil='rigid'"),
    (dict(bearing_number=2.0, compliance=0.0, loss_factor=0.2),
     r"^loss_factor = 0.2: must be 0 when the compliance S = 0"),
    (dict(bearing_number=2.0, compliance=1.0, loss_factor=float("nan")),
     r"^loss_factor = nan: must be finite"),
])
def test_bad_loss_factor(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        BearingModel(**kwargs)


def test_loss_factor_is_an_option_stated_in_every_output():
    model = BearingModel(bearing_number=2.0, compliance=1.0, loss_factor=0.3)
    assert model.options()["loss_factor"] == 0.3
    assert BearingModel(bearing_number=2.0).loss_factor == 0.0
    assert "film_convention" in model.options()


def test_default_film_convention_is_a_seam_opposite_the_load():
    """The default a foil-bearing user gets: a seam fixed in the housing, welded end 180° from
    the load (docstring of resolve_model_options); a rigid bearing gets the periodic film."""
    options = resolve_model_options()
    assert options.film == "seam" and options.seam_angle_deg == DEFAULT_SEAM_ANGLE_DEG == 180.0
    assert (options.foil, options.deflection_law, options.loss_factor) == ("simple", "mean", 0.0)
    assert options.to_dict()["seam_angle_deg"] == 180.0
    assert "fixed housing angle" in options.convention()
    assert resolve_model_options(ModelOptions(foil="rigid")).film == "periodic"
    stated = ModelOptions(film="seam", seam_angle_deg=MAX_FILM, loss_factor=0.2)
    assert resolve_model_options(stated).seam_angle_deg == MAX_FILM       # never overridden
    assert "maximum-film line" in resolve_model_options(stated).convention()
    kwargs = resolve_model_options(stated).model_kwargs()
    assert kwargs["seam_angle_deg"] is None and kwargs["loss_factor"] == 0.2


@pytest.mark.parametrize("options, match", [
    (ModelOptions(film="periodic", seam_angle_deg=90.0),
     r"^seam_angle_deg = 90.0: is not used with a periodic film"),
    (ModelOptions(film="periodic", seam_angle_deg=MAX_FILM), r"'max_film' needs film = 'seam'"),
])
def test_contradictory_options_are_refused(options, match):
    with pytest.raises(ParameterError, match=match):
        resolve_model_options(options)


@pytest.mark.parametrize("kwargs, match", [
    (dict(seam_angle_deg=360.0), r"^seam_angle_deg = 360.0: must lie in \[0, 360\) degrees"),
    (dict(seam_angle_deg=-0.1), r"^seam_angle_deg = -0.1: must lie in \[0, 360\)"),
    (dict(seam_angle=3.0), r"^seam_angle = 3.0: is no longer accepted.*seam_angle_deg=171.887"),
    (dict(film="open"), r"^film = 'open': must be one of periodic, seam"),
    (dict(loss_factor=-1.0), r"^loss_factor = -1.0: must be >= 0"),
])
def test_bad_model_options(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        ModelOptions(**kwargs)


def test_ruscitto_file_states_its_conventions():
    geometry, options = load_bearing_file(RUSCITTO_FILE)
    assert geometry == load_bearing(RUSCITTO_FILE)
    assert options == ModelOptions(film="seam", seam_angle_deg=180.0, foil="simple",
                                   deflection_law="mean", loss_factor=0.0)


def _file(tmp_path, model_table: str):
    text = RUSCITTO_FILE.read_text().split("[model]")[0] + model_table
    path = tmp_path / "b.toml"
    path.write_text(text)
    return path


def test_bearing_file_without_model_table_gets_the_default(tmp_path):
    _, options = load_bearing_file(_file(tmp_path, ""))
    assert options == ModelOptions()
    assert resolve_model_options(options).seam_angle_deg == 180.0


def test_bearing_file_model_table_max_film_and_degrees(tmp_path):
    _, options = load_bearing_file(_file(tmp_path, '[model]\nseam_angle_deg = "max_film"\n'))
    assert options.seam_angle_deg == MAX_FILM and options.film is None
    _, options = load_bearing_file(_file(tmp_path, "[model]\nseam_angle_deg = 90\n"
                                                   "loss_factor = 0.25\n"))
    assert options.seam_angle_deg == 90.0 and options.loss_factor == 0.25


@pytest.mark.parametrize("table, match", [
    ("[model]\nseam_angle_deg = 360.0\n", r"b.toml: model.seam_angle_deg = 360.0: must lie in "
                                          r"\[0, 360\) degrees"),
    ("[model]\nseam_angle_deg = \"north\"\n", r"seam_angle_deg = 'north': must be degrees in \[0, 360\)"),
    ("[model]\nloss_factor = -0.2\n", r"b.toml: model.loss_factor = -0.2: must be >= 0"),
    ("[model]\nfilm = \"open\"\n", r"b.toml: model.film = 'open': must be one of"),
    ("[model]\ngrid = \"72x20\"\n", r"b.toml: model.grid = '72x20': is not a key of \[model\]"),
])
def test_bad_model_table(tmp_path, table, match):
    with pytest.raises(ParameterError, match=match):
        load_bearing_file(_file(tmp_path, table))
