"""The hardening bump as a foil law ('hardened'): statics use the hardened stiffness,
the linear analysis its tangent at the static deflection.

The statics and the linear analysis of the law: tests/unit/test_hardened_statics.py."""
from pathlib import Path

import pytest

from gfbopt.errors import ParameterError
from gfbopt.inputs import load_bearing
from gfbopt.inputs.model import BearingModel
from gfbopt.inputs.options import resolve_model_options

ROOT = Path(__file__).resolve().parents[2]


def _case(**changes):
    bearing = load_bearing(ROOT / "problems/bearings/ruscitto.toml")
    kw = resolve_model_options(bearing.options).model_kwargs()
    return bearing.model(30000.0, **kw).replace(**changes), bearing.nondimensional_load(20.0)


def test_hardened_model_and_its_refusals():
    model, _ = _case(hardening_exponent=2.0, hardening_limit=2.0)
    assert model.foil_law == "hardened"
    assert model.options()["hardening_limit_ratio"] == 2.0   # δ_lim/c; hardening_limit is m
    assert "hardening_limit" not in model.options()
    assert _case()[0].foil_law == "simple" and "hardening_limit_ratio" not in _case()[0].options()
    for kw, rule in ((dict(hardening_exponent=0.5, hardening_limit=1.0), "n < 1"),
                     (dict(hardening_exponent=2.0), "hardening_limit = inf: must be finite"),
                     (dict(hardening_exponent=2.0, hardening_limit=1.0, deflection_law="local"),
                      "deflection_law 'mean'"),
                     (dict(hardening_exponent=float("nan")), "must be finite")):
        with pytest.raises(ParameterError, match=rule):
            BearingModel(2.0, 1.0, **kw)

