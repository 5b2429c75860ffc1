"""``gfbopt run``: named studies from ``problems/`` into ``results/``."""
from __future__ import annotations


def register(subparsers) -> None:
    run = subparsers.add_parser("run", help="run named studies: gfbopt run problems/NAME.toml")
    run.add_argument("problems", nargs="+", help="study files (problems/NAME.toml)")
    run.add_argument("--results", default="results", help="output folder (default results/)")
    run.set_defaults(handler=run_studies)


def run_studies(args) -> int:
    from ..studies import run_study

    failed = 0
    for path in args.problems:
        summary = run_study(path, results_root=args.results)
        print(summary.report())
        failed += not summary.passed
    return 1 if failed else 0
