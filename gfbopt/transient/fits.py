"""Growth rates and verdicts of journal orbits (stable, unstable, limit cycle, contact).

A small kick excites the rotor's whirling mode and decaying pressure modes; the matrix-pencil
fit of the orbit resolves them all at once, so the rotor mode's growth rate is read after a
few revolutions without waiting for the amplitude to double or halve (``docs/PHYSICS.md``,
"Rotor dynamics").  Growth rates are per radian of shaft rotation.
"""
from __future__ import annotations

import math

import numpy as np

#: The verdicts an orbit can receive.
VERDICTS = ("stable", "unstable", "limit cycle", "contact")


def fit_growth_rate(tau: np.ndarray, dx: np.ndarray, dy: np.ndarray,
                    max_modes: int = 10, rank_tolerance: float = 1e-5,
                    whirl_band: tuple = (0.02, 3.0)) -> tuple[float, float]:
    """Growth rate σ [1/rad] and whirl ratio of the dominant whirling mode of an orbit.

    Matrix-pencil fit (Hua & Sarkar, IEEE Trans. ASSP 38 (1990) 814) of both coordinates of
    the deviation from equilibrium as one sum of damped exponentials e^{s τ}: the model order
    is the numerical rank of the stacked Hankel matrices, so the decaying pressure modes the
    kick excites are fitted rather than biasing the rotor mode, and no spurious roots appear.
    The rotor mode is the whirling mode (``whirl_band`` on |Im s|) with the largest amplitude
    at the end of the window; its σ is returned with its whirl ratio |Im s|.
    """
    n = tau.size
    if n < 12:
        return math.nan, math.nan
    d = tau[1] - tau[0]
    signals = []
    for sgl in (dx, dy):
        scale = np.abs(sgl).max()
        if np.isfinite(scale) and scale > 0:
            signals.append(sgl / scale)
    if not signals:
        return math.nan, math.nan
    pencil = n // 3
    hankel = np.vstack([np.lib.stride_tricks.sliding_window_view(sgl, pencil + 1)
                        for sgl in signals])
    _, sv, vh = np.linalg.svd(hankel, full_matrices=False)
    rank = int(min(max_modes, np.sum(sv > rank_tolerance * sv[0])))
    if rank == 0:
        return math.nan, math.nan
    v = vh[:rank].conj().T                       # (pencil + 1, rank)
    z = np.linalg.eigvals(np.linalg.pinv(v[:-1]) @ v[1:])
    z = z[np.abs(z) > 1e-12]
    modes = np.log(z.astype(complex)) / d
    # a physical mode neither grows by e^3 per radian nor sits near the Nyquist frequency
    modes = modes[(modes.real < 3.0) & (np.abs(modes.imag) < 0.5 * math.pi / d)]
    if modes.size == 0:
        return math.nan, math.nan
    # amplitudes of each mode in each signal (least squares on the Vandermonde basis)
    basis = np.exp(np.outer(tau - tau[0], modes))
    amps = np.zeros(modes.size)
    for sgl in signals:
        c, *_ = np.linalg.lstsq(basis, sgl.astype(complex), rcond=None)
        amps += np.abs(c * np.exp(modes * (tau[-1] - tau[0])))
    whirling = (np.abs(modes.imag) >= whirl_band[0]) & (np.abs(modes.imag) <= whirl_band[1])
    if not whirling.any():
        return math.nan, math.nan
    k = np.flatnonzero(whirling)[np.argmax(amps[whirling])]
    return float(modes[k].real), float(abs(modes[k].imag))


def classify(tau, dx, dy, contact, settle, kick, growth_tolerance: float = 2e-5,
             cycle_amplitude: float = 0.05):
    """Fit each orbit's growth rate and give its verdict (stable, unstable, limit cycle,
    contact).

    A growth rate within ±``growth_tolerance`` [1/rad] with a final orbit larger than
    ``cycle_amplitude`` (clearances) is a limit cycle: the envelope is flat at a finite size.
    A large orbit shrinking towards such a cycle from outside has a negative fitted rate but
    a final amplitude that stays large, so it is called a limit cycle too, not stable.
    """
    batch = dx.shape[0]
    growth = np.full(batch, np.nan)
    whirl = np.full(batch, np.nan)
    amp = np.full(batch, np.nan)
    verdicts = []
    start = 2 * math.pi * settle
    for b in range(batch):
        valid = np.isfinite(dx[b])
        # fit at most the last 10 revolutions: the dominant mode is settled by then, and the
        # matrix pencil's cost grows with the square of the window
        window = valid & (tau >= start)
        if window.any():
            window &= tau >= tau[window].max() - 20 * math.pi
        r = np.hypot(dx[b], dy[b])
        last = valid & (tau >= tau[valid].max() - 4 * math.pi)
        amp[b] = float(r[last].max()) if last.any() else math.nan
        if contact[b]:
            verdicts.append("contact")
            growth[b] = math.inf
            continue
        growth[b], whirl[b] = fit_growth_rate(tau[window], dx[b][window], dy[b][window])
        # envelope trend in the last part of the run: ratio of peak radii
        half = valid & (tau >= tau[valid].max() - 8 * math.pi) & (tau < tau[valid].max() - 4 * math.pi)
        earlier = float(r[half].max()) if half.any() else amp[b]
        flat = abs(math.log(max(amp[b], 1e-300) / max(earlier, 1e-300))) < 0.05
        if amp[b] > cycle_amplitude and (flat or growth[b] < 0):
            verdicts.append("limit cycle")
        elif growth[b] > growth_tolerance or (growth[b] > 0 and amp[b] > cycle_amplitude):
            verdicts.append("unstable")
        elif growth[b] < -growth_tolerance:
            verdicts.append("stable")
        else:
            verdicts.append("stable" if growth[b] <= 0 else "unstable")
    return growth, whirl, amp, verdicts
