"""Structural damping of the bump foundation in the transient: a Kelvin–Voigt foil state.

With a loss factor η > 0 (``BearingModel.loss_factor``) the foil deflection W is no longer
algebraic in the pressure.  It becomes a state of its own, beside Φ = P H and the journal,
one per θ row (axial-mean law) or one per node (local law)::

    τ_f dW/dτ + W = S q,     τ_f = η / ν_ref                  (docs/PHYSICS.md §7)

q = P̄ − 1 per row (axial-mean law) or P − 1 per node (local law); compression-only bumps
relax towards S max(q, 0), the static law's deflection, so W ≥ 0 is kept by the equation
itself.  P and H are recovered from Φ and the current W without solving anything:
H = H_r + W, P = Φ/H (:meth:`gfbopt.physics.foil_laws.FoilLaw.recover_deflected`).

Why it agrees with the linear analysis at the threshold
--------------------------------------------------------
The linear analysis (:mod:`gfbopt.linear`) models η as hysteresis: for motion e^{iγτ} the
foundation stiffness is k (1 + iη sign γ), the compliance S/(1 + iη).  Constant-η hysteresis
has no causal time-domain form; Kelvin–Voigt is the causal model that matches it at one
frequency: for motion e^{iγτ} it gives W = S q/(1 + iτ_f γ) = S q/(1 + iη γ/ν_ref), which is
S q/(1 + iη) exactly at γ = ν_ref.  The stability threshold is a single-frequency condition
(s = iγ_c on the imaginary axis, docs/PHYSICS.md §8): with ν_ref = γ_c, the linear threshold whirl
ratio, both foundations have the same impedance there, so the same critical mass and whirl
ratio.  That is the default ν_ref (a user may give another, which moves the nonlinear
threshold away from the linear one).  Away from the threshold the two differ: Kelvin–Voigt
damping grows with frequency, hysteretic damping does not, so growth rates off the threshold
(and orbits) belong to the Kelvin–Voigt model, not to the hysteretic one.

Stiffness.  The foil rates are relaxations, ∂W'/∂W ≈ −(1 + S P/H)/τ_f: for η = 0.3 and
ν_ref ≈ 0.5 (τ_f = 0.6) a few per radian, far below the film's diffusion rates (≈ 400 at
72 × 20, ≈ 1600 at 144 × 36), so the RK4 step and the RKC stage count are unchanged; only a
very small η (τ_f → 0, the undamped limit) makes them the stiffest part of the system, and
:func:`foil_bound` puts them into the stability bound of both integrators.

Measured (tests/verification/test_kelvin_voigt.py; ε = 0.4, Λ = 2, S = 1, η = 0.3, rkc from
the damped linear mode): nonlinear over linear critical mass − 1 = −4e-6 (axial-mean law,
periodic film) and −2.5e-5 (local law, seam 180° from the load) at 72 × 20, −2.6e-6 and
−2.4e-5 at 144 × 36, where η = 0.3 raises the critical mass by ≈ 9.6 %.  The beam foil is not
supported (:attr:`gfbopt.physics.foil_laws.BeamLaw.damped_transient_refusal`: a Kelvin–Voigt
foundation under a massless bending foil is stiff).

With friction
-------------
With the bumps' spring–slider elements (:mod:`.friction_foil`, the one-bearing friction
driver) the foil's balance with the dashpot is q = W/S + (τ_f/S) W' + r, r the element's
reaction clip((κ/S)(W − Z), ±μ_f q⁺) at the state's W from the step's sliders Z (the play
operator; Z moved after each accepted step as without damping), so
τ_f W' + W = S (q − r) (the law's W(q − r): S max(q − r, 0) for compression-only bumps,
W_h(q − r) for hardening bumps).  P and H then come from W alone, H = H_r + W, as without
friction: the element enters the rate only, and with μ_f = 0 (r = 0) the rate is the
undamped-friction model's exactly.  Linearised at γ = ν_ref the foundation is
(1 + iη + κ D)/S, the linear analysis's (:mod:`gfbopt.linear.friction_units`).

References: J.-P. Peng, M. Carpino, "Calculation of stiffness and damping coefficients for
elastically supported gas foil bearings", J. Tribol. 115(1) (1993) 20–27; T. H. Kim,
L. San Andrés, "Heavily loaded gas foil bearings: a model anchored to test data", ASME J. Eng.
Gas Turbines Power 130(1) (2008) 012504; A. D. Nashif, D. I. G. Jones, J. P. Henderson,
*Vibration Damping*, Wiley, New York, 1985 (hysteretic and viscoelastic damping models).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import ParameterError

#: ν_ref when the linear analysis finds no whirl ratio (stable for every mass): half-frequency
#: whirl, the limit of these bearings' threshold whirl (docs/PHYSICS.md §8).
FALLBACK_WHIRL = 0.5


@dataclass(frozen=True, eq=False)
class KelvinVoigtFoil:
    """The Kelvin–Voigt foil state of a damped transient model (module docstring).

    loss_factor : η [-], > 0;  reference_whirl_ratio : ν_ref [-], > 0, the whirl ratio at
    which the foundation matches the hysteretic one;  reference_source : where ν_ref came
    from ('linear threshold', 'given' or the fallback);  layout : 'rows' (W per θ row,
    shape (m,)) or 'nodes' (per node, (m, n_z + 1));  equilibrium : W of the static
    equilibrium in that layout [-].
    """

    loss_factor: float
    reference_whirl_ratio: float
    reference_source: str
    layout: str
    equilibrium: np.ndarray

    @property
    def relaxation_time(self) -> float:
        """τ_f = η/ν_ref [rad of shaft rotation]."""
        return self.loss_factor / self.reference_whirl_ratio

    def rate(self, p: np.ndarray, w: np.ndarray, tm, slider=None) -> np.ndarray:
        """dW/dτ = (S q − W)/τ_f for a batch (P (B, m, n_z + 1), W in the layout) [1/rad].

        With the bumps' friction (``tm.friction`` and the sliders Z, ``slider``, in the same
        layout) the bump carries q − r, r the spring–slider element's reaction at W from Z
        (:func:`.friction_foil.element_reaction`): dW/dτ = (S (q − r) − W)/τ_f (module doc,
        "With friction")."""
        if slider is not None and tm.friction is not None:
            from .friction_foil import element_gauge, element_reaction

            q = element_gauge(p, tm)
            target = gauge_target(q - element_reaction(q, w, slider, tm), tm)
            target -= w
            target /= self.relaxation_time
            return target
        target = tm.law.deflection_target(p, tm)
        target -= w
        target /= self.relaxation_time
        return target

    def describe(self) -> dict:
        """η, ν_ref, its source and τ_f, for results."""
        return {"loss_factor": self.loss_factor,
                "reference_whirl_ratio": self.reference_whirl_ratio,
                "reference_whirl_source": self.reference_source,
                "foil_relaxation_time": self.relaxation_time,
                "foil_state": "Kelvin–Voigt, one W per "
                + ("θ row" if self.layout == "rows" else "node")}


def gauge_target(q: np.ndarray, tm) -> np.ndarray:
    """The static law's deflection at the gauge q (rows (B, m) or nodes (B, m, n_z + 1)):
    S q, S max(q, 0) for compression-only bumps, or the law's own (``law.gauge_target``, the
    hardening bump's W_h(q))."""
    own = getattr(tm.law, "gauge_target", None)
    if own is not None:
        return own(q, tm)
    s = tm.compliance_rows if q.ndim == 2 else tm.compliance_rows[:, None]
    return s * (np.maximum(q, 0.0) if tm.compression_only else q)


def check_reference_whirl(value) -> float:
    """ν_ref as a float; ParameterError unless finite and > 0."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError("reference_whirl_ratio", value, "must be a number") from None
    if not (math.isfinite(v) and v > 0):
        raise ParameterError("reference_whirl_ratio", value, "must be finite and > 0 (the "
                             "whirl ratio at which τ_f = η/ν_ref matches the hysteretic loss)")
    return v


def kelvin_voigt_foil(solution, law, rigid_film: np.ndarray,
                      reference_whirl_ratio: Optional[float] = None, solver=None,
                      threshold=None) -> Optional[KelvinVoigtFoil]:
    """The foil state of a transient model about ``solution``, or None without damping.

    law : the model's :class:`~gfbopt.physics.foil_laws.FoilLaw`; rigid_film : H_r (m,) at
    the equilibrium; reference_whirl_ratio : ν_ref [-] given by the user, or None for the
    default, the linear threshold whirl ratio of the damped model: from ``threshold`` (a
    :class:`gfbopt.linear.LinearThreshold` of ``solution`` already computed) or else from
    one linearisation (reusing ``solver``, the static solver of ``solution``).
    """
    eta = solution.model.loss_factor
    if eta <= 0.0:
        if reference_whirl_ratio is not None:
            raise ParameterError("reference_whirl_ratio", reference_whirl_ratio,
                                 "is used only with structural damping (loss_factor > 0)")
        return None
    if reference_whirl_ratio is not None:
        nu, source = check_reference_whirl(reference_whirl_ratio), "given"
    else:
        nu, source = threshold_whirl(solution, solver, threshold)
    deflection = solution.film - rigid_film[:, None]          # W per node of the equilibrium
    if law.damped_state == "rows":
        deflection = deflection[:, 0].copy()                  # uniform along each row
    return KelvinVoigtFoil(float(eta), nu, source, law.damped_state, deflection)


def threshold_whirl(solution, solver=None, threshold=None) -> tuple:
    """(ν_ref, source): the linear threshold whirl ratio of the damped (hysteretic) model
    (``threshold``, or computed), or :data:`FALLBACK_WHIRL` with the reason when the linear
    analysis finds no threshold (stable for every mass, or unstable already at M̄ → 0)."""
    if threshold is None:
        from ..linear import linear_threshold, linearise

        threshold = linear_threshold(linearise(solution, solver))
    gamma = threshold.whirl_ratio
    if not (math.isfinite(gamma) and gamma > 0):
        return FALLBACK_WHIRL, ("half-frequency whirl: the linear analysis found no threshold "
                                f"({threshold.message})")
    if math.isfinite(threshold.critical_mass) and threshold.critical_mass > 0:
        return float(gamma), "linear threshold"
    return float(gamma), f"whirl of the least-stable linear mode ({threshold.message})"


def foil_bound(p: np.ndarray, h: np.ndarray, tm) -> float:
    """Gershgorin bound on the foil rows of the Jacobian [1/rad of shaft rotation].

    Row of W (row i or node k): |∂W'/∂W| + Σ|∂W'/∂Φ| ≤ (1 + S (P + 1)/H)/τ_f, with P the
    row's largest pressure (axial-mean law: ∂q/∂W = −P̄/H, Σ ∂q/∂Φ ≤ 1/H).  With the bumps'
    friction, on rows with μ_f > 0: (1 + κ + S (1 + μ_f)(P + 1)/H)/τ_f (the stuck element's
    spring κ/S, the slipping one's ±μ_f q).  A hardening bump's tangent is below S.
    """
    foil = tm.foil_state
    top = p.max(axis=-1, keepdims=True) if foil.layout == "rows" else p
    s = tm.compliance_rows[:, None]                     # S per θ row (bump zones)
    fr = getattr(tm, "friction", None)
    if fr is not None:
        mu = fr.coefficient[:, None]
        rows = (1.0 + fr.stiffness_ratio * (mu > 0.0) + s * (1.0 + mu) * (top + 1.0) / h)
        return float((rows / foil.relaxation_time).max())
    return float(((1.0 + s * (top + 1.0) / h) / foil.relaxation_time).max())


def deflection_of_mode(deflection: np.ndarray, layout: str) -> np.ndarray:
    """A mode's δW per node (m, n_z + 1) in the layout of the foil state (rows: the mean
    over the row's unknown nodes, where the row's film is known; 0 on seam rows)."""
    if layout == "nodes":
        return deflection
    inner = deflection[:, 1:-1]
    return inner.mean(axis=1)
