"""Flexible rotors through ROSS: each gfbopt bearing's frequency-dependent K and C in the form
ROSS's ``BearingElement`` takes.

ROSS (ross-rotordynamics, an optional extra: ``pip install -e ".[ross]"``; ROSS 3.x needs
Python ≥ 3.12, the core of gfbopt stays on Python ≥ 3.10) takes bearing coefficients as tables
over speed and excitation frequency (``speed`` × ``frequency``, rad/s, PCHIP between points,
linear extrapolation outside: keep the table wide).  A gas bearing's coefficients must be taken
at the whirl frequency (matched whirl, ``run_modal(speed, matched_whirl=True)``): ROSS's
default, the running speed, misses the foil bearing's subsynchronous instability
(shared design notes, "ROSS 3.x").

:func:`bearing_tables` gives, for one bearing of a gfbopt rotor, the tables kxx … cyy [N/m,
N s/m] in the rotor's x–y frame (x along gravity by default; ROSS's x and y are the same
plane), from Z_k(iΩ) rotated out of the bearing's load frame: K = Re(R Z Rᵀ), C = Im(R Z Rᵀ)/Ω.
:func:`bearing_element` builds the ROSS element (ROSS imported only there).  The same signs as
ROSS: the bearing force on the shaft is −K u − C u̇.
"""
from __future__ import annotations

from typing import Sequence

import numpy as np

from ..errors import ParameterError
from ..inputs.conversions import rpm_to_rad_per_s
from .rigid import rotation
from .system import SpeedLine

#: the coefficient names of ROSS's BearingElement
NAMES = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")


def bearing_tables(line: SpeedLine, bearing: int, speeds_rpm: Sequence[float],
                   frequencies_hz: Sequence[float]) -> dict:
    """{'speed': ω [rad/s] (n_s,), 'frequency': Ω [rad/s] (n_f,), kxx … cyy: (n_s, n_f)}
    for bearing number ``bearing`` (0 or 1) of the rotor on ``line``."""
    if bearing not in (0, 1):
        raise ParameterError("bearing", bearing, "must be 0 or 1 (the rotor's two bearings)")
    freqs = np.asarray(frequencies_hz, dtype=float)
    if freqs.size == 0 or not np.all(np.isfinite(freqs) & (freqs > 0)):
        raise ParameterError("frequencies_hz", list(freqs), "must be finite and > 0 [Hz]")
    speeds = [float(s) for s in speeds_rpm]
    out = {n: np.zeros((len(speeds), freqs.size)) for n in NAMES}
    rot = rotation(line.rotor.loads[bearing].direction_rad)
    for i, speed in enumerate(speeds):
        states = line.states(speed)
        if not states.ok:
            raise ParameterError("speeds_rpm", speed, "a bearing's load exceeds its capacity "
                                 "here: " + states.failure["message"])
        omega = rpm_to_rad_per_s(speed)
        st = states.states[bearing]
        for j, f in enumerate(freqs):
            big = 2 * np.pi * f
            z = rot @ st.impedance(big / omega) @ rot.T
            for k, (p, q) in enumerate(((0, 0), (0, 1), (1, 0), (1, 1))):
                out[NAMES[k]][i, j] = z[p, q].real
                out[NAMES[4 + k]][i, j] = z[p, q].imag / big
    out["speed"] = np.array([rpm_to_rad_per_s(s) for s in speeds])
    out["frequency"] = 2 * np.pi * freqs
    return out


def bearing_element(node: int, tables: dict, **kwargs):
    """A ROSS ``BearingElement`` at ``node`` from :func:`bearing_tables` (needs ROSS ≥ 3.0,
    which takes speed × frequency tables)."""
    import ross  # optional extra: ParameterError below names it when missing

    return ross.BearingElement(node, **{n: tables[n] for n in NAMES},
                               speed=tables["speed"], frequency=tables["frequency"], **kwargs)


def ross_available() -> tuple[bool, str]:
    """(importable, reason) for the optional ROSS extra."""
    try:
        import importlib.util

        if importlib.util.find_spec("ross") is None:
            return False, ("ROSS is not installed (optional extra: pip install -e \".[ross]\","
                           " ross-rotordynamics >= 3.0 needs Python >= 3.12)")
    except (ImportError, ValueError) as exc:  # pragma: no cover
        return False, f"ROSS cannot be located ({exc})"
    return True, ""
