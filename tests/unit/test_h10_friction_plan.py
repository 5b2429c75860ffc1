"""A rotor design whose bearings carry Coulomb friction is refused at plan time (the top-speed
orbit runs the rotor transient, which has no sliders): one line naming the study file, the
bearing, the key and the rule, exit 2, before any search -- not after a minute of search."""
from __future__ import annotations

import time
from pathlib import Path

from gfbopt.cli import main

ROOT = Path(__file__).resolve().parents[2]


def _friction_rotor(tmp_path: Path) -> Path:
    text = (ROOT / "problems" / "bearings" / "ruscitto.toml").read_text()
    marker = "\nloss_factor = 0.0"
    assert marker in text
    (tmp_path / "fric.toml").write_text(text.replace(marker, "\nfriction_coefficient = 0.1"
                                                     + marker, 1))
    rotor = (ROOT / "problems" / "rotors" / "blower.toml").read_text()
    bearing_file = (ROOT / "problems" / "rotors" / "blower.toml").read_text()
    assert 'file = "../bearings/ruscitto.toml"' in bearing_file, "the blower's bearing path"
    rotor = rotor.replace('file = "../bearings/ruscitto.toml"', 'file = "fric.toml"')
    (tmp_path / "blower_fric.toml").write_text(rotor)
    return tmp_path / "blower_fric.toml"


def test_friction_rotor_design_is_refused_before_the_search(tmp_path, capsys):
    rotor = _friction_rotor(tmp_path)
    start = time.process_time()
    code = main(["run", str(ROOT / "problems" / "rotor_bearing_design.toml"), "--rotor",
                 str(rotor), "--top-speed", "30000", "--results", str(tmp_path / "res")])
    spent = time.process_time() - start
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2
    assert len(err) == 1 and "bearing A" in err[0] and "friction_coefficient = 0.1" in err[0]
    assert "limit_cycle_revolutions" in err[0] and "rotor_bearing_design.toml" in err[0]
    assert spent < 10.0                       # no search ran (the search takes ~30 s CPU)
    assert not (tmp_path / "res").exists() or not any((tmp_path / "res").rglob("*.parquet"))
