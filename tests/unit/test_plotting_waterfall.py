"""Figures of rotor transients: pure functions returning Axes (new figure or the given one)."""
import math

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from gfbopt.plotting import save_figure
from gfbopt.plotting.waterfall import plot_components, plot_journal_orbits, plot_waterfall
from gfbopt.transient import spectra


def _waterfall():
    t = np.linspace(0.0, 0.3, 6001)
    rpm = 10_000 + 20_000 * t
    angle = np.cumsum(rpm / 60 * 2 * math.pi) * (t[1] - t[0])
    z = np.exp(1j * angle) + np.where(t > 0.15, 2.0, 0.0) * np.exp(0.45j * angle)
    return spectra.waterfall(t, z.real, z.imag, angle, rpm, window_s=0.02)


def test_waterfall_components_and_orbits_figures(tmp_path):
    w = _waterfall()
    ax = plot_waterfall(w, bearing="A", linear_onset_rpm=14_000, appearance_rpm=15_500,
                        title="Waterfall")
    assert isinstance(ax, Axes) and isinstance(ax.figure, Figure)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels[0] == "1× (synchronous)" and "linear onset 14,000 rpm" in labels
    save_figure(ax.figure, tmp_path / "w.png")
    assert (tmp_path / "w.png").stat().st_size > 1000
    fig = Figure()
    given = fig.add_subplot()
    assert plot_waterfall(w, ax=given) is given and given.has_data()
    axes = plot_components({"A": w.table()}, linear_onset_rpm=14_000, threshold_um=0.4)
    assert len(axes) == 2 and axes[0].has_data()
    # the figure's 1× line is the synchronous amplitude of the JSON and the CSV
    first = axes[0].get_lines()[0]
    assert first.get_label() == "A: 1× (major semi-axis)"
    assert np.allclose(first.get_ydata(), w.table()["sync_amplitude_um"])
    frame = {"x_A_um": np.cos(np.linspace(0, 6, 50)), "y_A_um": np.sin(np.linspace(0, 6, 50))}
    ax = plot_journal_orbits(frame, ["A"], clearance_um=20.0)
    assert ax.yaxis_inverted() and ax.has_data()
