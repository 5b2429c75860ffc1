"""From what speed does my rotor whirl: the onset speed on the rotor's mass–speed line.

For a rotor of mass M per bearing under a fixed static load W0, the speed changes both
groups: Λ = 6 μ ω R²/(p_a c²) grows as ω and M̄ = M c ω²/W0 as ω², while W̄0 = W0/(p_a R²) stays
fixed.  The rotor whirls where M̄(ω) reaches the threshold M̄c(Λ(ω), W̄0); the onset speed is the
lowest such speed in the range asked (docs/PHYSICS.md §8, "Onset speed").

Search: the threshold is computed on a scan of speeds spaced geometrically by a ratio of at
most :data:`SCAN_RATIO` = 1.25 (M̄ grows by at most 1.56× from one scan speed to the next),
lowest speed first; the first scan interval where the sign of (M̄c − M̄) changes from + to − is
refined by Brent's method to :data:`SPEED_TOLERANCE` (relative).  At every scan speed the
threshold is the least-stable one over all root branches (:func:`gfbopt.linear.linear_threshold`
scans whirl ratios 0.02–1.2 and keeps the smallest critical mass, including the extra low-whirl
crossings, and 0 when the massless journal is already unstable), so the least-stable root
wins.  Inside the bracket, when both ends whirl at nearly the same ratio (within
:data:`SAME_BRANCH`), the refinement scans only a window of ±0.1 around it (8 whirl ratios
instead of 24; with the one-LU Krylov scan of :mod:`gfbopt.linear.krylov` the saving is
small); otherwise it scans the full range.  An unstable window narrower than
one scan interval can be missed; give a narrower range to look closer.  One static build
serves the whole line (Λ is a parameter of the CasADi model), and each speed warm-starts from
the previous equilibrium.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Optional, Union

from scipy.optimize import brentq

from ..errors import ParameterError
from ..inputs.bearing import BearingGeometry
from ..inputs.checks import check_positive
from ..inputs.conversions import rpm_to_rad_per_s, whirl_frequency_hz
from ..inputs.grid import DEFAULT_GRID, Grid
from ..inputs.options import ModelOptions
from ..inputs.rotor import Rotor
from ..static import SolverCache
from .analysis import Case, resolve_case, threshold_at

#: largest ratio between successive scan speeds [-]
SCAN_RATIO = 1.25
#: relative tolerance of the refined onset speed [-] (the grid's own error on M̄c is ~1e-3)
SPEED_TOLERANCE = 1e-4
#: bracket ends whose threshold whirl ratios differ by less than this are on one branch [-]
SAME_BRANCH = 0.05


def check_speed_range(speed_range) -> tuple[float, float]:
    """(low, high) [rpm] with 0 < low < high; ParameterError otherwise."""
    try:
        low, high = (float(v) for v in speed_range)
    except (TypeError, ValueError):
        raise ParameterError("speed_range", speed_range, "must be two speeds in rpm "
                             "(low, high)") from None
    low, high = check_positive("speed_range low", low), check_positive("speed_range high", high)
    if not high > low:
        raise ParameterError("speed_range", speed_range, "must be increasing: low < high [rpm]")
    return low, high


@dataclass(frozen=True)
class OnsetResult:
    """The onset speed of whirl of a rotor along its mass–speed line (SI, per bearing).

    onset_speed_rpm : lowest speed in the range where the rotor becomes linearly unstable
        [rpm] (nan when there is none in the range, or when it is unstable at the low end)
    whirl_frequency_hz : whirl frequency at the onset [Hz]; whirl_ratio γ there [-]
    stable_over_range : True when the rotor is stable at every scanned speed
    unstable_at_lower_end : True when it is already unstable at the lowest speed
    smallest_margin : smallest M_crit/M − 1 over the speeds evaluated [-], and
        smallest_margin_speed_rpm where it occurs [rpm]
    speed_range_rpm : the range searched; scan : one row per speed evaluated (speed_rpm,
        mass_parameter, critical_mass_parameter, mass_margin, whirl_ratio)
    rotor_mass_kg, load_newton [N], conventions (options used), evaluations (threshold
    computations), success, message, wall_time_s [s]
    """

    onset_speed_rpm: float
    whirl_frequency_hz: float
    whirl_ratio: float
    stable_over_range: bool
    unstable_at_lower_end: bool
    smallest_margin: float
    smallest_margin_speed_rpm: float
    speed_range_rpm: tuple
    scan: list = field(repr=False)
    rotor_mass_kg: float = math.nan
    load_newton: float = math.nan
    conventions: dict = field(default_factory=dict)
    evaluations: int = 0
    success: bool = True
    message: str = ""
    wall_time_s: float = 0.0

    @property
    def answer(self) -> str:
        """The answer in one line."""
        low, high = self.speed_range_rpm
        if self.unstable_at_lower_end:
            return (f"unstable already at {low:.6g} rpm: the onset lies below the range "
                    f"(mass margin there {self.scan[0]['mass_margin']:+.3g})")
        if self.stable_over_range:
            return (f"stable over the whole range {low:.6g}–{high:.6g} rpm (smallest mass "
                    f"margin {self.smallest_margin:+.3g} at {self.smallest_margin_speed_rpm:.6g}"
                    " rpm)")
        return (f"onset of whirl at {self.onset_speed_rpm:.6g} rpm, whirling at "
                f"{self.whirl_frequency_hz:.4g} Hz (whirl ratio {self.whirl_ratio:.3f})")

    def to_dict(self) -> dict:
        out = {k: getattr(self, k) for k in self.__dataclass_fields__}
        out["answer"] = self.answer
        return out


def onset_speed(bearing: BearingGeometry, rotor: Rotor, load_newton: Optional[float],
                speed_range, *, film: Optional[str] = None,
                seam_angle_deg: Union[float, str, None] = None, foil: Optional[str] = None,
                deflection_law: Optional[str] = None, loss_factor: Optional[float] = None,
                options: Optional[ModelOptions] = None, grid: Grid = DEFAULT_GRID,
                cache: Optional[SolverCache] = None, seam_angle=None) -> OnsetResult:
    """The lowest speed in ``speed_range`` [rpm] at which the rotor whirls (module docstring).

    Parameters
    ----------
    bearing : the bearing in SI; rotor : mass per bearing [kg]
    load_newton : static load per bearing W0 [N], fixed along the line (None: W0 = M g)
    speed_range : (low, high) [rpm]
    film, seam_angle_deg, foil, deflection_law, loss_factor, options, grid, cache : as for
        :func:`gfbopt.rotor.stability`

    Returns
    -------
    OnsetResult; "stable over the whole range" and "unstable at the lower end" are answers
    too.  A load the bearing cannot carry at a scanned speed raises LoadCapacityError.
    """
    t0 = time.perf_counter()
    low, high = check_speed_range(speed_range)
    case = resolve_case(bearing, rotor, load_newton, film=film, seam_angle_deg=seam_angle_deg,
                        seam_angle=seam_angle,
                        foil=foil, deflection_law=deflection_law, loss_factor=loss_factor,
                        options=options, grid=grid, cache=cache)
    line = _SpeedLine(case)
    count = max(2, math.ceil(math.log(high / low) / math.log(SCAN_RATIO) - 1e-9) + 1)
    speeds = [low * (high / low) ** (k / (count - 1)) for k in range(count)]
    common = dict(speed_range_rpm=(low, high), rotor_mass_kg=rotor.mass_kg,
                  load_newton=case.load_newton, conventions=case.conventions())
    previous = None
    for speed in speeds:
        value = line(speed)
        if value > 0:
            previous = speed
            continue
        if previous is None:
            return line.result(math.nan, None, unstable_at_lower_end=True, t0=t0, **common)
        line.narrow(previous, speed)
        root = brentq(line, previous, speed, xtol=SPEED_TOLERANCE * previous,
                      rtol=SPEED_TOLERANCE)
        return line.result(root, line.nearest(root), t0=t0, **common)
    return line.result(math.nan, None, stable_over_range=True, t0=t0, **common)


class _SpeedLine:
    """f(N) = (M̄c − M̄)/(M̄c + M̄) along the rotor's mass–speed line (> 0 stable), in [−1, 1]
    even when M̄c is 0 or infinite; remembers every evaluation and warm-starts each static
    solve from the equilibrium at the nearest speed already solved."""

    def __init__(self, case: Case):
        self.case = case
        self.rows: list[dict] = []
        self._solutions: dict = {}
        self._values: dict = {}
        self._threshold_options: dict = {}

    def narrow(self, low: float, high: float) -> None:
        """Refine between scan speeds ``low`` and ``high``: scan whirl ratios near the
        threshold's branch only, when both ends are on the same one."""
        ends = [r["whirl_ratio"] for r in self.rows if r["speed_rpm"] in (low, high)]
        if len(ends) == 2 and all(map(math.isfinite, ends)) and abs(
                ends[0] - ends[1]) < SAME_BRANCH:
            self._threshold_options = dict(whirl_range=(max(0.02, min(ends) - 0.1),
                                                        max(ends) + 0.1), samples=8)

    def __call__(self, speed: float) -> float:
        if speed in self._values:           # Brent's method starts with the bracket's ends
            return self._values[speed]
        nearest = min(self._solutions, key=lambda s: abs(math.log(s / speed)), default=None)
        sol, _, thr = threshold_at(self.case, speed, self._solutions.get(nearest),
                                   **self._threshold_options)
        self._solutions[speed] = sol
        mbar, mcrit = self.case.mass_parameter(speed), thr.critical_mass
        value = 1.0 if math.isinf(mcrit) else (mcrit - mbar) / (mcrit + mbar)
        self._values[speed] = value
        self.rows.append({"speed_rpm": speed, "mass_parameter": mbar,
                          "critical_mass_parameter": mcrit,
                          "mass_margin": mcrit / mbar - 1.0, "whirl_ratio": thr.whirl_ratio,
                          "bearing_number": sol.model.bearing_number,
                          "eccentricity": sol.eccentricity, "message": thr.message})
        return value

    def nearest(self, speed: float) -> dict:
        """The evaluation closest to ``speed``."""
        return min(self.rows, key=lambda r: abs(r["speed_rpm"] - speed))

    def result(self, onset: float, row: Optional[dict], t0: float,
               stable_over_range: bool = False, unstable_at_lower_end: bool = False,
               **common) -> OnsetResult:
        rows = sorted(self.rows, key=lambda r: r["speed_rpm"])
        worst = min(rows, key=lambda r: r["mass_margin"])
        gamma = row["whirl_ratio"] if row is not None else math.nan
        frequency = (whirl_frequency_hz(gamma, rpm_to_rad_per_s(onset)) if row is not None
                     else math.nan)
        notes = sorted({r["message"] for r in rows if r["message"]})
        return OnsetResult(onset_speed_rpm=onset, whirl_frequency_hz=frequency,
                           whirl_ratio=gamma, stable_over_range=stable_over_range,
                           unstable_at_lower_end=unstable_at_lower_end,
                           smallest_margin=worst["mass_margin"],
                           smallest_margin_speed_rpm=worst["speed_rpm"], scan=rows,
                           evaluations=len(rows), message="; ".join(notes),
                           wall_time_s=time.perf_counter() - t0, **common)
