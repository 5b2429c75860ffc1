"""Figures of the analyses: static sweeps, profiles, maps, coefficients, orbits (see the
package docstring for the conventions every figure follows).

The only module of gfbopt that imports matplotlib; solvers never plot, studies call these
functions.  Every ``plot_*(data, ax=None, ...)`` draws on ``ax`` when given and otherwise on
a new :class:`matplotlib.figure.Figure` (no pyplot, no backend and no global state, so it
works headless and leaves an interactive session's backend alone), and returns the Axes.
:func:`save_figure` writes a figure to a file.

Figures are read by people: axes carry units, legends carry descriptions rather than
variable codes, titles are wrapped to fit the axes, and published values are drawn beside
ours where there are any.
"""
from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Optional

import numpy as np
from matplotlib.figure import Figure

_VARIABLE = {"eccentricity": "eccentricity ratio ε [-]", "bearing_number": "bearing number Λ [-]"}


def new_axes(figsize=(6.4, 4.4), polar: bool = False, nrows: int = 1, ncols: int = 1,
             sharex: bool = False):
    """A new Figure (constrained layout, no pyplot) and its Axes (an array when there are
    several)."""
    fig = Figure(figsize=figsize, layout="constrained")
    if polar:
        return fig.add_subplot(projection="polar")
    return fig.subplots(nrows, ncols, sharex=sharex)


def set_title(ax, title: str, fontsize: float = 9.0) -> None:
    """``title`` wrapped to the width of ``ax`` (estimated from the font size) so that it
    is never cut."""
    if not title:
        return
    fig = ax.figure
    width_in = fig.get_figwidth() * ax.get_position().width
    chars = max(20, int(width_in * 72 / (0.55 * fontsize)))
    ax.set_title("\n".join(textwrap.wrap(title, chars)), fontsize=fontsize)


def figure_format(path) -> str:
    """The file format of ``path`` from its suffix (png when it has none), or ParameterError
    naming the formats matplotlib writes — checked before a figure's work starts."""
    from ..errors import ParameterError

    suffix = Path(path).suffix.lower().lstrip(".")
    formats = Figure().canvas.get_supported_filetypes()
    if suffix and suffix not in formats:
        raise ParameterError("figure file", str(path), "has a suffix matplotlib cannot write:"
                             f" use one of {', '.join('.' + f for f in sorted(formats))}")
    return suffix or "png"


def save_figure(fig, path) -> str:
    """Write ``fig`` to ``path`` (format from the suffix, png without one; 120 dpi, cropped
    to what is drawn so that no title or legend outside the axes is cut); returns the path.
    An existing file is overwritten (as the CSV tables are); the command line checks that it
    can be before anything is solved (gfbopt.cli.check_outputs)."""
    kind = figure_format(path)
    fig.savefig(Path(path), dpi=120, bbox_inches="tight", format=kind,
                metadata=figure_metadata(kind))
    return str(path)


def figure_metadata(kind: str) -> Optional[dict]:
    """What made the figure, in its file (as every output states it): gfbopt's version and
    source commit (with "+ uncommitted changes" when the checkout is dirty) — PNG's
    ``Software``, PDF's and SVG's ``Creator``; None for the formats without such a field."""
    from ..provenance import source_state
    from ..version import __version__

    state = source_state()
    made = f"gfbopt {__version__}" + (
        f" (commit {state['commit']}{' + uncommitted changes' if state['dirty'] else ''})"
        if state["commit"] else f" ({state['source']})")
    if kind == "png":
        return {"Software": made}
    if kind in ("pdf", "svg"):
        return {"Creator": made}
    return None


def plot_load_sweep(frame, quantity: str = "min_film_thickness_um", ax=None, title: str = "",
                    labels: Optional[dict] = None):
    """Minimum film thickness [µm] or attitude angle [deg] against static load [N], one line
    per variant and speed (thesis Figs 3.2–3.5).  ``labels``: variant → description."""
    ax = new_axes() if ax is None else ax
    labels = labels or {}
    for (variant, speed), sub in frame.groupby(["variant", "speed_rpm"], sort=False):
        ok = sub[sub["success"].astype(bool)]
        ax.plot(ok["load_newton"], ok[quantity], marker="o", ms=3,
                label=f"{labels.get(variant, variant)}, {speed:,.0f} rpm")
        bad = sub[~sub["success"].astype(bool)]
        if len(bad):
            ax.plot(bad["load_newton"], np.zeros(len(bad)), "rx", label="not converged")
    ax.set_xlabel("static load W [N]")
    ax.set_ylabel({"min_film_thickness_um": "minimum film thickness h_min [µm]",
                   "attitude_angle_deg": "attitude angle φ [deg]",
                   "eccentricity": "eccentricity ratio ε [-]"}.get(quantity, quantity))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    set_title(ax, title)
    return ax


_PROFILE = (("mean_pressure", "axially averaged pressure P̄ [-]", "max_mean_pressure"),
            ("deflection", "top-foil deflection W = w/c [-]", "max_deflection"),
            ("film_thickness", "film thickness H = h/c [-]", "min_film"))


def plot_profiles(profiles: dict, axes=None, published: Optional[dict] = None,
                  labels: Optional[dict] = None, title: str = ""):
    """P̄, W and H against the angle from the welded end of the top foil (thesis Figs
    3.6–3.8), one line per variant, with the published peaks as stars.

    ``profiles``: variant → table with ``angle_from_seam_deg``, ``mean_pressure``,
    ``deflection``, ``film_thickness``; ``axes``: three Axes (new figure when None); ``published``:
    reference → {``max_mean_pressure``, ``max_mean_pressure_angle_from_seam_deg``, …}.
    Returns the three Axes.
    """
    axes = new_axes(figsize=(6.4, 8.0), nrows=3, sharex=True) if axes is None else axes
    labels = labels or {}
    for label, table in profiles.items():
        for ax, (column, _, _) in zip(axes, _PROFILE):
            ax.plot(table["angle_from_seam_deg"], table[column], label=labels.get(label, label))
    for ref, values in (published or {}).items():
        for ax, (_, _, peak) in zip(axes, _PROFILE):
            angle = values.get(f"{peak}_angle_from_seam_deg")
            if peak in values and angle is not None:
                ax.plot(angle, values[peak], "k*", ms=10, label=f"{ref} (published peak)")
    for ax, (_, name, _) in zip(axes, _PROFILE):
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[-1].set_xlabel("angle from the welded end of the top foil [deg]")
    set_title(axes[0], title)
    return axes


def plot_pressure_field(angle_deg, z, pressure, ax=None, title: str = ""):
    """Contours of the film pressure P = p/p_a [-] over the angle from the welded end [deg]
    and the axial coordinate Z = z/R [-]; ``pressure`` has shape (angles, z)."""
    ax = new_axes(figsize=(7.0, 3.6)) if ax is None else ax
    order = np.argsort(angle_deg)
    filled = ax.contourf(np.asarray(angle_deg)[order], z, np.asarray(pressure)[order].T, 30,
                         cmap="viridis")
    ax.figure.colorbar(filled, ax=ax, label="pressure P = p/p_a [-]")
    ax.set_xlabel("angle from the welded end of the top foil [deg]")
    ax.set_ylabel("axial position Z = z/R [-]")
    set_title(ax, title)
    return ax


def plot_grid_convergence(frame, ax=None, title: str = ""):
    """|W̄ − W̄(finest grid)| / W̄ against the grid spacing 1/n_theta, log-log, per case, with a
    slope-2 guide (the scheme's formal order)."""
    ax = new_axes(figsize=(6.0, 4.6)) if ax is None else ax
    for case, sub in frame.groupby("case", sort=False):
        sub = sub.sort_values("grid_spacing")
        ref = sub["load"].iloc[0]
        err = np.abs(sub["load"].iloc[1:] - ref) / abs(ref)
        ax.loglog(sub["grid_spacing"].iloc[1:], err, "o-", label=case)
    h = np.array([frame["grid_spacing"].min() * 2, frame["grid_spacing"].max()])
    ax.loglog(h, 0.5 * (h / h[-1])**2 * 1e-2, "k--", label="second order (slope 2)")
    ax.set_xlabel("grid spacing 1/n_theta [-]")
    ax.set_ylabel("load error against the finest grid [-]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    set_title(ax, title)
    return ax


def plot_stability_map(frame, variable: str, ax=None, title: str = "", crossovers=None,
                       labels: Optional[dict] = None, linear: bool = False):
    """Critical mass M̄ = M c ω²/W0 against ε or Λ, one line per variant (thesis Figs 3.12,
    3.13, 4.9, 4.10); ``linear``: also the linear threshold (dashed); ``crossovers``: a
    table with published crossovers (``crossover_<reference>``), drawn as dotted lines."""
    ax = new_axes(figsize=(6.6, 5.6)) if ax is None else ax
    labels = labels or {}
    for label, sub in frame.groupby("variant", sort=False):
        sub = sub.sort_values(variable)
        line, = ax.plot(sub[variable], sub["critical_mass"], marker="o", ms=3,
                        label=labels.get(label, label))
        if linear and "linear_critical_mass" in sub:
            ax.plot(sub[variable], sub["linear_critical_mass"], ls="--", lw=0.8,
                    color=line.get_color(), label="_nolegend_")
    if linear:
        ax.plot([], [], "k--", lw=0.8, label="linear threshold (dashed, same colour)")
    styles = iter([":", "-.", (0, (1, 3)), (0, (5, 2, 1, 2))] * 3)
    if crossovers is not None:
        for col in [c for c in crossovers.columns if c.startswith("crossover_")]:
            ref = col[len("crossover_"):]
            for _, row in crossovers.dropna(subset=[col]).iterrows():
                ax.axvline(row[col], color="grey", ls=next(styles), lw=1.2,
                           label=f"{ref}, {row['where']}: "
                           f"{labels.get(row['variant'], row['variant'])} crosses "
                           f"{labels.get(row['against'], row['against'])}")
    ax.set_xlabel(_VARIABLE.get(variable, variable))
    ax.set_ylabel("critical mass M̄ = M c ω²/W0 [-]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1)
    set_title(ax, title)
    return ax


def plot_coefficients(frame, which: str = "stiffness", ax=None, title: str = ""):
    """Dimensional stiffness [MN/m] or damping [kN s/m] against excitation frequency [Hz],
    load frame (x along the static load), one line per coefficient."""
    ax = new_axes() if ax is None else ax
    for key in ("xx", "xy", "yx", "yy"):
        if which == "stiffness":
            ax.plot(frame["frequency_hz"], frame[f"k{key}_N_per_m"] / 1e6, label=f"$K_{{{key}}}$")
        else:
            ax.plot(frame["frequency_hz"], frame[f"c{key}_Ns_per_m"] / 1e3, label=f"$C_{{{key}}}$")
    ax.set_ylabel("stiffness [MN/m]" if which == "stiffness" else "damping [kN s/m]")
    ax.set_xlabel("excitation frequency [Hz]")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    set_title(ax, title)
    return ax


def plot_orbits(orbits: dict, ax=None, title: str = "", clearance: bool = False):
    """Journal-centre orbits in polar form (ε against attitude angle), thesis Figs 3.9–3.11.

    ``orbits`` maps a legend label to a table with columns ``eccentricity`` [-] and
    ``attitude_angle_deg`` [deg]; ``ax`` a polar Axes (a new figure when None);
    ``clearance`` draws the clearance circle ε = e/c = 1 (the undeflected foil; a compliant
    foil lets the journal beyond it).  Returns the Axes.
    """
    ax = new_axes(figsize=(5.8, 6.4), polar=True) if ax is None else ax
    if clearance:
        angle = np.linspace(0.0, 2 * np.pi, 361)
        ax.plot(angle, np.ones_like(angle), color="0.35", lw=1.0, ls="--",
                label="clearance circle ε = 1 (undeflected foil)")
        top = max([1.0] + [float(np.nanmax(t["eccentricity"])) for t in orbits.values()])
        ax.set_rmax(1.1 * top)
    for label, table in orbits.items():
        ax.plot(np.radians(table["attitude_angle_deg"]), table["eccentricity"], lw=0.8,
                label=label)
    # the radial axis: ε = e/c, the journal's displacement in radial clearances [-]
    ax.set_ylabel("eccentricity ε = e/c [-]", labelpad=34, fontsize=8)
    set_title(ax, title, fontsize=8.5)
    ax.title.set_y(1.08)             # above the 90° tick label
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.06), ncol=1)
    return ax


def plot_bifurcation(frame, ax=None, title: str = ""):
    """Limit-cycle amplitude [clearances] against M̄/M̄_crit, reached from a small and from
    a large initial displacement."""
    ax = new_axes(figsize=(6.0, 4.4)) if ax is None else ax
    ax.plot(frame["mass_ratio"], frame["amplitude_from_inside"], "o-",
            label="from a small displacement")
    ax.plot(frame["mass_ratio"], frame["amplitude_from_outside"], "x--",
            label="from a large displacement")
    ax.set_xlabel("rotor mass over linear critical mass M̄/M̄_crit [-]")
    ax.set_ylabel("limit-cycle amplitude [clearances]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    set_title(ax, title)
    return ax
