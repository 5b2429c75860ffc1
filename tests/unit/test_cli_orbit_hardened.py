"""`gfbopt orbit` runs a bearing file with a hardening bump (it refused it: 'does not support
the hardened foil law') and the hardening acts: the same run with the linear bump ends with a
different smallest film."""
import json
import re
from pathlib import Path

from cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]


def _bearing(tmp_path: Path, exponent: float) -> Path:
    text = (ROOT / "problems" / "bearings" / "ruscitto.toml").read_text()
    text, n = re.subn(r'(?m)^foil = "simple".*$', 'foil = "simple"\nhardening_exponent = '
                      f'{exponent}\nhardening_limit = 16e-6\nbump_height = 0.5e-3', text)
    assert n == 1
    path = tmp_path / f"hardened_{exponent:g}.toml"
    path.write_text(text)
    return path


def _orbit(path: Path, tmp_path: Path) -> dict:
    r = run_cli("orbit", "--bearing", str(path), "--speed-rpm", "30000", "--load-newton", "20",
                "--rotor-mass-kg", "2", "--revolutions", "3", "--grid", "24x8",
                "--json")
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def test_orbit_runs_a_hardened_bearing_and_the_hardening_acts(tmp_path):
    hard = _orbit(_bearing(tmp_path, 3.0), tmp_path)
    linear = _orbit(_bearing(tmp_path, 0.0), tmp_path)
    assert hard["min_film"] != linear["min_film"]
