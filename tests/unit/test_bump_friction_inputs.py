"""Bad friction and hardening input in a bearing file: one line naming file, key and rule,
exit 2 from the command line, before any solve."""
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import load_bearing
from gfbopt.inputs.options import ModelOptions, merge_options

from tests.cli_inprocess import run_cli

ROOT = Path(__file__).resolve().parents[2]
BEARING = (ROOT / "problems/bearings/ruscitto.toml").read_text().split("[model]")[0]


def _file(tmp_path, model: str) -> Path:
    path = tmp_path / "rub.toml"
    path.write_text(BEARING + "[model]\n" + model + "\n")
    return path


@pytest.mark.parametrize("model, message", [
    ("friction_coefficient = -0.1", "rub.toml: model.friction_coefficient = -0.1: must be >= 0"),
    ("friction_coefficient = nan", "rub.toml: model.friction_coefficient = nan: must be finite"),
    ("friction_coefficient = inf", "rub.toml: model.friction_coefficient = inf: must be finite"),
    ("friction_coefficient = 1.0", "rub.toml: model.friction_coefficient = 1.0: must be < 1"),
    ('foil = "rigid"\nfriction_coefficient = 0.2',
     "rub.toml: model.friction_coefficient = 0.2: must be 0 with foil='rigid'"),
    ('foil = "beam"\nseam_angle_deg = 180.0\nfriction_coefficient = 0.2',
     "rub.toml: model.friction_coefficient = 0.2: is not carried by the beam foil model"),
    ("friction_coefficient = 0.2\nfriction_stiffness_ratio = 0.0",
     "rub.toml: model.friction_stiffness_ratio = 0.0: must be > 0"),
    ("bump_height = 500e-6\nhardening_limit = 600e-6",
     "rub.toml: model.hardening_limit = 0.0006: must be <= the bump height"),
    ("hardening_limit = 400e-6", "rub.toml: model.hardening_limit = 0.0004: needs bump_height"),
    ('deflection_law = "local"\nbump_height = 500e-6\nhardening_exponent = 2.0',
     "rub.toml: model.hardening_exponent = 2.0: the hardening bump needs a bump foundation"),
    ("friction_coeficient = 0.2", "did you mean 'friction_coefficient'?"),
])
def test_refused_in_one_line_naming_file_key_rule(tmp_path, model, message):
    path = _file(tmp_path, model)
    with pytest.raises(ParameterError) as err:
        load_bearing(path)
    assert message in str(err.value) and "\n" not in str(err.value)
    out = run_cli("static", "--bearing", str(path), "--speed-rpm", "30000",
                  "--load-newton", "20")
    assert out.returncode == 2 and len(out.stderr.strip().splitlines()) == 1
    assert message in out.stderr and "Traceback" not in out.stderr


def test_stated_friction_reaches_the_model(tmp_path):
    bearing = load_bearing(_file(tmp_path, "friction_coefficient = 0.25\n"
                                           "friction_stiffness_ratio = 2.0"))
    model = bearing.model(30000.0, **merge_options(ModelOptions(), bearing.options)
                          .model_kwargs())
    assert (model.friction_coefficient, model.friction_stiffness_ratio) == (0.25, 2.0)
    assert model.options()["friction_coefficient"] == 0.25
    # a rigid comparison on the command line cannot keep the file's friction: refused
    with pytest.raises(ParameterError, match=r"model\.friction_coefficient = 0\.25"):
        merge_options(ModelOptions(foil="rigid"), bearing.options)
    # not stated: today's model and today's options (no new keys in the outputs)
    plain = load_bearing(ROOT / "problems/bearings/ruscitto.toml")
    kw = merge_options(ModelOptions(), plain.options).model_kwargs()
    assert "friction_coefficient" not in kw
    assert "friction_coefficient" not in plain.model(30000.0, **kw).options()
