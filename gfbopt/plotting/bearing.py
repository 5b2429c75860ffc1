"""Figures of the bearing as built: load capacity and lift-off curves, the bore profile, and
onset speed or drag against a design lever (preload, pads, speed, load)."""
from __future__ import annotations

import math

import numpy as np

from .core import new_axes, set_title


def plot_capacity_curve(result: dict, ax=None, title: str = ""):
    """Minimum film [µm] against load [N] (capacity) or speed [rpm] (lift-off) along the
    continuation, with the film limit and the answer drawn.  ``result``: the ``to_dict()``
    of :class:`gfbopt.rotor.capacity.CurveResult` (at the running condition, with
    ``thermal_model``: the title says each point is at its own running condition, and the
    points with no running state are drawn apart).  Returns the Axes."""
    ax = new_axes() if ax is None else ax
    capacity = result["kind"] == "capacity"
    x = "load_newton" if capacity else "speed_rpm"
    rows = sorted((r for r in result["curve"] if r["success"]), key=lambda r: r[x])
    model = result.get("thermal_model") or result.get("conventions", {}).get("thermal_model")
    heated = bool(model) and model != "isothermal, cold clearance"
    ax.plot([r[x] for r in rows], [r["min_film_thickness_um"] for r in rows], "o-", ms=3,
            label="gfbopt (continuation, warm starts)" + (
                ", each point at its running condition" if heated else ""))
    stateless = [r[x] for r in result["curve"]
                 if r.get("thermal_status") in ("runaway", "closure")]
    failed = [r[x] for r in result["curve"] if not r["success"]
              and r.get("thermal_status") not in ("runaway", "closure")]
    if failed:
        ax.plot(failed, np.zeros(len(failed)), "rx", label="no equilibrium (film closes)")
    if stateless:
        ax.plot(stateless, np.zeros(len(stateless)), "m^",
                label="no running state (thermal runaway or closure)")
    limit = result["min_film_limit_um"]
    ax.axhline(limit, color="k", ls="--", lw=1.0, label=f"film limit {limit:.4g} µm")
    value = result["load_capacity_newton" if capacity else "lift_off_speed_rpm"]
    if math.isfinite(value):
        ax.axvline(value, color="grey", ls=":", lw=1.0,
                   label=(f"load capacity {value:.4g} N" if capacity
                          else f"lift-off {value:,.0f} rpm"))
    ax.set_xscale("log")
    ax.set_xlabel("static load W [N]" if capacity else "shaft speed [rpm]")
    ax.set_ylabel("minimum film thickness h_min [µm]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fixed = (f"at {result['speed_rpm']:,.0f} rpm" if capacity
             else f"under {result['load_newton']:.4g} N")
    found = ((f"{value:.4g} N" if capacity else f"{value:,.0f} rpm") if math.isfinite(value)
             else result["answer"])
    where = f"; each point at its own running condition ({model})" if heated else ""
    set_title(ax, title or ("Load capacity " if capacity else "Lift-off speed ") + fixed
              + f" for h_min ≥ {limit:.4g} µm: {found} ({result.get('bearing', '')}{where})")
    return ax


def plot_bore_profile(theta_deg, clearance_um, ax=None, title: str = "",
                      nominal_um: float = math.nan):
    """Radial clearance [µm] with the journal concentric against the angle from the load
    line [deg], the nominal clearance dotted."""
    ax = new_axes() if ax is None else ax
    ax.plot(theta_deg, clearance_um, "-", label="bore as built")
    if math.isfinite(nominal_um):
        ax.axhline(nominal_um, color="k", ls=":", lw=1.0, label=f"nominal clearance "
                   f"{nominal_um:.4g} µm")
    ax.set_xlabel("angle from the load line θ [deg]")
    ax.set_ylabel("radial clearance c (1 + B) [µm]")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    set_title(ax, title)
    return ax


def plot_against_lever(table, x: str, y: str, group: str = "", ax=None, title: str = "",
                       xlabel: str = "", ylabel: str = "", reference: float = math.nan,
                       reference_label: str = "", group_label: str = "{}"):
    """``y`` against ``x`` from a table (DataFrame), one line per value of ``group`` (when
    given, labelled ``group_label.format(value)``, e.g. "W = {:g} N"); failed rows
    (``success`` False) as crosses; a reference value dashed."""
    ax = new_axes() if ax is None else ax
    groups = table.groupby(group, sort=True) if group else [(None, table)]
    for key, sub in groups:
        sub = sub.sort_values(x)
        ok = sub[sub["success"].astype(bool)]
        label = "gfbopt" if key is None else group_label.format(key)
        line, = ax.plot(ok[x], ok[y], "o-", ms=3, label=label)
        bad = sub[~sub["success"].astype(bool)]
        if len(bad):
            ax.plot(bad[x], np.zeros(len(bad)), "x", color=line.get_color(),
                    label="_nolegend_")
    if math.isfinite(reference):
        ax.axhline(reference, color="k", ls="--", lw=1.0, label=reference_label)
    ax.set_xlabel(xlabel or x)
    ax.set_ylabel(ylabel or y)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    set_title(ax, title)
    return ax
