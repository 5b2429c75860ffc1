"""The ``pitch_design`` study kind on a bearing file with [journal]/[thermal]: every trial S
of the stability-driven bump design is evaluated at the running condition of each speed
through the functions ``gfbopt stability`` calls (gfbopt.design.running_evaluation), so an
onset of the trade-off table, the original foil's and the chosen design's equal the
command's on a bearing file with that bump foil; summary.json and the README name the
thermal model; a file without the tables gives the shipped study's numbers.

The study is problems/ruscitto_pitch_design.toml cut to its first case (axial-mean law,
η = 0: the case the recommendation is made for; each case's search is independent of the
others), 5 scan points of S at 36 x 10: 2-3 s."""
import json
import math
import re
import shutil
from pathlib import Path

import pandas as pd
import pytest

from gfbopt.design.stability_design import BAND, evaluate_compliance
from gfbopt.studies import compute, load_study, run_study
from gfbopt.thermal.files import load_running_bearing
from gfbopt.thermal.running import HEAT_BALANCE
from tests.cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "problems"
SHIPPED = ROOT / "results" / "ruscitto_pitch_design"
THERMAL = PROBLEMS / "bearings" / "ruscitto_thermal.toml"
RUNNING = ("running_clearance_um", "centrifugal_growth_um", "thermal_growth_um",
           "film_temperature_c", "viscosity_pa_s")
#: the study's formulation and rotor as ``gfbopt stability`` flags
FLAGS = ("--rotor-mass-kg", "2", "--load-newton", "20", "--film", "seam", "--seam-angle",
         "180", "--foil", "simple", "--deflection-law", "mean", "--loss-factor", "0",
         "--grid", "36x10")


def _study(tmp_path: Path, bearing: str) -> Path:
    """problems/ruscitto_pitch_design.toml on ``bearing``, its first case only."""
    text = (PROBLEMS / "ruscitto_pitch_design.toml").read_text()
    for pattern, value in ((r'^name = .*$', 'name = "pitch_first_case"'),
                           (r'^bearing = .*$', f'bearing = "bearings/{bearing}"'),
                           (r'^loss_factors = .*$', "loss_factors = [0.0]"),
                           (r'^deflection_laws = .*$', 'deflection_laws = ["mean"]')):
        text, n = re.subn(pattern, value, text, flags=re.M)
        assert n == 1, pattern
    (tmp_path / "bearings").mkdir(exist_ok=True)
    shutil.copy(PROBLEMS / "bearings" / bearing, tmp_path / "bearings" / bearing)
    path = tmp_path / "study.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def heated(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("heated_pitch")
    path = _study(tmp, "ruscitto_thermal.toml")
    result = run_study(path, results_root=tmp / "results")
    return result, tmp / "results" / "pitch_first_case", load_study(path).plan, tmp


def _with_bump_foil(tmp_path: Path, pitch_m: float, half_length_m: float,
                    thickness_m: float) -> Path:
    """ruscitto_thermal.toml with the bump foil given (exact floats: repr round-trips)."""
    text = THERMAL.read_text()
    for key, value in (("bump_pitch", pitch_m), ("bump_half_length", half_length_m),
                       ("bump_thickness", thickness_m)):
        text, n = re.subn(rf"^{key} = \S+", f"{key} = {float(value)!r}", text, flags=re.M)
        assert n == 1, key
    path = tmp_path / f"foil_{float(pitch_m)!r}_{float(thickness_m)!r}.toml"
    path.write_text(text)
    return path


def _onset(bearing: Path) -> dict:
    cli = run_cli("stability", "--bearing", bearing, "--speed-range", "5000", "45000",
                  *FLAGS, "--json")
    assert cli.returncode == 0, cli.stderr
    return json.loads(cli.stdout)


def _film_check(bearing: Path) -> dict:
    cli = run_cli("stability", "--bearing", bearing, "--speed-rpm", "5000", *FLAGS, "--json")
    assert cli.returncode == 0, cli.stderr
    return json.loads(cli.stdout)


def _same_onset(row, out: dict) -> None:
    """One route: the same secant search on the same running points (1e-9: rounding only,
    the file's S from (s, l0, t_b) against the search's from t_b scaled, ~1e-16)."""
    assert out["thermal_model"] == HEAT_BALANCE == row["thermal_model"]
    assert row["onset_speed_rpm"] == pytest.approx(out["onset_speed_rpm"], rel=1e-9)
    assert row["onset_whirl_frequency_hz"] == pytest.approx(out["onset_whirl_frequency_hz"],
                                                            rel=1e-9)
    assert row["frozen_onset_speed_rpm"] == pytest.approx(
        out["onset"]["frozen_onset_speed_rpm"], rel=1e-9)
    for key in RUNNING:                          # the running point at the onset
        assert row[key] == pytest.approx(out[key], rel=1e-9), key


def test_the_original_foils_onset_is_the_stability_commands(heated):
    """baseline.csv: the bearing file's own bump foil, i.e. ``gfbopt stability`` on the file
    itself (Ruscitto thermal, 2 kg, 20 N, seam 180°, 36 x 10: 13,219 rpm at the running
    clearance 19.75 µm, against 13,079 rpm cold at 144 x 36)."""
    row = heated[0].tables["baseline.csv"].iloc[0]
    out = _onset(THERMAL)
    _same_onset(row, out)
    assert 13000.0 < row["onset_speed_rpm"] < 13500.0
    assert row["running_clearance_um"] < 20.0 and row["film_temperature_c"] > 20.0
    film = _film_check(THERMAL)        # h_min at 5,000 rpm, its own running clearance
    assert row["min_film_thickness_um"] == pytest.approx(film["min_film_thickness_um"],
                                                         rel=1e-9)
    assert row["mass_margin_at_check_speed"] == pytest.approx(film["mass_margin"], rel=1e-9)


def test_every_realised_trial_S_is_the_stability_command_on_its_bump_foil(heated):
    """Each realised row's bump foil (the least-stress geometric program's) in a bearing
    file gives the row's onset.  The program realises S to its solver's accuracy (measured
    1.0-1.5e-8 relative here), which moves the onset by ~0.05 of it (d ln onset / d ln S
    ≈ −0.04 between the rows): the foil's thickness is taken to its exact S (t_b ∝ S^−1/3,
    a shift of < 1e-8) so that the comparison is of the route, to 1e-9."""
    result, _, _, tmp = heated
    table = result.tables["tradeoff.csv"]
    realised = table[table["bump_pitch_mm"].notna()]
    assert len(realised) >= 2                      # more than one foil compared
    for _, row in realised.iterrows():
        foil = (row["bump_pitch_mm"] * 1e-3, row["half_bump_length_mm"] * 1e-3)
        realised_s = load_running_bearing(_with_bump_foil(
            tmp, *foil, row["bump_thickness_mm"] * 1e-3))[0].compliance
        assert realised_s == pytest.approx(row["compliance"], rel=1e-7)
        path = _with_bump_foil(tmp, *foil, row["bump_thickness_mm"] * 1e-3
                               * (realised_s / row["compliance"]) ** (1.0 / 3.0))
        assert load_running_bearing(path)[0].compliance == pytest.approx(
            row["compliance"], rel=1e-14)
        _same_onset(row, _onset(path))
        assert row["min_film_thickness_um"] == pytest.approx(
            _film_check(path)["min_film_thickness_um"], rel=1e-9)


def test_the_chosen_designs_onset_is_the_stability_command_on_its_bump_foil(heated):
    """The chosen bump foil (recommended.csv: least stress with S in the near-best band)
    evaluated by the search's own evaluation equals ``gfbopt stability`` on a file with its
    pitch, half length and thickness (its S) to 1e-9.  The recommendation's stated onset is the best
    S's (on the stiff bound, which no whole number of bumps reaches here): the design is
    chosen inside the band where the onset is within BAND (2 %) of it, so the command's onset
    on the chosen foil lies within BAND below it."""
    result, _, spec, tmp = heated
    rec = result.tables["recommended.csv"].iloc[0]
    path = _with_bump_foil(tmp, rec["pitch"], rec["half_length"], rec["thickness"])
    out = _onset(path)
    compliance = load_running_bearing(path)[0].compliance        # the foil's S
    # the geometric program's S of its own solution, to its solver's accuracy
    assert rec["compliance"] == pytest.approx(compliance, rel=1e-6)
    row = evaluate_compliance(spec, compliance, "mean", 0.0)
    _same_onset(row, out)
    assert row["success"] and math.isfinite(out["onset_speed_rpm"])
    stated = rec["onset_speed_rpm"]
    assert 1.0 - BAND <= out["onset_speed_rpm"] / stated <= 1.0
    assert int(rec["number_of_bumps"]) == 39 and 14000.0 < stated < 14500.0


def test_summary_and_readme_name_the_thermal_model(heated):
    _, folder, _, _ = heated
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["thermal_model"] == HEAT_BALANCE
    assert summary["provenance"]["options"]["thermal_model"] == HEAT_BALANCE
    assert any("Clearance at speed" in n and HEAT_BALANCE in n for n in summary["notes"])
    readme = (folder / "README.md").read_text()
    assert f"thermal_model = {HEAT_BALANCE}" in readme
    assert f"states the running condition ({HEAT_BALANCE})" in readme
    header = (folder / "tradeoff.csv").read_text().splitlines()[0].split(",")
    for column in ("thermal_model", *RUNNING, "frozen_onset_speed_rpm"):
        assert column in header, column
    # the nonlinear check ran on the warm bearing at its speed's running condition
    assert any(n.startswith("Nonlinear check at") for n in summary["notes"])


def test_a_file_without_the_tables_gives_the_shipped_study(tmp_path):
    """ruscitto.toml (no [journal]/[thermal]): the first case's trade-off rows, baseline and
    recommendation are results/ruscitto_pitch_design's (written to 7 significant digits:
    rel 1e-6), and no clearance-at-speed column, option or answer appears."""
    loaded = load_study(_study(tmp_path, "ruscitto.toml"))
    assert loaded.plan.running is None
    result = compute(loaded)
    assert "thermal_model" not in result.options and result.answer == {}
    shipped = pd.read_csv(SHIPPED / "tradeoff.csv")
    shipped = shipped[(shipped["deflection_law"] == "mean") & (shipped["loss_factor"] == 0.0)]
    ours = result.tables["tradeoff.csv"]
    assert list(ours.columns) == list(shipped.columns)
    assert len(ours) == len(shipped) == 5
    for column in ("compliance", "onset_speed_rpm", "min_film_thickness_um",
                   "onset_whirl_frequency_hz", "mass_margin_at_check_speed",
                   "bump_pitch_mm", "bump_thickness_mm"):
        assert ours[column].to_numpy() == pytest.approx(shipped[column].to_numpy(), rel=1e-6,
                                                        nan_ok=True), column
    assert list(ours["feasible"]) == list(shipped["feasible"])
    base = pd.read_csv(SHIPPED / "baseline.csv").iloc[0]
    assert result.tables["baseline.csv"].iloc[0]["onset_speed_rpm"] == pytest.approx(
        base["onset_speed_rpm"], rel=1e-6)
    rec, shipped_rec = (result.tables["recommended.csv"].iloc[0],
                        pd.read_csv(SHIPPED / "recommended.csv").iloc[0])
    for column in ("pitch", "half_length", "thickness", "compliance", "onset_speed_rpm"):
        assert rec[column] == pytest.approx(shipped_rec[column], rel=1e-6), column


@pytest.mark.parametrize("found, merit", [
    ({"onset_speed_rpm": 14000.0}, 14000.0),
    ({"onset_speed_rpm": math.nan, "stable_over_range": True}, 45000.0),
    ({"onset_speed_rpm": math.nan, "unstable_at_lower_end": True}, 5000.0),
    # no running state from 30,000 rpm on (thermal runaway) before any onset: the design
    # cannot run above it, whatever the whirl does
    ({"onset_speed_rpm": math.nan, "thermal_limit_kind": "runaway",
      "thermal_limit_rpm": 30000.0, "stable_over_range": True}, 30000.0),
    ({"onset_speed_rpm": math.nan, "thermal_limit_kind": "closure",
      "thermal_limit_rpm": 3000.0}, 5000.0)])
def test_the_merit_of_a_running_onset_search(found, merit):
    from gfbopt.design.running_evaluation import merit_speed

    assert merit_speed(found, (5000.0, 45000.0)) == merit
