"""Campbell diagram: damped natural frequencies and damping of the rotor's modes against speed,
from the eigenvalues of the full linearised system — rotor states plus both bearings' film and
foil states — not from coefficients frozen at an assumed frequency (Bonello 2019, Mech. Syst.
Signal Process. 129:502–530, shows why the latter misleads for foil bearings).

The descriptor system (time τ = ω t, so an eigenvalue s has growth rate Re s per radian of
shaft rotation and whirl ratio Im s), states v = (y_A, y_B, q̃, ũ = q̃'):

    B_k y_k' = −A_k y_k − C̃_k q̃                      each bearing (gfbopt.linear; C̃_k = C_ξ,k T_k Λ c/c_k)
    q̃'      = ũ
    μ M̃ ũ'  = −μ G̃ ũ + Σ_k F̃_k y_k                  F̃_k = Λ T_kᵀ f_k P_k/P_ref

with q = c Λ q̃ in units of the first bearing's clearance c (tilts times the half span L:
Λ = diag(1, 1, 1/L, 1/L)), M̃ = ω² c Λ M Λ/P_ref, G̃ = ω² c Λ G Λ/P_ref, P_k = p_a R_k²,
P_ref = P_A, μ the inertia scale of :mod:`.matched_whirl` (1: the rotor itself).

Structural damping (η > 0).  The hysteretic foundation of the matched-whirl threshold has no
time-domain form; here each bearing's foil carries the Kelvin–Voigt state of the transient
engine (:mod:`gfbopt.transient.foil_state`), compliance S/(1 + τ_f s), τ_f = η/ν_ref, stated
with the reference whirl ratio ν_ref (default: the first mode's threshold whirl ratio, where
both models give the same impedance, so the same threshold).  In the linearised equations the
rows carrying the compliance are multiplied by 1 + τ_f s, which keeps the system linear in s
when those rows are algebraic (axial-mean law: the lifted film rows) or when the entries scale
with the foundation stiffness (beam): B gains τ_f (A − a) in those rows and the rows' ξ input
gains τ_f ξ' (= τ_f C̃ ũ).  The local law's compliance also enters the squeeze term, which
would make the system quadratic in s: refused with that reason.

Coulomb friction in the bumps (``friction_coefficient`` > 0).  A Campbell diagram is the
small-motion analysis, so each loaded bump's spring–slider element is stuck and adds its
spring κ K_b to the bump (:func:`stuck_system`): the stiffness the matched-whirl onset sees for
small orbits, so that a mode's Campbell zero crossing is that onset.  The amplitude-dependent
answer above it is :mod:`.friction_onset`'s.

Eigenvalues: shift-invert Arnoldi (scipy ARPACK) on the sparse pencil, one LU of J − σE per
shift.  The shifts come from the rotor's own estimate: the n-DOF quadratic eigenproblem with
each bearing's K and C frozen at the whirl ratio of the estimate (two fixed-point passes from
γ = 1/2), so that every rigid-body root is found whatever its ratio to the shaft speed (a
shaft's: its four lowest and every other whirling below :data:`MAX_WHIRL` times the speed, or
below a stated frequency: a Campbell diagram's one limit for all its speeds).
Around each shift the eigenvalue whose eigenvector carries the most rotor motion is the
rotor's mode; modes are labelled (:mod:`.modes`) and tracked over speed by continuity
(:mod:`.tracking`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ParameterError
from ..linear.model import impedance
from ..sparse_lu import Factoriser, factor
from ..threads import single_threaded
from .modes import shape
from .structure import dof_scales, is_rigid
from .supports import RotorCase, SpeedStates

#: eigenvalues computed around each shift
NEAR = 6
#: fixed-point passes of the 4-DOF estimate (coefficients at the estimate's own whirl)
PASSES = 2
#: a shaft's modes are followed when among its LOWEST lowest or whirling below MAX_WHIRL
#: times the shaft speed (the rigid body's four are always all followed) [-]
LOWEST = 4
MAX_WHIRL = 3.0


@dataclass(frozen=True)
class SystemMode:
    """One eigenvalue of the full system at one speed.

    eigenvalue s [per radian of shaft rotation]; whirl_ratio Im s [-];
    whirl_frequency_hz [Hz]; growth_rate_per_s [1/s]; log_decrement δ = −2π Re s/Im s [-];
    damping_ratio ζ = −Re s/|s| [-]; label; shape; rotor_share (fraction of the eigenvector's
    norm in the rotor states, scaled units) [-]."""

    eigenvalue: complex
    whirl_frequency_hz: float
    growth_rate_per_s: float
    log_decrement: float
    damping_ratio: float
    label: str
    shape: dict
    rotor_share: float
    vector: np.ndarray

    @property
    def whirl_ratio(self) -> float:
        return float(self.eigenvalue.imag)


class FullSystem:
    """The sparse descriptor pencil (J, E) at one speed (module docstring)."""

    def __init__(self, rotor: RotorCase, states: SpeedStates, inertia_scale: float = 1.0,
                 reference_whirl: Optional[float] = None):
        if not states.ok:
            raise ParameterError("speed_rpm", states.speed_rpm, "a bearing's load exceeds its "
                                 "capacity here: " + states.failure["message"])
        structure = rotor.structure
        omega = states.omega
        g0 = rotor.cases[0].bearing
        self.c_ref = g0.radial_clearance
        self.p_ref = g0.ambient_pressure * g0.radius**2
        half_span = 0.5 * rotor.system.span
        nq = structure.size
        lam = (np.diag([1.0, 1.0, 1.0 / half_span, 1.0 / half_span]) if is_rigid(structure)
               else np.diag(dof_scales(structure, half_span)))
        scale = omega**2 * self.c_ref / self.p_ref
        self.m = inertia_scale * scale * lam @ structure.mass() @ lam
        self.g = inertia_scale * scale * lam @ structure.gyroscopic() @ lam
        # the shaft's own K̃ = c Λ K Λ/P_ref and C̃ = ω c Λ C Λ/P_ref (per radian; not scaled
        # by μ); none for the rigid body
        rigid = is_rigid(structure)
        self.k = (np.zeros((nq, nq)) if rigid
                  else self.c_ref / self.p_ref * lam @ structure.stiffness() @ lam)
        self.c = (np.zeros((nq, nq)) if rigid
                  else omega * self.c_ref / self.p_ref * lam @ structure.damping() @ lam)
        self.nq = nq
        self.lam, self.omega, self.inertia_scale = lam, omega, inertia_scale
        self.reference_whirl = reference_whirl
        blocks_j, blocks_e, inputs, outputs, rate_inputs = [], [], [], [], []
        for st, t in zip(states.states, rotor.transforms):
            lin = st.linearisation
            g = st.case.bearing
            c_in = lin.c_xi @ (t @ lam) * (self.c_ref / g.radial_clearance)      # n × 4
            f_out = lam @ t.T @ lin.force * (g.ambient_pressure * g.radius**2 / self.p_ref)
            a, b, rate = _kelvin_voigt(lin, c_in, reference_whirl, nq)
            blocks_j.append(-a)
            blocks_e.append(b)
            inputs.append(-c_in)
            rate_inputs.append(rate)
            outputs.append(f_out)
        self.sizes = [blk.shape[0] for blk in blocks_j]
        n = sum(self.sizes)
        film_j = sp.block_diag(blocks_j, format="csc")
        film_e = sp.block_diag(blocks_e, format="csc")
        cin = sp.csc_matrix(np.vstack(inputs))
        crate = sp.csc_matrix(np.vstack(rate_inputs))
        fout = sp.csc_matrix(np.hstack(outputs))
        zq = sp.csc_matrix((nq, nq))
        self.j = sp.bmat([[film_j, cin, crate],
                          [sp.csc_matrix((nq, n)), zq, sp.identity(nq)],
                          [fout, sp.csc_matrix(-self.k), sp.csc_matrix(-(self.g + self.c))]],
                         format="csc")
        self.e = sp.block_diag([film_e, sp.identity(nq), sp.csc_matrix(self.m)], format="csc")
        self.n_film = n
        self._factorise = Factoriser()     # one pattern, a new shift at every call

    @property
    def size(self) -> int:
        return self.j.shape[0]

    def eigen(self, shift: complex, count: int = NEAR) -> tuple[np.ndarray, np.ndarray]:
        """(eigenvalues, eigenvectors) nearest ``shift`` (shift-invert Arnoldi)."""
        lu = factor((self.j - shift * self.e).astype(complex), self._factorise)
        op = spla.LinearOperator(self.j.shape, matvec=lambda v: lu.solve(self.e @ v),
                                 dtype=complex)
        mu, vec = spla.eigs(op, k=count, which="LM", tol=1e-12, ncv=max(4 * count, 12))
        return shift + 1.0 / mu, vec

    def rotor_amplitude(self, vector: np.ndarray) -> np.ndarray:
        """q̂ [m, rad] of an eigenvector (the rotor's block, unscaled)."""
        qt = vector[self.n_film:self.n_film + self.nq]
        return self.c_ref * (self.lam @ qt)

    def rotor_share(self, vector: np.ndarray) -> float:
        """|q̃| / (|q̃| + max_k rms(y_k)) of an eigenvector (scaled units) [-]."""
        qt = np.linalg.norm(vector[self.n_film:self.n_film + self.nq])
        rms, start = 0.0, 0
        for n in self.sizes:
            rms = max(rms, float(np.linalg.norm(vector[start:start + n]) / math.sqrt(n)))
            start += n
        return float(qt / (qt + rms)) if qt + rms > 0 else 0.0


def _kelvin_voigt(lin, c_in: np.ndarray, reference_whirl: Optional[float], nq: int = 4):
    """(A, B, rate input) of one bearing, with Kelvin–Voigt foil states when η > 0 (module
    docstring); the rate input multiplies ũ (n × nq dense, zero without damping)."""
    n = lin.size
    rate = np.zeros((n, nq))
    eta, terms = lin.loss_factor, lin.compliance
    if lin.friction is not None:
        return (*stuck_system(lin), rate)
    if eta == 0.0 or terms is None:
        return lin.a, lin.b, rate
    if reference_whirl is None or not (math.isfinite(reference_whirl) and reference_whirl > 0):
        raise ParameterError("reference_whirl", reference_whirl, "must be a whirl ratio > 0: "
                             "the Kelvin–Voigt foil state's τ_f = η/ν_ref needs it")
    if terms.b is not None:
        raise ParameterError("deflection_law", "local", "the local law's compliance enters "
                             "the squeeze term: its Kelvin–Voigt form is not linear in s; the "
                             "Campbell diagram with η > 0 supports the axial-mean law and the "
                             "beam")
    tau = eta / reference_whirl
    a, b = lin.a.tocsr(), lin.b.tocsr()
    if terms.scales_with == "stiffness":
        return lin.a, (b + tau * terms.a).tocsc(), rate
    rows = np.unique(sp.coo_matrix(terms.a).row)
    if abs(b[rows]).sum() > 0:
        raise ParameterError("foil", "compliance rows", "carry a squeeze term: the "
                             "Kelvin–Voigt form would not be linear in s")
    mask = sp.diags(np.isin(np.arange(n), rows).astype(float))
    b_new = b + tau * (mask @ (a - terms.a.tocsr()))
    rate[rows] = -tau * c_in[rows]              # J row: −τ C̃ on ũ (τ C̃ ũ moved right)
    return lin.a, b_new.tocsc(), rate


def stuck_system(lin) -> tuple:
    """(A, B) of a bearing whose bumps rub, for small motion: every loaded unit's friction
    element stuck, so its spring κ K_b stands beside the bump (k_u = 1 + κ where loaded, 1
    where not; :mod:`gfbopt.linear.friction_units`) — real and independent of s, the
    foundation the matched-whirl threshold sees for small orbits.  Friction together with a
    loss factor η > 0 is refused: the Kelvin–Voigt bump beside a stuck spring is not built
    here."""
    if lin.loss_factor > 0:
        raise ParameterError("loss_factor", lin.loss_factor, "must be 0 in the Campbell "
                             "diagram when the bumps rub (friction_coefficient > 0): the "
                             "Kelvin-Voigt bump beside the stuck friction spring is not built")
    k = 1.0 + lin.friction.factor(None, 1.0).real
    a, b = lin.compliance.apply(lin.a, lin.b, k)
    return sp.csc_matrix(a.real), sp.csc_matrix(b.real)


def rotor_estimates(rotor: RotorCase, states: SpeedStates, inertia_scale: float = 1.0,
                    passes: int = PASSES, max_frequency_hz: Optional[float] = None
                    ) -> np.ndarray:
    """The rotor's eigenvalues s (upper half plane, per radian) from the n-DOF quadratic
    eigenproblem with the bearings' K, C frozen at γ = 1/2, then each root refined by
    ``passes`` fixed-point steps with K, C frozen at its own whirl ratio (nearest root).
    A shaft's: those :func:`_lower` keeps (``max_frequency_hz`` [Hz]: every root up to this
    frequency instead of :data:`MAX_WHIRL` times the speed)."""
    first = _frozen_roots(rotor, states, 0.5, inertia_scale)
    if not is_rigid(rotor.structure):
        limit = (None if max_frequency_hz is None
                 else 2 * math.pi * float(max_frequency_hz) / states.omega)
        first = _lower(first, limit)
    out = []
    for s in first:
        for _ in range(passes):
            roots = _frozen_roots(rotor, states, max(float(s.imag), 1e-3), inertia_scale)
            if roots.size == 0:
                break
            s = roots[np.argmin(np.abs(roots - s))]
        out.append(s)
    return _unique(np.array(out))


def _frozen_roots(rotor: RotorCase, states: SpeedStates, gamma: float,
                  inertia_scale: float) -> np.ndarray:
    """Upper-half-plane roots of det(s² μM ω² + s ω² μG + K + s C ω) = 0 (per radian) with
    the bearings' K and C frozen at whirl ratio γ."""
    structure = rotor.structure
    omega = states.omega
    m = inertia_scale * omega**2 * structure.mass()
    g = inertia_scale * omega**2 * structure.gyroscopic()
    k, c = _frozen(rotor, states, gamma)
    if not is_rigid(structure):           # the shaft's own K and C ω (per radian)
        k, c = k + structure.stiffness(), c + omega * structure.damping()
    n = structure.size
    a = np.block([[np.zeros((n, n)), np.eye(n)], [-k, -(g + c)]])
    bmat = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), m]])
    ev = sla.eig(a, bmat, right=False)
    return ev[(ev.imag > 1e-6) & np.isfinite(ev)]


def _frozen(rotor: RotorCase, states: SpeedStates, gamma: float) -> tuple:
    """(K, C·ω) of the bearings at whirl ratio γ in rotor coordinates, per radian: K_b(iγω)
    = K + iγ Cω, both real n × n."""
    n = rotor.structure.size
    kb = np.zeros((n, n), dtype=complex)
    for t, st in zip(rotor.transforms, states.states):
        kb += t.T @ st.impedance(gamma) @ t
    return kb.real, kb.imag / gamma


def _lower(roots: np.ndarray, max_whirl: Optional[float] = None) -> np.ndarray:
    """A shaft's roots worth following: its :data:`LOWEST` lowest whirl ratios (its
    rigid-body modes on the bearings) and every other below ``max_whirl`` (default
    :data:`MAX_WHIRL`) [-]."""
    order = roots[np.argsort(roots.imag)]
    if not order.size:
        return order
    limit = max(MAX_WHIRL if max_whirl is None else max_whirl,
                float(order[min(LOWEST, order.size) - 1].imag))
    return order[order.imag <= limit]


def _unique(values: np.ndarray, tol: float = 1e-6) -> np.ndarray:
    out = []
    for v in sorted(values, key=lambda z: z.imag):
        if not any(abs(v - w) <= tol * max(1.0, abs(w)) for w in out):
            out.append(v)
    return np.array(out)


def characteristic(rotor: RotorCase, states: SpeedStates, full: "FullSystem"):
    """s ↦ det of the scaled dynamic stiffness Λ D(s) Λ (per radian; each bearing's exact
    Z̄_k(s) at complex s: from its Krylov space where that has converged at s, else a direct
    LU (:meth:`~gfbopt.rotor.supports.BearingState.at`); with the Kelvin–Voigt foundation
    1 + τ_f s when η > 0, by a direct LU)."""
    structure = rotor.structure
    omega = states.omega
    lam = full.lam
    m, g = structure.mass(), structure.gyroscopic()
    rigid = is_rigid(structure)
    k, c = structure.stiffness(), omega * structure.damping()

    def d(s: complex) -> complex:
        mat = full.inertia_scale * omega**2 * (s * s * m + s * g)
        if not rigid:
            mat = mat + k + s * c
        for st, t in zip(states.states, rotor.transforms):
            lin = st.linearisation
            if lin.loss_factor > 0 and lin.compliance is not None:
                z = impedance(lin, s, 1.0 + lin.loss_factor / full.reference_whirl * s)
            else:                       # analytic in s: the Krylov space's value (.reduced)
                z = st.at(s)
            mat = mat + st.scale * (t.T @ z @ t)
        return complex(np.linalg.det(lam @ mat @ lam))

    return d


def _secant(f, guess: complex, tol: float = 1e-11, max_iter: int = 40) -> Optional[complex]:
    s0, s1 = guess, guess * (1 + 1e-4) + 1e-5j
    f0, f1 = f(s0), f(s1)
    for _ in range(max_iter):
        if f1 == f0:
            return None
        s2 = s1 - f1 * (s1 - s0) / (f1 - f0)
        s0, f0, s1, f1 = s1, f1, s2, f(s2)
        if abs(s1 - s0) < tol * max(1.0, abs(s1)):
            return complex(s1)
    return None


@single_threaded
def system_modes(rotor: RotorCase, states: SpeedStates, inertia_scale: float = 1.0,
                 reference_whirl: Optional[float] = None, guesses=(),
                 max_frequency_hz: Optional[float] = None) -> list:
    """The rotor's modes at one speed, lowest whirl ratio first.

    Each starting point — ``guesses`` first (per radian; in a Campbell diagram the previous
    speed's modes at the same frequency in Hz, :mod:`.tracking`), then the estimates
    (:func:`rotor_estimates`) — is followed to a root of the exact characteristic
    equation det D(s) = 0 (secant iteration, deflated by the roots already found so that two
    starts do not land on one root), and the root is then taken from the full sparse
    system: the eigenvalue nearest it by shift-invert Arnoldi, whose eigenvector gives the
    shape (one mode per eigenvalue: two roots that give one eigenvalue count once).
    ``reference_whirl``: ν_ref of the Kelvin–Voigt foil states (needed when η > 0);
    ``max_frequency_hz``: a shaft's estimates up to this frequency [Hz] (:func:`_lower`; a
    Campbell diagram states one limit for all its speeds)."""
    full = FullSystem(rotor, states, inertia_scale, reference_whirl)
    d = characteristic(rotor, states, full)
    names = rotor.names
    positions = list(rotor.positions)
    roots: list = []
    starts = [complex(g) for g in guesses] + sorted(
        rotor_estimates(rotor, states, inertia_scale, max_frequency_hz=max_frequency_hz),
        key=lambda z: z.imag)
    for est in starts:
        def deflated(s, found=tuple(roots)):
            value = d(s)
            for r in found:
                value /= (s - r)
            return value

        root = _secant(deflated, complex(est))
        if root is None or root.imag <= 0 or any(abs(root - r) <= 1e-8 * abs(r)
                                                 for r in roots):
            continue
        roots.append(root)
    modes = []
    for root in roots:
        ev, vec = full.eigen(root + 1e-6 * abs(root), count=2)   # off the root: LU regular
        j = int(np.argmin(np.abs(ev - root)))
        s = complex(ev[j])
        if any(abs(s - m.eigenvalue) <= 1e-8 * abs(s) for m in modes):
            continue            # two roots of det D within its tolerance: one eigenvalue
        q = full.rotor_amplitude(vec[:, j])
        sh = shape(q, positions, names, rotor.structure)
        modes.append(SystemMode(
            s, s.imag * states.omega / (2 * math.pi), s.real * states.omega,
            -2 * math.pi * s.real / s.imag, -s.real / abs(s), sh["label"], sh,
            full.rotor_share(vec[:, j]), q))
    return sorted(modes, key=lambda m: m.whirl_ratio)
