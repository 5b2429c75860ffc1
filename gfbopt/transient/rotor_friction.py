"""Bumps that rub in the rotor transient: each bearing's sliders Z beside the rotor's state.

A bearing whose file states Coulomb friction between its bumps and the housing (μ_f > 0,
docs/PHYSICS.md §7a) keeps the one-bearing friction model (:mod:`.friction_foil`): one
spring–slider (Jenkins) element per θ row (or node, local law) beside its bump, the slider
positions Z (B, m) — per run, per bearing — carried beside the packed state (they have no
rate, so they are not integrated by the Runge–Kutta step).  Every stage of a step recovers P
and H with the step's starting Z (``RotorRightHandSide.sliders``, passed as ``slider=`` to
:func:`.system.pressure_and_film`), and after every accepted step each bearing's Z moves once
by the play operator at the step's final deflection (:func:`move_sliders`, which calls
:func:`.friction_foil.slider_after_step`): the one-bearing operator splitting, whose error
is confined to the steps containing a reversal of W (tests/verification/
test_friction_transient.py: halving the step moves the settled amplitude by 1e-4).

The fused film evaluation (:mod:`.rotor_films`) carries no slider: a rotor whose every
bearing rubs on θ rows runs the fused friction rows (:mod:`.rotor_friction_films`), others
the one-bearing kernels (stacked in one call when both bearings have the same film structure
and the same friction elements, :func:`same_friction`).  Implicit methods (bdf) are refused
(the sliders move between accepted steps only).

With a loss factor η > 0 as well, each bearing keeps the one-bearing friction driver's
model (:mod:`.friction_orbit`, :mod:`.foil_state` "With friction"): its Kelvin–Voigt W is
integrated with the rest, P and H come from W alone, and the sliders enter W's rate,
τ_f W' + W = S (q − r); after each step Z moves from the state's W.  The fused rows carry it
(μ_f = 0 is the damped rotor transient bit for bit; the symmetric rotor equals the
one-bearing friction + η orbit to 4e-14 c, tests/unit/test_rotor_friction_damped.py), and
so do the one-bearing kernels (``KelvinVoigtFoil.rate`` with the bearing's sliders; the local
law's nodes).

How a constant-speed run ended, per bearing (:func:`bearing_outcomes`): 'contact' (the run
ended at the film's closure), 'settled limit cycle' (the semi-major axis of the whirl's
first harmonic at that journal, over the last ``periods`` whirl periods, within
``tolerance`` of the window before) or 'end of run' (still growing or decaying), with the
amplitude [µm] and the whirl frequency [Hz] — the measure of
:func:`.friction_orbit.orbit_axes` (the describing function's orbit amplitude), with the
imbalance's 1× removed by least squares when the run has an imbalance.

That measure is the orbit's one limit cycle (:func:`limit_cycle_of`): a rubbing rotor's
``limit_cycle_*`` fields carry the same amplitude, window and settled test (``limit_cycle_
measure`` 'first harmonic'), so that its status and ``friction_orbit_kind`` are one verdict
in two forms; where the spectral test of :func:`.spectra.limit_cycle` finds no
subsynchronous whirl at all, both say so.
"""
from __future__ import annotations

import dataclasses
import math
from typing import Optional

import numpy as np

from ..errors import ParameterError
from . import spectra
from .friction_foil import slider_after_step
from .system import rigid_film

#: the model's words in outputs
MODEL_WORDS = ("sliders integrated: a spring–slider element beside each bump, its slider "
               "moved by the play operator after each accepted step")
#: whirl periods per window of the settled test, and the settled tolerance (as the
#: one-bearing friction_outcome: a settled friction cycle measured 3e-5 per 6 periods)
PERIODS, TOLERANCE = 6, 1e-3


def rubbing(model) -> bool:
    """True when a bearing of the rotor transient model carries bump friction."""
    return any(b.tm.friction is not None for b in model.bearings)


def same_friction(model) -> bool:
    """True when every bearing's friction elements are the same (μ_f per row, κ, layout),
    or none has any: then the stacked one-bearing kernel serves all of them at once."""
    first = model.bearings[0].tm.friction
    for b in model.bearings[1:]:
        f = b.tm.friction
        if (f is None) != (first is None):
            return False
        if f is not None and not (f.layout == first.layout
                                  and f.stiffness_ratio == first.stiffness_ratio
                                  and np.array_equal(f.coefficient, first.coefficient)):
            return False
    return True


def check_method(model, method: str) -> None:
    """A rotor with bump friction integrates with an explicit method (rk4, rkc) only."""
    if rubbing(model) and method not in ("rk4", "rkc"):
        raise ParameterError("method", method, "the rotor transient with bump friction needs "
                             "rk4 or rkc (the sliders move between accepted explicit steps)")


def initial_sliders(model, batch: int, given=None) -> Optional[tuple]:
    """Per bearing the sliders Z (B, m) (or (B, m, n_z + 1), local law) to start from: the
    static equilibrium's (the element relaxed there, Z = W0), None for a bearing without
    friction; None for a rotor without friction.  ``given``: the sliders of an earlier run
    (:attr:`.rotor_run.RotorRun.sliders`), checked against the batch."""
    if not rubbing(model):
        if given is not None:
            raise ParameterError("sliders", "given", "the rotor's bearings carry no bump "
                                 "friction: there are no sliders to start from")
        return None
    out = []
    for k, b in enumerate(model.bearings):
        f = b.tm.friction
        if f is None:
            out.append(None)
            continue
        shape = (batch,) + f.equilibrium.shape
        z = (np.broadcast_to(f.equilibrium, shape) if given is None else
             np.asarray(given[k], dtype=float))
        if z.shape != shape:
            raise ParameterError("sliders", z.shape, f"bearing {b.label}'s must be {shape}")
        out.append(np.array(z, dtype=float))
    return tuple(out)


def move_sliders(rhs, z: np.ndarray) -> tuple:
    """Each bearing's Z after an accepted step ending at the packed states ``z`` (the play
    operator at the step's final deflection, from the step's starting Z, ``rhs.sliders``)."""
    xy = rhs.journals(z)
    if getattr(rhs.fused, "slider", None) is not None:      # the fused rows (every bearing)
        moved = rhs.fused.after_step(z, xy, rhs.fused.slider).reshape(
            z.shape[0], len(rhs.model.bearings), -1)
        return tuple(moved[:, k] for k in range(moved.shape[1]))
    out = []
    for k, (b, zk) in enumerate(zip(rhs.model.bearings, rhs.sliders)):
        if zk is None:
            out.append(None)
            continue
        hr = rigid_film(xy[:, k, 0], xy[:, k, 1], b.tm)
        out.append(slider_after_step(rhs.layout.phi_of(z, k), hr, zk, b.tm,
                                     rhs.layout.foil_of(z, k)))
    return tuple(out)


def last_state_words(rhs, z: np.ndarray) -> str:
    """'; at the last finite state: …' — the smallest absolute film pressure [p_a] and the
    largest journal displacement [clearances] of the runs at ``z``, with their bearings (what
    a blown-up run was doing: a film whose pressure nears 0 leaves the model, which has no
    cavitation)."""
    try:
        with np.errstate(all="ignore"):
            films = rhs.pressures(z)
            xy = rhs.journals(z)
    except (ParameterError, ValueError, FloatingPointError):
        return ""
    names = [b.label for b in rhs.model.bearings]
    low = [float(np.nanmin(p)) for p, _ in films]
    far = np.hypot(xy[..., 0], xy[..., 1]).max(axis=0)
    k, j = int(np.argmin(low)), int(np.argmax(far))
    return (f"; at the last finite state the smallest absolute film pressure was "
            f"{low[k]:.3g} p_a (bearing {names[k]}) and the journal {far[j]:.3g} clearances "
            f"off centre (bearing {names[j]})")


def describe(model) -> dict:
    """The friction model per bearing, for results: μ_f (largest over the rows), κ."""
    out = {}
    for b in model.bearings:
        if b.tm.friction is not None:
            out[b.label] = b.tm.friction.describe()
    return out


def model_words(model) -> str:
    """One line naming the model ('bump friction μ_f = …, κ = … at A, B; sliders …')."""
    d = describe(model)
    if not d:
        return ""
    parts = [f"μ_f = {v['friction_coefficient']:g}, κ = {v['friction_stiffness_ratio']:g} "
             f"at {name}" for name, v in d.items()]
    damped = any(b.tm.friction is not None and b.tm.foil_state is not None
                 for b in model.bearings)
    return "bump friction " + "; ".join(parts) + f" ({MODEL_WORDS}" + (
        "; with the loss factor the element acts in the Kelvin–Voigt foil's rate"
        if damped else "") + ")"


# ------------------------------------------------------------------ how a run ended
def whirl_axes(tau: np.ndarray, dx: np.ndarray, dy: np.ndarray,
               angle: Optional[np.ndarray] = None) -> tuple:
    """(semi-major axis, whirl frequency γ [per rad of τ]) of the whirl's first harmonic over
    a segment (:func:`.friction_orbit.orbit_axes`); with the shaft angle ``angle`` the 1×
    (cos ϑ, sin ϑ) is fitted beside it and removed (an imbalance's response)."""
    base = [np.ones_like(tau)]
    if angle is not None:
        base += [np.cos(angle), np.sin(angle)]
    data = np.column_stack([dx, dy])
    rest = data - np.column_stack(base) @ np.linalg.lstsq(np.column_stack(base), data,
                                                          rcond=None)[0]
    ex = rest[:, 0]
    up = np.flatnonzero((ex[:-1] < 0) & (ex[1:] >= 0))
    if up.size < 2:
        return math.nan, math.nan
    t_up = tau[up] - ex[up] * (tau[up + 1] - tau[up]) / (ex[up + 1] - ex[up])
    gamma = 2 * math.pi * (up.size - 1) / (t_up[-1] - t_up[0])
    basis = np.column_stack(base[:1] + [np.cos(gamma * tau), np.sin(gamma * tau)] + base[1:])
    coef = np.linalg.lstsq(basis, data, rcond=None)[0]
    return float(np.linalg.svd(coef[1:3].T, compute_uv=False)[0]), gamma


def bearing_outcomes(run, b: int = 0, periods: int = PERIODS,
                     tolerance: float = TOLERANCE) -> list:
    """How run ``b`` of a constant-speed rotor transient ended at each bearing (module
    docstring): a dict per bearing with kind, amplitude_um (semi-major axis over the last
    window), previous_amplitude_um (the window before), whirl_frequency_hz, whirl_ratio (to
    the shaft speed) and verdict.  Contact ends the run at both bearings."""
    model = run.model
    with_1x = bool(model.imbalance) and float(run.runs.imbalance_scale[b]) > 0
    out = []
    for k, bearing in enumerate(model.bearings):
        c = bearing.clearance
        x, y = run.journal(b, k)
        ok = np.isfinite(x) & np.isfinite(y)
        tau, dx, dy = run.tau[ok], x[ok] / c, y[ok] / c
        angle = run.shaft_angle(b)[ok] if with_1x else None
        amp = prev = gamma = math.nan
        if tau.size > 8:
            tail = tau >= 0.75 * tau[-1]
            gamma = whirl_axes(tau[tail], dx[tail], dy[tail],
                               None if angle is None else angle[tail])[1]
        if math.isfinite(gamma) and gamma > 0:
            span = 2 * math.pi / gamma * periods
            if tau[-1] - tau[0] >= 2 * span:
                last = tau >= tau[-1] - span
                before = (tau >= tau[-1] - 2 * span) & ~last
                pick = (lambda m: None) if angle is None else (lambda m: angle[m])
                amp, gamma = whirl_axes(tau[last], dx[last], dy[last], pick(last))
                prev = whirl_axes(tau[before], dx[before], dy[before], pick(before))[0]
        shaft = float(run.runs.speed[b] + run.runs.ramp[b] * (tau[-1] if tau.size else 0.0))
        hz = gamma * model.reference_speed / (2 * math.pi)
        entry = {"bearing": bearing.label, "amplitude_um": amp * c * 1e6,
                 "previous_amplitude_um": prev * c * 1e6, "whirl_frequency_hz": hz,
                 "whirl_ratio": gamma / shaft if shaft > 0 else math.nan}
        measured = math.isfinite(amp) and math.isfinite(prev)
        stopped = "" if run.success else (f" (the integration stopped at "
                                          f"{float(run.tau[-1]) / model.reference_speed * 1e3:.4g}"
                                          " ms: see the run's message)")
        whirl = (f"{amp * c * 1e6:.3g} µm at {hz:.4g} Hz ({entry['whirl_ratio']:.3f}× the "
                 "shaft speed)" if measured else "")
        if run.contact[b]:
            t_ms = float(run.contact_tau[b]) / model.reference_speed * 1e3
            entry.update(kind="contact", verdict=f"contact after {t_ms:.4g} ms" + (
                f" (whirl {whirl} over the last {periods} periods before it)"
                if measured else ""))
        elif measured and abs(amp / prev - 1.0) <= tolerance and run.success:
            entry.update(kind="settled limit cycle", verdict=f"settled limit cycle of {whirl}")
        elif measured:
            entry.update(kind="end of run", verdict=(
                f"end of run, {'growing' if amp > prev else 'decaying'}: {whirl}, "
                f"{100 * (amp / prev - 1):+.2g} % over the last {periods} whirl periods"
                + stopped))
        else:
            entry.update(kind="end of run", verdict=f"end of run: the record is shorter than "
                                                    f"two windows of {periods} whirl periods"
                                                    + stopped)
        out.append(entry)
    return out


#: the limit cycle's measure at a rubbing rotor (``limit_cycle_measure``)
MEASURE = "first harmonic"


def limit_cycle_of(entry: dict, spectral, periods: int = PERIODS,
                   tolerance: float = TOLERANCE) -> tuple:
    """(limit cycle, outcome) of one bearing of a rubbing orbit: the :func:`bearing_outcomes`
    ``entry``'s amplitude, window and settled test as a :class:`.spectra.LimitCycle`
    (measure 'first harmonic'; status 'limit cycle' exactly where the entry's kind is
    'settled limit cycle', else growing/decaying by the entry's own change; the frequency
    signed as the spectral whirl's), or, where ``spectral`` (:func:`.spectra.limit_cycle` on
    the same record) finds no subsynchronous whirl, its 'none' with the entry's kind 'end of
    run' saying so.  ``spectral`` None (the run ended in contact): (None, entry)."""
    if spectral is None:
        return None, entry
    if spectral.status == spectra.NO_WHIRL:
        none = dataclasses.replace(spectral, tolerance=tolerance, measure=MEASURE)
        return none, {**entry, "kind": "end of run",
                      "verdict": f"end of run: {spectral.reason}"}
    amp, prev, hz = (entry["amplitude_um"], entry["previous_amplitude_um"],
                     entry["whirl_frequency_hz"])
    settled = entry["kind"] == "settled limit cycle"
    measured = math.isfinite(amp) and math.isfinite(prev) and prev > 0
    change = amp / prev - 1.0 if measured else math.nan
    if settled:
        status = spectra.LIMIT_CYCLE
    else:
        status = spectra.GROWING if (change > 0 if measured else spectral.change > 0) \
            else spectra.DECAYING
    words = (f"{100 * change:+.2g} % over the last {periods} whirl periods against the "
             f"{periods} before (first harmonic)" if measured else
             f"the record is shorter than two windows of {periods} whirl periods")
    lc = spectra.LimitCycle(
        status, ("settled: " if settled else "not settled: ") + words, amp, prev,
        math.copysign(hz, spectral.frequency_hz) if math.isfinite(hz) else math.nan,
        entry["whirl_ratio"], settled, change, tolerance, spectral.threshold_um,
        periods / hz if math.isfinite(hz) and hz > 0 else math.nan, MEASURE)
    return lc, entry
