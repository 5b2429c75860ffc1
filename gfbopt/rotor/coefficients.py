"""Bearing stiffness and damping in SI against excitation frequency, for rotordynamics codes.

A gas film has no frequency-independent stiffness and damping: K(f) [N/m] and C(f) [N s/m]
depend on the excitation (whirl) frequency f, and a gas bearing's instability is
subsynchronous (f ≈ half the running frequency).  A rotordynamics code that evaluates the
bearing at the running speed (γ = 1) misses it; the coefficients must be taken at the whirl
frequency ("matched whirl", docs/PHYSICS.md §8).  The table below gives one row per frequency,
in the layout such codes read (e.g. ROSS, Timbó et al. 2020, doi:10.21105/joss.02120):

    frequency_hz, kxx_N_per_m, kxy_N_per_m, kyx_N_per_m, kyy_N_per_m,
    cxx_Ns_per_m, cxy_Ns_per_m, cyx_Ns_per_m, cyy_Ns_per_m

(the names of :mod:`gfbopt.glossary`, the same in the CSV, the JSON and the DataFrame).

Frame: x along the static load (the direction the load pushes the journal), y 90° ahead of it
in the direction of rotation; k_ij = −∂F_i/∂x_j, c_ij = −∂F_i/∂ẋ_j for the film force F on the
journal.  A code whose axes differ (e.g. x horizontal, y vertical up, load down) must rotate
them.  Conversions: K = K̄ p_a R²/c, C = C̄ p_a R²/(c ω), f = γ ω/(2π)
(:mod:`gfbopt.inputs.conversions`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Optional, Sequence

import numpy as np
import pandas as pd

from ..errors import ParameterError
from ..glossary import describe
from ..inputs.bearing import BearingGeometry
from ..inputs.conversions import (damping_scale, rpm_to_rad_per_s, stiffness_scale,
                                  whirl_frequency_hz, whirl_ratio_from_frequency)
from ..linear import Linearisation, coefficients

#: the glossary's names: stiffness [N/m] and damping [N s/m] in the load frame
COLUMNS = ("frequency_hz", *(f"k{a}{b}_N_per_m" for a in "xy" for b in "xy"),
           *(f"c{a}{b}_Ns_per_m" for a in "xy" for b in "xy"))
FRAME = ("x along the static load, y 90 degrees ahead of it in the direction of rotation; "
         "k_ij = -dF_i/dx_j [N/m], c_ij = -dF_i/d(dx_j/dt) [N s/m]; frequency-dependent: take "
         "them at the whirl frequency (matched whirl)")
#: default excitation frequencies, as whirl ratios γ = f/(shaft frequency) [-]
DEFAULT_WHIRL_RATIOS = tuple(np.round(np.arange(0.1, 1.01, 0.1), 10))


@dataclass(frozen=True)
class CoefficientTable:
    """K [N/m] and C [N s/m] against excitation frequency [Hz] at one operating point.

    table : one row per frequency, columns :data:`COLUMNS` (plus whirl_ratio [-]);
    speed_rpm : the shaft speed [rpm]; threshold_whirl_frequency_hz : the threshold whirl
    frequency [Hz]
    (nan if none), at which the table has a row; frame : the axes and sign convention.
    """

    table: pd.DataFrame
    speed_rpm: float
    threshold_whirl_frequency_hz: float
    frame: str = FRAME

    def write_csv(self, path) -> Path:
        """Write the table (columns :data:`COLUMNS` only) to ``path``; returns the path."""
        path = Path(path)
        self.table.loc[:, list(COLUMNS)].to_csv(path, index=False, float_format="%.9g")
        return path

    def to_dict(self) -> dict:
        """Column lists, the frame and the matched-whirl frequency (JSON-ready)."""
        return {"frame": self.frame, "speed_rpm": self.speed_rpm,
                "threshold_whirl_frequency_hz": self.threshold_whirl_frequency_hz,
                "units": {c: describe(c)[0] for c in ("whirl_ratio", *COLUMNS)},
                **{c: self.table[c].tolist() for c in ("whirl_ratio", *COLUMNS)}}


def coefficient_table(lin: Linearisation, bearing: BearingGeometry, speed_rpm: float,
                      frequencies_hz: Optional[Sequence[float]] = None,
                      matched_whirl_ratio: Optional[float] = None) -> CoefficientTable:
    """K and C in SI at ``frequencies_hz`` [Hz] (default: whirl ratios 0.1, 0.2, …, 1.0 of the
    shaft frequency), plus a row at the matched whirl ratio γc [-] when given.

    lin : the linearisation at the operating point (e.g. ``StabilityResult.linearisation``);
    bearing : the bearing in SI; speed_rpm : the shaft speed it was linearised at [rpm].
    Frequencies must be > 0: with structural damping the hysteretic damping is unbounded at
    zero frequency, and a zero-frequency damping is of no use to a rotordynamics code.
    """
    omega = rpm_to_rad_per_s(speed_rpm)
    if frequencies_hz is None:
        ratios = list(DEFAULT_WHIRL_RATIOS)
    else:
        ratios = []
        for f in frequencies_hz:
            if not (isinstance(f, (int, float)) and math.isfinite(f) and f > 0):
                raise ParameterError("frequency_hz", f, "must be finite and > 0 [Hz]")
            ratios.append(whirl_ratio_from_frequency(float(f), omega))
    matched = math.nan
    if matched_whirl_ratio is not None and math.isfinite(matched_whirl_ratio):
        ratios.append(float(matched_whirl_ratio))
        matched = whirl_frequency_hz(matched_whirl_ratio, omega)
    ratios = sorted(set(ratios))
    coeffs = coefficients(lin, ratios)
    k_scale = stiffness_scale(bearing.ambient_pressure, bearing.radius,
                              bearing.radial_clearance)
    c_scale = damping_scale(bearing.ambient_pressure, bearing.radius, bearing.radial_clearance,
                            omega)
    frame = {"frequency_hz": whirl_frequency_hz(coeffs.whirl_ratio, omega)}
    for name, unit, values, scale in (("k", "N_per_m", coeffs.stiffness, k_scale),
                                      ("c", "Ns_per_m", coeffs.damping, c_scale)):
        for i, a in enumerate("xy"):
            for j, b in enumerate("xy"):
                frame[f"{name}{a}{b}_{unit}"] = values[:, i, j] * scale
    frame["whirl_ratio"] = coeffs.whirl_ratio
    return CoefficientTable(pd.DataFrame(frame), speed_rpm, matched)
