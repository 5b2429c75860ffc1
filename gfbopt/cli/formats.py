"""``gfbopt formats``: the user documentation of the input files and the study kinds, printed
from the schemas the validators use (:mod:`gfbopt.file_formats`)::

    gfbopt formats                 # the pages and the study kinds
    gfbopt formats bearing_file    # one page (Markdown)
    gfbopt formats --kinds         # the study kinds, one per line
"""
from __future__ import annotations

from ..errors import ParameterError


def register(subparsers) -> None:
    sub = subparsers.add_parser("formats", help="the input file formats and study kinds "
                                "(generated from the validators' schemas)")
    sub.add_argument("page", nargs="?", default=None, help="a page to print, e.g. "
                     "bearing_file or study_file")
    sub.add_argument("--kinds", action="store_true", help="list the study kinds")
    sub.set_defaults(handler=run)


def run(args) -> int:
    from ..file_formats import PAGES
    from ..studies.runner import KINDS

    if args.kinds:
        print("\n".join(sorted(KINDS)))
        return 0
    if args.page is None:
        print("file formats (gfbopt formats NAME prints one; docs/formats/ has them all):")
        for name in PAGES:
            print(f"  {name.removesuffix('.md')}")
        print("study kinds (the `kind` of a study file; gfbopt formats study_file):")
        print("  " + ", ".join(sorted(KINDS)))
        return 0
    name = args.page if args.page.endswith(".md") else f"{args.page}.md"
    if name not in PAGES:
        import difflib

        close = difflib.get_close_matches(name, list(PAGES), n=1)
        hint = f" (did you mean '{close[0].removesuffix('.md')}'?)" if close else ""
        raise ParameterError("page", args.page, "is not a file format: one of "
                             + ", ".join(p.removesuffix(".md") for p in PAGES) + hint)
    print(PAGES[name]())
    return 0
