"""Rotors no machine can be are refused before any solve, as a bearing's c/R > 0.01 is: one
line naming the file, the key, the value and the rule, exit 2.

Before, positions in millimetres (``position = -40``, ``80``) gave "stable over the range,
whirl 495.7 Hz" with exit 0, side loads cancelling the weight left 1e-15 N bearing loads that
were analysed, and an imbalance displacing the mass centre beyond the clearance was answered.
"""
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs.rotor_limits import (MAX_REACH_DIAMETERS, MAX_RADIUS_DIAMETERS,
                                        MIN_LOAD_RATIO)
from gfbopt.inputs.rotor_system import load_rotor
from tests.cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]
BEARING = (ROOT / "problems" / "bearings" / "ruscitto.toml").as_posix()
D = 2 * 19.05e-3                               # the Ruscitto journal diameter [m]


def _rotor(tmp_path, rotor="", a=-0.035, b=0.065, extra=""):
    text = (f"[rotor]\nmass = 3.2\ntransverse_inertia = 0.012\npolar_inertia = 0.002\n{rotor}"
            f'[[bearings]]\nfile = "{BEARING}"\nposition = {a!r}\n'
            f'[[bearings]]\nfile = "{BEARING}"\nposition = {b!r}\n{extra}')
    path = tmp_path / "r.toml"
    path.write_text(text)
    return path


def test_the_example_rotor_is_within_every_limit(tmp_path):
    system = load_rotor(_rotor(tmp_path))
    (ax, ay), (bx, by) = system.static_shares()
    # force and moment balance: 3.2 kg, CG 35 / 65 mm from the bearings
    assert ax == pytest.approx(3.2 * 9.80665 * 0.065 / 0.1) and ay == 0.0
    assert bx == pytest.approx(3.2 * 9.80665 * 0.035 / 0.1) and by == 0.0


@pytest.mark.parametrize("a,b,key", [(-40, 80, "bearings[1].position"),
                                     (-0.035, 65.0, "bearings[2].position"),
                                     (-1e200, 1e200, "bearings[1].position"),
                                     (-0.96, 0.96, "bearings[2].position"),
                                     (0.0, 0.02, "bearings[2].position")])
def test_positions_that_are_no_rotor_are_refused(tmp_path, a, b, key):
    path = _rotor(tmp_path, a=a, b=b)
    with pytest.raises(ParameterError) as exc:
        load_rotor(path)
    assert exc.value.name == f"{path}: {key}"
    # the span rule (0.96 m = 25 D each side but 50.4 D between), overlap (20 mm < L = 38 mm)
    assert ("journal diameters" in exc.value.rule or "overlap" in exc.value.rule)


def test_a_span_just_inside_the_limit_is_accepted(tmp_path):
    half = 0.49 * MAX_REACH_DIAMETERS * D
    load_rotor(_rotor(tmp_path, a=-half, b=half))


@pytest.mark.parametrize("key,value", [("transverse_inertia", 120.0),      # kg cm²
                                       ("transverse_inertia", 1e308),
                                       ("polar_inertia", 1.0)])
def test_inertias_beyond_the_mass_and_reach_are_refused(tmp_path, key, value):
    path = _rotor(tmp_path)
    text = path.read_text().replace(f"{key} = ", f"{key} = {value!r}\n#", 1)
    if key == "polar_inertia":
        text = text.replace("transverse_inertia = 0.012", "transverse_inertia = 1.0")
    path.write_text(text)
    with pytest.raises(ParameterError, match=rf"rotor\.{key} = .*must be <= m") as exc:
        load_rotor(path)
    limit = 3.2 * ((MAX_REACH_DIAMETERS * D) ** 2 + 0.5 * (MAX_RADIUS_DIAMETERS * D) ** 2)
    if key == "transverse_inertia":
        assert f"{limit:.4g}" in exc.value.rule


def test_side_loads_that_cancel_the_weight_leave_the_rotor_unloaded(tmp_path):
    weight = 3.2 * 9.80665
    path = _rotor(tmp_path, extra=f"[[side_loads]]\nforce = {weight!r}\ndirection_deg = 180.0\n")
    with pytest.raises(ParameterError, match="unloaded") as exc:
        load_rotor(path)
    assert exc.value.name == f"{path}: bearing A load" and exc.value.value < 1e-9
    assert f"{MIN_LOAD_RATIO:g} p_a R²" in exc.value.rule


def test_a_huge_mass_is_refused_even_without_gravity(tmp_path):
    for rotor in ("", "gravity = 0.0\n[[side_loads]]\nforce = 10.0\ndirection_deg = 0.0\n"):
        path = _rotor(tmp_path, rotor=rotor)
        path.write_text(path.read_text().replace("mass = 3.2", "mass = 1e308"))
        with pytest.raises(ParameterError, match=r"rotor\.mass = 1e\+308: weighs"):
            load_rotor(path)


def test_an_imbalance_displacing_the_mass_centre_beyond_the_clearance_is_refused(tmp_path):
    # 64 g mm on 3.2 kg is a 20 µm offset: the clearance; 65 g mm is beyond it
    ok = "[[imbalance]]\namount_g_mm = 64.0\nposition = 0.065\n"
    load_rotor(_rotor(tmp_path, extra=ok))
    path = _rotor(tmp_path, extra=ok.replace("64.0", "65.0"))
    with pytest.raises(ParameterError, match=r"imbalance\[1\]\.amount_kg_m = 6\.5e-05: .*"
                       r"20\.31 µm, more than the clearance 20 µm"):
        load_rotor(path)


def test_the_command_line_refuses_a_rotor_in_millimetres_before_any_solve(tmp_path):
    out = run_cli("rotor", str(_rotor(tmp_path, a=-40, b=80)), "--speed-range", "5000",
                  "30000", "--grid", "12x4")
    assert out.returncode == 2 and out.stdout == ""
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "bearings[1].position = -40" in lines[0]
    assert "50 journal diameters" in lines[0]


@pytest.mark.parametrize("table, key", [("rotor", "gravity_direction_deg"),
                                        ("side_loads", "direction_deg"),
                                        ("imbalance", "phase_deg")])
def test_directions_beyond_a_turn_are_refused(tmp_path, table, key):
    extra = {"rotor": "", "side_loads": "[[side_loads]]\nforce = 5.0\ndirection_deg = 1e300\n",
             "imbalance": "[[imbalance]]\namount_g_mm = 2.0\nphase_deg = 1e300\n"
                          "position = 0.065\n"}[table]
    rotor = "gravity_direction_deg = 1e300\n" if table == "rotor" else ""
    path = _rotor(tmp_path, rotor=rotor, extra=extra)
    with pytest.raises(ParameterError, match=rf"{key} = 1e\+300: must be <= 360 deg "
                       r"\(a direction: \[-360, 360\] degrees"):
        load_rotor(path)
    load_rotor(_rotor(tmp_path, rotor=rotor.replace("1e300", "-90.0"),
                      extra=extra.replace("1e300", "-90.0")))


def test_speeds_no_journal_can_run_at_are_refused(tmp_path):
    from gfbopt.inputs.rotor_limits import MAX_SURFACE_SPEED, check_rotor_speeds

    system = load_rotor(_rotor(tmp_path))
    assert check_rotor_speeds(system, (5000, 30000)) == (5000.0, 30000.0)
    fastest = MAX_SURFACE_SPEED / 19.05e-3 * 30 / 3.141592653589793
    assert check_rotor_speeds(system, (100.0, 0.999 * fastest))[1] < fastest
    with pytest.raises(ParameterError, match=r"--speed-range = \[1000.0, 1e\+300\]: .*"
                       r"at most 501275 rpm"):
        check_rotor_speeds(system, (1000.0, 1e300))
    with pytest.raises(ParameterError, match="must be > 0"):
        check_rotor_speeds(system, (0.0, 1000.0))
    with pytest.raises(ParameterError, match=r"1e-300 rpm gives bearing A a bearing number "
                       r"Λ = 1\.7e-304, below 1e-06"):
        check_rotor_speeds(system, (1e-300, 1000.0))


def test_a_bearing_load_no_gas_bearing_carries_is_refused():
    """``static --load-newton 1e308`` ran IPOPT to "Restoration_Failed" (exit 1); the
    stability route turned a 1e308 kg rotor into an infinite load."""
    from gfbopt.inputs import load_bearing
    from gfbopt.inputs.rotor import Rotor

    bearing = load_bearing(ROOT / "problems" / "bearings" / "ruscitto.toml")
    ceiling = 100 * 1e5 * 38.1e-3 * 38.1e-3
    assert bearing.nondimensional_load(0.99 * ceiling) == pytest.approx(
        0.99 * ceiling / (1e5 * 19.05e-3 ** 2))
    with pytest.raises(ParameterError, match=r"load_newton = 1e\+308: must be <= 100 p_a L D "
                       r"= 1\.452e\+04 N"):
        bearing.nondimensional_load(1e308)
    with pytest.raises(ParameterError, match=r"load_newton = 1e-300: must be >= 0\.0001 p_a "
                       r"R² = 0\.00363 N: below it the bearing is unloaded"):
        bearing.nondimensional_load(1e-300)
    with pytest.raises(ParameterError, match=r"mass_kg = 1e\+308: must weigh a finite"):
        Rotor(1e308)
    out = run_cli("static", "--bearing", ROOT / "problems" / "bearings" / "ruscitto.toml",
                  "--speed-rpm", "30000", "--load-newton", "1e308", "--grid", "12x4")
    assert out.returncode == 2 and out.stdout == "" and "100 p_a L D" in out.stderr
