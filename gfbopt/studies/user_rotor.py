"""A study run on the user's own rotor: ``gfbopt run STUDY --rotor my_rotor.toml
--top-speed 60000``.

:func:`on_user_rotor` returns the study's table with the study's ``rotor`` replaced by the
user's file (its absolute path, as the command line named it from the current folder) and
the top of ``speed_range_rpm`` by the top speed; the name gets the rotor file's stem (the
result folder ``RESULTS/<name>_on_<rotor>_to_<top>rpm/``, the parts of the options given), the title is rewritten from the user's rotor
and top speed and the shipped notes, which describe the shipped rotor and top speed, are
replaced by one note saying so (:func:`_retitled`), so the run answers exactly what an
edited copy of the study file with those keys changed answers.  The source, when the study cites one, is kept with a note that the rotor is the
user's.  Each option is checked before any solve: the rotor file exists and is a valid
rotor file (:func:`gfbopt.inputs.rotor_system.load_rotor`), the top speed is a finite
number above the study's lowest speed; a mistake is one
:class:`~gfbopt.errors.ParameterError` naming the option, its value and the rule.
"""
from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Optional

from ..errors import ParameterError


def check_rotor_option(value: str) -> Path:
    """The rotor file ``--rotor`` names (absolute), or ParameterError: missing, a
    directory, or not a valid rotor file (the file's own first mistake quoted)."""
    from ..inputs.rotor_system import load_rotor

    path = Path(value).expanduser()
    if not path.is_file():
        rule = "is a directory: give a rotor file" if path.is_dir() else \
            "no such rotor file (a path from the current folder)"
        raise ParameterError("--rotor", value, rule)
    try:
        load_rotor(path, running=True)
    except ParameterError as exc:
        raise ParameterError("--rotor", value, f"is not a valid rotor file ({exc.name} = "
                             f"{exc.value!r}: {exc.rule})") from None
    except (OSError, UnicodeDecodeError, RecursionError) as exc:
        raise ParameterError("--rotor", value, f"cannot be read as a rotor file "
                             f"({type(exc).__name__})") from None
    return path.resolve()


def _stem(path: Path) -> str:
    """The rotor file's stem as part of a folder name (letters, digits, '_', '-', '.')."""
    stem = re.sub(r"[^A-Za-z0-9_.-]+", "_", path.stem).strip("_.") or "rotor"
    return stem[:40]


def on_user_rotor(data: dict, file: str, schema: dict, rotor: Optional[str],
                  top_speed, name: str) -> dict:
    """The study ``data`` (parsed, not yet validated) of ``file`` with ``--rotor`` and
    ``--top-speed`` applied (module docstring; ``top_speed`` as typed: a number or its
    text); ``schema``: its kind's keys; ``name``: the study's name as the file gives it
    (or its file name)."""
    out = dict(data)
    kind = data.get("kind")
    if rotor is not None and "rotor" not in schema:
        raise ParameterError("--rotor", rotor, f"{file}: a {kind} study has no rotor (it "
                             "applies to rotor studies, e.g. kind = \"rotor_bearing_design\")")
    if top_speed is not None:
        if "speed_range_rpm" not in schema or schema["speed_range_rpm"].length != 2:
            raise ParameterError("--top-speed", top_speed, f"{file}: a {kind} study has no "
                                 "[lowest, top] speed_range_rpm")
        try:
            top_speed = float(top_speed)
        except (TypeError, ValueError):
            raise ParameterError("--top-speed", top_speed, "must be a speed in rpm") \
                from None
        if not (math.isfinite(top_speed) and top_speed > 0.0):
            raise ParameterError("--top-speed", top_speed, "must be a finite speed > 0 [rpm]")
        speeds = data.get("speed_range_rpm")
        if not (isinstance(speeds, list) and len(speeds) == 2
                and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                        for v in speeds)):
            raise ParameterError(f"{file}: speed_range_rpm", speeds, "must be [lowest, top] "
                                 "running speeds [rpm]")
        if not top_speed > speeds[0]:
            raise ParameterError("--top-speed", top_speed, f"must be above the study's "
                                 f"lowest speed {speeds[0]:g} rpm (speed_range_rpm of "
                                 f"{file})")
        out["speed_range_rpm"] = [float(speeds[0]), float(top_speed)]
    mine = check_rotor_option(rotor) if rotor is not None else None
    if mine is not None:
        out["rotor"] = str(mine)
    said = []
    if mine is not None:
        said.append(f"on the user's rotor {mine.name}")
    if top_speed is not None:
        said.append(f"to {top_speed:,.0f} rpm")
    if said:
        suffix = (f"_on_{_stem(mine)}" if mine is not None else "") + \
            (f"_to_{top_speed:.0f}rpm" if top_speed is not None else "")
        out["name"] = f"{name}{suffix}"[:100]
        out["title"], out["notes"] = _retitled(data, name, kind, mine, top_speed, said)
        if isinstance(data.get("source"), str):
            out["source"] = (f"{data['source']} (the study {file} run "
                             f"{' '.join(said)}: the rotor and top speed are the user's; a "
                             "rotor or speed the citation names is the shipped study's)")
    return out


def _top_speed_texts(speed) -> tuple:
    """How a note may write the shipped top speed [rpm]: 45,000 / 45000 / 45 krpm."""
    if not isinstance(speed, (int, float)) or not math.isfinite(speed):
        return ()
    return (f"{speed:,.0f}", f"{speed:.0f}", f"{speed / 1000:g} krpm")


def _retitled(data: dict, name: str, kind, mine: Optional[Path], top_speed,
              said: list) -> tuple:
    """(title, notes) of the study run on the user's rotor and/or top speed.  The shipped
    title and notes describe the shipped rotor and top speed (its mass, its measured
    optimum, "drag at 45,000 rpm"), so the title is rewritten from the user's rotor and
    top speed, and the notes are dropped -- all of them with ``--rotor`` (a measured fact
    of the shipped rotor may sit in any note), those naming the shipped top speed with
    ``--top-speed`` alone -- and one note says what was replaced."""
    from ..inputs.rotor_system import load_rotor

    speeds = data.get("speed_range_rpm")
    shipped_top = speeds[1] if isinstance(speeds, list) and len(speeds) == 2 else None
    notes = [n for n in data.get("notes") or [] if isinstance(n, str)]
    described = []
    if mine is not None:
        system = load_rotor(mine, running=True)
        described.append(f"the rotor is {mine} ({system.body.name}, "
                         f"{system.total_mass:.4g} kg)")
        dropped, kept = notes, []
    else:
        texts = _top_speed_texts(shipped_top)
        dropped = [n for n in notes if any(t in n for t in texts)]
        kept = [n for n in notes if n not in dropped]
    if top_speed is not None:
        described.append(f"the speeds run from {speeds[0]:,.0f} to {top_speed:,.0f} rpm")
    title = f"The study {name} ({kind}) {' '.join(said)}"
    if mine is not None:
        title += f": {system.body.name}, {system.total_mass:.4g} kg"
    shipped = (f"the shipped rotor {data.get('rotor')}" if mine is not None else "")
    if top_speed is not None and shipped_top is not None:
        shipped += (" and " if shipped else "") + f"the top speed {shipped_top:,.0f} rpm"
    what = (f"title and {len(dropped)} of its notes, which described {shipped}, were"
            if dropped else f"title, which described {shipped}, was")
    note = (f"Run {' '.join(said)}: {'; '.join(described)}. The shipped study's {what} "
            "replaced (see the study file).")
    return title, [note] + kept
