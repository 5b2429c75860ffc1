"""The one-bearing analyses at the running condition, as the command line imports them: they
live in the library, :mod:`gfbopt.rotor.running_bearing` (this module re-exports its names
for the code that imported them from here)."""
from __future__ import annotations

from ..rotor.running_bearing import (RUNNING_KEYS, coarse_start, resolved_case,
                                     running_lift_off, running_load_capacity, running_onset,
                                     running_stability)

__all__ = ["RUNNING_KEYS", "coarse_start", "resolved_case", "running_lift_off",
           "running_load_capacity", "running_onset", "running_stability"]
