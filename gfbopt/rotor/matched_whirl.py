"""The exact linear threshold of a rotor on two bearings at one speed, with matched whirl, on
the structure contract of any size (:mod:`gfbopt.rotor.structure`: the rigid body's four
degrees of freedom, or a shaft condensed on its bearings, :mod:`gfbopt.rotor.condensed`): the
whirl frequencies Ω and inertia scales μ at which the dynamic stiffness

    D(Ω; μ) = −Ω² μ M + iΩ (C + ω μ G) + K + Σ_k T_kᵀ Z_k(iΩ) T_k,   T_k = R(α_k)ᵀ S(z_k),

is singular, Z_k each bearing's frequency-dependent impedance at its own equilibrium.  **μ
scales the rotor's inertias only — its mass matrix M and its gyroscopic matrix G together;
the shaft's own stiffness K and damping C (zero for the rigid body) are not scaled, nor are
the bearings; μ = 1 is the rotor itself.**  At each whirl ratio γ = Ω/ω this is the n × n
generalised eigenproblem

    A(Ω) v = ν K_b(Ω) v,    A = Ω² M − iΩ ω G,   K_b = K + iΩ C + Σ T_kᵀ Z_k T_k,   ν = 1/μ,

and a real ν > 0 is a threshold: the rotor with inertias μ = 1/ν has a mode on the imaginary
axis at s = iΩ, with shape v (docs/PHYSICS.md).  μ generalises the one-bearing
critical mass: for one bearing carrying mass M, μ = M̄c/M̄.  Scaling the inertias keeps
the rotor's shape (mass, inertias and the gyroscopic term alike), so the rotor itself
(μ = 1) is below the threshold of a mode — that mode is stable — when the mode's critical
μ_c > 1 (the rotor would need μ_c times its inertia to whirl; cf. M̄ < M̄c).

Search (as :mod:`gfbopt.linear.crossings` does for one bearing, with n roots instead of
two): ν(γ) on the scan (24 whirl ratios on (0.02, 1.2) by default, the one-bearing scan,
with midpoints added wherever a root moves by more than 0.3 of its distance to the next root
between two points — its move taken as the smaller of the plain one and the one from the
inertia term's trend ν ∝ γ², and no move counted for a decisive shape match
(:func:`_ambiguous`) — or its continuation is unsure (MAC below :data:`SURE_MAC`) — near
γ = 1/2 two forward modes can cross the axis 2e-4 apart in γ), the n branches followed by
continuity of their shapes: the eigenvectors of neighbouring whirl ratios are matched by the
optimal assignment (:func:`scipy.optimize.linear_sum_assignment`) on 1 − MAC, MAC =
|aᴴ M b|²/((aᴴ M a)(bᴴ M b)) the modal assurance criterion weighted by the mass matrix (one
consistent unit for translations and tilts, and for any n); every sign change of Im ν
refined by Brent's method to 1e-10 in γ, kept when the root is real there
(|Im ν| ≤ 1e-8 |ν|: a jump between branches is not a crossing) and ν > 0.  Every impedance
comes from the bearings' :class:`~gfbopt.rotor.supports.BearingState` at this speed (one
LU and one Krylov space per bearing for all modes and frequencies).  Each crossing's label
is :func:`gfbopt.rotor.modes.shape`'s (bending modes named as such).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np
from scipy.optimize import brentq, linear_sum_assignment

from .modes import shape
from .probe import probe, probe_scale
from .reduced import TaylorImpedance
from .structure import is_rigid
from ..linear.krylov import ShiftedImpedance
from .supports import WHIRL_RANGE, RotorCase, SpeedStates

#: absolute tolerance of a crossing's whirl ratio (Brent) [-] (that of gfbopt.linear)
WHIRL_TOLERANCE = 1e-10
#: a refined root counts as real when |Im ν| ≤ this × |ν| [-]
REAL_ROOT = 1e-8
#: scan points over the whirl range (as gfbopt.linear.linear_threshold)
SAMPLES = 24
#: a root may move by at most this fraction of its distance to the nearest other root from
#: one scan point to the next; else the interval is halved (branch following stays sure)
FOLLOW_FRACTION = 0.3
#: at most this many scan points in all, and no interval narrower than MIN_SPACING [-]
MAX_SAMPLES = 240
MIN_SPACING = 1e-5
#: a shaft's crossings with μ_c above this are not reported [-]: its bending modes reach the
#: axis only on a rotor this much heavier (μ_c ~ 1e6 measured for a steel shaft on foil
#: bearings), at whirl frequencies that are not its own; the rigid body's four roots are all
#: reported, as always
SHAFT_SCALE_LIMIT = 1e3
#: a branch's continuation between two scan points is sure when the MAC of its shapes is at
#: least this; else the interval is halved [-]
SURE_MAC = 0.5
#: a shaft's branch is refined in an interval only when its root at either end is at least
#: this over SHAFT_SCALE_LIMIT [-]: the root at a refined crossing never exceeded the larger
#: of its interval's ends (ratio ≤ 1.000 measured over every crossing of the blower's rigid
#: twin and of problems/rotors/flexible_rotor.toml at 72 × 20, 6,000–60,000 rpm), so a
#: crossing with μ_c ≤ SHAFT_SCALE_LIMIT is not missed unless that ratio exceeds 2
FAINT = 0.5
#: a branch's continuation is decisive when the MAC of its shapes is at least this and no
#: other root of either end matches either shape with a MAC of SURE_MAC or more [-]
DECISIVE_MAC = 0.9


@dataclass(frozen=True)
class ModeCrossing:
    """One mode on the imaginary axis at one speed.

    inertia_scale μ_c [-] (the rotor whirls in this mode when its inertias are μ_c times
    the real ones; μ_c > 1 stable), whirl_ratio γ = Ω/ω [-], whirl_frequency_hz [Hz],
    label ('forward conical', …), shape (:func:`gfbopt.rotor.modes.shape`), vector q̂;
    note: why μ_c = 0 when the probe found the rotor unstable below every crossing
    (:mod:`.probe`), else empty."""

    inertia_scale: float
    whirl_ratio: float
    whirl_frequency_hz: float
    label: str
    shape: dict
    vector: np.ndarray = field(repr=False, compare=False)
    note: str = ""


def bearing_stiffness(rotor: RotorCase, states: SpeedStates, whirl_ratio: float) -> np.ndarray:
    """K_b(iΩ) = K + iΩ C + Σ T_kᵀ Z_k(iΩ) T_k [N/m, N, N m] (n × n) at Ω = γ ω."""
    n = rotor.structure.size
    kb = np.zeros((n, n), dtype=complex)
    for t, st in zip(rotor.transforms, states.states):
        kb += t.T @ st.impedance(whirl_ratio) @ t
    return _with_shaft(rotor, kb, whirl_ratio * states.omega)


def _with_shaft(rotor: RotorCase, kb: np.ndarray, big) -> np.ndarray:
    """K_b plus the shaft's own K + iΩ C (``big``: Ω [rad/s], a scalar or one per matrix of a
    batch); the rigid body has none (K_b unchanged)."""
    structure = rotor.structure
    if is_rigid(structure):
        return kb
    big, c = np.asarray(big, dtype=float), structure.damping()
    rate = 1j * big[:, None, None] * c[None] if big.ndim else 1j * float(big) * c
    return kb + structure.stiffness() + rate


def _inertia(rotor: RotorCase, big, omega: float) -> np.ndarray:
    """A = Ω² M − iΩ ω G (``big``: Ω [rad/s], scalar or array: a batch)."""
    m, g = rotor.structure.mass(), rotor.structure.gyroscopic()
    big = np.asarray(big, dtype=float)
    if big.ndim == 0:
        return float(big)**2 * m - 1j * float(big) * omega * g
    return big[:, None, None] ** 2 * m[None] - 1j * (big * omega)[:, None, None] * g[None]


def inertia_roots(rotor: RotorCase, states: SpeedStates, whirl_ratio: float,
                  stiffness: Optional[np.ndarray] = None, vectors: bool = True
                  ) -> tuple[np.ndarray, Optional[np.ndarray]]:
    """(ν (n,), eigenvectors (n, n) as columns) of A v = ν K_b v at whirl ratio γ
    (``stiffness``: K_b when given, else :func:`bearing_stiffness`; without ``vectors``
    the eigenvalues alone, and None: a third cheaper, for Brent's iterations)."""
    omega = states.omega
    big = whirl_ratio * omega
    a = _inertia(rotor, big, omega)
    kb = bearing_stiffness(rotor, states, whirl_ratio) if stiffness is None else stiffness
    # K_b is the bearings' dynamic stiffness, regular wherever Z_k is: the standard problem
    # K_b⁻¹A v = ν v has the pencil's eigenpairs (numpy's driver costs a third of scipy's)
    pencil = np.linalg.solve(kb, a)
    if not vectors:
        return np.linalg.eigvals(pencil), None
    nu, vec = np.linalg.eig(pencil)
    return nu, vec


def inertia_roots_many(rotor: RotorCase, states: SpeedStates, whirl_ratios,
                       vectors: bool = False):
    """ν (m, n) of :func:`inertia_roots` at every whirl ratio of an array, in one batch
    (``vectors``: (ν, eigenvectors (m, n, n)))."""
    gammas = np.asarray(whirl_ratios, dtype=float)
    omega = states.omega
    big = gammas * omega
    a = _inertia(rotor, big, omega)
    n = rotor.structure.size
    kb = np.zeros((gammas.size, n, n), dtype=complex)
    for t, st in zip(rotor.transforms, states.states):
        kb += t.T[None] @ (st.scale * st.nondimensional_many(gammas)) @ t[None]
    kb = _with_shaft(rotor, kb, big)
    pencil = np.linalg.solve(kb, a)
    return np.linalg.eig(pencil) if vectors else np.linalg.eigvals(pencil)


def mass_mac(mass: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """MAC_ij = |a_iᴴ M b_j|²/((a_iᴴ M a_i)(b_jᴴ M b_j)) ∈ [0, 1] of the columns of a, b
    (n × r each, or batches (k, n, r); ``mass``: M, symmetric positive definite)."""
    ma, mb = mass @ a, mass @ b
    cross = np.abs(np.swapaxes(a.conj(), -1, -2) @ mb) ** 2
    na = np.einsum("...ij,...ij->...j", a.conj(), ma).real
    nb = np.einsum("...ij,...ij->...j", b.conj(), mb).real
    return cross / np.maximum(na[..., :, None] * nb[..., None, :], 1e-300)


def _assignments(mass: np.ndarray, left: np.ndarray, right: np.ndarray) -> tuple:
    """For each interval of the scan (``left``, ``right``: (k, n, n), the eigenvectors at its
    two ends as columns, roots in any order): (perm (k, n), its MAC (k, n), rival (k, n))
    such that root perm[j, i] of the right end continues root i of the left end — the
    optimal assignment on 1 − MAC (module docstring; the continuation of a root does not
    depend on how the roots of the left end are ordered); rival: the largest MAC of either
    root of that pair with any other root of the other end.  Where every root's best match
    is a different root, that is the optimal assignment (each takes its own maximum);
    elsewhere :func:`scipy.optimize.linear_sum_assignment` decides."""
    mac = mass_mac(mass, left, right)                                  # (k, n, n)
    perm = np.argmax(mac, axis=2)
    n = left.shape[1]
    distinct = np.sort(perm, axis=1) == np.arange(n)
    for k in np.flatnonzero(~distinct.all(axis=1)):
        perm[k] = linear_sum_assignment(1.0 - mac[k])[1]
    chosen = np.take_along_axis(mac, perm[:, :, None], axis=2)[:, :, 0]
    others = mac.copy()
    np.put_along_axis(others, perm[:, :, None], -1.0, axis=2)
    row = others.max(axis=2) if n > 1 else np.zeros_like(chosen)       # root i's rivals
    column = others.max(axis=1) if n > 1 else np.zeros_like(chosen)    # root perm[i]'s
    rival = np.maximum(row, np.take_along_axis(column, perm, axis=1))
    return perm, chosen, rival


def _ambiguous(values: np.ndarray, perm: np.ndarray, macs: np.ndarray,
               floor: float = 0.0, gammas: Optional[np.ndarray] = None,
               rivals: Optional[np.ndarray] = None) -> np.ndarray:
    """For each interval: True when continuing its roots is unsafe — some root moves by more
    than :data:`FOLLOW_FRACTION` of its distance to the nearest other root, or its shape's
    match is below :data:`SURE_MAC`.  Roots with |ν| below ``floor`` at both ends are not
    followed (a shaft's crossings beyond μ_c = 1/floor are not reported).

    With ``gammas`` (the scan's whirl ratios) a root's move is also measured from the trend
    of the inertia term, ν ∝ γ² (A = Ω² M − iΩ ω G; ν scales with it where K_b varies
    slowly), and the smaller of the two moves counts: roots that all grow as γ² keep their
    order and shapes however far each moves (a shaft's many small bending roots at low whirl
    ratios, whose plain moves exceed their separations from one scan point to the next while
    every MAC stays above 0.9), so that interval is not halved for them.  With ``rivals``
    (:func:`_assignments`) a root whose match is decisive — its MAC at least
    :data:`DECISIVE_MAC`, every rival's below :data:`SURE_MAC` — and whose move is at most
    :data:`FOLLOW_FRACTION` of its own size is sure however close another root's value lies
    (a shaft's bending roots passing each other: MAC 0.96–0.999 against rivals of
    0.2–0.35, moves of a few per cent; the rigid body's two forward roots that cross the
    axis together near γ = 1/2 move by more than half their size per interval there, and
    stay halved).  The MAC test is unchanged."""
    a = values[:-1]
    b = np.take_along_axis(values[1:], perm, axis=1)
    sep = np.abs(a[:, :, None] - a[:, None, :])
    sep[:, np.arange(a.shape[1]), np.arange(a.shape[1])] = np.inf
    move = np.abs(b - a)
    if gammas is not None:
        trend = (np.asarray(gammas[1:]) / np.asarray(gammas[:-1]))[:, None] ** 2
        move = np.minimum(move, np.abs(b - a * trend))
    moved = move > FOLLOW_FRACTION * sep.min(axis=2)
    if rivals is not None:
        moved &= ~((macs >= DECISIVE_MAC) & (rivals < SURE_MAC)
                   & (move <= FOLLOW_FRACTION * np.abs(a)))
    unsure = macs < SURE_MAC
    if floor > 0:
        relevant = (np.abs(a) >= floor) | (np.abs(b) >= floor)
        moved, unsure = moved & relevant, unsure & relevant
    return np.any(moved, axis=1) | np.any(unsure, axis=1)


def _branches(values: np.ndarray, perm: np.ndarray) -> np.ndarray:
    """``values`` with each row reordered to continue the previous row's roots (branches)."""
    order = np.empty(values.shape, dtype=int)
    order[0] = np.arange(values.shape[1])
    for k in range(len(perm)):
        order[k + 1] = perm[k][order[k]]
    return np.take_along_axis(values, order, axis=1)


def _adaptive_scan(roots, mass: np.ndarray, gammas: np.ndarray, floor: float = 0.0
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The scan with midpoints inserted wherever following the branches is ambiguous
    (:func:`_ambiguous`), until it is not or :data:`MAX_SAMPLES` points are reached; the
    roots of each point ordered by branch.  ``roots`` maps an array of whirl ratios to their
    (roots (m, n), eigenvectors (m, n, n)); ``mass``: M of the MAC."""
    nu, vec = roots(np.asarray(gammas, dtype=float))
    pts = {float(g): (x, v) for g, x, v in zip(gammas, nu, vec)}
    known: dict = {}                       # interval (left, right) -> (perm, MAC, rival)
    while True:
        g = np.array(sorted(pts))
        vals = np.array([pts[x][0] for x in g])
        pairs = list(zip(g[:-1], g[1:]))
        new = [pair for pair in pairs if pair not in known]
        if new:
            left = np.array([pts[pair[0]][1] for pair in new])
            right = np.array([pts[pair[1]][1] for pair in new])
            found = _assignments(mass, left, right)
            known.update((pair, tuple(f[j] for f in found)) for j, pair in enumerate(new))
        perm, macs, rivals = (np.array([known[pair][i] for pair in pairs]) for i in range(3))
        if len(pts) >= MAX_SAMPLES:
            break
        wide = (np.diff(g) > MIN_SPACING) & _ambiguous(vals, perm, macs, floor, g, rivals)
        split = [float(x) for x in 0.5 * (g[:-1] + g[1:])[wide]][:MAX_SAMPLES - len(pts)]
        if not split:
            break
        nu, vec = roots(np.array(split))
        pts.update((x, (r, v)) for x, r, v in zip(split, nu, vec))
    return g, _branches(vals, perm)


def crossings(rotor: RotorCase, states: SpeedStates, whirl_range=WHIRL_RANGE,
              samples: int = SAMPLES) -> list:
    """Every mode crossing (:class:`ModeCrossing`) with μ_c > 0 at this speed (a shaft's up
    to :data:`SHAFT_SCALE_LIMIT`), lowest μ_c first (module docstring), preceded by one with μ_c = 0 when the probe below the first
    crossing finds a growing mode (:mod:`.probe`: the massless journal is unstable).
    ``states`` must be complete (no bearing over capacity)."""
    gammas = np.linspace(whirl_range[0], whirl_range[1], samples)
    for st in states.states:
        st.prepare(gammas)
    floor = 0.0 if is_rigid(rotor.structure) else 1.0 / SHAFT_SCALE_LIMIT
    gammas, values = _adaptive_scan(
        lambda g: inertia_roots_many(rotor, states, g, vectors=True),
        rotor.structure.mass(), gammas, floor)
    samples = len(gammas)
    names = rotor.names
    positions = list(rotor.positions)
    found = []
    # a shaft's branch whose roots stay below FAINT/SHAFT_SCALE_LIMIT at both ends of an
    # interval cannot cross there with μ_c ≤ SHAFT_SCALE_LIMIT (its root at the crossing
    # would have to exceed both ends' twofold): not refined, as it would not be reported
    faint = 0.0 if is_rigid(rotor.structure) else FAINT / SHAFT_SCALE_LIMIT
    for branch in range(values.shape[1]):
        im = values[:, branch].imag
        size = np.abs(values[:, branch])
        for k in range(samples - 1):
            if not (im[k] == 0 or im[k] * im[k + 1] < 0):
                continue
            if max(size[k], size[k + 1]) < faint:
                continue
            crossing = _refine(rotor, states, gammas[k], gammas[k + 1], values[k, branch],
                               values[k + 1, branch], positions, names)
            if crossing is not None and not any(_same(crossing, c) for c in found):
                found.append(crossing)
    if not is_rigid(rotor.structure):
        found = [c for c in found if c.inertia_scale <= SHAFT_SCALE_LIMIT]
    found.sort(key=lambda c: (c.inertia_scale, c.whirl_ratio))
    low_scale = _probed(rotor, states, found, whirl_range, positions, names)
    return ([low_scale] if low_scale is not None else []) + found


def _probed(rotor, states, found, whirl_range, positions, names):
    """The probe below the smallest crossing (:mod:`.probe`): a crossing with μ_c = 0 (the
    rotor whirls at every inertia scale below the first crossing) when it is unstable."""
    mu = probe_scale([c.inertia_scale for c in found])
    p = probe(rotor, states, mu, whirl_range)
    if not p.unstable:
        return None
    sh = shape(p.vector, positions, names, rotor.structure)
    after = (f"; a crossing at μ_c = {found[0].inertia_scale:.4g} ({found[0].label}) may "
             "bound a stable range above it" if found else "")
    note = (f"unstable for every inertia scale: already at μ = {mu:.3g} a {sh['label']} "
            f"mode whirling at γ = {p.whirl_ratio:.3f} grows at {p.growth_rate:.3g} per "
            f"radian (the massless journal is unstable){after}")
    return ModeCrossing(0.0, p.whirl_ratio, float(p.whirl_ratio * states.omega / (2 * math.pi)),
                        sh["label"], sh, p.vector, note)


def _refine(rotor, states, low, high, nu_low, nu_high, positions, names):
    """The crossing of one branch between two scan points: Brent on Im of the root nearest
    the branch's linear interpolation between its values at the ends (two close roots keep
    their own references); None unless the root found is real and > 0."""
    def nearest(g, vectors=False):
        nu, vec = inertia_roots(rotor, states, g, vectors=vectors)
        ref = nu_low + (g - low) / (high - low) * (nu_high - nu_low)
        j = int(np.argmin(np.abs(nu - ref)))
        return nu[j], (vec[:, j] if vectors else None)

    try:
        g = brentq(lambda x: nearest(x)[0].imag, low, high, xtol=WHIRL_TOLERANCE)
    except ValueError:
        return None
    root, q = nearest(g, vectors=True)
    if not (abs(root.imag) <= REAL_ROOT * abs(root) and root.real > 0):
        return None
    sh = shape(q, positions, names, rotor.structure)
    return ModeCrossing(1.0 / root.real, float(g), float(g * states.omega / (2 * math.pi)),
                        sh["label"], sh, q)


def _same(a: ModeCrossing, b: ModeCrossing) -> bool:
    return (abs(a.whirl_ratio - b.whirl_ratio) <= 1e3 * WHIRL_TOLERANCE
            and abs(a.inertia_scale / b.inertia_scale - 1) <= 1e-6)


def by_mode(found: list) -> dict:
    """label → the crossing with the smallest μ_c among those with that label."""
    out: dict = {}
    for c in found:
        if c.label not in out or c.inertia_scale < out[c.label].inertia_scale:
            out[c.label] = c
    return out


#: half-width of the whirl-ratio window of a local search's Krylov spaces (their shift sits
#: over the start, a quarter of the window's width into the right half plane) [-]
LOCAL_WINDOW = 0.05
#: Newton steps on the whirl ratio before a local search gives up (the caller then scans)
LOCAL_STEPS = 12
#: step of the central difference for dν/dγ on the Krylov spaces [-]
SLOPE_STEP = 1e-6


def local_crossing(rotor: RotorCase, states: SpeedStates, near: ModeCrossing,
                   direct: bool = False) -> Optional[ModeCrossing]:
    """The crossing Im ν(γ) = 0 of the root branch through the crossing ``near`` (of a nearby
    speed, or of the same mode on another grid), by Newton's method on the whirl ratio; None
    when it does not converge in :data:`LOCAL_STEPS` steps, leaves the whirl range, or ends
    on a root that is not real and > 0 (the caller then computes every crossing,
    :func:`crossings`, which also decides between branches: this search follows one).

    For the onset's refinement, where one mode is followed from speed to speed.  Each
    bearing's Z̄(iγ) comes from a Krylov space on one LU with its shift over the start
    (:class:`~gfbopt.linear.krylov.ShiftedImpedance` on ±:data:`LOCAL_WINDOW`, a new one
    when a step leaves half of it), converged to its tolerance (1e-11) at every γ used, and
    dν/dγ from a central difference on it; the branch is the root whose shape is nearest the
    previous step's (``near``'s at first).
    The search stops when the Newton step is at most :data:`WHIRL_TOLERANCE` (the scan's own
    tolerance on γ, by Brent's method), so the crossing is the scan's on the same branch to
    ~1e-10 in γ and μ_c, for one LU and a few block steps per bearing instead of a converged
    space over the whole whirl range, the scan's refinements and the probe.

    ``direct``: each bearing's Z̄ from one direct LU at the start and its Taylor series
    instead (:class:`~gfbopt.rotor.reduced.TaylorImpedance`: a few solves where a Krylov
    space takes 6–7 block steps; the refinement's own search, :meth:`gfbopt.rotor.system.
    SpeedLine.follow_from`), accepted at every γ used by its last terms (≤ 1e-11 of Z̄);
    None when a point is beyond its reach (the caller then makes the Krylov search)."""
    if not (near.inertia_scale > 0 and states.ok):
        return None
    low, high = states.states[0].whirl_range
    gamma, shape_ref = float(near.whirl_ratio), np.asarray(near.vector, dtype=complex)
    mass = rotor.structure.mass()
    models, centre = None, math.nan
    for _ in range(LOCAL_STEPS):
        if not low <= gamma <= high:
            return None
        points = (gamma - SLOPE_STEP, gamma, gamma + SLOPE_STEP)
        if direct:
            try:
                models = models or [TaylorImpedance(st.linearisation, gamma)
                                    for st in states.states]
            except RuntimeError:                 # A + iγ B exactly singular
                return None
            if not all(m.evaluate(g)[1] for m in models for g in points):
                return None
        elif models is None or abs(gamma - centre) > 0.5 * LOCAL_WINDOW:
            window = (max(gamma - LOCAL_WINDOW, 0.5 * gamma), gamma + LOCAL_WINDOW)
            try:
                models = [ShiftedImpedance(st.linearisation, window) for st in states.states]
            except RuntimeError:                 # A + s0 B exactly singular
                return None
            centre = gamma
        if not direct and not all(m.converge(points[1:2]).all() for m in models):
            return None                          # ±1e-6 converge with it
        roots = [_local_roots(rotor, states, models, g) for g in points]
        # the branch: the root whose shape q̂ is nearest the previous one's (the largest
        # mass-weighted MAC), not the nearest ν: near γ = 1/2 two forward modes cross the
        # axis with nearly equal μ_c, 1e-3 apart in γ
        vectors = roots[1][1]
        j = int(np.argmax(mass_mac(mass, shape_ref[:, None], vectors)[0]))
        nu = roots[1][0][j]
        left, right = (r[0][np.argmin(np.abs(r[0] - nu))] for r in (roots[0], roots[2]))
        slope = (right - left) / (2 * SLOPE_STEP)
        if not (math.isfinite(slope.imag) and slope.imag != 0):
            return None
        step = -nu.imag / slope.imag
        if abs(step) <= WHIRL_TOLERANCE:
            nu_star = (nu + slope * step).real
            gamma += step
            if not (nu_star > 0 and low <= gamma <= high):
                return None
            q = roots[1][1][:, j]
            sh = shape(q, rotor.positions, rotor.names, rotor.structure)
            return ModeCrossing(1.0 / nu_star, float(gamma),
                                float(gamma * states.omega / (2 * math.pi)), sh["label"], sh, q)
        gamma, shape_ref = gamma + step, vectors[:, j]
    return None


def _local_roots(rotor, states, models, gamma: float) -> tuple[np.ndarray, np.ndarray]:
    """(ν, eigenvectors) of :func:`inertia_roots` with each bearing's Z̄ from ``models``."""
    n = rotor.structure.size
    kb = np.zeros((n, n), dtype=complex)
    for t, st, m in zip(rotor.transforms, states.states, models):
        kb += t.T @ (st.scale * m.evaluate(gamma)[0]) @ t
    return inertia_roots(rotor, states, gamma, _with_shaft(rotor, kb, gamma * states.omega))
