"""The registry of foil laws: how the top foil deflects under the film pressure.

W is the top-foil deflection over the clearance, positive away from the journal, and
q = P̄ − 1 the axially averaged gauge pressure at each θ row (``docs/PHYSICS.md``, "Foil
models").  Each law is one object that owns everything the engines need from it:

* its static equations (written once, evaluated on CasADi symbols for the IPOPT model and on
  numpy arrays to re-check the solution): :meth:`FoilLaw.static_film`,
  :meth:`FoilLaw.deflection`, :meth:`FoilLaw.start`;
* its dynamic response for the linear analysis: :meth:`FoilLaw.squeeze_film_slope`
  (how the film at a node moves with the pressure there) and
  :meth:`FoilLaw.compliance_terms` (which entries of the linearised equations carry the
  foundation compliance S, so that the linear analysis can make the foundation stiffness
  complex, k → k (1 + iη sign γ), for the structural loss factor η: :class:`ComplianceTerms`);
* its transient recovery of P and H from Φ = P H and the journal position:
  :meth:`FoilLaw.transient_data`, :meth:`FoilLaw.recover`; with damping (η > 0) W is a state
  (:mod:`gfbopt.transient.foil_state`): :meth:`FoilLaw.recover_deflected`,
  :meth:`FoilLaw.deflection_target`, :attr:`FoilLaw.damped_state`;
* and which engines support it (:attr:`FoilLaw.engines`).

=========  =====================================================  ===========================
law        deflection                                             reference
=========  =====================================================  ===========================
rigid      W = 0 (plain gas bearing, or any S = 0)                —
simple     W = S q, q = P̄ − 1 (axial-mean law, Heshmat's strips)   Heshmat et al. (1983)
local      W = S (P − 1) at every node                            e.g. Peng & Carpino (1993)
beam       C d⁴W/dθ⁴ + W/S = q, Hermite elements                  thesis eq. (4.2), App. B
hardened   W = W_h(q), k = k0/(1 − δ/δ_lim)^n (axial-mean law)   :mod:`.hardening` (chosen)
=========  =====================================================  ===========================

``compression_only`` (bumps cannot pull the foil inward): W = S max(q, 0), S max(P − 1, 0), or
a bump reaction max(W, 0)/S.  Adding a law is one subclass here plus its tests.

References: H. Heshmat, J. A. Walowit, O. Pinkus, "Analysis of gas-lubricated foil journal
bearings", J. Lubr. Technol. 105(4) (1983) 647–655; J.-P. Peng, M. Carpino, "Calculation of
stiffness and damping coefficients for elastically supported gas foil bearings", J. Tribol.
115(1) (1993) 20–27.
"""
from __future__ import annotations

from typing import Optional

import casadi as ca
import numpy as np
import scipy.sparse as sp

from ..errors import ParameterError
from .algebra import is_symbolic
from .beam import BeamMatrices, beam_deflection, beam_dofs, beam_matrices, beam_residual
from .compliance import ComplianceTerms, active, embed
from .foil_law_base import (ENGINES, TRANSIENT_ENGINES, FoilLaw, FoilParameters,
                            simple_deflection)
from .hardening import hardened_foil_deflection, hardened_tangent_compliance
from .foil_recovery import (beam_film, node_compliance, row_mean_phi, rows_to_nodes,
                            set_boundary)

#: re-exported from :mod:`.foil_law_base` (the contract every law implements)
__all__ = ["BeamLaw", "ENGINES", "FOIL_LAWS", "FoilLaw", "FoilParameters", "LocalLaw", "RigidLaw",
           "HardenedLaw", "SimpleLaw", "TRANSIENT_ENGINES",
           "foil_law", "simple_deflection", "static_structure"]


class SimpleLaw(FoilLaw):
    """Simple elastic foundation, axial-mean law W = S (P̄ − 1) (Heshmat et al. 1983)."""

    name = "simple"
    description = "simple elastic foundation, W = S (P̄ − 1)"
    static_structure = "simple"
    engines = ("static", "linear", "rk4", "rkc", "bdf")
    loss_factor_engines = ("linear", "rk4", "rkc", "bdf")
    damped_state = "rows"
    #: rk4: the one-bearing transient with the sliders as a state beside it
    #: (:func:`gfbopt.transient.friction_orbit.integrate_friction_orbits`)
    friction_engines = ("static", "linear", "rk4", "rkc")

    def static_film(self, h_rigid, lifted, mean_gauge, p_full, u, foil, st, data):
        w_rows = simple_deflection(mean_gauge, foil.compliance, foil.compression_only)
        return rows_to_nodes(lifted, st), lifted - (h_rigid + w_rows), None

    def deflection(self, p_full, mean_gauge, u, foil, st, data):
        w = simple_deflection(mean_gauge, foil.compliance, foil.compression_only)
        return rows_to_nodes(w, st), 0.0

    def start(self, h_rigid, mean_gauge, foil, st, data):
        w = simple_deflection(mean_gauge, foil.compliance, foil.compression_only)
        return np.maximum(h_rigid + w, 1e-3), np.zeros(0)

    def compliance_terms(self, ctx):
        # Lifted film row i: H_i − H_r,i − S c_i Q_i/(2 L/D) = 0 (c_i = 1, or [q_i > 0] for
        # compression-only bumps), so ∂/∂Q_i = −S c_i/(2 L/D) ∝ S.  Nothing else carries S:
        # Reynolds sees the row film H_i, and the squeeze term the rate of H_i.
        values = (-ctx.rows() / (2.0 * ctx.length_ratio)
                  * active(ctx.mean_gauge, ctx.compression_only))
        a = sp.csc_matrix((values, (ctx.film_rows, ctx.axial_cols)), shape=(ctx.size, ctx.size))
        # foil units: one per θ row, δW_i = S c_i δQ_i/(2 L/D) (column Q_i)
        rows_s = np.broadcast_to(np.asarray(ctx.rows(), dtype=float), ctx.mean_gauge.shape)
        return ComplianceTerms(a, None, "compliance", unit_columns=np.asarray(ctx.axial_cols),
                               unit_gain=-values, unit_gauge=np.asarray(ctx.mean_gauge),
                               unit_compliance=np.array(rows_s))

    def recover(self, phi, hr, tm, guess=None, cache=None):
        # On each row H = a with a = H_r + S (P̄ − 1) and P = Φ/a, P̄ = Φ̃/a + c, so
        # a² − b a − S Φ̃ = 0 with b = H_r + S (c − 1): closed form.
        phit, c = row_mean_phi(phi, hr, tm)
        s = tm.compliance_rows                            # S per θ row (bump zones)
        b = hr + s * (c - 1.0)
        a = 0.5 * (b + np.sqrt(b * b + 4 * s * phit))
        if tm.compression_only:
            a = np.maximum(a, hr)
        p = set_boundary(phi / a[:, :, None], tm)
        return p, a[:, :, None]

    def recover_deflected(self, phi, hr, w, tm):
        a = hr + w                                        # W (B, m): one per θ row
        return set_boundary(phi / a[:, :, None], tm), a[:, :, None]

    def deflection_target(self, p, tm):
        q = (p @ tm.z_weight) / tm.z_weight.sum() - 1.0   # P̄ − 1 per row (B, m)
        q[:, tm.ambient] = 0.0                            # seam and pad-end rows: P = 1
        return tm.compliance_rows * (np.maximum(q, 0.0) if tm.compression_only else q)


class RigidLaw(SimpleLaw):
    """Rigid bearing surface, W = 0 (a plain self-acting gas bearing, or S = 0)."""

    name = "rigid"
    description = "rigid bearing surface, W = 0"
    static_structure = "simple"
    loss_factor_engines = ()
    damped_state = None
    friction_engines = ()

    def compliance_terms(self, ctx):
        return None

    def recover(self, phi, hr, tm, guess=None, cache=None):
        p = set_boundary(phi / hr[:, :, None], tm)
        return p, hr[:, :, None]


class LocalLaw(FoilLaw):
    """Simple foundation with the local law W = S (P − 1) at every node."""

    name = "local"
    description = "simple elastic foundation, local law W = S (P − 1)"
    static_structure = "local"
    engines = ("static", "linear", "rk4", "rkc")
    loss_factor_engines = ("linear", "rk4", "rkc")
    damped_state = "nodes"
    #: rk4: the one-bearing transient with a slider per node (gfbopt.transient.friction_foil)
    friction_engines = ("static", "linear", "rk4", "rkc")
    lifted_film_is_total = False

    def static_film(self, h_rigid, lifted, mean_gauge, p_full, u, foil, st, data):
        w = simple_deflection(p_full - 1, node_compliance(foil.compliance, st),
                              foil.compression_only)
        return rows_to_nodes(lifted, st) + w, lifted - h_rigid, None

    def deflection(self, p_full, mean_gauge, u, foil, st, data):
        return simple_deflection(p_full - 1, node_compliance(foil.compliance, st),
                                 foil.compression_only), 0.0

    def start(self, h_rigid, mean_gauge, foil, st, data):
        return h_rigid, np.zeros(0)

    def squeeze_film_slope(self, pressure, compliance, compression_only):
        slope = np.ones(pressure.size) if not compression_only else (pressure > 1).astype(float)
        return compliance * slope

    def compliance_terms(self, ctx):
        # The film at unknown node k is H_k = H_r,row + S c_k (P_k − 1), so the Reynolds rows'
        # derivative in P_k is ∂R/∂P|_H + (∂R/∂H_k) S c_k: the second part ∝ S.  The squeeze
        # term −2Λ (H Ṗ + P Ḣ) carries −2Λ P_k S c_k Ṗ_k (∝ S) on the diagonal.
        n_p = ctx.pressure.size
        slope = self.squeeze_film_slope(ctx.pressure, ctx.nodes(), ctx.compression_only)
        rows = np.arange(n_p)
        a = embed(ctx.film_sensitivity() @ sp.diags(slope), rows, rows, ctx.size)
        b = embed(sp.diags(-2.0 * ctx.bearing_number * ctx.pressure * slope), rows, rows,
                   ctx.size)
        # foil units: one per unknown node, δW_k = S c_k δP_k (column P_k)
        nodes_s = np.broadcast_to(np.asarray(ctx.nodes(), dtype=float), ctx.pressure.shape)
        return ComplianceTerms(a, b, "compliance", unit_columns=rows, unit_gain=slope,
                               unit_gauge=ctx.pressure - 1.0, unit_compliance=np.array(nodes_s))

    def recover(self, phi, hr, tm, guess=None, cache=None):
        # S P² + (H_r − S) P − Φ = 0 per node: closed form.
        s = tm.compliance_rows[:, None]                   # S per θ row (bump zones)
        hr3 = hr[:, :, None]
        p = (-(hr3 - s) + np.sqrt((hr3 - s) ** 2 + 4 * s * phi)) / (2 * s)
        if tm.compression_only:   # W = S max(P − 1, 0): where P < 1 the film is rigid
            p = np.where(p < 1.0, phi / hr3, p)
        p = set_boundary(p, tm)
        h = hr3 + (s * (p - 1.0) if not tm.compression_only else s * np.maximum(p - 1.0, 0))
        return p, h

    def recover_deflected(self, phi, hr, w, tm):
        h = hr[:, :, None] + w                            # W (B, m, n_z + 1): one per node
        return set_boundary(phi / h, tm), h

    def deflection_target(self, p, tm):
        q = p - 1.0                                       # 0 on boundary nodes (P = 1)
        return tm.compliance_rows[:, None] * (np.maximum(q, 0.0) if tm.compression_only else q)


class BeamLaw(FoilLaw):
    """Euler–Bernoulli top foil on the bump foundation (:mod:`gfbopt.physics.beam`)."""

    name = "beam"
    description = "Euler–Bernoulli top foil on the bumps, C d⁴W/dθ⁴ + W/S = P̄ − 1"
    static_structure = "beam"
    engines = ("static", "linear", "rk4", "rkc")
    loss_factor_engines = ("linear",)
    damped_transient_refusal = (      # ≈ 1.6e9 per radian at 144 × 36, S = C = 1, τ_f = 0.6
        "a Kelvin–Voigt foundation under the massless beam is stiff, rates S C λ/τ_f with "
        "λ ≈ 3585/Δθ⁴ the largest bending eigenvalue, against ≈ 1.6e3 for the film")

    def extra_unknowns(self, grid) -> int:
        return 2 * grid.n_theta

    def prepare(self, grid, dpsi: float) -> BeamMatrices:
        return beam_matrices(grid.n_theta, dpsi)

    @staticmethod
    def _beam_load(mean_gauge, st):
        """q at the n + 1 beam nodes, welded end first (a periodic film's free end sees
        row 0's load)."""
        if not st.periodic:
            return mean_gauge
        if is_symbolic(mean_gauge):
            return ca.vertcat(mean_gauge, mean_gauge[0])
        return np.append(mean_gauge, mean_gauge[0])

    def static_film(self, h_rigid, lifted, mean_gauge, p_full, u, foil, st, data):
        w_rows = ca.vertcat(0, u[0::2])[:st.n_theta_nodes]
        residual = beam_residual(u, self._beam_load(mean_gauge, st), data, foil.compliance,
                                 foil.coefficient, foil.compression_only)
        return rows_to_nodes(lifted, st), lifted - (h_rigid + w_rows), residual

    def deflection(self, p_full, mean_gauge, u, foil, st, data):
        w_beam = np.concatenate([[0.0], u[0::2]])
        res = beam_residual(u, self._beam_load(mean_gauge, st), data, foil.compliance,
                            foil.coefficient, foil.compression_only)
        return rows_to_nodes(w_beam[:st.n_theta_nodes], st), float(np.abs(res).max())

    def start(self, h_rigid, mean_gauge, foil, st, data):
        u = beam_dofs(self._beam_load(mean_gauge, st), data, foil.compliance, foil.coefficient)
        w = np.concatenate([[0.0], u[0::2]])
        return np.maximum(h_rigid + w[:st.n_theta_nodes], 1e-3), u

    def compliance_terms(self, ctx):
        # Beam rows, multiplied by S: S C K_b u + M r(u) − S G q = 0.  Divided by S the
        # foundation term is M r(u)/S, the bump stiffness; a complex stiffness k/S gives
        # S C K_b u + k M r(u) − S G q (the row scale leaves the solution unchanged).  So the
        # entries M ∂r/∂u ∝ 1/S scale with the stiffness; ∂r/∂u = 1, or [W_k > 0] on both
        # dofs of node k for compression-only bumps.
        w = ctx.beam_dofs[0::2]
        acting = np.repeat(active(w, ctx.compression_only), 2)
        block = ctx.law_data.foundation @ sp.diags(acting)
        return ComplianceTerms(embed(block, ctx.beam, ctx.beam, ctx.size), None, "stiffness")

    def transient_data(self, model, grid, periodic, dtheta):
        if model.compression_only:
            raise ParameterError("compression_only", True, "is not available in the transient "
                                 "beam model (use the simple model for bumps that let go)")
        n = grid.n_theta
        mats = beam_matrices(n, dtheta)
        # W at beam nodes 0..n per unit load at each node (columns): the static beam law
        w = beam_deflection(np.eye(n + 1), mats, model.compliance, model.top_foil_coefficient)
        if periodic:       # film rows 0..n−1; the free end (node n) sees row 0's load
            w = w[:n]
            w[:, 0] += w[:, n]
            return w[:, :n]
        return w

    def recover(self, phi, hr, tm, guess=None, cache=None):
        phit, c = row_mean_phi(phi, hr, tm)
        a = beam_film(hr, phit, c, tm, guess, cache)
        p = set_boundary(phi / a[:, :, None], tm)
        return p, a[:, :, None]


class HardenedLaw(SimpleLaw):
    """The axial-mean foundation with hardening bumps, W = W_h(P̄ − 1): the stiffness
    k0/(1 − δ/δ_lim)^n rises as the bump flattens, the bump height the hard limit
    (:func:`gfbopt.physics.hardening.hardened_foil_deflection`).  Statics use the hardened
    law; the linear analysis its tangent at the static deflection.  Its own static structure
    (the 'simple' build, today's, is untouched); needs the build to pass (n, W_lim) in
    :attr:`FoilParameters.hardening`."""

    name = "hardened"
    description = "hardening bumps, W = W_h(P̄ − 1), k = k0/(1 − δ/δ_lim)^n"
    static_structure = "hardened"
    engines = ("static", "linear")
    loss_factor_engines = ("linear",)
    damped_state = None
    friction_engines = ("static", "linear")
    damped_transient_refusal = "no transient recovery of the hardening bump yet"

    @staticmethod
    def _w(q, foil):
        if foil.hardening is None:
            raise ParameterError("hardening_exponent", "on", "the static build does not pass "
                                 "the hardening bump's parameters (gfbopt.static.model "
                                 "PARAMETERS); use hardening_exponent = 0")
        n, limit = foil.hardening
        return hardened_foil_deflection(q, foil.compliance, n, limit, foil.compression_only)

    def static_film(self, h_rigid, lifted, mean_gauge, p_full, u, foil, st, data):
        return rows_to_nodes(lifted, st), lifted - (h_rigid + self._w(mean_gauge, foil)), None

    def deflection(self, p_full, mean_gauge, u, foil, st, data):
        return rows_to_nodes(self._w(mean_gauge, foil), st), 0.0

    def start(self, h_rigid, mean_gauge, foil, st, data):
        return np.maximum(h_rigid + self._w(mean_gauge, foil), 1e-3), np.zeros(0)

    def compliance_terms(self, ctx):
        # as the simple law's, with the tangent compliance dW/dq at the static deflection
        n, limit = ctx.hardening
        s0 = np.broadcast_to(np.asarray(ctx.rows(), dtype=float), ctx.mean_gauge.shape)
        tangent = hardened_tangent_compliance(ctx.mean_gauge, s0, n, limit,
                                              ctx.compression_only)
        values = -tangent / (2.0 * ctx.length_ratio)
        a = sp.csc_matrix((values, (ctx.film_rows, ctx.axial_cols)), shape=(ctx.size, ctx.size))
        with np.errstate(divide="ignore", invalid="ignore"):
            softening = np.where(s0 > 0, tangent / np.where(s0 > 0, s0, 1.0), 1.0)
        return ComplianceTerms(a, None, "compliance", unit_columns=np.asarray(ctx.axial_cols),
                               unit_gain=-values, unit_gauge=np.asarray(ctx.mean_gauge),
                               unit_compliance=np.array(s0), unit_softening=softening)

    def recover(self, phi, hr, tm, guess=None, cache=None):
        raise ParameterError("hardening_exponent", "on", "the transient engines do not model "
                             "the hardening bump yet")


#: The registry: law name → law.
FOIL_LAWS: dict[str, FoilLaw] = {law.name: law for law in (RigidLaw(), SimpleLaw(), LocalLaw(),
                                                           BeamLaw(), HardenedLaw())}


def foil_law(model, engine: Optional[str] = None) -> FoilLaw:
    """The foil law of a :class:`~gfbopt.inputs.model.BearingModel` (``model.foil_law``).

    A model with Coulomb friction (μ_f > 0) is handed only to an engine in
    :attr:`FoilLaw.friction_engines`.  A model with structural damping (η > 0) is handed only
    to an engine that names itself and models η (:attr:`FoilLaw.loss_factor_engines`): no
    engine ignores it silently.
    ``engine='transient'``: the model all integrators share (each checks its own name again,
    :meth:`FoilLaw.check_engine`), handed on when one of them models η for the law.
    """
    law = FOIL_LAWS[model.foil_law]
    mu = getattr(model, "friction_coefficient", 0.0)
    if getattr(model, "has_friction", mu > 0.0) and engine not in law.friction_engines:
        who = ("the transient engines" if engine == "transient" else
               f"the {engine} engine" if engine else "an unnamed engine")
        raise ParameterError("friction_coefficient", mu, "Coulomb friction of the bumps is "
                             f"modelled for the {law.name} foil law by "
                             f"{', '.join(law.friction_engines) or 'no engine'} only, not by "
                             f"{who} (the one-bearing transient carries the sliders with rk4 "
                             "or rkc: gfbopt orbit, or transient_model(..., friction=True) "
                             "with gfbopt.transient.integrate_orbits); use "
                             "friction_coefficient = 0")
    eta = getattr(model, "loss_factor", 0.0)
    if eta <= 0.0:
        return law
    if engine == "transient":
        if set(TRANSIENT_ENGINES) & set(law.loss_factor_engines):
            return law
        raise ParameterError("loss_factor", eta, "structural damping of the bumps is not "
                             f"modelled by the transient engines for the {law.name} foil law "
                             f"({law.damped_transient_refusal or 'no Kelvin–Voigt state'}); "
                             "the linear analysis models it, or use loss_factor = 0")
    if engine not in law.loss_factor_engines:
        who = f"the {engine} engine" if engine else "an unnamed engine"
        raise ParameterError("loss_factor", eta, "structural damping of the bumps is modelled "
                             f"for the {law.name} foil law by "
                             f"{', '.join(law.loss_factor_engines)} only, not by {who}")
    return law


def static_structure(model) -> str:
    """Name of the law whose static CasADi model serves ``model``.

    The simple foundation with S = 0 is the rigid bearing, so rigid models share it; a model
    that asks for the local law or the beam keeps that structure even at S = 0 (S is a
    parameter of the build).
    """
    if model.foil == "beam":
        return "beam"
    if model.foil == "simple" and model.deflection_law == "local":
        return "local"
    if getattr(model, "hardening_exponent", 0.0) > 0.0:
        return "hardened"
    return "simple"
