"""The Sphinx site reaches every documentation page: each Markdown page under docs/
and docs/formats/ is in a toctree of docs/index.rst, each toctree entry exists, and the
gallery configuration points at the examples the gallery test runs.  Sphinx is not needed."""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
#: generated at build time (sphinx-gallery, autosummary), not sources in the checkout
GENERATED = {"auto_examples/index", "sg_execution_times"}


def toctree_entries() -> list:
    text = (DOCS / "index.rst").read_text()
    entries = []
    for block in re.findall(r"^\.\. toctree::\n((?:(?:   .*)?\n)+)", text, re.M):
        entries += [line.strip() for line in block.splitlines()
                    if line.strip() and not line.strip().startswith(":")]
    return entries


def test_every_page_is_in_the_index():
    entries = set(toctree_entries())
    pages = {p.relative_to(DOCS).with_suffix("").as_posix()
             for p in [*DOCS.glob("*.md"), *(DOCS / "formats").glob("*.md")]}
    assert sorted(pages - entries) == [], "add these pages to a toctree of docs/index.rst"


def test_every_index_entry_exists():
    for entry in toctree_entries():
        if entry in GENERATED:
            continue
        assert any((DOCS / f"{entry}{suffix}").is_file() for suffix in (".md", ".rst")), entry


def test_the_gallery_builds_the_examples_the_tests_run():
    conf = (DOCS / "conf.py").read_text()
    assert '"examples_dirs": str(ROOT / "examples")' in conf
    assert '"filename_pattern": r"[\\\\/]plot_"' in conf
    assert (ROOT / "examples" / "GALLERY_HEADER.rst").is_file()
    assert "auto_examples/index" in toctree_entries()
