"""Figure functions: pure, return Axes, draw on a given Axes, need no pyplot or backend."""
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from gfbopt import plotting


def _map():
    rows = []
    for variant, slope in (("rigid", 10.0), ("S1", 4.0)):
        for eps in (0.1, 0.3, 0.5):
            rows.append({"variant": variant, "eccentricity": eps, "critical_mass": 1 + slope * eps,
                         "linear_critical_mass": 1 + slope * eps})
    crossovers = pd.DataFrame([{"variant": "S1", "against": "rigid", "crossover": np.nan,
                                "crossover_thesis": 0.45, "where": "Fig 3.12"}])
    return pd.DataFrame(rows), crossovers


def _sweep():
    return pd.DataFrame({"variant": ["simple"] * 3, "speed_rpm": [30000.0] * 3,
                         "load_newton": [5.0, 10.0, 20.0], "success": [True, True, False],
                         "min_film_thickness_um": [12.0, 10.0, np.nan],
                         "attitude_angle_deg": [50.0, 40.0, np.nan]})


def _coefficients():
    data = {"frequency_hz": [0.0, 100.0]}
    for key in ("xx", "xy", "yx", "yy"):
        data[f"k{key}_N_per_m"] = [1e6, 2e6]
        data[f"c{key}_Ns_per_m"] = [100.0, 200.0]
    return pd.DataFrame(data)


def _orbit():
    tau = np.linspace(0, 10, 50)
    return pd.DataFrame({"eccentricity": 0.4 + 0.01 * np.sin(tau),
                         "attitude_angle_deg": 45 + np.cos(tau)})


CALLS = {
    "stability_map": lambda ax: plotting.plot_stability_map(
        _map()[0], "eccentricity", ax=ax, title="A map", crossovers=_map()[1],
        labels={"S1": "simple foil, S = 1", "rigid": "rigid bearing"}, linear=True),
    "load_sweep": lambda ax: plotting.plot_load_sweep(_sweep(), ax=ax, title="Sweep"),
    "coefficients": lambda ax: plotting.plot_coefficients(_coefficients(), "damping", ax=ax),
    "grid_convergence": lambda ax: plotting.plot_grid_convergence(pd.DataFrame(
        {"case": ["a"] * 3, "grid_spacing": [1 / 144, 1 / 72, 1 / 36],
         "load": [1.0, 1.001, 1.004]}), ax=ax),
    "bifurcation": lambda ax: plotting.plot_bifurcation(pd.DataFrame(
        {"mass_ratio": [1.03, 1.05], "amplitude_from_inside": [0.1, 0.2],
         "amplitude_from_outside": [0.1, 0.2]}), ax=ax),
    "pressure_field": lambda ax: plotting.plot_pressure_field(
        np.linspace(0, 360, 10), np.linspace(-1, 1, 5), np.ones((10, 5)) + np.arange(5) * 0.1,
        ax=ax),
}


@pytest.mark.parametrize("name", sorted(CALLS))
def test_returns_axes_on_a_new_figure(name, tmp_path):
    ax = CALLS[name](None)
    assert isinstance(ax, Axes) and isinstance(ax.figure, Figure)
    path = plotting.save_figure(ax.figure, tmp_path / f"{name}.png")
    assert (tmp_path / f"{name}.png").stat().st_size > 1000 and path.endswith(".png")


@pytest.mark.parametrize("name", sorted(CALLS))
def test_draws_on_a_given_axes(name):
    fig = Figure()
    ax = fig.add_subplot()
    assert CALLS[name](ax) is ax
    assert ax.has_data()


def test_orbits_keep_their_signature_and_accept_a_polar_axes():
    ax = plotting.plot_orbits({"M̄ = 2: stable": _orbit()}, title="orbits")
    assert ax.name == "polar" and ax.get_legend().get_texts()[0].get_text() == "M̄ = 2: stable"
    fig = Figure()
    polar = fig.add_subplot(projection="polar")
    assert plotting.plot_orbits({"a": _orbit()}, ax=polar, title="") is polar


def test_profiles_draw_three_panels_with_the_published_peaks():
    angle = np.linspace(0, 360, 20)
    table = pd.DataFrame({"angle_from_seam_deg": angle, "mean_pressure": 1 + np.sin(angle / 60),
                          "deflection": np.sin(angle / 60),
                          "film_thickness": 1 - 0.5 * np.sin(angle / 60)})
    axes = plotting.plot_profiles({"thesis_seam": table},
                                  published={"thesis": {"min_film": 0.545,
                                                        "min_film_angle_from_seam_deg": 236.0}},
                                  labels={"thesis_seam": "seam on the max-film line"})
    assert len(axes) == 3
    labels = [t.get_text() for t in axes[2].get_legend().get_texts()]
    assert labels == ["seam on the max-film line", "thesis (published peak)"]


def test_a_long_title_is_wrapped_to_the_axes_width():
    ax = plotting.plot_bifurcation(pd.DataFrame(
        {"mass_ratio": [1.0], "amplitude_from_inside": [0.1], "amplitude_from_outside": [0.1]}),
        title="word " * 60)
    lines = ax.get_title().splitlines()
    assert len(lines) > 2 and max(len(line) for line in lines) < 110


def test_import_neither_loads_pyplot_nor_chooses_a_backend():
    code = ("import sys, matplotlib; before = matplotlib.get_backend.__module__; "
            "import gfbopt.plotting, gfbopt.studies; "
            "assert 'matplotlib.pyplot' not in sys.modules, 'pyplot imported'; print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


def test_orbit_figure_draws_the_clearance_circle():
    """Issue 14 item 9: the orbit shows e/c against the clearance circle ε = 1, labelled."""
    ax = plotting.plot_orbits({"M̄ = 2: stable": _orbit()}, title="orbits", clearance=True)
    circle = [line for line in ax.get_lines() if "clearance circle" in line.get_label()]
    assert len(circle) == 1
    np.testing.assert_allclose(circle[0].get_ydata(), 1.0)
    assert np.ptp(circle[0].get_xdata()) == pytest.approx(2 * np.pi)
    assert ax.get_rmax() >= 1.0
