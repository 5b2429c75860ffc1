"""``gfbopt run``: named studies from ``problems/`` into ``runs/`` (or ``--results DIR``).

Every file given is validated (schema, values, models, the size of sampled jobs) and every
results folder checked (writable, not foreign, not locked by another run) before the first
study starts, so a mistake in the tenth file costs no solving of the first nine.  One line
per study as it finishes; progress on stderr (a bar on a terminal, a status line every 10 s
otherwise).  One worker pool serves the whole run (:class:`gfbopt.parallel.WorkerPool`).

Exit status: 0 when every internal check passed, 1 when one failed (or the run could not
finish: workers or the Dask scheduler lost), 2 for a mistake in a study file or an option,
130 after Ctrl-C and 143 after SIGTERM — in both cases the finished rows of a sampled study
are written first and one line says what was kept and how to resume.

Rotor studies take ``--rotor FILE`` and ``--top-speed RPM``: the study run on the user's
rotor to that top speed, into ``RESULTS/NAME_on_<rotor>_to_<top>rpm/``, with the answer of a
copy of the study file with ``rotor``, the top of ``speed_range_rpm``, ``name`` and ``title``
edited (:mod:`gfbopt.studies.user_rotor`; a missing or invalid rotor file, a top speed not
above the study's lowest speed: one line, exit 2, before any solve).

Sampled studies (``kind = "sweep"``, :mod:`gfbopt.studies.doe`) also take ``--resume``
(compute only the points not yet in ``RESULTS/NAME/store/``) and ``--scheduler ADDRESS`` (run
on a Dask distributed cluster; docs/doe.md).  Other kinds run on the local executor whatever
these options say.
"""
from __future__ import annotations

import os
import sys

#: most worker processes per available core (each is a process with its own solvers)
WORKERS_PER_CORE = 4


def _cores() -> int:
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def _default_workers() -> int:
    """--workers when not given: the free cores (gfbopt.parallel.default_workers: the
    available cores minus the one-minute load average, rounded, at least 1)."""
    from ..parallel import default_workers

    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):  # pragma: no cover - no load average (Windows)
        load = 0.0
    return default_workers(_cores(), load)


def _positive(name: str):
    """argparse type: an integer >= 1, named by its flag ``--name`` in the error."""
    from .common import integer

    return integer(name, minimum=1)


def register(subparsers) -> None:
    run = subparsers.add_parser("run", help="run named studies: gfbopt run problems/NAME.toml")
    run.add_argument("problems", nargs="+", metavar="STUDY.toml",
                     help="study files (problems/NAME.toml)")
    run.add_argument("--results", default=None,
                     help="output folder (default runs/, which git ignores; the shipped "
                     "results/ are regenerated with --results results, docs/studies.md)")
    run.add_argument("--workers", type=_positive("workers"), default=None,
                     help="worker processes (one pool for the whole run); default: the "
                     "free cores (available cores minus the 1-minute load average, rounded, "
                     f"at least 1); at most {WORKERS_PER_CORE} per core unless --max-workers")
    run.add_argument("--max-workers", type=_positive("max-workers"), default=None,
                     help=f"raise the limit on --workers ({WORKERS_PER_CORE} × cores)")
    run.add_argument("--grid", default=None, metavar="NTHETAxNZ",
                     help="finite-difference grid of every study given (overrides the "
                     "files' grid, e.g. 72x20)")
    run.add_argument("--force", action="store_true",
                     help="overwrite files in RESULTS/NAME/ that gfbopt did not write")
    run.add_argument("--resume", action="store_true",
                     help="sampled and design studies: keep the points already stored in "
                     "RESULTS/NAME/store/ and compute only the others (refused when the "
                     "store holds other inputs)")
    run.add_argument("--max-points", type=_positive("max-points"), default=None,
                     help="sampled studies: raise the limit on the number of points "
                     "(default 100,000)")
    run.add_argument("--scheduler", metavar="ADDRESS", default=None,
                     help="sampled studies: run on the Dask scheduler at ADDRESS, e.g. "
                     "tcp://127.0.0.1:8786 (a scheduler is trusted code; docs/doe.md)")
    run.add_argument("--rotor", metavar="FILE", default=None,
                     help="rotor studies: run on this rotor file instead of the study's "
                     "(the result folder NAME_on_<rotor>, with _to_<top>rpm after it under "
                     "--top-speed; the same answer as a copy of the study file with rotor, "
                     "name and title changed)")
    run.add_argument("--top-speed", default=None, metavar="RPM",
                     help="rotor studies: the top of speed_range_rpm (above its lowest "
                     "speed)")
    run.set_defaults(handler=run_studies)


def _load(path: str, args):
    """Validate and plan one study file, with --grid, --max-points, --rotor and --top-speed
    applied (gfbopt.studies.user_rotor), refused when its estimated memory or time is above
    --max-memory-gb or --max-minutes."""
    from pathlib import Path

    from ..errors import ParameterError
    from ..studies import SCHEMAS, study_from_dict
    from ..studies.runner import read_study_file
    from .size import limits

    rotor, top = getattr(args, "rotor", None), getattr(args, "top_speed", None)
    if args.grid is None and args.max_points is None and rotor is None and top is None:
        from ..studies import load_study

        return load_study(path, limits(args))
    data = read_study_file(path)
    schema = SCHEMAS.get(data.get("kind"), {})
    if rotor is not None or top is not None:
        from ..studies.user_rotor import on_user_rotor

        if data.get("kind") not in SCHEMAS:        # the kind's own error first
            from ..studies.spec import validate

            validate(data, str(path))
        name = data["name"] if isinstance(data.get("name"), str) else Path(path).stem
        data = on_user_rotor(data, str(path), schema, rotor, top, name)
    if args.grid is not None:
        if "grid" not in schema and data.get("kind") in SCHEMAS:
            raise ParameterError("--grid", args.grid, f"{path}: a {data['kind']} study has "
                                 "no single grid (it names its grids itself)")
        data["grid"] = args.grid
    if args.max_points is not None:
        if "max_points" not in schema and data.get("kind") in SCHEMAS:
            raise ParameterError("--max-points", args.max_points, f"{path}: a {data['kind']} "
                                 "study has no points to cap (its size is set in the file, "
                                 "e.g. a design's search budget)")
        if "max_points" in schema:
            data["max_points"] = args.max_points
    import shlex

    typed = [(flag, value) for flag, value in (("--rotor", rotor), ("--top-speed", top),
                                                ("--grid", args.grid),
                                                ("--max-points", args.max_points))
             if value is not None]
    options = " ".join(f"{flag} {shlex.quote(str(value))}" for flag, value in typed)
    try:
        return study_from_dict(data, name=Path(path).stem, file=str(path),
                               directory=Path(path).parent, limits=limits(args),
                               options=options)
    except ParameterError as exc:
        raise _overridden(exc, str(path), args) from None


#: a study file's key that a flag of ``gfbopt run`` sets for the run → the flag
OVERRIDES = {"grid": "--grid", "max_points": "--max-points"}


def _overridden(exc, path: str, args):
    """A study's refusal of a key the command line set (``FILE: grid = '24x8'`` after
    ``--grid 24x8``) named by the flag typed, the file kept in the rule; else ``exc``."""
    from ..errors import ParameterError

    for key, flag in OVERRIDES.items():
        given = getattr(args, key, None)
        if given is not None and exc.name == f"{path}: {key}" and exc.value == given:
            return ParameterError(flag, given, f"{exc.rule} (set for {path}, whose {key} it "
                                  "replaces)")
    return exc


def _no_tqdm_monitor() -> None:
    """No tqdm monitor thread in this process (it re-tunes a bar's update interval every 10 s):
    the run's pool forks its workers only from a driver without other threads
    (gfbopt.parallel.start_method), else it takes the costlier forkserver."""
    if sys.stderr.isatty():
        import tqdm

        tqdm.tqdm.monitor_interval = 0


class _Progress:
    """A fraction callback drawing one study's progress (gfbopt.progress); the bar starts
    with the first report, so a study refused before any work prints nothing."""

    def __init__(self, name: str):
        self.name = name
        self.bar = None

    def __call__(self, fraction: float) -> None:
        from ..progress import progress

        if self.bar is None:
            _no_tqdm_monitor()
            self.bar = progress(total=100, desc=self.name, unit="%")
        step = int(round(100 * min(1.0, max(0.0, fraction)))) - self.bar.n
        if step > 0:
            self.bar.update(step)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _check_options(args, loaded) -> int:
    from ..errors import ParameterError
    from ..studies.doe import KINDS as SAMPLED

    workers = args.workers or _default_workers()
    limit = args.max_workers or WORKERS_PER_CORE * _cores()
    if workers > limit:
        raise ParameterError("--workers", workers, f"is more than {WORKERS_PER_CORE} × the "
                             f"{_cores()} available cores = {limit} (each worker is a process "
                             "with its own solvers, ~200 MB); raise the limit with "
                             "--max-workers")
    sampled = any(s.study.kind in SAMPLED for s in loaded)
    if args.scheduler is not None:
        from ..cluster import check_address

        check_address(args.scheduler)          # "" and ucx:// refused whatever the kinds
    from ..studies.rotor_design import KINDS as DESIGNS      # design runs resume too

    if args.resume and not sampled and not any(s.study.kind in DESIGNS for s in loaded):
        raise ParameterError("--resume", True, "applies to sampled and design studies "
                             "(kind = \"sweep\" or \"rotor_bearing_design\") only; none "
                             "is given")
    return workers


def run_studies(args) -> int:
    from ..parallel import InfrastructureError, Interrupted, WorkerPool, interrupt_on_signals
    from ..studies import run_study, summary_line
    from ..studies.base import DEFAULT_RESULTS
    from ..studies.doe import KINDS as SAMPLED
    from ..studies.doe import run_sampled
    from ..studies.report import prepare_output

    results = args.results or DEFAULT_RESULTS
    loaded = [_load(path, args) for path in args.problems]      # all validated first
    workers = _check_options(args, loaded)
    client = None
    if args.scheduler is not None and any(s.study.kind in SAMPLED or s.study.kind ==
                                          "rotor_bearing_design" for s in loaded):
        from ..cluster import quiet_logs
        from ..parallel import connect_scheduler

        quiet_logs()
        client = connect_scheduler(args.scheduler)             # before anything is written
    try:
        for study in loaded:                                    # every folder checked first
            prepare_output(results, study.study.name, force=args.force)
    except BaseException:
        if client is not None:
            client.close()
        raise
    failed = 0
    current = ""
    try:
        with interrupt_on_signals(), WorkerPool(workers):
            for study in loaded:
                current = study.study.name
                show = _Progress(current)
                try:
                    if study.study.kind == "rotor_bearing_design":    # resumable design
                        from ..studies.rotor_design import run_design

                        result = run_design(study, results, workers=workers,
                                            client=client, resume=args.resume,
                                            progress=show, force=args.force)
                    elif study.study.kind in SAMPLED:
                        result = run_sampled(study, results, workers=workers, client=client,
                                             scheduler=args.scheduler, resume=args.resume,
                                             progress=show, force=args.force)
                    else:
                        result = run_study(study, results_root=results, workers=workers,
                                           progress=show, force=args.force)
                finally:
                    show.close()
                print(summary_line(result, f"{results}/{study.study.name}/"), flush=True)
                failed += not result.passed
    except Interrupted as exc:
        report = exc.report or (f"{current}: stopped by {_signal_name(exc.signum)}; this "
                                "study's results are written when it ends, so none were "
                                "kept for it (studies reported above are complete)")
        print(f"gfbopt: interrupted: {report}", file=sys.stderr, flush=True)
        return exc.exit_status
    except InfrastructureError as exc:
        print(f"gfbopt: error: {exc}", file=sys.stderr, flush=True)
        return 1
    except OSError as exc:                  # a full disk, a folder removed under the run
        print(f"gfbopt: error: {current}: cannot write ({exc.strerror or exc}: "
              f"{exc.filename or '?'}); what was written is kept: free the space and run "
              "again (--resume for a sampled study)", file=sys.stderr, flush=True)
        return 1
    finally:
        if client is not None:
            _close(client)
    return 1 if failed else 0


def _close(client) -> None:
    """Close the Dask client without a traceback when its scheduler is already gone."""
    try:
        client.close(timeout=5)
    except Exception:  # noqa: BLE001 - nothing left to close cleanly
        pass


def _signal_name(signum: int) -> str:
    import signal

    return signal.Signals(signum).name
