"""The finite-difference grid and the default resolution."""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import ParameterError


@dataclass(frozen=True)
class Grid:
    """Finite-difference grid: ``n_theta`` intervals round the bearing, ``n_z`` axially.

    Periodic film: nodes θ_i = θ_0 + 2π i/n_theta, i = 0..n_theta−1.  Seam film: nodes
    i = 0..n_theta with P = 1 at both ends.  Axially Z_j = −L/D + j·2(L/D)/n_z,
    j = 0..n_z, with P = 1 at j = 0 and j = n_z.  ``Grid()`` is the default grid.
    """

    n_theta: int = 144
    n_z: int = 36

    def __post_init__(self) -> None:
        for key, low in (("n_theta", 12), ("n_z", 4)):
            value = getattr(self, key)
            if isinstance(value, bool) or not isinstance(value, int):
                raise ParameterError(f"grid {key}", value, "must be an integer")
            if value < low:
                raise ParameterError(f"grid {key}", value, f"must be >= {low} (grid too coarse)")
            if value > 2000:
                raise ParameterError(f"grid {key}", value, "must be <= 2000")
        if self.n_z % 2:
            raise ParameterError("grid n_z", self.n_z,
                                 "must be even (a node on the mid-plane Z = 0)")

    @classmethod
    def parse(cls, text: str) -> "Grid":
        """Grid from 'NTHETAxNZ', e.g. '72x20'."""
        parts = str(text).lower().split("x")
        if len(parts) != 2 or not all(p.strip().isdigit() for p in parts):
            raise ParameterError("grid", text, "must be written NTHETAxNZ, e.g. 72x20")
        return cls(int(parts[0]), int(parts[1]))

    def __str__(self) -> str:
        return f"{self.n_theta}x{self.n_z}"


#: Default grid: its load error is <= 0.5 % of the grid-converged value over the validation
#: cases up to ε = 0.9 (results/grid_convergence).  72 × 20 is 4× cheaper and within 0.5 % up
#: to ε ≈ 0.6, 1.7 % at ε = 0.9.
DEFAULT_GRID = Grid()
