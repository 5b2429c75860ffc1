"""Dry friction in a bump: the spring–slider (Jenkins) element.

A spring of stiffness k in series with a Coulomb slider of slip force F_s.  The bump keeps its
own elastic stiffness; this element acts beside it (in parallel), so with F_s = 0 (or k = 0)
the foundation is today's elastic one and with the slider stuck the stiffness is the bump's
plus k (``docs/PHYSICS.md`` §7a; the spring–slider element of Iwan, W. D. (1966), J. Appl.
Mech. 33(4):893–900).

State: the slider position z.  Under a displacement x the spring carries f = k (x − z) and
|f| ≤ F_s; the slider moves only when the spring would carry more, so

    z_new = min(max(z, x − x_s), x + x_s),      x_s = F_s/k           (the play operator)

is the exact stick/slip update for any displacement path that is monotone between the two
samples (no regularisation: it is the rate-independent element itself, a return mapping).
Sampling a harmonic motion with its two turning points among the samples makes every step
monotone, so a cycle computed with it is exact at the samples.

Describing function (harmonic motion x = X cos τ, β = x_s/X).  Stuck (β ≥ 1): f = k x, no
dissipation.  Slipping (β < 1): energy dissipated per cycle E = 4 F_s (X − x_s); in-phase
(equivalent) stiffness k_eq = (k/π)(ψ − ½ sin 2ψ), ψ = arccos(1 − 2β); quadrature part
E/(π X²) = (4k/π) β (1 − β), i.e. the first harmonic of the force is
f₁ = X (k_eq cos τ + q sin τ) with q = E/(π X²): a rate-independent (hysteretic) stiffness
k_eq + i q sign(ω), like a loss factor whose size depends on the amplitude.

References: the Jenkins (elastic–perfectly-plastic, "spring–slider") element, G. M. Jenkins,
"Analysis of the stress–strain relationships in reactor grade graphite", Br. J. Appl. Phys.
13 (1962) 30–32; its describing function e.g. in W. D. Iwan, "The dynamic response of
bilinear hysteretic systems", Proc. ASCE J. Eng. Mech. (1965); in foil bearings the bump with
frictional contacts at its feet and top: D. Le Lez, M. Arghir, J. Frêne, "A new bump-type foil
bearing structure analytical model", ASME J. Eng. Gas Turbines Power 129(4) (2007) 1047–1057,
and "Nonlinear numerical prediction of gas foil bearing stability and unbalanced response",
ibid. 131 (2009) 012503 (their link model: springs and Coulomb friction at the bump contacts).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..inputs.checks import check_nonnegative, check_positive

__all__ = ["JenkinsElement", "CycleResult", "describing_function", "dissipated_energy",
           "equivalent_stiffness", "harmonic_cycle", "quadrature_stiffness", "slider_update"]


def slider_update(z, x, slip_displacement):
    """The slider position after the element moves to x (the play operator) [m or -].

    z : slider position before; x : element displacement now; slip_displacement x_s = F_s/k
    (≥ 0).  Exact for a path monotone between the two samples.  Works elementwise on arrays.
    """
    return np.minimum(np.maximum(z, x - slip_displacement), x + slip_displacement)


def _ratio(slip_displacement, amplitude):
    """β = x_s/X (arrays), +inf where X = 0 (no motion: stuck)."""
    xs = np.asarray(slip_displacement, dtype=float)
    x = np.abs(np.asarray(amplitude, dtype=float))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(x > 0, xs / np.where(x > 0, x, 1.0), np.inf)


def equivalent_stiffness(stiffness, slip_displacement, amplitude):
    """k_eq: the in-phase first harmonic of the force over X [N/m or -] (arrays).

    k when stuck (β ≥ 1), (k/π)(ψ − ½ sin 2ψ) with ψ = arccos(1 − 2β) otherwise.
    """
    beta = _ratio(slip_displacement, amplitude)
    b = np.clip(beta, 0.0, 1.0)
    psi = np.arccos(1.0 - 2.0 * b)
    return np.asarray(stiffness) * np.where(beta >= 1.0, 1.0,
                                            (psi - 0.5 * np.sin(2.0 * psi)) / math.pi)


def quadrature_stiffness(stiffness, slip_displacement, amplitude):
    """q = E/(π X²) = (4k/π) β (1 − β): the quadrature part (0 when stuck) [N/m or -]."""
    beta = _ratio(slip_displacement, amplitude)
    b = np.clip(beta, 0.0, 1.0)
    return np.asarray(stiffness) * 4.0 / math.pi * b * (1.0 - b)


def dissipated_energy(slip_force, stiffness, amplitude):
    """E = 4 F_s (X − x_s) per cycle when slipping (X > x_s), 0 when stuck [J or -]."""
    xs = slip_force / stiffness
    return 4.0 * slip_force * max(abs(amplitude) - xs, 0.0)


def describing_function(stiffness, slip_displacement, amplitude, sign=1.0):
    """k_eq + i q sign(ω): the element's complex stiffness at amplitude X (arrays).

    sign : sign of the whirl frequency (the quadrature part is rate independent, like a loss
    factor: backward whirl sees −q).
    """
    return (equivalent_stiffness(stiffness, slip_displacement, amplitude)
            + 1j * float(np.sign(sign)) * quadrature_stiffness(stiffness, slip_displacement,
                                                               amplitude))


@dataclass(frozen=True)
class JenkinsElement:
    """One spring–slider element: stiffness k [N/m] (> 0), slip force F_s [N] (≥ 0)."""

    stiffness: float
    slip_force: float

    def __post_init__(self):
        object.__setattr__(self, "stiffness", check_positive("stiffness", self.stiffness))
        object.__setattr__(self, "slip_force", check_nonnegative("slip_force", self.slip_force))

    @property
    def slip_displacement(self) -> float:
        """x_s = F_s/k [m]: the stretch of the spring when the slider slips."""
        return self.slip_force / self.stiffness

    def force(self, x, z):
        """f = k (x − z) [N] for slider position z (already updated to x)."""
        return self.stiffness * (np.asarray(x) - np.asarray(z))

    def step(self, z, x):
        """(new slider position, force) after the displacement moves to x."""
        z_new = slider_update(z, x, self.slip_displacement)
        return z_new, self.force(x, z_new)


@dataclass(frozen=True)
class CycleResult:
    """One steady cycle of prescribed motion x = X cos τ, integrated numerically.

    energy : ∮ f dx per cycle [J]; stiffness : a₁/X (in phase) [N/m]; quadrature : −b₁/X
    [N/m], with a₁, b₁ the cos τ and sin τ Fourier coefficients of the force; samples : steps.
    """

    energy: float
    stiffness: float
    quadrature: float
    samples: int


#: Gauss–Legendre points per step of :func:`harmonic_cycle`
_GAUSS = np.polynomial.legendre.leggauss(6)


def harmonic_cycle(element: JenkinsElement, amplitude: float,
                   samples: int = 2000) -> CycleResult:
    """Time-step the element through x = X cos τ and integrate its force over one cycle.

    The slider starts where the steady cycle has it at τ = 0 (x = X, the spring stretched by
    +x_s when slipping): one warm-up cycle from z = 0 reaches it exactly after the first turning
    point, and the second cycle is integrated.  ``samples`` steps per cycle (even, so that both
    turning points τ = 0, π are samples and each step is monotone); the force inside each step
    comes from :func:`slider_update` applied from the step's start state at 6 Gauss points, so
    the quadrature is exact except in the one step where the slider starts to slip (a kink):
    error O(Δτ³).  Energy: ∮ f dx = −∫ f X sin τ dτ.
    """
    if samples < 4 or samples % 2:
        raise ParameterError("samples", samples, "must be an even whole number >= 4 (both "
                             "turning points of the cycle are samples)")
    amp = check_nonnegative("amplitude", amplitude)
    xs = element.slip_displacement
    tau = np.linspace(0.0, 2.0 * math.pi, samples + 1)
    z = 0.0
    for t in tau[1:]:                         # warm-up cycle: reach the steady cycle
        z = float(slider_update(z, amp * math.cos(t), xs))
    points, weights = _GAUSS
    a1 = b1 = 0.0
    for ta, tb in zip(tau[:-1], tau[1:]):
        tg = 0.5 * (tb - ta) * points + 0.5 * (ta + tb)
        wg = 0.5 * (tb - ta) * weights
        xg = amp * np.cos(tg)
        zg = slider_update(z, xg, xs)         # monotone step: exact from the start state
        fg = element.force(xg, zg)
        a1 += float(np.sum(wg * fg * np.cos(tg)))
        b1 += float(np.sum(wg * fg * np.sin(tg)))
        z = float(slider_update(z, amp * math.cos(tb), xs))
    a1 /= math.pi
    b1 /= math.pi
    energy = -math.pi * amp * b1              # ∮ f dx = −X ∫ f sin τ dτ = −π X b₁
    if amp == 0.0:
        return CycleResult(0.0, element.stiffness, 0.0, samples)
    return CycleResult(energy, a1 / amp, -b1 / amp, samples)
