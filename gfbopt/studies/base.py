"""The pieces every study kind shares: the validated study, what a run produced, and the
construction of bearing models from a study's tables (with errors naming the file)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Optional

import pandas as pd

from ..errors import ParameterError
from ..inputs import BearingGeometry, BearingModel, Grid, load_bearing
from ..model_text import foil_words, friction_words, hardened
from .spec import Where


@dataclass(frozen=True)
class Study:
    """A validated study: its file (as given), name, kind, the checked specification with
    defaults filled in (:func:`gfbopt.studies.spec.validate`), and the folder that paths in
    it are relative to."""

    file: str
    name: str
    kind: str
    spec: dict
    directory: Path
    #: the command-line options that shaped it beyond its file (``--rotor …``, ``--top-speed
    #: …``, ``--grid …``), as typed: part of the command that reproduces or resumes it
    options: str = ""

    @property
    def command(self) -> str:
        """The command that runs this study again (``gfbopt run FILE`` and its options)."""
        return f"gfbopt run {self.file}" + (f" {self.options}" if self.options else "")

    @property
    def grid(self) -> Optional[Grid]:
        return Grid.parse(self.spec["grid"]) if "grid" in self.spec else None

    def where(self, *path) -> Where:
        """A :class:`Where` for errors about ``path`` (keys and list indices)."""
        w = Where(self.file)
        for p in path:
            w = w / p
        return w


#: where ``gfbopt run`` writes by default: user runs go to ``runs/`` (git-ignored); the
#: shipped ``results/`` are regenerated only on purpose (``--results results``, docs/studies.md)
DEFAULT_RESULTS = "runs"


@dataclass(frozen=True)
class RunContext:
    """How to run: number of worker processes, an optional progress callback (fraction
    done), the results folder (where sampled studies keep their store) and, for a kind that
    writes its own folder (``Kind.writes``), whether to write it (``write``, over files it
    did not write when ``force``)."""

    workers: int = 1
    progress: Optional[Callable[[float], None]] = None
    results_root: str = DEFAULT_RESULTS
    write: bool = False
    force: bool = False


@dataclass(frozen=True, eq=False)
class StudyResult:
    """What a study computed, before anything is written.

    tables : file name → DataFrame (written as CSV); figures : file name → matplotlib
    Figure; checks : internal-consistency checks of the computation (never a verdict on the
    design or bearing studied); comparisons : deviations from published values; options :
    the physics options of every variant; notes : computed remarks; verdict : the answer in
    words; answer : what the study answers, as ``summary.json`` keys (a design study:
    ``verdict``, ``stable_to_top_speed``, ``best_first_onset_rpm``, ``chosen_design``).
    """

    study: Study
    tables: dict = field(default_factory=dict)
    figures: dict = field(default_factory=dict)
    checks: list = field(default_factory=list)
    comparisons: list = field(default_factory=list)
    options: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)
    wall_time_s: float = 0.0
    #: the answer in words, written as the README's first line and the console's last
    #: (design studies)
    verdict: str = ""
    #: the study's answer as summary.json keys (design studies; empty otherwise)
    answer: dict = field(default_factory=dict)

    @property
    def checks_hold(self) -> bool:
        """True when every internal consistency check holds (says nothing of whether a
        design studied is good: that is the ``verdict``)."""
        return all(c["passed"] for c in self.checks)

    @property
    def passed(self) -> bool:
        """The same as :attr:`checks_hold` (the older name, kept for callers)."""
        return self.checks_hold

    @property
    def agreement(self) -> str:
        """'yes', 'no' or 'not compared' with the published reference."""
        if not self.comparisons:
            return "not compared"
        return "yes" if all(c["agrees"] for c in self.comparisons) else "no"


# ------------------------------------------------------------------ model building
def _model_kwargs(options: dict) -> dict:
    return {k: v for k, v in options.items() if k != "label"}   # seam_angle_deg in degrees


def build_model(options: dict, where: Where, *, rigid_when_no_compliance: bool = False
                ) -> BearingModel:
    """A BearingModel from merged model keys of a study file; an inconsistent combination
    (e.g. ``foil = "rigid"`` with S > 0) names the file and the table it came from.

    ``rigid_when_no_compliance``: a point with S = 0 is the rigid bearing whatever the
    variant's foil (used by tables that mix plain and compliant rows).
    """
    kwargs = _model_kwargs(options)
    if rigid_when_no_compliance and float(kwargs.get("compliance", 0.0)) == 0.0:
        kwargs["foil"] = "rigid"
    try:
        return BearingModel(**kwargs)
    except ParameterError as exc:
        raise (where / exc.name).error(exc.value, exc.rule) from None
    except TypeError as exc:
        raise where.error(kwargs, f"is not a valid model ({exc})") from None


def load_geometry(study: Study) -> BearingGeometry:
    """The bearing file named by the study (relative to the study file).  A file stating
    ``[journal]``/``[thermal]`` is refused in one line naming the study kind and the kinds
    and commands that read the tables (:data:`~gfbopt.inputs.bearing_file.RUNNING_ROUTES`):
    this kind would answer with the cold clearance."""
    from ..inputs.bearing_file import RUNNING_ROUTES, read_bearing_file
    from ..inputs.thermal_tables import RUNNING_TABLES

    path = study.directory / study.spec["bearing"]
    try:
        stated = read_bearing_file(path)            # every table and key checked
    except ParameterError as exc:
        raise study.where("bearing").error(str(study.spec["bearing"]),
                                           f"{exc.name}: {exc.rule}") from None
    running = [f"[{t.name}]" for t in RUNNING_TABLES if t.name in stated]
    if running:
        raise study.where("bearing").error(str(study.spec["bearing"]), (
            f"states {' and '.join(running)}, which the study kind '{study.kind}' does not "
            "read in this version (it would use the cold clearance and a constant "
            f"viscosity): the clearance at speed is read by {RUNNING_ROUTES}; use one of "
            "those, or a file without the tables"))
    try:
        return load_bearing(path)
    except ParameterError as exc:
        raise study.where("bearing").error(str(study.spec["bearing"]),
                                           f"{exc.name}: {exc.rule}") from None


def load_running_geometry(study: Study):
    """(the bearing, its :class:`~gfbopt.thermal.running.RunningSpec`) of the bearing file
    named by the study, for the kinds of
    :data:`~gfbopt.inputs.bearing_file.RUNNING_STUDY_KINDS`: the ``[journal]`` and
    ``[thermal]`` tables read and checked as every command reads them
    (:func:`gfbopt.thermal.files.load_running_bearing`); a file with neither gives the
    isothermal spec (the kind's route of today)."""
    from ..thermal.files import load_running_bearing

    try:
        return load_running_bearing(study.directory / study.spec["bearing"])
    except ParameterError as exc:
        raise study.where("bearing").error(str(study.spec["bearing"]),
                                           f"{exc.name}: {exc.rule}") from None


def merged(*tables: dict) -> dict:
    """Later tables override earlier ones (study ``[model]`` → variant → point)."""
    out: dict = {}
    for t in tables:
        out.update(t)
    return out


# ------------------------------------------------------------------ labels for people
def _foil_text(model: BearingModel) -> str:
    if model.is_rigid:
        return "rigid bearing"
    bumps = ""
    if hardened(model.options()):          # the words of every text report (model_text)
        bumps = foil_words(model.options()).split(" foil", 1)[1]
    if model.foil == "beam":
        return (f"beam top foil{bumps}, S = {model.compliance:.3g}, "
                f"C = {model.top_foil_coefficient:.3g}")
    return f"simple foil{bumps}, S = {model.compliance:.3g}"


def _parts(model: BearingModel) -> dict:
    law = "" if model.is_rigid else ("local deflection law" if model.deflection_law == "local"
                                     else "axial-mean deflection law")
    if model.film == "periodic":
        film = "periodic film"
    elif model.seam_angle_rad is None:
        film = "seam on the max-film line"
    else:
        film = f"seam {math.degrees(model.seam_angle_rad):g}° from the load"
    return {"foil": _foil_text(model), "film": film,
            "force": "Gümbel force" if model.subambient == "gumbel" else "full-film force",
            "law": law, "co": "compression-only bumps" if model.compression_only
            and not model.is_rigid else "",
            "friction": "" if model.is_rigid else friction_words(model.options())}


def variant_titles(models: dict) -> dict:
    """label → a description for people ("simple foil, S = 1"), naming only what differs
    between the variants of the study (``models``: label → a representative model)."""
    parts = {label: _parts(m) for label, m in models.items()}
    keys = ("foil", "film", "force", "law", "co", "friction")
    # the foil law and compression-only apply to foil bearings only: a rigid bearing's
    # blank does not make them vary
    compliant = [parts[label] for label, m in models.items() if not m.is_rigid]
    varying = [k for k in keys
               if len({p[k] for p in (compliant if k in ("law", "co", "friction")
                                       else parts.values())})
               > 1] or ["foil"]
    return {label: ", ".join(p[k] for k in varying if p[k]) or label
            for label, p in parts.items()}


def options_of(models_by_label: dict, grid: Optional[Grid], **extra) -> dict:
    """The physics options of every variant (foil, film, seam, force, law, compression) for
    the provenance block; variants whose points differ (e.g. rigid rows) list each."""
    variants = {}
    for label, models in models_by_label.items():
        distinct = []
        for m in models:
            o = {**m.options(), "top_foil_coefficient": m.top_foil_coefficient}
            if o not in distinct:
                distinct.append(o)
        variants[label] = distinct[0] if len(distinct) == 1 else distinct
    out = {"variants": variants, **extra}
    if grid is not None:
        out["grid"] = str(grid)
    return out


def frame(rows: list, columns_first: tuple = (), ensure: tuple = ()) -> pd.DataFrame:
    """Rows as a DataFrame with ``columns_first`` in front (those present); the columns
    ``ensure`` are added as NaN when no row has them (every point failed)."""
    table = pd.DataFrame.from_records(rows)
    for column in ensure:
        if column not in table.columns:
            table[column] = math.nan
    first = [c for c in columns_first if c in table.columns]
    return table[first + [c for c in table.columns if c not in first]]


@dataclass(frozen=True)
class Kind:
    """A study kind: ``plan(study)`` builds its points (no solving), ``run(study, plan,
    context)`` computes; ``parallel`` kinds use the process pool; a kind that ``writes``
    writes its folder itself inside its run when ``context.write`` (the design study, whose
    store lock must cover the writing)."""

    plan: Callable
    run: Callable
    parallel: bool = False
    writes: bool = False


@dataclass(frozen=True)
class LoadedStudy:
    """A validated study and its plan (models and points, built without solving)."""

    study: Study
    plan: object
