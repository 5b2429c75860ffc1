"""The rotor in time, for engineers: an orbit at a constant speed, or a run-up / coast-down.

    from gfbopt.inputs.rotor_system import load_rotor
    from gfbopt.transient.rotor_analysis import rotor_orbit, rotor_ramp
    system = load_rotor("problems/rotors/study_rotor.toml")
    orbit = rotor_orbit(system, 45_000, revolutions=200, grid=Grid(72, 20))
    ramp = rotor_ramp(system, 5_000, 60_000, rate_rpm_per_s=20_000, grid=Grid(72, 20))
    ramp.to_dict(); ramp.tables()

Both build the transient model once (:mod:`.rotor_setup`: statics, each bearing's
equilibrium at the start speed, its film model), start from that equilibrium (optionally
perturbed), integrate (:mod:`.rotor_run`) and post-process (:mod:`.spectra`,
:mod:`.rotor_result`).  A run-up's film follows the speed through Λ(t) in the engine itself
(no rebuild); its time unit is the top speed's rotation, τ = ω_max t.

A heated rotor (bearing files with ``[journal]``/``[thermal]``, ``load_rotor(...,
running=True)``): a run-up or coast-down follows each bearing's running line, quasi-steady in
temperature — the running condition of the instantaneous speed, the temperatures taken as
settled, the thermal time constants neglected (:mod:`.rotor_running`, :mod:`.rotor_heated`);
a thermal runaway or closure on the way ends the ramp at the last speed that runs, with the
verdict in ``running_end`` (reported, not raised).  A constant-speed orbit holds its speed's
running condition.

Limits, refused before any solve (ParameterError, one line): a rate ≤ 0, a run-up whose end
speed is not above its start (a coast-down whose end is not below it), more shaft
revolutions than :data:`MAX_REVOLUTIONS` without ``force=True`` (each costs ≈ 0.05–0.5 s).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Union

import numpy as np

from ..errors import ParameterError
from ..inputs.checks import check_positive
from ..inputs.grid import Grid, as_grid
from ..inputs.rotor_system import RotorSystem
from ..static import SolverCache
from .rotor_io import rotor_input
from .rotor_result import RotorTransientResult, summarise
from .rotor_run import CONTACT_FILM, integrate_rotor
from .rotor_setup import RotorInput, build_model, equilibrium_states, set_station_velocities
from .rotor_running import STEP_RPM
from .rotor_system import runs

#: most shaft revolutions a run may take without ``force`` (a run-up 5,000 → 60,000 rpm at
#: 5,000 rpm/s is ≈ 6,000)
MAX_REVOLUTIONS = 20_000
#: rkc's accuracy limit of a ramp [rad of rotation at the top speed]: 30 steps per top-speed
#: revolution.  At Δτ = 0.2 the one-bearing accuracy study (gfbopt.transient.rkc) finds the
#: whirl ratio within 3e-4 and the growth rate within 2e-5 per rad of RK4's — ample for a
#: waterfall and the 1× response — at ≈ 0.7× the cost of Δτ = 0.1, the orbits' default.
RAMP_MAX_STEP = 0.2
#: starting perturbations: none (the equilibrium), a cylindrical or conical kick of the
#: journal velocities (both bearings moving together, or opposite)
PERTURBATIONS = ("none", "cylindrical", "conical")
#: how a heated rotor's orbit is run: at its speed's running condition on the bearing at
#: c_run ('frozen'), or on the cold-c model with the running line's one speed ('line')
RUNNING_PATHS = ("frozen", "line")


@dataclass(frozen=True)
class SpeedProfile:
    """kind : 'orbit', 'run-up' or 'coast-down'; start_rpm, end_rpm; rate_rpm_per_s (0 for
    an orbit); duration_s; revolutions (shaft revolutions over the run)."""

    kind: str
    start_rpm: float
    end_rpm: float
    rate_rpm_per_s: float
    duration_s: float
    revolutions: float

    @property
    def top_rpm(self) -> float:
        return max(self.start_rpm, self.end_rpm)

    def to_dict(self) -> dict:
        return {"run": self.kind, "start_speed_rpm": self.start_rpm,
                "end_speed_rpm": self.end_rpm, "rate_rpm_per_s": self.rate_rpm_per_s,
                "duration_s": self.duration_s, "revolutions": self.revolutions}



def _limit(revolutions: float, force: bool, name: str) -> None:
    if revolutions > MAX_REVOLUTIONS and not force:
        raise ParameterError(name, round(revolutions, 1), f"is more than {MAX_REVOLUTIONS:,} "
                             "shaft revolutions (≈ 0.05–0.5 s each); pass force=True "
                             "(--force) to run it anyway")


def orbit_profile(speed_rpm, revolutions, force: bool = False) -> SpeedProfile:
    speed = check_positive("speed_rpm", speed_rpm)
    revs = check_positive("revolutions", revolutions)
    _limit(revs, force, "revolutions")
    return SpeedProfile("orbit", speed, speed, 0.0, revs * 60.0 / speed, revs)


def ramp_profile(start_rpm, end_rpm, rate_rpm_per_s, kind: str = "run-up",
                 force: bool = False) -> SpeedProfile:
    """A linear speed ramp; a run-up must end above its start, a coast-down below."""
    start, end = check_positive("start_rpm", start_rpm), check_positive("end_rpm", end_rpm)
    rate = check_positive("rate_rpm_per_s", rate_rpm_per_s)
    if kind == "run-up" and not end > start:
        raise ParameterError("end_rpm", end, f"a run-up must end above its start speed "
                             f"{start:g} rpm (use a coast-down to slow down)")
    if kind == "coast-down" and not end < start:
        raise ParameterError("end_rpm", end, f"a coast-down must end below its start speed "
                             f"{start:g} rpm (use a run-up to speed up)")
    if kind not in ("run-up", "coast-down"):
        raise ParameterError("kind", kind, "must be 'run-up' or 'coast-down'")
    duration = abs(end - start) / rate
    revs = 0.5 * (start + end) / 60.0 * duration
    _limit(revs, force, "revolutions of the ramp")
    return SpeedProfile(kind, start, end, rate, duration, revs)


def progress_units(profile: SpeedProfile) -> tuple:
    """(total, unit) of a run's progress: revolutions of an orbit (uniform in time), the
    simulated milliseconds of a ramp (its revolutions are not: the ETA would mislead)."""
    if profile.kind == "orbit":
        return max(1, int(math.ceil(profile.revolutions))), "rev"
    return max(1, int(math.ceil(profile.duration_s * 1e3))), "ms simulated"


def _rotor(rotor: Union[RotorSystem, RotorInput]) -> RotorInput:
    return rotor if isinstance(rotor, RotorInput) else rotor_input(rotor)


def _check_batch(name: str, values) -> np.ndarray:
    arr = np.atleast_1d(np.asarray(values, dtype=float))
    if arr.ndim != 1 or not arr.size or not np.all(np.isfinite(arr)) or np.any(arr < 0):
        raise ParameterError(name, values, "must be finite numbers >= 0, one per run")
    return arr


def run_profile(rotor: Union[RotorSystem, RotorInput], profile: SpeedProfile, *,
                grid: Grid, method: str = "rkc", perturbation: str = "cylindrical",
                kick: float = 1e-3, inertia_scale=1.0, imbalance_scale=1.0,
                time_step: Optional[float] = None, stages: Optional[int] = None,
                reference_whirl_ratio: Optional[float] = None,
                contact_film: float = CONTACT_FILM, foil_travel_m: Optional[float] = None,
                sample_every: float = 0.2, progress=None,
                cache: Optional[SolverCache] = None, system: Optional[RotorSystem] = None,
                linear_onset=None, running_path: str = "frozen",
                running_step_rpm: float = STEP_RPM, force: bool = False,
                **post) -> RotorTransientResult:
    """Run ``profile`` for a batch of runs (one per entry of ``inertia_scale`` ×
    ``imbalance_scale``, broadcast) and post-process it (:func:`.rotor_result.summarise`).

    perturbation : 'none', 'cylindrical' or 'conical' (journal velocity ``kick``
    [clearances per rad] at both bearings, x and y each kick/√2, together or opposite);
    inertia_scale μ multiplies M and G (loads unchanged; μ = 1 is the rotor);
    imbalance_scale multiplies every imbalance plane; foil_travel_m : bump travel [m] before
    the foil is exhausted (None: not checked); the other options as :func:`.rotor_run
    .integrate_rotor`.  A heated rotor (bearings with [journal]/[thermal]): a ramp follows
    each bearing's running line, quasi-steady in temperature (thermal time constants
    neglected), solved at least every ``running_step_rpm`` and interpolated by a monotone
    cubic in speed (:mod:`.rotor_running`); an orbit holds its speed's running condition
    (``running_path`` 'frozen', or 'line': the orbit on the cold-c model with the line's
    one speed).
    """
    if perturbation not in PERTURBATIONS:
        raise ParameterError("perturbation", perturbation,
                             f"must be one of {', '.join(PERTURBATIONS)}")
    grid = as_grid(grid)
    check_running_friction(rotor, profile, running_path)
    cache = cache if cache is not None else SolverCache(grid)
    requested = profile
    rotor, running, plan = _at_running_condition(rotor, profile, grid, cache, running_path,
                                                 running_step_rpm)
    if running is not None:
        system = rotor
    if plan is not None:                # the ramp ends where the running line does
        profile = _to_end(profile, plan, force)
    inp = _rotor(rotor)
    mu, scale = np.broadcast_arrays(_check_batch("inertia_scale", inertia_scale),
                                    _check_batch("imbalance_scale", imbalance_scale))
    if np.any(mu <= 0):
        raise ParameterError("inertia_scale", inertia_scale, "must be > 0")
    if np.any(scale > 0) and not inp.imbalance:
        raise ParameterError("imbalance_scale", imbalance_scale, "scales the imbalance, but "
                             "the rotor has no imbalance plane; give one or set it to 0")
    travel = None
    if foil_travel_m is not None:
        travel = check_positive("foil_travel_m", foil_travel_m) / inp.bearings[0].geometry.radial_clearance
    model, solutions = build_model(inp, profile.start_rpm, grid,
                                   reference_speed_rpm=profile.top_rpm,
                                   reference_whirl_ratio=reference_whirl_ratio, cache=cache)
    if plan is not None:
        model, solutions, z0 = _on_running_line(model, inp, rotor, plan, profile, grid, cache,
                                                reference_whirl_ratio)
    omega = model.reference_speed
    r0 = profile.start_rpm / profile.top_rpm
    sign = 1.0 if profile.end_rpm >= profile.start_rpm else -1.0
    ramp = sign * profile.rate_rpm_per_s * math.pi / 30.0 / omega ** 2
    batch = runs(mu.size, speed=r0, ramp=ramp, inertia_scale=mu, imbalance_scale=scale)
    z = (equilibrium_states(model, batch.size) if plan is None
         else np.repeat(z0, batch.size, axis=0))
    if perturbation != "none":
        v = check_positive("kick", kick) / math.sqrt(2)
        sign_b = 1.0 if perturbation == "cylindrical" else -1.0
        z = set_station_velocities(model, z, [[v, v], [sign_b * v, sign_b * v]])
    duration = profile.duration_s * omega
    run = integrate_rotor(model, batch, duration, z, method=method, time_step=time_step,
                          stages=stages, sample_every=sample_every, contact_film=contact_film,
                          foil_travel=travel, progress=progress,
                          progress_total=progress_units(profile)[0],
                          exact_end=profile.kind != "orbit",
                          max_step=RAMP_MAX_STEP if profile.kind != "orbit" else 0.1)
    settings = {"grid": str(grid), "method": method, "perturbation": perturbation,
                "kick": kick if perturbation != "none" else 0.0,
                "reference_whirl_ratio": reference_whirl_ratio,
                "contact_film": contact_film, "foil_travel_m": foil_travel_m,
                "sample_every_rad": sample_every,
                "max_step_rad": RAMP_MAX_STEP if profile.kind != "orbit" else 0.1}
    if running is not None:             # the clearance model each bearing was held at
        settings["clearance_model"] = running["model"]
        settings["running_condition"] = running["bearings"]
    if plan is not None:                # the running line each bearing followed
        settings.update(plan.settings())
        settings["requested_end_rpm"] = requested.end_rpm
        settings["running_step_rpm"] = running_step_rpm
    result = summarise(run, profile, inp, solutions, settings, system=system,
                       linear_onset=linear_onset, **post)
    if plan is None:
        return result
    from .rotor_heated import heated_result

    if plan.verdict is not None:
        result.notes.append("Running line: " + plan.verdict["message"])
    result.notes.append("Clearance model: " + settings["clearance_model"] + "; the largest "
                        "interpolation miss at a solved midpoint "
                        f"{plan.errors['clearance_um'] * 1e3:.3g} nm of clearance, "
                        f"{plan.errors['viscosity_relative']:.2g} of μ; contact is H ≤ "
                        f"{contact_film:g} of the cold clearance (a fixed thickness).")
    opening = [sc.label for sc in plan.schedules
               if np.any(sc.clearance_m > sc.cold_clearance_m)
               or np.any(sc.viscosity_pa_s < sc.reference_viscosity_pa_s)]
    if opening:     # rotor_system.stiffness bounds the films at c and μ_ref (conservative
        result.notes.append(   # only while c_run ≤ c and μ ≥ μ_ref)
            "Step control: the films' stiffness bound is taken at the cold clearance and "
            f"μ_ref, which underestimates it where the running clearance opens or the gas "
            f"thins (bearing {', '.join(opening)}); check the run with a smaller --time-step.")
    return heated_result(result, plan)


def check_running_friction(rotor, profile: SpeedProfile, running_path: str = "frozen",
                           name: str = "profile", value=None) -> None:
    """Refuse, before any work, a run on the running line (a ramp, or an orbit with
    ``running_path`` 'line') of a rotor whose bearings state both [journal]/[thermal] and
    the bumps' friction: the sliders' play operator has no film offset.  ``name``/``value``:
    what the caller calls the run (the command line: its flag)."""
    if profile.kind == "orbit" and running_path != "line":
        return
    both = [b for b in getattr(rotor, "bearings", ()) if getattr(b, "running_tables", ())
            and (getattr(b.options, "friction_coefficient", None) or 0.0) > 0]
    if both:
        where = "; ".join(f"bearing {b.name} ({b.file}) friction_coefficient = "
                          f"{b.options.friction_coefficient:g}" for b in both)
        raise ParameterError(name, profile.kind if value is None else value,
                             f"{where} with [journal]/[thermal]: a run-up or coast-down on "
                             "the running line with bump friction is not modelled (the "
                             "sliders' play operator has no film offset); state no "
                             "friction_coefficient, or hold one speed (--orbit)")


def _to_end(profile: SpeedProfile, plan, force: bool) -> SpeedProfile:
    """The profile ending where the running line ends (a failure above, on a run-up)."""
    if plan.end_rpm == profile.end_rpm or profile.kind == "orbit":
        return profile
    return ramp_profile(profile.start_rpm, plan.end_rpm, profile.rate_rpm_per_s,
                        profile.kind, force)


def _on_running_line(model, inp, rotor, plan, profile, grid, cache, reference_whirl_ratio):
    """(the cold-c model carrying each bearing's running line, the start's static solutions
    in the cold-c reference, the start state (1, K, L)): the equilibria at the start speed's
    running condition (:func:`.rotor_heated.frozen_start`), converted
    (:func:`.rotor_heated.start_states`)."""
    from .rotor_heated import frozen_start, heated_model, start_states
    from .rotor_setup import bearing_equilibria

    warm = rotor_input(frozen_start(rotor, plan))
    warm_solutions, _ = bearing_equilibria(warm, profile.start_rpm, grid, cache)
    model = heated_model(model, plan)
    z, cold = start_states(model, 1, warm_solutions, plan)
    return model, cold, z


def _at_running_condition(rotor, profile, grid, cache, path: str, step_rpm: float) -> tuple:
    """(the rotor to integrate, its frozen running summary or None, the running line or
    None).  A rotor read with its bearings' [journal]/[thermal] tables
    (load_rotor(..., running=True)):

    * a run-up or coast-down (or an orbit with ``running_path="line"``) follows each
      bearing's running line (:mod:`.rotor_running`): at every instant the running condition
      of the instantaneous speed, quasi-steady in temperature (the temperatures settled at
      each speed, the thermal time constants neglected), on the cold-c model; a speed where
      a heat balance runs away or a clearance closes ends the ramp there, with that verdict
      (reported, not raised);
    * a constant-speed orbit (``running_path="frozen"``, the default) holds each bearing at
      the running condition of that speed on the bearing at c_run
      (:func:`gfbopt.rotor.supports.frozen_at_running_condition`)."""
    heated = [b for b in getattr(rotor, "bearings", ()) if getattr(b, "running_tables", ())]
    if path not in RUNNING_PATHS:
        raise ParameterError("running_path", path, f"must be one of {', '.join(RUNNING_PATHS)}")
    if not heated:
        return rotor, None, None
    if profile.kind != "orbit" or path == "line":
        from .rotor_running import solve_running_line

        plan = solve_running_line(rotor, grid, profile.start_rpm, profile.end_rpm,
                                  cache=cache, step_rpm=step_rpm)
        return rotor, None, plan
    b = heated[0]
    from ..rotor.supports import frozen_at_running_condition

    frozen, running = frozen_at_running_condition(rotor, profile.start_rpm, grid)
    if running.get("failure"):
        raise ParameterError(f"bearing {b.name} ({b.file})", "[journal]/[thermal]",
                             f"has no running state to hold: {running['failure']}")
    return frozen, running, None


def rotor_orbit(rotor, speed_rpm: float, revolutions: float, *, grid: Grid,
                force: bool = False, **options) -> RotorTransientResult:
    """The rotor at a constant ``speed_rpm`` for ``revolutions`` from its equilibrium
    (perturbed as ``perturbation``); journal orbits at both bearings, the limit cycle."""
    return run_profile(rotor, orbit_profile(speed_rpm, revolutions, force), grid=grid,
                       system=rotor if isinstance(rotor, RotorSystem) else None, force=force,
                       **options)


def rotor_ramp(rotor, start_rpm: float, end_rpm: float, rate_rpm_per_s: float, *,
               grid: Grid, force: bool = False, **options) -> RotorTransientResult:
    """A run-up (end above start) or coast-down (end below) at ``rate_rpm_per_s``; the
    waterfall, 1× and subsynchronous components against speed, the subsynchronous line's
    appearance against the linear onset."""
    kind = "run-up" if float(end_rpm) > float(start_rpm) else "coast-down"
    options.setdefault("perturbation", "none")
    return run_profile(rotor, ramp_profile(start_rpm, end_rpm, rate_rpm_per_s, kind, force),
                       grid=grid, system=rotor if isinstance(rotor, RotorSystem) else None,
                       force=force, **options)
