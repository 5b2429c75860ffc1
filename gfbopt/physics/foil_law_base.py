"""The base of the foil-law registry (:mod:`gfbopt.physics.foil_laws`): the contract every law
implements (:class:`FoilLaw`), the foil's groups as the static equations see them
(:class:`FoilParameters`) and the simple foundation's deflection (:func:`simple_deflection`).

Kept apart from the laws themselves so that the registry stays short; import these names from
:mod:`gfbopt.physics.foil_laws`, which re-exports them.
"""
from __future__ import annotations

import abc
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import ParameterError
from .algebra import positive_part
from .compliance import ComplianceTerms, PerturbationContext

#: Engines a law may support: the CasADi/IPOPT equilibrium, the linearisation, and the
#: transient integrators.
ENGINES = ("static", "linear", "rk4", "rkc", "bdf")
#: The transient integrators among them.
TRANSIENT_ENGINES = ("rk4", "rkc", "bdf")


@dataclass(frozen=True)
class FoilParameters:
    """The foil's groups as the static equations see them (numbers or CasADi symbols).

    compliance S [-], coefficient C [-] (beam only), compression_only 0/1; hardening: the
    hardening bump's (exponent n, limit W_lim = δ_lim/c) for the 'hardened' law
    (:mod:`gfbopt.physics.hardening`), None when the build does not pass them.
    """

    compliance: object
    coefficient: object
    compression_only: object
    hardening: object = None


def simple_deflection(q, compliance, compression_only):
    """W = S q, or S max(q, 0) when ``compression_only`` is 1 [-].

    q : gauge pressure (P̄ − 1 per row, or P − 1 per node) [-]; compliance S [-];
    compression_only 0 or 1 (may be a CasADi parameter, so the choice is arithmetic).
    """
    return compliance * ((1 - compression_only) * q + compression_only * positive_part(q))


class FoilLaw(abc.ABC):
    """Base class: one foil law (see the module docstring for the contract)."""

    #: registry name
    name: str = ""
    #: one line for reports
    description: str = ""
    #: the law whose static model serves this one (the rigid bearing is the simple
    #: foundation with S = 0, so it needs no model of its own)
    static_structure: str = ""
    #: engines that support the law (subset of ENGINES)
    engines: tuple = ()
    #: True when the lifted film variable of the static model is the whole film H (> 0
    #: bound); False when it is only the rigid part (the local law adds W per node)
    lifted_film_is_total: bool = True
    #: engines that model the structural loss factor η (others are refused a damped model,
    #: :func:`foil_law`): linear (hysteretic), transient (Kelvin–Voigt state, docs/PHYSICS.md §7)
    loss_factor_engines: tuple = ()
    #: the transient's Kelvin–Voigt state: one W per θ 'rows', per 'nodes', or None
    damped_state: Optional[str] = None
    #: why the transient engines do not model η for this law, if they do not
    damped_transient_refusal: str = ""
    #: engines that model the bumps' Coulomb friction (``BearingModel.friction_coefficient``,
    #: a spring–slider element beside each bump, :mod:`gfbopt.physics.friction`): the static
    #: equilibrium (friction holds no static deflection, so it is today's) and the linear
    #: analysis (stuck stiffness for small orbits; the describing function at a stated
    #: amplitude).  Others are refused a model with friction by :func:`foil_law`.
    friction_engines: tuple = ()

    # ------------------------------------------------------------------ static model
    def extra_unknowns(self, grid) -> int:
        """Number of foil unknowns beside the film (e.g. the beam's Hermite dofs)."""
        return 0

    def prepare(self, grid, dpsi: float):
        """Grid-dependent data the law needs (e.g. beam matrices), or None."""
        return None

    @abc.abstractmethod
    def static_film(self, h_rigid, lifted, mean_gauge, p_full, u, foil: FoilParameters, st,
                    data) -> tuple:
        """(H at every node, lifted-film equations per row, extra foil equations or None).

        h_rigid : H_r per row; lifted : the lifted film per row; mean_gauge : P̄ − 1 per row;
        p_full : P at every node (flat); u : extra unknowns; st : the grid's Stencil.
        Numbers or CasADi symbols.
        """

    @abc.abstractmethod
    def deflection(self, p_full, mean_gauge, u, foil: FoilParameters, st, data) -> tuple:
        """(W at every node (flat), max |foil equation residual|) from a solved state (numpy)."""

    @abc.abstractmethod
    def start(self, h_rigid, mean_gauge, foil: FoilParameters, st, data) -> tuple:
        """(lifted film per row, extra unknowns) consistent with a guessed pressure (numpy)."""

    # ------------------------------------------------------------------ linear model
    def squeeze_film_slope(self, pressure: np.ndarray, compliance: float,
                           compression_only: bool) -> Optional[np.ndarray]:
        """∂H/∂P at the unknown nodes where the film follows the local pressure, else None.

        The squeeze term −2Λ ∂(PH)/∂τ then carries −2Λ P (∂H/∂P) Ṗ besides −2Λ H Ṗ.
        """
        return None

    def compliance_terms(self, ctx: PerturbationContext) -> Optional[ComplianceTerms]:
        """The entries of the linearised equations that carry the foundation compliance S
        (:class:`ComplianceTerms`), or None when the law has no foundation (rigid).

        This is the foil's dynamic compliance in the linearisation: the linear analysis
        replaces S by S/(1 + iη sign γ) in exactly these entries.
        """
        return None

    # --------------------------------------------------------------- transient model
    def transient_data(self, model, grid, periodic: bool, dtheta: float):
        """Precomputed data of the transient recovery (e.g. the beam's compliance map)."""
        return None

    @abc.abstractmethod
    def recover(self, phi: np.ndarray, hr: np.ndarray, tm, guess=None, cache=None) -> tuple:
        """(P, H) of a batch from Φ = P H (B, m, n_z + 1) and the rigid film H_r (B, m).

        H has shape (B, m, n_z + 1) when it varies along Z, else (B, m, 1).
        """

    def recover_deflected(self, phi: np.ndarray, hr: np.ndarray, w: np.ndarray, tm) -> tuple:
        """(P, H) from Φ (B, m, n_z + 1), H_r (B, m) and the damped transient's state W:
        H = H_r + W, P = Φ/H (no foil equation to solve)."""
        raise ParameterError("loss_factor", self.name, "this foil law has no damped transient")

    def deflection_target(self, p: np.ndarray, tm) -> np.ndarray:
        """S q, or S max(q, 0) (compression only), in the :attr:`damped_state` layout [-]."""
        raise ParameterError("loss_factor", self.name, "this foil law has no damped transient")

    def check_engine(self, engine: str, damped: bool = False) -> None:
        """Refuse an engine the law does not support, or does not support with structural
        damping when ``damped`` (one line naming both)."""
        name = "method" if engine in TRANSIENT_ENGINES else "engine"
        if engine not in self.engines:
            raise ParameterError(name, engine, f"does not support the {self.name} foil law "
                                 f"({self.description}); supported: {', '.join(self.engines)}")
        if damped and engine not in self.loss_factor_engines:
            raise ParameterError(name, engine, "does not model structural damping (η > 0) of "
                                 f"the {self.name} foil law; supported: "
                                 f"{', '.join(self.loss_factor_engines)}")
