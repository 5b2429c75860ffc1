"""The nonlinear critical mass of a rigid rotor from small-amplitude transients, and the
bifurcation diagram above it.

M̄ = M c ω²/W0 with M the rotor mass and W0 the static load carried by one bearing
(``docs/PHYSICS.md``).  The growth rate of the whirling mode is linear in M̄ near the
threshold, so the threshold is the zero of a line fitted to the measured growth rates.

The search (:func:`find_critical_mass`)
---------------------------------------
* With a linear estimate M̄_lin the first round is TWO transients at M̄_lin (1 ± tolerance/2).
  If one is stable and the other unstable the threshold lies between them, and the zero of
  the line through their growth rates is the answer (bracket width = tolerance).
* If they do not bracket it (the linear estimate is off), the next pair is centred on the
  zero extrapolated from the growth rates measured so far (clamped to at most a factor 4 per
  round) and its spread doubles every round that still fails, so the search widens
  automatically; once a sign change is found it is refined around the regression zero.
  The answer is always a zero inside a bracket of verdicts actually measured (stable below,
  unstable above), never the estimate itself, so a wrong estimate costs rounds, not accuracy.
* Without an estimate the first round is a geometric batch of 8 over M̄ = 0.25–64.
* Start: from the least-stable linear mode shape when ``initial_mode`` is given
  (:mod:`.mode`; then the orbit is the whirling mode alone and one whirl period suffices
  for the fit), else from a kick of the journal's velocity (then 5 revolutions, the first
  skipped).  A damped model (η > 0) starts its Kelvin–Voigt foil state on the mode's foil
  part too (:meth:`.mode.LinearMode.foil`).
* Structural damping: with the default ν_ref (the linear threshold whirl ratio) the
  Kelvin–Voigt foil has the hysteretic foundation's impedance at the threshold, so the
  nonlinear critical mass equals the damped linear one (:mod:`.foil_state`).

Default method: ``rkc`` (:mod:`.rkc`).  Evidence (benchmarks/bench_critical_mass.py,
results/benchmarks/critical_mass.json; ε = 0.4, Λ = 2, S = 1, simple foundation, periodic
film, 144 × 36, one core of a shared 2-core machine, tolerance 0.005; the search alone,
without the static and linear solutions):

=======================================  ========  ========  ==========  ===============
search                                   wall [s]  CPU [s]   RHS evals.  |M̄/M̄_lin − 1|
=======================================  ========  ========  ==========  ===============
rkc, 2 transients from the linear mode   1.9       1.2       2 431       0.005 %
rkc, 2 transients from a kick            3.3       2.2       5 355       0.002 %
rk4, 2 transients from the linear mode   25.9      15.8      35 740      0.002 %
bdf, 2 transients from the linear mode   29.0      16.5      —           0.054 %
previous: rk4, 8 transients, kick, 5 rev 187.0     106.7     78 804      0.001 %
=======================================  ========  ========  ==========  ===============

At equal accuracy (all far inside the 0.5 % tolerance) rkc is ≈ 13× faster than rk4 and
bdf on the same search, and the two-transient search from the mode ≈ 90× faster than the
previous one.  ``integrate_orbits`` itself keeps ``method='rk4'`` as its default: it is the
reference, and the regression tier pins RK4's numbers.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..errors import ParameterError
from .orbit import integrate_orbits
from .result import check_positive, damping_fields
from .system import State, TransientModel, equilibrium_state

#: The integration method of the search and the bifurcation diagram (module docstring).
DEFAULT_METHOD = "rkc"
#: Journal speed of the starting perturbation [-]: a generic kick, and the linear mode
#: (small, so that the quadratic terms stay ≲ 1e-5 of the mode: measured, a mode start at
#: 1e-3 biases a one-period fit by ≈ 1e-4 in σ, at 1e-5 by ≲ 3e-6).
KICK, MODE_KICK = 1e-3, 1e-5


@dataclass(frozen=True)
class CriticalMass:
    """Nonlinear (transient) critical mass M̄_crit = M c ω²/W0 of a rigid rotor.

    critical_mass : zero of the growth rate fitted inside the bracket [-] (nan on failure)
    bracket : (largest stable mass, smallest unstable mass) tested [-]
    whirl_ratio : whirl ratio at the threshold [-]
    linear_critical_mass : the linear threshold used to centre the search (nan if unused)
    history : one dict per transient (round, mass, growth_rate, whirl_ratio, verdict)
    transients, rounds, rotor_revolutions (summed over transients), evaluations (of the
    right-hand side, summed over batches) : cost counters
    wall_time_s : time of the search alone [s] (not the static or linear solution)
    success, message : a run-time failure is reported here, not raised
    method : integration method; start : 'linear mode' or 'kick'
    damping : {} without structural damping, else η, ν_ref, its source and τ_f
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
    method: str = DEFAULT_METHOD
    rounds: int = 0
    start: str = "kick"
    damping: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        return {"critical_mass": self.critical_mass, "bracket": list(self.bracket),
                "whirl_ratio": self.whirl_ratio,
                "linear_critical_mass": self.linear_critical_mass,
                "transients": self.transients, "rounds": self.rounds,
                "rotor_revolutions": self.rotor_revolutions,
                "evaluations": self.evaluations, "method": self.method,
                "start": self.start, "wall_time_s": self.wall_time_s,
                "success": self.success, "message": self.message,
                **damping_fields(self.damping)}


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


def _mode_arrays(initial_mode, tm: TransientModel, mass: float) -> tuple:
    """(δΦ, (δX, δY, δU, δV), δW or None) of ``initial_mode`` at ``mass``, scaled to unit
    journal speed (unit displacement if it has no speed).  δW, the damped foil state's part
    (η > 0), comes from a :class:`.mode.LinearMode` or as a third array; without it the
    foil starts at its equilibrium deflection."""
    raw = initial_mode(mass) if callable(initial_mode) else initial_mode
    try:
        dphi, journal, *foil = raw
        dphi = np.asarray(dphi, dtype=float)
        journal = np.asarray(journal, dtype=float).ravel()
        foil = np.asarray(foil[0], dtype=float) if foil else None
    except (TypeError, ValueError):
        raise ParameterError("initial_mode", type(raw).__name__, "must give (δΦ, (δX, δY, "
                             "δU, δV)[, δW]) as real arrays") from None
    if dphi.shape != tm.shape or journal.shape != (4,):
        raise ParameterError("initial_mode", f"shapes {dphi.shape}, {journal.shape}",
                             f"must be δΦ of shape {tm.shape} and (δX, δY, δU, δV)")
    scale = math.hypot(journal[2], journal[3]) or math.hypot(journal[0], journal[1])
    if not (math.isfinite(scale) and scale > 0 and np.all(np.isfinite(dphi))):
        raise ParameterError("initial_mode", "journal part 0 or not finite",
                             "must move the journal (finite, non-zero)")
    if tm.foil_state is None:
        return dphi / scale, journal / scale, None
    if foil is None and hasattr(initial_mode, "foil"):   # a LinearMode: δW on the scale of
        foil = initial_mode.foil(tm.foil_state.layout)   # the (δΦ, journal) it returned
    shape = tm.foil_state.equilibrium.shape
    if foil is not None and foil.shape != shape:
        raise ParameterError("initial_mode", f"foil part of shape {foil.shape}",
                             f"must be δW of shape {shape} (the damped foil state)")
    return dphi / scale, journal / scale, None if foil is None else foil / scale


def _start_state(tm: TransientModel, masses: np.ndarray, initial_mode, kick: float) -> State:
    """The equilibrium plus ``kick`` × the unit mode shape, one rotor per mass."""
    state = equilibrium_state(tm, masses.size)
    for b, mm in enumerate(masses):
        dphi, journal, foil = _mode_arrays(initial_mode, tm, float(mm))
        state.phi[b] += kick * dphi
        if foil is not None:
            state.w[b] += kick * foil
        state.x[b] += kick * journal[0]
        state.y[b] += kick * journal[1]
        state.u[b] += kick * journal[2]
        state.v[b] += kick * journal[3]
    return state


def _pair(centre: float, spread: float, batch: int) -> np.ndarray:
    """``batch`` masses centred on ``centre``, spaced by ``spread`` (relative)."""
    offsets = np.arange(batch) - 0.5 * (batch - 1)
    return centre * (1.0 + spread * offsets)


def _extrapolated_zero(history: list) -> float:
    """Zero of the least-squares line through the finite growth rates (nan if none)."""
    pts = [(h["mass"], h["growth_rate"]) for h in history if math.isfinite(h["growth_rate"])]
    if len({p[0] for p in pts}) < 2:
        return math.nan
    pts = sorted(pts)[-4:] if all(p[1] < 0 for p in pts) else sorted(pts)[:4]
    slope, intercept = np.polyfit([p[0] for p in pts], [p[1] for p in pts], 1)
    return -intercept / slope if slope > 0 else math.nan


def _next_masses(history: list, lo: float, hi: float, mc: float, tolerance: float,
                 batch: int, widen: float) -> np.ndarray:
    """The masses of the next round (module docstring)."""
    if math.isfinite(mc):                              # bracketed: refine about the zero
        masses = _pair(mc, tolerance, batch)
        if masses.min() <= lo or masses.max() >= hi:
            masses = np.linspace(lo, hi, batch + 2)[1:-1]
        return masses
    zero = _extrapolated_zero(history)
    if hi == math.inf:                                 # all stable so far: heavier
        centre = zero if math.isfinite(zero) else 2.0 * lo
        centre = min(max(centre, lo * (1 + 2 * tolerance * widen)), 4.0 * lo)
        return np.maximum(_pair(centre, tolerance * widen, batch), lo * (1 + 0.5 * tolerance))
    centre = zero if math.isfinite(zero) and zero > 0 else 0.5 * hi   # all unstable: lighter
    centre = max(min(centre, hi * (1 - 2 * tolerance * widen)), 0.25 * hi)
    return np.minimum(_pair(centre, tolerance * widen, batch), hi * (1 - 0.5 * tolerance))


def find_critical_mass(tm: TransientModel, *, tolerance: float = 0.005,
                       linear_estimate: Optional[float] = None, batch: Optional[int] = None,
                       revolutions: Optional[float] = None, settle: Optional[float] = None,
                       kick: Optional[float] = None, max_rounds: int = 8, progress=None,
                       method: str = DEFAULT_METHOD, initial_mode=None) -> CriticalMass:
    """Find M̄_crit = M c ω²/W0 to a relative ``tolerance`` from transients (module doc).

    Parameters
    ----------
    tm : the transient model about the static equilibrium
    tolerance : relative half-width of the final bracket [-], in (0, 0.5)
    linear_estimate : the linear threshold M̄_lin [-] to centre the search on, or None
    batch : rotors per round (default 2 with a linear estimate, 8 without)
    revolutions : shaft revolutions per transient [-] (default: with ``initial_mode`` one
        whirl period 2π/γ of its eigenvalue plus 10 % (γ = 0.5 when it carries none), at
        least 1.5; else 5)
    settle : revolutions skipped before the growth-rate fit (default 0 with
        ``initial_mode``, 1 with a kick)
    kick : journal speed of the start [-] (default 1e-5 on the mode, 1e-3 as a kick)
    max_rounds : most rounds of transients
    progress : optional callable(fraction in [0, 1])
    method : integration method ('rkc', 'rk4' or 'bdf'; :data:`gfbopt.transient.METHODS`)
    initial_mode : start from a mode shape: a :class:`gfbopt.transient.mode.LinearMode`,
        any callable mass → (δΦ (m, n_z + 1), (δX, δY, δU, δV)), or that pair of arrays

    Returns
    -------
    CriticalMass (``success`` False, with a message, when no bracket was found or an
    integration failed).
    """
    tolerance = check_positive("tolerance", tolerance)
    if tolerance >= 0.5:
        raise ParameterError("tolerance", tolerance, "must be < 0.5 (relative)")
    estimate = linear_estimate is not None and math.isfinite(linear_estimate)
    if estimate:
        check_positive("linear_estimate", linear_estimate)
    batch = int(check_positive("batch", batch if batch is not None else (2 if estimate else 8)))
    max_rounds = int(check_positive("max_rounds", max_rounds))
    start = "kick" if initial_mode is None else "linear mode"
    kick = check_positive("kick", kick if kick is not None else
                          (KICK if initial_mode is None else MODE_KICK))
    if revolutions is None:
        whirl = abs(getattr(initial_mode, "eigenvalue", 0.5j).imag) or 0.5
        revolutions = 5.0 if initial_mode is None else max(1.5, 1.1 / whirl)
    revolutions = check_positive("revolutions", revolutions)
    settle = (1.0 if initial_mode is None else 0.0) if settle is None else float(settle)
    if not 0 <= settle < revolutions:
        raise ParameterError("settle", settle, f"must lie in [0, revolutions = {revolutions:g})")
    t0 = time.perf_counter()
    history: list = []
    masses = (_pair(linear_estimate, tolerance, batch) if estimate
              else np.geomspace(0.25, 64.0, batch))
    evaluations, rotor_revs, rounds, failed = 0, 0.0, 0, 0
    message = ""
    mc, whirl, lo, hi = math.nan, math.nan, 0.0, math.inf
    done = 0.0                               # share of the progress bar already filled
    for round_ in range(max_rounds):
        share = 0.8 if round_ == 0 else 0.5

        def inner(fraction, base=done, width=(1.0 - done) * share):
            progress(min(base + width * fraction, 1.0))

        initial = None if initial_mode is None else _start_state(tm, masses, initial_mode,
                                                                 kick)
        orbit = integrate_orbits(tm, masses, revolutions, kick=kick, initial=initial,
                                 settle=settle, method=method,
                                 progress=inner if progress is not None else None)
        done += (1.0 - done) * share
        rounds += 1
        evaluations += orbit.evaluations
        rotor_revs += orbit.revolutions * masses.size
        for k, mm in enumerate(masses):
            g = float(orbit.growth_rate[k])
            if orbit.verdict[k] in ("contact", "limit cycle"):
                g = math.inf if not math.isfinite(g) or g <= 0 else g
            history.append({"round": round_, "mass": float(mm), "growth_rate": g,
                            "whirl_ratio": float(orbit.whirl_ratio[k]),
                            "verdict": orbit.verdict[k]})
        if not orbit.success:
            message = f"transient failed in round {round_}: {orbit.message}"
            break
        mc, whirl, lo, hi = _threshold_from_history(history)
        if math.isnan(mc) and lo == 0.0 and hi == math.inf:
            message = "no finite growth rate was measured"
            break
        if math.isfinite(mc) and (hi - lo) <= 2 * tolerance * mc:
            break
        failed = 0 if math.isfinite(mc) else failed + 1
        masses = _next_masses(history, lo, hi, mc, tolerance, batch, 2.0 ** max(failed - 1, 0))
    wall = time.perf_counter() - t0
    ok = not message and math.isfinite(mc) and (hi - lo) <= 2 * tolerance * mc
    if not ok:
        message = message or (f"no bracket of relative width {2 * tolerance:g} after "
                              f"{max_rounds} rounds (bracket {lo:.4g}–{hi:.4g})")
    if progress is not None:
        progress(1.0)
    return CriticalMass(mc if ok else math.nan, (lo, hi), whirl,
                        float(linear_estimate) if estimate else math.nan,
                        tuple(history), len(history), rotor_revs, evaluations, wall, ok,
                        message, method, rounds, start,
                        {} if tm.foil_state is None else tm.foil_state.describe())


def limit_cycle_amplitudes(tm: TransientModel, masses, revolutions: float = 60.0,
                           kicks: tuple = (0.05, 0.6), method: str = DEFAULT_METHOD):
    """Bifurcation diagram: the limit-cycle size against M̄ above the threshold.

    Each mass runs twice in one batch, from the journal displaced along X by ``kicks[0]``
    (inside the cycle) and by ``kicks[1]`` (outside) [clearances]; where both reach
    the same final amplitude the cycle is established.  Amplitude: largest distance of the
    journal centre from the equilibrium over the last two whirl periods [clearances].
    ``method`` : integration method (default :data:`DEFAULT_METHOD`).
    """
    import pandas as pd

    masses = np.asarray(masses, dtype=float)
    batch = 2 * masses.size
    state = equilibrium_state(tm, batch)
    n = masses.size
    state.x[:n] += kicks[0]
    state.x[n:] += kicks[1]
    orbit = integrate_orbits(tm, np.concatenate([masses, masses]), revolutions, initial=state,
                             settle=revolutions / 2, method=method)
    return pd.DataFrame({
        "mass": masses, "amplitude_from_inside": orbit.amplitude[:n],
        "amplitude_from_outside": orbit.amplitude[n:],
        "verdict_from_inside": orbit.verdict[:n], "verdict_from_outside": orbit.verdict[n:],
        "min_film": np.nanmin(orbit.min_film[:n], axis=1),
        "wall_time_s": orbit.wall_time_s})
