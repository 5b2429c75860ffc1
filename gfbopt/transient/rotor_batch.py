"""A batch of rotor runs: each run's speed profile, inertia scale and imbalance scale.

Speeds are over the reference speed ω_ref of the time unit τ = ω_ref t
(:mod:`.rotor_system`): ω/ω_ref = r0 + a τ, the shaft angle ϑ = r0 τ + a τ²/2.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError


@dataclass(frozen=True, eq=False)
class Runs:
    """Per-run parameters of a batch (arrays of shape (B,)).

    speed : r0 = ω(0)/ω_ref; ramp : a = ω̇/ω_ref² (dr/dτ); inertia_scale μ (M and G × μ,
    loads unchanged); imbalance_scale (every plane's amount × this).
    """

    speed: np.ndarray
    ramp: np.ndarray
    inertia_scale: np.ndarray
    imbalance_scale: np.ndarray

    @property
    def size(self) -> int:
        return self.speed.size

    def take(self, keep) -> "Runs":
        return Runs(self.speed[keep], self.ramp[keep], self.inertia_scale[keep],
                    self.imbalance_scale[keep])

    def speed_at(self, tau) -> np.ndarray:
        """ω/ω_ref of each run at τ (scalar or (B,))."""
        return self.speed + self.ramp * tau

    def angle_at(self, tau) -> np.ndarray:
        """Shaft angle ϑ [rad] since τ = 0."""
        return self.speed * tau + 0.5 * self.ramp * tau * tau


def runs(batch: int, speed=1.0, ramp=0.0, inertia_scale=1.0, imbalance_scale=1.0) -> Runs:
    """A :class:`Runs` of ``batch`` rows, each value a scalar or one per run."""
    def arr(name, v, positive):
        a = np.broadcast_to(np.asarray(v, dtype=float), (batch,)).copy()
        bad = ~np.isfinite(a) | ((a <= 0) if positive else np.zeros(batch, bool))
        if bad.any():
            raise ParameterError(name, float(a[bad][0]), "must be finite" +
                                 (" and > 0" if positive else ""))
        return a
    return Runs(arr("speed", speed, True), arr("ramp", ramp, False),
                arr("inertia_scale", inertia_scale, True),
                arr("imbalance_scale", imbalance_scale, False))
