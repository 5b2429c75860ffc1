"""Every typed flag of every command is refused in one form: ``--flag = 'abc': must be an
integer`` / ``… must be a number`` (gfbopt.cli.common.integer / number), exit 2 — never
argparse's own ``argument --flag: invalid int value: 'abc'``."""
from __future__ import annotations

import argparse

import pytest

from gfbopt.cli import build_parser, main

#: (argv up to the flag, flag, the rule the helper states) — integer flags and a few numbers
TABLE = [
    (["export-ross", "problems/rotors/blower.toml", "--speed-range", "1000", "2000",
      "--out", "OUT"], "--speeds", "must be an integer"),
    (["export-ross", "problems/rotors/blower.toml", "--speed-range", "1000", "2000",
      "--out", "OUT"], "--frequencies", "must be an integer"),
    (["run", "problems/x.toml"], "--workers", "must be an integer"),
    (["run", "problems/x.toml"], "--max-workers", "must be an integer"),
    (["run", "problems/x.toml"], "--max-points", "must be an integer"),
    (["rotor", "problems/rotors/blower.toml", "--run-up", "1000", "2000"], "--rate",
     "must be a number"),
    (["orbit"], "--stages", "must be a number"),
    (["critical-mass"], "--batch", "must be a number"),
    (["rotor", "problems/rotors/blower.toml", "--speed-range", "10000", "60000",
      "--campbell"], "--campbell-speeds", "must be an integer"),
]


@pytest.mark.parametrize("argv, flag, rule", TABLE, ids=[f"{r[0][0]} {r[1]}" for r in TABLE])
def test_typed_flag_refusal_is_one_line_naming_the_flag(argv, flag, rule, capsys, tmp_path):
    argv = [str(tmp_path) if a == "OUT" else a for a in argv]
    with pytest.raises(SystemExit) as exc:
        main([*argv, flag, "abc"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert err == f"gfbopt: error: {flag} = 'abc': {rule}\n"


def _typed_actions():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for command, p in sub.choices.items():
        for action in p._actions:
            if action.type is not None and action.type is not str and action.option_strings:
                yield command, action


def test_no_command_has_a_bare_int_or_float_flag():
    """argparse's own int/float types print 'invalid int value': every typed flag of every
    command goes through the helpers, whose message starts with the flag and the text."""
    actions = list(_typed_actions())
    assert len(actions) > 100                     # every command's typed flags were seen
    for command, action in actions:
        assert action.type not in (int, float), (command, action.option_strings)
        with pytest.raises(argparse.ArgumentTypeError) as exc:
            action.type("abc")
        assert str(exc.value).startswith(f"{action.option_strings[-1]} = 'abc': must be"), \
            (command, str(exc.value))


def test_integer_helper_minimum():
    from gfbopt.cli.common import integer

    parse = integer("speeds", minimum=2)
    assert parse("7") == 7
    with pytest.raises(argparse.ArgumentTypeError, match=r"^--speeds = 1: must be >= 2$"):
        parse("1")
    with pytest.raises(argparse.ArgumentTypeError, match=r"^--speeds = '2.5': must be an "
                       r"integer$"):
        parse("2.5")
