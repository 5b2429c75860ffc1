"""Every file or folder a command writes is checked before anything is solved: a folder
target that is an existing file, a path where nothing can be created (``/proc``: os.access
says yes to root there, so the check creates and removes a file for real), a figure suffix
matplotlib cannot write, and a bearing name that would become part of a file name.  Each
refusal is one line, exit 2, and the command's handler never starts (it is replaced by one
that fails the test).  An existing file named as a file target is overwritten (the policy of
gfbopt.plotting.core.save_figure and of the CSV writers)."""
from __future__ import annotations

from pathlib import Path

import pytest
from cli_inprocess import run_cli

import gfbopt.cli.capacity as capacity
import gfbopt.cli.rotor as rotor
import gfbopt.cli.run as run
import gfbopt.cli.stability as stability
import gfbopt.cli.transient as transient
from gfbopt.errors import ParameterError

ROOT = Path(__file__).resolve().parents[2]
BLOWER = ROOT / "problems" / "rotors" / "blower.toml"
BEARING = str(ROOT / "problems" / "bearings" / "ruscitto.toml")
RUN_UP = ROOT / "problems" / "rotor_run_up.toml"
UNWRITABLE = "/proc"          # a folder in which nothing can be created, even by root

STABILITY = ["stability", "--bearing", BEARING, "--rotor-mass-kg", "2", "--load-newton", "20",
             "--speed-rpm", "30000", "--grid", "24x8"]
CAPACITY = ["capacity", "--bearing", BEARING, "--speed-rpm", "30000", "--min-film-um", "5",
            "--grid", "24x8"]
ORBIT = ["orbit", "--eccentricity", "0.4", "--bearing-number", "2", "--mass", "2",
         "--revolutions", "4", "--grid", "24x8"]
ROTOR = ["rotor", str(BLOWER), "--speed-range", "5000", "6000", "--campbell", "--grid",
         "24x8"]
ROTOR_ORBIT = ["rotor", str(BLOWER), "--orbit", "--speed-rpm", "13000", "--revolutions", "4",
               "--grid", "24x8"]


@pytest.fixture
def no_handler(monkeypatch):
    """Every command's handler fails the test if it starts."""
    def refuse(*args, **kwargs):
        raise AssertionError("the command started: its output paths must be refused first")
    for module, name in ((stability, "run"), (capacity, "run"), (transient, "run_orbit"),
                         (rotor, "run"), (run, "run_studies")):
        monkeypatch.setattr(module, name, refuse)


def _refused(args, option: str, says: str) -> str:
    r = run_cli(*args)
    err = r.stderr.strip()
    assert r.returncode == 2 and len(err.splitlines()) == 1, err
    assert err.startswith(f"gfbopt: error: {option} = ") and says in err, err
    assert r.stdout == ""
    return err


@pytest.mark.parametrize("args, option", [
    (STABILITY + ["--csv", f"{UNWRITABLE}/x.csv"], "--csv"),
    (CAPACITY + ["--figure", f"{UNWRITABLE}/f.png"], "--figure"),
    (CAPACITY + ["--csv", f"{UNWRITABLE}/c.csv"], "--csv"),
    (ORBIT + ["--plot", f"{UNWRITABLE}/o.png"], "--plot"),
    (ORBIT + ["--csv", f"{UNWRITABLE}/o.csv"], "--csv"),
    (ROTOR + ["--csv", f"{UNWRITABLE}/tables"], "--csv"),
    (ROTOR + ["--plot", f"{UNWRITABLE}/figures/campbell"], "--plot"),
    (ROTOR_ORBIT + ["--csv", f"{UNWRITABLE}/orbit"], "--csv"),
    (["run", str(RUN_UP), "--results", f"{UNWRITABLE}/runs"], "--results"),
], ids=lambda a: " ".join(map(str, a[:1] + a[-2:])) if isinstance(a, list) else a)
def test_a_path_where_nothing_can_be_created_is_refused_before_the_command(args, option,
                                                                        no_handler):
    err = _refused(args, option, "cannot be written: nothing can be created in '/proc'")
    assert "Traceback" not in err


@pytest.mark.parametrize("args, option", [
    (ROTOR, "--csv"), (ROTOR, "--plot"), (ROTOR_ORBIT, "--csv"), (ROTOR_ORBIT, "--plot")])
def test_an_existing_file_as_a_folder_target_is_refused_before_the_command(tmp_path, args,
                                                                          option, no_handler):
    target = tmp_path / "results.csv"
    target.write_text("kept\n")
    _refused(args + [option, str(target)], option, "is a file, not a folder")
    assert target.read_text() == "kept\n"              # nothing written over it
    below = tmp_path / "results.csv" / "inside"
    _refused(args + [option, str(below)], option, "is a file")


@pytest.mark.parametrize("args, option", [
    (ORBIT, "--plot"), (CAPACITY, "--figure")])
def test_a_figure_suffix_matplotlib_cannot_write_is_refused_before_the_command(
        tmp_path, args, option, no_handler):
    _refused(args + [option, str(tmp_path / "orbit.xyz")], option,
             "has a suffix matplotlib cannot write: use one of")


def _rotor_named(tmp_path, name: str) -> Path:
    text = BLOWER.read_text().replace("../bearings/", f"{(ROOT / 'problems/bearings').as_posix()}/")
    assert 'name = "A"' in text
    path = tmp_path / "named.toml"
    path.write_text(text.replace('name = "A"', f'name = "{name}"', 1))
    return path


@pytest.mark.parametrize("name", ["A/B", "..", "A\\\\B"])
def test_a_bearing_name_that_names_files_must_be_a_file_name(tmp_path, name, no_handler):
    path = _rotor_named(tmp_path, name)
    args = ["rotor", str(path), "--orbit", "--speed-rpm", "13000", "--revolutions", "4",
            "--grid", "24x8", "--plot", str(tmp_path / "figs")]
    _refused(args, f"{path}: bearing name", "cannot be part of a file name")
    assert not (tmp_path / "figs").exists()


def test_a_study_naming_files_after_a_bearing_refuses_the_name_before_planning(tmp_path):
    from gfbopt.studies import load_study

    rotor_file = _rotor_named(tmp_path, "A/B")
    study = tmp_path / "run_up.toml"
    study.write_text(RUN_UP.read_text().replace('rotor = "rotors/blower.toml"',
                                                f'rotor = "{rotor_file.as_posix()}"'))
    with pytest.raises(ParameterError, match="bearing name = 'A/B': cannot be part of a file"):
        load_study(study)


def test_the_writability_probe_leaves_nothing_behind(tmp_path, no_handler):
    """The folder is probed by creating a file: it is removed again (a refusal that comes
    later, here the figure's suffix, shows that the probe ran)."""
    _refused(ORBIT + ["--csv", str(tmp_path / "o.csv"), "--plot", str(tmp_path / "o.xyz")],
             "--plot", "suffix")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("option", ["--csv", "--plot"])
def test_an_existing_folder_is_a_folder_target(tmp_path, option, monkeypatch):
    """``gfbopt rotor --csv DIR`` / ``--plot DIR`` write several files in DIR: an existing
    folder is accepted (it was refused as "a directory: give a file name"), the command
    starts, and the probe leaves the folder as it was."""
    started = []
    monkeypatch.setattr(rotor, "run", lambda args: started.append(args) or 0)
    (tmp_path / "kept.txt").write_text("kept\n")
    r = run_cli(*ROTOR, option, str(tmp_path))
    assert r.returncode == 0 and len(started) == 1, r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["kept.txt"]
