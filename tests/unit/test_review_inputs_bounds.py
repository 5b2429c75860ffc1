"""One rule per key, stated in the schema and enforced by every route (review defects 3 and
5): μ_f < 1 at file read (the transients' slipping balance W = S(1 − μ_f) q needs it; before,
the file allowed 2 and a design study failed after 30 s), and hardening_exponent 0 (off) or
in [1, 10] (before, the schema said 0–10 and the model refused 0 < n < 1)."""
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import BearingModel, load_bearing
from gfbopt.inputs.file_schema import MODEL

from tests.cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]
BEARING = (ROOT / "problems/bearings/ruscitto.toml").read_text().split("[model]")[0]
HALVES = ("[[zones]]\nstart_deg = 0.0\nend_deg = 180.0\nfriction_coefficient = {}\n"
          "[[zones]]\nstart_deg = 180.0\nend_deg = 360.0\n")


def _file(tmp_path, model: str, tail: str = "") -> Path:
    path = tmp_path / "rub.toml"
    path.write_text(BEARING + "[model]\n" + model + "\n" + tail)
    return path


@pytest.mark.parametrize("mu", [1.0, 1.5, 2.0])
def test_friction_of_one_or_more_is_refused_at_file_read(tmp_path, mu):
    path = _file(tmp_path, f"friction_coefficient = {mu}")
    with pytest.raises(ParameterError) as err:
        load_bearing(path)
    assert str(err.value).startswith(f"rub.toml: model.friction_coefficient = {mu}: must be < 1")
    out = run_cli("static", "--bearing", str(path), "--speed-rpm", "30000", "--load-newton",
                  "20", cwd=ROOT)
    assert out.returncode == 2 and len(out.stderr.strip().splitlines()) == 1
    assert "W = S(1 − μ_f) q" in out.stderr


def test_a_zones_friction_obeys_the_same_rule(tmp_path):
    with pytest.raises(ParameterError, match=r"zones\[1\]\.friction_coefficient = 1\.5: must "
                                             r"be < 1"):
        load_bearing(_file(tmp_path, "", HALVES.format(1.5)))
    assert load_bearing(_file(tmp_path, "", HALVES.format(0.99))) is not None


def test_the_model_and_the_file_agree_on_friction(tmp_path):
    load_bearing(_file(tmp_path, "friction_coefficient = 0.99"))
    BearingModel(bearing_number=1.0, compliance=1.0, friction_coefficient=0.99)
    with pytest.raises(ParameterError, match="friction_coefficient = 1.0: must be < 1"):
        BearingModel(bearing_number=1.0, compliance=1.0, friction_coefficient=1.0)


@pytest.mark.parametrize("n, accepted", [(0.0, True), (0.5, False), (0.999, False),
                                         (1.0, True), (3.0, True), (10.0, True),
                                         (10.5, False)])
def test_hardening_exponent_one_rule_for_file_and_model(tmp_path, n, accepted):
    path = _file(tmp_path, f"bump_height = 0.5e-3\nhardening_exponent = {n}")
    file_ok = model_ok = True
    try:
        load_bearing(path)
    except ParameterError as exc:
        file_ok = False
        assert str(exc).startswith(f"rub.toml: model.hardening_exponent = {n}: must be 0 "
                                   "(off) or ")
    try:
        BearingModel(bearing_number=1.0, compliance=1.0, hardening_exponent=n,
                     hardening_limit=20.0)
    except ParameterError:
        model_ok = False
    assert file_ok == model_ok == accepted


def test_the_schema_and_the_generated_docs_state_the_rules():
    assert MODEL.field("hardening_exponent").rule() == ("a finite number, 0 (off) or >= 1 "
                                                        "and <= 10")
    assert MODEL.field("friction_coefficient").rule() == "a finite number, >= 0 and < 1"
    docs = (ROOT / "docs/formats/bearing_file.md").read_text()
    assert "0 (off) or >= 1 and <= 10" in docs and ">= 0 and < 1 (" in docs
    assert "<= 2 (dry metal" not in docs and ">= 0 and <= 10" not in docs
    thermal = (ROOT / "docs/thermal.md").read_text()
    assert "waits for the file schema" not in thermal
