"""Study kind ``rotor_bearing_design``: design both bearings of a rotor against its top speed
— which bearing pair keeps the rotor stable to its top speed, at what drag and film margin,
and if none does, how far short the best one falls.

The study file (validated by :mod:`gfbopt.design.rotor_spec`) names a rotor file on two
bearings, the lowest and top speeds, the goal, the limits, the design variables and the
search.  A run:

1. searches the design space on the coarse ``search_grid`` with a real optimiser
   (:func:`gfbopt.design.optimiser.optimise`: pymoo NSGA-II for the Pareto front of first
   onset against power loss, or GP Bayesian optimisation of one objective), every evaluation
   streamed into ``RESULTS/NAME/store/`` (resumable: a killed run continues with the
   evaluations it holds, :func:`run_design` with ``resume=True``), through the run's pool;
2. chooses a design (stable to the top speed at the least power loss if any design is, else
   the highest first onset) and states why;
3. checks the chosen and front designs for robustness (± manufacturing tolerances and the
   loss-factor band, a Latin-hypercube sample: worst case and 5th percentile beside the
   nominal onset) and re-evaluates them on the default ``grid`` (grid honesty: the
   difference is reported and the verdict names both grids);
4. writes the verdict in words as the README's first line (and the console's last line,
   and ``verdict``, ``stable_to_top_speed``, ``best_first_onset_rpm`` and ``chosen_design``
   in ``summary.json``), the tables (every evaluation, with the store's columns; the front,
   the robustness and the default-grid check) and figures that mark the top speed.

The run holds the store's lock from the search to the last file written, so a second run of
the same study into the same folder is refused (one line) whatever phase the first is in.  A
design lost by the executor (workers that keep dying) stops the run with the command that
resumes it (:class:`gfbopt.runtime.InfrastructureError`); nothing is told to the optimiser
about a design nobody evaluated.  The internal checks (every design stored once, the chosen
design reproduced) check the computation; whether a design is good is the verdict's.

When no design is stable to the top speed, the chosen one is run at the top speed in time
(the rotor transient, :func:`gfbopt.design.robustness.whirl_at_top_speed`): the
verdict gives its whirl limit cycle at each bearing and the minimum film, or the contact.
"""
from __future__ import annotations

import hashlib
import json
import time
from pathlib import Path

from ..errors import ParameterError
from ..design.rotor_objectives import design_outputs
from ..design.rotor_spec import BORE_KINDS, GOALS, plan_rotor_design
from ..design.search import METHODS
from .base import Kind, LoadedStudy, RunContext, Study, StudyResult
from .work import LEVER_EVALUATIONS  # noqa: F401  (one lever's evaluations, the guard's too)
from .spec import GRID, UNSET, opt, req

VARIABLE = {
    "name": req("string", "design variable (gfbopt.design.rotor_objectives.DESIGN_VARIABLES; "
                "'A:name' for bearing A only)"),
    "low": opt("number", None, "low end of the range (in the variable's unit)"),
    "high": opt("number", None, "high end of the range"),
    "scale": opt("string", "linear", "linear or log", choices=("linear", "log")),
    "values": opt("numbers", None, "discrete levels (whole-number variables)"),
}
SEARCH = {
    "method": opt("string", "nsga2", "nsga2 (front) or bayes (one objective)",
                  choices=METHODS),
    "budget": opt("integer", 24, "designs evaluated", minimum=1),
    "population": opt("integer", 8, "NSGA-II designs per generation", minimum=4),
    "startup": opt("integer", 6, "Latin-hypercube designs before the GP proposes (bayes)",
                   minimum=2),
    "batch": opt("integer", 2, "designs proposed at once (bayes; the number of workers)",
                 minimum=1),
    "seed": opt("integer", 0, "seed of the search", minimum=0),
}
SEARCH_DEFAULT = {"method": "nsga2", "budget": 24, "population": 8, "startup": 6, "batch": 2,
                  "seed": 0}
ROBUSTNESS = {
    "tolerances": opt("mapping", {}, "± manufacturing tolerance per design variable (its "
                      "unit)", values=req("number", "half-width", positive=True)),
    "samples": opt("integer", 8, "Latin-hypercube samples per design checked", minimum=2),
    "seed": opt("integer", 0, "seed of the samples", minimum=0),
    "designs": opt("integer", 3, "front designs checked (the chosen one first)", minimum=1),
}
ROBUSTNESS_DEFAULT = {"tolerances": {}, "samples": 8, "seed": 0, "designs": 3}
BORE = {
    "kind": opt("string", "shims", "preload form", choices=BORE_KINDS),
    "count": opt("integer", 3, "shims or lobes when preload_count is not a variable",
                 minimum=1),
    "width_deg": opt("number", 60.0, "angular width of each shim [deg]", positive=True),
    "offset_deg": opt("number", 0.0, "centre of the first shim or lobe from the load [deg]"),
}
BORE_DEFAULT = {"kind": "shims", "count": 3, "width_deg": 60.0, "offset_deg": 0.0}
LEVER = {
    "low": opt("number", UNSET, "lowest value the lever can physically take (its unit)"),
    "high": opt("number", UNSET, "highest value the lever can physically take"),
    "direction_deg": opt("number", UNSET, "side_load_n: direction from +x in the direction "
                         "of rotation [deg] (default: the gravity's)"),
    "position": opt("number", UNSET, "side_load_n: axial position from the centre of "
                    "gravity [m] (default 0)"),
}

SCHEMAS = {"rotor_bearing_design": {
    **GRID,
    "search_grid": opt("grid", "36x10", "coarse grid of the search (the default grid "
                       "re-evaluates the chosen and front designs)"),
    "regrid_designs": opt("integer", 3, "designs re-evaluated on the default grid (the "
                          "chosen one, then the front's best onsets)", minimum=1),
    "limit_cycle_revolutions": opt("number", 200.0, "revolutions of the orbit at the top "
                                   "speed when no design is stable there (0: none)",
                                   minimum=0.0),
    "limit_cycle_grid": opt("grid", "72x20", "grid of that orbit (the rotor transient's "
                            "documented grid)"),
    "rotor": req("string", "rotor file (SI), relative to the study file"),
    "speed_range_rpm": req("numbers", "[lowest, top] running speeds [rpm]", length=2),
    "search_high_rpm": opt("number", None, "top of the onset search [rpm] (default 1.25 × "
                           "top speed)", positive=True),
    "goal": opt("string", "front", "front | max_onset | stable_then_min_power",
                choices=GOALS),
    "loss_factor_band": opt("numbers", [0.0, 0.0], "[low, high] of the uncertain loss "
                            "factor η; the search uses the low end", length=2),
    "heaviest_load_factor": opt("number", 1.0, "heaviest load over the static load of the "
                                "film check", positive=True),
    "min_film_um": req("number", "least minimum film at the lowest speed and heaviest "
                       "load [µm]", positive=True),
    "lift_off_film_um": opt("number", None, "h_min of the lift-off speed [µm]",
                            positive=True),
    "max_lift_off_speed_rpm": opt("number", None, "largest lift-off speed [rpm]",
                                  positive=True),
    "capacity_film_um": opt("number", None, "h_min of the load capacity at the lowest "
                            "speed [µm]", positive=True),
    "min_capacity_margin": opt("number", None, "least load capacity over static load [-]",
                               positive=True),
    "allowable_stress_mpa": opt("number", None, "bump bending stress limit [MPa]",
                                positive=True),
    "sag_limit": opt("number", None, "top-foil sag limit over the clearance κ_c [-]",
                     positive=True),
    "design_pressure_bar": opt("number", 1.0, "gauge pressure of the stress and sag checks "
                               "[bar]", positive=True),
    "gap_mm": opt("number", 0.2, "flat gap between bumps: 2 l0 + gap ≤ pitch [mm]",
                  minimum=0.0),
    "pitch_range_mm": opt("numbers", [2.0, 6.0], "bump pitch range of the geometric "
                          "program [mm] (compliance variable)", length=2),
    "half_length_range_mm": opt("numbers", [0.5, 3.0], "half bump length range [mm]",
                                length=2),
    "thickness_range_um": opt("numbers", [50.0, 200.0], "bump thickness range [µm]",
                              length=2),
    "pad_offset_deg": opt("number", 180.0, "leading end of the first pad from the load "
                          "[deg] (pads variable)"),
    "zone_edges_deg": opt("numbers", None, "edges of the bump zones round the bearing [deg "
                          "from the load line], e.g. [0, 120, 240, 360]: per-zone bump "
                          "variables zoneK_bump_pitch_mm, zoneK_bump_half_length_mm, "
                          "zoneK_bump_thickness_um (zone K between edges K and K + 1)"),
    "bore": opt("table", BORE_DEFAULT, "the preload's form", keys=BORE),
    "variables": req("tables", "design variables and their ranges", keys=VARIABLE),
    "search": opt("table", SEARCH_DEFAULT, "the optimiser", keys=SEARCH),
    "robustness": opt("table", ROBUSTNESS_DEFAULT, "the tolerance check", keys=ROBUSTNESS),
    "what_it_would_take": opt("mapping", {}, "levers outside the design space and their "
                              "physical bounds, e.g. loss_factor = {low = 0, high = 0.5}: "
                              "when no design is stable to the top speed, the smallest "
                              "change of each that makes the chosen one stable "
                              "(gfbopt.design.what_it_takes)",
                              values=req("table", "the lever's bounds in its unit",
                                         keys=LEVER)),
}}


#: keys that do not change a stored evaluation (words, and what happens after the search)
AFTER_SEARCH = ("title", "source", "notes", "name", "robustness", "grid", "regrid_designs",
                "limit_cycle_revolutions", "limit_cycle_grid", "what_it_would_take")


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest() if path.is_file() else ""


def design_hash(study: Study) -> str:
    """What the stored evaluations depend on: the validated spec (except
    :data:`AFTER_SEARCH`), the rotor file and its bearing files (content), and gfbopt's
    major.minor version."""
    from ..inputs import read_toml
    from ..version import __version__

    from ..design.optimiser import BOOK_KEEPING
    from ..design.rotor_objectives import OUTPUTS

    spec = {k: v for k, v in study.spec.items() if k not in AFTER_SEARCH}
    rotor = study.directory / study.spec["rotor"]
    files = {"rotor": _digest(rotor)}
    try:
        for k, b in enumerate(read_toml(rotor).get("bearings", [])):
            files[f"bearing{k}"] = _digest(rotor.parent / str(b.get("file", "")))
    except (ParameterError, OSError):  # an unreadable rotor file is refused by the plan
        pass
    version = ".".join(__version__.split(".")[:2])
    columns = [*BOOK_KEEPING, *OUTPUTS]          # a store with other columns is not resumed
    text = json.dumps({"spec": spec, "files": files, "version": version, "columns": columns},
                      sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()


def plan(study: Study):
    """Validate the study before any solve
    (:func:`gfbopt.design.rotor_spec.plan_rotor_design`, and the levers of
    ``[what_it_would_take]``, :func:`gfbopt.design.what_it_takes.parse_levers`)."""
    from ..design.lever_runs import check_starts
    from ..design.what_it_takes import parse_levers

    p = plan_rotor_design(study, design_hash(study))
    levers = parse_levers(study.spec.get("what_it_would_take") or None, study.file,
                          tuple(b.name for b in p.system.bearings), tuple(p.problem.names))
    check_starts(tuple(v for v in levers if v.name not in p.problem.names
                       and v.name.split(":")[-1] not in p.problem.names),
                 p.system, p.settings, study.file)
    return p


#: cost of an evaluation against one on a grid with ``cells`` times the nodes: measured on
#: the blower (36x10 1.03 s, 72x20 1.84 s, 144x36 5.28 s CPU, one design), ≈ cells^0.6
GRID_COST_EXPONENT = 0.6
#: cost of 100 revolutions of the orbit at the top speed, in design evaluations on the
#: orbit's grid (measured on the blower at 72x20: 0.18 s CPU per revolution at 45,000 rpm,
#: 0.28 s at 12,000 rpm, 1.84 s per evaluation); an orbit that ends at contact is shorter:
#: until it ends the ETA is an upper bound, then it is re-based on the work left
#: (gfbopt.progress.Stages)
ORBIT_COST_PER_100_REVOLUTIONS = 10.0




def grid_cost(grid, reference) -> float:
    """Cost of one design evaluation on ``grid`` over one on ``reference``."""
    return ((grid.n_theta * grid.n_z) / (reference.n_theta * reference.n_z)) \
        ** GRID_COST_EXPONENT


def run_stages(p, workers: int, levers: int = 0) -> list:
    """The stages of a design run weighed by the evaluations each will do (at most: fewer
    designs may need checking), the cost of one on its grid and the workers running them
    at once (:class:`gfbopt.progress.Stage`); ``levers``: those of ``[what_it_would_take]``."""
    from ..progress import Stage

    s, r = p.settings, p.robustness
    per_batch = p.search.population if p.search.method == "nsga2" else p.search.batch
    ends = len(set(p.loss_factor_band) - {s.loss_factor})
    samples = r.samples if r.tolerances else 0
    tolerances = r.designs * (ends + samples) if (r.tolerances or ends) else 0
    orbit = (grid_cost(p.limit_cycle_grid, s.grid) * ORBIT_COST_PER_100_REVOLUTIONS
             * p.limit_cycle_revolutions / 100.0)
    return [Stage("search", p.search.budget, 1.0, min(workers, per_batch)),
            Stage("whirl at top speed", 1 if p.limit_cycle_revolutions > 0 else 0, orbit),
            Stage("default-grid check", p.regrid_designs,
                  grid_cost(p.default_settings.grid, s.grid), workers),
            Stage("tolerances", tolerances, 1.0, workers),
            *([Stage("what it would take", levers * LEVER_EVALUATIONS, 1.0)] if levers
              else []),
            Stage("reproduction", 1, 1.0)]


def resume_command(study: Study, results_root) -> str:
    """The command that resumes this design run into ``results_root``."""
    from .base import DEFAULT_RESULTS

    where = "" if str(results_root) == DEFAULT_RESULTS else f" --results {results_root}"
    return f"{study.command}{where} --resume"


def run_design(loaded: LoadedStudy, results_root="results", *, workers: int = 1,
               client=None, resume: bool = False, progress=None,
               write: bool = True, force: bool = False) -> StudyResult:
    """Run the design study into ``results_root/NAME/`` (module docstring); ``resume``
    keeps the evaluations of an earlier (killed) run of the same study.  The store's lock
    is held until every file is written; a design the executor lost raises
    :class:`gfbopt.runtime.InfrastructureError` naming the command that resumes."""
    from ..design.optimiser import executor, optimise, store_schema
    from ..design.rotor_objectives import evaluate_rotor_design
    from ..doe.store import ResultStore, lock_store
    from ..progress import Stages
    from ..provenance import provenance
    from ..runtime import InfrastructureError
    from .rotor_report import report

    study, p = loaded.study, loaded.plan
    out = Path(results_root) / study.name
    t0 = time.perf_counter()
    run_tasks = executor(workers, client)
    stages = Stages(progress, run_stages(p, workers,
                                         len(study.spec.get("what_it_would_take") or {})))
    with lock_store(out / "store"):                 # the whole run: search, report, files
        store = ResultStore.create(out / "store", study=study.name, study_hash=p.study_hash,
                                   schema=store_schema(p.problem, design_outputs(p.settings)),
                                   resume=resume,
                                   metadata={"study_file": study.file, "provenance":
                                             provenance(grid=str(p.settings.grid))})
        try:
            search = optimise(p.problem, evaluate_rotor_design, p.search,
                              fixed={"system": p.system, "settings": p.settings},
                              store=store, run_tasks=run_tasks,
                              progress=stages.stage("search"))
            result = report(study, p, search, run_tasks, stages, t0, store, resume)
        except InfrastructureError as exc:
            kept = len(store.read())
            raise InfrastructureError(
                f"{study.name}: {exc}. {kept} evaluated designs are stored in "
                f"{out / 'store'}; `{resume_command(study, results_root)}` continues the "
                "design with them") from None
        if write:
            from .report import write_result

            write_result(result, Path(results_root), force=force)
    return result


def _run(study: Study, plan_, context: RunContext) -> StudyResult:
    """``gfbopt run``/``run_study``: a fresh store in the results folder, the run's pool."""
    root = getattr(context, "results_root", "results")
    return run_design(LoadedStudy(study, plan_), root, workers=context.workers,
                      progress=context.progress, write=context.write, force=context.force)


KINDS = {"rotor_bearing_design": Kind(plan, _run, parallel=True, writes=True)}
