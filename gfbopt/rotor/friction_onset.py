"""The rotor on two bearings whose bumps rub, above its small-motion onset: the orbit it
settles on by the describing function of the friction elements, or "no bounded orbit inside
the film" (the one-bearing form is :mod:`gfbopt.linear.friction_onset`).

For small orbits every loaded bump's spring–slider element is stuck: that is the foundation of
the rotor's matched-whirl onset and of its Campbell diagram (:mod:`.campbell`).  Above that
onset the first mode's inertia scale μ_c(0) < 1 and its orbit grows.  At an orbit of the mode
shape q̂ scaled by r, bearing k's journal moves by ξ_k = T_k q̂/c_k [clearances], each foil
unit u of that bearing by |δW_k,u| (:func:`gfbopt.linear.friction_onset.deflection_amplitudes`,
the bearing's own linearisation at s = iγ), and the unit's element has the describing-function
stiffness κ D(X_s,u/|δW_k,u|) beside its bump (:mod:`gfbopt.linear.friction_units`).  The
threshold with those factors, μ_c(r), is the mode's matched-whirl crossing on both bearings'
amplitude-dependent linearisations (:func:`gfbopt.rotor.matched_whirl.local_crossing`,
followed by its shape from the stuck crossing); shape and factors depend on each other, so the
two are iterated to a fixed point, as the one-bearing form does.

The orbit's size r is the share of the film it uses: r = max_k A_k/H_min,k, A_k the
semi-major axis of the journal's orbit at bearing k and H_min,k its equilibrium's minimum film
[clearances].  The rotor settles where μ_c(r) = 1 with μ_c rising through 1 (searched on
log-spaced r up to 1, refined by bisection on log r); when μ_c(r) < 1 up to r = 1 the answer
is "no bounded orbit inside the film".  The minimum film stated is min_k (H_min,k − A_k) c_k:
the journal's orbit against the static film, the foil's own motion not subtracted (a bound of
the linear mode shape, not a contact model — the same statement as the one-bearing form's).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Optional

import numpy as np

from ..errors import ParameterError
from ..inputs.checks import check_positive
from ..linear.friction_onset import deflection_amplitudes
from .matched_whirl import ModeCrossing, crossings, local_crossing
from .supports import RotorCase, SpeedStates, support_states

#: relative change of μ_c between two fixed-point iterations counted as converged
ONSET_TOLERANCE = 1e-7
#: most fixed-point iterations at one orbit size
MAX_ITERATIONS = 40
#: the model this module's answers come from, as outputs name it
MODEL = ("describing function of the bumps' Coulomb friction (spring-slider elements) on the "
         "rotor's matched-whirl threshold")


@dataclass(frozen=True)
class RotorFrictionOrbit:
    """Where the rotor settles above its small-motion onset (module docstring).

    speed_rpm [rpm]; bounded : True when a settled orbit lies inside the film (or the rotor is
    stable for small orbits); bearings : the bearings' names; amplitude_um : semi-major axis
    of the journal orbit at each bearing [µm] (zeros when stable, nan when unbounded);
    whirl_frequency_hz [Hz]; whirl_ratio [-]; min_film_um : min over the bearings of the
    static minimum film less the orbit [µm] (nan when unbounded); small_motion_inertia_scale
    μ_c(0) [-] (stuck bumps); inertia_scale μ_c at the settled orbit (unbounded: at the
    orbit that fills the film, r = 1) [-]; film_share r [-]; label : the mode;
    verdict : one line; model : which model gave it; converged : bool."""

    speed_rpm: float
    bounded: bool
    bearings: tuple
    amplitude_um: tuple
    whirl_frequency_hz: float
    whirl_ratio: float
    min_film_um: float
    small_motion_inertia_scale: float
    inertia_scale: float
    film_share: float
    label: str
    verdict: str
    model: str = MODEL
    converged: bool = True


@dataclass(frozen=True)
class _AmplitudeState:
    """What :func:`local_crossing` reads of a bearing: its linearisation (here with the
    friction elements at an orbit's amplitudes), impedance scale and whirl range."""

    linearisation: object
    scale: float
    whirl_range: tuple


@dataclass(frozen=True)
class _AtSize:
    crossing: Optional[ModeCrossing]
    journal: tuple          # ξ_k per bearing [clearances], complex 2-vectors
    iterations: int
    converged: bool


def semi_major(xi: np.ndarray) -> float:
    """Semi-major axis of the orbit Re(ξ e^{iτ}) of a complex 2-vector ξ [its units]."""
    xi = np.asarray(xi, dtype=complex)
    return math.sqrt(0.5 * (np.vdot(xi, xi).real + abs(xi @ xi)))


def _journals(rotor: RotorCase, vector: np.ndarray, size: float, films) -> tuple:
    """ξ_k = T_k q̂/c_k scaled so that max_k A_k/H_min,k = ``size``."""
    xi = [t @ np.asarray(vector, dtype=complex) / case.bearing.radial_clearance
          for t, case in zip(rotor.transforms, rotor.cases)]
    share = max(semi_major(x) / h for x, h in zip(xi, films))
    return tuple(x * (size / share) for x in xi)


def onset_at_size(rotor: RotorCase, states: SpeedStates, stuck: ModeCrossing,
                  size: float) -> _AtSize:
    """μ_c of the mode ``stuck`` (its small-motion crossing) with the friction elements at the
    orbit of film share ``size`` (module docstring): mode shape ↔ describing function iterated
    from the stuck foundation until μ_c changes by ≤ :data:`ONSET_TOLERANCE` relative."""
    films = [float(st.solution.min_film) for st in states.states]
    base = [st.linearisation for st in states.states]
    current, lins = stuck, list(base)
    journal = _journals(rotor, stuck.vector, size, films)
    for it in range(1, MAX_ITERATIONS + 1):
        journal = _journals(rotor, current.vector, size, films)
        lins = [lin if b.friction is None else
                b.at_amplitude(deflection_amplitudes(lin, xi, current.whirl_ratio))
                for b, lin, xi in zip(base, lins, journal)]
        amp_states = SpeedStates(states.speed_rpm, tuple(
            _AmplitudeState(lin, st.scale, st.whirl_range)
            for lin, st in zip(lins, states.states)))
        found = local_crossing(rotor, amp_states, current)
        if found is None:
            return _AtSize(None, journal, it, False)
        change = abs(found.inertia_scale - current.inertia_scale)
        current = found
        if change <= ONSET_TOLERANCE * found.inertia_scale:
            return _AtSize(current, _journals(rotor, current.vector, size, films), it, True)
    return _AtSize(current, journal, MAX_ITERATIONS, False)


def settled_whirl(rotor: RotorCase, speed_rpm: float, samples: int = 10,
                  smallest: float = 1e-2, xtol: float = 1e-4,
                  states: Optional[SpeedStates] = None) -> RotorFrictionOrbit:
    """The rotor's settled whirl at ``speed_rpm`` [rpm] by the describing function of its
    bumps' friction, or "no bounded orbit inside the film" (module docstring).

    rotor : a resolved rotor (:func:`~gfbopt.rotor.supports.resolve_rotor`) whose bearing
    files state ``friction_coefficient`` > 0 at one bearing at least; samples : log-spaced
    film shares from ``smallest`` to 1 scanned for μ_c ≥ 1; xtol : relative width of the
    bisection on the film share.  The mode followed is the first crossing (lowest μ_c) of the
    stuck foundation.  Raises ParameterError without friction, or when a bearing's load
    exceeds its capacity at this speed.
    """
    speed = check_positive("speed_rpm", speed_rpm)
    if not 0 < smallest < 1:
        raise ParameterError("smallest", smallest, "must lie in (0, 1): a share of the film")
    if not (isinstance(samples, int) and samples >= 2):
        raise ParameterError("samples", samples, "must be an integer >= 2")
    states = support_states(rotor, speed) if states is None else states
    if not states.ok:
        raise ParameterError("speed_rpm", speed, "a bearing's load exceeds its capacity "
                             "here: " + states.failure["message"])
    if all(st.linearisation.friction is None for st in states.states):
        raise ParameterError("friction_coefficient", 0.0, "must be > 0 in a bearing file of "
                             "the rotor for the settled whirl (the bumps have no friction)")
    names = tuple(rotor.names)
    films = [float(st.solution.min_film) for st in states.states]
    clear = [case.bearing.radial_clearance for case in rotor.cases]
    h_um = min(h * c * 1e6 for h, c in zip(films, clear))
    found = crossings(rotor, states)
    if found and found[0].inertia_scale == 0:          # the probe: unstable at every inertia
        return RotorFrictionOrbit(speed, False, names, (math.nan,) * len(names), math.nan,
                                  math.nan, math.nan, 0.0, 0.0, math.nan, found[0].label,
                                  "no describing-function answer: the rotor is unstable "
                                  "at every inertia scale (" + found[0].note + ")",
                                  MODEL, False)
    if not found:
        return RotorFrictionOrbit(speed, True, names, (0.0,) * len(names), math.nan,
                                  math.nan, h_um, math.inf, math.inf, 0.0, "",
                                  "stable for small orbits: no mode crosses the axis")
    stuck = found[0]
    omega_hz = stuck.whirl_frequency_hz / stuck.whirl_ratio

    def orbit(bounded, at: Optional[_AtSize], size, verdict, converged=True, last=None):
        if at is None:                  # stable, or unbounded (μ_c of the largest orbit)
            amp = (0.0 if bounded else math.nan,) * len(names)
            c = stuck if last is None else last
            film = h_um if bounded else math.nan
        else:
            c = at.crossing
            amp = tuple(semi_major(x) * cl * 1e6 for x, cl in zip(at.journal, clear))
            film = min((h - semi_major(x)) * cl * 1e6
                       for h, x, cl in zip(films, at.journal, clear))
        return RotorFrictionOrbit(speed, bounded, names, amp, c.whirl_ratio * omega_hz,
                                  c.whirl_ratio, film, stuck.inertia_scale, c.inertia_scale,
                                  size, stuck.label, verdict, MODEL, converged)

    if stuck.inertia_scale >= 1.0:
        return orbit(True, None, 0.0, f"stable for small orbits: μ_c = "
                     f"{stuck.inertia_scale:.4g} >= 1 ({stuck.label}, stuck bumps)")
    low, high_at = None, None
    for r in np.geomspace(smallest, 1.0, samples):
        here = onset_at_size(rotor, states, stuck, float(r))
        if not here.converged:
            return orbit(False, None, float(r), f"no answer: the describing function did not "
                         f"settle at film share {r:.3g} ({here.iterations} iterations)", False)
        if here.crossing.inertia_scale >= 1.0:
            high, high_at = float(r), here
            break
        low = float(r)
    else:
        return orbit(False, None, 1.0, "no bounded orbit inside the film",
                     last=here.crossing)
    low = high * 1e-3 if low is None else low
    while high / low - 1.0 > xtol:
        mid = math.sqrt(low * high)
        here = onset_at_size(rotor, states, stuck, mid)
        if not here.converged:
            return orbit(False, None, mid, f"no answer: the describing function did not "
                         f"settle at film share {mid:.3g}", False)
        if here.crossing.inertia_scale >= 1.0:
            high, high_at = mid, here
        else:
            low = mid
    result = orbit(True, high_at, high, "")
    amps = ", ".join(f"{a:.3g}" for a in result.amplitude_um)
    verdict = (f"bounded whirl of {amps} µm (bearings {', '.join(names)}) at "
               f"{result.whirl_frequency_hz:.4g} Hz, minimum film {result.min_film_um:.3g} µm")
    return replace(result, verdict=verdict)
