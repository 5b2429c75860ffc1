"""The package's shape: layers point one way, no import cycle, modules a newcomer can read.

Checked statically (ast) over every module of gfbopt, so it runs in milliseconds:
* the import graph between gfbopt modules has no cycle (Tarjan's strongly connected
  components over module-level *and* function-level imports);
* no module is longer than 500 lines;
* only :mod:`gfbopt.plotting` imports matplotlib, and only :mod:`gfbopt.design` imports
  cvxpy (``docs/ARCHITECTURE.md``, "Layers point one way");
* importing gfbopt sets no environment variables (no global side effects).
"""
import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "gfbopt"
MAX_LINES = 500


def _modules() -> dict[str, Path]:
    out = {}
    for path in PACKAGE.rglob("*.py"):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def _imports(name: str, path: Path) -> set[str]:
    """gfbopt modules imported by ``name`` (absolute names), anywhere in the file."""
    tree = ast.parse(path.read_text())
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.startswith("gfbopt")}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            if not mod.startswith("gfbopt"):
                continue
            found.add(mod)
            for alias in node.names:            # "from . import x" may name a submodule
                if f"{mod}.{alias.name}" in MODULES:
                    found.add(f"{mod}.{alias.name}")
    return {m for m in found if m in MODULES and m != name}


def _third_party(path: Path) -> set[str]:
    tree = ast.parse(path.read_text())
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
            names.add(node.module.split(".")[0])
    return names


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in graph:
        if v not in index:
            visit(v)
    return out


def test_import_graph_has_no_cycle():
    """A package's __init__ re-exporting its submodules is not a cycle; any other loop is."""
    graph = {}
    for name, path in MODULES.items():
        deps = _imports(name, path)
        # edges from a submodule to its own parent package's __init__ are allowed only if the
        # parent does not import it back; edges parent → child are the re-export pattern.
        graph[name] = {d for d in deps if not name.startswith(d + ".")}
    assert _cycles(graph) == []


@pytest.mark.parametrize("name", sorted(MODULES))
def test_module_is_at_most_500_lines(name):
    lines = len(MODULES[name].read_text().splitlines())
    assert lines <= MAX_LINES, f"{name}: {lines} lines"


def test_matplotlib_only_in_plotting_and_cvxpy_only_in_design():
    for name, path in MODULES.items():
        deps = _third_party(path)
        if "matplotlib" in deps:
            assert name.startswith("gfbopt.plotting"), name
        if "cvxpy" in deps:
            assert name.startswith("gfbopt.design"), name


def test_import_has_no_global_side_effects():
    code = ("import os; before = dict(os.environ); import gfbopt, gfbopt.transient, "
            "gfbopt.linear; assert dict(os.environ) == before, "
            "set(os.environ) ^ set(before)")
    env = {k: v for k, v in os.environ.items()
           if k not in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert out.returncode == 0, out.stderr


def test_cycle_detector_finds_a_planted_cycle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert _cycles(graph) == [["a", "b", "c"]]


#: the floors of docs/ARCHITECTURE.md ("Layers point one way"), bottom first: a module may
#: import from its own floor and the floors below, never from above.  Units are gfbopt's
#: subpackages and top-level modules; a new one must be placed here (the test names it).
FLOORS = (
    ("errors", "version", "runtime", "threads", "progress", "terms", "glossary", "provenance",
     "model_text"),
    ("inputs", "physics", "plotting", "sparse_lu", "pool_stream", "cluster"),
    ("discretisation", "guard"),
    ("static",),
    ("linear", "parallel"),
    ("thermal",),
    ("rotor",),
    ("transient",),
    ("analyses",),
    ("doe",),
    ("design",),
    ("studies",),
    ("file_formats", "api", "cli", "__main__"),
)


def _unit(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "gfbopt"


def test_every_unit_has_a_floor():
    placed = {u for floor in FLOORS for u in floor}
    units = {_unit(m) for m in MODULES} - {"gfbopt"}
    assert sorted(units - placed) == [], "place these in FLOORS (and docs/ARCHITECTURE.md)"


def test_imports_point_down_the_floors():
    """Each import between units goes to the same floor or a lower one (the package's own
    ``__init__`` re-exporting from the top is the one exception: it is the face, not a floor)."""
    floor = {u: k for k, units in enumerate(FLOORS) for u in units}
    upward = []
    for name, path in MODULES.items():
        src = _unit(name)
        if src == "gfbopt":
            continue
        for dep in _imports(name, path):
            dst = _unit(dep)
            if dst != "gfbopt" and dst in floor and floor[dst] > floor.get(src, -1):
                upward.append(f"{name} -> {dep}")
    assert upward == []
