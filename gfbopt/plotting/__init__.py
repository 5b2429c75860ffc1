"""Figures: pure functions from results (DataFrames, dicts of tables) to matplotlib Axes.

The only package of gfbopt that imports matplotlib; solvers never plot, studies call these
functions.  Every ``plot_*(data, ax=None, ...)`` draws on ``ax`` when given and otherwise on
a new :class:`matplotlib.figure.Figure` (no pyplot, no backend, no global state), and returns
the Axes; :func:`save_figure` writes a figure to a file.

=====================  ==============================================================
module                 figures
=====================  ==============================================================
:mod:`.core`           static sweeps, profiles, grid convergence, stability maps,
                       coefficients, orbits, bifurcation; the shared helpers
:mod:`.design`         stability-driven bump design (onset speed against S and pitch)
:mod:`.stability`      onset speed against seam angle and loss factor
:mod:`.bearing`        the bearing as built: capacity, lift-off, bore profile, levers
:mod:`.design_front`   a rotor's bearing-pair design search: designs, front, choice
:mod:`.doe`            Sobol sensitivity indices
:mod:`.rotor`          Campbell diagram, imbalance response, onsets of a rotor
:mod:`.waterfall`      rotor transients: waterfall, components against speed, orbits
=====================  ==============================================================
"""
from .design import plot_design_against_compliance, plot_design_against_pitch
from .core import (new_axes, plot_bifurcation, plot_coefficients, plot_grid_convergence,
                   plot_load_sweep, plot_orbits, plot_pressure_field, plot_profiles,
                   plot_stability_map, save_figure, set_title)

__all__ = ["plot_design_against_compliance", "plot_design_against_pitch", "new_axes", "plot_bifurcation", "plot_coefficients", "plot_grid_convergence",
           "plot_load_sweep", "plot_orbits", "plot_pressure_field", "plot_profiles",
           "plot_stability_map", "save_figure", "set_title"]
from .doe import plot_sobol_indices  # noqa: E402  (design of experiments)

__all__ += ["plot_sobol_indices"]
from .stability import (plot_critical_mass_against_compliance,  # noqa: E402  (stability)
                        plot_onset_against_compliance, plot_onset_against_seam)

__all__ += ["plot_critical_mass_against_compliance", "plot_onset_against_compliance",
            "plot_onset_against_seam"]
