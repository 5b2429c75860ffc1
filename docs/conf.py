"""Sphinx configuration of gfbopt's documentation: the executed example gallery
(sphinx-gallery, ``examples/*.py`` → ``docs/auto_examples/``), the API reference generated
from the docstrings (autodoc + autosummary, ``docs/api/``), and the Markdown pages
(myst-parser).

Build (one command, from the repository root)::

    pip install -e ".[docs]" && sphinx-build -b html docs docs/_build/html

The gallery executes every ``examples/plot_*.py`` on its small grid; the figures each
example writes besides the page go to ``docs/_build/example_outputs`` (the examples read
``GFBOPT_EXAMPLES_OUTPUT``).
"""
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))            # the checkout's gfbopt, installed or not
os.environ.setdefault("GFBOPT_EXAMPLES_OUTPUT", str(HERE / "_build" / "example_outputs"))
os.environ.setdefault("MPLBACKEND", "Agg")
# one BLAS/OpenMP thread: the examples' solves are small, threads only contend
for _name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

from gfbopt.version import __version__  # noqa: E402

project = "gfbopt"
author = "the gfbopt developers"
copyright = "the gfbopt developers, BSD-3-Clause"
version = release = __version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "sphinx_gallery.gen_gallery",
    "myst_parser",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.md5", "examples/*.py",
                    "**/*.codeobj.json"]

# -- the API reference ------------------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_typehints = "signature"
autodoc_member_order = "bysource"
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False
napoleon_use_ivar = True          # dataclass fields: one description each, not two
# gfbopt's docstrings cite modules relatively (:mod:`.analysis`): not every one resolves
suppress_warnings = ["ref.python", "myst.xref_missing", "myst.header"]
nitpicky = False

# -- the gallery ------------------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": str(HERE / "auto_examples"),
    # executed: every plot_*.py (small grids, a few seconds each); the ROSS comparison needs
    # the optional extra on Python >= 3.12 and is listed, not run
    "filename_pattern": r"[\\/]plot_",
    "ignore_pattern": r"__init__\.py",
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "show_memory": False,
    "min_reported_time": 1,
    # an example that raises fails the build (no silently broken page)
    "only_warn_on_example_error": False,
    "abort_on_example_error": False,
}

# -- HTML --------------------------------------------------------------------------------
html_theme = "furo" if __import__("importlib.util").util.find_spec("furo") else "alabaster"
html_title = f"gfbopt {release}"
html_static_path = []
myst_heading_anchors = 3
