"""What engineers read from a rotor transient: waterfall, synchronous and subsynchronous
components against speed, the speed where a subsynchronous line appears, and limit cycles.

Signals are the journal centre of one bearing, z = x + i y (global frame, µm), sampled
uniformly in time; a positive frequency is forward whirl (in the direction of rotation), a
negative one backward.  Conventions:

* **Synchronous (1×) component**, order-tracked: over each window a least-squares fit
  x ≈ x̄ + x_t (t − t̄) + Re(X̂ e^{iϑ}), the same for y, with ϑ the shaft angle (0 at the start of
  the run, the imbalance phase origin).  |X̂| is the 1× amplitude of x (zero to peak) and
  arg X̂ its phase: x peaks when ϑ = −arg X̂ (a phase lag of −arg X̂ behind the reference
  mark).  Exact for a changing speed, no spectral leakage at 1×.
* **Synchronous amplitude** (``sync_amplitude_um``): the major semi-axis of the 1× orbit
  ellipse, (|X̂ + iŶ| + |X̂ − iŶ|)/2 — the forward plus the backward circular radius
  (:func:`ellipse_radii`), the largest 1× excursion in any direction: what a probe orbit
  shows and what the linear imbalance response reports as ``amplitude_um``.
* **Amplitude spectrum** of a window: Hann window, zero-padded ×4 (the peak's scalloping loss
  ≤ 1 %), scaled so that a circular whirl A e^{iΩt} shows A at Ω/2π; the mean and the tracked
  1× component are removed first for the subsynchronous search.
* **Subsynchronous component**: the largest spectral peak with 0.05 ≤ |f|/f_shaft ≤ 0.95 of
  the window's mean shaft frequency; its amplitude [µm] and signed frequency [Hz].  A peak is
  a local maximum of the spectrum strictly inside the band (the band's largest value on its
  edge is the skirt of the 1× line or of the mean, not a whirl: then there is none, NaN); its
  frequency is refined inside ± one padded bin and stays in the band; its amplitude is the
  largest |transform| there (≥ 0 by definition; a parabola refines it only where it is
  concave with its vertex inside the scan).
* **Appearance speed**: the first window from which the subsynchronous amplitude stays above
  a threshold to the end of the record (a line that appears and persists, not a blip).
* **Separation in short windows**: the 1× and the subsynchronous peak's sinusoid are fitted
  together (least squares), so neither leaks into the other's amplitude.
* **Limit cycle** at constant speed: the subsynchronous orbit (tracked 1× and mean removed);
  its amplitude is the largest distance from the orbit's centre (zero to peak) over the
  last window of ``periods`` whirl periods, its frequency the spectral peak.  **Settled**
  when that amplitude differs from the previous window's by ≤ ``tolerance`` (default 1 %)
  relative — equivalently |growth| ≤ tolerance per window: a limit cycle still approaching
  from inside or outside is reported as not settled, with the measured change.
* **Whether there is a subsynchronous whirl at all** (:func:`limit_cycle`'s ``status``): only
  when the last window has a subsynchronous peak (above), whose amplitude is at least the
  threshold (the run-up's appearance threshold, default 2 % of the clearance) and at least
  :data:`NOISE_FACTOR` × the band's median spectral amplitude (the noise floor).  Otherwise
  the status is ``none`` with the reason, and amplitude, frequency, whirl ratio, change and
  settledness are NaN/None — never a ratio outside the band or the residual noise of a
  stable orbit read as a whirl.  With a whirl: ``limit cycle`` (settled), ``growing`` or
  ``decaying`` (not settled).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..rotor.modes import ellipse_radii

#: band of the subsynchronous search, |f| / f_shaft
SUB_BAND = (0.05, 0.95)
#: zero padding of the spectra
PADDING = 4
#: a subsynchronous peak is a whirl only this many times above the band's median spectral
#: amplitude (its noise floor); a pure tone's Hann skirt is ≥ 30 dB below its peak
NOISE_FACTOR = 5.0
#: status of a constant-speed orbit's subsynchronous whirl
NO_WHIRL, LIMIT_CYCLE, GROWING, DECAYING = "none", "limit cycle", "growing", "decaying"


def synchronous_fit(t: np.ndarray, signal: np.ndarray, angle: np.ndarray,
                    also_hz: float = math.nan) -> tuple:
    """(complex 1× amplitude X̂, fitted 1× part) of a real ``signal`` over its samples.

    With ``also_hz`` (a subsynchronous frequency found in the window) that sinusoid is fitted
    jointly, so that it does not leak into the 1× estimate over a short window."""
    tc = t - t.mean()
    columns = [np.ones_like(t), tc, np.cos(angle), np.sin(angle)]
    if math.isfinite(also_hz) and also_hz != 0:
        columns += [np.cos(2 * math.pi * also_hz * tc), np.sin(2 * math.pi * also_hz * tc)]
    basis = np.column_stack(columns)
    coef, *_ = np.linalg.lstsq(basis, signal, rcond=None)
    amp = complex(coef[2], -coef[3])
    return amp, basis[:, 2:4] @ coef[2:4]


def components(t: np.ndarray, x: np.ndarray, y: np.ndarray, angle: np.ndarray,
               shaft_hz: float) -> tuple:
    """(X̂, Ŷ 1× amplitudes, subsynchronous frequency [Hz], its amplitude, the orbit with
    the mean and 1× removed) of one window: 1× tracked, the subsynchronous peak found in the
    rest, then both fitted together and the peak re-read."""
    sx, px = synchronous_fit(t, x, angle)
    sy, py = synchronous_fit(t, y, angle)
    fs, _ = subsynchronous_peak(t, (x - px) + 1j * (y - py), shaft_hz)
    if math.isfinite(fs):
        sx, px = synchronous_fit(t, x, angle, abs(fs))
        sy, py = synchronous_fit(t, y, angle, abs(fs))
    rest = (x - px) + 1j * (y - py)
    fs, amp = subsynchronous_peak(t, rest, shaft_hz)
    return sx, sy, fs, amp, rest


def amplitude_spectrum(t: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(frequency [Hz], |Z| [units of z]) of a complex signal, Hann window, zero-padded,
    scaled so that A e^{iΩt} shows A at Ω/2π; frequencies sorted from negative to positive."""
    n = t.size
    dt = (t[-1] - t[0]) / (n - 1)
    w = np.hanning(n)
    spec = np.fft.fft((z - z.mean()) * w, PADDING * n) / w.sum()
    f = np.fft.fftfreq(PADDING * n, dt)
    order = np.argsort(f)
    return f[order], np.abs(spec[order])


@dataclass(frozen=True)
class Waterfall:
    """Amplitude spectra of one bearing's whirl against time and speed.

    frequency_hz (nf,) signed (+ forward); time_s, speed_rpm (nw,) at each window's centre;
    amplitude (nw, nf) [µm]; synchronous (nw, 2) complex 1× amplitudes of x and y [µm];
    sub_amplitude (nw,) [µm], sub_frequency_hz (nw,) signed (NaN: no peak inside the band);
    window_s [s]; hop_s [s] between window starts."""

    frequency_hz: np.ndarray
    time_s: np.ndarray
    speed_rpm: np.ndarray
    amplitude: np.ndarray
    synchronous: np.ndarray
    sub_amplitude: np.ndarray
    sub_frequency_hz: np.ndarray
    window_s: float
    hop_s: float = 0.0

    @property
    def sync_amplitude(self) -> np.ndarray:
        """(nw,) synchronous amplitude [µm] of each window: the major semi-axis of its 1×
        orbit ellipse (:func:`ellipse_radii`)."""
        return ellipse_radii(self.synchronous[:, 0], self.synchronous[:, 1])[2]

    def table(self):
        """One row per window: speed, synchronous amplitude (major semi-axis), 1× amplitude
        and phase of x and y, subsynchronous amplitude, frequency and whirl ratio (glossary
        names; the subsynchronous columns are empty where the window has no peak inside
        the band)."""
        import pandas as pd

        shaft = self.speed_rpm / 60.0
        return pd.DataFrame({
            "time_s": self.time_s, "speed_rpm": self.speed_rpm,
            "sync_amplitude_um": self.sync_amplitude,
            "sync_amplitude_x_um": np.abs(self.synchronous[:, 0]),
            "sync_phase_x_deg": np.degrees(np.angle(self.synchronous[:, 0])),
            "sync_amplitude_y_um": np.abs(self.synchronous[:, 1]),
            "sync_phase_y_deg": np.degrees(np.angle(self.synchronous[:, 1])),
            "sub_amplitude_um": self.sub_amplitude,
            "sub_frequency_hz": self.sub_frequency_hz,
            "sub_whirl_ratio": self.sub_frequency_hz / shaft})


def waterfall(t: np.ndarray, x: np.ndarray, y: np.ndarray, angle: np.ndarray,
              speed_rpm: np.ndarray, window_s: float, max_order: float = 2.5,
              overlap: float = 0.5) -> Waterfall:
    """The waterfall of a journal record (µm; module docstring): windows of ``window_s``
    seconds overlapping by ``overlap``, the last one ending at the record's end (so that the
    last row is the end of the run: a settled orbit's synchronous amplitude); spectra kept
    for |f| ≤ ``max_order`` × the highest shaft frequency (what the figure shows: memory
    bounded by windows × that band)."""
    good = np.isfinite(x) & np.isfinite(y)
    t, x, y, angle, speed_rpm = (a[good] for a in (t, x, y, angle, speed_rpm))
    dt = float(np.median(np.diff(t))) if t.size > 1 else math.nan
    n = int(round(window_s / dt)) if math.isfinite(dt) and dt > 0 else 0
    if n < 16 or t.size < n:
        empty = np.zeros((0,))
        return Waterfall(empty, empty, empty, np.zeros((0, 0)), np.zeros((0, 2), complex),
                         empty, empty, float(window_s))
    hop = max(1, int(round(n * (1.0 - overlap))))
    starts = range((t.size - n) % hop, t.size - n + 1, hop)
    fmax = max_order * float(np.max(speed_rpm)) / 60.0
    rows, times, speeds, syncs, sub_a, sub_f, freq = [], [], [], [], [], [], None
    for s in starts:
        sl = slice(s, s + n)
        tt, aa = t[sl], angle[sl]
        f, amp = amplitude_spectrum(tt, x[sl] + 1j * y[sl])
        if freq is None:       # one frequency axis (a record's last step may be shorter)
            keep = np.abs(f) <= fmax
            freq = f[keep]
        rows.append(amp[keep])
        shaft = float(np.mean(speed_rpm[sl])) / 60.0
        sx, sy, fs, asub, _ = components(tt, x[sl], y[sl], aa, shaft)
        times.append(float(tt.mean()))
        speeds.append(shaft * 60.0)
        syncs.append((sx, sy))
        sub_a.append(asub)
        sub_f.append(fs)
    return Waterfall(freq, np.array(times), np.array(speeds), np.array(rows),
                     np.array(syncs), np.array(sub_a), np.array(sub_f), float(window_s),
                     hop * dt)


def _band(f: np.ndarray, shaft_hz: float) -> np.ndarray:
    return (np.abs(f) >= SUB_BAND[0] * shaft_hz) & (np.abs(f) <= SUB_BAND[1] * shaft_hz)


def noise_floor(t: np.ndarray, z: np.ndarray, shaft_hz: float) -> float:
    """Median amplitude of the spectrum of ``z`` over the subsynchronous band [units of z]:
    the floor a subsynchronous peak must stand clearly above (:data:`NOISE_FACTOR`)."""
    f, amp = amplitude_spectrum(t, z)
    band = _band(f, shaft_hz)
    return float(np.median(amp[band])) if band.any() else math.nan


def subsynchronous_peak(t: np.ndarray, z: np.ndarray, shaft_hz: float) -> tuple:
    """(signed frequency [Hz], amplitude ≥ 0) of the largest peak in the subsynchronous band,
    or (nan, nan) when the band's largest value is not a local maximum strictly inside it
    (module docstring).  The frequency is refined to the maximum of the windowed transform
    (a fine scan of ± one padded bin, then a parabola where it is concave with its vertex
    inside the scan step: the single-tone estimate, well below the bin width), and kept in
    the band."""
    f, amp = amplitude_spectrum(t, z)
    band = _band(f, shaft_hz)
    if not band.any():
        return math.nan, math.nan
    k = np.flatnonzero(band)[np.argmax(amp[band])]
    # a peak has a neighbour inside the band on either side that is not above it
    if not (0 < k < f.size - 1 and band[k - 1] and band[k + 1]
            and amp[k] >= amp[k - 1] and amp[k] >= amp[k + 1]):
        return math.nan, math.nan
    bin_hz = f[1] - f[0]
    trial = f[k] + bin_hz * np.linspace(-1.0, 1.0, 21)
    trial = trial[_band(trial, shaft_hz)]
    w = np.hanning(t.size)
    zc = (z - z.mean()) * w
    tc = t - t[0]
    # the trial frequencies are equally spaced: e^{-2πi f_j t} = e^{-2πi f_0 t} ρ^j with
    # ρ = e^{-2πi Δf t} (two exponentials of the record instead of one per trial; equal to
    # round-off)
    step = bin_hz / 10.0
    term = zc * np.exp(-2j * math.pi * trial[0] * tc)
    turn = np.exp(-2j * math.pi * step * tc)
    sums = np.empty(trial.size, dtype=complex)
    for j in range(trial.size):
        sums[j] = term.sum()
        term *= turn
    values = np.abs(sums) / w.sum()
    j = int(np.argmax(values))
    freq, peak = float(trial[j]), float(values[j])
    if 0 < j < trial.size - 1:
        a, b, c = values[j - 1], values[j], values[j + 1]
        curvature = a - 2 * b + c
        if curvature < 0:                       # concave: its vertex is within ± ½ step
            shift = 0.5 * (a - c) / curvature
            freq += shift * step
            peak = max(peak, float(b - 0.25 * (a - c) * shift))
    return freq, peak


def appearance(speed_rpm: np.ndarray, amplitude: np.ndarray, threshold: float) -> tuple:
    """(speed [rpm] from which ``amplitude`` stays ≥ ``threshold`` to the end, its index) or
    (nan, −1) when the record ends below it."""
    above = np.asarray(amplitude) >= threshold
    if not above.size or not above[-1]:
        return math.nan, -1
    below = np.flatnonzero(~above)
    first = int(below[-1] + 1) if below.size else 0
    return float(speed_rpm[first]), first


@dataclass(frozen=True)
class LimitCycle:
    """The subsynchronous whirl at a constant speed over the end of a record (module
    docstring).

    status : 'limit cycle' (settled), 'growing', 'decaying' (not settled) or 'none' (no
    subsynchronous whirl: every other field but tolerance, threshold and window_s is
    NaN/None); reason : why, in words; amplitude_um : largest distance of the subsynchronous
    orbit from its centre, last window [µm]; previous_amplitude_um : the same over the
    window before; frequency_hz (signed) and whirl_ratio (inside the band); settled :
    |change| ≤ tolerance; change : relative change between the two windows; threshold_um :
    the smallest subsynchronous peak counted as a whirl [µm]; window_s [s]; measure : how
    the amplitude and its settling were measured ('largest distance' here; a rotor whose
    bumps rub: gfbopt.transient.rotor_friction.limit_cycle_of)."""

    status: str
    reason: str
    amplitude_um: float
    previous_amplitude_um: float
    frequency_hz: float
    whirl_ratio: float
    settled: Optional[bool]
    change: float
    tolerance: float
    threshold_um: float
    window_s: float
    measure: str = "largest distance"

    def to_dict(self, prefix: str = "") -> dict:
        return {f"{prefix}{k}": getattr(self, k) for k in self.__dataclass_fields__}


def _no_whirl(reason: str, tolerance: float, threshold: float, window: float) -> LimitCycle:
    nan = math.nan
    return LimitCycle(NO_WHIRL, reason, nan, nan, nan, nan, None, nan, tolerance, threshold,
                      window)


def limit_cycle(t: np.ndarray, x: np.ndarray, y: np.ndarray, angle: np.ndarray,
                shaft_hz: float, periods: float = 10.0, tolerance: float = 0.01,
                whirl_guess: float = 0.5, threshold_um: float = 0.0) -> LimitCycle:
    """The subsynchronous whirl over the last two windows of ``periods`` whirl periods each
    (whirl frequency from the last stretch's spectrum, else ``whirl_guess`` × shaft), or
    status 'none' when the last window has no subsynchronous peak of at least
    ``threshold_um`` standing :data:`NOISE_FACTOR` × above the band's noise floor."""
    good = np.isfinite(x) & np.isfinite(y)
    t, x, y, angle = t[good], x[good], y[good], angle[good]
    if t.size < 64:
        return _no_whirl("record too short (< 64 samples)", tolerance, threshold_um,
                         math.nan)
    span = t[-1] - t[0]
    probe = t >= t[-1] - min(span / 2, periods / (whirl_guess * shaft_hz))
    f0, _ = subsynchronous_peak(t[probe], x[probe] + 1j * y[probe], shaft_hz)
    whirl_hz = abs(f0) if math.isfinite(f0) and f0 != 0 else whirl_guess * shaft_hz
    window = periods / whirl_hz
    if 2 * window > span:
        window = span / 2
    amps, freq, peak, floor = [], math.nan, math.nan, math.nan
    for k in (1, 0):
        sel = (t >= t[-1] - (k + 1) * window) & (t <= t[-1] - k * window)
        _, _, fs, asub, zs = components(t[sel], x[sel], y[sel], angle[sel], shaft_hz)
        amps.append(float(np.abs(zs - zs.mean()).max()))
        if k == 0:
            freq, peak, floor = fs, asub, noise_floor(t[sel], zs, shaft_hz)
    band = f"{SUB_BAND[0]:g}–{SUB_BAND[1]:g}× the shaft speed"
    if not math.isfinite(freq):
        return _no_whirl(f"no subsynchronous whirl: no spectral peak inside {band} over the "
                         "last window", tolerance, threshold_um, window)
    if peak < threshold_um or not peak >= NOISE_FACTOR * floor:
        return _no_whirl(f"no subsynchronous whirl: the largest peak inside {band} "
                         f"({peak:.3g} µm at {abs(freq) / shaft_hz:.3f}×) is below the "
                         f"threshold {threshold_um:.3g} µm or {NOISE_FACTOR:g}× the band's "
                         f"noise floor {floor:.3g} µm", tolerance, threshold_um, window)
    change = amps[1] / amps[0] - 1.0 if amps[0] > 0 else math.nan
    settled = bool(abs(change) <= tolerance)
    status = LIMIT_CYCLE if settled else (GROWING if change > 0 else DECAYING)
    reason = (f"settled: {100 * change:+.2g} % between the last two windows" if settled else
              f"not settled: {100 * change:+.2g} % between the last two windows")
    return LimitCycle(status, reason, amps[1], amps[0], freq, abs(freq) / shaft_hz, settled,
                      change, tolerance, threshold_um, window)
