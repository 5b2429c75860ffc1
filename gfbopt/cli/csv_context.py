"""The context of every CSV file a command writes: ``FILE.csv.json`` beside ``FILE.csv``.

A CSV alone does not say which gfbopt, which source commit, which command and options made
it, or what its columns mean.  Each command that writes a CSV (``gfbopt rotor --csv``,
``stability --csv``, ``capacity --csv``, ``orbit --csv``) or a ROSS table (``export-ross``)
writes beside it a sidecar named after the whole file name plus ``.json`` (``modes.csv`` →
``modes.csv.json``; never the name of the file itself nor of another output) holding:

=================  ==============================================================================
``file``           the CSV's file name
``read_with``      how to read it: ``pandas.read_csv(path)``, no options (the CSV has one
                   header row of column names and nothing else)
``columns``        column → ``{"unit", "meaning"}`` from the glossary
                   (:func:`gfbopt.glossary.describe`; unit null for a name not yet in it);
                   not for a ROSS table (ROSS's own keys, SI)
``provenance``     the block of the command's ``--json`` (:func:`gfbopt.provenance.provenance`):
                   version, source commit and dirty flag, date, conventions, and the options,
                   with ``command_line`` (as typed) and ``arguments`` (every option by its
                   flag, defaults included)
=================  ==============================================================================

The CSV stays a plain table (one header row), so ``pandas.read_csv`` reads it with no
options; the sidecar is the provenance mechanism of the ``--json`` outputs and of the
studies' ``summary.json``, extended to the CSV files.
"""
from __future__ import annotations

import json
from pathlib import Path
from typing import Iterable, Optional, Sequence

#: what a sidecar's name adds to its CSV's
SUFFIX = ".json"
#: the help text of every --csv option ends with this
HELP = "; beside each CSV its context FILE.csv.json (version, source commit, options, " \
       "column units; docs/cli_outputs.md)"
#: argparse's bookkeeping in the parsed namespace, not options
_NOT_OPTIONS = ("handler", "command", "option_flags", "command_line")


def sidecar_path(path) -> Path:
    """The context file of the CSV ``path``: the whole name plus ``.json``."""
    path = Path(path)
    return path.with_name(path.name + SUFFIX)


def arguments(args) -> dict:
    """Every option of the parsed ``args`` by its flag as typed (defaults included)."""
    flags = getattr(args, "option_flags", None) or {}
    return {flags.get(k, "--" + k.replace("_", "-")): v for k, v in sorted(vars(args).items())
            if k not in _NOT_OPTIONS}


def context_options(args, **options) -> dict:
    """The options of a command's provenance block: ``options`` with the command line as
    typed and every argument by its flag — the same for ``--json`` and the CSV sidecars."""
    line = getattr(args, "command_line", None)
    return {**options, "command_line": list(line) if line is not None else None,
            "arguments": arguments(args)}


def columns(names: Iterable[str], references: tuple = ()) -> dict:
    """column → {"unit", "meaning"} from the glossary; unit None for a name not in it."""
    from ..glossary import describe

    out = {}
    for name in names:
        try:
            unit, meaning = describe(str(name), references)
        except KeyError:         # never lose a computed result over a missing description
            unit, meaning = None, "not yet described in gfbopt/glossary.py"
        out[str(name)] = {"unit": unit, "meaning": meaning}
    return out


def write_context(path, names: Optional[Sequence[str]], options: dict,
                  read_with: str = "pandas.read_csv(path)") -> Path:
    """Write the context file of ``path`` (a CSV whose columns are ``names``; ``names``
    None for another table, e.g. a ROSS file, which says ``read_with``); ``options`` are the
    provenance options of the command's ``--json`` (:func:`context_options`)."""
    from ..provenance import jsonable, provenance

    path = Path(path)
    side = sidecar_path(path)
    data = {"file": path.name, "read_with": read_with,
            **({} if names is None else {"columns": columns(names)}),
            "provenance": provenance(**options)}
    side.write_text(json.dumps(jsonable(data), indent=2, ensure_ascii=False) + "\n")
    return side


def write_csv(frame, path, options: dict, float_format: Optional[str] = "%.9g") -> Path:
    """Write ``frame`` to ``path`` (no index, one header row) and its sidecar; the path."""
    path = Path(path)
    frame.to_csv(path, index=False, float_format=float_format)
    write_context(path, list(frame.columns), options)
    return path
