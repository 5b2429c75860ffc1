"""Speed scans of the rotor on two bearings: the Campbell diagram (full-system eigenvalues,
modes tracked over speed), the linear imbalance response (Bode) and the per-bearing
(half-mass) approximation that engineers use and that this module shows beside the exact
answer.

* :func:`campbell_diagram` — at each speed the rotor's modes from :func:`gfbopt.rotor.
  campbell.system_modes`, tracked by continuation and continuity (:mod:`gfbopt.rotor.
  tracking`: MAC of the orbits at the bearings plus frequency continuity), each row with the
  mode's name (``track_label``, one name per track, no two alike: the matched-whirl onset's
  label where the track loses its damping at that onset; :func:`gfbopt.rotor.tracking.
  name_tracks` states the rule) and the shape class of its own row (``shape_label``, which
  drifts with speed on an asymmetric rotor); a track that breaks between two speeds is
  joined again and a root found at one speed only that continues no track is left out of
  the table and stated (``dropped``; :func:`gfbopt.rotor.tracking.stitch`: no line of one
  point, no name of no mode); the table has the damped
  natural frequency [Hz], whirl ratio, log decrement, damping ratio and growth rate of every
  mode.  With a loss factor the foil's Kelvin–Voigt states use at each
  speed the reference whirl ratio of the least-stable matched-whirl crossing there (stated in
  the column ``reference_whirl_ratio``; 1/2 when no mode crosses).
* :func:`imbalance_response` — the synchronous response q̂ = D(iω)⁻¹ Q̂ on the rotor's
  structure (:mod:`.structure`: Q̂ = Σ S(z)ᵀ(1, −i) U ω² e^{iφ}, station motion S(z) q̂; Ω = ω, γ = 1: the
  bearings' impedance at the running speed, which is right for a synchronous forcing) at each
  bearing and named station: major semi-axis of the orbit [µm] (``amplitude_um``, the
  forward plus the backward radius: :func:`gfbopt.rotor.modes.ellipse_radii`, the
  rotor transient's ``sync_amplitude_um`` by the same function), x and y amplitudes [µm]
  and phases [deg] (x = Re(X̂ e^{iωt})), forward and backward radii; the peak (critical
  speed) of each station refined by a bounded scalar search.
* :func:`half_mass_onsets` — each bearing alone, carrying its share of the weight and the same
  share of the mass (m |W_k|/Σ|W|), in cylindrical whirl: :func:`gfbopt.rotor.onset_speed`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.optimize import minimize_scalar

from ..errors import ParameterError
from ..inputs.conversions import rpm_to_rad_per_s
from ..progress import progress
from ..threads import single_threaded
from .campbell import MAX_WHIRL, system_modes
from .modes import ellipse_radii
from .tracking import MAX_COST, assign, guesses, name_tracks, stitch
from .onset import onset_speed
from .running import speed_columns
from .rigid import dynamic_stiffness, imbalance_forces, station_matrix
from .structure import is_rigid
from .system import SpeedLine

#: ν_ref of the Kelvin–Voigt foil states when no mode crosses at a speed [-]
FALLBACK_REFERENCE_WHIRL = 0.5


@dataclass(frozen=True)
class CampbellDiagram:
    """table : one row per (speed, tracked mode): speed_rpm, mode (track number),
    track_label (the mode's name), shape_label (this row's shape class), track_zero_rpm,
    whirl_frequency_hz, whirl_ratio, log_decrement, damping_ratio, growth_rate_per_s,
    reference_whirl_ratio; capacity : speeds skipped (a bearing over capacity)."""

    table: pd.DataFrame
    capacity: list = field(default_factory=list)
    #: a shaft's modes are followed up to this damped natural frequency [Hz] (every mode
    #: below it at every speed; the rigid body's four always); nan: a rigid body
    frequency_limit_hz: float = math.nan
    #: the roots found at one speed only that no track continues, taken out of the table
    #: (:func:`~gfbopt.rotor.tracking.stitch`): one dict each, speed_rpm, whirl_frequency_hz,
    #: log_decrement, shape_label and reason
    dropped: tuple = ()

    def least_stable(self) -> pd.Series:
        """The row with the smallest log decrement."""
        return self.table.loc[self.table["log_decrement"].idxmin()]

    def tracks(self) -> list:
        """One dict per tracked mode: mode (number), label (its name, ``track_label``),
        track_zero_rpm (nan: its damping does not fall through zero)."""
        if self.table.empty:
            return []
        first = self.table.groupby("mode", sort=True).first()
        return [{"mode": int(k), "label": r["track_label"],
                 "track_zero_rpm": float(r["track_zero_rpm"])} for k, r in first.iterrows()]


def reference_whirl(line: SpeedLine, speed: float) -> float:
    """ν_ref at ``speed``: the whirl ratio of the least-stable matched-whirl crossing."""
    found = line.crossings(speed)
    return found[0].whirl_ratio if found else FALLBACK_REFERENCE_WHIRL


@single_threaded
def campbell_diagram(line: SpeedLine, speeds, show_progress: bool = True,
                     onsets=None, max_frequency_hz=None) -> CampbellDiagram:
    """The Campbell diagram at ``speeds`` [rpm] (module docstring).  ``onsets``: the
    matched-whirl onsets (:class:`~gfbopt.rotor.mode_search.ModeOnset`) that name the tracks
    crossing zero damping next to them, or of the same shape
    (:func:`~gfbopt.rotor.tracking.name_tracks`); ``max_frequency_hz``: a shaft's modes are
    followed up to this frequency [Hz] at every speed (default :data:`~gfbopt.rotor.
    campbell.MAX_WHIRL` times the highest speed), bending modes included."""
    damped = any(c.options.loss_factor for c in line.rotor.cases)
    positions = list(line.rotor.positions)
    limit = math.nan
    if not is_rigid(line.rotor.structure):
        limit = float(max_frequency_hz if max_frequency_hz is not None
                      else MAX_WHIRL * max(speeds) / 60.0)
        if not (math.isfinite(limit) and limit > 0):
            raise ParameterError("max_frequency_hz", max_frequency_hz, "must be > 0 [Hz]")
    tracks: list = []
    active: list = []
    refs, skipped = {}, []
    with progress(total=len(speeds), desc="Campbell diagram", unit="speed",
                  enabled=show_progress) as bar:
        for speed in speeds:
            states = line.states(speed)
            bar.update(1)
            if not states.ok:
                skipped.append(states.failure)
                continue
            ref = reference_whirl(line, speed) if damped else math.nan
            start = guesses(tracks, active, speed, states.omega)
            modes = system_modes(line.rotor, states, reference_whirl=ref if damped else None,
                                 guesses=start, max_frequency_hz=(
                                     None if math.isnan(limit) else limit))
            if not math.isnan(limit):          # the stated limit, the same at every speed
                modes = [m for m in modes if m.whirl_frequency_hz <= limit]
            active = assign(tracks, active, speed, states.omega, modes, positions, start,
                            line.rotor.structure)
            refs[speed] = ref
    tracks, lost = stitch(tracks, list(refs), positions, line.rotor.structure)
    dropped = tuple(_dropped(tr, least) for tr, least in lost)
    rows = []
    names = name_tracks([[(s, m) for s, m, _ in tr] for tr in tracks], onsets or (),
                        line.rotor)
    for number, (tr, (name, zero)) in enumerate(zip(tracks, names), 1):
        for speed, m, _ in tr:
            rows.append({"speed_rpm": speed, "mode": number, "track_label": name,
                         "shape_label": m.label, "track_zero_rpm": zero,
                         "whirl_frequency_hz": m.whirl_frequency_hz,
                         "whirl_ratio": m.whirl_ratio, "log_decrement": m.log_decrement,
                         "damping_ratio": m.damping_ratio,
                         "growth_rate_per_s": m.growth_rate_per_s,
                         "reference_whirl_ratio": refs[speed],
                         **speed_columns(line.states(speed))})
    table = pd.DataFrame(rows)
    if not table.empty:
        table = table.sort_values(["mode", "speed_rpm"]).reset_index(drop=True)
    return CampbellDiagram(table, skipped, limit, dropped)


def _dropped(track: list, least: float) -> dict:
    """What a root found at one speed only was, and why it is not a track."""
    speed, m, _ = track[0]
    why = f"found at {speed:,.0f} rpm only: "
    if not math.isfinite(least):
        way = m.shape.get("direction", "its") if isinstance(m.shape, dict) else "its"
        why += (f"no track whirling {way} (a track keeps its whirl direction) ends at the "
                "speed before it or starts at the one after, so it continues none")
    elif least > MAX_COST:
        why += (f"it continues no track (least join cost {least:.3g} > {MAX_COST:g}: "
                "gfbopt.rotor.tracking.stitch)")
    else:
        why += (f"the track it could continue (join cost {least:.3g}) continues a mode "
                "nearer it")
    return {"speed_rpm": float(speed), "whirl_frequency_hz": float(m.whirl_frequency_hz),
            "log_decrement": float(m.log_decrement), "shape_label": m.label, "reason": why}


@dataclass(frozen=True)
class ImbalanceResponse:
    """table : one row per (speed, station): speed_rpm, station, position_m, amplitude_um
    (major semi-axis), amplitude_x_um, phase_x_deg, amplitude_y_um, phase_y_deg,
    forward_radius_um, backward_radius_um; peaks : station → peak_speed_rpm,
    peak_amplitude_um, at_range_end, above_first_onset (the peak lies where the rotor is
    unstable: the linear response there is not an orbit that would be observed), and
    largest_below_onset_um / largest_below_onset_rpm (the largest tabulated amplitude below
    the first onset; nan when none); unstable_from_rpm : the first onset [rpm] (the lowest
    speed when unstable there; nan: stable over the range); capacity : speeds skipped."""

    table: pd.DataFrame
    peaks: dict
    capacity: list = field(default_factory=list)
    unstable_from_rpm: float = math.nan

    def to_dict(self) -> dict:
        """JSON-ready: the peaks, where the rotor is unstable from, the speeds skipped, and
        the amplitude table itself (``table``: one record per speed and station, the CSV's
        columns and numbers; ``amplitude_um`` is the major semi-axis of the synchronous
        orbit, the rotor transient's ``sync_amplitude_um``)."""
        from ..provenance import jsonable

        return jsonable({"peaks": self.peaks, "unstable_from_rpm": self.unstable_from_rpm,
                         "load_capacity_exceeded": self.capacity,
                         "table": self.table.to_dict(orient="records")})


def synchronous_response(line: SpeedLine, speed: float) -> dict:
    """station → (X̂, Ŷ) [m] at ``speed`` [rpm], or None when a bearing is over capacity."""
    system = line.rotor.system
    if not system.imbalance:
        raise ParameterError("imbalance", (), "the rotor file has no [[imbalance]] plane: "
                             "there is no imbalance response to compute")
    states = line.states(speed)
    if not states.ok:
        return None
    omega = rpm_to_rad_per_s(speed)
    z = [st.impedance(1.0) for st in states.states]
    structure = line.rotor.structure
    d = dynamic_stiffness(structure, omega, 1j * omega, line.rotor.transforms, z)
    q = np.linalg.solve(d, imbalance_forces(system, omega, structure))
    if is_rigid(structure):
        return {name: station_matrix(pos) @ q
                for name, pos in system.station_positions().items()}
    return {name: structure.station(pos) @ q
            for name, pos in system.station_positions().items()}


def _row(speed, name, pos, xy) -> dict:
    x, y = xy
    f, b, major = (float(r) for r in ellipse_radii(x, y))
    return {"speed_rpm": speed, "station": name, "position_m": pos,
            "amplitude_um": major * 1e6, "amplitude_x_um": abs(x) * 1e6,
            "phase_x_deg": math.degrees(np.angle(x)), "amplitude_y_um": abs(y) * 1e6,
            "phase_y_deg": math.degrees(np.angle(y)), "forward_radius_um": f * 1e6,
            "backward_radius_um": b * 1e6}


@single_threaded
def imbalance_response(line: SpeedLine, speeds, show_progress: bool = True,
                       refine_peaks: bool = True,
                       unstable_from_rpm: float = math.nan) -> ImbalanceResponse:
    """The synchronous imbalance response at ``speeds`` [rpm] (module docstring);
    ``unstable_from_rpm``: the first onset (nan: none), above which a peak is flagged."""
    positions = line.rotor.system.station_positions()
    rows, skipped = [], []
    with progress(total=len(speeds), desc="imbalance response", unit="speed",
                  enabled=show_progress) as bar:
        for speed in speeds:
            resp = synchronous_response(line, speed)
            bar.update(1)
            if resp is None:
                skipped.append(line.states(speed).failure)
                continue
            extra = speed_columns(line.states(speed))
            rows += [{**_row(speed, n, positions[n], xy), **extra} for n, xy in resp.items()]
    table = pd.DataFrame(rows)
    peaks = {}
    for name in positions:
        part = table[table["station"] == name].reset_index(drop=True) if rows else table
        if part.empty:
            continue
        k = int(part["amplitude_um"].idxmax())
        speed, amp = float(part.loc[k, "speed_rpm"]), float(part.loc[k, "amplitude_um"])
        if refine_peaks and 0 < k < len(part) - 1:
            lo, hi = float(part.loc[k - 1, "speed_rpm"]), float(part.loc[k + 1, "speed_rpm"])

            def minus(s, name=name):
                r = synchronous_response(line, s)
                return 0.0 if r is None else -_row(s, name, 0.0, r[name])["amplitude_um"]

            opt = minimize_scalar(minus, bounds=(lo, hi), method="bounded",
                                  options={"xatol": 1e-4 * speed})
            if -opt.fun >= amp:
                speed, amp = float(opt.x), float(-opt.fun)
        at_end = k in (0, len(part) - 1)
        below = part[~(part["speed_rpm"] >= unstable_from_rpm)]
        best = below.loc[below["amplitude_um"].idxmax()] if len(below) else None
        peaks[name] = {"peak_speed_rpm": speed, "peak_amplitude_um": amp,
                       "at_range_end": bool(at_end),
                       "above_first_onset": bool(speed >= unstable_from_rpm),
                       "largest_below_onset_um": (math.nan if best is None
                                                  else float(best["amplitude_um"])),
                       "largest_below_onset_rpm": (math.nan if best is None
                                                   else float(best["speed_rpm"]))}
    return ImbalanceResponse(table, peaks, skipped, unstable_from_rpm)


@single_threaded
def half_mass_onsets(line: SpeedLine, speed_range, show_progress: bool = False) -> list:
    """Each bearing alone with its share of mass and load (module docstring): one dict per
    bearing (bearing, mass_share_kg, load_newton, onset_speed_rpm, whirl_frequency_hz,
    answer).  A rotor loaded with its bearings' running condition (``rotor.running``: a
    bearing file with ``[journal]``/``[thermal]``) gives each such bearing's onset at the
    running condition of each speed, by the function ``gfbopt stability --bearing FILE
    --speed-range LOW HIGH`` calls (:func:`gfbopt.rotor.running_bearing.running_onset`,
    searched from the geometric mean of the range), with the running point at the onset
    (``thermal_model`` and :data:`~gfbopt.rotor.running_bearing.RUNNING_KEYS`); a thermal
    runaway before the onset is the answer (NaN onset, the message)."""
    rotor = line.rotor
    running = getattr(rotor, "running", None)
    out = []
    for k, (case, load, share) in enumerate(zip(rotor.cases, rotor.loads,
                                                rotor.mass_share_kg)):
        row = {"bearing": load.name, "mass_share_kg": share, "load_newton": load.magnitude}
        spec = None if running is None else running.specs[k]
        try:
            if spec is not None:
                row.update(_running_half_mass(case, spec, speed_range))
            else:
                res = onset_speed(case.bearing, case.rotor, case.load_newton, speed_range,
                                  options=case.options, grid=case.grid, cache=case.cache)
                row.update(onset_speed_rpm=res.onset_speed_rpm,
                           whirl_frequency_hz=res.whirl_frequency_hz, answer=res.answer)
                if running is not None:
                    row.update(_cold_running_columns(case))
        except ParameterError as exc:
            row.update(onset_speed_rpm=math.nan, whirl_frequency_hz=math.nan,
                       answer=str(exc))
        out.append(row)
    return out


def _running_half_mass(case, spec, speed_range) -> dict:
    """One bearing's half-mass onset at the running condition (:func:`half_mass_onsets`)."""
    from .running_bearing import RUNNING_KEYS, running_onset

    found = running_onset(case.bearing, spec, case.rotor, case.load_newton,
                          tuple(speed_range), options=case.options, grid=case.grid,
                          cache=case.cache)
    point = found.get("running") or {}
    return {"onset_speed_rpm": found.get("onset_speed_rpm", math.nan),
            "whirl_frequency_hz": found.get("whirl_frequency_hz", math.nan),
            "answer": found.get("answer") or found.get("message", ""),
            "thermal_model": spec.model_name,
            **{key: point.get(key, math.nan) for key in RUNNING_KEYS[1:]}}


def _cold_running_columns(case) -> dict:
    """The running columns of a bearing with neither table in a rotor whose other bearing
    states them: the cold clearance, no heat."""
    from ..thermal.running import ISOTHERMAL
    from .running_bearing import RUNNING_KEYS

    return {"thermal_model": ISOTHERMAL,
            **dict.fromkeys(RUNNING_KEYS[1:], math.nan),
            "running_clearance_um": case.bearing.radial_clearance * 1e6,
            "centrifugal_growth_um": 0.0, "thermal_growth_um": 0.0,
            "viscosity_pa_s": case.bearing.viscosity}
