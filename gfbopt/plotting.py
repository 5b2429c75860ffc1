"""Figures.  The only module that imports matplotlib; solvers never plot.

Every function takes results (solutions or DataFrames) and an output folder, writes PNG
files and returns their paths.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def _save(fig, path: Path) -> str:
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return str(path)


def plot_load_sweep(frame, out: Path, title: str = "") -> list[str]:
    """Minimum film [µm] and attitude angle [deg] against load [N] (thesis Figs 3.2–3.5)."""
    files = []
    for column, label, name in (("min_film_um", "minimum film thickness [µm]", "min_film"),
                                ("attitude_deg", "attitude angle [deg]", "attitude")):
        fig, ax = plt.subplots(figsize=(6, 4))
        for (variant, speed), sub in frame.groupby(["variant", "speed_rpm"]):
            ok = sub[sub["success"]]
            ax.plot(ok["load_newton"], ok[column], marker="o", ms=3,
                    label=f"{variant}, {speed:,.0f} rpm")
            bad = sub[~sub["success"]]
            if len(bad):
                ax.plot(bad["load_newton"], bad[column], "rx", label="not converged")
        ax.set_xlabel("static load [N]")
        ax.set_ylabel(label)
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        files.append(_save(fig, out / f"{name}_vs_load.png"))
    return files


def plot_profiles(solutions: dict, out: Path, published: dict | None = None) -> list[str]:
    """P̄, W and H against the angle from the welded end (thesis Figs 3.6–3.8), and P(θ, Z)."""
    published = published or {}
    files = []
    fig, axes = plt.subplots(3, 1, figsize=(6, 8), sharex=True)
    for label, sol in solutions.items():
        ang = np.degrees(sol.theta_from_seam)
        order = np.argsort(ang)
        axes[0].plot(ang[order], sol.mean_pressure[order], label=label)
        axes[1].plot(ang[order], sol.deflection[order, 0], label=label)
        axes[2].plot(ang[order], sol.film.min(axis=1)[order], label=label)
    marks = (("max_mean_pressure", 0), ("max_deflection", 1), ("min_film", 2))
    for key, i in marks:
        if key in published and f"{key}_at_deg" in published:
            axes[i].plot(published[f"{key}_at_deg"], published[key], "k*", ms=10,
                         label="thesis")
    for ax, name in zip(axes, ("axially averaged pressure P̄ [-]", "top-foil deflection W [-]",
                               "film thickness H [-]")):
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[-1].set_xlabel("angle from the welded end of the top foil [deg]")
    files.append(_save(fig, out / "profiles.png"))
    for label, sol in solutions.items():
        fig, ax = plt.subplots(figsize=(7, 3.5))
        ang = np.degrees(sol.theta_from_seam)
        order = np.argsort(ang)
        c = ax.contourf(ang[order], sol.z, sol.pressure[order].T, 30, cmap="viridis")
        fig.colorbar(c, ax=ax, label="P [-]")
        ax.set_xlabel("angle from the welded end [deg]")
        ax.set_ylabel("Z = z/R [-]")
        ax.set_title(f"pressure field — {label}", fontsize=9)
        files.append(_save(fig, out / f"pressure_field_{label}.png"))
    return files


def plot_grid_convergence(frame, out: Path) -> list[str]:
    """|load − finest| against the grid spacing, log-log, per case."""
    fig, ax = plt.subplots(figsize=(5, 4))
    for case, sub in frame.groupby("case", sort=False):
        sub = sub.sort_values("h")
        ref = sub["load"].iloc[0]
        err = np.abs(sub["load"].iloc[1:] - ref) / abs(ref)
        ax.loglog(sub["h"].iloc[1:], err, "o-", label=case)
    h = np.array([frame["h"].min() * 2, frame["h"].max()])
    ax.loglog(h, 0.5 * (h / h[-1])**2 * 1e-2, "k--", label="slope 2")
    ax.set_xlabel("1 / n_theta")
    ax.set_ylabel("|load − finest-grid load| / load")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    return [_save(fig, out / "grid_convergence.png")]


def plot_stability_map(frame, axis: str, out: Path, title: str = "",
                       crossovers=None) -> list[str]:
    """Critical mass M̄ = M c ω²/W0 against ε or Λ per variant (thesis Figs 3.12, 3.13, …)."""
    fig, ax = plt.subplots(figsize=(6, 4))
    for label, sub in frame.groupby("variant", sort=False):
        sub = sub.sort_values(axis)
        ax.plot(sub[axis], sub["critical_mass"], marker="o", ms=3, label=label)
    if crossovers is not None and "crossover_thesis" in crossovers:
        for _, row in crossovers.dropna(subset=["crossover_thesis"]).iterrows():
            ax.axvline(row["crossover_thesis"], color="grey", ls=":", lw=1)
    ax.set_xlabel("eccentricity ratio ε" if axis == "eps" else "bearing number Λ")
    ax.set_ylabel("critical mass M̄ = M c ω²/W0 [-]")
    ax.set_title(title, fontsize=8)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return [_save(fig, out / "critical_mass.png")]


def plot_coefficients(frame, out: Path, title: str = "") -> list[str]:
    """Dimensional stiffness [MN/m] and damping [kN s/m] against excitation frequency."""
    files = []
    for (label, speed, load_n), sub in frame.groupby(["variant", "speed_rpm", "load_newton"]):
        fig, axes = plt.subplots(1, 2, figsize=(10, 4))
        for key in ("xx", "xy", "yx", "yy"):
            axes[0].plot(sub["frequency_hz"], sub[f"k{key}_N_per_m"] / 1e6, label=f"K{key}")
            axes[1].plot(sub["frequency_hz"], sub[f"c{key}_Ns_per_m"] / 1e3, label=f"C{key}")
        axes[0].set_ylabel("stiffness [MN/m]")
        axes[1].set_ylabel("damping [kN s/m]")
        for ax in axes:
            ax.set_xlabel("excitation frequency [Hz]")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
        fig.suptitle(f"{title}\n{label}, {speed:,.0f} rpm, {load_n:g} N", fontsize=8)
        files.append(_save(fig, out / f"coefficients_{label}_{int(speed)}rpm_{int(load_n)}N.png"))
    return files


def save_figure(fig, path) -> str:
    """Lay out ``fig``, write it to ``path`` (PNG, 120 dpi), close it; returns the path."""
    return _save(fig, Path(path))


def plot_orbits(orbits: dict, ax=None, title: str = ""):
    """Journal-centre orbits in polar form (ε against attitude angle), thesis Figs 3.9–3.11.

    ``orbits`` maps a legend label to a table with columns ``eccentricity`` [-] and
    ``attitude_angle_deg`` [deg]; ``ax`` a polar Axes (a new figure when None).  Returns the
    Axes.
    """
    if ax is None:
        fig = plt.figure(figsize=(5.5, 5.5))
        ax = fig.add_subplot(projection="polar")
    for label, table in orbits.items():
        ax.plot(np.radians(table["attitude_angle_deg"]), table["eccentricity"], lw=0.8,
                label=label)
    ax.set_title(title, fontsize=8)
    ax.legend(fontsize=7, loc="lower left", bbox_to_anchor=(-0.1, -0.15))
    return ax


def plot_bifurcation(frame, out: Path, title: str = "") -> list[str]:
    """Limit-cycle amplitude against M̄/M̄_crit, reached from inside and from outside."""
    fig, ax = plt.subplots(figsize=(5.5, 4))
    ax.plot(frame["mass_ratio"], frame["amplitude_from_inside"], "o-", label="from a small kick")
    ax.plot(frame["mass_ratio"], frame["amplitude_from_outside"], "x--",
            label="from a large displacement")
    ax.set_xlabel("M̄ / M̄_crit (linear)")
    ax.set_ylabel("limit-cycle amplitude [clearances]")
    ax.set_title(title, fontsize=8)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return [_save(fig, out / "bifurcation.png")]
