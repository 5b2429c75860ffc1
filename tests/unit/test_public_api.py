"""The public API from the top (gfbopt.load_rotor, the rotor analysis, the design entry point)
and the grid's string form with the command line's one-line message."""
import inspect
import subprocess
import sys
from pathlib import Path

import pytest

import gfbopt
from gfbopt import Grid, ParameterError, as_grid
from gfbopt.cli import main

ROOT = Path(__file__).resolve().parents[2]
BLOWER = ROOT / "problems" / "rotors" / "blower.toml"
RUSCITTO = ROOT / "problems" / "bearings" / "ruscitto.toml"
MALFORMED = ["72x", "72-20", "72x20x3", "x20", "72 20", "7.2x20", "²x20", ""]


def test_load_rotor_from_the_top_in_a_fresh_interpreter():
    """As the issue states it: ``python -c "import gfbopt; gfbopt.load_rotor"``, and the
    lazy names stay out of ``import gfbopt`` (the rotor layer is loaded on first use)."""
    code = ("import sys, gfbopt; assert 'gfbopt.rotor' not in sys.modules; "
            "gfbopt.load_rotor; from gfbopt import analyse_rotor, run_study, stability; "
            "assert 'gfbopt.rotor' in sys.modules; print(gfbopt.load_rotor.__module__)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT)
    assert out.stdout.strip() == "gfbopt.inputs.rotor_system"


def test_top_level_names_are_the_library_functions():
    from gfbopt.inputs.rotor_system import load_rotor
    from gfbopt.rotor import analysis, onset
    from gfbopt.rotor.analyse import analyse_rotor
    from gfbopt.studies import run_study
    assert gfbopt.load_rotor is load_rotor
    assert gfbopt.run_study is run_study
    for top, inner in ((gfbopt.stability, analysis.stability),
                       (gfbopt.onset_speed, onset.onset_speed),
                       (gfbopt.analyse_rotor, analyse_rotor)):
        assert top.__wrapped__ is inner           # same function, grid strings read first
        assert top.__doc__ == inner.__doc__
        assert inspect.signature(top) == inspect.signature(inner)
    assert set(gfbopt.__all__) <= set(dir(gfbopt))
    with pytest.raises(AttributeError, match="no attribute 'load_rotr'"):
        gfbopt.load_rotr


def test_load_rotor_reads_the_study_rotor():
    system = gfbopt.load_rotor(BLOWER)
    assert system.body.mass == 3.2                 # the 3.2 kg blower rotor of the README
    assert len(system.bearings) == 2


@pytest.mark.parametrize("text, expected", [("72x20", Grid(72, 20)), (" 36 X 10 ", Grid(36, 10)),
                                            (Grid(48, 12), Grid(48, 12))])
def test_grid_strings_and_grids(text, expected):
    assert as_grid(text) == expected
    assert as_grid(str(expected)) == expected      # str(Grid) round-trips


@pytest.mark.parametrize("text", MALFORMED)
def test_malformed_grid_string_gets_the_command_lines_message(text, capsys):
    """The API's message is the CLI's ``--grid`` line, word for word (not 'must be a Grid')
    but for the name: the CLI names the flag as typed (``--grid``), the API its keyword
    (``grid``); raised before anything is read or solved (the bearing and rotor here are not
    even valid)."""
    assert main(["stability", "--bearing", str(RUSCITTO), "--rotor-mass-kg", "2",
                 "--speed-rpm", "30000", "--grid", text]) == 2
    cli_line = capsys.readouterr().err.strip().removeprefix("gfbopt: error: ")
    assert cli_line == f"--grid = {text!r}: must be written NTHETAxNZ, e.g. 72x20"
    for call in (lambda: gfbopt.stability(None, None, None, grid=text),
                 lambda: gfbopt.onset_speed(None, None, None, (1, 2), grid=text),
                 lambda: gfbopt.analyse_rotor(None, (1, 2), grid=text),
                 lambda: gfbopt.load_capacity(None, 1.0, 1.0, grid=text),
                 lambda: gfbopt.lift_off_speed(None, 1.0, 1.0, grid=text),
                 lambda: gfbopt.rotor_orbit(None, 1.0, 1.0, grid=text),
                 lambda: gfbopt.rotor_ramp(None, 1.0, 2.0, 1.0, grid=text),
                 lambda: gfbopt.solve_static(None, eccentricity=0.5, grid=text),
                 lambda: gfbopt.solver_for(None, text),
                 lambda: as_grid(text)):
        with pytest.raises(ParameterError) as info:
            call()
        assert "--" + str(info.value) == cli_line


def test_grid_of_another_type_names_both_forms():
    with pytest.raises(ParameterError, match=r"^grid = \(72, 20\): must be a gfbopt Grid or a "
                                             r"string written NTHETAxNZ, e.g. 72x20$"):
        gfbopt.stability(None, None, None, grid=(72, 20))
    with pytest.raises(ParameterError, match=r"^grid n_z = 21: must be even"):
        gfbopt.analyse_rotor(None, (1, 2), grid="72x21")   # the Grid's own rules still apply


def test_static_solver_functions_take_grid_strings():
    model = gfbopt.BearingModel(bearing_number=1.0, compliance=0.0)
    assert gfbopt.solver_for(model, "24x8").grid == Grid(24, 8)
    by_text = gfbopt.solve_static(model, eccentricity=0.5, grid="24x8")
    by_grid = gfbopt.solve_static(model, eccentricity=0.5, grid=Grid(24, 8))
    assert by_text.success and by_text.load == by_grid.load


def test_a_grid_string_reaches_the_solver():
    """``grid="24x8"`` gives the same answer as ``Grid(24, 8)`` (a real solve, coarse grid)."""
    bearing = gfbopt.load_bearing(RUSCITTO)
    point = gfbopt.OperatingPoint(30000.0, 20.0)
    by_text = gfbopt.stability(bearing, gfbopt.Rotor(2.0), point, grid="24x8")
    by_grid = gfbopt.stability(bearing, gfbopt.Rotor(2.0), point, grid=Grid(24, 8))
    finer = gfbopt.stability(bearing, gfbopt.Rotor(2.0), point, grid=Grid(36, 10))
    assert by_text.critical_mass_kg == by_grid.critical_mass_kg
    # the grid was used, not dropped: another grid moves the critical mass by > 0.1 %
    assert abs(finer.critical_mass_kg / by_grid.critical_mass_kg - 1) > 1e-3
