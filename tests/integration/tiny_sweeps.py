"""Tiny sampled static sweeps (seconds on a coarse grid) for the store, durability, Dask and
safety tests: one template instead of a copy per test file."""
from __future__ import annotations

#: (name, low, high) of the sampled inputs of the default sweep
VARIABLES = (("bearing_number", 0.5, 3.0), ("eccentricity", 0.2, 0.7))


def sweep_toml(*, n: int = 8, chunk: int = 1, batch: int = 1, grid: str = "24x6",
               title: str = "tiny static sweep", min_success: float = 0.9,
               fixed: str = "length_ratio = 1.0", variables=VARIABLES) -> str:
    """The text of a ``kind = "sweep"`` static study file: a Latin hypercube (seed 5) of
    ``n`` points over ``variables``, a simple foil, chunks of ``chunk``, parts of ``batch``."""
    lines = ['kind = "sweep"', f'title = "{title}"', 'source = "test"', 'analysis = "static"',
             f'grid = "{grid}"', f"chunk_size = {chunk}", f"batch_rows = {batch}",
             f"min_success_fraction = {min_success}", "", "[model]", 'foil = "simple"', "",
             "[fixed]", fixed, "", "[sampling]", 'method = "lhs"', f"n = {n}", "seed = 5"]
    for name, low, high in variables:
        lines += ["", "[[sampling.variables]]", f'name = "{name}"', f"low = {low}",
                  f"high = {high}"]
    return "\n".join(lines) + "\n"
