"""The rotor transient of a heated rotor on its running line: the model, its start, its result.

A run-up or coast-down of a rotor read with its bearings' ``[journal]``/``[thermal]`` tables
(``load_rotor(path, running=True)``) integrates the rotor model built on the bearings'
**cold** clearances c (their files', the rotor model's reference) with each bearing carrying
its running line (:mod:`.rotor_running`: quasi-steady in temperature, thermal time constants
neglected), applied in the fused films (:class:`.rotor_films.FusedFilms`) as the film offset
(c − c_run(ω))/c and the viscosity ratio μ(ω)/μ_ref.  It starts from the equilibrium at the
start speed's running condition — each bearing's static solution on the bearing at c_run and
μ there (as :func:`gfbopt.rotor.supports.frozen_at_running_condition` builds it), converted to
the cold-c reference: X = e/c = ε c_run/c, Φ = P h/c = P H_run c_run/c (and W likewise).
On the cold-c model the contact criterion H ≤ contact_film is a fixed thickness,
contact_film × c (the frozen orbit's is contact_film × c_run); the kick of a perturbed start is
in cold clearances per rad.  Otherwise a constant-speed orbit on the line (one speed) is the
frozen orbit in another scaling: equal to round-off (tests/unit/test_rotor_heated_rampup.py).
"""
from __future__ import annotations

from dataclasses import fields, replace

import numpy as np

from ..errors import ParameterError
from .rotor_result import RotorTransientResult
from .rotor_running import RunningLinePlan


def heated_model(model, plan: RunningLinePlan):
    """``model`` with each bearing carrying its RunningSchedule (same order, checked by
    label and cold clearance)."""
    bearings = []
    for b, s in zip(model.bearings, plan.schedules):
        if abs(s.cold_clearance_m - b.clearance) > 1e-15 * b.clearance:
            raise ParameterError(f"bearing {b.label}.radial_clearance", b.clearance,
                                 f"the running line was solved for a cold clearance of "
                                 f"{s.cold_clearance_m:g} m")
        bearings.append(replace(b, running=s))
    return replace(model, bearings=tuple(bearings))


def frozen_start(system, plan: RunningLinePlan):
    """The rotor with each bearing at the start speed's running condition (the warm
    geometry of the plan's start cases, no tables): its equilibria are the start."""
    bearings = tuple(replace(b, geometry=case.bearing, running_tables=())
                     for b, case in zip(system.bearings, plan.start_cases))
    return replace(system, bearings=bearings)


def cold_reference(solution, running_clearance: float, cold_clearance: float):
    """A static solution on the bearing at ``running_clearance`` in the cold-c reference:
    ε, H, the deflection and the smallest film times c_run/c; the pressure unchanged."""
    k = running_clearance / cold_clearance
    return replace(solution, eccentricity=solution.eccentricity * k,
                   min_film=solution.min_film * k, film=solution.film * k,
                   deflection=solution.deflection * k)


def start_states(model, batch: int, warm_solutions, plan: RunningLinePlan):
    """States (B, K, L) of the start: each film at its warm equilibrium in the cold-c
    reference; a Kelvin–Voigt foil state W = H − (H_r − δ) with the start's offset δ."""
    from .rotor_setup import equilibrium_states
    from .rotor_layout import layout

    cold = [cold_reference(s, float(p.clearance_m[_index(p, plan)]), p.cold_clearance_m)
            for s, p in zip(warm_solutions, plan.schedules)]
    z = equilibrium_states(model, batch, cold)
    lay = layout(model)
    for k, (b, p) in enumerate(zip(model.bearings, plan.schedules)):
        if lay.foil[k] is not None:     # equilibrium_states' W is H − H_r (no offset)
            j = _index(p, plan)
            lay.foil_of(z, k)[...] += 1.0 - p.clearance_m[j] / p.cold_clearance_m
    return z, cold


def _index(schedule, plan) -> int:
    """The start speed's node (the first node in the direction of travel)."""
    return int(np.argmin(np.abs(schedule.speeds_rpm - plan.start_rpm)))


class HeatedRotorResult(RotorTransientResult):
    """A :class:`~.rotor_result.RotorTransientResult` of a heated rotor: its settings state
    the quasi-steady model and carry the running line (JSON ``running_line``: per bearing
    and solved speed running_clearance_um, film_temperature_c, viscosity_pa_s); its tables
    add ``running_line.csv`` and, in each components table, the interpolated running
    condition of the bearing at each window's speed."""

    schedules: tuple = ()

    def tables(self, run: int = 0) -> dict:
        import pandas as pd

        out = super().tables(run)
        out["running_line.csv"] = pd.DataFrame(self.settings.get("running_line", []))
        for s in self.schedules:
            name = f"components_{s.label}.csv"
            if name in out and len(out[name]):
                at = s.at(out[name]["speed_rpm"].to_numpy())
                out[name] = out[name].assign(**at)
        return out


def heated_result(result: RotorTransientResult, plan: RunningLinePlan) -> HeatedRotorResult:
    """``result`` as a HeatedRotorResult carrying the plan's schedules."""
    values = {f.name: getattr(result, f.name) for f in fields(RotorTransientResult)}
    out = HeatedRotorResult(**values)
    object.__setattr__(out, "schedules", plan.schedules)
    return out
