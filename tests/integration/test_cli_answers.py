"""Command-line answers that read the same whatever the flags and
bounded, clearly refused work.  In process through
``gfbopt.cli.main`` (the console script's entry point) on coarse grids."""
from __future__ import annotations

import json
import math
import time
from pathlib import Path

import pytest

from gfbopt import cli
from gfbopt.cli.stability import SCHEMA
from gfbopt.errors import ConvergenceError
from gfbopt.inputs import load_bearing

ROOT = Path(__file__).resolve().parents[2]
RUSCITTO = str(ROOT / "problems" / "bearings" / "ruscitto.toml")
STAB = ["stability", "--bearing", RUSCITTO, "--rotor-mass-kg", "2", "--load-newton", "20",
        "--grid", "24x8", "--json"]


def run(capsys, *args) -> tuple:
    code = cli.main(list(args))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_stability_json_has_one_schema_whatever_the_flags(capsys):
    """Every field present in the three shapes (operating point only, onset only, both);
    null exactly where nothing was computed (on 0.2.0 --speed-range dropped the verdict
    fields)."""
    shapes = {}
    for name, extra in (("point", ["--speed-rpm", "20000"]),
                        ("onset", ["--speed-range", "11000", "16000"]),
                        ("both", ["--speed-rpm", "20000", "--speed-range", "11000", "16000"])):
        code, out, _ = run(capsys, *STAB, *extra)
        assert code == 0
        shapes[name] = json.loads(out)
    for data in shapes.values():
        assert set(SCHEMA) | {"provenance"} == set(data)
    assert shapes["onset"]["verdict"] is None and shapes["onset"]["coefficients"] is None
    assert shapes["point"]["onset"] is None and shapes["point"]["onset_speed_rpm"] is None
    assert shapes["point"]["csv"] is None and shapes["point"]["verdict"] == "unstable"
    assert shapes["both"]["verdict"] == shapes["point"]["verdict"]
    assert shapes["both"]["onset_speed_rpm"] == pytest.approx(
        shapes["onset"]["onset_speed_rpm"], rel=1e-9)
    assert isinstance(shapes["point"]["warnings"], list)


def test_plausibility_flags_name_their_limits(capsys):
    """At 5,000 rpm and 20 N the least-damped root whirls at 2.9x running speed (flagged);
    at 5,000 rpm and 100 N the film is 3.7 µm thick on this grid (below the 5 µm limit) and
    the load is above DellaCorte & Valco's rule of thumb for the best bump-foil bearings,
    D (L D)(D N) = 1 lbf/(in³ krpm) × 1.5 in × (1.5 in)² × 5 krpm = 16.9 lbf = 75.1 N."""
    code, out, _ = run(capsys, *STAB, "--speed-rpm", "5000")
    low = json.loads(out)
    assert code == 0 and low["mode_whirl_ratio"] > 1
    assert [w for w in low["warnings"] if "above running speed" in w]
    assert not [w for w in low["warnings"] if "µm" in w or "capacity" in w]
    args = [a if a != "20" else "100" for a in STAB]
    code, out, _ = run(capsys, *args, "--speed-rpm", "5000")
    heavy = json.loads(out)
    assert code == 0 and heavy["min_film_thickness_um"] < 5.0
    assert [w for w in heavy["warnings"] if "below 5 µm" in w]
    assert [w for w in heavy["warnings"] if "rule-of-thumb load capacity" in w
            and "= 75.06 N" in w]


def test_orbit_takes_the_rotor_in_kg_with_a_bearing(capsys):
    """M̄ = M c ω²/W0 is derived from --rotor-mass-kg (2 kg, 20 N, 20,000 rpm, c = 20 µm:
    M̄ = 2 · 20e-6 · (2094.4 rad/s)² / 20 = 8.773); --mass is refused there."""
    code, out, err = run(capsys, "orbit", "--bearing", RUSCITTO, "--speed-rpm", "20000",
                         "--load-newton", "20", "--rotor-mass-kg", "2", "--revolutions", "1",
                         "--grid", "24x8", "--json")
    assert code == 0, err
    data = json.loads(out)
    omega = 20000 * 2 * math.pi / 60
    assert data["mass"] == pytest.approx(2 * 20e-6 * omega**2 / 20, rel=1e-12)
    assert data["rotor_mass_kg"] == 2.0
    code, _, err = run(capsys, "orbit", "--bearing", RUSCITTO, "--speed-rpm", "20000",
                       "--load-newton", "20", "--mass", "8.7", "--grid", "24x8")
    assert code == 2 and "--mass = 8.7: is the non-dimensional M̄; with --bearing give the " \
        "rotor in kg" in err


@pytest.mark.parametrize("args, message", [
    (["orbit", "--eccentricity", "0.4", "--bearing-number", "2", "--mass", "2",
      "--revolutions", "1e308"], "--revolutions = 1e+308: 1e+308 revolutions would take at least"),
    (["orbit", "--eccentricity", "0.4", "--bearing-number", "2", "--mass", "2",
      "--revolutions", "1e9"], "above the limit of 2e+06: shorten the run, or raise --max-steps"),
    (["orbit", "--eccentricity", "0.4", "--bearing-number", "2", "--mass", "2",
      "--time-step", "1e-12"], "--time-step = 1e-12: 20 revolutions would take at least 1.26e+14"),
    (["orbit", "--eccentricity", "0.4", "--bearing-number", "2", "--mass", "2",
      "--stages", "1e308"], "--stages = 1e+308: must be an integer in [2, 1000]"),
    (["critical-mass", "--eccentricity", "0.4", "--bearing-number", "2", "--batch", "10000"],
     "--batch = 10000.0: must be an integer in [1, 64]"),
    (["static", "--eccentricity", "0.4", "--bearing-number", "2", "--grid", "2000x2000"],
     "grid = '2000x2000': 4,004,001 nodes: estimated 40.1 GB of memory"),
    (["static", "--eccentricity", "0.4", "--bearing-number", "2", "--foil", "beam",
      "--compliance", "1", "--top-foil-coefficient", "1e308"],
     "--top-foil-coefficient = 1e+308: must be <= 10000"),
    (["static", "--eccentricity", "0.4", "--bearing-number", "2", "--json", "--grid", "24x8",
      "--compliance", "1"] + ["--max-memory-gb", "-1"], "--max-memory-gb = -1.0: must be > 0"),
])
def test_unbounded_work_is_refused_in_one_line(capsys, args, message):
    t0 = time.perf_counter()
    code, out, err = run(capsys, *args)
    elapsed = time.perf_counter() - t0
    assert code == 2 and message in err, err
    assert err.count("\n") == 1 and "Traceback" not in err and out == ""
    assert elapsed < 1.0          # refused from the inputs, before anything is built


def test_threshold_zero_is_an_answer_not_a_bad_mass(capsys):
    """A welded end 60° after the load makes the massless journal whirl (M̄c = 0): the
    critical-mass command says "unstable at every rotor mass" (exit 0); on 0.2.0 it refused
    the point as 'mass = 0.0: must be finite and > 0'."""
    code, out, err = run(capsys, "critical-mass", "--eccentricity", "0.4", "--bearing-number",
                         "2", "--compliance", "1", "--film", "seam", "--seam-angle", "60",
                         "--grid", "24x8", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["critical_mass"] == 0.0 and data["verdict"] == "unstable at every rotor mass"
    assert data["transients"] == 0 and "massless journal is unstable" in data["message"]


def test_convergence_error_exits_1_as_documented(capsys, monkeypatch):
    """A solver failure is exit 1 with its status and residual (the docs); bad input is 2."""
    def fails(args):
        raise ConvergenceError("static solve did not converge", "Maximum_Iterations_Exceeded",
                               3.2e-4)
    monkeypatch.setattr("gfbopt.cli.static.run", fails)
    code, _, err = run(capsys, "static", "--eccentricity", "0.4", "--bearing-number", "2")
    assert code == 1
    assert "did not converge" in err and "Maximum_Iterations_Exceeded" in err and "3.2" in err


def test_unwritable_output_is_refused_before_solving(capsys, tmp_path):
    code, _, err = run(capsys, *STAB, "--speed-rpm", "20000", "--csv",
                       str(tmp_path / "missing" / "k.csv"))
    assert code == 2 and "--csv" in err and "does not exist" in err


def test_readme_python_route_uses_the_file(tmp_path):
    """The README's ``load_bearing(FILE)`` carries the file's [model] table."""
    bearing = load_bearing(RUSCITTO)
    assert bearing.options.film == "seam" and bearing.options.seam_angle_deg == 180.0


def test_a_static_solve_has_a_stated_time_budget(capsys):
    """--time-limit bounds each IPOPT solve (with its 60-iteration budget): exceeded, the
    command fails with IPOPT's status and says which budget (exit 1), never hangs."""
    code, _, err = run(capsys, "static", "--eccentricity", "0.6", "--bearing-number", "3",
                       "--compliance", "1", "--grid", "24x8", "--time-limit", "1e-4")
    assert code == 1
    assert "Maximum_CpuTime_Exceeded" in err and "60 iterations, 0.0001 s CPU (--time-limit)" in err


def test_long_work_reports_progress_off_a_terminal(capsys):
    """Off a terminal (here: captured stderr) the stability command writes a status line to
    stderr (gfbopt.progress), and stdout stays one JSON object."""
    code, out, err = run(capsys, *STAB, "--speed-rpm", "20000")
    assert code == 0 and json.loads(out)["verdict"] == "unstable"
    assert "gfbopt: stability 2/2 step (100 %)" in err
