"""Figures of rotor transients: the waterfall, the components against speed, journal orbits.

Pure functions of the results of :mod:`gfbopt.transient.rotor_result` (a
:class:`~gfbopt.transient.spectra.Waterfall` per bearing, tables with glossary columns).
"""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

from .core import new_axes, set_title


def contact_label(contact: Optional[dict]) -> str:
    """The legend entry of a contact ``{contact_bearing, contact_speed_rpm, contact_time_s}``
    (a run's JSON keys): 'contact at B, 15,528 rpm, t = 0.2764 s'."""
    return (f"contact at {contact['contact_bearing']}, {contact['contact_speed_rpm']:,.0f} "
            f"rpm, t = {contact['contact_time_s']:.4g} s")


def plot_waterfall(waterfall, ax=None, title: str = "", bearing: str = "",
                   floor_um: Optional[float] = None, linear_onset_rpm: float = math.nan,
                   appearance_rpm: float = math.nan, contact: Optional[dict] = None):
    """Amplitude spectrum of a bearing's whirl [µm, log colour] against frequency [Hz]
    (positive: forward whirl) and shaft speed [rpm], with the 1× and ½× lines, the linear
    onset (dashed), the speed where the subsynchronous line appears (dotted) and, for a run
    that ended in ``contact`` (its JSON keys, :func:`contact_label`), the contact speed
    (solid black; the speed axis reaches it)."""
    ax = new_axes(figsize=(7.0, 5.0)) if ax is None else ax
    w = waterfall
    if not w.time_s.size:
        ax.text(0.5, 0.5, "record too short for a waterfall", ha="center",
                transform=ax.transAxes)
        set_title(ax, title)
        return ax
    amp = np.maximum(w.amplitude, 1e-12)
    top = float(np.nanmax(amp))
    floor = floor_um if floor_um is not None else top * 1e-3
    from matplotlib.colors import LogNorm

    mesh = ax.pcolormesh(w.frequency_hz, w.speed_rpm, np.clip(amp, floor, top),
                         norm=LogNorm(floor, top), cmap="viridis", shading="nearest")
    ax.figure.colorbar(mesh, ax=ax, label=f"whirl amplitude {bearing} [µm, zero to peak]")
    speeds = np.array([w.speed_rpm.min(), w.speed_rpm.max()])
    ax.plot(speeds / 60.0, speeds, "w-", lw=1.0, label="1× (synchronous)")
    ax.plot(speeds / 120.0, speeds, "w:", lw=1.0, label="½×")
    if math.isfinite(linear_onset_rpm):
        ax.axhline(linear_onset_rpm, color="r", ls="--", lw=1.2,
                   label=f"linear onset {linear_onset_rpm:,.0f} rpm")
    if math.isfinite(appearance_rpm):
        ax.axhline(appearance_rpm, color="orange", ls=":", lw=1.5,
                   label=f"subsynchronous line appears {appearance_rpm:,.0f} rpm")
    if contact is not None:
        speed = contact["contact_speed_rpm"]
        ax.axhline(speed, color="k", ls="-", lw=1.5, label=contact_label(contact))
        low, high = ax.get_ylim()
        ax.set_ylim(min(low, speed), max(high, speed))
    ax.set_xlim(0.0, float(w.frequency_hz.max()))
    ax.set_xlabel("frequency [Hz] (forward whirl)")
    ax.set_ylabel("shaft speed [rpm]")
    ax.legend(fontsize=7, loc="lower right")
    set_title(ax, title)
    return ax


def plot_components(tables: dict, axes=None, title: str = "",
                    linear_onset_rpm: float = math.nan, threshold_um: float = math.nan,
                    contact: Optional[dict] = None):
    """Synchronous amplitude (the 1× orbit's major semi-axis, ``sync_amplitude_um``, as in
    the JSON and the linear imbalance response), its x and y amplitudes, and the
    subsynchronous amplitude [µm] against speed (top) and the subsynchronous whirl ratio
    (bottom), one colour per bearing (``tables``: bearing → components table of
    :meth:`~gfbopt.transient.spectra.Waterfall.table`); a run that ended in ``contact`` has
    its contact speed marked (solid black, :func:`contact_label`)."""
    axes = new_axes(figsize=(6.6, 6.4), nrows=2, sharex=True) if axes is None else axes
    top, bottom = axes
    for name, t in tables.items():
        line, = top.semilogy(t["speed_rpm"], t["sync_amplitude_um"],
                             label=f"{name}: 1× (major semi-axis)")
        top.semilogy(t["speed_rpm"], t["sync_amplitude_x_um"], ls="--", lw=0.8,
                     color=line.get_color(), label=f"{name}: 1×, x")
        top.semilogy(t["speed_rpm"], t["sync_amplitude_y_um"], ls="-.", lw=0.8,
                     color=line.get_color(), label=f"{name}: 1×, y")
        top.semilogy(t["speed_rpm"], t["sub_amplitude_um"], ls=":", lw=2,
                     color=line.get_color(), label=f"{name}: subsynchronous")
        bottom.plot(t["speed_rpm"], t["sub_whirl_ratio"], ".", color=line.get_color(),
                    label=name)
    for ax in axes:
        if math.isfinite(linear_onset_rpm):
            ax.axvline(linear_onset_rpm, color="r", ls="--", lw=1, label="linear onset")
        if contact is not None:
            ax.axvline(contact["contact_speed_rpm"], color="k", ls="-", lw=1.5,
                       label=contact_label(contact))
        ax.grid(alpha=0.3, which="both")
    if math.isfinite(threshold_um):
        top.axhline(threshold_um, color="grey", lw=0.8, label="appearance threshold")
    top.set_ylabel("amplitude [µm, zero to peak]")
    bottom.set_ylabel("subsynchronous whirl ratio f/f_shaft [-]")
    bottom.set_xlabel("shaft speed [rpm]")
    top.legend(fontsize=7, ncol=2)
    bottom.legend(fontsize=7)
    set_title(top, title)
    return axes


def plot_journal_orbits(frame, names, ax=None, title: str = "", clearance_um=None):
    """Journal-centre orbits [µm, global frame: x along gravity] of each bearing, with the
    clearance circle when ``clearance_um`` is given."""
    ax = new_axes(figsize=(5.6, 5.6)) if ax is None else ax
    for name in names:
        ax.plot(frame[f"y_{name}_um"], frame[f"x_{name}_um"], lw=0.7, label=f"bearing {name}")
    if clearance_um:
        a = np.linspace(0, 2 * np.pi, 200)
        ax.plot(clearance_um * np.cos(a), clearance_um * np.sin(a), "k--", lw=0.8,
                label=f"clearance {clearance_um:g} µm")
    ax.set_aspect("equal")
    ax.invert_yaxis()                                   # gravity (+x) points down
    ax.set_xlabel("y [µm] (90° ahead of gravity, direction of rotation)")
    ax.set_ylabel("x [µm] (along gravity, downwards)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    set_title(ax, title)
    return ax
