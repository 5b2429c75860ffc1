"""The film: its thickness over a rigid journal, and the pressure that loads the journal.

Conventions (``docs/PHYSICS.md``, "Frames and angles"): X lies along the static load, θ is
measured from +X in the direction of rotation, and the journal centre sits at
(X, Y) = ε (cos φ, sin φ).  All quantities are non-dimensional (H = h/c, P = p/p_a).
"""
from __future__ import annotations

from .algebra import cos, positive_part, sin


def rigid_film(x, y, theta):
    """Film thickness over a rigid surface H_r = 1 − X cos θ − Y sin θ [-].

    x, y : journal centre X = ε cos φ, Y = ε sin φ [-] (numbers, arrays broadcasting against
    ``theta``, or CasADi symbols); theta : angle from the load line [rad].  The film is
    thickest at θ = π + φ.  With the foil deflection W the film is H = H_r + W.
    """
    return rigid_film_tabulated(x, y, cos(theta), sin(theta))


def rigid_film_tabulated(x, y, cos_theta, sin_theta):
    """H_r = 1 − X cos θ − Y sin θ [-] with cos θ and sin θ given (tabulated once per grid
    by the transient engine, which evaluates the film millions of times)."""
    return 1 - x * cos_theta - y * sin_theta


def rigid_film_polar(eccentricity, attitude, theta):
    """H_r = 1 − ε cos(θ − φ) [-]: :func:`rigid_film` with the centre in polar form.

    eccentricity ε [-], attitude φ [rad] and θ [rad] may be CasADi symbols.
    """
    return 1 - eccentricity * cos(theta - attitude)


def force_gauge(gauge, gumbel):
    """The gauge pressure that loads the journal [-].

    gauge : P − 1 [-]; gumbel : 0/False — the whole film pressure acts (full film); 1/True —
    sub-ambient gauge pressure is dropped, max(P − 1, 0) (Gümbel's condition, the convention
    of thesis Table 3.2; ``docs/PHYSICS.md``).  ``gumbel`` may be a CasADi parameter, so the
    choice is arithmetic rather than an ``if``.
    """
    if isinstance(gumbel, bool):
        return positive_part(gauge) if gumbel else gauge
    return (1 - gumbel) * gauge + gumbel * positive_part(gauge)
