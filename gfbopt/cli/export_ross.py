"""``gfbopt export-ross``: each bearing of a rotor file as a ROSS 3.x coefficient-table file.

    gfbopt export-ross ROTOR.toml --speed-range LOW HIGH --out DIR [--speeds N]
                       [--frequency-range F_LOW F_HIGH] [--frequencies N] [--json-format]
                       [--grid NTxNZ] [--json]

For each bearing, ``DIR/bearing_NAME.toml`` (``.json`` with ``--json-format``) holds its
stiffness and damping kxx … cyy [N/m, N s/m] over N speeds (rpm at this edge, rad/s in the
file) × N whirl frequencies (Hz here, rad/s in the file), in the rotor's x–y frame
(:func:`gfbopt.rotor.ross_bridge.bearing_tables`), in the file format ROSS's own
``BearingElement.save_coefficient_table`` writes; ROSS reads it with
``ross.BearingElement.load(path)`` (gfbopt need not be installed there).  The element's node
``n`` is the bearing's node in gfbopt's model: the shaft's node at the bearing (nodes at
every element end and named position, :mod:`gfbopt.rotor.shaft`), or for a rigid rotor its
place among the sorted bearing positions and the centre of gravity (the layout of
:func:`gfbopt.rotor.ross_bridge.ross_rotor`); set ``bearing.n`` to your ROSS rotor's node.

ROSS interpolates inside the table (PCHIP) and **extrapolates linearly outside it**: asking
for coefficients beyond the table's speed and frequency span — e.g. at the running speed
alone instead of the whirl frequency — extrapolated kxx 35–48 % too high in a trial (shared
design notes).  The command states the span; keep ROSS's analysis (``run_modal(speed,
matched_whirl=True)``) inside it.  Default frequencies: from 0.1 × LOW/60 to 1.5 × HIGH/60 Hz.
Beside each file its context ``bearing_NAME.toml.json`` (:mod:`.csv_context`): version,
source commit, command line and options.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..errors import ParameterError
from .common import add_grid, emit, grid_of, integer, number
from .csv_context import context_options, sidecar_path, write_context

#: default number of speeds and of whirl frequencies of a table
SPEEDS = 8
FREQUENCIES = 12
#: the default frequency span, over the speed span's ends in Hz (LOW/60, HIGH/60)
FREQUENCY_SPAN = (0.1, 1.5)


def register(subparsers) -> None:
    sub = subparsers.add_parser("export-ross", help="each bearing's speed × whirl-frequency "
                                "K and C table as a ROSS 3.x BearingElement file (SI)")
    sub.add_argument("rotor_file", metavar="ROTOR.toml", help="rotor file (SI; "
                     "docs/formats/rotor_file.md)")
    sub.add_argument("--speed-range", type=number("speed-range"), nargs=2, required=True,
                     metavar=("LOW", "HIGH"), help="speeds of the table [rpm]")
    sub.add_argument("--speeds", type=integer("speeds"), default=SPEEDS,
                     help=f"number of speeds, evenly spaced (default {SPEEDS})")
    sub.add_argument("--frequency-range", type=number("frequency-range"), nargs=2,
                     default=None, metavar=("F_LOW", "F_HIGH"), help="whirl frequencies of "
                     "the table [Hz] (default: 0.1 × LOW/60 to 1.5 × HIGH/60)")
    sub.add_argument("--frequencies", type=integer("frequencies"), default=FREQUENCIES,
                     help=f"number of whirl frequencies, evenly spaced (default {FREQUENCIES})")
    sub.add_argument("--out", required=True, metavar="DIR", help="folder for the files "
                     "(created if missing); beside each its context FILE.json (version, "
                     "source commit, options; docs/cli_outputs.md)")
    sub.add_argument("--json-format", action="store_true", help="write .json files (ROSS "
                     "reads both; default .toml)")
    add_grid(sub)
    sub.add_argument("--json", action="store_true", help="print one JSON object")
    sub.set_defaults(handler=run)


def _axis(name: str, low: float, high: float, count: int) -> np.ndarray:
    if not (math.isfinite(low) and math.isfinite(high) and 0 < low < high):
        raise ParameterError(f"--{name}-range", [low, high], "must be two values 0 < LOW < "
                             "HIGH")
    key = "speeds" if name == "speed" else "frequencies"
    if count < 2:
        raise ParameterError(f"--{key}", count, "must be >= 2 (a table axis; ROSS recommends "
                             ">= 5)")
    return np.linspace(low, high, count)


def _folder(value: str) -> Path:
    path = Path(value)
    if path.exists() and not path.is_dir():
        raise ParameterError("--out", value, "is a file, not a folder")
    existing = path
    while not existing.exists():
        existing = existing.parent
    if not existing.is_dir():
        raise ParameterError("--out", value, f"cannot be created: {str(existing)!r} is a file")
    import os

    if not os.access(existing, os.W_OK):
        raise ParameterError("--out", value, f"cannot be written: {str(existing)!r} is not "
                             "writable")
    return path


def bearing_nodes(system) -> tuple:
    """Each bearing's node in gfbopt's model (module docstring)."""
    if system.shaft is not None:
        from ..rotor.shaft import shaft_structure

        structure = shaft_structure(system)
        return tuple(structure.node_index(b.position) for b in system.bearings)
    positions = sorted({b.position for b in system.bearings} | {0.0})
    return tuple(positions.index(b.position) for b in system.bearings)


def run(args) -> int:
    from ..guard import check_file_name_part
    from ..inputs.rotor_limits import check_rotor_speeds
    from ..inputs.rotor_system import load_rotor
    from ..rotor.ross_bridge import ROSS_MIN_AXIS_POINTS, bearing_tables, write_ross_table
    from ..rotor.supports import resolve_rotor
    from ..rotor.system import SpeedLine
    from ..provenance import source_state
    from ..version import __version__

    speeds = _axis("speed", *args.speed_range, args.speeds)
    low, high = args.speed_range
    f_range = args.frequency_range or (FREQUENCY_SPAN[0] * low / 60.0,
                                       FREQUENCY_SPAN[1] * high / 60.0)
    freqs = _axis("frequency", *f_range, args.frequencies)
    folder = _folder(args.out)
    grid = grid_of(args)
    system = load_rotor(args.rotor_file)
    check_rotor_speeds(system, speeds, name="--speed-range")
    for b in system.bearings:
        check_file_name_part(b.name, f"{args.rotor_file}: bearing name",
                             "export-ross writes bearing_NAME.toml")
    nodes = bearing_nodes(system)
    case = resolve_rotor(system, grid)
    line = SpeedLine(case)
    conventions = case.conventions()      # each bearing's film, foil, friction, hardening
    folder.mkdir(parents=True, exist_ok=True)
    suffix = ".json" if args.json_format else ".toml"
    span = (f"speeds {low:g}–{high:g} rpm ({len(speeds)}), whirl frequencies "
            f"{f_range[0]:.6g}–{f_range[1]:.6g} Hz ({len(freqs)})")
    files = []
    options = context_options(args, command="export-ross", grid=str(grid),
                              conventions=conventions)
    state = source_state()
    commit = (state["commit"] or state["source"]) + (" with uncommitted changes"
                                                     if state["dirty"] else "")
    for k, (support, node) in enumerate(zip(system.bearings, nodes)):
        tables = bearing_tables(line, k, speeds, freqs)
        header = (f"gfbopt {__version__} export-ross: bearing {support.name} of "
                  f"{args.rotor_file}, grid {grid}",
                  f"source commit {commit}; command, options and provenance in "
                  f"{sidecar_path(folder / f'bearing_{support.name}{suffix}').name}",
                  "ROSS 3.x BearingElement coefficient table (load: "
                  "ross.BearingElement.load(path)); SI: speed, frequency rad/s, k N/m, c N s/m",
                  f"table span: {span}; ROSS extrapolates linearly outside it",
                  f"model: {_model_line(conventions['bearings'][support.name])}",
                  FRAME)
        path = write_ross_table(folder / f"bearing_{support.name}{suffix}", tables, node,
                                support.name, support.geometry.radial_clearance, header)
        write_context(path, None, options, read_with="ross.BearingElement.load(path)")
        files.append({"bearing": support.name, "file": str(path), "node": node,
                      "position_m": support.position})
    out = {"rotor_file": args.rotor_file, "grid": str(grid), "files": files,
           "conventions": conventions,
           "speed_range_rpm": [low, high], "speeds": len(speeds),
           "frequency_range_hz": list(f_range), "frequencies": len(freqs),
           "extrapolation": "ROSS extrapolates linearly outside the table's speed and "
                            "frequency span: keep its analysis inside it",
           "few_points": min(len(speeds), len(freqs)) < ROSS_MIN_AXIS_POINTS, "frame": FRAME}
    emit(out, args.json, lambda: _report(out, span), options)
    return 0


#: the coefficients' frame, stated in every file and output (a ROSS model whose x–y differ, e.g.
#: with gravity along −y, needs the tables rotated into its own frame)
FRAME = ("the rotor file's x–y (gravity at gravity_direction_deg from +x, 0 by default: x along "
         "gravity), the shaft spinning from x towards y; a ROSS model with other axes (e.g. "
         "gravity along −y) needs the tables rotated into its frame")


def _model_line(conv: dict) -> str:
    """One bearing's model in words: film convention; foil, law, η, friction; clearance."""
    from ..model_text import model_words

    return (f"{conv['film_convention']}; {model_words(conv)}; "
            f"{conv.get('thermal_model', 'isothermal, cold clearance')}")


def _report(out: dict, span: str) -> str:
    lines = [f"gfbopt export-ross — {out['rotor_file']}, grid {out['grid']}"]
    lines += [f"  bearing {f['bearing']} (node {f['node']}, z = {f['position_m']:g} m): "
              f"{f['file']}; {_model_line(out['conventions']['bearings'][f['bearing']])}"
              for f in out["files"]]
    lines += [f"Table span: {span}.",
              "ROSS extrapolates linearly outside this span (coefficients asked for at the "
              "running speed alone extrapolated kxx 35–48 % too high in a trial): keep "
              "run_modal(speed, matched_whirl=True) inside it.",
              "Load in ROSS: ross.BearingElement.load(path); set its n to your rotor's node.",
              f"Frame: {FRAME}."]
    if out["few_points"]:
        lines.append("Note: fewer than 5 points on an axis (ROSS recommends at least 5).")
    return "\n".join(lines)
