"""Each option by the flag a user types: in refusals and in the outputs' provenance.

The library names a bad value by its Python name (``speed_rpm = -5.0: must be > 0``,
``bearing_number``, ``grid n_theta``, ``file``); on the command line the user typed
``--speed-rpm``.  :func:`as_typed` turns such a :class:`~gfbopt.errors.ParameterError` into
the same one line with the flag — only when the value it names is the value given to that
option (a value the library computed itself keeps its own name), so a refusal always names
what the user can change.  Library names that are not an option's (``balance_grade`` of
``--imbalance-grade``) are in :data:`ALIASES`.
"""
from __future__ import annotations

import math
from typing import Optional

from ..errors import ParameterError

#: a library's name for a value → the option (dest) it comes from
ALIASES = {"balance_grade": "imbalance_grade",          # gfbopt.transient.rotor_setup
           "seam_angle_deg": "seam_angle",               # gfbopt.inputs.options
           "rate_rpm_per_s": "rate",                     # gfbopt.transient.rotor_analysis
           "target compliance S": "target_compliance",   # gfbopt.design.geometry_program
           "target compliance band": "target_compliance"}
#: names that say which file (their value is the path an option was given)
FILE_NAMES = ("file", "path")
#: a bearing file's key refused because of an option's choice: the key → (a word of the rule
#: that names the choice, the option's dest).  ``friction_coefficient = 0.5: is not carried by
#: the beam foil model`` after ``--foil beam`` reads ``--foil = 'beam': FILE's
#: friction_coefficient = 0.5 is not carried …`` (the user typed --foil, not the key)
CHOICES = {key: (("engine", "method"), ("foil model", "foil"),
                 ("deflection_law", "deflection_law"))
           for key in ("friction_coefficient", "friction_stiffness_ratio",
                       "hardening_exponent", "hardening_limit")}


def option_flags(parser) -> dict:
    """dest → the flag as a user types it (``speed_rpm`` → ``--speed-rpm``; a positional's
    metavar, ``ROTOR.toml``) for every argument of one sub-command's ``parser``."""
    flags = {}
    for action in parser._actions:            # argparse keeps them there (no public list)
        if action.dest in ("help", "version"):
            continue
        longs = [s for s in action.option_strings if s.startswith("--")]
        if longs:
            flags[action.dest] = longs[0]
        elif not action.option_strings:
            metavar = action.metavar
            flags[action.dest] = metavar if isinstance(metavar, str) else action.dest
    return flags


def _same(value, given) -> bool:
    """``value`` (as the library reports it) is what the option was given: equal, or the
    one element of a list option, or the list as a tuple."""
    if given is None:
        return False
    if isinstance(given, (list, tuple)):
        if isinstance(value, (list, tuple)):
            return [*value] == [*given]
        return any(_equal(value, g) for g in given)     # one element of a list option
    return _equal(value, given)


def _equal(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    try:
        return bool(a == b) or str(a) == str(b)
    except (TypeError, ValueError):
        return False


def _flag_of(name: str, value, args, flags: dict) -> Optional[str]:
    """The flag whose given value the error names, else None."""
    dest = ALIASES.get(name, name.replace("-", "_"))
    if dest in flags and flags[dest].startswith("--") and _same(value, getattr(args, dest,
                                                                                None)):
        return flags[dest]
    if name in FILE_NAMES:                       # a flag's or a positional's file
        hits = [f for d, f in flags.items() if _same(value, getattr(args, d, None))]
        return hits[0] if len(hits) == 1 else None
    return None


def as_typed(exc: ParameterError, args) -> ParameterError:
    """``exc`` with the parameter named by the flag the user typed (``--speed-rpm``) when it
    names an option by its Python name and the value given to it; else ``exc`` itself.
    ``grid n_theta = 4`` (a part of ``--grid``'s value) reads ``--grid n_theta = 4``."""
    flags = getattr(args, "option_flags", None) or {}
    name = exc.name if isinstance(exc.name, str) else ""
    if not name or name.startswith("--") or not flags:
        return exc
    flag = _flag_of(name, exc.value, args, flags)
    if flag is None and name in CHOICES:        # a file's value refused for a flag's choice
        choice = _choice(exc, args, flags)
        if choice is not None:
            return choice
    if flag is None and " " in name:            # a part of an option's value
        head, rest = name.split(" ", 1)
        dest = head.replace("-", "_")
        if dest in flags and flags[dest].startswith("--") and rest.isidentifier() \
                and getattr(args, dest, None) is not None:
            flag = f"{flags[dest]} {rest}"
    if flag is None:
        return exc
    new = ParameterError(flag, exc.value, exc.rule)
    new.__cause__ = exc.__cause__
    return new


def _choice(exc: ParameterError, args, flags: dict) -> Optional[ParameterError]:
    """``exc`` (a bearing file's bump key refused by the model or an engine) as the refusal of
    the option whose choice the rule names (:data:`CHOICES`), when that option was given."""
    for word, dest in CHOICES[exc.name]:
        given = getattr(args, dest, None)
        if word in exc.rule and given is not None and dest in flags \
                and _typed(args, flags[dest]) and (word != "engine" or str(given) in exc.rule):
            source = getattr(args, "bearing", None)
            where = f"{source}: " if isinstance(source, str) else ""
            rule = exc.rule[3:] if exc.rule.startswith("is ") else exc.rule
            new = ParameterError(flags[dest], given, f"{where}{exc.name} = {exc.value!r}: "
                                 f"{'is ' if exc.rule.startswith('is ') else ''}{rule}")
            new.__cause__ = exc.__cause__
            return new
    return None


def _typed(args, flag: str) -> bool:
    """``flag`` is on the command line as typed (not a value filled in from a file)."""
    line = getattr(args, "command_line", None)
    return line is None or any(w == flag or w.startswith(flag + "=") for w in line)


def refusal_line(exc: ParameterError, args) -> str:
    """The one line of a refusal after ``gfbopt: error:``: ``PARAMETER = VALUE: RULE`` with
    the parameter as typed (:func:`as_typed`), or ``PARAMETER (not given): RULE`` for a value
    that is missing (never ``--speed-rpm = None``, which reads as a value typed)."""
    typed = as_typed(exc, args)
    if typed.value is None and isinstance(typed.name, str) and typed.name:
        return f"{typed.name} (not given): {typed.rule}"
    return str(typed)
