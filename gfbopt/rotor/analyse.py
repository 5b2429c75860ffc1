"""One call for everything ``gfbopt rotor`` answers (the CLI and the rotor study wrap it):

    from gfbopt.inputs.rotor_system import load_rotor
    from gfbopt.rotor.analyse import analyse_rotor
    result = analyse_rotor(load_rotor("problems/rotors/blower.toml"), (5000, 60000),
                           campbell=True, imbalance=True, half_mass=True)
    result.to_dict()["onset_speed_rpm"], result.tables()["campbell"]

Onsets of every mode (:func:`gfbopt.rotor.system.rotor_onsets`), optionally the modes at one
speed, the Campbell diagram, the imbalance response and the per-bearing approximation
(:mod:`gfbopt.rotor.diagrams`), all on one :class:`~gfbopt.rotor.system.SpeedLine`: each
bearing's equilibrium and impedance at a speed are computed once for all of them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np
import pandas as pd

from ..errors import ParameterError
from ..inputs.grid import DEFAULT_GRID, Grid
from ..inputs.options import ModelOptions
from ..inputs.rotor_system import RotorSystem
from ..static import SolverCache
from .campbell import system_modes
from .diagrams import (CampbellDiagram, ImbalanceResponse, campbell_diagram, half_mass_onsets,
                       imbalance_response, reference_whirl)
from .onset import check_speed_range
from .supports import resolve_rotor
from .system import RotorOnsets, SpeedLine, rotor_onsets

#: speeds of the Campbell diagram and of the imbalance response by default
CAMPBELL_SPEEDS = 20
IMBALANCE_SPEEDS = 40


@dataclass(frozen=True, eq=False)
class RotorAnalysis:
    """What :func:`analyse_rotor` computed (None for what was not asked)."""

    onsets: RotorOnsets
    at_speed: Optional[dict]
    campbell: Optional[CampbellDiagram]
    imbalance: Optional[ImbalanceResponse]
    half_mass: Optional[list]

    def to_dict(self) -> dict:
        out = self.onsets.to_dict()
        out["at_speed"] = self.at_speed
        if self.campbell is not None:
            table = self.campbell.table
            out["campbell"] = {"speeds": int(table["speed_rpm"].nunique()) if len(table)
                               else 0, "modes": int(table["mode"].nunique()) if len(table)
                               else 0, "least_stable": (self.campbell.least_stable().to_dict()
                                                        if len(table) else None),
                               "tracks": self.campbell.tracks(),
                               "load_capacity_exceeded": self.campbell.capacity}
        if self.imbalance is not None:
            out["imbalance_response"] = {"peaks": self.imbalance.peaks,
                                         "note": _IMBALANCE_NOTE,
                                         "load_capacity_exceeded": self.imbalance.capacity}
        if self.half_mass is not None:
            first = min((h["onset_speed_rpm"] for h in self.half_mass
                         if math.isfinite(h["onset_speed_rpm"])), default=math.nan)
            out["half_mass_approximation"] = {
                "bearings": self.half_mass, "onset_speed_rpm": first,
                "error_of_approximation": (first / self.onsets.onset_speed_rpm - 1.0
                                           if math.isfinite(self.onsets.onset_speed_rpm)
                                           else math.nan),
                "note": "each bearing alone with its share of the mass and of the load, "
                        "cylindrical whirl (gfbopt stability --onset)"}
        return out

    def tables(self) -> dict:
        """name → DataFrame: modes, scan, equilibria, and campbell / imbalance when computed."""
        out = {"modes": pd.DataFrame([{k: v for k, v in m.to_dict().items() if k != "shape"}
                                      | _shape_columns(m.shape) for m in self.onsets.modes]),
               "threshold_scan": pd.DataFrame(self.onsets.scan),
               "equilibria": pd.DataFrame(self.onsets.equilibria)}
        if self.campbell is not None:
            out["campbell"] = self.campbell.table
        if self.imbalance is not None:
            out["imbalance_response"] = self.imbalance.table
        if self.half_mass is not None:
            out["half_mass"] = pd.DataFrame(self.half_mass)
        return out


_IMBALANCE_NOTE = ("synchronous response from the bearings' impedance at the running speed "
                   "(γ = 1); above the first onset it is the linear response of an unstable "
                   "rotor, not an orbit that would be observed")


def _shape_columns(shape: dict) -> dict:
    out = {"node_position_m": shape["node_position_m"],
           "phase_b_from_a_deg": shape["phase_b_from_a_deg"]}
    for name, at in shape["at_bearings"].items():
        for key, value in at.items():
            out[f"{key}_{name}"] = value
    return out


def modes_at_speed(line: SpeedLine, speed_rpm: float) -> dict:
    """Each bearing's equilibrium and the rotor's modes (full system) at one speed, with
    every mode's matched-whirl threshold μ_c there."""
    states = line.states(speed_rpm)
    if not states.ok:
        return {"speed_rpm": speed_rpm, "load_capacity_exceeded": states.failure}
    damped = any(c.options.loss_factor for c in line.rotor.cases)
    ref = reference_whirl(line, speed_rpm) if damped else None
    modes = system_modes(line.rotor, states, reference_whirl=ref)
    return {"speed_rpm": speed_rpm, "bearings": [s.summary() for s in states.states],
            "reference_whirl_ratio": ref,
            "modes": [{"label": m.label, "whirl_frequency_hz": m.whirl_frequency_hz,
                       "whirl_ratio": m.whirl_ratio, "log_decrement": m.log_decrement,
                       "damping_ratio": m.damping_ratio,
                       "growth_rate_per_s": m.growth_rate_per_s, "shape": m.shape}
                      for m in modes],
            "thresholds": [{"label": c.label, "inertia_scale": c.inertia_scale,
                            "inertia_margin": c.inertia_scale - 1.0,
                            "whirl_frequency_hz": c.whirl_frequency_hz,
                            "whirl_ratio": c.whirl_ratio, "note": c.note}
                           for c in line.crossings(speed_rpm)]}


def analyse_rotor(system: RotorSystem, speed_range, *, speed_rpm: Optional[float] = None,
                  campbell: bool = False, imbalance: bool = False, half_mass: bool = False,
                  grid: Grid = DEFAULT_GRID, options: Optional[ModelOptions] = None,
                  cache: Optional[SolverCache] = None, campbell_speeds: int = CAMPBELL_SPEEDS,
                  imbalance_speeds: int = IMBALANCE_SPEEDS,
                  show_progress: bool = True) -> RotorAnalysis:
    """Onset of every mode in ``speed_range`` [rpm] and what else is asked (module docstring).
    Every input is checked before anything is solved."""
    low, high = check_speed_range(speed_range)
    if speed_rpm is not None and not (isinstance(speed_rpm, (int, float))
                                      and math.isfinite(speed_rpm) and speed_rpm > 0):
        raise ParameterError("speed_rpm", speed_rpm, "must be finite and > 0 [rpm]")
    for name, n in (("campbell_speeds", campbell_speeds),
                    ("imbalance_speeds", imbalance_speeds)):
        if isinstance(n, bool) or not isinstance(n, int) or n < 2:
            raise ParameterError(name, n, "must be an integer >= 2")
    if imbalance and not system.imbalance:
        raise ParameterError("imbalance", (), "the rotor file has no [[imbalance]] plane: "
                             "there is no imbalance response to compute")
    line = SpeedLine(resolve_rotor(system, grid, cache, options))
    onsets = rotor_onsets(system, (low, high), line=line, show_progress=show_progress)
    at = modes_at_speed(line, float(speed_rpm)) if speed_rpm is not None else None
    cd = (campbell_diagram(line, list(np.linspace(low, high, campbell_speeds)),
                           show_progress, onsets=onsets.modes) if campbell else None)
    ir = (imbalance_response(line, list(np.linspace(low, high, imbalance_speeds)),
                             show_progress) if imbalance else None)
    hm = half_mass_onsets(line, (low, high)) if half_mass else None
    return RotorAnalysis(onsets, at, cd, ir, hm)
