"""``gfbopt linear``: stiffness and damping against whirl ratio, and the linear threshold.

With ``--loss-factor η > 0`` (structural damping of the bumps) the damping at whirl ratio 0 is
reported as null: hysteretic damping η k/γ is unbounded at zero frequency.

A bearing file with ``[journal]``/``[thermal]``: K and C at the running condition of
``--speed-rpm`` (the equilibrium at the running clearance and μ(T),
:mod:`gfbopt.cli.running_point`), the output naming the model and giving the running
clearance, growths, film temperature and viscosity; a file without them: today's output.
"""
from __future__ import annotations

import sys
import time

from ..errors import ParameterError
from .common import add_operating_point, describe, emit, number, operating_point
from .csv_context import context_options
from ..model_text import foil_words, friction_words


#: largest whirl ratio of a K, C table [-]
MAX_WHIRL_RATIO = 100.0
#: largest rotor mass parameter M̄ [-] (the thresholds of gfbopt's studies are below 100)
MAX_MASS_PARAMETER = 1e6


def register(subparsers) -> None:
    sub = subparsers.add_parser("linear", help="stiffness, damping and linear stability "
                                "threshold")
    add_operating_point(sub)
    sub.add_argument("--whirl-ratio", type=number("whirl-ratio"), nargs="+",
                     default=[0.0, 0.5, 1.0], help="whirl ratios γ for K and C (default 0 0.5 1)")
    sub.add_argument("--frame", default="load", choices=("load", "line-of-centres"),
                     help="axes of K and C (default: load frame)")
    sub.add_argument("--mass", type=number("mass"), default=None,
                     help="also give the least stable eigenvalue at this M̄ = M c ω²/W0")
    sub.add_argument("--loss-factor", type=number("loss-factor"), default=None,
                     help="structural loss factor η of the bump foundation, 0–1: its "
                     "stiffness becomes k(1 + iη sign γ) in the perturbation (default 0, or "
                     "the bearing file's)")
    sub.set_defaults(handler=run)


def run(args) -> int:
    from ..linear import coefficients, least_stable_mode, linear_threshold, linearise
    from ..static import solve_static, solver_for

    from ..thermal.running import ISOTHERMAL
    from .running_point import no_running_state, running_fields, running_operating_point

    running = running_operating_point(args)
    point = None
    if running is None:                          # no [journal]/[thermal]: today's route
        op = operating_point(args)
    else:
        op, point, solver = running
    if args.mass is not None and not 0 < args.mass <= MAX_MASS_PARAMETER:
        raise ParameterError("--mass", args.mass, f"must lie in (0, {MAX_MASS_PARAMETER:g}]")
    for gamma in args.whirl_ratio:
        if not 0 <= gamma <= MAX_WHIRL_RATIO:
            raise ParameterError("--whirl-ratio", gamma, f"must lie in [0, {MAX_WHIRL_RATIO:g}]"
                                 " (the rotor's roots lie below 3 times the shaft speed)")
    if point is not None and op is None:         # thermal runaway or closure at the speed
        return no_running_state(point, "linear", args.json)
    t0 = time.perf_counter()
    if point is None:
        solver = solver_for(op.model, op.grid)
    sol = solve_static(op.model, eccentricity=op.eccentricity, load=op.load, solver=solver)
    if not sol.success:
        print(f"gfbopt: error: static equilibrium did not converge ({sol.message}); "
              "no linearisation", file=sys.stderr)
        return 1
    lin = linearise(sol, solver)
    threshold = linear_threshold(lin)
    coeffs = coefficients(lin, args.whirl_ratio)
    if args.frame == "line-of-centres":
        coeffs = coeffs.in_line_of_centres_frame()
    mode = least_stable_mode(lin, args.mass, threshold) if args.mass is not None else None
    out = {**describe(op, frame=args.frame),
           "critical_mass": threshold.critical_mass, "whirl_ratio": threshold.whirl_ratio,
           "stable_for_all_masses": threshold.stable_for_all_masses,
           "threshold_message": threshold.message,
           "stiffness": {f"{g:g}": coeffs.stiffness[k].tolist()
                         for k, g in enumerate(coeffs.whirl_ratio)},
           "damping": {f"{g:g}": coeffs.damping[k].tolist()
                       for k, g in enumerate(coeffs.whirl_ratio)},
           "load": sol.load, "eccentricity": sol.eccentricity,
           "attitude_angle_deg": sol.attitude_angle_deg,
           "success": bool(sol.success and threshold.success),
           "message": sol.message or threshold.message,
           "wall_time_s": time.perf_counter() - t0}
    if mode is not None:
        out.update({"mass": args.mass, "growth_rate": mode.real, "mode_whirl_ratio": mode.imag})
    if point is not None:
        out.update(running_fields(point))
    else:                                    # a file without [journal]/[thermal]
        out["thermal_model"] = ISOTHERMAL

    def report() -> str:
        model = op.model
        friction = friction_words(model.options())
        lines = [f"gfbopt linear — {foil_words(model.options())}, {model.film} film"
                 + (f", {friction}" if friction else "") + f", grid {op.grid}",
                 f"  ε = {sol.eccentricity:.5f}, load W/(p_a R²) = {sol.load:.5f}, "
                 f"attitude {out['attitude_angle_deg']:.3f} deg",
                 (f"  critical mass M̄ = M c ω²/W0 = {threshold.critical_mass:.5g} at whirl "
                  f"ratio {threshold.whirl_ratio:.4f}" if not threshold.stable_for_all_masses
                  else f"  {threshold.message}"),
                 f"  stiffness K c/(p_a R²) and damping C c ω/(p_a R²), {args.frame} frame:"]
        for k, g in enumerate(coeffs.whirl_ratio):
            kk, cc = coeffs.stiffness[k], coeffs.damping[k]
            lines.append(f"    γ = {g:<6g} K = [[{kk[0, 0]:.4g}, {kk[0, 1]:.4g}], "
                         f"[{kk[1, 0]:.4g}, {kk[1, 1]:.4g}]]  C = [[{cc[0, 0]:.4g}, "
                         f"{cc[0, 1]:.4g}], [{cc[1, 0]:.4g}, {cc[1, 1]:.4g}]]")
        if mode is not None:
            lines.append(f"  least stable mode at M̄ = {args.mass:g}: growth rate "
                         f"{mode.real:.4g} per rad, whirl ratio {mode.imag:.4f}")
        if point is not None:
            from .stability import running_lines

            lines.extend(running_lines(out["running"]))
        else:
            lines.append(f"  clearance model: {out['thermal_model']}")
        return "\n".join(lines)

    emit(out, args.json, report, context_options(args, **describe(op, frame=args.frame)))
    return 0 if out["success"] else 1
