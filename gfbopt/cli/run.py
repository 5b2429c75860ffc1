"""``gfbopt run``: named studies from ``problems/`` into ``results/``.

Every file given is validated (schema, values, models) before the first study starts, so a
mistake in the tenth file costs no solving of the first nine.  One line per study as it
finishes; a progress bar on a terminal (nothing when stderr is not a TTY).  Exit status 0
when every internal check passed, 1 when one failed, 2 for a mistake in a study file.

Sampled studies (``kind = "sweep"``, :mod:`gfbopt.studies.doe`) also take ``--resume``
(compute only the points not yet in ``RESULTS/NAME/store/``) and ``--scheduler ADDRESS`` (run
on a Dask distributed cluster; an unreachable address is one line and exit 2, nothing
written).  Other kinds run on the local executor whatever these options say.
"""
from __future__ import annotations

import os


def _default_workers() -> int:
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def _workers(text: str) -> int:
    import argparse

    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"workers = {text!r}: must be an integer") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"workers = {value}: must be >= 1")
    return value


def register(subparsers) -> None:
    run = subparsers.add_parser("run", help="run named studies: gfbopt run problems/NAME.toml")
    run.add_argument("problems", nargs="+", help="study files (problems/NAME.toml)")
    run.add_argument("--results", default="results", help="output folder (default results/)")
    run.add_argument("--workers", type=_workers, default=None,
                     help="worker processes for the studies whose points are independent "
                     "(stability maps); default: the number of available cores")
    run.add_argument("--resume", action="store_true",
                     help="sampled studies: keep the points already stored in "
                     "RESULTS/NAME/store/ and compute only the others (refused when the store "
                     "belongs to another study file)")
    run.add_argument("--scheduler", metavar="ADDRESS", default=None,
                     help="sampled studies: run on the Dask distributed scheduler at ADDRESS "
                     "(e.g. tcp://10.0.0.5:8786) instead of the local process pool")
    run.set_defaults(handler=run_studies)


def run_studies(args) -> int:
    from ..studies import load_study, run_study, summary_line
    from ..studies.doe import KINDS as SAMPLED
    from ..studies.doe import run_sampled
    from .common import progress_bar

    loaded = [load_study(path) for path in args.problems]      # all validated first
    workers = args.workers or _default_workers()
    client = None
    if args.scheduler and any(s.study.kind in SAMPLED for s in loaded):
        from ..parallel import connect_scheduler

        client = connect_scheduler(args.scheduler)             # before anything is written
    failed = 0
    try:
        for study in loaded:
            if study.study.kind in SAMPLED:
                result = run_sampled(study, args.results, workers=workers, client=client,
                                     scheduler=args.scheduler, resume=args.resume,
                                     progress=progress_bar(study.study.name))
            else:
                result = run_study(study, results_root=args.results, workers=workers,
                                   progress=progress_bar(study.study.name))
            print(summary_line(result, f"{args.results}/{study.study.name}/"), flush=True)
            failed += not result.passed
    finally:
        if client is not None:
            client.close()
    return 1 if failed else 0

