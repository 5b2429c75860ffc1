"""The nonlinear critical mass of a rigid rotor from batches of small-kick transients, and
the bifurcation diagram above it.

M̄ = M c ω²/W0 with M the rotor mass and W0 the static load carried by one bearing
(``docs/PHYSICS.md``).  The growth rate of the whirling mode is linear in M̄ near the
threshold, so the threshold is the zero of a line fitted to the measured growth rates.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import ParameterError
from .orbit import integrate_orbits
from .result import check_positive
from .system import TransientModel, equilibrium_state


@dataclass(frozen=True)
class CriticalMass:
    """Nonlinear (transient) critical mass M̄_crit = M c ω²/W0 of a rigid rotor.

    critical_mass : interpolated zero of the fitted growth rate between the bracket [-]
    bracket : (largest stable mass, smallest unstable mass) tested [-]
    whirl_ratio : whirl ratio at the threshold [-]
    linear_critical_mass : the linear threshold used to centre the search (nan if unused)
    history : one dict per transient (round, mass, growth_rate, whirl_ratio, verdict)
    transients, rotor_revolutions, evaluations : cost counters; wall_time_s
    success, message
    """

    critical_mass: float
    bracket: tuple
    whirl_ratio: float
    linear_critical_mass: float
    history: tuple
    transients: int
    rotor_revolutions: float
    evaluations: int
    wall_time_s: float
    success: bool
    message: str = ""

    def to_dict(self) -> dict:
        return {"critical_mass": self.critical_mass, "bracket": list(self.bracket),
                "whirl_ratio": self.whirl_ratio,
                "linear_critical_mass": self.linear_critical_mass,
                "transients": self.transients, "rotor_revolutions": self.rotor_revolutions,
                "wall_time_s": self.wall_time_s, "success": self.success,
                "message": self.message}


def _threshold_from_history(history: list) -> tuple:
    """(M̄_crit, whirl ratio, bracket low, bracket high) from all transients so far.

    The growth rate is linear in M̄ near the threshold: the zero of a least-squares line
    through the (up to) four finite growth rates nearest the sign change is the estimate, so
    a single noisy fit (growth rates ~1e-5 within 0.5 % of threshold) cannot break the
    search.  The bracket is the nearest tested masses on either side of that zero.
    """
    pts = sorted((h["mass"], h["growth_rate"], h["whirl_ratio"]) for h in history
                 if not math.isnan(h["growth_rate"]))
    stable = [p for p in pts if p[1] < 0]
    unstable = [p for p in pts if p[1] > 0]
    if not stable or not unstable:
        lo = max((p[0] for p in stable), default=0.0)
        hi = min((p[0] for p in unstable), default=math.inf)
        return math.nan, math.nan, lo, hi
    # the sign change: between the largest stable mass below the smallest unstable one
    first_unstable = min(p[0] for p in unstable)
    last_stable = max((p[0] for p in stable if p[0] < first_unstable), default=None)
    if last_stable is None:
        last_stable = max(p[0] for p in stable)
    centre = 0.5 * (last_stable + first_unstable)
    near = sorted((p for p in pts if math.isfinite(p[1])), key=lambda p: abs(p[0] - centre))[:4]
    m = np.array([p[0] for p in near])
    g = np.array([p[1] for p in near])
    if np.ptp(m) == 0:
        return math.nan, math.nan, last_stable, first_unstable
    slope, intercept = np.polyfit(m, g, 1)
    mc = -intercept / slope if slope > 0 else centre
    mc = min(max(mc, last_stable), first_unstable)     # never outside the verdicts' bracket
    lo = max((p[0] for p in pts if p[0] <= mc), default=0.0)
    hi = min((p[0] for p in pts if p[0] > mc), default=math.inf)
    whirls = [p[2] for p in near if math.isfinite(p[2])]
    whirl = float(np.interp(mc, [p[0] for p in near if math.isfinite(p[2])], whirls)) \
        if whirls else math.nan
    return float(mc), whirl, lo, hi


def find_critical_mass(tm: TransientModel, *, tolerance: float = 0.005,
                       linear_estimate: Optional[float] = None, batch: int = 8,
                       revolutions: float = 5.0, settle: float = 1.0, kick: float = 1e-3,
                       max_rounds: int = 8, progress=None,
                       method: str = "rk4") -> CriticalMass:
    """Find M̄_crit to a relative ``tolerance`` with batches of RK4 transients.

    Each round integrates ``batch`` rotors of different mass together and fits each orbit's
    growth rate (:func:`fit_growth_rate`).  Around a linear estimate the first batch spans
    ±(batch/2)·tolerance; otherwise a geometric batch over 0.25–64 brackets it first.  The
    threshold is the zero of a line fitted to the growth rates nearest the sign change
    (:func:`_threshold_from_history`); rounds go on until the tested masses on either side of
    it are at most 2·tolerance apart.  Contact and limit cycles count as unstable.
    """
    tolerance = check_positive("tolerance", tolerance)
    if tolerance >= 0.5:
        raise ParameterError("tolerance", tolerance, "must be < 0.5 (relative)")
    batch = int(check_positive("batch", batch))
    revolutions = check_positive("revolutions", revolutions)
    t0 = time.perf_counter()
    history = []
    if linear_estimate is not None and math.isfinite(linear_estimate):
        half = batch // 2
        offsets = np.concatenate([np.arange(-half, 0) + 0.5, np.arange(0, batch - half) + 0.5])
        masses = linear_estimate * (1 + tolerance * offsets)
    else:
        masses = np.geomspace(0.25, 64.0, batch)
    evaluations = 0
    rotor_revs = 0.0
    message = ""
    mc, whirl, lo, hi = math.nan, math.nan, 0.0, math.inf
    for round_ in range(max_rounds):
        orbit = integrate_orbits(tm, masses, revolutions, kick=kick, settle=settle,
                                 method=method)
        evaluations += orbit.evaluations
        rotor_revs += orbit.revolutions * masses.size
        for k, mm in enumerate(masses):
            g = float(orbit.growth_rate[k])
            if orbit.verdict[k] in ("contact", "limit cycle"):
                g = math.inf if not math.isfinite(g) or g <= 0 else g
            history.append({"round": round_, "mass": float(mm), "growth_rate": g,
                            "whirl_ratio": float(orbit.whirl_ratio[k]),
                            "verdict": orbit.verdict[k]})
        if progress is not None:
            progress((round_ + 1) / max_rounds)
        mc, whirl, lo, hi = _threshold_from_history(history)
        if math.isnan(mc):
            if lo == 0.0 and hi == math.inf:
                message = "no finite growth rate was measured"
                break
            if hi == math.inf:            # everything stable: go heavier
                masses = lo * np.geomspace(1.1, 4.0, batch)
            else:                         # everything unstable: go lighter
                masses = hi / np.geomspace(4.0, 1.1, batch)
            continue
        if (hi - lo) <= 2 * tolerance * mc:
            break
        masses = np.linspace(lo, hi, batch + 2)[1:-1]
    wall = time.perf_counter() - t0
    ok = math.isfinite(mc) and (hi - lo) <= 2 * tolerance * mc
    if not ok:
        message = message or (f"no bracket of relative width {2 * tolerance:g} after "
                              f"{max_rounds} rounds (bracket {lo:.4g}–{hi:.4g})")
        mc = mc if math.isfinite(mc) else math.nan
    return CriticalMass(mc if ok else math.nan, (lo, hi), whirl,
                        math.nan if linear_estimate is None else float(linear_estimate),
                        tuple(history), len(history), rotor_revs, evaluations, wall, ok,
                        message)


def limit_cycle_amplitudes(tm: TransientModel, masses, revolutions: float = 60.0,
                           kicks: tuple = (0.05, 0.6)):
    """Bifurcation diagram: the limit-cycle size against M̄ above the threshold.

    Each mass runs twice in one batch, from the journal displaced along X by ``kicks[0]``
    (inside the cycle) and by ``kicks[1]`` (outside) [clearances]; where both reach
    the same final amplitude the cycle is established.  Amplitude: largest distance of the
    journal centre from the equilibrium over the last two whirl periods [clearances].
    """
    import pandas as pd

    masses = np.asarray(masses, dtype=float)
    batch = 2 * masses.size
    state = equilibrium_state(tm, batch)
    n = masses.size
    state.x[:n] += kicks[0]
    state.x[n:] += kicks[1]
    orbit = integrate_orbits(tm, np.concatenate([masses, masses]), revolutions, initial=state,
                             settle=revolutions / 2)
    return pd.DataFrame({
        "mass": masses, "amplitude_from_inside": orbit.amplitude[:n],
        "amplitude_from_outside": orbit.amplitude[n:],
        "verdict_from_inside": orbit.verdict[:n], "verdict_from_outside": orbit.verdict[n:],
        "min_film": np.nanmin(orbit.min_film[:n], axis=1),
        "wall_time_s": orbit.wall_time_s})
