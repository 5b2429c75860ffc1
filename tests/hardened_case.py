"""The hardened-bump case the hardening transient tests share: Ruscitto's bearing at
30,000 rpm under 20 N on 24 × 8, the hardening law n = 3 with its limit at 0.8 of the bump
height (the statics' hardened case, tests/unit/test_hardening.py)."""
from pathlib import Path

from gfbopt.inputs import load_bearing
from gfbopt.inputs.grid import Grid
from gfbopt.inputs.options import resolve_model_options
from gfbopt.static import solve_static

ROOT = Path(__file__).resolve().parents[1]
RUSCITTO = ROOT / "problems/bearings/ruscitto.toml"
GRID = Grid(24, 8)
HARD = dict(hardening_exponent=3.0, hardening_limit=0.8)


def solved(**changes):
    """The static solution of the case's model with ``changes`` (model fields)."""
    bearing = load_bearing(RUSCITTO)
    kw = resolve_model_options(bearing.options).model_kwargs()
    model = bearing.model(30000.0, **kw).replace(**changes)
    return solve_static(model, load=bearing.nondimensional_load(20.0), grid=GRID)
