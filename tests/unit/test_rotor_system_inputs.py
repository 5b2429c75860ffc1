"""The rotor file (gfbopt.inputs.rotor_system): every bad input the issue lists is refused in one
line naming the file, the key, the value and the rule, before any solve; legal unusual rotors
(overhung CG, a bearing pushed away from gravity) are accepted; statics and the 4-DOF matrices."""
import math
from pathlib import Path

import numpy as np
import pytest

from gfbopt.errors import ParameterError
from gfbopt.file_formats import PAGES, render_format
from gfbopt.inputs.rotor_schema import ROTOR_FILE
from gfbopt.inputs.rotor_system import load_rotor, rotor_from_dict
from gfbopt.rotor.rigid import (bearing_loads, gyroscopic_matrix, mass_matrix, seam_from_load,
                                transformation)

ROOT = Path(__file__).resolve().parents[2]
BEARING = str(ROOT / "problems" / "bearings" / "ruscitto.toml")


def _data(**changes):
    data = {"rotor": {"mass": 3.2, "transverse_inertia": 0.012, "polar_inertia": 0.002},
            "bearings": [{"file": BEARING, "position": -0.035},
                         {"file": BEARING, "position": 0.065}]}
    for key, value in changes.items():
        table, _, name = key.partition("__")
        if table == "bearings":
            data["bearings"] = value
        elif table == "imbalance":
            data["imbalance"] = value
        else:
            data[table][name] = value
    return data


def test_example_rotor_file_loads_with_the_contract_keys():
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    assert system.body.mass == 3.2 and system.body.polar_inertia == 0.002
    assert [b.position for b in system.bearings] == [-0.035, 0.065]
    assert system.imbalance[0].amount_kg_m == pytest.approx(2.0e-6, rel=1e-15)  # 2 g mm


@pytest.mark.parametrize("key,value,rule", [
    ("rotor__mass", 0.0, "> 0"), ("rotor__mass", float("nan"), "finite"),
    ("rotor__transverse_inertia", -1.0, "> 0"), ("rotor__polar_inertia", 0.0, "> 0"),
    ("rotor__polar_inertia", float("inf"), "finite"),
    ("rotor__polar_inertia", 0.03, "2 × transverse_inertia"),
])
def test_bad_inertia_is_refused_naming_file_key_value_rule(key, value, rule):
    with pytest.raises(ParameterError) as err:
        rotor_from_dict(_data(**{key: value}), where="r.toml")
    message = str(err.value)
    assert message.startswith("r.toml: rotor.") and key.split("__")[1] in message
    assert rule in message and "\n" not in message


def test_bearing_count_position_file_and_imbalance_amount_are_checked():
    one = [{"file": BEARING, "position": 0.0}]
    with pytest.raises(ParameterError, match="exactly two bearings are supported"):
        rotor_from_dict(_data(bearings=one), where="r.toml")
    three = one * 3
    with pytest.raises(ParameterError, match="exactly two bearings"):
        rotor_from_dict(_data(bearings=three), where="r.toml")
    same = [{"file": BEARING, "position": 0.05}, {"file": BEARING, "position": 0.05}]
    with pytest.raises(ParameterError, match=r"bearings\[2\].position = 0.05: must differ"):
        rotor_from_dict(_data(bearings=same), where="r.toml")
    missing = [{"file": "nowhere.toml", "position": -0.05}, {"file": BEARING, "position": 0.05}]
    with pytest.raises(ParameterError, match=r"r.toml: bearings\[1\].file = 'nowhere.toml'"):
        rotor_from_dict(_data(bearings=missing), where="r.toml")
    with pytest.raises(ParameterError, match=r"imbalance\[1\].amount_kg_m = None: is required"):
        rotor_from_dict(_data(imbalance=[{"position": 0.1}]), where="r.toml")
    with pytest.raises(ParameterError, match=r"rotor.masss.*did you mean 'mass'"):
        rotor_from_dict({**_data(), "rotor": {**_data()["rotor"], "masss": 1}}, where="r.toml")


def test_symmetric_statics_share_the_weight_equally():
    sym = rotor_from_dict(_data(bearings=[{"file": BEARING, "position": -0.05},
                                          {"file": BEARING, "position": 0.05}]))
    a, b = bearing_loads(sym)
    weight = 3.2 * 9.80665
    # exact arithmetic of the lever rule: equal shares to round-off
    assert a.magnitude == pytest.approx(weight / 2, rel=1e-14)
    assert b.magnitude == pytest.approx(weight / 2, rel=1e-14)
    assert a.direction_deg == 0.0 and b.away_from_gravity_deg == 0.0


def test_overhung_rotor_lifts_the_far_bearing_and_its_frame_rotates():
    # CG outside the span: bearings at +0.02 and +0.10 m, the CG 20 mm beyond A.
    hung = rotor_from_dict(_data(bearings=[{"file": BEARING, "position": 0.02},
                                           {"file": BEARING, "position": 0.10}]))
    a, b = bearing_loads(hung)
    weight = 3.2 * 9.80665
    assert a.magnitude == pytest.approx(weight * 0.10 / 0.08, rel=1e-14)   # lever rule
    assert b.magnitude == pytest.approx(weight * 0.02 / 0.08, rel=1e-14)
    assert b.away_from_gravity_deg == 180.0 and a.away_from_gravity_deg == 0.0
    # its seam, 180° from gravity in the housing, is at 0° from its own (reversed) load
    options = seam_from_load(hung.bearings[1].options, b.away_from_gravity_deg)
    assert options.seam_angle_deg == pytest.approx(0.0, abs=1e-12)
    t = transformation(b.position, b.direction_rad)
    # the bearing's X axis points up (−x): a CG displacement +x is −X there
    assert t[0] @ np.array([1.0, 0, 0, 0]) == pytest.approx(-1.0, abs=1e-15)


def test_matrices_and_gyroscopic_sign():
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    m, g = mass_matrix(system.body), gyroscopic_matrix(system.body)
    assert np.allclose(g, -g.T) and g[2, 3] == 0.002
    # Free forward conical whirl on tilt stiffness k: I_t Ω² − I_p ω Ω = k (module docstring)
    k, omega = 1e5, 3000.0
    it, ip = 0.012, 0.002
    big = (ip * omega + math.sqrt((ip * omega) ** 2 + 4 * it * k)) / (2 * it)
    d = -big**2 * m[2:, 2:] + 1j * big * omega * g[2:, 2:] + k * np.eye(2)
    forward = np.array([1.0, -1j])     # ψx = cos Ωt = Re e^{iΩt}, ψy = sin Ωt = Re(−i e^{iΩt})
    assert np.abs(d @ forward).max() < 1e-9 * k


def test_schema_documents_every_key_and_docs_page_is_current():
    """The page is ROTOR_FILE rendered as every file format is (file_formats.render_format),
    names every key of every table, and is what docs/formats/rotor_file.md holds."""
    page = render_format(ROTOR_FILE)
    assert page == PAGES["rotor_file.md"]()
    tables = {t.name: t for t in ROTOR_FILE.tables}
    assert set(tables) == {"rotor", "bearings", "bearings.model", "side_loads", "imbalance",
                           "stations", "shaft", "disks"}
    for table in ROTOR_FILE.tables:
        head = f"[[{table.name}]]" if table.array else f"[{table.name}]"
        section = page.split(f"## `{head}`")[1].split("\n## ")[0]
        for f in table.fields:
            assert f"| `{f.name}` |" in section, (table.name, f.name)
    stored = (ROOT / "docs" / "formats" / "rotor_file.md").read_text()
    assert stored == page, ("docs/formats/rotor_file.md is stale: run python -m "
                            "gfbopt.file_formats")
