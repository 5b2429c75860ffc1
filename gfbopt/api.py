"""The public entry points reachable from the top: ``gfbopt.load_rotor``, ``gfbopt.stability``
… — the functions the command line wraps, each taking the grid as a :class:`~gfbopt.inputs.
grid.Grid` or as the command line writes it (``grid="72x20"``).

=========================  ==================================================================
name                       what it answers (the command that wraps it)
=========================  ==================================================================
*inputs*
:func:`load_bearing`       a bearing file → the bearing in SI, with its ``[model]`` table
:func:`load_rotor`         a rotor file → the rigid rotor on its two bearings
*one bearing*
:func:`stability`          verdict and margin at one operating point (``gfbopt stability``)
:func:`onset_speed`        the lowest speed of whirl (``gfbopt stability --speed-range``)
:func:`coefficient_table`  K [N/m], C [N s/m] against frequency (``--csv``)
:func:`load_capacity`      the largest load for a minimum film (``gfbopt capacity``)
:func:`lift_off_speed`     the lowest speed for a load and a minimum film (``--lift-off``)
*a rotor on two bearings*
:func:`analyse_rotor`      onset of every mode, Campbell, imbalance (``gfbopt rotor``)
:func:`rotor_orbit`        the rotor in time at one speed (``gfbopt rotor --orbit``)
:func:`rotor_ramp`         a run-up or coast-down (``gfbopt rotor --run-up``)
*studies and designs*
:func:`load_study`         a study file, validated before anything is solved
:func:`run_study`          run it into ``results_root/NAME/`` (``gfbopt run``; the bearing-pair
                           design of ``problems/rotor_bearing_design.toml`` is one)
:func:`run_doe`            a design of experiments of your own function, resumable
=========================  ==================================================================

The functions are the library's own (same docstrings, arguments and results); the
additions: ``stability``, ``onset_speed``, ``load_capacity`` and ``lift_off_speed`` also take
a bearing file's path in place of the bearing — read with its ``[journal]`` and
``[thermal]`` tables and analysed at the running condition exactly as ``gfbopt stability``
and ``gfbopt capacity`` do (:mod:`gfbopt.rotor.running_files`; a file without them is
today's analysis), answering with the command line's JSON fields, each also an attribute
(``onset_speed(path, …).answer`` reads as for a bearing's result) — and the grid's
string form (:func:`~gfbopt.inputs.grid.accepts_grid_strings`), read
by :func:`~gfbopt.inputs.grid.as_grid` with the command line's one-line message for a
malformed one (``grid = '72x': must be written NTHETAxNZ, e.g. 72x20``).  Importing this
module imports the solvers (CasADi): ``import gfbopt`` loads it only when one of these names
is first used.
"""
from __future__ import annotations

from .doe import run_doe
from .inputs.bearing_file import load_bearing_public as load_bearing
from .inputs.grid import accepts_grid_strings, as_grid
from .inputs.rotor_system import load_rotor
from .rotor import coefficient_table, onset_speed, stability
from .rotor.analyse import analyse_rotor
from .rotor.capacity import lift_off_speed, load_capacity
from .rotor.running_files import (accepts_bearing_files, lift_off_of_file,
                                  load_capacity_of_file, onset_of_file, stability_of_file)
from .studies import load_study, run_study
from .transient import rotor_orbit, rotor_ramp

# a bearing file's path in place of the bearing: its [journal]/[thermal] tables read and the
# analysis run at the running condition, as `gfbopt stability` / `gfbopt capacity` do
stability = accepts_bearing_files(accepts_grid_strings(stability),
                                  accepts_grid_strings(stability_of_file))
onset_speed = accepts_bearing_files(accepts_grid_strings(onset_speed),
                                    accepts_grid_strings(onset_of_file))
coefficient_table = accepts_grid_strings(coefficient_table)
load_capacity = accepts_bearing_files(accepts_grid_strings(load_capacity),
                                      accepts_grid_strings(load_capacity_of_file))
lift_off_speed = accepts_bearing_files(accepts_grid_strings(lift_off_speed),
                                       accepts_grid_strings(lift_off_of_file))
analyse_rotor = accepts_grid_strings(analyse_rotor)
rotor_orbit = accepts_grid_strings(rotor_orbit)
rotor_ramp = accepts_grid_strings(rotor_ramp)

__all__ = ["analyse_rotor", "as_grid", "coefficient_table", "lift_off_speed", "load_bearing",
           "load_capacity", "load_rotor", "load_study", "onset_speed", "rotor_orbit",
           "rotor_ramp", "run_doe", "run_study", "stability"]
