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
  :data:`SECANT_STEPS` steps.  Each secant speed computes that mode's crossing alone, by
  Newton's method on the whirl ratio from the previous step's crossing
  (:func:`~gfbopt.rotor.matched_whirl.local_crossing`: one LU per bearing at the start and
  a few solves of its Taylor series, or when that is refused a Krylov space on a narrow
  window, instead of every crossing over the whole whirl range and the probe; the start's
  whirl ratio extrapolated from the two latest steps when the step is short), accepted when it keeps the mode's label and lies within ±0.05 of its whirl ratio
  (else every crossing there, as the scan); it is the scan's crossing to ~1e-10, and the
  onsets equal those of every crossing at every speed (``SpeedLine(local=False)``) to 1e-9
  (a test; measured 1e-14).  The scan rows of those speeds list that mode only.  On a fine
  grid guided by a coarse one, an equilibrium far from this grid's solved speeds starts from
  the guide's (interpolated, :data:`GUIDE_START`);
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

from ..errors import ParameterError
from ..inputs.grid import DEFAULT_GRID, Grid
from ..inputs.options import ModelOptions
from ..inputs.rotor_system import RotorSystem
from ..progress import progress
from ..static import SolverCache
from ..threads import single_threaded
from .matched_whirl import LOCAL_WINDOW, ModeCrossing, crossings, local_crossing
from .modes import family
from .mode_search import (ONSET, SECANT_TOLERANCE, STABLE, THERMAL_KINDS,  # noqa: F401
                          UNSTABLE_LOW, ModeOnset, track_onsets)
from .onset import SCAN_RATIO, check_coarse_grid, check_speed_range
from .speed_line import transferred_start
from .supports import (WHIRL_RANGE, RotorCase, SpeedStates, predicted_starts, resolve_rotor,
                       support_states)

#: relative tolerance of each mode's onset speed with method "scan" [-] (Brent)
SPEED_TOLERANCE = 1e-4
#: ways to refine each mode's onset (module docstring)
METHODS = ("secant", "scan")
#: a fine equilibrium starts from the coarse guide's (interpolated) when the guide solved a
#: speed nearer than this grid's nearest by more than this, in |ln(speed ratio)| [-]
#: (measured at 144 × 36: 6–7 Newton steps from the guide's at the same speed, 3–4 from this
#: grid's own 8–15 % away, 9–12 from 4,000 rpm to 12,000 rpm)
GUIDE_START = 0.3


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
    equilibria warm-start from the nearest speed solved.  ``local``: :meth:`follow` from a
    nearby crossing computes that mode's crossing alone (:func:`~gfbopt.rotor.
    matched_whirl.local_crossing`) where every crossing has not been computed (False: every
    crossing at every speed, the reference)."""

    def __init__(self, rotor: RotorCase, whirl_range=WHIRL_RANGE, local: bool = True):
        self.rotor, self.whirl_range, self.local = rotor, tuple(whirl_range), bool(local)
        self._states: dict = {}
        self._crossings: dict = {}
        self._local: dict = {}                   # (speed, label) -> ModeCrossing
        self.guide: Optional["SpeedLine"] = None  # a coarse line whose equilibria start ours

    @property
    def speeds_solved(self) -> list:
        """The speeds whose support states were asked for so far [rpm], in order."""
        return sorted(self._states)

    @single_threaded
    def states(self, speed: float) -> SpeedStates:
        if speed not in self._states:
            ok = sorted((s for s, st in self._states.items() if st.ok),
                        key=lambda s: abs(math.log(s / speed)))
            guesses = (predicted_starts(self._states[ok[0]],
                                        self._states[ok[1]] if len(ok) > 1 else None, speed,
                                        self._states[ok[2]] if len(ok) > 2 else None)
                       if ok else None)
            guesses = self._guide_starts(speed, ok[0] if ok else None) or guesses
            self._states[speed] = support_states(self.rotor, speed, None, self.whirl_range,
                                                 guesses=guesses)
        return self._states[speed]

    def _guide_starts(self, speed: float, nearest: Optional[float]) -> Optional[tuple]:
        """Each bearing's start from the guide's equilibria at its nearest speed solved,
        interpolated onto this grid (:func:`~gfbopt.rotor.speed_line.transferred_start`),
        when that speed is nearer than ``nearest`` (this line's) by more than
        :data:`GUIDE_START` in |ln(speed ratio)|; None otherwise."""
        if self.guide is None:
            return None
        def distance(other):
            return abs(math.log(other / speed))
        near = min((s for s in self.guide.speeds_solved if self.guide.states(s).ok),
                   key=distance, default=None)
        if near is None or (nearest is not None
                            and not distance(near) + GUIDE_START < distance(nearest)):
            return None
        out = []
        for case, st in zip(self.rotor.cases, self.guide.states(near).states):
            model = case.model(speed)
            out.append(transferred_start(st.solution, case.cache(model, case.grid), model))
        return tuple(out)

    @single_threaded
    def crossings(self, speed: float) -> list:
        if speed not in self._crossings:
            st = self.states(speed)
            self._crossings[speed] = (crossings(self.rotor, st, self.whirl_range)
                                      if st.ok else None)
        return self._crossings[speed]

    def computed(self, speed: float) -> bool:
        """True when every crossing at ``speed`` has been computed (not only local ones)."""
        return speed in self._crossings

    def follow_from(self, speed: float, label: str, whirl: float,
                    near: Optional[ModeCrossing]) -> Optional[ModeCrossing]:
        """:meth:`follow` from ``near`` (the mode's crossing at a nearby speed or on another
        grid): with ``local``, where every crossing at ``speed`` has not been computed, the
        crossing of the branch through ``near`` alone when it has the label and lies within
        :data:`~gfbopt.rotor.matched_whirl.LOCAL_WINDOW` of ``whirl``: by the direct search
        (``local_crossing(direct=True)``: one LU per bearing and its Taylor series), by the
        Krylov one when that is refused."""
        key = (speed, label)
        if (near is not None and self.local and speed not in self._crossings
                and key not in self._local):
            st = self.states(speed)
            found = local_crossing(self.rotor, st, near, direct=True) if st.ok else None
            found = found or (local_crossing(self.rotor, st, near) if st.ok else None)
            if (found is not None and found.label == label
                    and abs(found.whirl_ratio - whirl) <= LOCAL_WINDOW):
                self._local[key] = found
        return self.follow(speed, label, whirl)

    def follow(self, speed: float, label: str, whirl: float) -> Optional[ModeCrossing]:
        """The crossing at ``speed`` that continues a mode: same label, nearest whirl ratio
        (any label of the same family when none has it — rigid-body or bending,
        :func:`~gfbopt.rotor.modes.family`: a rigid-body mode whose shape changed class is
        not continued by a shaft's bending mode; any label when the family has none); the
        local crossing of :meth:`follow_from` when that is all that was computed there."""
        if speed not in self._crossings and (speed, label) in self._local:
            return self._local[(speed, label)]
        found = self.crossings(speed) or []
        same = ([c for c in found if c.label == label]
                or [c for c in found if family(c.label) == family(label)] or found)
        return min(same, key=lambda c: abs(c.whirl_ratio - whirl), default=None)

    def margin(self, speed: float, label: str, whirl: float) -> float:
        """(μ_c − 1)/(μ_c + 1) ∈ (−1, 1] of the mode at ``speed`` (1 when it has no
        crossing: stable for every inertia scale)."""
        c = self.follow(speed, label, whirl)
        return 1.0 if c is None else (c.inertia_scale - 1) / (c.inertia_scale + 1)

    def scan_rows(self, names: Optional[dict] = None) -> list:
        """One row per (speed, crossing) evaluated (speed_rpm, track_label: the name of the
        mode it belongs to, ``names`` id(crossing) → name of
        :func:`~gfbopt.rotor.mode_search.track_onsets`, empty when none; shape_label: its
        shape class at that speed; inertia_scale, whirl ratio, whirl frequency [Hz], grid)."""
        names = names or {}
        grid = str(self.rotor.grid)
        found = {s: c for s, c in self._crossings.items() if c}
        for (s, _), c in self._local.items():
            if s not in self._crossings:
                found.setdefault(s, []).append(c)
        return [{"speed_rpm": s, "track_label": names.get(id(c), ""), "shape_label": c.label,
                 "inertia_scale": c.inertia_scale,
                 "whirl_ratio": c.whirl_ratio, "whirl_frequency_hz": c.whirl_frequency_hz,
                 "grid": grid}
                for s in sorted(found) for c in found[s]]

    def equilibria(self) -> list:
        """One row per (speed, bearing) solved: the equilibrium (:meth:`~gfbopt.rotor.
        supports.BearingState.summary`) or the load-capacity message, with the grid."""
        grid = str(self.rotor.grid)
        rows = []
        for speed in sorted(self._states):
            st = self._states[speed]
            for k, s in enumerate(st.states):
                if s is not None:
                    rows.append(s.summary() | {"grid": grid})
                else:
                    load = self.rotor.loads[k]
                    rows.append({"bearing": load.name, "speed_rpm": speed,
                                 "load_newton": load.magnitude, "load_exceeds_capacity": True,
                                 "message": (st.failure or {}).get("message", ""),
                                 "grid": grid})
        return rows


def scan_speeds(low: float, high: float) -> list:
    """Geometric speeds from low to high [rpm], ratio at most :data:`SCAN_RATIO`."""
    count = max(2, math.ceil(math.log(high / low) / math.log(SCAN_RATIO) - 1e-9) + 1)
    return [low * (high / low) ** (k / (count - 1)) for k in range(count)]


@single_threaded
def rotor_onsets(system: RotorSystem, speed_range, *, grid: Grid = DEFAULT_GRID,
                 options: Optional[ModelOptions] = None, cache: Optional[SolverCache] = None,
                 whirl_range=WHIRL_RANGE, speed_tolerance: float = SPEED_TOLERANCE,
                 show_progress: bool = True, line: Optional[SpeedLine] = None,
                 method: str = "secant", coarse_grid="auto") -> RotorOnsets:
    """The onset speed of each mode of ``system`` in ``speed_range`` = (low, high) [rpm]
    (module docstring).  ``options`` stated here override every bearing's formulation;
    ``line`` reuses a :class:`SpeedLine` (e.g. the Campbell diagram's); ``method``: "secant"
    or "scan" (the reference refinement); ``coarse_grid``: the grid of the scan's guide
    with "secant" — "auto" (:data:`gfbopt.rotor.onset.COARSE_GRID` on grids with at least
    :data:`~gfbopt.rotor.onset.GUIDE_FACTOR` times its cells, as the one-bearing onset),
    None, or a coarser Grid / 'NTHETAxNZ'."""
    t0 = time.perf_counter()
    low, high = check_speed_range(speed_range)
    if method not in METHODS:
        raise ParameterError("method", method, f"must be one of: {', '.join(METHODS)}")
    rotor = line.rotor if line is not None else resolve_rotor(system, grid, cache, options)
    guide_grid = check_coarse_grid(coarse_grid, rotor.grid) if method == "secant" else None
    line = line or SpeedLine(rotor, whirl_range)
    guide = (SpeedLine(replace(rotor, grid=guide_grid,
                               cases=tuple(replace(c, grid=guide_grid) for c in rotor.cases)),
                       line.whirl_range, line.local) if guide_grid is not None else None)
    scan_line = guide or line
    speeds = scan_speeds(low, high)
    with progress(total=len(speeds), desc=f"rotor onset scan on {scan_line.rotor.grid}",
                  unit="speed", enabled=show_progress) as bar:
        for speed in speeds:
            scan_line.crossings(speed)
            bar.update(1)
    line.guide = guide
    try:
        names: dict = {}               # id(crossing) -> its mode's name, for the scan rows
        modes = track_onsets(line, guide, speeds, speed_tolerance, method, show_progress,
                             names)
    finally:
        line.guide = None
    modes.sort(key=lambda m: (math.isnan(m.onset_speed_rpm), m.onset_speed_rpm, m.label))
    first = next((m for m in modes if m.status == ONSET), None)
    low_unstable = [m.label for m in modes if m.status == UNSTABLE_LOW]
    lines = [x for x in (line, guide) if x is not None]
    capacity = [x.states(s).failure for x in lines for s in x.speeds_solved
                if not x.states(s).ok]
    if low_unstable:
        notes = sorted({m.note for m in modes if m.status == UNSTABLE_LOW and m.note})
        reason = (f"unstable already at the lowest valid speed in mode(s) "
                  f"{', '.join(low_unstable)}: the onset lies below the range"
                  + "".join(f" ({n})" for n in notes))
        first = None
    elif first is None:
        reason = ("no onset in the range: every mode is stable from "
                  f"{low:.6g} to {high:.6g} rpm" if modes else
                  "no speed in the range where both bearings carry their loads")
    else:
        reason = ""
    conventions = rotor.conventions() | {
        "onset_search": method, "coarse_grid": str(guide_grid) if guide_grid else ""}
    return RotorOnsets(
        modes=tuple(modes), onset_speed_rpm=first.onset_speed_rpm if first else math.nan,
        first_mode=first.label if first else None,
        onset_whirl_frequency_hz=first.whirl_frequency_hz if first else math.nan,
        onset_reason=reason, bearing_loads=rotor.loads,
        scan=[row for x in lines for row in x.scan_rows(names)],
        equilibria=[row for x in lines for row in x.equilibria()], capacity=capacity,
        conventions=conventions, speed_range_rpm=(low, high),
        wall_time_s=time.perf_counter() - t0)


def without_gyroscopics(system: RotorSystem) -> RotorSystem:
    """The same rigid rotor with I_p = 0 (no gyroscopic coupling), for comparisons.
    ParameterError for a shaft of beam elements: its gyroscopic matrix comes from its elements
    and disks, which the rotor file states."""
    if getattr(system, "shaft", None) is not None:
        raise ParameterError("shaft", "beam elements", "the comparison without gyroscopic "
                             "coupling (I_p = 0) is defined for a rigid rotor; a shaft's "
                             "gyroscopic terms come from its elements and disks")
    return replace(system, body=replace(system.body, polar_inertia=0.0))
