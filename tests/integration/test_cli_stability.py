"""The ``gfbopt stability`` command and ``--loss-factor``: JSON and CSV contracts, the
cross-check of the SI answer against ``gfbopt linear``'s non-dimensional critical mass, the
conventions in every output, and bad input (one line, exit 2, before any solve)."""
import json
import math
import subprocess
from pathlib import Path

import pytest

from gfbopt.glossary import describe

from cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
RUSCITTO = "problems/bearings/ruscitto.toml"
POINT = ["--bearing", RUSCITTO, "--load-newton", "20", "--speed-rpm", "45000", "--grid",
         "72x20"]


def gfbopt(*args: str) -> subprocess.CompletedProcess:
    # in this process (tests/cli_inprocess.py: same main, exit status and output)
    return run_cli(*args, cwd=REPO)


def _json(*args: str) -> dict:
    out = gfbopt(*args, "--json")
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def test_stability_json_and_csv_contract(tmp_path):
    csv = tmp_path / "kc.csv"
    data = _json("stability", *POINT, "--rotor-mass-kg", "2", "--csv", str(csv))
    for key in ("stable", "verdict", "critical_mass_kg", "mass_margin", "whirl_frequency_hz",
                "growth_rate_per_s", "log_decrement", "eccentricity", "attitude_angle_deg",
                "min_film_thickness_um", "bearing_number", "mass",
                "critical_mass", "threshold_whirl_frequency_hz", "conventions",
                "coefficients", "success", "message", "wall_time_s", "provenance"):
        assert key in data, key
    assert data["stable"] is False and data["verdict"] == "unstable" and data["success"]
    conventions = data["conventions"]
    assert conventions["film"] == "seam" and conventions["seam_angle_deg"] == 180.0
    assert "welded end 180°" in conventions["film_convention"]
    assert data["provenance"]["options"]["film_convention"] == conventions["film_convention"]
    lines = csv.read_text().splitlines()
    # the glossary's names with their units, as in the shipped results/*/coefficients CSVs
    assert lines[0] == ("frequency_hz,kxx_N_per_m,kxy_N_per_m,kyx_N_per_m,kyy_N_per_m,"
                        "cxx_Ns_per_m,cxy_Ns_per_m,cyx_Ns_per_m,cyy_Ns_per_m")
    assert [describe(c)[0] for c in lines[0].split(",")] == ["Hz", *["N/m"] * 4,
                                                              *["N s/m"] * 4]
    assert data["coefficients"]["units"]["kxy_N_per_m"] == "N/m"
    assert len(lines) == 1 + len(data["coefficients"]["frequency_hz"]) == 12   # 10 + matched
    assert "matched whirl" in data["coefficients"]["frame"]


def test_si_answer_equals_the_nondimensional_path():
    """``gfbopt linear`` (same file, same conventions) gives M̄c; M = M̄c W0/(c ω²) must be
    ``gfbopt stability``'s critical mass in kg, and the rotor given as M̄ = M c ω²/W0 = 44.41
    must be the same 2 kg rotor with the same answer."""
    linear = _json("linear", *POINT)
    stab = _json("stability", *POINT, "--rotor-mass-kg", "2")
    omega = 45000 * 2 * math.pi / 60
    assert linear["film"] == "seam" and linear["seam_angle_deg"] == 180.0
    assert stab["critical_mass_kg"] == pytest.approx(
        linear["critical_mass"] * 20.0 / (20e-6 * omega**2), rel=1e-9)
    mbar = 2.0 * 20e-6 * omega**2 / 20.0
    assert stab["mass"] == pytest.approx(mbar, rel=1e-12)
    by_mbar = _json("stability", *POINT, "--mass", repr(mbar))
    assert by_mbar["rotor_mass_kg"] == pytest.approx(2.0, rel=1e-12)
    assert by_mbar["critical_mass_kg"] == pytest.approx(stab["critical_mass_kg"], rel=1e-9)


def test_onset_from_the_command_line():
    data = _json("stability", "--bearing", RUSCITTO, "--rotor-mass-kg", "2", "--load-newton",
                 "20", "--speed-range", "5000", "20000", "--grid", "72x20")
    assert data["onset_speed_rpm"] == pytest.approx(13098.5, rel=5e-3)
    assert data["onset"]["answer"].startswith("onset of whirl at 13")
    assert data["critical_mass_kg"] is None        # no --speed-rpm: the onset only (null)


def test_text_report_states_the_default_convention(tmp_path):
    """A bearing file without a [model] table gets the default (a seam 180° from the load),
    and the text output says so; so does ``gfbopt static`` with that file."""
    plain = tmp_path / "plain.toml"
    plain.write_text((REPO / RUSCITTO).read_text().split("[model]")[0])
    out = gfbopt("stability", "--bearing", str(plain), "--rotor-mass-kg", "0.1",
                 "--load-newton", "20", "--speed-rpm", "10000", "--grid", "36x10")
    assert out.returncode == 0, out.stderr
    assert "seam at a fixed housing angle: top-foil welded end 180°" in out.stdout
    assert "verdict: STABLE" in out.stdout
    static = json.loads(gfbopt("static", "--bearing", str(plain), "--speed-rpm", "10000",
                               "--load-newton", "20", "--grid", "36x10", "--json").stdout)
    assert static["film"] == "seam" and static["seam_angle_deg"] == 180.0
    periodic = json.loads(gfbopt("static", "--bearing", RUSCITTO, "--speed-rpm", "10000",
                                 "--load-newton", "20", "--grid", "36x10", "--film",
                                 "periodic", "--json").stdout)
    assert periodic["film"] == "periodic" and periodic["seam_angle_deg"] is None   # no seam


def test_linear_loss_factor():
    base = ["linear", "--eccentricity", "0.4", "--bearing-number", "2", "--compliance", "1",
            "--whirl-ratio", "0", "0.5", "--grid", "36x10"]
    undamped, damped = _json(*base), _json(*base, "--loss-factor", "0.3")
    assert undamped["loss_factor"] == 0.0 and damped["loss_factor"] == 0.3
    assert damped["critical_mass"] > 1.05 * undamped["critical_mass"]
    assert damped["damping"]["0"] == [[None, None], [None, None]]    # unbounded at γ = 0
    for row, expected in zip(damped["stiffness"]["0"], undamped["stiffness"]["0"]):
        assert row == pytest.approx(expected, rel=1e-10)


def test_a_damped_bearing_file_reaches_the_transient_with_its_loss_factor(tmp_path):
    """η from a bearing file acts in the transient too (Kelvin–Voigt foil state) and the
    output states it with the reference whirl ratio it used."""
    damped = tmp_path / "damped.toml"
    damped.write_text((REPO / RUSCITTO).read_text().replace("loss_factor = 0.0",
                                                            "loss_factor = 0.2"))
    out = gfbopt("orbit", "--bearing", str(damped), "--speed-rpm", "20000", "--load-newton",
                 "20", "--rotor-mass-kg", "0.23", "--revolutions", "1", "--grid", "24x8",  # M̄ ≈ 1
                 "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["loss_factor"] == pytest.approx(0.2)
    assert 0.0 < data["reference_whirl_ratio"] < 1.0


@pytest.mark.parametrize("args, message", [
    (["--rotor-mass-kg", "0"], "--rotor-mass-kg = 0.0: must be > 0"),
    (["--rotor-mass-kg", "-2"], "--rotor-mass-kg = -2.0: must be > 0"),
    (["--rotor-mass-kg", "2", "--load-newton", "0"], "--load-newton = 0.0: must be > 0"),
    (["--rotor-mass-kg", "2", "--loss-factor", "-0.1"], "--loss-factor = -0.1: must be >= 0"),
    (["--rotor-mass-kg", "2", "--seam-angle", "360"],
     "--seam-angle = 360.0: must lie in [0, 360) degrees"),
    (["--rotor-mass-kg", "2", "--seam-angle", "-5"], "--seam-angle = -5.0: must lie in [0, 360)"),
    (["--rotor-mass-kg", "2", "--mass", "3"], "--mass = 3.0: contradicts --rotor-mass-kg"),
    (["--mass", "3"], "--mass = 3.0: needs --load-newton and --speed-rpm"),
    ([], "--rotor-mass-kg (not given): is required"),
    (["--rotor-mass-kg", "2", "--speed-range", "3000", "1000"],
     "--speed-range = [3000.0, 1000.0]: must be two speeds 0 < LOW < HIGH"),
    (["--rotor-mass-kg", "2", "--foil", "rigid", "--loss-factor", "0.2"],
     "--loss-factor = 0.2: must be 0 with foil='rigid'"),
    (["--rotor-mass-kg", "2", "--film", "periodic", "--seam-angle", "90"],
     "--seam-angle = 90.0: is not used with a periodic film"),
    (["--rotor-mass-kg", "2", "--seam-angle", "north"], "must be a number of degrees"),
])
def test_bad_stability_input_is_one_line_exit_2(args, message):
    out = gfbopt("stability", "--bearing", RUSCITTO, "--speed-rpm", "45000", *args)
    assert out.returncode == 2, out.stdout
    assert "Traceback" not in out.stderr and len(out.stderr.strip().splitlines()) == 1
    assert message in out.stderr


def test_load_beyond_capacity_is_one_line_exit_2():
    out = gfbopt("stability", "--bearing", RUSCITTO, "--rotor-mass-kg", "2", "--load-newton",
                 "2000", "--speed-rpm", "45000", "--grid", "36x10")
    assert out.returncode == 2 and len(out.stderr.strip().splitlines()) == 1
    assert "load exceeds the load capacity at this speed (45000 rpm): the largest load that " \
           "converged is" in out.stderr
