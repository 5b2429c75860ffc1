"""Design-of-experiments figures: Sobol sensitivity indices."""
from __future__ import annotations

import numpy as np

from .core import new_axes


def plot_sobol_indices(table, ax=None, output: str = ""):
    """Bar chart of first-order (S1) and total (ST) Sobol indices per input, with their 95 %
    bootstrap confidence intervals (``table``: columns input, S1, S1_conf, ST, ST_conf, as
    from :func:`gfbopt.doe.sensitivity.sobol_indices`)."""
    ax = ax if ax is not None else new_axes()
    x = np.arange(len(table))
    width = 0.38
    ax.bar(x - width / 2, table["S1"], width, yerr=table["S1_conf"], capsize=3,
           label="first order S1")
    ax.bar(x + width / 2, table["ST"], width, yerr=table["ST_conf"], capsize=3,
           label="total ST")
    ax.set_xticks(x)
    ax.set_xticklabels(list(table["input"]), rotation=20, ha="right")
    ax.set_ylabel("Sobol index [-]")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_title(f"Sensitivity of {output}" if output else "Sobol indices")
    ax.legend()
    return ax
