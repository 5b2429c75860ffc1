"""The result of a rotor transient, post-processed for engineers (SI and µm at the edges).

Per run of the batch and per bearing: the journal orbit [µm, global frame from the bearing
centre], the smallest film over the run with the time and speed it happened, contact (film
H ≤ ``contact_film`` or the foil's travel exhausted) with its time, speed and bearing, the
waterfall, 1× and subsynchronous components against speed (:mod:`.spectra`), and at a
constant speed the subsynchronous whirl's status (a limit cycle, growing, decaying, or none:
then no amplitude, frequency or ratio) and the settled synchronous amplitude (the major
semi-axis of the 1× orbit over the last window, the linear imbalance response's
``amplitude_um``; a ramp's peak of it over its windows).  For a run-up the speed where the
subsynchronous line appears is set beside the rotor's linear onset (gfbopt.rotor's
matched-whirl threshold, when that is available in this build).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from ..provenance import jsonable
from . import rotor_friction, spectra
from .rotor_run import RotorRun

#: default window of the waterfall [shaft revolutions at the run's mean speed]
WINDOW_REVOLUTIONS = 20.0
#: default threshold of the subsynchronous line's appearance [fraction of the clearance]
SUBSYNC_THRESHOLD = 0.02


@dataclass(frozen=True, eq=False)
class RotorTransientResult:
    """What a rotor orbit or ramp computed (module docstring).

    run : the raw record (:class:`.rotor_run.RotorRun`); profile : the speed profile;
    names : bearing names; equilibria : per bearing at the start speed; films : per run, per
    bearing {min_film_um, time_s, speed_rpm}; contacts : per run {contact, bearing, kind,
    time_s, speed_rpm}; waterfalls, limit_cycles : per run, per bearing; onset : the
    subsynchronous appearance against the linear onset (ramps); settings : the options;
    notes : computed remarks."""

    run: RotorRun
    profile: object
    names: tuple
    equilibria: list
    films: list
    contacts: list
    waterfalls: list
    limit_cycles: list
    onset: dict
    settings: dict
    description: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)
    #: bumps that rub: per run, per bearing how an orbit ended (:func:`.rotor_friction.
    #: bearing_outcomes`); empty without friction or for a ramp
    friction: list = field(default_factory=list)

    @property
    def success(self) -> bool:
        return self.run.success

    def orbit_frame(self, run: int = 0):
        """Time [s], speed [rpm], shaft angle [deg] and, per bearing, x, y [µm] and the
        smallest film since the previous sample [µm]."""
        import pandas as pd

        r = self.run
        out = {"time_s": r.time_s, "speed_rpm": r.speed_rpm(run),
               "shaft_angle_deg": np.degrees(r.shaft_angle(run))}
        for k, name in enumerate(self.names):
            x, y = r.journal(run, k)
            out[f"x_{name}_um"] = x * 1e6
            out[f"y_{name}_um"] = y * 1e6
            out[f"min_film_{name}_um"] = r.min_film[run, k] * r.model.bearings[k].clearance * 1e6
        return pd.DataFrame(out)

    def tables(self, run: int = 0) -> dict:
        """CSV name → DataFrame: the orbit record and, per bearing, the components against
        speed (the waterfall's windows)."""
        out = {"orbit.csv": self.orbit_frame(run)}
        for k, name in enumerate(self.names):
            w = self.waterfalls[run][k]
            if w.time_s.size:
                out[f"components_{name}.csv"] = w.table()
        return out

    def ramp_end(self, run: int = 0) -> Optional[dict]:
        """Where a ramp cut short ended (contact, or the integration stopped): end_speed_rpm,
        duration_s and revolutions of the record up to there, and the end asked for
        (requested_end_rpm, requested_duration_s); None for an orbit or a ramp that reached
        its requested end.  (A heated ramp whose running line ends early was already cut
        to that end: its requested_end_rpm is the settings'.)"""
        r, p = self.run, self.profile
        if p.kind == "orbit" or not r.tau.size or (r.success and not r.contact[run]):
            return None
        tau = float(r.contact_tau[run]) if r.contact[run] else float(r.tau[-1])
        angle = r.runs.speed[run] * tau + 0.5 * r.runs.ramp[run] * tau ** 2
        return {"end_speed_rpm": float(r.speed_rpm(run, tau)),
                "duration_s": tau / r.model.reference_speed,
                "revolutions": float(angle / (2 * math.pi)),
                "end_cause": (f"contact at bearing {self.names[int(r.contact_bearing[run])]}"
                              if r.contact[run] else "the integration stopped"),
                **self.requested()}

    def requested(self) -> dict:
        """A ramp's asked end: requested_end_rpm and requested_duration_s."""
        p = self.profile
        end = float(self.settings.get("requested_end_rpm", p.end_rpm))
        return {"requested_end_rpm": end,
                "requested_duration_s": abs(end - p.start_rpm) / p.rate_rpm_per_s}

    def run_words(self, run: int = 0) -> str:
        """What was run, for titles: 'orbit at N rpm', or 'run-up A → E rpm at R rpm/s' with,
        for a ramp cut short, '(asked → F rpm; contact at bearing B at E rpm, t = T s)'."""
        p = self.profile
        if p.kind == "orbit":
            return f"orbit at {p.start_rpm:,.0f} rpm"
        end = self.ramp_end(run)
        ended = p.end_rpm if end is None else end["end_speed_rpm"]
        words = (f"{p.kind} {p.start_rpm:,.0f} → {ended:,.0f} rpm at "
                 f"{p.rate_rpm_per_s:,.0f} rpm/s")
        asked = self.requested()["requested_end_rpm"]
        if end is not None:
            return words + (f" (asked → {asked:,.0f} rpm; {end['end_cause']} at "
                            f"{ended:,.0f} rpm, t = {end['duration_s']:.4g} s)")
        return words + (f" (asked → {asked:,.0f} rpm)" if asked != p.end_rpm else "")

    def to_dict(self, run: int = 0) -> dict:
        """Scalar results of one run, JSON-ready; a ramp's end_speed_rpm and duration_s are
        where it ended, requested_end_rpm and requested_duration_s what was asked."""
        r = self.run
        ramp = {} if self.profile.kind == "orbit" else {
            **self.requested(), "end_cause": ("the running line ends (running_end)"
                                              if self.settings.get("running_end") else None)}
        out = {**self.profile.to_dict(), **self.settings, **ramp,
               **(self.ramp_end(run) or {}),
               "success": r.success, "message": r.message, "method": r.method,
               "time_step_rad": r.time_step, "step_rule": r.options.get("step_rule", ""),
               "rkc_stages": list(r.stages),
               "evaluations": r.evaluations, "wall_time_s": r.wall_time_s,
               "revolutions_integrated": r.revolutions,
               "inertia_scale": float(r.runs.inertia_scale[run]),
               "imbalance_scale": float(r.runs.imbalance_scale[run]),
               "bearings": []}
        for k, name in enumerate(self.names):
            entry = {"bearing": name, **self.equilibria[k], **self.films[run][k]}
            lc = self.limit_cycles[run][k]
            if lc is not None:
                entry.update(lc.to_dict("limit_cycle_"))
            entry.update(self._synchronous(self.waterfalls[run][k],
                                           bool(self.contacts[run]["contact"])))
            if self.friction:
                entry.update({f"friction_orbit_{key}": value for key, value in
                              self.friction[run][k].items() if key != "bearing"})
            out["bearings"].append(entry)
        out.update(self.contacts[run])
        out.update(self.onset)
        out["rotor"] = self.description
        out["notes"] = list(self.notes)
        return jsonable(out)


    def _synchronous(self, w, contact: bool) -> dict:
        """The synchronous amplitude (major semi-axis of the 1× orbit, the components
        table's ``sync_amplitude_um``): of an orbit over its last window, the end of the
        record, with its change from the window before it (null when the orbit ends in
        contact: no settled response); of a ramp its peak over the ramp's windows
        (glossary names)."""
        if not w.time_s.size:
            return {}
        amp = w.sync_amplitude
        if self.profile.kind == "orbit" and contact:
            return {"sync_amplitude_um": math.nan, "sync_time_s": math.nan,
                    "sync_window_s": w.window_s, "sync_amplitude_change": math.nan}
        if self.profile.kind == "orbit":
            before = len(amp) - 1 - round(w.window_s / w.hop_s) if w.hop_s > 0 else -1
            change = float(amp[-1] / amp[before] - 1.0) if before >= 0 and amp[before] > 0 \
                else math.nan
            return {"sync_amplitude_um": float(amp[-1]), "sync_time_s": float(w.time_s[-1]),
                    "sync_window_s": w.window_s, "sync_amplitude_change": change}
        j = int(np.argmax(amp))
        return {"peak_amplitude_um": float(amp[j]), "peak_speed_rpm": float(w.speed_rpm[j]),
                "sync_window_s": w.window_s,
                "final_sub_amplitude_um": float(w.sub_amplitude[-1]),
                "final_sub_frequency_hz": float(w.sub_frequency_hz[-1])}


def whirl_words(b: dict, prefix: str = "limit_cycle_") -> str:
    """A constant-speed orbit's subsynchronous whirl in words, from its JSON entry (or a
    table row) ``b``: 'no subsynchronous whirl' when its status is 'none'."""
    if b.get(f"{prefix}status") in (None, "none"):
        return "no subsynchronous whirl"
    return (f"whirl {b[f'{prefix}amplitude_um']:.3g} µm at {b[f'{prefix}frequency_hz']:.4g} Hz "
            f"({b[f'{prefix}whirl_ratio']:.3f}×, {b[f'{prefix}status']}"
            + ("" if b[f"{prefix}settled"] else
               f": {100 * b[f'{prefix}change']:+.2g} % over the last window") + ")")


def _equilibrium(sol, film, load_newton: float) -> dict:
    c = film.clearance
    return {"eccentricity": sol.eccentricity,
            "attitude_angle_deg": sol.attitude_angle_deg,
            "min_film_thickness_um": sol.min_film * c * 1e6,
            "load_newton": load_newton,
            "load_direction_deg": math.degrees(film.frame_angle) + 0.0,
            "bearing_number": sol.model.bearing_number}


def summarise(run: RotorRun, profile, rotor, solutions, settings: dict, *, system=None,
              linear_onset=None, window_revolutions: float = WINDOW_REVOLUTIONS,
              subsync_threshold_um: Optional[float] = None, settle_periods: float = 10.0,
              settle_tolerance: float = 0.01, max_order: float = 2.5) -> RotorTransientResult:
    """Post-process ``run`` (module docstring).  ``linear_onset`` : a dict with
    ``linear_onset_speed_rpm`` (and ``first_mode``, ``linear_onset_whirl_frequency_hz``) to
    compare with, False to skip, or None to ask gfbopt.rotor (when available)."""
    model = run.model
    names = tuple(b.label for b in model.bearings)
    clearances = [b.clearance for b in model.bearings]
    threshold = (SUBSYNC_THRESHOLD * min(clearances) * 1e6 if subsync_threshold_um is None
                 else float(subsync_threshold_um))
    loads = [float(np.hypot(*l)) for l in _loads(rotor)]
    equilibria = [_equilibrium(s, b, w) for s, b, w in zip(solutions, model.bearings, loads)]
    # windows of ``window_revolutions`` at the record's mean speed, at least 10 per record
    # (a ramp cut short by contact keeps its resolution)
    span = float(run.time_s[-1] - run.time_s[0]) if run.tau.size > 1 else 0.0
    mean_speed = (float(np.mean(run.speed_rpm(0))) if run.tau.size
                  else 0.5 * (profile.start_rpm + profile.end_rpm))
    window_s = window_revolutions * 60.0 / mean_speed
    if span > 0:       # a ramp keeps ≥ 10 windows, an orbit ≥ 2 (the last one settled)
        window_s = min(window_s, span / (10.0 if profile.kind != "orbit" else 2.0))
    films, contacts, falls, cycles = [], [], [], []
    t = run.time_s
    for b in range(run.runs.size):
        speed = run.speed_rpm(b)
        angle = run.shaft_angle(b)
        per, fall, cyc = [], [], []
        for k in range(len(names)):
            tau = run.run_min_film_tau[b, k]
            # a film that closed within the contact step is reported as 0 (closed), not < 0
            per.append({"min_film_um": max(float(run.run_min_film[b, k] * clearances[k]
                                                 * 1e6), 0.0),
                        "min_film_time_s": float(tau / model.reference_speed),
                        "min_film_speed_rpm": float(run.speed_rpm(b, tau))})
            if math.isfinite(run.max_deflection[b, k]):
                per[-1]["max_foil_deflection_um"] = float(run.max_deflection[b, k]
                                                          * clearances[k] * 1e6)
            x, y = run.journal(b, k)
            fall.append(spectra.waterfall(t, x * 1e6, y * 1e6, angle, speed, window_s,
                                          max_order=max_order))
            cyc.append(spectra.limit_cycle(t, x * 1e6, y * 1e6, angle,
                                           profile.start_rpm / 60.0, settle_periods,
                                           settle_tolerance, threshold_um=threshold)
                       if profile.kind == "orbit" and not run.contact[b] else None)
        films.append(per)
        falls.append(fall)
        cycles.append(cyc)
        contacts.append(_contact(run, b, names, clearances))
    onset, notes = {}, []
    if profile.kind != "orbit":
        onset = _onset(falls[0], names, threshold, profile, system, settings, linear_onset)
        notes.append("Synchronous amplitude: sync_amplitude_um of the components table, "
                     "the major semi-axis of each window's order-tracked 1× orbit (as the "
                     "linear imbalance response's amplitude_um); peak_amplitude_um is its "
                     "largest value over the ramp's windows (the ramp starts from the "
                     "static equilibrium: its first windows carry the 1× build-up).")
        notes.append(f"Subsynchronous line: the largest spectral peak between "
                     f"{spectra.SUB_BAND[0]:g}× and {spectra.SUB_BAND[1]:g}× of the shaft "
                     f"speed after the tracked 1× component is removed; it 'appears' at the "
                     f"first window from which its amplitude stays ≥ {threshold:.3g} µm to "
                     f"the end of the record; windows of {window_s * 1e3:.3g} ms "
                     f"({window_revolutions:g} revolutions at the record's mean speed, at "
                     f"most 1/10 of the record), 50 % overlap, Hann.")
    else:
        notes.append(f"Limit cycle: subsynchronous orbit (tracked 1× removed), largest "
                     f"distance from its centre over the last {settle_periods:g} whirl "
                     f"periods; settled when it differs from the previous "
                     f"{settle_periods:g} periods by ≤ {100 * settle_tolerance:g} %. A "
                     f"whirl only where that window has a spectral peak inside "
                     f"{spectra.SUB_BAND[0]:g}–{spectra.SUB_BAND[1]:g}× of at least "
                     f"{threshold:.3g} µm and {spectra.NOISE_FACTOR:g}× the band's noise "
                     f"floor; otherwise status 'none' and no amplitude, frequency or ratio.")
        notes.append(f"Synchronous amplitude sync_amplitude_um: major semi-axis of the "
                     f"order-tracked 1× orbit over the last window ({window_s * 1e3:.3g} ms, "
                     f"{window_s * profile.start_rpm / 60.0:.3g} revolutions, ending at the "
                     f"record's end: the settled response, not the start-up), as the linear "
                     f"imbalance response's amplitude_um; the last row of the components "
                     f"table.")
    if settings.get("foil_travel_m") is None:
        notes.append("Foil travel not checked (no bump travel given): contact is the film "
                     f"reaching H ≤ {settings['contact_film']:g} c only.")
    damping = [b.tm.foil_state.describe() for b in model.bearings if b.tm.foil_state]
    if damping:
        notes.append("Kelvin–Voigt foil state per bearing (time constant fixed in seconds "
                     "over a ramp): " + "; ".join(
                         f"η = {d['loss_factor']:g}, ν_ref = {d['reference_whirl_ratio']:.4g} "
                         f"({d['reference_whirl_source']}) at {profile.start_rpm:g} rpm"
                         for d in damping))
    friction = []
    if rotor_friction.rubbing(model):
        settings = {**settings, "bump_friction": rotor_friction.model_words(model)}
        notes.append("Bumps that rub: " + settings["bump_friction"] + "; " + (
            "per bearing, how the orbit ended (friction_orbit_kind: settled limit cycle, "
            "contact or end of run): the semi-major axis of the whirl's first harmonic over "
            f"the last {rotor_friction.PERIODS} whirl periods against the "
            f"{rotor_friction.PERIODS} before (settled within {rotor_friction.TOLERANCE:g}), "
            "1× removed; the limit cycle's own measure and settled test here (limit_cycle_"
            f"measure '{rotor_friction.MEASURE}', replacing the largest distance over "
            f"{settle_periods:g} periods above), so limit_cycle_status and "
            "friction_orbit_kind are one verdict"
            if profile.kind == "orbit" else "a ramp states no limit cycle"))
        if profile.kind == "orbit":      # the orbit's one limit cycle: the sliders' measure
            for b in range(run.runs.size):
                pairs = [rotor_friction.limit_cycle_of(e, lc) for e, lc in
                         zip(rotor_friction.bearing_outcomes(run, b), cycles[b])]
                cycles[b] = [lc for lc, _ in pairs]
                friction.append([e for _, e in pairs])
    description = dict(rotor.description)
    description["bearing_frames_deg"] = [math.degrees(b.frame_angle) for b in model.bearings]
    return RotorTransientResult(run, profile, names, equilibria, films, contacts, falls,
                                cycles, onset, settings, description, notes, friction)


def _loads(rotor) -> np.ndarray:
    from .rotor_setup import bearing_loads

    return bearing_loads(rotor)


def _contact(run: RotorRun, b: int, names: tuple, clearances: list) -> dict:
    if not run.contact[b]:
        return {"contact": False, "contact_bearing": None, "contact_kind": "",
                "contact_time_s": math.nan, "contact_speed_rpm": math.nan}
    k = int(run.contact_bearing[b])
    tau = run.contact_tau[b]
    return {"contact": True, "contact_bearing": names[k], "contact_kind": run.contact_kind[b],
            "contact_time_s": float(tau / run.model.reference_speed),
            "contact_speed_rpm": float(run.speed_rpm(b, tau)),
            "contact_min_film_um": max(float(run.run_min_film[b, k] * clearances[k] * 1e6),
                                       0.0)}


def _onset(falls: list, names: tuple, threshold: float, profile, system, settings,
           linear_onset) -> dict:
    out = {"subsync_threshold_um": threshold}
    speeds = []
    for k, name in enumerate(names):
        w = falls[k]
        speed, idx = (spectra.appearance(w.speed_rpm, w.sub_amplitude, threshold)
                      if w.time_s.size else (math.nan, -1))
        out[f"subsync_appearance_{name}_rpm"] = speed
        out[f"subsync_frequency_{name}_hz"] = (float(w.sub_frequency_hz[idx]) if idx >= 0
                                               else math.nan)
        speeds.append(speed)
    finite = [s for s in speeds if math.isfinite(s)]
    out["subsync_appearance_rpm"] = (min(finite) if profile.kind == "run-up" else max(finite)) \
        if finite else math.nan
    linear = _linear_onset(system, profile, settings, linear_onset)
    out.update(linear)
    lin = linear.get("linear_onset_speed_rpm", math.nan)
    out["appearance_over_linear_onset"] = (out["subsync_appearance_rpm"] / lin
                                           if math.isfinite(lin) and lin > 0 else math.nan)
    return out


def _linear_onset(system, profile, settings, given) -> dict:
    """The rotor's linear onset over the profile's speed range (gfbopt.rotor.system's
    matched-whirl threshold), or NaN with the reason."""
    if isinstance(given, dict):
        return {"linear_onset_source": "given", **given}
    if given is False:
        return {"linear_onset_speed_rpm": math.nan, "linear_onset_source": "not computed"}
    if system is None:
        return {"linear_onset_speed_rpm": math.nan,
                "linear_onset_source": "not computed (no rotor file: a RotorInput was given)"}
    try:
        from ..rotor.system import rotor_onsets
    except ImportError:
        return {"linear_onset_speed_rpm": math.nan, "linear_onset_source":
                "not available in this build (gfbopt.rotor.system)"}
    from ..inputs.grid import Grid

    low = min(profile.start_rpm, profile.end_rpm)
    result = rotor_onsets(system, (low, profile.top_rpm), grid=Grid.parse(settings["grid"]),
                          show_progress=False)
    return {"linear_onset_speed_rpm": result.onset_speed_rpm,
            "linear_first_mode": result.first_mode,
            "linear_onset_whirl_frequency_hz": result.onset_whirl_frequency_hz,
            "linear_onset_reason": result.onset_reason,
            "linear_onset_source": "gfbopt.rotor.system.rotor_onsets (matched whirl)",
            "linear_modes": [m.to_dict() for m in result.modes]}
