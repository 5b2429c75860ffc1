"""Figures of the stability studies (:mod:`gfbopt.studies.stability`): the onset speed of whirl
against the top foil's welded-end angle and the film convention, and the critical mass and
onset speed against the compliance S per structural loss factor η."""
from __future__ import annotations

import math

import numpy as np
from matplotlib.ticker import ScalarFormatter

from .core import new_axes, set_title

_LAW = {"mean": "axial-mean deflection law", "local": "local deflection law"}
#: markers for searches that end without an onset inside the speed range
_NO_ONSET = {"unstable at every mass": ("v", "tab:red", ("unstable at every rotor mass "
                                                       "(at the lowest speed)")),
             "unstable at the lowest speed": ("v", "tab:orange",
                                              "unstable already at the lowest speed"),
             "stable over the range": ("^", "tab:green", "stable over the whole range"),
             "load exceeds capacity": ("x", "black", "load exceeds the capacity")}


def _top(values, status, speed_range) -> float:
    """Upper y limit: the high end of the range when some search was stable over it, else
    15 % above the largest onset."""
    finite = [float(v) for v in values if math.isfinite(float(v))]
    if "stable over the range" in set(status) or not finite:
        return speed_range[1] * 1.05
    return min(speed_range[1] * 1.05, max(finite) * 1.15)


def _range_band(ax, low: float) -> None:
    ax.axhspan(0, low, color="0.9", zorder=0, label=f"below the speed range (< {low:,.0f} rpm)")


def _no_onset_markers(ax, x, status, speed_range, color=None, labelled=None):
    """Draw searches without an onset: at the low end of the range (unstable) or the high
    end (stable), so that they are visible, never silently missing."""
    low, high = speed_range
    labelled = set() if labelled is None else labelled
    for xv, st in zip(x, status):
        if st not in _NO_ONSET:
            continue
        marker, c, text = _NO_ONSET[st]
        y = high if st == "stable over the range" else low
        ax.plot([xv], [y], marker=marker, color=color or c, ls="none", ms=8,
                markerfacecolor="none" if color else c,
                label=None if st in labelled else text)
        labelled.add(st)
    return labelled


def plot_onset_against_seam(frame, speed_range: tuple, ax=None, title: str = "",
                            conventions: dict | None = None):
    """Onset speed of whirl [rpm] against the welded-end angle [deg] (rows with
    ``convention`` = 'seam_<deg>'), the periodic film and the seam on the maximum-film line
    as horizontal lines; searches without an onset drawn at the ends of the range."""
    ax = new_axes(figsize=(7.2, 4.6)) if ax is None else ax
    conventions = conventions or {}
    seams = frame[frame["convention"].astype(str).str.startswith("seam_")].copy()
    seams["angle"] = seams["seam_angle_deg"].astype(float)
    seams = seams.sort_values("angle")
    ok = seams["onset_status"] == "onset"
    y = np.where(ok, seams["onset_speed_rpm"].astype(float), np.nan)
    ax.plot(seams["angle"], y, "o-", color="tab:blue",
            label="welded end at a fixed housing angle")
    _no_onset_markers(ax, seams["angle"], seams["onset_status"], speed_range)
    styles = {"periodic": ("--", "tab:purple"), "max_film": ("-.", "tab:brown")}
    for name, (ls, color) in styles.items():
        row = frame[frame["convention"] == name]
        if not len(row):
            continue
        row = row.iloc[0]
        text = conventions.get(name, name)
        if row["onset_status"] == "onset":
            ax.axhline(row["onset_speed_rpm"], ls=ls, color=color,
                       label=f"{text}: {row['onset_speed_rpm']:,.0f} rpm")
        else:
            ax.plot([], [], ls=ls, color=color, label=f"{text}: {row['onset_status']}")
    low = speed_range[0]
    ax.set_ylim(0, _top(frame["onset_speed_rpm"], frame["onset_status"], speed_range))
    _range_band(ax, low)
    ax.set_xlim(-5, 365)
    ax.set_xticks(np.arange(0, 361, 45))
    ax.set_xlabel("welded end of the top foil from the load line, in the direction of "
                  "rotation [deg]")
    ax.set_ylabel("onset speed of whirl [rpm]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    set_title(ax, title)
    return ax


def _eta_colors(etas):
    import matplotlib

    cmap = matplotlib.colormaps["viridis"]
    etas = sorted(etas)
    return {eta: cmap(0.85 * k / max(1, len(etas) - 1)) for k, eta in enumerate(etas)}


def plot_critical_mass_against_compliance(frame, axes=None, title: str = ""):
    """Linear critical mass M̄c against S, one line per η, one panel per (case, law): rows
    of the figure are the cases (Λ, W̄), columns the deflection laws; the rigid bearing
    (S = 0) is a dashed line and a square at S = 0."""
    cases = list(dict.fromkeys(frame["case"]))
    laws = [law for law in ("mean", "local") if law in set(frame["deflection_law"])]
    if axes is None:
        axes = new_axes(figsize=(4.2 * len(laws), 3.4 * len(cases)), nrows=len(cases),
                        ncols=len(laws))
    axes = np.atleast_2d(np.asarray(axes).reshape(len(cases), len(laws)))
    colors = _eta_colors(set(frame.loc[frame["deflection_law"] != "rigid", "loss_factor"]))
    for i, case in enumerate(cases):
        sub = frame[frame["case"] == case]
        rigid = sub[sub["deflection_law"] == "rigid"]["critical_mass"]
        rigid = float(rigid.iloc[0]) if len(rigid) else math.nan
        for j, law in enumerate(laws):
            ax = axes[i, j]
            finite = sub["critical_mass"].astype(float)
            finite = finite[np.isfinite(finite)]
            top = float(finite.max()) * 1.15 if len(finite) else 10.0
            marked = set()
            for eta, g in sub[sub["deflection_law"] == law].groupby("loss_factor"):
                g = g.sort_values("compliance")
                y = g["critical_mass"].astype(float).to_numpy()
                ax.plot(g["compliance"], np.where(np.isinf(y), np.nan, y), "o-", ms=3,
                        color=colors[eta], label=f"η = {eta:g}")
                over = (g["load_exceeds_capacity"].fillna(False).astype(bool).to_numpy()
                        if "load_exceeds_capacity" in g else np.zeros(len(g), bool))
                bottom = float(finite.min()) * 0.9 if len(finite) else 1.0
                for name, mask, level, marker in (
                        ("stable for every rotor mass", np.isinf(y), top, "^"),
                        ("load exceeds the capacity", over, bottom, "x")):
                    if mask.any():
                        ax.plot(g["compliance"][mask], [level] * int(mask.sum()), marker,
                                ls="none", color=colors[eta], ms=7,
                                label=None if name in marked else name)
                        marked.add(name)
            if math.isfinite(rigid):
                ax.axhline(rigid, ls="--", color="k", lw=1,
                           label=f"rigid bearing: {rigid:.3g}")
                ax.plot([0], [rigid], "s", color="k")
            ax.set_yscale("log")
            ax.yaxis.set_major_formatter(ScalarFormatter())
            ax.yaxis.set_minor_formatter(ScalarFormatter())
            ax.tick_params(axis="y", which="minor", labelsize=6)
            ax.set_xlim(-0.15, float(frame["compliance"].max()) + 0.15)
            ax.set_xlabel("compliance S [-]")
            ax.set_ylabel("critical mass M̄c = M c ω²/W0 [-]")
            ax.grid(alpha=0.3, which="both")
            b, w = sub["bearing_number"].iloc[0], sub["load"].iloc[0]
            set_title(ax, f"{_LAW[law]}, Λ = {b:g}, W̄ = {w:.3g}")
            ax.legend(fontsize=6.5)
    if title:
        axes[0, 0].figure.suptitle(title, fontsize=9)
    return axes


def plot_onset_against_compliance(frame, speed_range: tuple, axes=None, title: str = ""):
    """Onset speed of whirl [rpm] against S (bump thickness), one line per η, one panel per
    deflection law; the rigid bearing dashed; searches without an onset drawn at the ends
    of the range (open markers in the colour of η)."""
    laws = [law for law in ("mean", "local") if law in set(frame["deflection_law"])]
    if axes is None:
        axes = new_axes(figsize=(4.4 * len(laws), 3.8), ncols=len(laws))
    axes = np.atleast_1d(axes)
    colors = _eta_colors(set(frame.loc[frame["deflection_law"] != "rigid", "loss_factor"]))
    rigid = frame[frame["deflection_law"] == "rigid"]
    low = speed_range[0]
    for ax, law in zip(axes, laws):
        labelled = set()
        for eta, g in frame[frame["deflection_law"] == law].groupby("loss_factor"):
            g = g.sort_values("compliance")
            ok = g["onset_status"] == "onset"
            ax.plot(g["compliance"], np.where(ok, g["onset_speed_rpm"].astype(float), np.nan),
                    "o-", ms=3, color=colors[eta], label=f"η = {eta:g}")
            labelled = _no_onset_markers(ax, g["compliance"], g["onset_status"], speed_range,
                                         color=colors[eta], labelled=labelled)
        if len(rigid):
            r = rigid.iloc[0]
            if r["onset_status"] == "onset":
                ax.axhline(r["onset_speed_rpm"], ls="--", color="k", lw=1,
                           label=f"rigid bearing: {r['onset_speed_rpm']:,.0f} rpm")
            else:
                ax.plot([], [], ls="--", color="k", label=f"rigid bearing: {r['onset_status']}")
        speeds = frame["onset_speed_rpm"].astype(float)
        speeds = speeds[np.isfinite(speeds)]
        unstable = bool(frame["onset_status"].isin(["unstable at every mass",
                                                    "unstable at the lowest speed",
                                                    "load exceeds capacity"]).any())
        bottom = 0.0 if unstable or not len(speeds) else float(speeds.min()) * 0.95
        ax.set_ylim(bottom, _top(frame["onset_speed_rpm"], frame["onset_status"],
                                 speed_range))
        if bottom < low:
            _range_band(ax, low)
        if len(rigid) and rigid.iloc[0]["onset_status"] == "onset":
            ax.plot([0], [rigid.iloc[0]["onset_speed_rpm"]], "s", color="k")
        ax.set_xlim(-0.15, float(frame["compliance"].max()) + 0.15)
        ax.set_xlabel("compliance S [-]")
        ax.set_ylabel("onset speed of whirl [rpm]")
        ax.grid(alpha=0.3)
        set_title(ax, _LAW[law])
        ax.legend(fontsize=6.5)
    if title:
        import textwrap

        axes[0].figure.suptitle("\n".join(textwrap.wrap(title, 110)), fontsize=9)
    return axes
