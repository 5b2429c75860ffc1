"""The finite-difference grid and the default resolution."""
from __future__ import annotations

import functools
import inspect
import re
from dataclasses import dataclass

from ..errors import ParameterError

#: the written form of a grid, as on the command line: 'NTHETAxNZ' ('72x20', ASCII digits)
_GRID_TEXT = re.compile(r"\s*(\d+)\s*[xX]\s*(\d+)\s*", re.ASCII)
#: the rule a malformed grid string breaks: one message for the command line and the API
GRID_TEXT_RULE = "must be written NTHETAxNZ, e.g. 72x20"


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
        """Grid from 'NTHETAxNZ', e.g. '72x20' (the ``--grid`` form of the command line).

        Anything else is the one-line ParameterError of ``--grid``:
        ``grid = '72x': must be written NTHETAxNZ, e.g. 72x20``."""
        match = _GRID_TEXT.fullmatch(text) if isinstance(text, str) else None
        if match is None:
            raise ParameterError("grid", text, GRID_TEXT_RULE)
        return cls(int(match.group(1)), int(match.group(2)))

    def __str__(self) -> str:
        return f"{self.n_theta}x{self.n_z}"


def as_grid(value) -> "Grid":
    """``value`` as a :class:`Grid`: a Grid as it is, a string 'NTHETAxNZ' ('72x20') parsed
    as the command line's ``--grid``, with the same one-line ParameterError when malformed;
    anything else is refused naming both forms."""
    if isinstance(value, Grid):
        return value
    if isinstance(value, str):
        return Grid.parse(value)
    raise ParameterError("grid", value,
                         "must be a gfbopt Grid or a string written NTHETAxNZ, e.g. 72x20")


def accepts_grid_strings(function):
    """``function`` with its ``grid`` argument (positional or keyword) read by
    :func:`as_grid` first, so that it takes ``"72x20"`` as well as a :class:`Grid`;
    signature and docstring kept (``__wrapped__`` is the function itself)."""
    signature = inspect.signature(function)
    if "grid" not in signature.parameters:
        return function

    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        bound = signature.bind_partial(*args, **kwargs)
        if "grid" in bound.arguments and bound.arguments["grid"] is not None:
            bound.arguments["grid"] = as_grid(bound.arguments["grid"])
        return function(*bound.args, **bound.kwargs)

    return wrapper


#: Default grid: its load error is <= 0.5 % of the grid-converged value over the validation
#: cases up to ε = 0.9 (results/grid_convergence).  72 × 20 is 4× cheaper and within 0.5 % up
#: to ε ≈ 0.6, 1.7 % at ε = 0.9.
DEFAULT_GRID = Grid()


#: memory of a static build and solve per grid node [bytes], above a base of
#: :data:`BASE_MEMORY_BYTES`: measured 7.3–9.7 kB per node at 144 × 36 and 288 × 72 (the
#: sparse LU's fill-in grows faster than the node count, so this is a lower bound further up)
MEMORY_PER_NODE_BYTES = 10e3
#: memory of an idle gfbopt process with CasADi loaded [bytes] (measured: 68 MB)
BASE_MEMORY_BYTES = 70e6
#: wall time of one static solve per grid node [s] (measured 0.5–1.5 ms per node at
#: 144 × 36 and 288 × 72 on a shared 2-core machine)
SOLVE_SECONDS_PER_NODE = 1e-3
#: default largest estimated memory of a run [GB]; the command-line option
#: ``--max-memory-gb`` raises it
DEFAULT_MAX_MEMORY_GB = 4.0


def grid_estimate(grid: Grid) -> tuple[float, float]:
    """(memory [bytes], seconds per static solve) estimated from the node count."""
    nodes = (grid.n_theta + 1) * (grid.n_z + 1)
    return BASE_MEMORY_BYTES + MEMORY_PER_NODE_BYTES * nodes, SOLVE_SECONDS_PER_NODE * nodes


def check_grid_budget(grid: Grid, max_memory_gb: float = DEFAULT_MAX_MEMORY_GB,
                      option: str = "--max-memory-gb") -> Grid:
    """``grid`` unless its estimated memory exceeds ``max_memory_gb``: then ParameterError
    with the estimate and the option that raises the limit (nothing is built)."""
    memory, seconds = grid_estimate(grid)
    if memory > max_memory_gb * 1e9:
        nodes = (grid.n_theta + 1) * (grid.n_z + 1)
        raise ParameterError("grid", str(grid), (
            f"{nodes:,} nodes: estimated {memory / 1e9:.3g} GB of memory and about "
            f"{seconds / 60:.3g} min per static solve ({MEMORY_PER_NODE_BYTES / 1e3:g} kB and "
            f"{SOLVE_SECONDS_PER_NODE * 1e3:g} ms per node, measured up to 288x72), above the "
            f"limit of {max_memory_gb:g} GB: use a coarser grid (the default {DEFAULT_GRID} is "
            f"within 0.5 % of grid convergence) or raise {option}"))
    return grid
