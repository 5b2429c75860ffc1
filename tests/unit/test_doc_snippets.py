"""The documented Python snippets run as written: every ```python block of the
README and of the Markdown pages under docs/, and the ``.. code-block:: python`` of the docs
index, each in a fresh interpreter from the repository root.

A block on a page that names its worked example script (``docs/examples/NAME.py``) is an
excerpt of it: there the functions it defines must be the script's (same code, docstrings
aside), and the script itself runs, on the coarsest grid it accepts.
"""
import ast
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")),
         *sorted((ROOT / "docs" / "formats").glob("*.md"))]
_FENCE = re.compile(r"^```python\n(.*?)^```", re.S | re.M)
_RST = re.compile(r"^\.\. code-block:: python\n\n((?:(?:   .*)?\n)+)", re.M)
_WORKED = re.compile(r"\((?:\.\./)*((?:docs/)?examples/[\w]+\.py)\)")


def snippets() -> list:
    """(page, index, code, worked example script or None) of every documented block."""
    out = []
    for page in PAGES:
        text = page.read_text()
        worked = _WORKED.search(text)
        script = None
        if worked:
            name = worked.group(1)
            script = ROOT / (name if name.startswith("docs/") else f"docs/{name}")
        for k, code in enumerate(_FENCE.findall(text)):
            out.append((page, k, code, script))
    index = (ROOT / "docs" / "index.rst").read_text()
    for k, code in enumerate(_RST.findall(index)):
        out.append((ROOT / "docs" / "index.rst", k, textwrap.dedent(code), None))
    return out


SNIPPETS = snippets()
IDS = [f"{page.relative_to(ROOT)}#{k}" for page, k, _, _ in SNIPPETS]


def run(args, **kwargs):
    env = {**os.environ, "MPLBACKEND": "Agg", "OMP_NUM_THREADS": "1",
           "OPENBLAS_NUM_THREADS": "1"}
    return subprocess.run([sys.executable, *args], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=600, **kwargs)


def functions(source: str) -> dict:
    """name → AST dump of each top-level function, its docstring removed."""
    out = {}
    for node in ast.parse(source).body:
        if isinstance(node, ast.FunctionDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value,
                                                                     ast.Constant):
                node.body = body[1:]
            out[node.name] = ast.dump(node, include_attributes=False)
    return out


def test_the_snippets_are_found():
    """The README's Python section and the docs pages hold snippets (the extraction is not
    silently empty)."""
    pages = {page.name for page, *_ in SNIPPETS}
    assert {"README.md", "index.rst"} <= pages
    readme = next(code for page, _, code, _ in SNIPPETS if page.name == "README.md")
    assert "from gfbopt import load_bearing" in readme


@pytest.mark.parametrize("page, k, code, script", SNIPPETS, ids=IDS)
def test_snippet_runs_as_written(page, k, code, script, tmp_path):
    if script is None:
        result = run(["-c", code])
        assert result.returncode == 0, f"{page.name} block {k}:\n{result.stderr[-3000:]}"
        return
    assert script.is_file(), f"{page.name} names {script}, which is not there"
    ours, theirs = functions(code), functions(script.read_text())
    assert ours, f"{page.name} block {k} defines no function of {script.name}"
    for name, dump in ours.items():
        assert theirs.get(name) == dump, (f"{page.name} block {k}: {name}() differs from "
                                          f"{script.relative_to(ROOT)}")
    result = run([str(script), str(tmp_path / "store"), "--grid", "12x4"])
    assert result.returncode == 0, result.stderr[-3000:]
