"""The command-line contract: JSON keys, exit codes, one-line errors, studies."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

from cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]


def gfbopt(*args: str) -> subprocess.CompletedProcess:
    """The command run in this process (tests/cli_inprocess.py: same ``main``, same exit
    status and output, no interpreter start per call); the entry point ``python -m gfbopt``
    has its own subprocess tests below (version, provenance, bad input)."""
    return run_cli(*args, cwd=REPO)


def gfbopt_process(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "gfbopt", *args], capture_output=True,
                          text=True, cwd=REPO, timeout=300)


def test_static_json_contract():
    out = gfbopt("static", "--eccentricity", "0.6", "--bearing-number", "3",
                 "--compliance", "0", "--length-ratio", "1", "--grid", "72x20", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    for key in ("load", "attitude_angle_deg", "eccentricity", "min_film", "min_film_angle_deg",
                "success", "iterations", "solve_time_s"):
        assert key in data
    assert data["success"] is True
    assert data["load"] == pytest.approx(2.8631, rel=0.015)            # Yang et al.
    assert data["attitude_angle_deg"] == pytest.approx(30.04, abs=0.5)
    assert data["min_film"] == pytest.approx(0.4, abs=1e-3)


def test_static_load_and_beam_options():
    out = gfbopt("static", "--load", "0.9", "--bearing-number", "5", "--compliance", "1",
                 "--length-ratio", "1", "--foil", "beam", "--top-foil-coefficient", "1",
                 "--film", "seam", "--grid", "36x10", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["load"] == pytest.approx(0.9, rel=1e-9)
    assert data["foil"] == "beam" and data["film"] == "seam"


def test_dimensional_static():
    out = gfbopt("static", "--bearing", "problems/bearings/ruscitto.toml", "--speed-rpm",
                 "45000", "--load-newton", "50", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert "min_film_thickness_um" in data and "eccentricity" in data
    assert data["min_film_thickness_um"] == pytest.approx(data["min_film"] * 20.0, rel=1e-12)
    assert data["load_newton"] == pytest.approx(50.0, rel=1e-9)


def test_version_and_provenance_in_every_json_output():
    out = gfbopt_process("--version")
    assert out.returncode == 0 and out.stdout.startswith("gfbopt ")
    version = out.stdout.split()[1]
    data = json.loads(gfbopt_process("static", "--eccentricity", "0.5", "--bearing-number", "1",
                             "--compliance", "1", "--film", "seam", "--grid", "36x10",
                             "--json").stdout)
    prov = data["provenance"]
    assert prov["gfbopt_version"] == version
    assert len(prov["source_commit"]) == 40 and isinstance(prov["source_dirty"], bool)
    assert prov["options"]["film"] == "seam" and prov["options"]["foil_law"] == "simple"
    assert prov["options"]["grid"] == "36x10" and "M̄ = M c ω²/W0" in prov["conventions"]


def test_provenance_is_the_gfbopt_source_not_the_working_directory(tmp_path):
    """Run from an unrelated git repository: the commit recorded is gfbopt's own."""
    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    out = subprocess.run([sys.executable, "-m", "gfbopt", "static", "--eccentricity", "0.3",
                          "--bearing-number", "1", "--grid", "24x8", "--json"],
                         capture_output=True, text=True, cwd=tmp_path, timeout=300)
    # the gfbopt package that subprocess imports (an editable install may point elsewhere
    # than this test file's checkout): its own repository's commit must be recorded
    package = subprocess.run([sys.executable, "-c", "import gfbopt; print(gfbopt.__file__)"],
                             capture_output=True, text=True, cwd=tmp_path).stdout.strip()
    head = subprocess.run(["git", "-C", str(Path(package).parent), "rev-parse", "HEAD"],
                          capture_output=True, text=True).stdout.strip()
    assert len(head) == 40
    assert json.loads(out.stdout)["provenance"]["source_commit"] == head


def test_readable_report():
    out = gfbopt("static", "--eccentricity", "0.5", "--bearing-number", "1", "--grid", "36x10")
    assert out.returncode == 0
    assert "attitude angle" in out.stdout and "Solve_Succeeded" in out.stdout


@pytest.mark.parametrize("args, message", [
    (["--eccentricity", "-0.2", "--bearing-number", "1"], "eccentricity = -0.2: must be >= 0"),
    (["--eccentricity", "nan", "--bearing-number", "1"], "must be finite"),
    (["--eccentricity", "0.95", "--bearing-number", "1", "--foil", "rigid", "--compliance",
      "0"], None),
    (["--eccentricity", "1.2", "--bearing-number", "1"], "must be < 1 for a rigid bearing"),
    (["--eccentricity", "0.5", "--bearing-number", "1", "--compliance", "-1"],
     "compliance = -1.0: must be >= 0"),
    (["--eccentricity", "0.5", "--bearing-number", "0"], "--bearing-number = 0.0: must be > 0"),
    (["--eccentricity", "0.5", "--bearing-number", "1", "--grid", "8x2"],
     "--grid n_theta = 8: must be >= 12"),
    (["--eccentricity", "0.5", "--bearing-number", "1", "--grid", "big"],
     "must be written NTHETAxNZ"),
    (["--eccentricity", "0.5", "--bearing-number", "1", "--foil", "plastic"],
     "argument --foil: invalid choice: 'plastic'"),
    (["--eccentricity", "0.5", "--bearing-number", "1", "--film", "open"],
     "argument --film: invalid choice: 'open'"),
    # options the chosen mode would ignore are refused with the reason
    (["--bearing", "problems/bearings/ruscitto.toml", "--speed-rpm", "30000", "--load-newton",
      "10", "--length-ratio", "1"], "--length-ratio = 1.0: is taken from the bearing file"),
    (["--eccentricity", "0.5", "--bearing-number", "1", "--speed-rpm", "30000"],
     "--speed-rpm = 30000.0: needs --bearing FILE.toml"),
    (["--eccentricity", "0.5", "--bearing-number", "1", "--foil", "rigid", "--compliance", "1"],
     "--compliance = 1.0: is not used with --foil rigid"),
    (["--eccentricity", "0.5", "--bearing-number", "1", "--compliance", "1", "--seam-angle",
      "90"], "--seam-angle = 90.0: is not used with a periodic film"),
    (["--eccentricity", "0.5", "--bearing-number", "1", "--compliance", "1",
      "--top-foil-coefficient", "1"], "--top-foil-coefficient = 1.0: is used by the beam foil only"),
    (["--eccentricity", "0.5", "--bearing-number", "1", "--film", "seam", "--seam-angle",
      "400"], "--seam-angle = 400.0: must lie in [0, 360) degrees"),
    (["--bearing", "nope.toml", "--speed-rpm", "1000", "--load-newton", "10"],
     "must be an existing TOML file"),
    (["--bearing", "problems/bearings/ruscitto.toml", "--load-newton", "10"],
     "--speed-rpm (not given): is required with --bearing"),
])
def test_bad_input_is_one_line_exit_2(args, message):
    out = gfbopt("static", *args)
    if message is None:       # a valid request: must succeed
        assert out.returncode == 0, out.stderr
        return
    assert out.returncode == 2
    assert "Traceback" not in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1
    assert message in out.stderr


def test_the_entry_point_refuses_bad_input_in_one_line_exit_2():
    """``python -m gfbopt`` itself (the other refusals run ``main`` in this process): exit
    status 2 reaches the shell, one line on stderr, no traceback, nothing on stdout."""
    out = gfbopt_process("static", "--eccentricity", "-0.2", "--bearing-number", "1")
    assert out.returncode == 2 and out.stdout == ""
    assert "Traceback" not in out.stderr and len(out.stderr.strip().splitlines()) == 1
    assert "eccentricity = -0.2: must be >= 0" in out.stderr


def test_bad_bearing_file_is_one_line(tmp_path):
    bad = tmp_path / "b.toml"
    bad.write_text("[bearing]\nradius = 0.02\n")
    out = gfbopt("static", "--bearing", str(bad), "--speed-rpm", "1000", "--load-newton", "1")
    assert out.returncode == 2 and "is required" in out.stderr
    assert "Traceback" not in out.stderr


def test_run_study_writes_results(tmp_path):
    out = gfbopt("run", "problems/thesis_table_3_1.toml", "--results", str(tmp_path))
    assert out.returncode == 0, out.stdout + out.stderr
    folder = tmp_path / "thesis_table_3_1"
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["consistency_checks_hold"] is True and "passed" not in summary
    assert (folder / "table.csv").is_file() and (folder / "README.md").is_file()
    assert (tmp_path / "index.md").is_file()


def test_unknown_study_kind(tmp_path):
    bad = tmp_path / "x.toml"
    bad.write_text('kind = "dance"\n')
    out = gfbopt("run", str(bad), "--results", str(tmp_path))
    assert out.returncode == 2 and "kind = 'dance': must be one of" in out.stderr


def test_linear_json_contract():
    out = gfbopt("linear", "--eccentricity", "0.4", "--bearing-number", "2", "--compliance",
                 "1", "--length-ratio", "1", "--whirl-ratio", "0", "0.5", "--grid", "36x10",
                 "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    for key in ("critical_mass", "whirl_ratio", "stiffness", "damping", "load",
                "attitude_angle_deg", "success"):
        assert key in data
    assert set(data["stiffness"]) == {"0", "0.5"}
    assert len(data["damping"]["0.5"]) == 2 and len(data["damping"]["0.5"][0]) == 2
    assert 1.0 < data["critical_mass"] < 4.0 and 0.4 < data["whirl_ratio"] < 0.55


@pytest.mark.parametrize("args, message", [
    (["--whirl-ratio", "-0.5"], "--whirl-ratio = -0.5: must lie in [0, 100]"),
    (["--whirl-ratio", "nan"], "must be finite"),
])
def test_linear_bad_input(args, message):
    out = gfbopt("linear", "--eccentricity", "0.4", "--bearing-number", "2", "--grid", "36x10",
                 *args)
    assert out.returncode == 2 and message in out.stderr and "Traceback" not in out.stderr


def test_linear_at_zero_eccentricity_is_refused():
    out = gfbopt("linear", "--eccentricity", "0", "--bearing-number", "2", "--grid", "36x10")
    assert out.returncode == 2 and "must be > 0" in out.stderr


def test_orbit_json_contract(tmp_path):
    png, csv = tmp_path / "o.png", tmp_path / "o.csv"
    out = gfbopt("orbit", "--eccentricity", "0.4", "--bearing-number", "2", "--compliance",
                 "1", "--length-ratio", "1", "--mass", "2.5", "--revolutions", "4", "--grid",
                 "24x8", "--plot", str(png), "--csv", str(csv), "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    for key in ("verdict", "growth_rate", "revolutions", "min_film"):
        assert key in data
    assert data["verdict"] == "unstable" and data["growth_rate"] > 0
    assert png.is_file() and csv.read_text().startswith("tau,x,y,eccentricity")
    # off a terminal: one status line (gfbopt.progress), no bar; stdout is the JSON alone
    assert out.stderr.startswith("gfbopt: orbit 100 %,") and out.stderr.count("\n") == 1


def test_critical_mass_json_contract():
    out = gfbopt("critical-mass", "--eccentricity", "0.4", "--bearing-number", "2",
                 "--compliance", "1", "--length-ratio", "1", "--grid", "24x8", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    for key in ("critical_mass", "whirl_ratio", "linear_critical_mass", "transients",
                "wall_time_s", "success"):
        assert key in data
    assert data["success"] is True
    assert data["critical_mass"] == pytest.approx(data["linear_critical_mass"], rel=0.01)


@pytest.mark.parametrize("command, args, message", [
    ("orbit", ["--mass", "0"], "--mass = 0.0: must be > 0"),
    ("orbit", ["--mass", "2", "--revolutions", "-3"], "--revolutions = -3.0: must be > 0"),
    ("orbit", ["--mass", "2", "--method", "rk4", "--time-step", "0.5"],
     "exceeds the RK4 stability limit"),
    ("orbit", ["--mass", "2", "--time-step", "0.5", "--stages", "2"],
     "exceeds the RKC stability interval"),
    ("orbit", ["--mass", "2", "--method", "bdf", "--time-step", "0.01"],
     "--time-step"),
    ("critical-mass", ["--tolerance", "0"], "--tolerance = 0.0: must lie in (0, 0.5)"),
])
def test_transient_bad_input(command, args, message):
    out = gfbopt(command, "--eccentricity", "0.4", "--bearing-number", "2", "--grid", "24x8",
                 *args)
    assert out.returncode == 2, out.stdout
    assert message in out.stderr and "Traceback" not in out.stderr
