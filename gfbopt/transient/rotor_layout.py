"""Where each part of a rotor transient's packed state sits (:class:`Layout`), and whether the
bearings' films can run through one call of the one-bearing kernel (:func:`stackable`).

A batch of B runs of a rotor on K bearings is one array (B, K, L): slot k holds bearing k's
film Φ_k and (with a loss factor) its foil state W_k; the rotor's coordinates, velocities
and τ are the tail of slot 0 (:mod:`.rotor_system`), 2n + 1 entries for a structure of n
degrees of freedom.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np


@dataclass(frozen=True)
class Layout:
    """Where each part of a packed state sits.  A batch is one array (B, K, L): slot k
    holds bearing k's Φ (first) and foil state W (next); the rotor's q̃, q̃' (n each, the
    structure's degrees of freedom) and τ are the last 2n + 1 entries of slot 0 (the other
    slots' tails stay 0).  Bearings of one film structure
    are then one contiguous (B·K, …) view, so the one-bearing kernel runs once for all."""

    phi: tuple          # per bearing: shape of Φ
    foil: tuple         # per bearing: shape of W, or None
    width: int          # L
    phi_size: tuple = ()    # per bearing: entries of Φ
    foil_size: tuple = ()   # per bearing: entries of W (0 without a foil state)
    dofs: int = 4           # n, the rotor structure's degrees of freedom

    @property
    def rotor(self) -> int:
        """Start of q̃ in slot 0 (then q̃' at +n, τ at +2n)."""
        return self.width - (2 * self.dofs + 1)

    @property
    def filled(self) -> int:
        """Entries every slot's film and foil state fill (the rest of a slot is padding)."""
        return min(p + f for p, f in zip(self.phi_size, self.foil_size))

    def phi_of(self, z: np.ndarray, k: int) -> np.ndarray:
        return z[:, k, :self.phi_size[k]].reshape((z.shape[0],) + self.phi[k])

    def foil_of(self, z: np.ndarray, k: int) -> Optional[np.ndarray]:
        if self.foil[k] is None:
            return None
        n = self.phi_size[k]
        return z[:, k, n:n + self.foil_size[k]].reshape((z.shape[0],) + self.foil[k])

    def rotor_of(self, z: np.ndarray) -> np.ndarray:
        """q̃, q̃' and τ of every run, (B, 2n + 1) (a view)."""
        return z[:, 0, self.rotor:]


def layout(model) -> Layout:
    phis, foils, width = [], [], 0
    for b in model.bearings:
        fs = b.tm.foil_state
        phis.append(tuple(b.tm.shape))
        foils.append(None if fs is None else tuple(fs.equilibrium.shape))
        width = max(width, int(np.prod(b.tm.shape)) +
                    (0 if fs is None else int(np.prod(fs.equilibrium.shape))))
    sizes = tuple(int(np.prod(p)) for p in phis)
    foil_sizes = tuple(0 if f is None else int(np.prod(f)) for f in foils)
    n = int(model.dofs)
    return Layout(tuple(phis), tuple(foils), width + 2 * n + 1, sizes, foil_sizes, n)


def empty_states(model, batch: int) -> np.ndarray:
    """Zero states of ``batch`` runs, (B, K, L)."""
    return np.zeros((batch, len(model.bearings), layout(model).width))


def stackable(model) -> bool:
    """True when every bearing has the same film structure (grid, film, law, S, Λ, foil
    state, speed), so one call of the one-bearing kernel serves all of them at once."""
    first = model.bearings[0]
    a = first.tm
    for b in model.bearings[1:]:
        t = b.tm
        fa, fb = a.foil_state, t.foil_state
        same = (t.shape == a.shape and t.periodic == a.periodic and t.law.name == a.law.name
                and t.compliance == a.compliance and t.bearing_number == a.bearing_number
                and t.compression_only == a.compression_only and t.gumbel == a.gumbel
                and t.dtheta == a.dtheta and t.dz == a.dz and t.foil_data is None
                and a.foil_data is None and b.model_speed == first.model_speed
                and np.array_equal(t.cos, a.cos) and np.array_equal(t.sin, a.sin)
                and np.array_equal(t.theta_weight, a.theta_weight)
                and np.array_equal(t.z_weight, a.z_weight)
                and all(_same(getattr(t, name, None), getattr(a, name, None))
                        for name in ("ambient", "bore", "compliance_rows"))
                and (fa is None) == (fb is None)
                and (fa is None or (fa.relaxation_time == fb.relaxation_time
                                    and fa.layout == fb.layout)))
        if not same:
            return False
    return True



def _same(a, b) -> bool:
    """Two optional per-row arrays of the bearing as built are equal (or both absent)."""
    if a is None or b is None:
        return a is None and b is None
    return bool(np.array_equal(a, b))
