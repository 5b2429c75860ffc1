"""The result every integration method returns: a batch of journal-centre orbits."""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import ParameterError
from .fits import classify
from .system import TransientModel


@dataclass(frozen=True, eq=False)
class OrbitBatch:
    """Journal-centre orbits of a batch of rotors (non-dimensional; τ = ω t [rad]).

    tau (n,), x, y, min_film (B, n): positions and the minimum film H; equilibrium (X0, Y0);
    mass (B,) M̄ = M c ω²/W0; growth_rate (B,) [1/rad of shaft rotation] and whirl_ratio (B,)
    fitted to the orbit after ``settle`` revolutions; amplitude (B,) final orbit radius about
    the equilibrium [clearances]; contact (B,) bool; contact_tau (B,) [rad]; verdict (B,)
    strings; time_step Δτ [rad] (nan for variable-step methods); evaluations of the
    right-hand side; wall_time_s [s]; revolutions integrated; method; success and message
    (a run-time failure — a blown-up or failed integration — is reported here, not raised);
    damping : the structural damping of the foil, {} without it, else η, ν_ref, its source
    and τ_f = η/ν_ref (:meth:`gfbopt.transient.foil_state.KelvinVoigtFoil.describe`).
    """

    tau: np.ndarray
    x: np.ndarray
    y: np.ndarray
    min_film: np.ndarray
    equilibrium: tuple
    mass: np.ndarray
    growth_rate: np.ndarray
    whirl_ratio: np.ndarray
    amplitude: np.ndarray
    contact: np.ndarray
    contact_tau: np.ndarray
    verdict: tuple
    time_step: float
    evaluations: int
    wall_time_s: float
    revolutions: float
    method: str = "rk4"
    success: bool = True
    message: str = ""
    damping: dict = field(default_factory=dict)

    def to_frame(self, rotor: int = 0):
        """The orbit of one rotor as a table: τ, X, Y, ε, φ [deg], minimum film."""
        import pandas as pd

        x, y = self.x[rotor], self.y[rotor]
        return pd.DataFrame({"tau": self.tau, "x": x, "y": y, "eccentricity": np.hypot(x, y),
                             "attitude_angle_deg": np.degrees(np.arctan2(y, x)),
                             "min_film": self.min_film[rotor]})

    def to_dict(self, rotor: int = 0) -> dict:
        """Scalar results of one rotor as a flat dict (JSON, table rows)."""
        return {"mass": float(self.mass[rotor]), "verdict": self.verdict[rotor],
                "growth_rate": float(self.growth_rate[rotor]),
                "whirl_ratio": float(self.whirl_ratio[rotor]),
                "final_amplitude": float(self.amplitude[rotor]),
                "min_film": float(np.nanmin(self.min_film[rotor])),
                "contact": bool(self.contact[rotor]),
                "contact_tau": float(self.contact_tau[rotor]),
                "revolutions": float(self.revolutions),
                "time_step_rad": float(self.time_step),
                "method": self.method, "evaluations": int(self.evaluations),
                "wall_time_s": self.wall_time_s, "success": self.success,
                "message": self.message, **damping_fields(self.damping)}


def damping_fields(damping: dict) -> dict:
    """η and ν_ref for a result's flat dict: loss_factor 0 and no ν_ref without damping."""
    return {"loss_factor": 0.0, "reference_whirl_ratio": math.nan, **damping}


def check_positive(name: str, value) -> float:
    """``value`` as a float; ParameterError unless finite and > 0."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be a number") from None
    if not math.isfinite(v) or v <= 0:
        raise ParameterError(name, value if isinstance(value, (int, str)) else v,
                             "must be finite and > 0")
    return v


def check_masses(mass) -> np.ndarray:
    """The batch of M̄ values as an array; each finite and > 0."""
    mass = np.atleast_1d(np.asarray(mass, dtype=float))
    for mm in mass:
        check_positive("mass", mm)
    return mass


def finish_orbits(tm: TransientModel, tau: np.ndarray, x: np.ndarray, y: np.ndarray,
                  hmin: np.ndarray, contact: np.ndarray, contact_tau: np.ndarray,
                  mass: np.ndarray, *, settle: float, kick: float, time_step: float,
                  evaluations: int, started: float, revolutions: float, method: str,
                  success: bool = True, message: str = "") -> OrbitBatch:
    """Fit and classify the orbits and pack them (shared by every integration method).

    ``started`` is the ``time.perf_counter()`` value at the start of the run.
    """
    sol = tm.static
    x0 = sol.eccentricity * math.cos(sol.attitude_angle_rad)
    y0 = sol.eccentricity * math.sin(sol.attitude_angle_rad)
    growth, whirl, amp, verdicts = classify(tau, x - x0, y - y0, contact, settle, kick)
    damping = {} if tm.foil_state is None else tm.foil_state.describe()
    return OrbitBatch(tau, x, y, hmin, (x0, y0), mass, growth, whirl, amp, contact,
                      contact_tau, tuple(verdicts), time_step, evaluations,
                      time.perf_counter() - started, revolutions, method, success, message,
                      damping)
