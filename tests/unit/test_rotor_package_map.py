"""gfbopt/rotor/__init__.py's table of modules lists every module of the package, and only
those (maps that are true)."""
import re
from pathlib import Path

import gfbopt.rotor as rotor


def test_the_rotor_packages_table_lists_every_module():
    listed = set(re.findall(r":mod:`\.(\w+)`", rotor.__doc__))
    here = Path(rotor.__file__).parent
    modules = {p.stem for p in here.glob("*.py")} - {"__init__"}
    assert modules - listed == set()
    assert listed - modules == set()
