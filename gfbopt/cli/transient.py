"""``gfbopt orbit`` and ``gfbopt critical-mass``: nonlinear transients of a rigid rotor."""
from __future__ import annotations

import math

from .common import add_operating_point, describe, emit, number, operating_point, progress_bar


def register(subparsers) -> None:
    orb = subparsers.add_parser("orbit", help="journal-centre orbit of a rigid rotor "
                                "(transient)")
    add_operating_point(orb)
    orb.add_argument("--mass", type=number("mass"), required=True, help="M̄ = M c ω²/W0 [-]")
    orb.add_argument("--revolutions", type=number("revolutions"), default=20.0,
                     help="shaft revolutions to integrate (default 20)")
    orb.add_argument("--kick", type=number("kick"), default=1e-3,
                     help="initial journal speed dX/dτ = dY/dτ = kick/√2 (default 1e-3)")
    orb.add_argument("--time-step", type=number("time-step"), default=None,
                     help="Δτ [rad] (rk4 only; default: 0.9 × the RK4 stability limit)")
    orb.add_argument("--plot", default=None, help="write the polar orbit plot to this PNG")
    orb.add_argument("--method", default="rk4", choices=("rk4", "bdf"),
                     help="integration method (default rk4)")
    orb.add_argument("--csv", default=None, help="write the orbit table to this CSV")
    orb.set_defaults(handler=run_orbit)

    crit = subparsers.add_parser("critical-mass", help="nonlinear critical mass from "
                                 "transients")
    add_operating_point(crit)
    crit.add_argument("--tolerance", type=number("tolerance"), default=0.005,
                      help="relative tolerance on M̄_crit (default 0.005)")
    crit.add_argument("--revolutions", type=number("revolutions"), default=5.0,
                      help="revolutions per transient (default 5)")
    crit.add_argument("--batch", type=int, default=8, help="rotors per batch (default 8)")
    crit.add_argument("--method", default="rk4", choices=("rk4", "bdf"),
                      help="integration method (default rk4)")
    crit.add_argument("--no-linear-start", action="store_true",
                      help="do not centre the search on the linear threshold")
    crit.set_defaults(handler=run_critical_mass)


def _setup(args):
    from ..static import solve_static, solver_for
    from ..transient import transient_model

    op = operating_point(args)
    solver = solver_for(op.model, op.grid)
    sol = solve_static(op.model, eccentricity=op.eccentricity, load=op.load, solver=solver)
    return op, solver, sol, transient_model(sol)


def run_orbit(args) -> int:
    from ..transient import integrate_orbits

    op, _, sol, tm = _setup(args)
    options = {} if args.time_step is None else {"time_step": args.time_step}
    orbit = integrate_orbits(tm, [args.mass], args.revolutions, kick=args.kick,
                             progress=progress_bar("orbit", not args.json),
                             method=args.method, **options)
    table = orbit.to_frame(0)
    if args.csv:
        table.to_csv(args.csv, index=False, float_format="%.8g")
    if args.plot:
        from ..plotting import plot_orbits, save_figure

        model = op.model
        ax = plot_orbits({f"M̄ = {args.mass:g}: {orbit.verdict[0]}": table},
                         title=f"{model.foil} foil, ε0 = {sol.eccentricity:.3g}, "
                         f"Λ = {model.bearing_number:g}, S = {model.compliance:g}")
        save_figure(ax.figure, args.plot)
    settings = describe(op, method=args.method, kick=args.kick)
    out = {**settings, **orbit.to_dict(0), "eccentricity": sol.eccentricity,
           "load": sol.load, "attitude_angle_deg": math.degrees(sol.attitude_angle)}
    emit(out, args.json, lambda: (
        f"gfbopt orbit — M̄ = {args.mass:g}: {out['verdict']}, growth rate "
        f"{out['growth_rate']:.3g} per rad, whirl ratio {out['whirl_ratio']:.4g}, "
        f"min film {out['min_film']:.4g}, {out['revolutions']:.1f} revolutions "
        f"(Δτ = {orbit.time_step:.3g}) in {orbit.wall_time_s:.1f} s"
        + ("" if orbit.success else f"  ** FAILED: {orbit.message}")), settings)
    return 0 if orbit.success else 1


def run_critical_mass(args) -> int:
    from ..linear import linear_threshold, linearise
    from ..transient import find_critical_mass

    op, solver, sol, tm = _setup(args)
    linear = linear_threshold(linearise(sol, solver))
    estimate = None if args.no_linear_start else linear.critical_mass
    result = find_critical_mass(tm, tolerance=args.tolerance, linear_estimate=estimate,
                                batch=args.batch, revolutions=args.revolutions,
                                progress=progress_bar("critical mass", not args.json),
                                method=args.method)
    settings = describe(op, method=args.method, tolerance=args.tolerance,
                        revolutions_per_transient=args.revolutions, batch=args.batch)
    out = {**settings, **result.to_dict(),
           "linear_critical_mass": linear.critical_mass,
           "linear_whirl_ratio": linear.whirl_ratio, "eccentricity": sol.eccentricity,
           "load": sol.load, "attitude_angle_deg": math.degrees(sol.attitude_angle),
           "history": list(result.history)}
    emit(out, args.json, lambda: (
        f"gfbopt critical-mass — M̄_crit = {result.critical_mass:.5g} (bracket "
        f"{result.bracket[0]:.5g}–{result.bracket[1]:.5g}), whirl ratio "
        f"{result.whirl_ratio:.4g}; linear {linear.critical_mass:.5g} at "
        f"{linear.whirl_ratio:.4g}; {result.transients} transients, "
        f"{result.wall_time_s:.1f} s" + ("" if result.success else
                                          f"  ** FAILED: {result.message}")), settings)
    return 0 if result.success else 1
