"""Implicit (BDF) integration of the same transient model, one rotor at a time.

The right-hand side is :class:`gfbopt.transient.system.RightHandSide` (one physics); this module only
flattens a rotor's state to a vector y = (Φ, X, Y, U, V) and gives scipy's BDF a sparse
Jacobian: grouped finite differences on the exact sparsity pattern of the stencil, plus the
two dense rows ∂(U', V')/∂Φ written analytically (left to finite differences they would make
every Φ column its own group).

When it wins (benchmarks/bench_transient.py, 72 × 20): the rigid bearing, whose Jacobian is the
five-point stencil (12 colour groups) — BDF takes far larger steps than RK4's stability limit.
With the simple foil the axial-mean coupling widens the pattern to three whole θ rows (~75
groups) and the batched RK4 engine is as fast or faster; the beam couples every row to every
row, so it is RK4 only.  Supported here: rigid and simple (axial-mean law, full-film force),
and the simple foil with structural damping (η > 0): then the foil deflection W is a state, one
per θ row (:mod:`.foil_state`), H = H_r + W no longer depends on Φ, and the pattern is the
five-point stencil plus each node's three W rows (the W rows see their own row of Φ).
"""
from __future__ import annotations

import math
import time
from typing import Optional

import numpy as np
import scipy.sparse as sp
from scipy.integrate import solve_ivp

from ..errors import ParameterError
from ..threads import single_threaded
from .result import OrbitBatch, finish_orbits
from .system import RightHandSide, State, TransientModel, equilibrium_state, pressure_and_film


def greedy_column_groups(pattern: sp.csc_matrix) -> np.ndarray:
    """Group columns that share no row (Curtis–Powell–Reid), greedily; returns a group index
    per column.  Columns of one group can be perturbed together in finite differences."""
    pattern = pattern.tocsc()
    n_rows, n_cols = pattern.shape
    groups = np.full(n_cols, -1)
    used_rows: list = []                       # per group: boolean mask of rows touched
    for col in range(n_cols):
        rows = pattern.indices[pattern.indptr[col]:pattern.indptr[col + 1]]
        for g, mask in enumerate(used_rows):
            if not mask[rows].any():
                mask[rows] = True
                groups[col] = g
                break
        else:
            mask = np.zeros(n_rows, dtype=bool)
            mask[rows] = True
            used_rows.append(mask)
            groups[col] = len(used_rows) - 1
    return groups


class FlatRotor:
    """One rotor of mass M̄ as y' = f(y), y = (Φ.ravel(), X, Y, U, V), with its Jacobian."""

    def __init__(self, tm: TransientModel, mass: float):
        tm.law.check_engine("bdf", damped=tm.foil_state is not None)
        if tm.gumbel:
            raise ParameterError("method", "bdf", "supports the full-film force only "
                                 "(subambient='full'); use method='rk4' with the Gümbel force")
        self.tm = tm
        self.rhs = RightHandSide(tm, np.array([float(mass)]))
        self.m, self.nzn = tm.shape
        self.n_phi = self.m * self.nzn
        self.damped = tm.foil_state is not None       # W per θ row after Φ (module doc)
        self.n_w = self.m if self.damped else 0
        self.n = self.n_phi + self.n_w + 4
        start = self.n_phi + self.n_w
        self.ix, self.iy, self.iu, self.iv = range(start, start + 4)
        self.evaluations = 0
        self._build_pattern()

    def unpack(self, y: np.ndarray) -> State:
        w = y[self.n_phi:self.ix].reshape(1, self.m).copy() if self.damped else None
        return State(y[:self.n_phi].reshape(1, self.m, self.nzn).copy(), y[self.ix:self.ix + 1],
                     y[self.iy:self.iy + 1], y[self.iu:self.iu + 1], y[self.iv:self.iv + 1], w)

    @staticmethod
    def pack(s: State) -> np.ndarray:
        foil = [] if s.w is None else [s.w.ravel()]
        return np.concatenate([s.phi.ravel()] + foil + [s.x, s.y, s.u, s.v])

    def __call__(self, t, y):
        self.evaluations += 1
        return self.pack(self.rhs(self.unpack(y)))

    def _live_rows(self) -> np.ndarray:
        return np.flatnonzero(~self.tm.ambient)        # not the seam or pad-end rows

    def _build_pattern(self) -> None:
        m, nzn, tm = self.m, self.nzn, self.tm
        node = np.arange(self.n_phi).reshape(m, nzn)
        rows, cols = [], []
        jj = np.arange(1, nzn - 1)
        for i in self._live_rows():
            if tm.periodic:
                neighbour_rows = [(i - 1) % m, i, (i + 1) % m]
            else:
                neighbour_rows = [r for r in (i - 1, i, i + 1) if 0 <= r < m]
            for j in jj:
                r = node[i, j]
                if tm.foil == "rigid" or self.damped:
                    nb = [node[a, j] for a in neighbour_rows] + [node[i, j - 1], node[i, j + 1]]
                    if self.damped:                       # the film of the three rows
                        nb += [self.n_phi + a for a in neighbour_rows]
                else:                                     # P on a row depends on its mean
                    nb = [node[a, k] for a in neighbour_rows for k in jj]
                rows += [r] * (len(nb) + 2)
                cols += nb + [self.ix, self.iy]
        if self.damped:               # W' of row i: its own Φ, W and (through H_r) X, Y
            for i in range(m):
                nb = [node[i, k] for k in jj] + [self.ix, self.iy] \
                    if i in self._live_rows() else []
                rows += [self.n_phi + i] * (len(nb) + 1)
                cols += nb + [self.n_phi + i]
        rows += [self.ix, self.iy, self.iu, self.iu, self.iv, self.iv]
        cols += [self.iu, self.iv, self.ix, self.iy, self.ix, self.iy]
        pattern = sp.csc_matrix((np.ones(len(rows)), (rows, cols)), shape=(self.n, self.n))
        pattern.data[:] = 1.0
        self.fd_pattern = pattern
        self.groups = greedy_column_groups(pattern)
        self.n_groups = int(self.groups.max()) + 1
        coo = pattern.tocoo()
        self._fd_rows, self._fd_cols = coo.row, coo.col
        inner = np.zeros((m, nzn), dtype=bool)
        inner[self._live_rows(), 1:-1] = True
        self._inner = np.flatnonzero(inner.ravel())
        # columns of the analytic force rows: Φ at the live interior nodes (then W)
        self._dense_cols = np.concatenate([self._inner, self.n_phi + self._live_rows()]) \
            if self.damped else self._inner

    def force_rows(self, y: np.ndarray) -> np.ndarray:
        """∂(U', V')/∂Φ at the live interior nodes, then (damped) ∂(U', V')/∂W on the live
        rows: (2, len(self._dense_cols)), analytically (module doc)."""
        tm = self.tm
        s = self.unpack(y)
        hr = 1.0 + tm.bore - s.x[0] * tm.cos - s.y[0] * tm.sin
        zw = tm.z_weight
        total = zw.sum()
        if self.damped:               # P = Φ/H, H = H_r + W: ∂P/∂W = −Φ/H²
            h = hr + s.w[0]
            g = zw[None, 1:-1] / h[:, None]
            g_w = -(s.phi[0][:, 1:-1] @ zw[1:-1]) / (h * h)
        elif tm.foil == "rigid":
            g = zw[None, 1:-1] / hr[:, None]
        else:
            sc = tm.compliance_rows
            c = (zw[0] + zw[-1]) / total
            phit = (s.phi[0][:, 1:-1] @ zw[1:-1]) / total
            b = hr + sc * (c - 1.0)
            root = np.sqrt(b * b + 4 * sc * phit)
            a = 0.5 * (b + root)
            da = sc / root
            if tm.compression_only:
                on_bumps = a > hr
                a = np.where(on_bumps, a, hr)
                da = np.where(on_bumps, da, 0.0)
            g = zw[None, 1:-1] * (1.0 / a - phit * da / (a * a))[:, None]
        w = tm.theta_weight[:, None] / self.rhs.mass_load[0]
        rows = self._live_rows()
        fx = (-(tm.cos[:, None] * w) * g)[rows]
        fy = (-(tm.sin[:, None] * w) * g)[rows]
        if not self.damped:
            return np.vstack([fx.ravel(), fy.ravel()])
        fx_w = (-(tm.cos * w[:, 0]) * g_w)[rows]
        fy_w = (-(tm.sin * w[:, 0]) * g_w)[rows]
        return np.vstack([np.concatenate([fx.ravel(), fx_w]), np.concatenate([fy.ravel(), fy_w])])

    def jacobian(self, t, y) -> sp.csc_matrix:
        """Grouped finite differences on the pattern + the analytic force rows."""
        f0 = self(t, y)
        steps = math.sqrt(np.finfo(float).eps) * np.maximum(1.0, np.abs(y))
        df = np.empty((self.n_groups, self.n))
        for k in range(self.n_groups):
            mask = self.groups == k
            yk = y.copy()
            yk[mask] += steps[mask]
            steps[mask] = yk[mask] - y[mask]
            df[k] = self(t, yk) - f0
        vals = df[self.groups[self._fd_cols], self._fd_rows] / steps[self._fd_cols]
        jac = sp.coo_matrix((vals, (self._fd_rows, self._fd_cols)), shape=(self.n, self.n))
        fr = self.force_rows(y)
        cols = self._dense_cols
        dense = sp.coo_matrix((fr.ravel(), (np.repeat([self.iu, self.iv], cols.size),
                                            np.tile(cols, 2))), shape=(self.n, self.n))
        return (jac + dense).tocsc()

    def min_film(self, y: np.ndarray) -> float:
        s = self.unpack(y)
        _, h = pressure_and_film(s.phi, s.x, s.y, self.tm, deflection=s.w)
        return float(h.min())


@single_threaded
def integrate_bdf(tm: TransientModel, mass: np.ndarray, revolutions: float, *,
                  kick: float, initial: Optional[State], sample_every: float,
                  contact_film: float, settle: float, rtol: float = 1e-6,
                  atol: float = 1e-9, progress=None) -> OrbitBatch:
    """The same contract as :func:`gfbopt.transient.orbit.integrate_orbits`, with scipy's BDF
    (variable step, ``rtol``/``atol``) on each rotor in turn.  A rotor whose integration
    fails ends the run with ``success=False`` and scipy's message; rotors already done are
    kept."""
    t0 = time.perf_counter()
    start = initial if initial is not None else equilibrium_state(tm, mass.size)
    if initial is None:
        start.u[:] = kick / math.sqrt(2)
        start.v[:] = kick / math.sqrt(2)
    t_end = 2 * math.pi * revolutions
    tau = np.arange(0.0, t_end + 1e-9, sample_every)
    x = np.full((mass.size, tau.size), np.nan)
    y = np.full_like(x, np.nan)
    hmin = np.full_like(x, np.nan)
    contact = np.zeros(mass.size, dtype=bool)
    contact_tau = np.full(mass.size, np.nan)
    evaluations = 0
    failure = ""
    for b, mm in enumerate(mass):
        rotor = FlatRotor(tm, mm)
        y0 = rotor.pack(start.take(slice(b, b + 1)))

        def touch(t, yy, rotor=rotor):
            return rotor.min_film(yy) - contact_film

        touch.terminal = True
        touch.direction = -1
        sol = solve_ivp(rotor, (0.0, t_end), y0, method="BDF", t_eval=tau, rtol=rtol,
                        atol=atol, jac=rotor.jacobian, events=touch)
        evaluations += rotor.evaluations
        k = sol.t.size
        x[b, :k] = sol.y[rotor.ix]
        y[b, :k] = sol.y[rotor.iy]
        hmin[b, :k] = [rotor.min_film(sol.y[:, i]) for i in range(k)]
        if progress is not None:
            progress((b + 1) / mass.size)
        if sol.status == 1 and sol.t_events[0].size:
            contact[b] = True
            contact_tau[b] = float(sol.t_events[0][0])
        elif sol.status != 0:
            failure = f"BDF failed for rotor {b} (M̄ = {mm:.6g}): {sol.message}"
            break
    return finish_orbits(tm, tau, x, y, hmin, contact, contact_tau, mass, settle=settle,
                         kick=kick, time_step=math.nan, evaluations=evaluations, started=t0,
                         revolutions=revolutions, method="bdf", success=not failure,
                         message=failure)
