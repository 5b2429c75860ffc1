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
from ..inputs.rotor_limits import check_rotor_speeds
from ..inputs.rotor_system import RotorSystem
from ..static import SolverCache
from ..threads import single_threaded
from .analysis import plausibility
from .campbell import system_modes
from .diagrams import (CampbellDiagram, ImbalanceResponse, campbell_diagram, half_mass_onsets,
                       imbalance_response, reference_whirl)
from .onset import check_speed_range
from .running import ISOTHERMAL, running_summary
from .supports import resolve_rotor
from .mode_search import UNSTABLE_LOW
from .system import RotorOnsets, SpeedLine, rotor_onsets
from .tracking import names_at_speed

#: the widest speed range analysed at once: HIGH/LOW at most this [-]
MAX_SPEED_RATIO = 1000.0
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
    warnings: tuple = ()
    running: Optional[dict] = None

    def running_fields(self) -> dict:
        """Which model each bearing was analysed with (``thermal_models``) and, with a
        bearing at its running condition, ``running_at_onset`` (bearing → its
        running clearance, growths, film temperature and viscosity at the first onset),
        ``thermal_limits`` ("thermal runaway at bearing A from N rpm") and
        ``running_cost``."""
        if self.running is None:
            names = [l.name for l in self.onsets.bearing_loads]
            return {"thermal_models": {n: ISOTHERMAL for n in names}}
        r = self.running
        return {"thermal_models": r["thermal_models"], "running_at_onset": r["at_onset"],
                "thermal_limits": r["thermal_limits"],
                "running_cost": {k: r[k] for k in ("fixed_points", "static_solves",
                                                   "static_solves_per_point",
                                                   "max_static_solves")}}

    def to_dict(self) -> dict:
        out = self.onsets.to_dict()
        out["at_speed"] = self.at_speed
        out["warnings"] = list(self.warnings)
        out["bearing_notes"] = load_notes(self.onsets)
        out.update(self.running_fields())
        if self.campbell is not None:
            table = self.campbell.table
            out["campbell"] = {"speeds": int(table["speed_rpm"].nunique()) if len(table)
                               else 0, "modes": int(table["mode"].nunique()) if len(table)
                               else 0, "least_stable": (self.campbell.least_stable().to_dict()
                                                        if len(table) else None),
                               "tracks": self.campbell.tracks(),
                               "load_capacity_exceeded": self.campbell.capacity,
                               "frequency_limit_hz": self.campbell.frequency_limit_hz,
                               "dropped_roots": list(self.campbell.dropped)}
        if self.imbalance is not None:
            above = self.imbalance.unstable_from_rpm
            out["imbalance_response"] = {**self.imbalance.to_dict(),
                                         "note": imbalance_note(above)}
        if self.half_mass is not None:
            first = min((h["onset_speed_rpm"] for h in self.half_mass
                         if math.isfinite(h["onset_speed_rpm"])), default=math.nan)
            out["half_mass_approximation"] = {
                "bearings": self.half_mass, "onset_speed_rpm": first,
                "error_of_approximation": (first / self.onsets.onset_speed_rpm - 1.0
                                           if math.isfinite(self.onsets.onset_speed_rpm)
                                           else math.nan),
                "note": "each bearing alone with its share of the mass and of the load, "
                        "cylindrical whirl (gfbopt stability --onset)" + (
                            "; each bearing with [journal]/[thermal] at its running "
                            "condition of each speed, as gfbopt stability --bearing FILE "
                            "--speed-range LOW HIGH (gfbopt.rotor.running_bearing."
                            "running_onset)" if self.running is not None else "")}
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
        if self.running is not None:
            out["running"] = pd.DataFrame(self.running["table"])
        return out


def unstable_from(onsets: RotorOnsets, low: float) -> float:
    """Where the rotor is unstable from [rpm]: its first onset, ``low`` when a mode is
    unstable at the lowest speed, nan when it is stable over the range."""
    if any(m.status == UNSTABLE_LOW for m in onsets.modes):
        return float(low)
    return float(onsets.onset_speed_rpm)


def imbalance_note(unstable_from_rpm: float) -> str:
    """What the linear imbalance response is, and where it is not physical."""
    text = ("synchronous response from the bearings' impedance at the running speed (γ = 1)")
    if not math.isfinite(unstable_from_rpm):
        return text + "; the rotor is stable over the range"
    return (text + f"; above {unstable_from_rpm:,.0f} rpm, where the rotor is unstable, it is "
            "the linear response of an unstable rotor, not an orbit that would be observed: "
            "not physical there (peaks there are flagged above_first_onset; the figure shades "
            "that range)")


def _shape_columns(shape: dict) -> dict:
    out = {"node_position_m": shape["node_position_m"],
           "node_location": shape["node_location"],
           "node_relative_whirl": shape["node_relative_whirl"],
           "phase_b_from_a_deg": shape["phase_b_from_a_deg"]}
    if "bending_share" in shape:          # a shaft's mode: how much it bends (as in the JSON)
        out["bending_share"] = shape["bending_share"]
    for name, at in shape["at_bearings"].items():
        for key, value in at.items():
            out[f"{key}_{name}"] = value
    return out


def load_notes(onsets: RotorOnsets) -> list:
    """A plain sentence for each bearing whose static load points against gravity (the
    rotor's geometry or its side loads pull it upwards), saying where its seam now is: in
    the loaded arc when the top foil's welded end is within 90° of its load line."""
    loads = onsets.bearing_loads
    one_side = len(loads) == 2 and loads[0].position * loads[1].position > 0
    notes = []
    for load in loads:
        away = load.away_from_gravity_deg
        if not (math.isfinite(away) and abs((away + 180.0) % 360.0 - 180.0) > 90.0):
            continue
        text = (f"bearing {load.name} is pulled upwards: its load is {load.magnitude:.4g} N at "
                f"{away:.4g}° from gravity")
        if one_side:
            text += " (both bearings lie on one side of the centre of gravity)"
        conv = onsets.conventions.get("bearings", {}).get(load.name, {})
        seam = conv.get("seam_angle_deg")
        if conv.get("film") == "seam" and isinstance(seam, (int, float)):
            arc = abs((seam + 180.0) % 360.0 - 180.0) < 90.0
            text += (", and its seam is now in the loaded arc" if arc else
                     ", and its seam stays out of the loaded arc") + (
                f" (the top foil's welded end {seam:.4g}° from its load line)")
        notes.append(text)
    return notes


def check_speed_span(speed_range, system: Optional[RotorSystem] = None,
                     name: str = "speed_range") -> tuple[float, float]:
    """(low, high) [rpm] of a speed range the rotor analyses can mean: 0 < low < high,
    high/low ≤ :data:`MAX_SPEED_RATIO` and, with ``system``, speeds every bearing can run at
    (:func:`gfbopt.inputs.rotor_limits.check_rotor_speeds`: surface speed and bearing number);
    one ParameterError naming ``name``."""
    low, high = check_speed_range(speed_range)
    if high / low > MAX_SPEED_RATIO:
        raise ParameterError(name, [low, high], f"HIGH/LOW = {high / low:.3g} exceeds "
                             f"{MAX_SPEED_RATIO:g}: one analysis spans at most "
                             f"{MAX_SPEED_RATIO:g}× in speed")
    if system is not None:
        check_rotor_speeds(system, (low, high), name)
    return low, high


def plausibility_warnings(line: SpeedLine) -> tuple:
    """The statics' plausibility flags (:func:`gfbopt.rotor.analysis.plausibility`: a film
    thinner than surface roughness, a load above the rule-of-thumb capacity) of each bearing,
    each kind of flag at the lowest speed solved that has it, with how far up it reaches."""
    flagged: dict = {}
    for speed in line.speeds_solved:
        for st in line.states(speed).states:
            for flag in (plausibility(st.case, st.solution, speed, math.nan) if st else ()):
                kind = flag.split(" = ", 1)[0]          # e.g. "minimum film h_min"
                flagged.setdefault((st.load.name, kind), []).append((speed, flag))
    out = []
    for (name, _), rows in flagged.items():
        speed, flag = rows[0]
        more = (f" (at {len(rows)} of the speeds solved, up to {rows[-1][0]:,.0f} rpm)"
                if len(rows) > 1 else "")
        out.append(f"bearing {name} at {speed:,.6g} rpm: {flag}{more}")
    return tuple(out)


def clearance_warnings(system: RotorSystem, response: Optional[ImbalanceResponse]) -> tuple:
    """A warning for each bearing whose linear imbalance response, at a speed below the first
    onset (where it is a real orbit), is larger than the bearing's radial clearance: the
    journal would cross the clearance, so the linear model does not hold there (the largest
    such amplitude and its speed)."""
    if response is None or not len(response.table):
        return ()
    table = response.table
    onset = response.unstable_from_rpm
    if math.isfinite(onset):
        table = table[table["speed_rpm"] < onset]
    out = []
    for support in system.bearings:
        running = f"running_clearance_um_{support.name}"
        clearance_um = (table[running] if running in table       # at each speed's running
                        else support.geometry.radial_clearance * 1e6)      # condition
        rows = table[(table["station"] == support.name) & (table["amplitude_um"] > clearance_um)]
        if not len(rows):
            continue
        worst = rows.loc[rows["amplitude_um"].idxmax()]
        if running in rows:
            clearance_um = worst[running]
        out.append(f"the linear imbalance response reaches {worst['amplitude_um']:.4g} µm at "
                   f"bearing {support.name} at {worst['speed_rpm']:,.0f} rpm, above the radial "
                   f"clearance of {clearance_um:.4g} µm: the linear model does not hold there; "
                   "run the rotor transient (--run-up)")
    return tuple(out)


def modes_at_speed(line: SpeedLine, speed_rpm: float, onsets=()) -> dict:
    """Each bearing's equilibrium and the rotor's modes (full system) at one speed, each with
    its shape class there (``shape_label``: one speed's eigenvector), and every matched-whirl
    threshold μ_c there (``shape_label``: its shape class at this speed); each with the name
    of the onset-list mode of ``onsets`` of the same shape (``track_label``; null when none
    has that shape there, :func:`~gfbopt.rotor.tracking.names_at_speed`)."""
    states = line.states(speed_rpm)
    if not states.ok:
        return {"speed_rpm": speed_rpm, "load_capacity_exceeded": states.failure}
    damped = any(c.options.loss_factor for c in line.rotor.cases)
    ref = reference_whirl(line, speed_rpm) if damped else None
    modes = system_modes(line.rotor, states, reference_whirl=ref)
    crossings = line.crossings(speed_rpm)
    mode_names = names_at_speed(modes, onsets, line.rotor)
    crossing_names = names_at_speed(crossings, onsets, line.rotor)
    return {"speed_rpm": speed_rpm, "bearings": [s.summary() for s in states.states],
            "reference_whirl_ratio": ref,
            "modes": [{"track_label": n, "shape_label": m.label,
                       "whirl_frequency_hz": m.whirl_frequency_hz,
                       "whirl_ratio": m.whirl_ratio, "log_decrement": m.log_decrement,
                       "damping_ratio": m.damping_ratio,
                       "growth_rate_per_s": m.growth_rate_per_s, "shape": m.shape}
                      for m, n in zip(modes, mode_names)],
            "thresholds": [{"track_label": n, "shape_label": c.label,
                            "inertia_scale": c.inertia_scale,
                            "inertia_margin": c.inertia_scale - 1.0,
                            "whirl_frequency_hz": c.whirl_frequency_hz,
                            "whirl_ratio": c.whirl_ratio, "note": c.note}
                           for c, n in zip(crossings, crossing_names)]}


@single_threaded
def analyse_rotor(system: RotorSystem, speed_range, *, speed_rpm: Optional[float] = None,
                  campbell: bool = False, imbalance: bool = False, half_mass: bool = False,
                  grid: Grid = DEFAULT_GRID, options: Optional[ModelOptions] = None,
                  cache: Optional[SolverCache] = None, campbell_speeds: int = CAMPBELL_SPEEDS,
                  imbalance_speeds: int = IMBALANCE_SPEEDS,
                  show_progress: bool = True) -> RotorAnalysis:
    """Onset of every mode in ``speed_range`` [rpm] and what else is asked (module docstring).
    Every input is checked before anything is solved."""
    low, high = check_speed_span(speed_range, system)
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
    at = (modes_at_speed(line, float(speed_rpm), onsets.modes) if speed_rpm is not None
          else None)
    cd = (campbell_diagram(line, list(np.linspace(low, high, campbell_speeds)),
                           show_progress, onsets=onsets.modes) if campbell else None)
    ir = (imbalance_response(line, list(np.linspace(low, high, imbalance_speeds)),
                             show_progress, unstable_from_rpm=unstable_from(onsets, low))
          if imbalance else None)
    hm = half_mass_onsets(line, (low, high)) if half_mass else None
    run = running_summary(line, onsets.onset_speed_rpm)
    limits = tuple(x["message"] for x in run["thermal_limits"]) if run else ()
    return RotorAnalysis(onsets, at, cd, ir, hm,
                         limits + plausibility_warnings(line) + clearance_warnings(system, ir),
                         run)
