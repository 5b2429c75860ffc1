"""Loading, validating and running studies.

    from gfbopt.studies import load_study, run_study, study_from_dict, compute
    run_study("problems/thesis_table_3_1.toml")          # writes runs/thesis_table_3_1/
    study = study_from_dict({...}, name="mine")          # a study built in Python
    result = compute(study, workers=2)                   # StudyResult: tables, checks, …

:func:`load_study` validates the file and builds every model and operating point (no
solving), so every mistake in a study file is found before any solve starts.
"""
from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path
from typing import Callable, Optional, Union

from ..errors import ParameterError
from ..guard import Limits, check
from ..inputs import read_toml
from . import design, maps, sweeps, tables, transients
from . import doe
from . import damping, stability
from . import rotor
from . import bearing_as_built
from . import rotor_design
from .base import DEFAULT_RESULTS, Kind, LoadedStudy, RunContext, Study, StudyResult
from .output import check_name
from .report import prepare_output, write_result
from .spec import SCHEMAS, validate
from .work import check_file_names, study_work


KINDS: dict[str, Kind] = {
    "static_table": Kind(tables.plan_static_table, tables.run_static_table),
    "profile": Kind(tables.plan_profile, tables.run_profile),
    "grid_convergence": Kind(tables.plan_grid_convergence, tables.run_grid_convergence),
    "concentric_impedance": Kind(tables.plan_concentric_impedance,
                                 tables.run_concentric_impedance),
    "load_sweep": Kind(sweeps.plan_load_sweep, sweeps.run_load_sweep),
    "linear_coefficients": Kind(sweeps.plan_linear_coefficients,
                                sweeps.run_linear_coefficients),
    "linear_map": Kind(maps.plan_map, maps.run_linear_map, parallel=True),
    "transient_map": Kind(maps.plan_map, maps.run_transient_map, parallel=True),
    "transient_points": Kind(maps.plan_transient_points, maps.run_transient_points,
                             parallel=True),
    "orbits": Kind(transients.plan_orbits, transients.run_orbits),
    "bifurcation": Kind(transients.plan_bifurcation, transients.run_bifurcation),
}


def register(family) -> None:
    """Add a family of study kinds defined in its own module: ``family.SCHEMAS`` (kind →
    schema, in the vocabulary of :mod:`.spec`) and ``family.KINDS`` (kind → :class:`Kind`).

    A kind's ``run(study, plan, context)`` gets a :class:`RunContext` (``workers``,
    ``progress``, ``results_root``); it should call :func:`gfbopt.parallel.run_points` with
    ``workers=context.workers``, which uses the run's one worker pool when ``gfbopt run``
    opened it (:class:`gfbopt.parallel.WorkerPool`)."""
    clash = set(family.KINDS) & set(KINDS)
    if clash or set(family.KINDS) != set(family.SCHEMAS):
        raise ValueError(f"study kinds of {family.__name__}: clash {sorted(clash)} or "
                         "schemas without runners")
    SCHEMAS.update(family.SCHEMAS)
    KINDS.update(family.KINDS)


for _family in (design, doe, stability, damping, rotor):
    register(_family)
register(bearing_as_built)
register(rotor_design)
assert set(KINDS) == set(SCHEMAS), "every schema has a runner and vice versa"


#: kinds whose plan reads their files and builds no points (cheap whatever the size): it runs
#: before the resource estimate, so a typo'd variable or a reversed speed range is reported as
#: itself rather than as a run too long to start
PLAN_FIRST = ("rotor_bearing_design", "rotor_two_bearings", "rotor_run_up")


def study_from_dict(data: dict, *, name: Optional[str] = None, file: str = "<dict>",
                    directory: Union[str, Path] = ".",
                    limits: Optional[Limits] = None, options: str = "") -> LoadedStudy:
    """Validate a study given as a dict (the same keys as a study file) and plan it.

    ``file`` names it in error messages; ``directory`` is where relative paths (a
    ``bearing`` file) are looked up.  A study whose estimated memory or time is above
    ``limits`` (:class:`gfbopt.guard.Limits`, default 4 GB and 60 min) is refused before it
    is planned (:mod:`.work`).  ``options``: the command-line options that shaped ``data``
    beyond its file (``--rotor …``), part of the commands its results print.
    """
    spec = validate(data, file)
    name = spec["name"] if spec["name"] is not None else (name or Path(file).stem)
    check_name(name, f"{file}: name")
    check_file_names(spec, directory, file)      # what no run can mean, then the estimate
    study = Study(file=file, name=name, kind=spec["kind"], spec={**spec, "name": name},
                  directory=Path(directory), options=options)
    if spec["kind"] in PLAN_FIRST:              # a mistake in the file before the time
        work = study_work(spec, file)
        memory = limits or Limits()
        check([replace(w, seconds=0.0) for w in work], memory)      # memory first
        plan = KINDS[study.kind].plan(study)
        check(work, limits)
        return LoadedStudy(study, plan)
    check(study_work(spec, file), limits)
    return LoadedStudy(study, KINDS[study.kind].plan(study))


def load_study(path: Union[str, Path], limits: Optional[Limits] = None) -> LoadedStudy:
    """Read, validate and plan the study file ``path``; any mistake raises one
    ParameterError naming the file and the key, before anything is solved (a study above
    ``limits`` too)."""
    path = Path(path)
    return study_from_dict(read_study_file(path), name=path.stem, file=str(path),
                           directory=path.parent, limits=limits)


def read_study_file(path: Union[str, Path]) -> dict:
    """The parsed study file; a file nested too deeply to parse (tomllib recurses) is one
    ParameterError, not a RecursionError."""
    try:
        return read_toml(path)
    except RecursionError:
        raise ParameterError("file", str(path), "is nested too deeply to be a study file"
                             ) from None


def compute(loaded: LoadedStudy, *, workers: int = 1,
            progress: Optional[Callable[[float], None]] = None,
            results_root: Union[str, Path] = DEFAULT_RESULTS, write: bool = False,
            force: bool = False) -> StudyResult:
    """Run a loaded study and return its results (nothing is written, except the store of
    a sampled or design study, kept in ``results_root/NAME/store/``; with ``write`` a kind
    that writes its own folder, ``Kind.writes``, writes it inside its run)."""
    kind = KINDS[loaded.study.kind]
    context = RunContext(workers=workers if kind.parallel else 1, progress=progress,
                         results_root=str(results_root), write=write, force=force)
    t0 = time.perf_counter()
    result = kind.run(loaded.study, loaded.plan, context)
    return replace(result, wall_time_s=time.perf_counter() - t0)


def run_study(path: Union[str, Path, LoadedStudy],
              results_root: Union[str, Path] = DEFAULT_RESULTS, *, workers: int = 1,
              progress: Optional[Callable[[float], None]] = None,
              force: bool = False) -> StudyResult:
    """Run a study file (or a loaded study) and write ``results_root/NAME/`` and the index.

    The folder is checked before computing (writable, not a symlink out of
    ``results_root``, no file gfbopt did not write unless ``force``; :mod:`.output`).
    Returns the :class:`StudyResult` (``checks_hold``, ``agreement``, tables, checks).
    """
    loaded = path if isinstance(path, LoadedStudy) else load_study(path)
    prepare_output(Path(results_root), loaded.study.name, force=force)
    result = compute(loaded, workers=workers, progress=progress, results_root=results_root,
                     write=True, force=force)
    if not KINDS[loaded.study.kind].writes:      # a kind that writes did so inside its run
        write_result(result, Path(results_root), force=force)
    return result


from . import rotor_transient  # noqa: E402  (rotor transients)

register(rotor_transient)
