"""A linear imbalance response larger than the radial clearance at a speed below the first
onset is warned about (the journal would cross the clearance: the linear model does not hold
there), in the result, the JSON and the text of ``gfbopt rotor --imbalance-response``; a
response within the clearance is not."""
import json
import re
from pathlib import Path

from gfbopt import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.analyse import analyse_rotor

from cli_inprocess import run_cli

REPO = Path(__file__).resolve().parents[2]
GRID = Grid(24, 8)
RANGE = (4000.0, 16000.0)


def _rotor(tmp_path, amount_g_mm: float) -> Path:
    """The blower rotor (3.2 kg, c = 20 µm: Σ amount ≤ m c = 64 g mm) with ``amount_g_mm``."""
    text = (REPO / "problems/rotors/blower.toml").read_text()
    text = text.replace("amount_g_mm = 2.0 ", f"amount_g_mm = {amount_g_mm} ")
    text = text.replace("../bearings/ruscitto.toml",
                        str(REPO / "problems/bearings/ruscitto.toml"))
    path = tmp_path / f"rotor_{amount_g_mm:g}.toml"
    path.write_text(text)
    return path


def test_warning_names_the_amplitude_above_the_clearance(tmp_path):
    system = load_rotor(_rotor(tmp_path, 60.0))
    result = analyse_rotor(system, RANGE, imbalance=True, grid=GRID, imbalance_speeds=7,
                           show_progress=False)
    onset = result.imbalance.unstable_from_rpm
    table = result.imbalance.table
    below = table[(table["station"] == "B") & (table["speed_rpm"] < onset)]
    worst = below.loc[below["amplitude_um"].idxmax()]
    assert worst["amplitude_um"] > 20.0                  # the linear orbit crosses c
    ours = [w for w in result.warnings if w.startswith("the linear imbalance response")]
    assert any(f"reaches {worst['amplitude_um']:.4g} µm at bearing B at "
               f"{worst['speed_rpm']:,.0f} rpm, above the radial clearance of 20 µm" in w
               and "--run-up" in w for w in ours), result.warnings
    for w in ours:                                      # every one below the first onset
        speed = float(re.search(r"at ([0-9,]+) rpm", w).group(1).replace(",", ""))
        assert speed < onset


def test_no_warning_within_the_clearance_and_the_cli_prints_it(tmp_path):
    small = analyse_rotor(load_rotor(_rotor(tmp_path, 2.0)), RANGE, imbalance=True, grid=GRID,
                          imbalance_speeds=7, show_progress=False)
    assert small.imbalance.table["amplitude_um"].max() < 20.0
    assert not any("linear imbalance response" in w for w in small.warnings)
    args = ("rotor", str(_rotor(tmp_path, 60.0)), "--imbalance-response",
            "--speed-range", "4000", "16000", "--grid", "24x8")
    out = run_cli(*args, "--json", cwd=REPO)
    assert out.returncode == 0, out.stderr
    warnings = json.loads(out.stdout)["warnings"]
    assert any("linear imbalance response reaches" in w and "bearing B" in w for w in warnings)
