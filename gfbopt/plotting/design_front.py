"""Figures of a rotor's bearing-pair design search (gfbopt.studies.rotor_design): the
designs evaluated against the top speed, the Pareto front, the chosen design, and the first
onset against each design variable.  Pure functions: ``ax=None`` draws on a new Figure."""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

from .core import new_axes, set_title

_LABELS = {
    "radial_clearance_um": "radial clearance c [µm]",
    "length_mm": "bearing length L [mm]",
    "bump_pitch_mm": "bump pitch s [mm]",
    "bump_half_length_mm": "half bump length l0 [mm]",
    "bump_thickness_um": "bump thickness t_b [µm]",
    "compliance": "compliance S [-]",
    "preload_depth_um": "preload depth [µm]",
    "preload_count": "number of shims or lobes [-]",
    "pads": "number of top-foil pads [-]",
}


def variable_label(name: str) -> str:
    """Axis label of a design variable (a bearing prefix "A:" is kept in front)."""
    bearing, var = name.split(":", 1) if ":" in name else ("", name)
    head, _, rest = var.partition("_")
    if head.startswith("zone") and head[4:].isdigit() and rest in _LABELS:
        label = f"zone {head[4:]}: {_LABELS[rest]}"          # a per-zone bump variable
    else:
        label = _LABELS.get(var, var)
    return f"bearing {bearing}: {label}" if bearing else label


def plot_design_front(table, front, chosen: Optional[dict], top_speed_rpm: float,
                      search_high_rpm: float, robust=None, ax=None, title: str = "",
                      limits: str = ""):
    """First onset over all modes [krpm] against power loss at the top speed [W] of every
    evaluated design (feasible filled, infeasible open, failed omitted), the Pareto front,
    the chosen design, the top speed and the top of the onset search (where 'stable over
    the range' designs sit), and, for the designs checked for robustness, a bar down to
    their worst-case onset under the tolerances; ``limits``: the study's limits in words
    (e.g. "start-up film"), named in the legend of the designs that break one."""
    ax = new_axes() if ax is None else ax
    ok = table[table["success"].astype(bool)]
    feasible = ok["feasible"].astype(bool) if "feasible" in ok else np.ones(len(ok), bool)
    ax.scatter(ok.loc[feasible, "total_power_loss_w"], ok.loc[feasible, "first_onset_speed_rpm"]
               / 1e3, s=14, color="tab:blue", alpha=0.6, label="feasible design")
    ax.scatter(ok.loc[~feasible, "total_power_loss_w"], ok.loc[~feasible, "first_onset_speed_rpm"]
               / 1e3, s=14, facecolors="none", edgecolors="tab:gray",
               label=f"breaks a limit ({limits})" if limits else "breaks a limit")
    if front is not None and len(front):
        f = front.sort_values("total_power_loss_w")
        ax.plot(f["total_power_loss_w"], f["first_onset_speed_rpm"] / 1e3, "-o", color="tab:orange",
                ms=5, label="Pareto front (non-dominated feasible)")
    if robust is not None and len(robust):
        merged = robust.merge(table[["point", "total_power_loss_w"]], on="point")
        for _, r in merged.iterrows():
            ax.plot([r["total_power_loss_w"]] * 2, [r["worst_onset_speed_rpm"] / 1e3,
                                              r["nominal_onset_speed_rpm"] / 1e3],
                    color="tab:red", lw=2, alpha=0.7)
        ax.plot([], [], color="tab:red", lw=2, label="down to the worst case under "
                "tolerances and loss-factor band")
    if chosen is not None:
        ax.plot(chosen["total_power_loss_w"], chosen["first_onset_speed_rpm"] / 1e3, "*",
                color="black", ms=14, label="chosen design")
    ax.axhline(top_speed_rpm / 1e3, color="tab:green", ls="--",
               label=f"top speed {top_speed_rpm:,.0f} rpm")
    ax.axhline(search_high_rpm / 1e3, color="tab:gray", ls=":",
               label=f"end of the onset search ({search_high_rpm:,.0f} rpm): stable to here")
    ax.set_xlabel("power loss of both bearings at the top speed [W]")
    ax.set_ylabel("first onset of whirl over all modes [krpm]")
    ax.legend(fontsize=7, loc="best")
    ax.grid(alpha=0.3)
    set_title(ax, title)
    return ax


def plot_onset_against_variables(table, names: list, top_speed_rpm: float, axes=None,
                                 title: str = "", chosen: Optional[dict] = None,
                                 bounds: Optional[dict] = None):
    """First onset [krpm] of every successful design against each design variable, feasible
    and infeasible apart, the top speed drawn; ``chosen``: the chosen design (a star);
    ``bounds``: {variable: (low, high)} of the design space (dotted lines).  Returns the
    array of Axes."""
    n = len(names)
    if axes is None:
        cols = min(n, 3)
        rows = int(math.ceil(n / cols))
        axes = new_axes(figsize=(3.6 * cols, 3.2 * rows), nrows=rows, ncols=cols)
    flat = np.atleast_1d(axes).ravel()
    ok = table[table["success"].astype(bool)]
    feasible = ok["feasible"].astype(bool) if "feasible" in ok else np.ones(len(ok), bool)
    for ax, name in zip(flat, names):
        ax.scatter(ok.loc[feasible, name], ok.loc[feasible, "first_onset_speed_rpm"] / 1e3,
                   s=12, color="tab:blue", alpha=0.6, label="feasible")
        ax.scatter(ok.loc[~feasible, name], ok.loc[~feasible, "first_onset_speed_rpm"] / 1e3,
                   s=12, facecolors="none", edgecolors="tab:gray", label="breaks a limit")
        ax.axhline(top_speed_rpm / 1e3, color="tab:green", ls="--",
                   label=f"top speed {top_speed_rpm:,.0f} rpm")
        if chosen is not None and name in chosen:
            ax.plot(chosen[name], chosen["first_onset_speed_rpm"] / 1e3, "*", color="black",
                    ms=12, label="chosen design")
        for k, edge in enumerate((bounds or {}).get(name, ())):
            ax.axvline(edge, color="tab:gray", ls=":", lw=1,
                       label="bounds of the design space" if k == 0 else None)
        ax.set_xlabel(variable_label(name))
        ax.set_ylabel("first onset [krpm]")
        ax.grid(alpha=0.3)
    for ax in flat[n:]:
        ax.set_visible(False)
    flat[0].legend(fontsize=7)
    if title:
        flat[0].figure.suptitle(title, fontsize=9)
    return axes
