"""Linearised dynamics: frequency-dependent stiffness and damping, and the linear threshold.

Small harmonic journal motion ξ = (δX, δY) e^{sτ} about a static equilibrium (s = iγ for a
whirl at γ times the shaft speed).  The semi-discrete equations of the static model
(:mod:`gfbopt.static`) with the squeeze term of the time-dependent Reynolds equation,

    E(y, ξ) − 2Λ ∂(P H)/∂τ = 0       at the unknown pressure nodes,
    the lifted algebraic equations    (film, axial integrals, beam, force sums),

are linearised about the static state y0: (A + s B) ŷ = −C_ξ ξ, where A = ∂E/∂y (IPOPT's own
Jacobian of the static problem), B = ∂(−2Λ ∂(PH)/∂τ)/∂ẏ and C_ξ = ∂E/∂ξ.  The foil enters
through the algebraic rows, so it responds quasi-statically through its compliance (simple,
local or beam law).  The film-force perturbation is ΔF = f·ŷ and the impedance

    Z(s) = −ΔF/ξ = f (A + s B)⁻¹ C_ξ,        Z(iγ) = K(γ) + iγ C(γ)

gives the non-dimensional stiffness K̄ = K c/(p_a R²) and damping C̄ = C c ω/(p_a R²) in the
load frame (X along the static load, Y ahead of it in the direction of rotation).

Rigid rotor (mass M per bearing, M̄ = M c ω²/W0): M̄ W̄0 ξ'' = ΔF, i.e.
det(M̄ W̄0 s² I + Z(s)) = 0.  At the threshold s = iγ: with u = M̄ W̄0 γ², u² − u tr Z + det Z = 0
must have a real positive root u; M̄_crit = u/(γ² W̄0).

A seam that follows the maximum-film line in the static solution (``seam_angle=None``) is frozen
at its static position for the perturbation: the top foil is fixed in the housing.

Structural damping of the bumps (``BearingModel.loss_factor`` η, docs/PHYSICS.md §7).  The
foundation stiffness is hysteretic, k → k (1 + iη sign γ): the compliance S becomes
S/(1 + iη sign γ) in the perturbation only (the equilibrium does not depend on η).  Each foil
law names the entries of (A, B) that carry S (:meth:`FoilLaw.compliance_terms`), and only those
are scaled.  The hysteretic model is not analytic in s: for complex s every function here uses
sign γ = sign(Im s) (forward and backward whirl are damped alike; s on the real axis gets the
undamped foundation, the zero-frequency limit).  Along the imaginary axis this is the standard
hysteretic impedance, so the threshold (s = iγ) is exact; growth rates off the axis use the
damping of the nearest whirl frequency, which is the usual reading of a constant loss factor.
At η = 0 nothing is scaled and every result is the undamped one, bit for bit.

=====================  ====================================================================
module                 contents
=====================  ====================================================================
:mod:`.model`          :class:`Linearisation`, :func:`linearise`, :func:`impedance`,
                       :func:`coefficients` (K̄, C̄ against γ), :func:`dimensional_coefficients`
:mod:`.threshold`      :func:`linear_threshold`, :func:`characteristic_root`,
                       :func:`semi_discrete_eigenvalues`
:mod:`.least_stable`   :func:`least_stable_mode`: the least-damped rigid-body root
:mod:`.crossings`      the threshold's search for real roots u(γ): the reference scan and the
                       fast search on the Krylov model, checked on the exact impedance
:mod:`.krylov`         :class:`~.krylov.ShiftedImpedance`: Z(iγ) on a whirl-ratio interval
                       from one sparse LU (shift-invariant block Krylov space)
=====================  ====================================================================
"""
from .model import (Coefficients, Linearisation, coefficients, dimensional_coefficients,
                    film_sensitivity, impedance, linearise)
from .threshold import (PROBE_MASS, STABILITY_TOLERANCE, LinearThreshold, characteristic_root,
                        linear_threshold, semi_discrete_eigenvalues)
from .least_stable import least_stable_mode

__all__ = ["Coefficients", "LinearThreshold", "Linearisation", "PROBE_MASS",
           "STABILITY_TOLERANCE", "characteristic_root", "coefficients",
           "dimensional_coefficients", "film_sensitivity", "impedance", "least_stable_mode",
           "linear_threshold", "linearise", "semi_discrete_eigenvalues"]
