"""A rigid rotor on two foil bearings: from what speed does each of its modes whirl, which
whirls first, at what frequency and in what shape — the Python API that ``gfbopt rotor`` wraps.

    from gfbopt.inputs.rotor_system import load_rotor
    from gfbopt.rotor.system import rotor_onsets
    result = rotor_onsets(load_rotor("problems/rotors/blower.toml"), (5000, 60000))
    result.first_mode, result.onset_speed_rpm, result.modes

Along the speed line the rotor, its bearings' loads and its imbalance are fixed; each bearing's
Λ grows with ω.  At each speed both bearings are solved under their own static loads
(:mod:`.supports`) and every mode's matched-whirl threshold μ_c is found (:mod:`.matched_whirl`:
the rotor whirls in that mode when its inertias are μ_c times the real ones).  A mode's onset
speed is where μ_c(ω) falls through 1.  Speeds are scanned geometrically with a ratio of at
most 1.25 (as the one-bearing :func:`gfbopt.rotor.onset_speed`), and the first scan interval of
each mode where μ_c − 1 changes sign from + to − is refined, following that mode (same label,
nearest whirl ratio) inside the bracket:

* ``method="secant"`` (default): secant steps on g = ln μ_c against ln N (nearly linear: the
  inertia terms grow as N², the bearings' impedance slowly), safeguarded by bisection inside the
  bracket, until the next step from the latest point would be at most
  :data:`SECANT_TOLERANCE` on ln N (the latest point, whose error that step estimates, is the
  onset; 2–3 speeds per mode); Brent's method as below if it has not converged in
  :data:`SECANT_STEPS` steps;
* ``method="scan"`` (the reference of gfbopt 0.2): Brent's method on (μ_c − 1)/(μ_c + 1) to a
  relative :data:`SPEED_TOLERANCE` (5–7 speeds per mode).

The two agree to the reference's tolerance (a test).  An unstable window narrower than a scan
interval can be missed.

A speed at which a bearing's share exceeds its load capacity is reported (``capacity`` rows,
with the largest load it carries), not raised; the modes are searched over the other speeds.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Optional

from scipy.optimize import brentq

from ..errors import ParameterError
from ..inputs.grid import DEFAULT_GRID, Grid
from ..inputs.options import ModelOptions
from ..inputs.rotor_system import RotorSystem
from ..progress import progress
from ..static import SolverCache
from .matched_whirl import ModeCrossing, by_mode, crossings
from .onset import SCAN_RATIO, check_speed_range
from .supports import (WHIRL_RANGE, RotorCase, SpeedStates, predicted_starts, resolve_rotor,
                       support_states)

#: relative tolerance of each mode's onset speed with method "scan" [-] (Brent)
SPEED_TOLERANCE = 1e-4
#: the secant refinement stops when the next secant step from its latest point would be at
#: most this on ln N [-]: that step estimates the latest point's error (superlinear
#: convergence of a nearly linear g), which is returned
SECANT_TOLERANCE = 1e-6
#: secant steps before the refinement falls back to Brent's method
SECANT_STEPS = 12
#: ways to refine each mode's onset (module docstring)
METHODS = ("secant", "scan")


@dataclass(frozen=True)
class ModeOnset:
    """The onset of one mode along the speed line.

    label ('forward conical', …); onset_speed_rpm [rpm] (nan: none in the range, see
    status); whirl_ratio, whirl_frequency_hz [Hz] at the onset; shape at the onset
    (:func:`gfbopt.rotor.modes.shape`); status: 'onset', 'unstable at the lowest speed' or
    'stable over the range'; smallest_inertia_margin: the least μ_c − 1 over the scan [-]."""

    label: str
    onset_speed_rpm: float
    whirl_ratio: float
    whirl_frequency_hz: float
    shape: dict
    status: str
    smallest_inertia_margin: float

    def to_dict(self) -> dict:
        return {"label": self.label, "onset_speed_rpm": self.onset_speed_rpm,
                "whirl_ratio": self.whirl_ratio,
                "whirl_frequency_hz": self.whirl_frequency_hz, "status": self.status,
                "smallest_inertia_margin": self.smallest_inertia_margin, "shape": self.shape}


ONSET, UNSTABLE_LOW, STABLE = "onset", "unstable at the lowest speed", "stable over the range"


@dataclass(frozen=True)
class RotorOnsets:
    """Onset of every mode of the rotor (SI) and what it was computed from.

    modes : :class:`ModeOnset` per mode label found, lowest onset first; onset_speed_rpm :
    the first onset over all modes [rpm] (nan, with ``onset_reason``, when none);
    first_mode : its label; onset_whirl_frequency_hz [Hz]; bearing_loads : each bearing's
    static load (:class:`gfbopt.rotor.rigid.BearingLoad`); scan : one row per (speed, mode)
    crossing (speed_rpm, label, inertia_scale, whirl_ratio); equilibria : one row per
    (speed, bearing) (ε, φ, h_min, load, Λ); capacity : speeds where a bearing's load exceeds
    its capacity (with the message); conventions; speed_range_rpm; wall_time_s."""

    modes: tuple
    onset_speed_rpm: float
    first_mode: Optional[str]
    onset_whirl_frequency_hz: float
    onset_reason: str
    bearing_loads: tuple
    scan: list = field(repr=False)
    equilibria: list = field(repr=False)
    capacity: list = field(repr=False)
    conventions: dict = field(repr=False)
    speed_range_rpm: tuple = ()
    wall_time_s: float = 0.0

    def mode(self, label: str) -> Optional[ModeOnset]:
        return next((m for m in self.modes if m.label == label), None)

    def to_dict(self) -> dict:
        return {"onset_speed_rpm": self.onset_speed_rpm, "first_mode": self.first_mode,
                "onset_whirl_frequency_hz": self.onset_whirl_frequency_hz,
                "onset_reason": self.onset_reason,
                "modes": [m.to_dict() for m in self.modes],
                "bearing_loads_newton": {l.name: l.magnitude for l in self.bearing_loads},
                "bearing_loads": [l.to_dict() for l in self.bearing_loads],
                "load_capacity_exceeded": self.capacity, "equilibria": self.equilibria,
                "scan": self.scan, "speed_range_rpm": list(self.speed_range_rpm),
                "conventions": self.conventions, "wall_time_s": self.wall_time_s}


class SpeedLine:
    """Both bearings and every mode crossing at each speed asked, cached; each speed's
    equilibria warm-start from the nearest speed solved."""

    def __init__(self, rotor: RotorCase, whirl_range=WHIRL_RANGE):
        self.rotor, self.whirl_range = rotor, tuple(whirl_range)
        self._states: dict = {}
        self._crossings: dict = {}

    def states(self, speed: float) -> SpeedStates:
        if speed not in self._states:
            ok = sorted((s for s, st in self._states.items() if st.ok),
                        key=lambda s: abs(math.log(s / speed)))
            guesses = (predicted_starts(self._states[ok[0]],
                                        self._states[ok[1]] if len(ok) > 1 else None, speed)
                       if ok else None)
            self._states[speed] = support_states(self.rotor, speed, None, self.whirl_range,
                                                 guesses=guesses)
        return self._states[speed]

    def crossings(self, speed: float) -> list:
        if speed not in self._crossings:
            st = self.states(speed)
            self._crossings[speed] = (crossings(self.rotor, st, self.whirl_range)
                                      if st.ok else None)
        return self._crossings[speed]

    def follow(self, speed: float, label: str, whirl: float) -> Optional[ModeCrossing]:
        """The crossing at ``speed`` that continues a mode: same label, nearest whirl ratio
        (any label when none has it)."""
        found = self.crossings(speed) or []
        same = [c for c in found if c.label == label] or found
        return min(same, key=lambda c: abs(c.whirl_ratio - whirl), default=None)

    def margin(self, speed: float, label: str, whirl: float) -> float:
        """(μ_c − 1)/(μ_c + 1) ∈ (−1, 1] of the mode at ``speed`` (1 when it has no
        crossing: stable for every inertia scale)."""
        c = self.follow(speed, label, whirl)
        return 1.0 if c is None else (c.inertia_scale - 1) / (c.inertia_scale + 1)

    def equilibria(self) -> list:
        rows = []
        for speed in sorted(self._states):
            st = self._states[speed]
            for k, s in enumerate(st.states):
                if s is not None:
                    rows.append(s.summary())
                else:
                    load = self.rotor.loads[k]
                    rows.append({"bearing": load.name, "speed_rpm": speed,
                                 "load_newton": load.magnitude, "load_exceeds_capacity": True,
                                 "message": (st.failure or {}).get("message", "")})
        return rows


def scan_speeds(low: float, high: float) -> list:
    """Geometric speeds from low to high [rpm], ratio at most :data:`SCAN_RATIO`."""
    count = max(2, math.ceil(math.log(high / low) / math.log(SCAN_RATIO) - 1e-9) + 1)
    return [low * (high / low) ** (k / (count - 1)) for k in range(count)]


def rotor_onsets(system: RotorSystem, speed_range, *, grid: Grid = DEFAULT_GRID,
                 options: Optional[ModelOptions] = None, cache: Optional[SolverCache] = None,
                 whirl_range=WHIRL_RANGE, speed_tolerance: float = SPEED_TOLERANCE,
                 show_progress: bool = True, line: Optional[SpeedLine] = None,
                 method: str = "secant") -> RotorOnsets:
    """The onset speed of each mode of ``system`` in ``speed_range`` = (low, high) [rpm]
    (module docstring).  ``options`` stated here override every bearing's formulation;
    ``line`` reuses a :class:`SpeedLine` (e.g. the Campbell diagram's); ``method``: "secant"
    or "scan" (the reference refinement)."""
    t0 = time.perf_counter()
    low, high = check_speed_range(speed_range)
    if method not in METHODS:
        raise ParameterError("method", method, f"must be one of: {', '.join(METHODS)}")
    rotor = line.rotor if line is not None else resolve_rotor(system, grid, cache, options)
    line = line or SpeedLine(rotor, whirl_range)
    speeds = scan_speeds(low, high)
    with progress(total=len(speeds), desc="rotor onset scan", unit="speed",
                  enabled=show_progress) as bar:
        for speed in speeds:
            line.crossings(speed)
            bar.update(1)
    valid = [s for s in speeds if line.crossings(s) is not None]
    labels = sorted({c.label for s in valid for c in line.crossings(s)})
    modes = [_mode_onset(line, valid, label, speed_tolerance, method) for label in labels]
    modes.sort(key=lambda m: (math.isnan(m.onset_speed_rpm), m.onset_speed_rpm, m.label))
    first = next((m for m in modes if m.status == ONSET), None)
    low_unstable = [m.label for m in modes if m.status == UNSTABLE_LOW]
    capacity = [line.states(s).failure for s in speeds if not line.states(s).ok]
    if low_unstable:
        reason = (f"unstable already at the lowest valid speed in mode(s) "
                  f"{', '.join(low_unstable)}: the onset lies below the range")
        first = None
    elif first is None:
        reason = ("no onset in the range: every mode is stable from "
                  f"{low:.6g} to {high:.6g} rpm" if valid else
                  "no speed in the range where both bearings carry their loads")
    else:
        reason = ""
    scan = [{"speed_rpm": s, "label": c.label, "inertia_scale": c.inertia_scale,
             "whirl_ratio": c.whirl_ratio, "whirl_frequency_hz": c.whirl_frequency_hz}
            for s in sorted(line._crossings) if line._crossings[s]
            for c in line._crossings[s]]
    return RotorOnsets(
        modes=tuple(modes), onset_speed_rpm=first.onset_speed_rpm if first else math.nan,
        first_mode=first.label if first else None,
        onset_whirl_frequency_hz=first.whirl_frequency_hz if first else math.nan,
        onset_reason=reason, bearing_loads=rotor.loads, scan=scan,
        equilibria=line.equilibria(), capacity=capacity, conventions=rotor.conventions(),
        speed_range_rpm=(low, high), wall_time_s=time.perf_counter() - t0)


def _mode_onset(line: SpeedLine, speeds: list, label: str, tol: float,
                method: str = "secant") -> ModeOnset:
    """One mode's onset on the scanned ``speeds`` (those with both bearings solved)."""
    rows = []                                    # (speed, crossing or None)
    for s in speeds:
        own = [c for c in line.crossings(s) if c.label == label]
        rows.append((s, min(own, key=lambda c: c.inertia_scale) if own else None))
    present = [c for _, c in rows if c is not None]
    margin = min(c.inertia_scale for c in present) - 1.0
    previous = None
    for s, c in rows:
        if c is None or c.inertia_scale > 1.0:
            previous = (s, c)
            continue
        if previous is None:
            return ModeOnset(label, math.nan, c.whirl_ratio, c.whirl_frequency_hz, c.shape,
                             UNSTABLE_LOW, margin)
        whirl = c.whirl_ratio
        root = (_secant(line, label, previous, (s, c)) if method == "secant" else None)
        if root is None:
            root = brentq(lambda x: line.margin(x, label, whirl), previous[0], s,
                          xtol=tol * previous[0], rtol=tol)
        at = line.follow(root, label, whirl)
        return ModeOnset(label, root, at.whirl_ratio, at.whirl_frequency_hz,
                         at.shape, ONSET, margin)
    best = min(present, key=lambda c: c.inertia_scale)
    return ModeOnset(label, math.nan, best.whirl_ratio, best.whirl_frequency_hz, best.shape,
                     STABLE, margin)


def _log_scale(crossing: Optional[ModeCrossing]) -> float:
    """ln μ_c of a crossing; +inf when the mode has none (stable for every inertia scale)."""
    return math.inf if crossing is None else math.log(crossing.inertia_scale)


def _secant(line: SpeedLine, label: str, stable: tuple, unstable: tuple) -> Optional[float]:
    """The onset of mode ``label`` between the scan speeds ``stable`` = (N, crossing) with
    μ_c > 1 and ``unstable`` with μ_c ≤ 1: secant steps on ln μ_c against ln N from the
    bracket's ends, bisection whenever a step would leave the bracket or a point has no
    crossing (module docstring).  None when it has not converged (Brent's method then)."""
    a, b = math.log(stable[0]), math.log(unstable[0])
    x0, g0 = a, _log_scale(stable[1])
    x1, g1 = b, _log_scale(unstable[1])
    whirl = unstable[1].whirl_ratio
    for _ in range(SECANT_STEPS):
        finite = math.isfinite(g0) and math.isfinite(g1) and g1 != g0
        x = x1 - g1 * (x1 - x0) / (g1 - g0) if finite else 0.5 * (a + b)
        if not a < x < b:
            x = 0.5 * (a + b)
        c = line.follow(math.exp(x), label, whirl)
        gx = _log_scale(c)
        if c is not None:
            whirl = c.whirl_ratio
        if gx > 0:
            a = x
        else:
            b = x
        if math.isfinite(gx) and math.isfinite(g1) and gx != g1 and abs(
                gx * (x - x1) / (gx - g1)) <= SECANT_TOLERANCE:
            return math.exp(x)
        x0, g0, x1, g1 = x1, g1, x, gx
    return None


def without_gyroscopics(system: RotorSystem) -> RotorSystem:
    """The same rotor with I_p = 0 (no gyroscopic coupling), for comparisons."""
    return replace(system, body=replace(system.body, polar_inertia=0.0))
