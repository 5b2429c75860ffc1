"""Figures of the stability-driven bump design: onset speed of whirl against the compliance
coefficient S and against the bump pitch, one line per foundation law and loss factor, with
the limits drawn (the reachable range of S, the original foil, film-limited points)."""
from __future__ import annotations

import numpy as np

from .core import new_axes, set_title

_LAW = {"mean": "axial-mean law", "local": "local law"}


def _lines(ax, table, x: str):
    styles = {"mean": "-", "local": "--"}
    for (law, eta), sub in table.groupby(["deflection_law", "loss_factor"], sort=True):
        sub = sub.sort_values(x)
        ok = sub[sub["success"].astype(bool) & sub["feasible"].astype(bool)]
        line, = ax.plot(ok[x], ok["onset_speed_rpm"], styles.get(law, "-"), marker="o", ms=3,
                        label=f"{_LAW.get(law, law)}, η = {eta:g}")
        bad = sub[~(sub["success"].astype(bool) & sub["feasible"].astype(bool))]
        bad = bad[np.isfinite(bad["onset_speed_rpm"].astype(float))]
        if len(bad):
            ax.plot(bad[x], bad["onset_speed_rpm"], "x", color=line.get_color(),
                    label="_nolegend_")
    ax.plot([], [], "kx", label="film thinner than the limit, or failed (not admissible)")


def plot_design_against_compliance(table, limits: dict, ax=None, title: str = ""):
    """Onset speed of whirl [rpm] against S [-] (log axis) per (law, η); the reachable range
    of S shaded outside, the original foil's S dotted.  ``limits``: compliance_range,
    baseline_compliance.  Returns the Axes."""
    ax = new_axes(figsize=(7.0, 5.4)) if ax is None else ax
    _lines(ax, table, "compliance")
    low, high = limits["compliance_range"]
    ax.axvline(low, color="grey", lw=1.0, ls="-.", label=f"stiffest bump foil the limits allow "
               f"(S = {low:.3g})")
    ax.axvline(high, color="grey", lw=1.0, ls=(0, (5, 2)), label=f"softest bump foil the "
               f"limits allow (S = {high:.3g})")
    ax.axvline(limits["baseline_compliance"], color="k", lw=1.0, ls=":",
               label=f"original bump foil (S = {limits['baseline_compliance']:.3g})")
    ax.set_xscale("log")
    ax.set_xlabel("compliance coefficient S = p_a α / c [-]")
    ax.set_ylabel("onset speed of whirl [rpm]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    set_title(ax, title)
    return ax


def plot_design_against_pitch(table, limits: dict, ax=None, title: str = ""):
    """Onset speed of whirl [rpm] against the bump pitch [mm] of the least-stress bump foil
    that realises each S (geometric program), per (law, η).  Returns the Axes."""
    ax = new_axes(figsize=(7.0, 5.4)) if ax is None else ax
    usable = table[np.isfinite(table["bump_pitch_mm"].astype(float))]
    _lines(ax, usable, "bump_pitch_mm")
    ax.set_xlabel("bump pitch s of the least-stress bump foil for each S [mm]")
    ax.set_ylabel("onset speed of whirl [rpm]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    set_title(ax, title)
    return ax
