"""The symbolic equilibrium problem: lifted equations in SX, Reynolds by θ-strips in MX.

Unknowns (``x``): P at interior nodes; lifted per-θ-row H (or its rigid part for the local
law), Q_i = ∫(P − 1) dZ and the force integrand Q^F_i; the beam's free Hermite dofs; force
partial sums; ε and φ.  Lifting the axial integrals and the film geometry keeps the Jacobian
sparse (docs/PHYSICS.md).  Equations (``g``), in this order: Reynolds at the unknown nodes, the
lifting definitions, the beam equations, the partial sums and two closing equations
``mode·(F_X + W̄) + (1 − mode)(ε − ε_given) = 0`` and ``F_Y = 0``.  The equation that defines
a lifted variable sits at that variable's index (the linearisation relies on it).

How it is built (the build cost is what this layout is for)
-----------------------------------------------------------
* Everything except Reynolds is O(n_θ n_z) scalar SX (the film law, the axial integrals, the
  force sums), differentiated by CasADi block by block (one colouring per equation group).
* Reynolds is :func:`gfbopt.discretisation.reynolds_residual` itself, evaluated on a
  *three-row patch* (one θ-row of unknown nodes with its two neighbour rows).  That patch
  function and its sparse Jacobian are small SX functions, mapped over the θ-rows (``map``),
  so the symbolic graph does not grow with the grid: the grid enters only through index
  arrays.  The global Reynolds Jacobian is the chain rule
  ``∂R/∂x = (∂R/∂(P, H) at the nodes) · ∂(P, H)/∂x``, a sparse product.
* The NLP is an MX graph over these functions; IPOPT receives the Jacobian function (no AD
  of the global graph) and an empty Hessian of the Lagrangian (square system: the Newton
  step is fixed by the constraints).

The residual g is bitwise the one of a flat SX build (same arithmetic per node); Jacobian
entries agree with CasADi's own AD to round-off (tests/verification/test_static_build.py).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import casadi as ca
import numpy as np

from .. import discretisation as disc
from ..physics.film import force_gauge, rigid_film_polar
from ..physics.foil_laws import FoilLaw, FoilParameters

#: Names of the scalar entries of the parameter vector ``p`` (see
#: :meth:`StaticSolver.parameters`); after them come two vectors of one value per θ row:
#: the bore's clearance change B_i = Δc/c and the foundation compliance S_i (the bearing as
#: built, :mod:`gfbopt.inputs.bore`), so a preload or a zone change needs no rebuild.
PARAMETERS = ("bearing_number", "compliance", "top_foil_coefficient", "length_ratio",
              "load_mode", "target", "seam_angle", "seam_follows", "compression_only", "gumbel",
              "position_mode", "attitude_target", "hardening_exponent", "hardening_limit")
#: Names of the per-θ-row parameter vectors, in order after :data:`PARAMETERS`.
ROW_PARAMETERS = ("bore", "row_compliance")


def n_parameters(st: disc.Stencil) -> int:
    """Length of the parameter vector of a build on stencil ``st``."""
    return len(PARAMETERS) + len(ROW_PARAMETERS) * st.n_theta_nodes


@dataclass(frozen=True)
class Layout:
    """Where each block of unknowns sits in the solver's vector ``x`` (slices)."""

    pressure: slice
    film: slice
    axial: slice
    force: slice
    beam: slice
    partial_sums: slice
    eccentricity: int
    attitude: int
    size: int


@dataclass(frozen=True, eq=False)
class SymbolicProblem:
    """The built problem: MX symbols and expressions, and where things sit.

    x, p : MX symbols of the unknowns and the parameters; g : the equations (MX);
    jacobian : ∂g/∂x (sparse MX); layout : the unknowns' :class:`Layout`;
    force_blocks : the θ-row indices of each force partial sum.
    """

    x: ca.MX
    p: ca.MX
    g: ca.MX
    jacobian: ca.MX
    layout: Layout
    force_blocks: list


def build_problem(st: disc.Stencil, law: FoilLaw, law_data) -> SymbolicProblem:
    """The equations g(x, p) = 0 and their Jacobian for one stencil and foil law.

    st : the grid's stencil; law : the static structure (a law of
    :mod:`gfbopt.physics.foil_laws`); law_data : ``law.prepare(grid, st.dpsi)``.
    """
    lifted = _lifted_equations(st, law, law_data)
    x = ca.MX.sym("x", lifted.layout.size)
    p = ca.MX.sym("p", n_parameters(st))
    fields, g_lifted, dz = lifted.values(x, p)
    jac_lifted, d_fields = lifted.derivatives(x, p)
    strips = _StripReynolds(st)
    lam = p[PARAMETERS.index("bearing_number")]
    reynolds, d_reynolds = strips.residual_and_jacobian(fields, lam, dz)
    g = ca.vertcat(reynolds, g_lifted)
    jac = ca.vertcat(ca.mtimes(d_reynolds, d_fields), jac_lifted)
    return SymbolicProblem(x, p, g, jac, lifted.layout, lifted.force_blocks)


@dataclass(frozen=True, eq=False)
class _Lifted:
    """The SX part: node fields (P, H at every node), the non-Reynolds equations, and
    their derivatives, as two CasADi functions of (x, p)."""

    values: ca.Function        # (x, p) ↦ (fields = [P; H] at every node, g_lifted, ΔZ)
    derivatives: ca.Function   # (x, p) ↦ (∂g_lifted/∂x, ∂fields/∂x)
    layout: Layout
    force_blocks: list


def _lifted_equations(st: disc.Stencil, law: FoilLaw, law_data) -> _Lifted:
    m = st.n_theta_nodes
    n_beam = law.extra_unknowns(st.grid)
    par = ca.SX.sym("p", n_parameters(st))
    n_scalar = len(PARAMETERS)
    (_, s, c, ld, mode, target, seam_angle, follows, comp, gumbel,
     position, attitude_target, hard_n, hard_lim) = ca.vertsplit(par[:n_scalar])  # Λ: Reynolds
    bore = par[n_scalar:n_scalar + m]                  # B_i = Δc/c per θ row
    s_rows = par[n_scalar + m:n_scalar + 2 * m]        # S_i per θ row
    pu = ca.SX.sym("P", st.n_unknown)
    hr = ca.SX.sym("H", m)
    q = ca.SX.sym("Q", m)
    qf = ca.SX.sym("QF", m)
    u = ca.SX.sym("U", n_beam)
    # Force integrals in the grid's own frame, lifted into block partial sums so that no
    # Jacobian row is dense (dense rows defeat CasADi's colouring: docs/PHYSICS.md).
    blocks = np.array_split(np.arange(m), max(1, int(round(math.sqrt(m)))))
    nb = len(blocks)
    sums = ca.SX.sym("FS", 2 * nb)
    ecc = ca.SX.sym("eps")
    phi = ca.SX.sym("phi")
    x = ca.vertcat(pu, hr, q, qf, u, sums, ecc, phi)
    offset, slices = 0, []
    for size in (st.n_unknown, m, m, m, n_beam, 2 * nb):
        slices.append(slice(offset, offset + size))
        offset += size
    layout = Layout(*slices, eccentricity=offset, attitude=offset + 1, size=offset + 2)

    dz = st.axial_spacing(ld)
    p_full = ca.SX.ones(st.n_nodes)
    p_full[st.unknown.tolist()] = pu
    theta_seam = follows * (math.pi + phi) + (1 - follows) * seam_angle
    theta = theta_seam + ca.DM(st.psi)
    h_rigid = rigid_film_polar(ecc, phi, theta) + bore
    mean_gauge = q / (2 * ld)
    foil = FoilParameters(s if law.name == "beam" else s_rows, c, comp, (hard_n, hard_lim))
    h_nodes, film_eq, foil_eq = law.static_film(
        h_rigid, hr, mean_gauge, p_full, u, foil, st, law_data)
    force_p = 1 + force_gauge(p_full - 1, gumbel)
    groups = [film_eq, q - disc.axial_integral(p_full, st, dz),
              qf - disc.axial_integral(force_p, st, dz)]
    if foil_eq is not None:
        groups.append(foil_eq)
    # F = −Σ w (cos θ, sin θ) Q^F with θ = θ_s + ψ: partial sums of the ψ-frame force
    # components A = −Σ w cos ψ Q^F and B = −Σ w sin ψ Q^F, then a rotation by θ_s.
    w = st.theta_weight
    part = [disc.film_forces(qf[b.tolist()], st.psi[b], w[b]) for b in blocks]
    groups.append(ca.vertcat(*([sums[k] - f[0] for k, f in enumerate(part)]
                               + [sums[nb + k] - f[1] for k, f in enumerate(part)])))
    fa, fb = ca.sum1(sums[:nb]), ca.sum1(sums[nb:])
    fx = ca.cos(theta_seam) * fa - ca.sin(theta_seam) * fb
    fy = ca.sin(theta_seam) * fa + ca.cos(theta_seam) * fb
    groups.append(ca.vertcat(mode * (fx + target) + (1 - mode) * (ecc - target),
                             position * (phi - attitude_target) + (1 - position) * fy))
    fields = ca.vertcat(p_full, h_nodes)
    # One Jacobian per equation group: each is coloured on its own, so the axial integrals
    # (a whole θ-row of P per equation) do not set the colour count of the others.
    jac = ca.vertcat(*[ca.jacobian(group, x) for group in groups])
    values = ca.Function("static_lifted", [x, par], [fields, ca.vertcat(*groups), dz],
                         ["x", "p"], ["fields", "g", "dz"])
    derivatives = ca.Function("static_lifted_jac", [x, par], [jac, ca.jacobian(fields, x)],
                              ["x", "p"], ["jac_g_x", "jac_fields_x"])
    return _Lifted(values, derivatives, layout, blocks)


class _StripReynolds:
    """Reynolds on θ-strips: one θ-row of unknown nodes and its two neighbour rows.

    The residual of a strip is :func:`gfbopt.discretisation.reynolds_residual` on a three-row
    patch stencil; it and its sparse Jacobian are SX functions mapped over the strips.
    """

    def __init__(self, st: disc.Stencil):
        nzn, m = st.n_z_nodes, st.n_theta_nodes
        rows = np.unique(st.row)
        j = np.arange(1, nzn - 1)
        if not np.array_equal(st.unknown, (rows[:, None] * nzn + j[None, :]).ravel()):
            raise AssertionError("stencil unknowns are not whole θ-rows of interior nodes")
        node = np.arange(st.n_nodes).reshape(m, nzn)
        patch_nodes = np.stack([node[(rows - 1) % m], node[rows], node[(rows + 1) % m]],
                               axis=1).reshape(rows.size, 3 * nzn)
        #: index in fields = [P; H] (every node) of each strip input, one strip per row
        self.index = np.hstack([patch_nodes, patch_nodes + st.n_nodes])
        self.n_strips = rows.size
        self.n_fields = 2 * st.n_nodes
        self.n_unknown = st.n_unknown
        centre = nzn + j
        patch = replace(st, periodic=False, n_theta_nodes=3, psi=st.dpsi * np.arange(3),
                        unknown=centre, row=np.ones_like(j), east=centre + nzn,
                        west=centre - nzn, north=centre + 1, south=centre - 1,
                        east_row=np.full_like(j, 2), west_row=np.zeros_like(j),
                        theta_weight=st.dpsi * np.ones(3))
        v = ca.SX.sym("v", 6 * nzn)          # [P; H] on the patch, row by row
        lam, dz = ca.SX.sym("lam"), ca.SX.sym("dz")
        r = disc.reynolds_residual(v[:3 * nzn], v[3 * nzn:], patch, lam, dz)
        jac = ca.jacobian(r, v)
        self.residual = ca.Function("reynolds_strip", [v, lam, dz], [r])
        self.jacobian = ca.Function("reynolds_strip_jac", [v, lam, dz], [jac])
        # Where each nonzero of the mapped strip Jacobians goes in ∂R/∂fields.  The map
        # concatenates the strips' Jacobians side by side, so its nonzeros are strip after
        # strip, each in the local pattern's column-major order (that of get_triplet);
        # ``order`` sorts them into the global matrix's column-major order.
        local_rows, local_cols = (np.asarray(k) for k in jac.sparsity().get_triplet())
        g_rows = (np.arange(self.n_strips)[:, None] * j.size + local_rows[None, :]).ravel()
        g_cols = self.index[:, local_cols].ravel()
        self.order = np.lexsort((g_rows, g_cols))
        self.sparsity = ca.Sparsity.triplet(self.n_unknown, self.n_fields,
                                            g_rows[self.order].tolist(),
                                            g_cols[self.order].tolist())
        if self.sparsity.nnz() != g_rows.size:
            raise AssertionError("strip Jacobian entries overlap")

    def residual_and_jacobian(self, fields: ca.MX, lam: ca.MX, dz: ca.MX) -> tuple:
        """(R at the unknown nodes, ∂R/∂fields sparse) as MX, from fields = [P; H]."""
        v = ca.reshape(fields[self.index.ravel().tolist()], self.index.shape[1],
                       self.n_strips)
        residual = ca.vec(self.residual.map(self.n_strips)(v, lam, dz))
        local = self.jacobian.map(self.n_strips)(v, lam, dz)
        nz = ca.sparsity_cast(local, ca.Sparsity.dense(local.nnz(), 1))
        return residual, ca.sparsity_cast(nz[self.order.tolist()], self.sparsity)
