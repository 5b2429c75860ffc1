"""Studies on a bearing file with [journal]/[thermal]: ``onset_conventions`` evaluates each
onset at the running condition through the functions ``gfbopt stability`` and gfbopt.api
call (``onset_as_built`` too, per preload and pad count, and ``loss_factor_map``'s onset
part, per S and η), ``load_sweep``,
``linear_coefficients`` and ``drag_power`` each (speed, load) as
``gfbopt static`` and ``gfbopt linear`` do (one answer whatever the route), naming the model in summary.json and the README (``pitch_design``: test_running_routes_pitch.py); the
kind that does not read the tables (the DOE ``sweep``) refuses the file in one line naming
the kind, before any solve."""
import json
import math
import re
import shutil
from pathlib import Path

import pytest

from gfbopt import StaticSolver
from gfbopt.inputs import Grid, Rotor, load_bearing
from gfbopt.inputs.bearing_file import RUNNING_ROUTES, RUNNING_STUDY_KINDS
from gfbopt.studies import compute, load_study, run_study
from gfbopt.thermal.running import HEAT_BALANCE
from tests.cli_inprocess import run_cli

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"
THERMAL = PROBLEMS / "bearings" / "ruscitto_thermal.toml"
GRID = "36x10"
STUDY = f"""
name = "heated_conventions"
kind = "onset_conventions"
title = "Onset against the film convention at the running condition"
source = "gfbopt"
grid = "{GRID}"
bearing = "bearings/BEARING"
rotor_mass_kg = 2.0
load_newton = 20.0
speed_range_rpm = [3000.0, 60000.0]
seam_angles_deg = [180.0]
"""
#: convention → the formulation flags of ``gfbopt stability``
FLAGS = {"periodic": ("--film", "periodic"),
         "max_film": ("--film", "seam", "--seam-angle", "max_film"),
         "seam_180": ("--film", "seam", "--seam-angle", "180")}
RUNNING = ("running_clearance_um", "centrifugal_growth_um", "thermal_growth_um",
           "film_temperature_c", "viscosity_pa_s")


def _study(tmp_path, bearing="ruscitto_thermal.toml", text=STUDY):
    (tmp_path / "bearings").mkdir(exist_ok=True)
    shutil.copy(PROBLEMS / "bearings" / bearing, tmp_path / "bearings" / bearing)
    path = tmp_path / "study.toml"
    path.write_text(text.replace("BEARING", bearing))
    return path


@pytest.fixture(scope="module")
def heated(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("heated")
    result = run_study(_study(tmp), results_root=tmp / "results")
    return result, tmp / "results" / "heated_conventions"


def test_the_study_kinds_reading_the_tables_are_listed_in_the_routes():
    assert RUNNING_STUDY_KINDS == ("onset_conventions", "onset_as_built", "loss_factor_map",
                                   "load_sweep", "linear_coefficients", "drag_power",
                                   "pitch_design")
    for route in ("`onset_conventions`", "`onset_as_built`", "`loss_factor_map`",
                  "`load_sweep`", "`linear_coefficients`", "`drag_power`", "`pitch_design`",
                  "`gfbopt orbit`", "`gfbopt critical-mass`"):
        assert route in RUNNING_ROUTES


@pytest.mark.parametrize("convention", sorted(FLAGS))
def test_a_study_row_is_the_stability_commands_onset(heated, convention):
    result, _ = heated
    table = result.tables["onset.csv"].set_index("convention")
    row = table.loc[convention]
    cli = run_cli("stability", "--bearing", THERMAL, "--rotor-mass-kg", "2", "--load-newton",
                  "20", "--speed-range", "3000", "60000", *FLAGS[convention], "--grid", GRID,
                  "--json")
    assert cli.returncode == 0, cli.stderr
    out = json.loads(cli.stdout)
    assert out["thermal_model"] == HEAT_BALANCE == row["thermal_model"]
    # one route: the same secant search on the same running points (1e-9: rounding only)
    assert row["onset_status"] == "onset"
    assert row["onset_speed_rpm"] == pytest.approx(out["onset_speed_rpm"], rel=1e-9)
    assert row["whirl_frequency_hz"] == pytest.approx(out["onset_whirl_frequency_hz"],
                                                      rel=1e-9)
    assert row["frozen_onset_speed_rpm"] == pytest.approx(
        out["onset"]["frozen_onset_speed_rpm"], rel=1e-9)
    for key in RUNNING:                          # the running point at the onset
        assert row[key] == pytest.approx(out[key], rel=1e-9), key
    assert row["running_clearance_um"] < 20.0 and row["film_temperature_c"] > 20.0
    # the frozen search's smallest margin is not the running answer's: empty in both
    assert math.isnan(row["smallest_margin"]) and out["onset"]["smallest_margin"] is None


def test_a_study_row_is_the_apis_onset(heated):
    from gfbopt import api

    row = heated[0].tables["onset.csv"].set_index("convention").loc["seam_180"]
    found = api.onset_speed(str(THERMAL), Rotor(2.0), 20.0, (3000.0, 60000.0), film="seam",
                            seam_angle_deg=180.0, grid=Grid.parse(GRID))
    assert row["onset_speed_rpm"] == pytest.approx(found["onset_speed_rpm"], rel=1e-9)
    assert row["running_clearance_um"] == pytest.approx(
        found["running"]["running_clearance_um"], rel=1e-9)


def test_summary_and_readme_name_the_thermal_model(heated):
    _, folder = heated
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["thermal_model"] == HEAT_BALANCE
    assert summary["provenance"]["options"]["thermal_model"] == HEAT_BALANCE
    assert any("heat balance + growth" in n for n in summary["notes"])
    readme = (folder / "README.md").read_text()
    assert f"thermal_model = {HEAT_BALANCE}" in readme
    header = (folder / "onset.csv").read_text().splitlines()[0].split(",")
    for column in ("thermal_model", *RUNNING, "frozen_onset_speed_rpm"):
        assert column in header, column


def test_a_file_without_the_tables_gives_todays_study(tmp_path):
    """No clearance-at-speed column or option, and the row is the isothermal onset of the
    cold bearing (gfbopt.rotor.onset_speed on the file's geometry)."""
    from gfbopt.rotor import onset_speed

    loaded = load_study(_study(tmp_path, "ruscitto.toml"))
    assert all("running" not in p for p in loaded.plan["points"])
    result = compute(loaded)
    table = result.tables["onset.csv"].set_index("convention")
    assert not set(table.columns) & {"thermal_model", *RUNNING}
    assert "thermal_model" not in result.options and result.answer == {}
    bearing = load_bearing(PROBLEMS / "bearings" / "ruscitto.toml")
    found = onset_speed(bearing, Rotor(2.0), 20.0, (3000.0, 60000.0), film="seam",
                        seam_angle_deg=180.0, foil="simple", deflection_law="mean",
                        loss_factor=0.0, grid=Grid.parse(GRID))
    assert table.loc["seam_180", "onset_speed_rpm"] == found.onset_speed_rpm
    assert math.isfinite(found.onset_speed_rpm)


@pytest.fixture
def no_solver(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("a solver was built before the file was refused")
    monkeypatch.setattr(StaticSolver, "__init__", refuse)


@pytest.mark.parametrize("problem, kind", [("ruscitto_tolerances", "sweep")])
def test_kinds_that_do_not_read_the_tables_refuse_in_one_line(tmp_path, no_solver, problem,
                                                               kind):
    text = (PROBLEMS / f"{problem}.toml").read_text()
    assert '"bearings/ruscitto.toml"' in text
    path = _study(tmp_path, text=text.replace('"bearings/ruscitto.toml"',
                                              '"bearings/BEARING"'))
    result = run_cli("run", path, "--results", tmp_path / "results")
    assert result.returncode == 2 and result.stdout == ""
    line = result.stderr.strip()
    assert len(line.splitlines()) == 1
    assert f"the study kind '{kind}' does not read" in line
    assert re.search(r"states \[journal\] and \[thermal\]", line)
    assert ("`onset_conventions`, `onset_as_built`, `loss_factor_map`, `load_sweep`, "
            "`linear_coefficients`, `drag_power`, `pitch_design`") in line
    assert "`gfbopt stability`" in line
    assert not (tmp_path / "results").exists() or not any((tmp_path / "results").iterdir())


SWEEP = f"""
name = "heated_sweep"
kind = "load_sweep"
title = "Minimum film against load at the running condition"
source = "gfbopt"
grid = "{GRID}"
bearing = "bearings/BEARING"
speeds_rpm = [30000.0, 45000.0]
loads_newton = [10.0, 20.0, 40.0]
trends = ["min_film_thickness_decreases_with_load", "eccentricity_increases_with_load"]
[model]
film = "seam"
seam_angle_deg = "max_film"
[[variants]]
label = "simple"
foil = "simple"
[[variants]]
label = "beam"
foil = "beam"
"""


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("sweep")
    result = run_study(_study(tmp, text=SWEEP), results_root=tmp / "results")
    return result, tmp / "results" / "heated_sweep"


@pytest.mark.parametrize("foil, speed, load", [("simple", 45000.0, 20.0),
                                               ("beam", 30000.0, 40.0)])
def test_a_load_sweep_row_is_the_static_commands_equilibrium(sweep, foil, speed, load):
    table = sweep[0].tables["table.csv"]
    row = table[(table["variant"] == foil) & (table["speed_rpm"] == speed)
                & (table["load_newton"] == load)].iloc[0]
    cli = run_cli("static", "--bearing", THERMAL, "--speed-rpm", f"{speed:g}",
                  "--load-newton", f"{load:g}", "--seam-angle", "max_film", "--foil", foil,
                  "--grid", GRID, "--json")
    assert cli.returncode == 0, cli.stderr
    out = json.loads(cli.stdout)
    assert row["thermal_model"] == out["thermal_model"] == HEAT_BALANCE
    # the same fixed point and the same cold solve of the warm bearing (1e-9: rounding)
    for key in (*RUNNING, "eccentricity", "attitude_angle_deg", "min_film_thickness_um",
                "power_loss_w", "bearing_number", "compliance"):
        assert row[key] == pytest.approx(out[key], rel=1e-9), key
    assert row["min_film_thickness_um"] == pytest.approx(
        row["min_film"] * row["running_clearance_um"], rel=1e-12)
    assert row["running_clearance_um"] < 19.0 and bool(row["success"])


def test_the_load_sweeps_outputs_name_the_thermal_model(sweep):
    result, folder = sweep
    assert result.checks_hold                     # converged, h_min falls and ε rises
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["thermal_model"] == HEAT_BALANCE
    assert any("running clearance" in n for n in summary["notes"])
    assert f"thermal_model = {HEAT_BALANCE}" in (folder / "README.md").read_text()
    header = (folder / "table.csv").read_text().splitlines()[0].split(",")
    assert {"thermal_model", "thermal_static_solves", *RUNNING} <= set(header)


def test_a_load_sweep_without_the_tables_is_todays(tmp_path):
    loaded = load_study(_study(tmp_path, "ruscitto.toml", text=SWEEP))
    assert len(loaded.plan) == 2                  # today's plan: no running condition
    result = compute(loaded)
    assert not set(result.tables["table.csv"].columns) & {"thermal_model", *RUNNING}
    assert result.answer == {} and "thermal_model" not in result.options


def _hot(tmp_path):
    """The thermal file with its paths to ambient choked (a runaway below 60,000 rpm)."""
    src = THERMAL.read_text()
    for old, new in (("journal_to_ambient = 0.5 ", "journal_to_ambient = 0.02"),
                     ("sleeve_to_ambient = 1.0 ", "sleeve_to_ambient = 0.02")):
        assert old in src
        src = src.replace(old, new)
    (tmp_path / "bearings").mkdir(exist_ok=True)
    (tmp_path / "bearings" / "hot.toml").write_text(src)


def test_no_running_state_is_a_row_saying_so(tmp_path):
    _hot(tmp_path)
    text = (SWEEP.replace("bearings/BEARING", "bearings/hot.toml")
            .replace("[30000.0, 45000.0]", "[60000.0]").replace("[10.0, 20.0, 40.0]", "[20.0]"))
    (tmp_path / "sweep.toml").write_text(text)
    result = compute(load_study(tmp_path / "sweep.toml"))
    row = result.tables["table.csv"].iloc[0]
    assert row["thermal_status"] == "runaway" and "thermal runaway" in row["message"]
    assert math.isnan(row["min_film_thickness_um"]) and math.isnan(row["eccentricity"])
    # no equilibrium solved (success False), but a runaway is an answer, not a failed
    # solve: the check counts solver failures only and states the row apart
    assert not bool(row["success"]) and result.checks_hold
    assert "not counted, answers: 2 rows with no running state: thermal runaway at 60,000 " \
        "rpm under 20 N (simple); thermal runaway at 60,000 rpm under 20 N (beam)" in \
        result.checks[0]["what"]
    # the command says the same: no running state, exit 1
    cli = run_cli("static", "--bearing", tmp_path / "bearings" / "hot.toml", "--speed-rpm",
                  "60000", "--load-newton", "20", "--seam-angle", "max_film", "--grid", GRID,
                  "--json")
    assert cli.returncode == 1 and json.loads(cli.stdout)["running"]["thermal_status"] == \
        "runaway"


def test_a_runaway_before_the_onset_is_the_rows_status(tmp_path):
    _hot(tmp_path)
    text = (STUDY.replace("bearings/BEARING", "bearings/hot.toml")
            .replace("rotor_mass_kg = 2.0", "rotor_mass_kg = 0.2"))
    (tmp_path / "study.toml").write_text(text)
    table = compute(load_study(tmp_path / "study.toml")).tables["onset.csv"]
    row = table.set_index("convention").loc["seam_180"]
    assert row["onset_status"] == "thermal runaway" and math.isnan(row["onset_speed_rpm"])
    cli = run_cli("stability", "--bearing", tmp_path / "bearings" / "hot.toml",
                  "--rotor-mass-kg", "0.2", "--load-newton", "20", "--speed-range", "3000",
                  "60000", "--film", "seam", "--seam-angle", "180", "--grid", GRID, "--json")
    out = json.loads(cli.stdout)
    assert out["onset_speed_rpm"] is None
    assert row["thermal_limit_rpm"] == pytest.approx(out["onset"]["thermal_limit_rpm"],
                                                     rel=1e-9)
    assert 20000.0 < row["thermal_limit_rpm"] < 60000.0
    # the same fields whatever the answer: a runaway's onset has every key of an onset's
    # (null where it has no value), and the load typed is the top level's
    onset = run_cli("stability", "--bearing", THERMAL, "--rotor-mass-kg", "0.2",
                    "--load-newton", "20", "--speed-range", "3000", "60000", "--film", "seam",
                    "--seam-angle", "180", "--grid", GRID, "--json")
    found = json.loads(onset.stdout)["onset"]
    assert set(found) - {"thermal_limit_kind", "thermal_limit_rpm"} <= set(out["onset"])
    assert set(out["onset"]) - {"thermal_limit_kind", "thermal_limit_rpm"} == \
        set(found) - {"thermal_limit_kind", "thermal_limit_rpm"}
    assert out["load_newton"] == 20.0 and out["onset"]["load_newton"] == 20.0
    assert out["onset"]["speed_range_rpm"] == [3000.0, 60000.0]


COEFFICIENTS = SWEEP.replace('name = "heated_sweep"', 'name = "heated_coefficients"').replace(
    'kind = "load_sweep"', 'kind = "linear_coefficients"').replace(
    "[30000.0, 45000.0]", "[45000.0]").replace("[10.0, 20.0, 40.0]", "[20.0, 50.0]").replace(
    'trends = ["min_film_thickness_decreases_with_load", "eccentricity_increases_with_load"]',
    "whirl_ratios = [0.0, 0.5, 1.0]")


@pytest.fixture(scope="module")
def coefficients(tmp_path_factory):
    return compute(load_study(_study(tmp_path_factory.mktemp("coefficients"),
                                     text=COEFFICIENTS)))


@pytest.mark.parametrize("foil, load", [("simple", 20.0), ("beam", 50.0)])
def test_a_coefficient_row_is_the_linear_commands(coefficients, foil, load):
    result = coefficients
    assert result.answer == {"thermal_model": HEAT_BALANCE} and result.checks_hold
    table = result.tables["coefficients.csv"]
    row = table[(table["variant"] == foil) & (table["load_newton"] == load)
                & (table["whirl_ratio"] == 0.5)].iloc[0]
    cli = run_cli("linear", "--bearing", THERMAL, "--speed-rpm", "45000", "--load-newton",
                  f"{load:g}", "--seam-angle", "max_film", "--foil", foil, "--whirl-ratio",
                  "0", "0.5", "1", "--grid", GRID, "--json")
    assert cli.returncode == 0, cli.stderr
    out = json.loads(cli.stdout)
    for key in (*RUNNING, "eccentricity", "critical_mass"):
        assert row[key] == pytest.approx(out[key], rel=1e-9), key
    k, c = out["stiffness"]["0.5"], out["damping"]["0.5"]
    for i, a in enumerate("xy"):
        for j, b in enumerate("xy"):
            assert row[f"k{a}{b}"] == pytest.approx(k[i][j], rel=1e-9, abs=1e-12)
            assert row[f"c{a}{b}"] == pytest.approx(c[i][j], rel=1e-9, abs=1e-12)
    # K in N/m of the running clearance: K̄ p_a R²/c_run (p_a = 1e5 Pa, R = 19.05 mm)
    assert row["kxx_N_per_m"] == pytest.approx(
        row["kxx"] * 1e5 * 19.05e-3**2 / (row["running_clearance_um"] * 1e-6), rel=1e-9)


DRAG = f"""
name = "heated_drag"
kind = "drag_power"
title = "Drag at the running condition"
source = "gfbopt"
grid = "{GRID}"
bearing = "bearings/BEARING"
speeds_rpm = [20000.0, 45000.0]
loads_newton = [20.0, 50.0]
"""


def test_a_drag_row_is_the_static_commands_drag(tmp_path):
    result = compute(load_study(_study(tmp_path, text=DRAG)))
    assert result.answer == {"thermal_model": HEAT_BALANCE} and result.checks_hold
    table = result.tables["drag.csv"]
    row = table[(table["speed_rpm"] == 45000.0) & (table["load_newton"] == 50.0)].iloc[0]
    cli = run_cli("static", "--bearing", THERMAL, "--speed-rpm", "45000", "--load-newton",
                  "50", "--grid", GRID, "--json")                # the file's [model]
    assert cli.returncode == 0, cli.stderr
    out = json.loads(cli.stdout)
    for key in (*RUNNING, "power_loss_w", "drag_torque_nm", "min_film_thickness_um"):
        assert row[key] == pytest.approx(out[key], rel=1e-9), key
    # Petroff's power at the row's own running clearance and μ: P/P_Petroff is the ratio
    for _, r in table.iterrows():
        assert r["power_loss_w"] / r["petroff_power_w"] == pytest.approx(r["torque_ratio"],
                                                                         rel=1e-9)
    # a hot film (more viscous) in a closed-down clearance: 64.0 W against 50.7 W cold
    assert row["film_temperature_c"] > 60.0 and row["running_clearance_um"] < 17.0


AS_BUILT = f"""
name = "heated_preload"
kind = "onset_as_built"
title = "Onset against preload at the running condition"
source = "gfbopt"
grid = "{GRID}"
bearing = "bearings/BEARING"
rotor_mass_kg = 2.0
load_newton = 20.0
speed_range_rpm = [3000.0, 120000.0]
seam_angle_deg = 180.0
bore = "shims"
n_shims = 3
shim_width_deg = 60.0
shim_offset_deg = 0.0
preload_depths_um = [0.0, 4.0]
n_pads = [2.0]
"""
#: the same bearings as built, stated in the file: 3 shims 4 µm deep; two 180° pads
AS_FILES = {("preload", 4.0): '[bore]\nkind = "shims"\ncount = 3\npreload_depth = 4e-6\n'
                              'width_deg = 60.0\noffset_deg = 0.0\n',
            ("pads", 0.0): "[[pads]]\nleading_end_deg = 180.0\narc_deg = 180.0\n"
                           "[[pads]]\nleading_end_deg = 0.0\narc_deg = 180.0\n"}


def test_an_as_built_onset_row_is_the_stability_commands(tmp_path):
    result = compute(load_study(_study(tmp_path, text=AS_BUILT)))
    assert result.answer == {"thermal_model": HEAT_BALANCE} and result.checks_hold
    table = result.tables["onset.csv"]
    for (variant, depth), tables in AS_FILES.items():
        row = table[(table["variant"] == variant)
                    & (table["preload_depth_um"] == depth)].iloc[0]
        built = tmp_path / f"{variant}.toml"
        built.write_text(THERMAL.read_text() + "\n" + tables)
        cli = run_cli("stability", "--bearing", built, "--rotor-mass-kg", "2",
                      "--load-newton", "20", "--speed-range", "3000", "120000", "--grid",
                      GRID, "--json")
        assert cli.returncode == 0, cli.stderr
        out = json.loads(cli.stdout)
        assert row["onset_status"] == "onset", variant
        assert row["onset_speed_rpm"] == pytest.approx(out["onset_speed_rpm"], rel=1e-9)
        for key in RUNNING:
            assert row[key] == pytest.approx(out[key], rel=1e-9), (variant, key)
    # the preload still raises the onset at the running condition (13,219 → 16,226 rpm)
    preload = table[table["variant"] == "preload"].set_index("preload_depth_um")
    assert preload.loc[4.0, "onset_speed_rpm"] > 1.15 * preload.loc[0.0, "onset_speed_rpm"]


LOSS_FACTOR = f"""
name = "heated_loss_factor"
kind = "loss_factor_map"
title = "Onset against S and η at the running condition"
source = "gfbopt"
grid = "{GRID}"
loss_factors = [0.3]
compliances = [1.0]
deflection_laws = ["mean"]
[model]
film = "seam"
seam_angle_deg = 180.0
[[cases]]
label = "L2"
bearing_number = 2.0
eccentricity = 0.4
[onset]
bearing = "bearings/BEARING"
rotor_mass_kg = 2.0
load_newton = 20.0
speed_range_rpm = [5000.0, 60000.0]
"""


def test_a_loss_factor_onset_row_is_the_stability_commands(tmp_path):
    from gfbopt.design.stability_design import bearing_with_compliance

    result = compute(load_study(_study(tmp_path, text=LOSS_FACTOR)))
    assert result.answer == {"thermal_model": HEAT_BALANCE} and result.checks_hold
    onset = result.tables["onset.csv"].set_index("deflection_law")
    assert "thermal_model" not in result.tables["critical_mass.csv"]   # non-dimensional
    # S = 1 by the bump thickness (bearing_with_compliance), stated in a file for the command
    bearing = bearing_with_compliance(load_bearing(THERMAL, running=True), 1.0)
    src = re.sub(r"bump_thickness = [^#\n]*", f"bump_thickness = {bearing.bump_thickness!r} ",
                 THERMAL.read_text())
    assert src.count(repr(bearing.bump_thickness)) == 1
    (tmp_path / "s1.toml").write_text(src)
    for law, flags, path in (("rigid", ("--foil", "rigid", "--film", "seam", "--seam-angle",
                                        "180"), THERMAL),
                             ("mean", ("--loss-factor", "0.3"), tmp_path / "s1.toml")):
        cli = run_cli("stability", "--bearing", path, "--rotor-mass-kg", "2", "--load-newton",
                      "20", "--speed-range", "5000", "60000", *flags, "--grid", GRID, "--json")
        assert cli.returncode == 0, cli.stderr
        out = json.loads(cli.stdout)
        assert onset.loc[law, "onset_speed_rpm"] == pytest.approx(out["onset_speed_rpm"],
                                                                  rel=1e-9), law
        assert onset.loc[law, "running_clearance_um"] == pytest.approx(
            out["running_clearance_um"], rel=1e-9), law


def test_the_commands_onset_does_not_depend_on_the_operating_speed(heated):
    """With --speed-rpm beside --speed-range the heated onset is the study row's (the search
    starts from the range's geometric mean whatever the operating speed)."""
    row = heated[0].tables["onset.csv"].set_index("convention").loc["seam_180"]
    cli = run_cli("stability", "--bearing", THERMAL, "--rotor-mass-kg", "2", "--load-newton",
                  "20", "--speed-rpm", "30000", "--speed-range", "3000", "60000",
                  *FLAGS["seam_180"], "--grid", GRID, "--json")
    assert cli.returncode == 0, cli.stderr
    out = json.loads(cli.stdout)
    assert out["onset_speed_rpm"] == pytest.approx(row["onset_speed_rpm"], rel=1e-12)
    assert out["onset_whirl_frequency_hz"] == pytest.approx(row["whirl_frequency_hz"],
                                                            rel=1e-12)


def test_a_non_dimensional_mass_is_refused_on_a_heated_file():
    """M̄ = M c ω²/W0 on a heated file would be converted with one clearance and analysed at
    another: refused in one line naming the flag, before any solve."""
    cli = run_cli("stability", "--bearing", THERMAL, "--mass", "18.43", "--load-newton", "20",
                  "--speed-rpm", "30000", "--grid", GRID)
    assert cli.returncode == 2
    lines = cli.stderr.strip().splitlines()
    assert len(lines) == 1 and "--mass = 18.43" in lines[0] and "--rotor-mass-kg" in lines[0]


def test_the_apis_file_answer_reads_as_a_result(heated):
    """gfbopt.api given a file's path: the command line's JSON fields, each also an attribute
    (``.answer``, ``.onset_speed_rpm``), so the README's ``onset_speed(...).answer`` works."""
    from gfbopt import api
    from gfbopt.rotor.running_files import FileAnswer

    found = api.onset_speed(str(THERMAL), Rotor(2.0), 20.0, (3000.0, 60000.0), film="seam",
                            seam_angle_deg=180.0, grid=Grid.parse(GRID))
    assert isinstance(found, FileAnswer) and isinstance(found, dict)
    assert found.onset_speed_rpm == found["onset_speed_rpm"]
    assert found.answer.startswith("onset of whirl at ")
    assert found.to_dict() == dict(found)
    with pytest.raises(AttributeError, match="not a field"):
        found.critical_mass_kg
