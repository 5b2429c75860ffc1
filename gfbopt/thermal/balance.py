"""The heat balance of one bearing with the film's torque ratio and the conductances frozen:
one equation in the drag power P [W] (:mod:`.running` ties it to the static solves).

With the conductances g frozen the network's temperatures are affine in P
(:func:`~gfbopt.thermal.network.solve_network` at P = 0 and P = 1), so are the journal's and
the sleeve's thermal growths and the running clearance c(P); the film temperature T_f(P) gives
μ(T_f) (Sutherland).  With the torque ratio τ = T/T_Petroff a function of ln Λ
(Λ = 6 μ ω R²/(p_a c²), the bearing number at the running state) the balance is

    F(P) = P − τ(ln Λ(P)) · 2π μ(T_f(P)) ω² R³ L / c(P) = 0.

Its lowest root is found by sampling F at :data:`N_SAMPLES` powers up to the highest power
with a valid state (the clearance falling to :data:`MIN_RUNNING_CLEARANCE`, or the film
reaching its limit) — one vectorised evaluation — then Brent's method on the first sign
change; without one, a bounded search for the P where F comes closest to 0 (a narrow crossing
between samples is still found; else there is no root: thermal runaway).
"""
from __future__ import annotations

import math
from typing import Callable, Optional

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from .network import Conductances, solve_network
from .viscosity import sutherland_viscosity

#: smallest running clearance analysed [m]: the bearing file's floor of the clearance (below
#: 1 µm the gas film is no longer a continuum); a clearance that falls to it has closed
MIN_RUNNING_CLEARANCE = 1e-6
#: samples of F(P) when looking for its lowest root
N_SAMPLES = 256


def log_bearing_number(spec, omega: float, viscosity, clearance):
    """ln Λ, Λ = 6 μ ω R²/(p_a c²) [-] (scalars or numpy arrays; μ [Pa s], c [m], ω
    [rad/s]); −inf at rest (ω = 0)."""
    with np.errstate(divide="ignore"):
        return np.log(6.0 * viscosity * omega * spec.radius**2
                      / (spec.ambient_pressure * clearance**2))


class Balance:
    """The heat balance at speed ω [rad/s] with the conductances ``g`` [W/K] and
    ``torque_ratio`` τ(ln Λ) [-] frozen (module docstring); ``spec`` a
    :class:`~gfbopt.thermal.running.RunningSpec` with a ``[thermal]`` table.  Every method
    taking a power accepts a float or a numpy array of powers [W]."""

    def __init__(self, spec, omega: float, torque_ratio: Callable, g: Conductances):
        t = spec.thermal
        self.spec, self.omega, self.tau, self.g = spec, omega, torque_ratio, g
        capacity = t.cooling_mass_flow * t.gas_specific_heat
        self.capacity = capacity
        self.base = solve_network(0.0, g, t.ambient_temperature, t.inlet_k, capacity)
        unit = solve_network(1.0, g, t.ambient_temperature, t.inlet_k, capacity)
        self.rate = {k: getattr(unit, k) - getattr(self.base, k)
                     for k in ("film_k", "journal_k", "sleeve_k")}
        self.uc = spec.centrifugal(omega)

    def temperatures(self, power):
        return {k: getattr(self.base, k) + power * r for k, r in self.rate.items()}

    def clearance(self, power) -> tuple:
        """(running clearance, journal growth, sleeve bore growth) [m] at P."""
        t = self.temperatures(power)
        gj, gs = self.spec.thermal_growths(t["journal_k"], t["sleeve_k"])
        return self.spec.cold_clearance - self.uc - gj + gs, gj, gs

    def viscosity(self, film_k):
        """μ(T_f) [Pa s] (Sutherland through the stated viscosity; arrays too)."""
        t = self.spec.thermal
        return sutherland_viscosity(film_k, self.spec.viscosity, t.viscosity_k,
                                    t.sutherland_constant)

    def residual(self, power):
        """F(P) [W] (module docstring)."""
        c = self.clearance(power)[0]
        mu = self.viscosity(self.temperatures(power)["film_k"])
        tau = self.tau(log_bearing_number(self.spec, self.omega, mu, c))
        value = power - tau * self.spec.petroff_power(self.omega, mu, c)
        return float(value) if np.ndim(value) == 0 else value

    def ceiling(self) -> Optional[float]:
        """The power at which the clearance falls to the floor (None: it never does)."""
        c0 = self.clearance(0.0)[0]
        slope = self.clearance(1.0)[0] - c0
        if slope >= 0:
            return None
        return max((c0 - MIN_RUNNING_CLEARANCE) / -slope, 0.0)

    def film_ceiling(self) -> float:
        """The power at which the film reaches the network's film limit
        (:attr:`~gfbopt.thermal.network.ThermalNetwork.film_limit_k`) [W]: above it the
        model has no valid state (the film temperature rises with P)."""
        rate = self.rate["film_k"]
        room = self.spec.thermal.film_limit_k - self.base.film_k
        return max(room / rate, 0.0) if rate > 0 else math.inf

    def top(self) -> tuple:
        """(the highest power with a valid state [W] or inf, what sets it: "closure",
        "film" or "")."""
        closes, hot = self.ceiling(), self.film_ceiling()
        if closes is not None and closes <= hot:
            return closes, "closure"
        return (hot, "film") if math.isfinite(hot) else (math.inf, "")

    def lowest_root(self) -> tuple:
        """(the lowest P > 0 with F(P) = 0, or None; the P where F comes closest to 0)."""
        if self.clearance(0.0)[0] <= MIN_RUNNING_CLEARANCE or self.film_ceiling() <= 0.0:
            return None, 0.0
        top, _ = self.top()
        if not math.isfinite(top):           # the clearance never closes: F → +∞
            c0, mu0 = self.clearance(0.0)[0], self.viscosity(self.base.film_k)
            top = max(float(self.tau(log_bearing_number(self.spec, self.omega, mu0, c0)))
                      * self.spec.petroff_power(self.omega, self.spec.viscosity,
                                                self.spec.cold_clearance), 1e-12)
            for _ in range(200):
                if self.residual(top) > 0:
                    break
                top *= 2.0
        if self.residual(0.0) >= 0:          # no drag at all (zero speed)
            return 0.0, 0.0
        grid = top * np.linspace(0.0, 1.0, N_SAMPLES + 1)[:-1]
        grid = np.append(grid, top * (1.0 - 1e-12))
        values = self.residual(grid)         # one vectorised evaluation of the samples
        crossing = np.nonzero(values > 0)[0]
        if crossing.size:
            k = crossing[0]
            return brentq(self.residual, grid[k - 1], grid[k], xtol=1e-300, rtol=1e-15,
                          maxiter=200), grid[k]
        k = int(np.argmax(values))
        lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
        best = minimize_scalar(lambda p: -self.residual(p), bounds=(lo, hi),
                               method="bounded", options={"xatol": 1e-12 * top})
        if self.residual(best.x) > 0:        # a narrow crossing between samples
            return brentq(self.residual, lo, best.x, xtol=1e-300, rtol=1e-15,
                          maxiter=200), best.x
        return None, float(best.x)
