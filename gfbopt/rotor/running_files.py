"""A bearing *file* given to the library's one-bearing analyses: read with its
``[journal]`` and ``[thermal]`` tables (:func:`gfbopt.thermal.files.load_running_bearing`,
checked before any solve) and analysed at the running condition by
:mod:`gfbopt.rotor.running_bearing` — the functions ``gfbopt stability`` and ``gfbopt
capacity`` call, so the library and the command line give the same answer for the same
file.  A file without the tables is today's isothermal, cold-clearance analysis.

:func:`accepts_bearing_files` makes :func:`gfbopt.api.stability`, ``onset_speed``,
``load_capacity`` and ``lift_off_speed`` take a path (``str`` or ``os.PathLike``) where they
take a :class:`~gfbopt.inputs.BearingGeometry`; with a geometry they are unchanged.

What a file returns (every answer names the clearance model, ``thermal_model``, and carries
``running_clearance_um``, ``centrifugal_growth_um``, ``thermal_growth_um``,
``film_temperature_c``, ``viscosity_pa_s`` and the whole running point, ``running``):

- ``stability``: a :class:`RunningStability` (the StabilityResult's attributes, or None
  figures when there is no running state, plus ``running``);
- ``onset_speed``, ``load_capacity``, ``lift_off_speed``: a :class:`FileAnswer`, the dict
  of :func:`~gfbopt.rotor.running_bearing.running_onset`,
  :func:`~gfbopt.rotor.running_bearing.running_load_capacity`,
  :func:`~gfbopt.rotor.running_bearing.running_lift_off` (the command line's JSON fields)
  whose keys are also attributes (``.answer``, ``.onset_speed_rpm``, ``.to_dict()``), as a
  bearing's result reads.
"""
from __future__ import annotations

import functools
import os
from dataclasses import dataclass, field
from typing import Callable, Optional

from ..inputs.grid import DEFAULT_GRID, Grid
from ..thermal.running import RunningPoint

#: the clearance at speed's top-level fields of a stability answer (as ``gfbopt stability``)
RUNNING_FIELDS = ("thermal_model", "running_clearance_um", "centrifugal_growth_um",
                  "thermal_growth_um", "film_temperature_c", "viscosity_pa_s")


@dataclass(frozen=True)
class RunningStability:
    """The stability of a bearing file at an operating point at its running condition.

    ``result``: the :class:`~gfbopt.rotor.analysis.StabilityResult` of the warm bearing,
    None when there is no running state (thermal runaway, or the journal reaching the foil:
    ``running.message`` says why); ``running``: the
    :class:`~gfbopt.thermal.running.RunningPoint`; ``bearing``: the bearing analysed (the
    warm one).  Other attributes are the result's (``critical_mass_kg``, ``verdict``, …)."""

    result: Optional[object]
    running: RunningPoint
    bearing: object = field(repr=False)

    def __getattr__(self, name):
        if name.startswith("_") or name in ("result", "running", "bearing"):
            raise AttributeError(name)
        if self.result is None:
            if name == "verdict":
                return self.running.status
            if name == "success":
                return True
            if name == "message":
                return self.running.message
            raise AttributeError(f"{name}: no running state at {self.running.speed_rpm:g} "
                                 f"rpm ({self.running.message})")
        return getattr(self.result, name)

    def to_dict(self) -> dict:
        """The result's dict (None figures without a running state) with the clearance at
        speed's fields (RUNNING_FIELDS) and the running point (``running``)."""
        d = self.running.to_dict()
        out = {} if self.result is None else self.result.to_dict()
        if self.result is None:
            out.update(verdict=self.running.status, speed_rpm=self.running.speed_rpm,
                       success=True, message=self.running.message)
        return {**out, **{k: d[k] for k in RUNNING_FIELDS}, "running": d}


class FileAnswer(dict):
    """The answer for a bearing file: the command line's JSON fields, each key also an
    attribute (``found.answer``, ``found.onset_speed_rpm``), ``to_dict()`` a plain copy — so
    code written for a bearing's result object reads a file's answer unchanged."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(f"{name}: not a field of this answer (its fields: "
                                 f"{', '.join(sorted(self))})") from None

    def to_dict(self) -> dict:
        return dict(self)


def _resolved(bearing, options, stated: dict):
    """The formulation: the options stated as keywords (``film``, ``seam_angle_deg``,
    ``foil``, ``deflection_law``, ``loss_factor``) over ``options``, else the file's
    ``[model]`` table, then the defaults — as the command line merges its flags."""
    from ..inputs.options import ModelOptions, merge_options

    return merge_options(ModelOptions(**stated),
                         bearing.options if options is None else options)


def stability_of_file(path, rotor, operating_point, *, options=None,
                      grid: Grid = DEFAULT_GRID, cache=None,
                      **stated) -> RunningStability:
    """:func:`gfbopt.rotor.stability` of the bearing file ``path`` at the running condition
    of the operating point (``gfbopt stability --bearing FILE --speed-rpm N``)."""
    from ..static import SolverCache
    from ..thermal.files import load_running_bearing
    from .running_bearing import running_stability

    bearing, spec = load_running_bearing(path)
    result, point, warm = running_stability(
        bearing, spec, rotor, operating_point, options=_resolved(bearing, options, stated),
        grid=grid, cache=cache or SolverCache(grid))
    return RunningStability(result, point, warm)


def onset_of_file(path, rotor, load_newton, speed_range, *, guess_rpm=None, options=None,
                  grid: Grid = DEFAULT_GRID, cache=None, progress=False,
                  **stated) -> FileAnswer:
    """The onset of whirl of the bearing file ``path`` at the running condition of each
    speed (``gfbopt stability --speed-range LOW HIGH``; with ``guess_rpm`` as
    ``--speed-rpm N --onset`` gives it)."""
    from ..static import SolverCache
    from ..thermal.files import load_running_bearing
    from .running_bearing import running_onset

    bearing, spec = load_running_bearing(path)
    return FileAnswer(running_onset(
        bearing, spec, rotor, load_newton, tuple(speed_range), guess_rpm=guess_rpm,
        options=_resolved(bearing, options, stated), grid=grid,
        cache=cache or SolverCache(grid), progress=progress))


def load_capacity_of_file(path, speed_rpm, min_film_um, *, options=None,
                          grid: Grid = DEFAULT_GRID, cache=None, **stated) -> FileAnswer:
    """The load capacity [N] of the bearing file ``path`` at its running condition
    (``gfbopt capacity --bearing FILE --speed-rpm N --min-film-um H``)."""
    from ..thermal.files import load_running_bearing
    from .running_bearing import running_load_capacity

    bearing, spec = load_running_bearing(path)
    return FileAnswer(running_load_capacity(bearing, spec, speed_rpm, min_film_um,
                                            options=_resolved(bearing, options, stated),
                                            grid=grid, cache=cache))


def lift_off_of_file(path, load_newton, min_film_um, *, max_speed_rpm=100_000.0,
                     options=None, grid: Grid = DEFAULT_GRID, cache=None,
                     **stated) -> FileAnswer:
    """The lift-off speed [rpm] of the bearing file ``path`` at its running condition
    (``gfbopt capacity --bearing FILE --lift-off --load-newton F --min-film-um H``)."""
    from ..thermal.files import load_running_bearing
    from .running_bearing import running_lift_off

    bearing, spec = load_running_bearing(path)
    return FileAnswer(running_lift_off(bearing, spec, load_newton, min_film_um,
                                       max_speed_rpm=max_speed_rpm,
                                       options=_resolved(bearing, options, stated),
                                       grid=grid, cache=cache))


def accepts_bearing_files(function: Callable, of_file: Callable) -> Callable:
    """``function`` (taking a BearingGeometry first) that also takes a bearing file's path
    first, answered by ``of_file`` (module docstring).  Name, docstring and signature are
    the library function's (``__wrapped__`` is the innermost function itself, as
    :func:`~gfbopt.inputs.grid.accepts_grid_strings` keeps it); the path form is documented
    in :mod:`gfbopt.api` and here."""
    @functools.wraps(function)
    def wrapper(bearing, *args, **kwargs):
        if isinstance(bearing, (str, os.PathLike)):
            return of_file(bearing, *args, **kwargs)
        return function(bearing, *args, **kwargs)
    wrapper.__wrapped__ = getattr(function, "__wrapped__", function)
    wrapper.of_file = of_file
    return wrapper
