"""Figures of a rigid rotor on two foil bearings (:mod:`gfbopt.rotor.diagrams`): the Campbell
diagram (damped natural frequencies and log decrement against speed, the 1× line, each mode's
onset and the top speed marked) and the imbalance response (Bode: amplitude and phase against
speed, the peak and the onset marked, the range above the first onset shaded)."""
from __future__ import annotations

import math

import numpy as np

from .core import new_axes, set_title

_STYLE = {"forward": "-", "backward": "--"}
#: the markers of tracks 1–10, 11–20, … (the colours C0–C9 repeat every ten tracks)
_MARKERS = ("o", "s", "^", "D")


def _mark_speeds(ax, onsets: dict, top_speed_rpm, legend: bool = True) -> None:
    """Vertical lines: each mode's onset (red, dotted) and the top running speed (black)."""
    for k, (label, speed) in enumerate(sorted(onsets.items(), key=lambda kv: kv[1])):
        if speed is not None and math.isfinite(speed):
            ax.axvline(speed, color="tab:red", ls=":", lw=1.2 if k else 1.8,
                       label=(f"onset, {label}: {speed:,.0f} rpm" if legend else None))
    if top_speed_rpm:
        ax.axvline(top_speed_rpm, color="black", lw=1.0,
                   label=f"top speed {top_speed_rpm:,.0f} rpm" if legend else None)


def plot_campbell(table, onsets: dict | None = None, top_speed_rpm: float | None = None,
                  axes=None, title: str = ""):
    """Campbell diagram from a :class:`~gfbopt.rotor.diagrams.CampbellDiagram` table: damped
    natural frequency [Hz] against speed [rpm] with the 1× (synchronous) line, and the log
    decrement [-] below (0: onset); one line per tracked mode (solid forward, dashed
    backward; colour and marker its own: colours C0–C9, the marker changing every ten
    tracks), its legend entry "mode N: track_label"; ``onsets`` : mode label → onset speed [rpm] (the matched-whirl onsets)."""
    if axes is None:
        axes = new_axes(figsize=(7.2, 6.4), nrows=2, sharex=True)
    ax_f, ax_d = axes
    onsets = onsets or {}
    count = int(table["mode"].nunique())
    colors = {}
    for mode, part in table.groupby("mode"):
        part = part.sort_values("speed_rpm")
        label = part["track_label"].iloc[0]
        # each track its own colour and marker: beyond ten tracks the colours repeat, the
        # markers do not (a track read as another mode in the legend otherwise)
        k = len(colors)
        color = colors.setdefault(mode, f"C{k % 10}")
        marker = _MARKERS[(k // 10) % len(_MARKERS)]
        style = _STYLE["backward" if label.startswith("backward") else "forward"]
        ax_f.plot(part["speed_rpm"], part["whirl_frequency_hz"], style, marker=marker, ms=3,
                  color=color, label=f"mode {mode}: {label}")
        ax_d.plot(part["speed_rpm"], part["log_decrement"], style, marker=marker, ms=3,
                  color=color)
    speeds = np.array([0.0, float(table["speed_rpm"].max()) * 1.05])
    ax_f.plot(speeds, speeds / 60.0, color="0.4", lw=1.0, label="1× (synchronous) line")
    ax_d.axhline(0.0, color="0.4", lw=1.0)
    ax_d.axhspan(min(0.0, float(table["log_decrement"].min()) * 1.1), 0.0, color="mistyrose",
                 zorder=0, label="unstable (log decrement < 0)")
    _mark_speeds(ax_f, onsets, top_speed_rpm)
    _mark_speeds(ax_d, onsets, top_speed_rpm, legend=False)
    ax_f.set_ylabel("damped natural frequency [Hz]")
    ax_d.set_ylabel("log decrement [-]")
    ax_d.set_xlabel("shaft speed [rpm]")
    ax_f.set_xlim(0, speeds[1])
    ax_f.set_ylim(0, max(float(table["whirl_frequency_hz"].max()) * 1.1, 1.0))
    ax_f.legend(fontsize=7, loc="upper left", ncol=2 if count > 8 else 1)
    ax_d.legend(fontsize=7, loc="lower left")
    set_title(ax_f, title or "Campbell diagram (eigenvalues of the full linearised system)")
    return ax_f, ax_d


def plot_imbalance_response(table, peaks: dict | None = None, onsets: dict | None = None,
                            top_speed_rpm: float | None = None, axes=None, title: str = "",
                            unstable_from_rpm: float | None = None):
    """Bode diagram from an :class:`~gfbopt.rotor.diagrams.ImbalanceResponse` table: the
    orbit's major semi-axis [µm] and the phase of x [deg] against speed [rpm], one line per
    station; the onsets and the top speed as vertical lines.  Above ``unstable_from_rpm`` (the
    first onset) the linear response belongs to an unstable rotor and is not physical: that
    range is shaded (as the Campbell diagram shades negative damping), the curve drawn thin
    and dashed there, and a peak there drawn as an open marker labelled so; a peak below it
    as a filled marker."""
    if axes is None:
        axes = new_axes(figsize=(7.2, 6.0), nrows=2, sharex=True)
    ax_a, ax_p = axes
    peaks = peaks or {}
    limit = (unstable_from_rpm if unstable_from_rpm is not None
             and math.isfinite(unstable_from_rpm) else math.inf)
    for k, (station, part) in enumerate(table.groupby("station", sort=False)):
        part = part.sort_values("speed_rpm")
        color = f"C{k % 10}"
        below = part[part["speed_rpm"] < limit]
        above = part.iloc[max(len(below) - 1, 0):] if len(below) < len(part) else below[:0]
        for piece, style, width, label in ((below, "-", 1.5, str(station)),
                                           (above, "--", 0.8, None)):
            if len(piece):
                ax_a.plot(piece["speed_rpm"], piece["amplitude_um"], style, lw=width,
                          color=color, label=label if len(below) else str(station))
                ax_p.plot(piece["speed_rpm"], piece["phase_x_deg"], style, lw=width,
                          color=color)
        if station in peaks:
            p = peaks[station]
            unstable = p["peak_speed_rpm"] >= limit
            ax_a.plot([p["peak_speed_rpm"]], [p["peak_amplitude_um"]], "v", color=color,
                      mfc="none" if unstable else color,
                      label=f"peak {station}: {p['peak_amplitude_um']:.3g} µm at "
                      f"{p['peak_speed_rpm']:,.0f} rpm"
                      + (" (above the onset: not physical)" if unstable else ""))
    if math.isfinite(limit):
        right = max(float(table["speed_rpm"].max()), top_speed_rpm or 0.0) * 1.05
        for ax, label in ((ax_a, f"unstable above {limit:,.0f} rpm: linear response not "
                           "physical"), (ax_p, None)):
            ax.axvspan(limit, right, color="mistyrose", zorder=0, label=label)
    _mark_speeds(ax_a, onsets or {}, top_speed_rpm)
    _mark_speeds(ax_p, onsets or {}, top_speed_rpm, legend=False)
    ax_a.set_ylabel("orbit major semi-axis [µm]")
    ax_p.set_ylabel("phase of x [deg]")
    ax_p.set_xlabel("shaft speed [rpm]")
    ax_p.set_ylim(-180, 180)
    ax_a.set_ylim(bottom=0)
    ax_a.legend(fontsize=7)
    set_title(ax_a, title or "Linear imbalance response (synchronous impedances)")
    return ax_a, ax_p


def plot_onsets(modes: list, half_mass: list | None = None, top_speed_rpm: float | None = None,
                ax=None, title: str = ""):
    """Onset speed [rpm] of each mode (exact, two-bearing matched whirl) beside the
    per-bearing half-mass approximation (each bearing alone with its share of mass and load);
    modes without an onset are drawn at the top speed with an open marker."""
    ax = new_axes(figsize=(7.2, 4.0)) if ax is None else ax
    labels, values, open_ = [], [], []
    for m in modes:
        labels.append(f"{m['label']}\n(two bearings)")
        v = m["onset_speed_rpm"]
        open_.append(v is None or not math.isfinite(v))
        values.append(top_speed_rpm if open_[-1] else v)
    for h in half_mass or []:
        labels.append(f"bearing {h['bearing']} alone\n({h['mass_share_kg']:.3g} kg, "
                      f"{h['load_newton']:.3g} N)")
        v = h["onset_speed_rpm"]
        open_.append(v is None or not math.isfinite(v))
        values.append(top_speed_rpm if open_[-1] else v)
    y = np.arange(len(labels))
    colors = ["tab:blue"] * len(modes) + ["tab:gray"] * len(half_mass or [])
    ax.barh(y, [v or 0 for v in values], color=colors,
            hatch=None, alpha=0.85)
    for yi, v, o in zip(y, values, open_):
        if v:
            ax.text(v, yi, (" no onset in range" if o else f" {v:,.0f} rpm"), va="center",
                    fontsize=8)
    if top_speed_rpm:
        ax.axvline(top_speed_rpm, color="black", lw=1, label=f"top speed {top_speed_rpm:,.0f}"
                   " rpm")
        ax.legend(fontsize=7, loc="lower right")
    ax.set_yticks(y, labels, fontsize=7)
    ax.set_xlabel("onset speed of whirl [rpm]")
    ax.set_xlim(0, max([v for v in values if v] + [top_speed_rpm or 1]) * 1.3)
    set_title(ax, title or "Onset of each mode against the per-bearing (half-mass) rule")
    return ax
