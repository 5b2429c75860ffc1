"""One answer whatever the route: the same bearing file gives the same
stability answer from the command line, the Python API and a study, for every setting of its
``[model]`` table.

Routes: ``gfbopt stability --bearing FILE --speed-rpm N --json`` (through ``gfbopt.cli.main``,
the entry point of the console script; its ``--speed-range`` calls the same ``onset_speed``
with the same resolved options); ``stability(load_bearing(FILE),
…)`` and ``onset_speed(load_bearing(FILE), …)`` exactly as the README writes them (no options
passed); a ``kind = "sweep"`` study with ``analysis = "onset_speed"`` and ``bearing = FILE``
run through :mod:`gfbopt.studies`.  On 0.2.0 the Python route ignored the file's ``[model]``
table (4.3x different critical mass for the periodic file).

Grid 24 x 8 keeps the 8 x 3 routes to a few seconds; the comparison is between routes on the
same grid, so the grid's own error does not enter.  Tolerance 1e-6 relative: every route
solves the same equations with the same solver; only the solver caches and warm starts
differ, which moves IPOPT's converged point by far less than that.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from gfbopt.cli import main
from gfbopt.inputs import Grid, load_bearing
from gfbopt.inputs.rotor import OperatingPoint, Rotor
from gfbopt.rotor import onset_speed, stability
from gfbopt.studies import study_from_dict
from gfbopt.studies.doe import run_sampled

ROOT = Path(__file__).resolve().parents[2]
RUSCITTO = ROOT / "problems" / "bearings" / "ruscitto.toml"
GRID = "24x8"
MASS, LOAD, SPEED, RANGE = 2.0, 20.0, 20000.0, (11000.0, 16000.0)
REL = 1e-6

#: every setting of a [model] table (and none at all)
SETTINGS = {
    "no [model] table": "",
    "periodic film": 'film = "periodic"\n',
    "seam at 120°": 'film = "seam"\nseam_angle_deg = 120.0\n',
    "seam on the max-film line": 'film = "seam"\nseam_angle_deg = "max_film"\n',
    "rigid foil": 'foil = "rigid"\n',
    "beam foil": 'foil = "beam"\n',
    "local deflection law": 'deflection_law = "local"\n',
    "loss factor 0.2": "loss_factor = 0.2\n",
}


def _bearing_file(tmp_path: Path, model: str) -> Path:
    geometry = RUSCITTO.read_text().split("[model]")[0]
    path = tmp_path / "bearing.toml"
    path.write_text(geometry + (f"[model]\n{model}" if model else ""))
    return path


def _cli(path: Path, capsys) -> dict:
    code = main(["stability", "--bearing", str(path), "--rotor-mass-kg", str(MASS),
                 "--load-newton", str(LOAD), "--speed-rpm", str(SPEED), "--grid", GRID,
                 "--json"])
    out = capsys.readouterr().out
    assert code == 0, out
    return json.loads(out)


def _study(path: Path, tmp_path: Path) -> dict:
    data = {"kind": "sweep", "title": "route check", "source": "test", "analysis":
            "onset_speed", "bearing": path.name, "grid": GRID, "min_success_fraction": 1.0,
            "fixed": {"load_newton": LOAD, "speed_low_rpm": RANGE[0],
                      "speed_high_rpm": RANGE[1]},
            "sampling": {"method": "list", "variables": [{"name": "rotor_mass_kg",
                                                          "values": [MASS]}]}}
    loaded = study_from_dict(data, name="routes", directory=path.parent)
    frame = run_sampled(loaded, tmp_path / "results", write=False).tables["routes.csv"]
    assert len(frame) == 1 and bool(frame["success"].iloc[0]), frame["message"].iloc[0]
    return frame.iloc[0].to_dict()


def _same(a, b) -> bool:
    """Equal to REL, or both not computed (NaN in Python, null in JSON)."""
    a, b = (math.nan if v is None else float(v) for v in (a, b))
    return (math.isnan(a) and math.isnan(b)) or a == pytest.approx(b, rel=REL)


@pytest.mark.parametrize("setting", list(SETTINGS))
def test_cli_python_and_study_agree(setting, tmp_path, capsys):
    path = _bearing_file(tmp_path, SETTINGS[setting])
    cli = _cli(path, capsys)
    bearing = load_bearing(path)                       # the README's Python route
    grid = Grid.parse(GRID)
    py = stability(bearing, Rotor(MASS), OperatingPoint(SPEED, LOAD), grid=grid)
    py_onset = onset_speed(bearing, Rotor(MASS), LOAD, RANGE, grid=grid)
    study = _study(path, tmp_path)
    # the conventions every route states are the file's
    assert cli["conventions"]["film_convention"] == py.conventions["film_convention"]
    # the CLI's JSON names M̄c critical_mass (the glossary's), the result critical_mass_parameter
    for key, attr in (("critical_mass_kg", "critical_mass_kg"),
                      ("critical_mass", "critical_mass_parameter"),
                      ("eccentricity", "eccentricity"), ("log_decrement", "log_decrement"),
                      ("mode_whirl_ratio", "mode_whirl_ratio")):
        assert _same(cli[key], getattr(py, attr)), key
    assert _same(study["smallest_margin"], py_onset.smallest_margin)
    assert _same(study["onset_speed_rpm"], py_onset.onset_speed_rpm)


def test_the_settings_act(tmp_path):
    """Each [model] setting changes the answer (so the agreement above is not vacuous): every
    file's critical mass differs from that of the file without a [model] table by more than
    1e-3 relative, a thousand times the tolerance of the route comparison.  (The beam foil
    differs least, 0.3 %: this top foil is very flexible, C = 2.8e-5.)"""
    answers = {}
    for setting, model in SETTINGS.items():
        bearing = load_bearing(_bearing_file(tmp_path, model))
        answers[setting] = stability(bearing, Rotor(MASS), OperatingPoint(SPEED, LOAD),
                                     grid=Grid.parse(GRID)).critical_mass_kg
    default = answers.pop("no [model] table")
    for setting, value in answers.items():
        assert abs(value / default - 1) > 1e-3, (setting, value, default)


def test_studies_naming_the_file_inherit_its_model_table(tmp_path):
    """The study kinds that name a bearing file and do not sweep an option take it from the
    file's [model] table, as the command line and the Python API do (0.2.0 filled the
    study's own defaults in: simple foil, mean law, η = 0, seam at 180°)."""
    path = _bearing_file(tmp_path, 'film = "periodic"\ndeflection_law = "local"\n'
                                   "loss_factor = 0.2\n")
    conventions = study_from_dict(
        {"kind": "onset_conventions", "title": "t", "source": "s", "bearing": path.name,
         "grid": GRID, "rotor_mass_kg": MASS, "load_newton": LOAD,
         "speed_range_rpm": list(RANGE), "seam_angles_deg": [120.0]},
        name="conventions", directory=path.parent)
    point = conventions.plan["points"][0]
    assert (point["foil"], point["deflection_law"], point["loss_factor"]) == \
        ("simple", "local", 0.2)
    design = study_from_dict(
        {"kind": "pitch_design", "title": "t", "source": "s", "bearing": path.name,
         "grid": GRID, "rotor_mass_kg": MASS, "load_newton": LOAD,
         "speed_range_rpm": list(RANGE), "min_film_thickness_um": 5.0,
         "pitch_range_mm": [2.0, 6.0], "half_length_range_mm": [0.5, 2.5],
         "thickness_range_um": [50.0, 200.0]}, name="design", directory=path.parent)
    assert design.plan.options.film == "periodic"            # the file's film
    stated = study_from_dict(
        {"kind": "pitch_design", "title": "t", "source": "s", "bearing": path.name,
         "grid": GRID, "rotor_mass_kg": MASS, "load_newton": LOAD,
         "speed_range_rpm": list(RANGE), "min_film_thickness_um": 5.0, "film": "seam",
         "seam_angle_deg": 150.0, "pitch_range_mm": [2.0, 6.0],
         "half_length_range_mm": [0.5, 2.5], "thickness_range_um": [50.0, 200.0]},
        name="design", directory=path.parent)
    assert (stated.plan.options.film, stated.plan.options.seam_angle_deg) == ("seam", 150.0)


# ------------------------------------------------------------- static and linear routes
#: the operating point and whirl ratios of the static and K, C routes (γ = 0 is left out:
#: with structural damping the damping there is NaN by definition)
STATIC_SPEED, WHIRL = 30000.0, (0.5, 1.0)
STATIC_KEYS = ("eccentricity", "attitude_angle_deg", "min_film")
COEFFICIENT_KEYS = tuple(f"{q}{a}{b}" for q in "kc" for a in "xy" for b in "xy")


def _cli_json(argv: list, capsys) -> dict:
    code = main(argv + ["--json"])
    out = capsys.readouterr().out
    assert code == 0, out
    return json.loads(out)


def _kind_study(kind: str, path: Path, extra: dict) -> object:
    """A one-variant study of ``kind`` naming the bearing file and stating no formulation:
    it must take the file's [model] table, as the CLI and the Python API do."""
    from gfbopt.studies.runner import compute

    data = {"kind": kind, "title": "route check", "source": "test", "bearing": path.name,
            "grid": GRID, "speeds_rpm": [STATIC_SPEED], "loads_newton": [LOAD],
            "variants": [{"label": "file"}], **extra}
    return compute(study_from_dict(data, name="routes", directory=path.parent))


@pytest.mark.parametrize("setting", list(SETTINGS))
def test_static_and_coefficient_routes_agree(setting, tmp_path, capsys):
    """``gfbopt static`` / ``gfbopt linear`` with ``--bearing``, the Python API
    (``analyses.bearing_model(load_bearing(FILE), speed)``, then ``solve_static`` and
    ``coefficients_point``) and the ``load_sweep`` / ``linear_coefficients`` studies give the
    same equilibrium and K, C for every [model] setting (same tolerance and reason as above)."""
    from gfbopt import analyses, solve_static
    from gfbopt.static import SolverCache

    path = _bearing_file(tmp_path, SETTINGS[setting])
    common = ["--bearing", str(path), "--speed-rpm", str(STATIC_SPEED), "--load-newton",
              str(LOAD), "--grid", GRID]
    cli_static = _cli_json(["static"] + common, capsys)
    cli_linear = _cli_json(["linear"] + common + ["--whirl-ratio", *map(str, WHIRL)], capsys)
    bearing = load_bearing(path)
    model = analyses.bearing_model(bearing, STATIC_SPEED)          # the Python route
    grid, cache = Grid.parse(GRID), SolverCache()
    py = solve_static(model, load=bearing.nondimensional_load(LOAD), grid=grid)
    py_k = analyses.coefficients_point(model, whirl_ratios=WHIRL,
                                       load=bearing.nondimensional_load(LOAD), grid=grid,
                                       cache=cache, geometry=bearing, speed_rpm=STATIC_SPEED)
    sweep = _kind_study("load_sweep", path, {}).tables["table.csv"].iloc[0]
    study_k = _kind_study("linear_coefficients", path, {"whirl_ratios": list(WHIRL)}
                          ).tables["coefficients.csv"]
    options = model.options()                     # the formulation every route states
    for out in (cli_static, cli_linear):
        assert {k: out[k] for k in ("foil", "film", "seam_angle_deg", "deflection_law",
                                    "loss_factor", "film_convention")} == \
            {k: options[k] for k in ("foil", "film", "seam_angle_deg", "deflection_law",
                                     "loss_factor", "film_convention")}
    for key in STATIC_KEYS:
        value = py.to_dict()[key]
        assert _same(cli_static[key], value), key
        assert _same(sweep[key], value), key
    assert _same(cli_linear["critical_mass"], py_k[0]["critical_mass"])
    assert _same(study_k["critical_mass"].iloc[0], py_k[0]["critical_mass"])
    for n, gamma in enumerate(WHIRL):
        row = py_k[n]
        cli_k, cli_c = cli_linear["stiffness"][f"{gamma:g}"], cli_linear["damping"][f"{gamma:g}"]
        for key in COEFFICIENT_KEYS:
            i, j = "xy".index(key[1]), "xy".index(key[2])
            assert _same((cli_k if key[0] == "k" else cli_c)[i][j], row[key]), (gamma, key)
            assert _same(study_k[key].iloc[n], row[key]), (gamma, key)


def test_the_dimensional_studies_state_their_convention():
    """The shipped load_sweep and linear_coefficients studies keep the thesis's seam on the
    maximum-film line explicitly (inheriting the bearing file would move them to 180°)."""
    from gfbopt.studies import load_study

    for name in ("ruscitto_static", "ruscitto_coefficients"):
        loaded = load_study(ROOT / "problems" / f"{name}.toml")
        _, models = loaded.plan
        assert {m.film for _, _, m in models} == {"seam"}
        assert {m.seam_angle_deg for _, _, m in models} == {None}       # the max-film seam
        assert {m.foil for _, _, m in models} == {"simple", "beam"}
