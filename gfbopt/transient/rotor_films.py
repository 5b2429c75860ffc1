"""Both bearings' films of the rotor transient in one fused evaluation (numpy).

The rotor's right-hand side (:class:`.rotor_system.RotorRightHandSide`) spends its time in
the films: the recovery of P and H from Φ = P H, the flux residual R(P, H), the film force
and the Kelvin–Voigt foil rate.  Each is a handful of numpy calls on arrays of a few
thousand nodes, so the cost is the number of calls, not the arithmetic (≈ 2–4 µs a call at
72 × 20).  :class:`FusedFilms` evaluates them for every bearing of every run at once — one
(B·K, m, n_z + 1) array, with the per-bearing numbers (compliance rows S, bore, bearing
number Λ, relaxation time τ_f, the time scale 2Λ ω_ref/ω_m) as per-row coefficients — and
shares the recovery between the force, the flux and the foil:

* the row film a (rigid H_r, the axial-mean law's closed form, or H_r + W of the damped
  foil) and P = Φ/a once; the axial mean Σ w P once, for the force and the foil's target
  (the axial-mean law: its recovery's row means Φ̄ = Σ_inner w Φ / Σ w give the force
  too, Σ w P = Φ̄ Σw / a + w_0 + w_n on a live row, with no pass over P);
* the flux R of :func:`.system.flux_residual` with its row coefficients (H³ over ΔZ²,
  the face means of H³ over Δθ², Λ/Δθ) already divided by the time scale, written into the
  output rows; the advection as the central difference of P H (the two face sums' shared
  term cancels exactly); only the interior columns are formed;
* the force −∬ (P − 1)(cos θ, sin θ) as (Σ w P − Σ w) @ [w_θ cos θ, w_θ sin θ].

It serves the films whose H is uniform along each θ row (rigid and axial-mean laws, undamped
or with the row foil state) and bearings of one grid, film and law; others (local law,
beam) keep the one-bearing kernels bearing by bearing.  The answers equal those kernels' to
round-off (tests/unit/test_rotor_films.py).
"""
from __future__ import annotations

from typing import Optional

import numpy as np

from .rotor_running import speed_table
from .system import TransientModel, rigid_film

FUSED_LAWS = ("rigid", "simple")


def fusable(model) -> bool:
    """True when :class:`FusedFilms` serves every bearing of ``model`` (module docstring)."""
    first = model.bearings[0].tm
    for b in model.bearings:
        t = b.tm
        fs = t.foil_state
        if (t.law.name not in FUSED_LAWS or t.foil_data is not None or t.gumbel
                or (fs is not None and fs.layout != "rows")):
            return False
        if not (t.periodic or (t.ambient[0] and t.ambient[-1])):
            return False            # a seamed film's end rows are at ambient (see evaluate)
        if not (t.shape == first.shape and t.periodic == first.periodic
                and t.law.name == first.law.name and t.compression_only == first.compression_only
                and (fs is None) == (first.foil_state is None)
                and t.dtheta == first.dtheta and t.dz == first.dz
                and all(np.array_equal(getattr(t, n), getattr(first, n))
                        for n in ("theta_weight", "z_weight", "ambient"))):
            return False
    return True


class FusedFilms:
    """The films of every bearing of a batch of ``size`` runs, evaluated together.

    ``film_divisor`` and ``foil_factor`` per bearing are the rotor system's (2Λ_m ω_ref/ω_m
    and ω_m/ω_ref); ``base_lambda`` per bearing is Λ at ω = ω_ref.

    Bearings that carry a running line (``BearingFilm.running``, a heated rotor's ramp,
    :mod:`.rotor_running`) get, at each evaluation's speed, the film offset
    H_r → H_r − (c − c_run)/c and the viscosity ratio f = μ/μ_ref: Λ → f Λ in the Couette
    term and in the time scale 2Λ, so the diffusion coefficients (H³ terms) are divided by
    f and the advection is unchanged; S stays the cold-c one (exact, see that module).
    Without one the evaluation is today's, operation for operation.
    """

    def __init__(self, model, size: int, film_divisor, foil_factor, base_lambda):
        tms = [b.tm for b in model.bearings]
        tm = tms[0]
        k = len(tms)
        self.k, self.size, self.n = k, size, int(np.prod(tm.shape))
        self.shape = tuple(tm.shape)
        self.periodic, self.law = tm.periodic, tm.law.name
        self.compression_only = tm.compression_only
        self.damped = tm.foil_state is not None
        self.shared_mean = self.law == "simple" and not self.damped
        self.ambient = tm.ambient
        m = self.shape[0]
        div = np.asarray(film_divisor, dtype=float)
        tile = lambda per: np.tile(np.asarray(per, dtype=float), (size,) + (1,) * (  # noqa: E731
            np.ndim(per) - 1))
        # θ from each bearing's load line: the same grid angles (seam films) or not (periodic)
        self.same_angles = all(np.array_equal(t.cos, tm.cos) and np.array_equal(t.sin, tm.sin)
                               for t in tms)
        trig = -np.array([[t.cos, t.sin] for t in tms])                      # (K, 2, m)
        self.trig = trig[0] if self.same_angles else np.tile(trig, (size, 1, 1))
        self.base = tile([1.0 + t.bore for t in tms])                          # (N, m)
        self.s = tile([t.compliance_rows for t in tms])                        # (N, m)
        self.axial = tile((0.5 / (tm.dz * tm.dz)) / div)[:, None]              # (N, 1)
        self.face = tile((0.25 / (tm.dtheta * tm.dtheta)) / div)[:, None]      # (N, 1)
        self.advect = tile(np.asarray(base_lambda) * (0.5 / tm.dtheta) / div)  # (N,)
        zw = tm.z_weight
        self.zw, self.zw_sum = zw, float(zw.sum())
        ends = zw[[0, -1]].sum() / self.zw_sum
        self.zw_inner = np.concatenate([[0.0], zw[1:-1] / self.zw_sum, [0.0]])
        self.live = (~self.ambient).astype(float)
        # Σ_j w_j P_j of a row from Φ̄ = Σ_inner w_j Φ_j / Σ w (the recovery's own mean):
        # Φ̄ Σw / a + (w_0 + w_n) on a live row (P = 1 on the axial ends), Σ w at ambient
        self.pz_gain = self.zw_sum * self.live
        self.pz_fill = (self.zw_sum * ends) * self.live + self.zw_sum * self.ambient
        self.ambient_fill = (1.0 - ends) * self.ambient                       # (m,)
        self.s_ends, self.s4 = self.s * (ends - 1.0), 4.0 * self.s             # (N, m)
        self.s4_live, self.s4_fill = self.s4 * self.live, self.s4 * self.ambient_fill
        rows = -np.transpose(trig, (0, 2, 1)) * tm.theta_weight[:, None]      # (K, m, 2)
        self.force_rows = rows[0] if self.same_angles else np.tile(rows, (size, 1, 1))
        self.force_ends = self.zw_sum * self.force_rows.sum(axis=-2)           # Σ w (cos, sin)
        if self.damped:
            relax = [t.foil_state.relaxation_time for t in tms]
            self.foil_scale = tile(np.asarray(foil_factor) / np.asarray(relax))[:, None]
            self.live_s = self.s * (~self.ambient)                             # S, 0 at ambient
            self.foil_gain = self.live_s / self.zw_sum
        big, rows, w = k * size, m + 2 if self.periodic else m, self.shape[1]
        # the per-row coefficients (1/H, H³, face sums of H³, H), then their scales
        self._coef = np.zeros((4, big, rows))
        self._scale = np.ones((4, big, 1))
        self._scale[1], self._scale[2] = self.axial, self.face
        self._spread = np.empty((4, big * rows, w))
        self._bufs = [np.zeros(big * rows * w) for _ in range(5)]
        self._edge_index = None
        self._mean, self._pz = np.empty((big, m)), np.empty((big, m))
        self._rows = np.empty((3, big, m))            # the axial-mean law's row buffers
        # the force from Φ̄ directly: f = [Σw(cos, sin) − fill @ rows] − (Φ̄/a) @ (gain rows)
        if self.same_angles:
            self.force_gain_rows = self.pz_gain[:, None] * self.force_rows    # (m, 2)
            self.force_const = self.force_ends - self.pz_fill @ self.force_rows
        self._interior = np.ones(self.shape)          # 1 at a film's interior nodes, else 0
        self._interior[:, [0, -1]] = 0.0
        self._interior[self.ambient, :] = 0.0
        #: the bearings' running lines (None: today's films)
        self.running = speed_table(model)
        if self.running is not None:                 # the diffusion scales at μ = μ_ref
            self._axial0 = self.axial[:, 0].reshape(size, k).copy()
            self._face0 = self.face[:, 0].reshape(size, k).copy()

    def evaluate(self, z: np.ndarray, xy: np.ndarray, speed, out: np.ndarray,
                 min_film: np.ndarray, max_deflection: Optional[np.ndarray]) -> np.ndarray:
        """Write dΦ/dτ and dW/dτ of every bearing into ``out`` (B, K, L); lower ``min_film``
        (B, K) and raise ``max_deflection`` (B, K, or None); return the film forces (B, K, 2)
        [non-dimensional].

        Every full-size step works on flat contiguous arrays of the (B·K, R, n_z + 1) films
        (R = m, or m + 2 with the periodic film's wrapped rows): a neighbour along Z is the
        next entry, along θ the entry n_z + 1 further; the values this forms across a row's
        end or a film's last row fall on boundary nodes, rows at ambient pressure or wrapped
        rows, all overwritten.  The per-row coefficients are spread over the nodes by one
        copy (broadcasting over rows of 21 nodes costs 3× a flat step).
        """
        nb, k, n = z.shape[0], self.k, self.n
        m, w = self.shape
        big = nb * k
        if big != self._coef.shape[1]:
            raise ValueError(f"a fused film evaluation of {big} films was built for "
                             f"{self._coef.shape[1]}")
        flat = z.reshape(big, -1)
        phi = flat[:, :n].reshape(big, m, w)
        hr = (np.dot(xy.reshape(big, 2), self.trig) if self.same_angles
              else np.einsum("ni,nim->nm", xy.reshape(big, 2), self.trig))
        hr += self.base
        if self.running is not None:                 # at the running condition of ``speed``
            self._at_speed(hr, speed, nb)
        # Φ̄ (B·K, m): the axial-mean law's recovery and the force share it
        mean = np.matmul(phi, self.zw_inner, out=self._mean) if self.shared_mean else None
        a = self._film(hr, mean, flat)
        ae = np.concatenate([a[:, -1:], a, a[:, :1]], axis=1) if self.periodic else a
        rows = ae.shape[1]
        coef, scale, spread = self._coef, self._scale, self._spread
        if isinstance(speed, float):
            np.multiply(self.advect, speed, out=scale[3, :, 0])
        else:
            scale[3, :, 0] = self.advect * np.repeat(speed, k)
        np.divide(1.0, ae, out=coef[0])
        np.multiply(ae, ae, out=coef[1])
        coef[1] *= ae
        np.add(coef[1, :, :-1], coef[1, :, 1:], out=coef[2, :, :-1])     # last face: 0
        coef[3] = ae
        coef *= scale                                # over the time scale 2Λ ω_ref/ω_m
        np.copyto(spread, coef.reshape(4, -1)[:, :, None])
        off = 1 if self.periodic else 0
        pf, p2, res, face, d = self._bufs
        pe = pf.reshape(big, rows, w)
        np.multiply(phi, spread[0].reshape(big, rows, w)[:, off:off + m], out=pe[:, off:off + m])
        pf[self._edges(big)] = 1.0                   # P = 1 on the axial ends and ambient rows
        if self.periodic:
            pe[:, 0], pe[:, -1] = pe[:, m], pe[:, 1]
        # the film force and the foil's target from one axial mean Σ w P (from Φ̄ and 1/a)
        if mean is not None and self.same_angles and not self.damped:
            pz = None                                # the force needs no Σ w P of its own
        elif mean is not None:
            pz = np.multiply(mean, coef[0, :, off:off + m], out=self._pz)
            pz *= self.pz_gain
            pz += self.pz_fill
        else:
            pz = np.dot(pe.reshape(-1, w), self.zw).reshape(big, rows)[:, off:off + m]
        if pz is None:
            forces = np.dot(np.multiply(mean, coef[0, :, off:off + m], out=self._pz),
                            self.force_gain_rows)
            np.subtract(self.force_const, forces, out=forces)
        else:
            forces = (np.dot(pz, self.force_rows) if self.same_angles
                      else np.einsum("nm,nmi->ni", pz, self.force_rows))
            np.subtract(self.force_ends, forces, out=forces)
        outflat = out.reshape(big, -1)
        if self.damped:
            slot = outflat[:, n:n + m]
            if self.compression_only:
                np.multiply(pz, 1.0 / self.zw_sum, out=slot)
                slot -= 1.0
                np.maximum(slot, 0.0, out=slot)
                slot *= self.live_s
            else:
                np.multiply(pz, self.foil_gain, out=slot)
                slot -= self.live_s
            slot -= flat[:, n:n + m]
            slot *= self.foil_scale
        # the flux residual over the time scale (axial, circumferential, advection)
        np.multiply(pf, pf, out=p2)
        np.subtract(p2[1:], p2[:-1], out=d[:-1])
        np.subtract(d[1:-1], d[:-2], out=res[1:-1])
        res *= spread[1].reshape(-1)
        np.subtract(p2[w:], p2[:-w], out=face[:-w])  # face[-w:] stays 0
        face *= spread[2].reshape(-1)
        res[w:] += face[w:]
        res[w:] -= face[:-w]
        pf *= spread[3].reshape(-1)                  # P H Λ/(2Δθ) over the time scale
        res[w:-w] -= pf[2 * w:]
        res[w:-w] += pf[:-2 * w]
        np.multiply(res.reshape(big, rows, w)[:, off:off + m], self._interior,   # 0 on the
                    out=outflat[:, :n].reshape(big, m, w))                        # boundary
        low = min_film.reshape(-1)
        np.minimum(low, a.min(axis=1), out=low)
        if max_deflection is not None:
            dfl = np.zeros(big) if self.law == "rigid" else (a - hr).max(axis=1)
            np.maximum(max_deflection, dfl.reshape(nb, k), out=max_deflection)
        return forces.reshape(nb, k, 2)

    def _at_speed(self, hr: np.ndarray, speed, nb: int) -> None:
        """Lower ``hr`` (B·K, m) by each bearing's offset δ(ω) and set the diffusion scales
        to their μ = μ_ref values times μ_ref/μ(ω) (class docstring)."""
        offset, inverse = self.running.at(speed)            # (K,) or (B, K)
        k = self.k
        hr.reshape(nb, k, -1)[...] -= offset[..., None]
        np.multiply(self._axial0, inverse, out=self._scale[1, :, 0].reshape(nb, k))
        np.multiply(self._face0, inverse, out=self._scale[2, :, 0].reshape(nb, k))

    def _edges(self, big: int) -> np.ndarray:
        """Flat indices of the boundary nodes (axial ends, ambient rows) of ``big`` films in
        the row layout of :meth:`evaluate` (kept for the batch size last seen)."""
        if self._edge_index is None or self._edge_index[0] != big:
            m, w = self.shape
            rows = m + 2 if self.periodic else m
            mask = np.zeros((big, rows, w), dtype=bool)
            real = mask[:, 1:-1] if self.periodic else mask
            real[:, :, 0] = real[:, :, -1] = True
            real[:, self.ambient, :] = True
            self._edge_index = (big, np.flatnonzero(mask))
        return self._edge_index[1]

    def _film(self, hr: np.ndarray, mean: np.ndarray, flat: np.ndarray) -> np.ndarray:
        """The row film a (B·K, m): H_r + W (damped), H_r (rigid), or the axial-mean law's
        closed form a² − b a − S Φ̃ = 0 (:meth:`gfbopt.physics.foil_laws.SimpleLaw.recover`),
        with Φ̃ from the row means ``mean`` = Σ_inner w Φ / Σ w."""
        m = self.shape[0]
        if self.damped:
            return hr + flat[:, self.n:self.n + m]
        if self.law == "rigid":
            return hr
        # 4 S Φ̃ = 4 S (live Φ̄ + fill H_r): Φ̃ of foil_recovery.row_mean_phi, rows at ambient
        # P̄ − 1 = 0; every product into the evaluation's own row buffers
        b = np.add(hr, self.s_ends, out=self._rows[0])
        disc = np.multiply(b, b, out=self._rows[1])
        term = np.multiply(self.s4_live, mean, out=self._rows[2])
        disc += term
        disc += np.multiply(self.s4_fill, hr, out=term)
        a = np.sqrt(disc, out=disc)
        a += b
        a *= 0.5
        if self.compression_only:
            np.maximum(a, hr, out=a)
        return a


class AtSpeed:
    """The one-bearing model seen by the flux kernel at the current bearing number: Λ is
    set per evaluation (a run-up changes it continuously, without rebuilding anything);
    every other attribute is the model's own."""

    def __init__(self, tm: TransientModel):
        self._tm = tm
        self.bearing_number = tm.bearing_number

    def __getattr__(self, name):
        return getattr(self._tm, name)


def largest_deflection(h: np.ndarray, x: np.ndarray, y: np.ndarray, tm: TransientModel):
    """Largest foil deflection W = H − H_r of each run [clearances]."""
    if tm.law.name == "rigid":
        return np.zeros(x.shape)
    hr = rigid_film(x, y, tm)                                     # (B, m), with the bore
    return (h - hr[:, :, None]).max(axis=(1, 2))
