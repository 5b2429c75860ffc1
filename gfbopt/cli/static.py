"""``gfbopt static``: one static equilibrium (non-dimensional, or SI from a bearing file).

A bearing file with ``[journal]``/``[thermal]``: the equilibrium at the running condition of
``--speed-rpm`` (the running clearance and μ(T), :mod:`gfbopt.cli.running_point`), its
output naming the model (``thermal_model``) and giving running_clearance_um,
centrifugal_growth_um, thermal_growth_um, film_temperature_c and viscosity_pa_s; a file
without them gives today's output unchanged."""
from __future__ import annotations

import math
import sys

from ..errors import ParameterError
from .common import add_operating_point, describe, emit, number, operating_point
from .csv_context import context_options

#: default CPU-time budget of one IPOPT solve [s] (``--time-limit``); the iteration budget is
#: IPOPT's max_iter of gfbopt.static.build.default_ipopt_options (60 per solve)
TIME_LIMIT_S = 600.0


def register(subparsers) -> None:
    sub = subparsers.add_parser("static", help="static equilibrium at one operating point")
    add_operating_point(sub)
    sub.add_argument("--time-limit", type=number("time-limit"), default=TIME_LIMIT_S,
                     help=f"CPU-time budget of each IPOPT solve [s] (default {TIME_LIMIT_S:g}; "
                     "with the iteration budget of 60 per solve): a solve that exceeds it "
                     "fails with IPOPT's status, exit 1")
    sub.set_defaults(handler=run)


def run(args) -> int:
    from ..static import solve_static, solver_for
    from ..static.build import default_ipopt_options

    if not 0 < args.time_limit <= 1e6:
        raise ParameterError("--time-limit", args.time_limit, "must lie in (0, 1e6] s")
    from ..thermal.running import ISOTHERMAL
    from .running_point import no_running_state, running_fields, running_operating_point

    ipopt = {"ipopt.max_cpu_time": float(args.time_limit)}
    running = running_operating_point(args, ipopt_options=ipopt)
    if running is None:                          # no [journal]/[thermal]: today's route
        op, point = operating_point(args), None
        solver = solver_for(op.model, op.grid, ipopt_options=ipopt)
    else:
        op, point, solver = running
        if op is None:                           # thermal runaway or closure at the speed
            return no_running_state(point, "static", args.json)
    sol = solve_static(op.model, eccentricity=op.eccentricity, load=op.load, solver=solver)
    budget = (f"budget per IPOPT solve: {default_ipopt_options()['ipopt.max_iter']} "
              f"iterations, {args.time_limit:g} s CPU (--time-limit)")
    out = {**describe(op), **sol.to_dict(), "message": sol.message}
    if op.geometry is not None:
        from ..physics.torque import drag_torque_and_power

        out["min_film_thickness_um"] = sol.min_film * op.geometry.radial_clearance * 1e6
        out["load_newton"] = op.geometry.load_newton(sol.load)
        out["drag_torque_nm"], out["power_loss_w"] = drag_torque_and_power(
            sol.torque_ratio, op.model.bearing_number, op.geometry)
    if point is not None:
        out.update(running_fields(point))
    else:                                    # a file without [journal]/[thermal]
        out["thermal_model"] = ISOTHERMAL
    emit(out, args.json, lambda: _report(out), context_options(args, **describe(op)))
    if not sol.success:
        print(f"gfbopt: solve did not converge: {sol.message} (status {sol.status}, residual "
              f"{sol.residual:.3g}; {budget})", file=sys.stderr)
        return 1
    return 0


def _report(out: dict) -> str:
    from ..model_text import built_words, foil_words, friction_words

    friction = friction_words(out)
    lines = [f"gfbopt static — {foil_words(out)}, {out['film']} film"
             + (f", {friction}" if friction else "") + f", grid {out['grid']}",
             f"  Λ = {out['bearing_number']:.4g}, S = {out['compliance']:.4g}, "
             f"L/D = {out['length_ratio']:.4g}, C = {out['top_foil_coefficient']:.4g}",
             f"  eccentricity ε          {out['eccentricity']:.5f}",
             f"  load W/(p_a R²)         {out['load']:.5f}"]
    if out["eccentricity"] == 0.0:
        # concentric: the load carried is the film force's magnitude; say its direction
        angle = out["film_force_angle_deg"]
        lines += [f"  film force direction    {angle:.1f} deg from the load line, in the "
                  "direction of rotation (concentric journal: the load is |F|)"
                  if angle is not None and math.isfinite(angle) else
                  "  film force direction    none (no film force on the concentric journal)",
                  "  attitude angle          none (concentric journal: no line of centres)"]
    else:
        lines.append(f"  attitude angle          {out['attitude_angle_deg']:.3f} deg")
    lines += [f"  minimum film h/c        {out['min_film']:.5f} at "
              f"{out['min_film_angle_deg']:.1f} deg from the load line",
              f"  drag torque / Petroff's {out['torque_ratio']:.5f}"]
    zones = [{"start_deg": a, "end_deg": b} | (
        {"friction_coefficient": out["zones_friction_coefficient"][k]}
        if out.get("zones_friction_coefficient") else {})
        for k, (a, b) in enumerate(out.get("zones_deg") or [])]
    built = built_words({**out, "zones": zones})       # the phrase of every text report
    if built:
        lines.append(f"  as built: {built}")
    if "min_film_thickness_um" in out:
        lines.append(f"  minimum film            {out['min_film_thickness_um']:.2f} µm "
                     f"(load {out['load_newton']:.2f} N at {out['speed_rpm']:.0f} rpm)")
        lines.append(f"  drag torque             {out['drag_torque_nm'] * 1e3:.4g} mN m, power "
                     f"loss {out['power_loss_w']:.4g} W")
    if out.get("running"):
        from .stability import running_lines

        lines += running_lines(out["running"])
    else:
        lines.append(f"  clearance model: {out['thermal_model']}")
    lines.append(f"  solver: {out['status']}, {out['iterations']} iterations, residual "
                 f"{out['residual']:.1e}, {out['solve_time_s']:.3f} s"
                 + ("" if out["success"] else "  ** NOT CONVERGED **"))
    return "\n".join(lines)
