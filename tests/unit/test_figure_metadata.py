"""Every figure says what made it, in its file: gfbopt's version and source commit (PNG's
Software, PDF's and SVG's Creator), as every other output states them."""
import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402
from PIL import Image  # noqa: E402

from gfbopt.plotting.core import save_figure  # noqa: E402
from gfbopt.provenance import source_state  # noqa: E402
from gfbopt.version import __version__  # noqa: E402


@pytest.fixture()
def figure():
    fig, ax = plt.subplots()
    ax.plot([0.0, 1.0])
    yield fig
    plt.close(fig)


def _made() -> str:
    state = source_state()
    return f"gfbopt {__version__}" + (f" (commit {state['commit']}" if state["commit"]
                                      else f" ({state['source']})")


def test_a_png_names_the_version_and_commit(figure, tmp_path):
    with Image.open(save_figure(figure, tmp_path / "a.png")) as image:
        assert image.info["Software"].startswith(_made())


@pytest.mark.parametrize("suffix, text", [("svg", lambda m: m),
                                          ("pdf", lambda m: m.replace("(", "\\("))])
def test_svg_and_pdf_name_them_as_their_creator(figure, tmp_path, suffix, text):
    path = save_figure(figure, tmp_path / f"a.{suffix}")
    with open(path, "rb") as handle:
        assert text(_made()).encode() in handle.read()
