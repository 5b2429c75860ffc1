"""The rotor file's [[shaft]] and [[disks]]: reading, statics about the shaft's centre of
gravity, positions from the shaft's first end, and every refusal (one line naming the file,
the key and the rule; ``gfbopt rotor`` exits 2 before any solve)."""
import copy
import math
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs.bearing_file import read_toml
from gfbopt.inputs.rotor_system import RotorSystem, load_rotor, rotor_from_dict, shaft_body
from gfbopt.inputs.shaft_file import Disk, ShaftElement, ShaftModel
from gfbopt.rotor.shaft import shaft_structure

from tests.cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]
FLEX = ROOT / "problems" / "rotors" / "flexible_rotor.toml"


@pytest.fixture(scope="module")
def data():
    return read_toml(FLEX)


def _load(data, where="flex.toml"):
    return rotor_from_dict(data, directory=FLEX.parent, where=where)


def test_example_reads_with_nodes_at_every_position(data):
    system = load_rotor(FLEX)
    shaft = system.shaft
    assert len(shaft.elements) == 20 and shaft.length == pytest.approx(0.4)
    # elements: 0.4 m of tube 38.1/20 mm at 7810 kg/m³, plus the disks 1.5 and 1.0 kg
    tube = 7810.0 * math.pi / 4 * (0.0381**2 - 0.02**2) * 0.4
    assert system.total_mass == pytest.approx(tube + 2.5, rel=1e-12)
    zg = (tube * 0.2 + 1.5 * 0.18 + 1.0 * 0.38) / (tube + 2.5)
    assert system.centre_of_gravity == pytest.approx(zg, rel=1e-12)
    structure = shaft_structure(system)
    assert structure.kind == "shaft" and structure.size == 4 * 21
    assert [structure.node_index(b.position) for b in system.bearings] == [3, 15]
    assert structure.node_index(0.38) == 19


def test_statics_balance_force_and_moment_about_the_centre_of_gravity():
    system = load_rotor(FLEX)
    (wa, _), (wb, _) = system.static_shares()
    weight = system.total_mass * system.gravity
    za, zb = (b.position for b in system.bearings)
    assert wa + wb == pytest.approx(weight, rel=1e-12)
    assert za * wa + zb * wb == pytest.approx(system.centre_of_gravity * weight, rel=1e-12)
    assert wb == pytest.approx(weight * (system.centre_of_gravity - za) / (zb - za), rel=1e-12)


def test_rigid_rotor_file_unchanged():
    system = load_rotor(ROOT / "problems" / "rotors" / "blower.toml")
    assert system.shaft is None and system.centre_of_gravity == 0.0
    assert system.body.mass == 3.2 and system.total_mass == 3.2


def test_python_api_body_is_the_shafts_own():
    system = load_rotor(FLEX)
    again = RotorSystem(None, system.bearings, shaft=system.shaft)
    assert again.body.mass == system.body.mass
    assert again.body.transverse_inertia == system.body.transverse_inertia
    RotorSystem(system.body, system.bearings, shaft=system.shaft)    # the same body: taken
    wrong = type(system.body)(system.body.mass * 2, system.body.transverse_inertia,
                              system.body.polar_inertia)
    with pytest.raises(ParameterError, match="the shaft's own rigid body"):
        RotorSystem(wrong, system.bearings, shaft=system.shaft)


def test_equivalent_body_of_a_uniform_shaft_is_the_tube_and_disk():
    el = ShaftElement(0.5, 0.04, 8000.0, 2e11, 0.01)
    model = ShaftModel((el,), (Disk(0.5, 2.0, 0.01, 0.015),))
    m_tube = 8000.0 * math.pi / 4 * (0.04**2 - 0.01**2) * 0.5
    zg = (m_tube * 0.25 + 2.0 * 0.5) / (m_tube + 2.0)
    it = (m_tube * ((0.04**2 + 0.01**2) / 16 + 0.5**2 / 12) + m_tube * (0.25 - zg) ** 2
          + 0.01 + 2.0 * (0.5 - zg) ** 2)
    body = shaft_body(model)
    assert body.mass == pytest.approx(m_tube + 2.0, rel=1e-14)
    assert body.transverse_inertia == pytest.approx(it, rel=1e-14)
    assert body.polar_inertia == pytest.approx(m_tube * (0.04**2 + 0.01**2) / 8 + 0.015,
                                               rel=1e-14)


def _edit(data, path, value):
    out = copy.deepcopy(data)
    table, index, key = path
    target = out[table] if index is None else out[table][index]
    if value is None:
        del target[key]
    else:
        target[key] = value
    return out


@pytest.mark.parametrize("path, value, key, rule", [
    (("shaft", 4, "length"), 0.0, "shaft[5].length", "> 0"),
    (("shaft", 4, "length"), -0.02, "shaft[5].length", "> 0"),
    (("shaft", 0, "outer_diameter"), 0.0, "shaft[1].outer_diameter", "> 0"),
    (("shaft", 0, "inner_diameter"), -0.001, "shaft[1].inner_diameter", ">= 0"),
    (("shaft", 2, "inner_diameter"), 0.0381, "shaft[3].inner_diameter",
     "must be < outer_diameter"),
    (("shaft", 2, "inner_diameter"), 0.05, "shaft[3].inner_diameter",
     "must be < outer_diameter"),
    (("shaft", 7, "density"), None, "shaft[8].density", "is required"),
    (("shaft", 7, "youngs_modulus"), None, "shaft[8].youngs_modulus", "is required"),
    (("shaft", 7, "youngs_modulus"), 0.0, "shaft[8].youngs_modulus", "> 0"),
    (("shaft", 1, "poisson_ratio"), 0.5, "shaft[2].poisson_ratio", "(-1, 0.5)"),
    (("shaft", 1, "lenght"), 0.02, "shaft[2].lenght", "did you mean 'length'"),
    (("disks", 1, "position"), 0.41, "disks[2].position", "must lie on the shaft"),
    (("disks", 0, "position"), -0.01, "disks[1].position", "must lie on the shaft"),
    (("disks", 0, "mass"), 0.0, "disks[1].mass", "> 0"),
    (("disks", 0, "polar_inertia"), 0.005, "disks[1].polar_inertia", "2 × transverse"),
    (("bearings", 1, "position"), 0.45, "bearings[2].position", "must lie on the shaft"),
    (("bearings", 0, "position"), -0.06, "bearings[1].position", "must lie on the shaft"),
    (("imbalance", 0, "position"), 0.5, "imbalance[1].position", "must lie on the shaft"),
    (("stations", 0, "position"), 0.5, "stations[1].position", "must lie on the shaft"),
    (("shaft", 3, "outer_diameter"), 0.04, "shaft[4].outer_diameter",
     "must be <= bearing A's journal diameter 2R = 0.0381 m at z = 0.06 m"),
    (("shaft", 2, "outer_diameter"), 0.04, "shaft[3].outer_diameter",
     "must be <= bearing A's journal diameter"),
    (("shaft", 0, "outer_diameter"), 38.1, "shaft (total mass)", "above what both bearings"),
    (("rotor", None, "mass"), 5.0, "rotor.mass", "refused with a [[shaft]]"),
    (("rotor", None, "polar_inertia"), 5.0, "rotor.polar_inertia", "refused with a [[shaft]]"),
])
def test_bad_shaft_input_is_refused_in_one_line(data, path, value, key, rule):
    with pytest.raises(ParameterError) as exc:
        _load(_edit(data, path, value))
    message = str(exc.value)
    assert message.startswith(f"flex.toml: {key}") and rule in message and "\n" not in message


def test_disks_need_a_shaft_and_side_loads_a_position(data):
    rigid = read_toml(ROOT / "problems" / "rotors" / "blower.toml")
    rigid = dict(rigid, disks=[{"position": 0.0, "mass": 1.0}])
    with pytest.raises(ParameterError, match=r"flex.toml: disks = .*need a \[\[shaft\]\]"):
        rotor_from_dict(rigid, directory=FLEX.parent / "..", where="flex.toml")
    loaded = dict(copy.deepcopy(data), side_loads=[{"force": 5.0, "direction_deg": 90.0}])
    with pytest.raises(ParameterError, match=r"side_loads\[1\].position = None: is required"):
        _load(loaded)
    loaded["side_loads"][0]["position"] = 0.2
    assert _load(loaded).side_loads[0].position == 0.2


def test_an_empty_shaft_is_refused(data):
    with pytest.raises(ParameterError, match="disks = "):
        _load(dict(copy.deepcopy(data), shaft=[]))


def test_cli_exits_2_before_any_solve(tmp_path):
    text = FLEX.read_text().replace('file = "../bearings/ruscitto.toml"',
                                    f'file = "{ROOT / "problems" / "bearings" / "ruscitto.toml"}"')
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace("position = 0.30 ", "position = 0.52 "))
    run = run_cli("rotor", bad, "--speed-range", "10000", "20000")
    assert run.returncode == 2
    assert run.stderr.count("\n") == 1 and "bearings[2].position = 0.52" in run.stderr
    assert "must lie on the shaft" in run.stderr and str(bad) in run.stderr
