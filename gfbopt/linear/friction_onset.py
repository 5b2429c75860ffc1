"""The onset against the orbit amplitude when the bumps rub: describing function (harmonic
balance) of the spring–slider elements (:mod:`.friction_units`, :mod:`gfbopt.physics.friction`).

A whirl orbit of the journal of semi-major axis A (in clearances) at the threshold whirl ratio
γ deflects each foil unit by |δW_u| (from the perturbation of the threshold's mode shape), and
the unit's friction element then has the describing-function stiffness κ D(β_u) beside the
bump, β_u = X_s,u/|δW_u|.  The critical mass at amplitude A, M̄c(A), is the threshold of the
linearisation with those factors; the factors depend on the mode shape and the mode shape on
the factors, so the two are iterated to a fixed point (:func:`onset_at_amplitude`).  Small
orbits (A → 0) give the stuck foundation, large ones the bare bump (the slider carries only
F_s, whose share of the force falls as 1/A).

A rotor of mass M̄ above its small-motion onset (M̄ > M̄c(0)) whirls with a growing orbit; the
orbit settles where the friction's equivalent damping restores the threshold, M̄c(A) = M̄ with
M̄c rising through M̄ (a stable limit cycle of the describing function), searched for between
0 and the film's minimum thickness H_min (:func:`settled_amplitude`).  When M̄c(A) stays below
M̄ up to H_min the answer is "no bounded orbit inside the film".  A is the journal's orbit in
clearances; the film closes near A ≈ H_min (the foil's own motion is not subtracted: the
statement is a bound of the linear mode shape, not a contact model).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np
import pandas as pd

from ..errors import ParameterError
from ..inputs.checks import check_positive
from ..sparse_lu import factor
from .crossings import direct_local_crossing
from .model import Linearisation
from .threshold import LinearThreshold, linear_threshold

#: relative change of M̄c between two fixed-point iterations counted as converged
ONSET_TOLERANCE = 1e-7
#: most fixed-point iterations of :func:`onset_at_amplitude`
MAX_ITERATIONS = 40
#: most restarts from the full threshold search when it finds another branch
OUTER_ROUNDS = 3


@dataclass(frozen=True)
class FrictionOnset:
    """The threshold at one orbit amplitude (non-dimensional).

    amplitude : journal orbit semi-major axis A [clearances]; critical_mass M̄c(A) [-];
    whirl_ratio γ [-]; stuck_fraction : share of the loaded foil units that stay stuck [-];
    iterations : fixed-point iterations; converged : bool; message.
    """

    amplitude: float
    critical_mass: float
    whirl_ratio: float
    stuck_fraction: float
    iterations: int
    converged: bool
    message: str = ""


def mode_shape(lin: Linearisation, mass: float, whirl: float) -> np.ndarray:
    """ξ = (δX, δY): the null vector of M̄W̄0 s² I + Z(s) at s = iγ, scaled so that the orbit
    Re(ξ e^{iτ}) has semi-major axis 1 [clearances]."""
    return _mode_and_response(lin, mass, whirl)[0]


def deflection_amplitudes(lin: Linearisation, xi: np.ndarray, whirl: float) -> np.ndarray:
    """|δW_u| per foil unit for the journal motion ξ at s = iγ [clearances]."""
    s = 1j * whirl
    a, b = lin.system(s)
    lu = factor((a + s * b).astype(complex), lin.factoriser)
    y = -lu.solve(lin.c_xi.astype(complex) @ xi)
    return np.abs(lin.compliance.deflection(y, lin.stiffness_factor(s)))


def _mode_and_response(lin: Linearisation, mass: float, whirl: float) -> tuple:
    """(ξ of unit semi-major axis, the perturbation ŷ per unit ξ columns X = (A+sB)⁻¹C_ξ)
    from one LU at s = iγ."""
    s = 1j * whirl
    a, b = lin.system(s)
    lu = factor((a + s * b).astype(complex), lin.factoriser)
    x = lu.solve(lin.c_xi.astype(complex))
    d = mass * lin.load * s * s * np.eye(2) + lin.force @ x
    xi = np.linalg.svd(d)[2][-1].conj()
    semi_major = math.sqrt(0.5 * (np.vdot(xi, xi).real + abs(xi @ xi)))
    return xi / semi_major, x


def _amplitudes(lin: Linearisation, amplitude: float, mass: float, whirl: float) -> np.ndarray:
    """|δW_u| for the threshold mode at (M̄, γ) scaled to the orbit amplitude A."""
    xi, x = _mode_and_response(lin, mass, whirl)
    y = -(x @ (amplitude * xi))
    return np.abs(lin.compliance.deflection(y, lin.stiffness_factor(1j * whirl)))


def onset_at_amplitude(lin: Linearisation, amplitude: float,
                       whirl_range: tuple = (0.02, 1.2),
                       stuck: Optional[LinearThreshold] = None) -> FrictionOnset:
    """M̄c(A): the threshold with the friction elements at the orbit amplitude A (module doc).

    lin : a linearisation of a model with friction (``friction_coefficient`` > 0);
    amplitude : A [clearances], > 0; stuck : the small-motion threshold of ``lin`` when known
    (:func:`linear_threshold` of ``lin.at_amplitude(None)``).  Iterates mode shape ↔
    describing function from the stuck foundation until M̄c changes by less than
    :data:`ONSET_TOLERANCE` relative: each step follows the crossing by Newton's method on γ
    (:func:`~.crossings.direct_local_crossing`, an LU per step) and one LU gives the mode
    shape and the units' deflections; the full threshold search then confirms the branch
    (it finds the smallest crossing and checks stability below it) — when it finds another,
    the iteration restarts from it.
    """
    if lin.friction is None:
        raise ParameterError("friction_coefficient", 0.0, "must be > 0 for the onset against "
                             "the orbit amplitude (the bumps have no friction)")
    amp = check_positive("amplitude", amplitude)
    current = lin.at_amplitude(None)
    th = stuck if stuck is not None else linear_threshold(current, whirl_range)
    iterations, stuck_share = 0, 1.0
    for _ in range(OUTER_ROUNDS):
        mc, gamma = th.critical_mass, th.whirl_ratio
        if not (math.isfinite(mc) and mc > 0):
            return FrictionOnset(amp, mc, gamma, stuck_share, iterations, True, th.message)
        settled = False
        while iterations < MAX_ITERATIONS:
            iterations += 1
            w = _amplitudes(current, amp, mc, gamma)
            stuck_share = lin.friction.stuck_fraction(w)
            current = lin.at_amplitude(w)
            found = direct_local_crossing(current, gamma, mc * gamma**2 * lin.load,
                                          whirl_range)
            if found is None:
                break
            change = abs(found.mass - mc)
            mc, gamma = found.mass, found.whirl
            if change <= ONSET_TOLERANCE * mc:
                settled = True
                break
        th = linear_threshold(current, whirl_range)       # the branch, and stability below
        if settled and abs(th.critical_mass - mc) <= 10 * ONSET_TOLERANCE * mc:
            return FrictionOnset(amp, th.critical_mass, th.whirl_ratio, stuck_share,
                                 iterations, True)
    return FrictionOnset(amp, th.critical_mass, th.whirl_ratio, stuck_share, iterations,
                         False, f"mode shape and describing function did not settle in "
                                f"{iterations} iterations")


def onset_curve(lin: Linearisation, amplitudes: Sequence[float],
                whirl_range: tuple = (0.02, 1.2)) -> pd.DataFrame:
    """M̄c against the orbit amplitude: one row per amplitude (columns in
    :mod:`gfbopt.terms.friction`)."""
    stuck = linear_threshold(lin.at_amplitude(None), whirl_range)
    rows = [onset_at_amplitude(lin, a, whirl_range, stuck) for a in amplitudes]
    return pd.DataFrame({"orbit_amplitude": [r.amplitude for r in rows],
                         "critical_mass": [r.critical_mass for r in rows],
                         "whirl_ratio": [r.whirl_ratio for r in rows],
                         "stuck_fraction": [r.stuck_fraction for r in rows],
                         "converged": [r.converged for r in rows]})


@dataclass(frozen=True)
class SettledOrbit:
    """Where a rotor above its small-motion onset settles, by the describing function.

    mass : the rotor's M̄ [-]; small_motion_mass : M̄c for small orbits (stuck) [-];
    amplitude : settled orbit semi-major axis A [clearances] (nan when none);
    whirl_ratio : at the settled orbit [-]; bounded : True when an orbit was found inside the
    film; film_limit : H_min of the equilibrium [clearances]; verdict : one line.
    """

    mass: float
    small_motion_mass: float
    amplitude: float
    whirl_ratio: float
    bounded: bool
    film_limit: float
    verdict: str


def settled_amplitude(lin: Linearisation, mass: float, samples: int = 12,
                      smallest: float = 1e-3, xtol: float = 1e-6,
                      whirl_range: tuple = (0.02, 1.2)) -> SettledOrbit:
    """The orbit amplitude where M̄c(A) = M̄ (module docstring), or no bounded orbit.

    Scans A on ``samples`` log-spaced points from ``smallest`` H_min to H_min, takes the first
    point where M̄c(A) ≥ M̄ and refines the crossing by bisection on log A to ``xtol``
    relative.  mass : the rotor's M̄ = M c ω²/W0 [-].
    """
    m = check_positive("mass", mass)
    h_min = float(lin.static.min_film)
    small = linear_threshold(lin.at_amplitude(None), whirl_range)
    if not m > small.critical_mass:
        return SettledOrbit(m, small.critical_mass, 0.0, small.whirl_ratio, True, h_min,
                            f"stable for small orbits: M̄ = {m:.4g} <= M̄c = "
                            f"{small.critical_mass:.4g} (stuck bumps)")
    grid = h_min * np.geomspace(smallest, 1.0, samples)
    low = None
    for a in grid:
        here = onset_at_amplitude(lin, a, whirl_range, small)
        if here.critical_mass >= m:
            high = a
            break
        low = a
    else:
        return SettledOrbit(m, small.critical_mass, math.nan, math.nan, False, h_min,
                            f"no bounded orbit inside the film: M̄c(A) < M̄ = {m:.4g} for "
                            f"every orbit amplitude up to the minimum film {h_min:.4g} c")
    if low is None:
        low = high * 1e-3
    while high / low - 1.0 > xtol:
        mid = math.sqrt(low * high)
        here = onset_at_amplitude(lin, mid, whirl_range, small)
        if here.critical_mass >= m:
            high = mid
        else:
            low = mid
    final = onset_at_amplitude(lin, high, whirl_range, small)
    return SettledOrbit(m, small.critical_mass, high, final.whirl_ratio, True, h_min,
                        f"bounded whirl of A = {high:.4g} c at γ = {final.whirl_ratio:.4f} "
                        f"(M̄ = {m:.4g} above the stuck onset M̄c = "
                        f"{small.critical_mass:.4g}; describing function of the bumps' "
                        "friction)")

