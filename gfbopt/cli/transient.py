"""``gfbopt orbit`` and ``gfbopt critical-mass``: nonlinear transients of a rigid rotor.

Integration methods (``--method``): ``rkc`` (default), damped Runge–Kutta–Chebyshev, the
step chosen for accuracy and the stages for stability; ``rk4``, classic Runge–Kutta at 0.9 ×
its stability limit, the reference; ``bdf``, scipy's implicit BDF (rigid and simple foil
only).  Why rkc is the default (benchmarks/bench_critical_mass.py): at the default 144 × 36
grid (ε = 0.4, Λ = 2, S = 1, one core) the same two-transient critical-mass search takes
1.9 s with rkc, 26 s with rk4 and 29 s with bdf, all within 0.06 % of the linear threshold,
and the README's 20-revolution orbit 7 s with rkc, where rk4 needs 15× more evaluations.
``critical-mass`` starts from the least-stable linear mode shape by default (``--start``).

Structural damping (``--loss-factor η``, or a bearing file's ``loss_factor``): the foil
deflection becomes a Kelvin–Voigt state, τ_f dW/dτ + W = S q with τ_f = η/ν_ref
(:mod:`gfbopt.transient.foil_state`); ν_ref is the linear threshold whirl ratio of the damped
bearing unless ``--reference-whirl-ratio`` gives it, and both are printed.  Supported by rkc
and rk4 for both deflection laws, by bdf for the axial-mean law; refused for the beam foil
and for a foil without bumps (rigid, S = 0), in one line before anything is solved.

A bearing file with ``[journal]``/``[thermal]``: the bearing held at its running condition at
``--speed-rpm`` for the whole transient (constant speed, the temperatures taken as settled),
exactly as ``gfbopt static`` holds it (:mod:`gfbopt.cli.running_point`: the running clearance,
μ(T) and the model; ``--eccentricity`` refused with the heat balance); the output names the
model (``thermal_model``) and gives the running point's fields.  A file without the tables:
today's output.
"""
from __future__ import annotations

import math

from .common import (FractionProgress, add_operating_point, describe, emit, number,
                     operating_point)
from .running_point import answer_text, point_fields
from .si import critical_mass_in_si, orbit_in_si
from .csv_context import HELP as CSV_HELP, context_options, write_csv

#: One line of evidence for the default method (benchmarks/bench_critical_mass.py).
METHOD_EVIDENCE = ("At the default 144×36 grid (ε = 0.4, Λ = 2, S = 1, one core) the same "
                   "critical-mass search takes 1.9 s with rkc, 26 s with rk4 and 29 s with "
                   "bdf, all within 0.06 %% of the linear threshold; the 20-revolution orbit "
                   "7 s with rkc (rk4 needs 15× more evaluations)")
METHOD_HELP = ("integration method: rkc (default; damped Runge–Kutta–Chebyshev), rk4 (the "
               "reference), bdf (implicit; rigid and simple foil only, axial-mean law). "
               + METHOD_EVIDENCE)
METHODS = ("rkc", "rk4", "bdf")
#: default largest number of time steps of one orbit (``--max-steps`` raises it): about an
#: hour at 144 × 36 with rkc
MAX_STEPS = 2e6
#: largest automatic time step of any method [rad] (rkc: min(0.1, …)); with it the number of
#: steps of a run is at least revolutions · 2π / this
LARGEST_AUTOMATIC_STEP = 0.1
#: most rotors integrated together in one round of the critical-mass search (each one is a
#: copy of the film state; the round's masses are spread by the tolerance around the centre)
MAX_BATCH = 64
#: most RKC stages (the stiffness bound needs far fewer at any grid gfbopt accepts)
MAX_STAGES = 1000


DAMPING_HELP = ("structural loss factor η of the bump foundation, 0–1 (default 0, or the "
                "bearing file's): the foil becomes a Kelvin–Voigt state with τ_f = η/ν_ref")
REFERENCE_HELP = ("ν_ref [-], the whirl ratio at which the Kelvin–Voigt foil matches the "
                  "hysteretic loss factor (default: the linear threshold whirl ratio)")


def _add_damping(sub) -> None:
    sub.add_argument("--loss-factor", type=number("loss-factor"), default=None,
                     help=DAMPING_HELP)
    sub.add_argument("--reference-whirl-ratio", type=number("reference-whirl-ratio"),
                     default=None, help=REFERENCE_HELP)


def register(subparsers) -> None:
    orb = subparsers.add_parser("orbit", help="journal-centre orbit of a rigid rotor "
                                "(transient)")
    add_operating_point(orb)
    orb.add_argument("--mass", type=number("mass"), default=None, help="the rotor as "
                     "M̄ = M c ω²/W0 [-] (non-dimensional input, without --bearing)")
    orb.add_argument("--rotor-mass-kg", type=number("rotor-mass-kg"), default=None,
                     help="rotor mass carried by the bearing [kg] (with --bearing and "
                     "--speed-rpm; M̄ = M c ω²/W0 is derived with W0 = --load-newton or the "
                     "equilibrium's load, and printed)")
    orb.add_argument("--revolutions", type=number("revolutions"), default=20.0,
                     help="shaft revolutions to integrate (default 20; refused when the "
                     "integration would take more than --max-steps steps)")
    orb.add_argument("--kick", type=number("kick"), default=1e-3,
                     help="initial journal speed dX/dτ = dY/dτ = kick/√2 (default 1e-3)")
    orb.add_argument("--time-step", type=number("time-step"), default=None,
                     help="Δτ [rad] (rk4: default 0.9 × its stability limit; rkc: default "
                     "min(0.1, rotor period/30, film time/4), chosen for accuracy; not bdf)")
    orb.add_argument("--stages", type=number("stages"), default=None,
                     help="RKC stages s ≥ 2 (rkc only; default: the fewest that are stable "
                     "for the step, Δτ·ρ ≤ 0.9 × 0.65 s²)")
    orb.add_argument("--plot", default=None, help="write the polar orbit plot to this PNG")
    orb.add_argument("--method", default="rkc", choices=METHODS, help=METHOD_HELP)
    orb.add_argument("--csv", default=None, help="write the orbit table to this CSV" + CSV_HELP)
    orb.add_argument("--max-steps", type=number("max-steps"), default=MAX_STEPS,
                     help=f"largest number of time steps a run may take (default "
                     f"{MAX_STEPS:.0e}; estimated from --revolutions and --time-step, or the "
                     "method's largest automatic step)")
    _add_damping(orb)
    orb.set_defaults(handler=run_orbit)

    crit = subparsers.add_parser("critical-mass", help="nonlinear critical mass from "
                                 "transients")
    add_operating_point(crit)
    crit.add_argument("--tolerance", type=number("tolerance"), default=0.005,
                      help="relative tolerance on M̄_crit (default 0.005)")
    crit.add_argument("--revolutions", type=number("revolutions"), default=None,
                      help="revolutions per transient (default: one whirl period + 10 %% "
                      "from the linear mode, 5 from a kick)")
    crit.add_argument("--batch", type=number("batch"), default=None, help="rotors per round "
                      f"(default 2 bracketing the linear threshold, 8 without it; at most "
                      f"{MAX_BATCH})")
    crit.add_argument("--method", default="rkc", choices=METHODS, help=METHOD_HELP)
    crit.add_argument("--start", default=None, choices=("mode", "kick"),
                      help="start each transient from the least-stable linear mode shape "
                      "(default with the linear start) or from a kick of the journal")
    crit.add_argument("--no-linear-start", action="store_true",
                      help="do not centre the search on the linear threshold")
    _add_damping(crit)
    crit.set_defaults(handler=run_critical_mass)


def _refuse_method_options(args) -> None:
    """--time-step/--stages only for the methods that use them (before anything is solved)."""
    from ..errors import ParameterError
    from ..transient import METHODS as TABLE

    accepted = TABLE[args.method][1]
    for option, key in (("--time-step", "time_step"), ("--stages", "stages")):
        value = getattr(args, key, None)
        if value is not None and key not in accepted:
            users = "/".join(m for m, (_, opts) in TABLE.items() if key in opts)
            raise ParameterError(option, value, f"applies to --method {users} only, not to "
                                 f"--method {args.method}")
    if getattr(args, "stages", None) is not None and (not float(args.stages).is_integer()
                                                      or not 2 <= args.stages <= MAX_STAGES):
        raise ParameterError("--stages", args.stages, f"must be an integer in [2, {MAX_STAGES}]")
    check_run_length(args)


def check_run_length(args) -> None:
    """--revolutions, --time-step and --kick within bounds, and the number of steps the run
    would take within --max-steps (one line with the estimate, before anything is built)."""
    from ..errors import ParameterError

    revolutions = getattr(args, "revolutions", None)
    if revolutions is not None and not revolutions > 0:
        raise ParameterError("--revolutions", revolutions, "must be > 0")
    step = getattr(args, "time_step", None)
    if step is not None and not 0 < step <= LARGEST_AUTOMATIC_STEP * 10:
        raise ParameterError("--time-step", step, f"must lie in (0, "
                             f"{LARGEST_AUTOMATIC_STEP * 10:g}] rad (a step of about a "
                             "revolution/60 or less resolves the whirl)")
    kick = getattr(args, "kick", None)
    if kick is not None and not 0 < kick < 1:
        raise ParameterError("--kick", kick, "must lie in (0, 1) (a journal speed in "
                             "clearances per radian)")
    limit = getattr(args, "max_steps", None) or MAX_STEPS
    if revolutions is None:
        return
    if not limit >= 1:
        raise ParameterError("--max-steps", limit, "must be >= 1")
    steps = revolutions * 2 * math.pi / (step or LARGEST_AUTOMATIC_STEP)
    if steps > limit:
        option, value = (("--time-step", step) if step else ("--revolutions", revolutions))
        raise ParameterError(option, value, f"{revolutions:.6g} revolutions would take at least "
                             f"{steps:.3g} time steps, above the limit of {limit:.3g}: "
                             "shorten the run" + (", or raise --max-steps"
                                                  if hasattr(args, "max_steps") else ""))


def _check_damping(args, op) -> None:
    """Refuse structural-damping options the run would not use, and a method or foil law
    the damped transient does not support (before anything is solved)."""
    from ..errors import ParameterError
    from ..transient.hardening_recovery import transient_foil_law as foil_law

    eta = op.model.loss_factor
    ref = args.reference_whirl_ratio
    if ref is not None and eta <= 0.0:
        raise ParameterError("--reference-whirl-ratio", ref, "is used only with structural "
                             "damping: add --loss-factor η > 0")
    if ref is not None and not ref > 0:
        raise ParameterError("--reference-whirl-ratio", ref, "must be > 0")
    rubbing = op.model.has_friction and getattr(args, "command", None) == "orbit"
    foil_law(op.model, engine=args.method if rubbing else "transient").check_engine(
        args.method, damped=eta > 0.0)


def _check_loss_factor(args) -> None:
    from ..errors import ParameterError

    if args.loss_factor is not None and args.loss_factor < 0:
        raise ParameterError("--loss-factor", args.loss_factor, "must be >= 0 (a negative "
                             "loss factor would feed energy into the rotor)")


def _operating_point(args):
    _check_loss_factor(args)
    op = operating_point(args)
    _check_damping(args, op)
    return op


def _check_no_friction(args, model) -> None:
    """``gfbopt critical-mass`` searches with transients that carry no slider: a bearing
    whose bumps rub is refused before any solve, saying which commands model it."""
    from ..errors import ParameterError

    mu = getattr(model, "friction_coefficient", 0.0)
    if mu > 0:
        raise ParameterError("--bearing", args.bearing, f"friction_coefficient = {mu:g}: "
                             "gfbopt critical-mass does not model the bumps' Coulomb friction "
                             "(its search runs transients without sliders); gfbopt orbit runs "
                             "a rubbing bearing in time, gfbopt stability and linear give its "
                             "small-motion (stuck) threshold")


def _held_point(args, friction: bool = True):
    """(OperatingPoint or None, RunningPoint or None, solver or None) of ``gfbopt orbit`` and
    ``critical-mass``: a bearing file with ``[journal]``/``[thermal]`` held at its running
    condition at ``--speed-rpm`` exactly as ``gfbopt static`` holds it
    (:func:`gfbopt.cli.running_point.running_operating_point`; the damping and method checked
    on the cold model before the heat balance is solved); else today's operating point."""
    from .running_point import running_operating_point

    _check_loss_factor(args)

    def check(model):                            # the cold model, before any solve
        if not friction:
            _check_no_friction(args, model)
        _check_damping(args, _Model(model))

    running = running_operating_point(args, check=check)
    if running is None:                          # no [journal]/[thermal]: today's route
        op = operating_point(args)
        if not friction:
            _check_no_friction(args, op.model)
        _check_damping(args, op)
        return op, None, None
    op, point, solver = running
    if op is not None:
        _check_damping(args, op)
    return op, point, solver


class _Model:
    """An operating point's ``model`` alone (what :func:`_check_damping` reads)."""

    def __init__(self, model):
        self.model = model


def _solve(op, solver=None):
    """(solver, equilibrium) of the operating point; a load the bearing cannot carry is
    refused as ``gfbopt stability`` refuses it (the largest load that converged)."""
    from ..errors import ParameterError
    from ..rotor.analysis import capacity_rule, largest_converged_load
    from ..static import solve_static, solver_for

    solver = solver or solver_for(op.model, op.grid)
    sol = solve_static(op.model, eccentricity=op.eccentricity, load=op.load, solver=solver)
    if not sol.success and op.load is not None and op.eccentricity is None:
        largest = largest_converged_load(op.model, op.load, solver)
        if op.geometry is not None and op.load_newton is not None:
            raise ParameterError("--load-newton", op.load_newton, capacity_rule(
                op.speed_rpm, op.geometry.load_newton(largest) if largest > 0 else 0.0,
                op.geometry.load_newton(op.load / 64)))
        raise ParameterError("--load", op.load, capacity_rule(None, largest, op.load / 64,
                                                              unit=""))
    return solver, sol


def _damping_text(result) -> str:
    """'; η = …, ν_ref = … (source)' for a damped run, else ''."""
    d = result.damping
    if not d:
        return ""
    return (f"; η = {d['loss_factor']:g}, Kelvin–Voigt foil τ_f = "
            f"{d['foil_relaxation_time']:.4g} (ν_ref = {d['reference_whirl_ratio']:.4g}, "
            f"{d['reference_whirl_source']})")


def _check_orbit_mass(args) -> None:
    """The rotor in kg with --bearing (SI), as M̄ without it; never both (before any solve)."""
    from ..errors import ParameterError

    if args.bearing is not None:
        if args.mass is not None:
            raise ParameterError("--mass", args.mass, "is the non-dimensional M̄; with "
                                 "--bearing give the rotor in kg (--rotor-mass-kg): M̄ = "
                                 "M c ω²/W0 is derived and printed")
        if args.rotor_mass_kg is None:
            raise ParameterError("--rotor-mass-kg", None, "is required with --bearing (rotor "
                                 "mass carried by the bearing [kg])")
        value, option = args.rotor_mass_kg, "--rotor-mass-kg"
    else:
        if args.rotor_mass_kg is not None:
            raise ParameterError("--rotor-mass-kg", args.rotor_mass_kg, "needs --bearing "
                                 "FILE.toml and --speed-rpm (a mass in kg means nothing "
                                 "without the bearing's dimensions); give --mass M̄")
        if args.mass is None:
            raise ParameterError("--mass", None, "is required (M̄ = M c ω²/W0), or give "
                                 "--bearing with --rotor-mass-kg")
        value, option = args.mass, "--mass"
    if not value > 0:
        raise ParameterError(option, value, "must be > 0")


def _orbit_mass(args, op, sol) -> float:
    """M̄ of the run: --mass, or M c ω²/W0 from --rotor-mass-kg with W0 the stated load or the
    equilibrium's (:mod:`gfbopt.inputs.conversions`)."""
    if args.mass is not None:
        return args.mass
    from ..inputs.conversions import mass_parameter, rpm_to_rad_per_s

    load = op.load_newton if op.load_newton is not None else op.geometry.load_newton(sol.load)
    return mass_parameter(args.rotor_mass_kg, op.geometry.radial_clearance,
                          rpm_to_rad_per_s(op.speed_rpm), load)


def run_orbit(args) -> int:
    from ..transient import integrate_orbits, transient_model

    _refuse_method_options(args)
    _check_orbit_mass(args)
    op, point, solver = _held_point(args)
    if op is None:                               # thermal runaway or closure at the speed
        from .running_point import no_running_state

        return no_running_state(point, "orbit", args.json)
    solver, sol = _solve(op, solver)
    mass = _orbit_mass(args, op, sol)
    tm = transient_model(sol, args.reference_whirl_ratio, solver,
                         friction=op.model.has_friction)
    options = {"time_step": args.time_step,
               "stages": None if args.stages is None else int(args.stages)}
    with FractionProgress("orbit") as bar:
        orbit = integrate_orbits(tm, [mass], args.revolutions, kick=args.kick,
                                 progress=bar, method=args.method,
                                 **{k: v for k, v in options.items() if v is not None})
    table = orbit.to_frame(0)
    if args.plot:
        from ..plotting import plot_orbits, save_figure

        model = op.model
        label = (f"M = {args.rotor_mass_kg:g} kg (M̄ = {mass:.4g})" if args.mass is None
                 else f"M̄ = {mass:g}")
        from ..model_text import foil_words, friction_words

        friction = friction_words(model.options())
        ax = plot_orbits({f"{label}: {orbit.verdict[0]}": table},
                         title=f"{foil_words(model.options())}"
                         + (f", {friction}" if friction else "")
                         + f", ε0 = {sol.eccentricity:.3g}, "
                         f"Λ = {model.bearing_number:.4g}, S = {model.compliance:.4g}",
                         clearance=True)
        save_figure(ax.figure, args.plot)
    settings = describe(op, method=args.method, kick=args.kick, mass=mass,
                        rotor_mass_kg=args.rotor_mass_kg)
    out = {**settings, **orbit.to_dict(0), "eccentricity": sol.eccentricity,
           "load": sol.load, "attitude_angle_deg": sol.attitude_angle_deg}
    orbit_in_si(table, out, op)                  # µm and s beside X/c and τ (a bearing file)
    running = point_fields(point)                # the clearance at speed (RUNNING_FIELDS)
    out.update(running)
    # its figures in the context too, as gfbopt stability's (the clearance model and the
    # running clearance the orbit was integrated at), without the nested "running" record
    context = context_options(args, command="orbit", **settings,
                              **{k: v for k, v in running.items() if k != "running"})
    if args.csv:                    # with its context FILE.csv.json (gfbopt.cli.csv_context)
        out["csv"] = str(write_csv(table, args.csv, context, float_format="%.8g"))
    emit(out, args.json, lambda: answer_text(
        f"gfbopt orbit — M̄ = {mass:.6g}"
        + (f" ({args.rotor_mass_kg:g} kg)" if args.mass is None else "")
        + f": {out['verdict']}, {_orbit_numbers(out, op)}, {out['revolutions']:.1f} revolutions "
        f"({args.method}, Δτ = {orbit.time_step:.3g}) in {orbit.wall_time_s:.1f} s"
        + _damping_text(orbit)
        + ("" if orbit.success else f"  ** FAILED: {orbit.message}"), out), context)
    return 0 if orbit.success else 1


def _measured(value, text: str) -> str:
    """``text`` formatted with ``value``, or 'not measured' (the JSON's null: NaN, inf)."""
    return text.format(value) if value is not None and math.isfinite(value) \
        else "not measured"


def _orbit_numbers(out: dict, op) -> str:
    """'growth rate …, whirl ratio …, min film …' of the orbit's text: 'not measured' where
    the JSON has null, the minimum film in µm with --bearing (h/c without)."""
    film = out["min_film"]
    if op.geometry is not None:
        film_text = _measured(None if film is None else film * op.geometry.radial_clearance
                              * 1e6, "{:.4g} µm")
    else:
        film_text = _measured(film, "{:.4g} (h/c)")
    return (f"growth rate {_measured(out['growth_rate'], '{:.3g} per rad')}, whirl ratio "
            f"{_measured(out['whirl_ratio'], '{:.4g}')}, min film {film_text}")


def run_critical_mass(args) -> int:
    from ..errors import ParameterError
    from ..linear import linear_threshold, linearise
    from ..transient import find_critical_mass, linear_mode, transient_model

    if args.start == "mode" and args.no_linear_start:
        raise ParameterError("--start", "mode", "needs the linear threshold; drop "
                             "--no-linear-start")
    if args.batch is not None and not (float(args.batch).is_integer()
                                       and 1 <= args.batch <= MAX_BATCH):
        raise ParameterError("--batch", args.batch, f"must be an integer in [1, {MAX_BATCH}] "
                             "(rotors integrated together per round)")
    if not 0 < args.tolerance < 0.5:
        raise ParameterError("--tolerance", args.tolerance, "must lie in (0, 0.5) (relative)")
    if args.batch is not None and args.tolerance * (args.batch - 1) >= 1:
        raise ParameterError("--batch", args.batch, f"spreads the masses of a round by "
                             f"±{args.tolerance * (args.batch - 1) / 2:.0%} of the centre "
                             f"with --tolerance {args.tolerance:g}: (batch − 1) × tolerance "
                             "must be < 1 so that every mass is > 0")
    check_run_length(args)
    # a heated file: at its running condition; a rubbing one refused
    op, point, solver = _held_point(args, friction=False)
    if op is None:                               # thermal runaway or closure at the speed
        from .running_point import no_running_state

        return no_running_state(point, "critical-mass", args.json)
    solver, sol = _solve(op, solver)
    lin = linearise(sol, solver)
    linear = linear_threshold(lin)
    if linear.critical_mass == 0.0:
        return _unstable_at_any_mass(args, op, sol, linear, point)
    tm = transient_model(sol, args.reference_whirl_ratio, solver, threshold=linear)
    usable = math.isfinite(linear.critical_mass)
    estimate = None if args.no_linear_start or not usable else linear.critical_mass
    start = args.start or ("mode" if estimate is not None else "kick")
    mode = None
    if start == "mode" and usable:
        mode = linear_mode(lin, linear.critical_mass, 1j * linear.whirl_ratio)
    with FractionProgress("critical mass") as bar:
        result = find_critical_mass(tm, tolerance=args.tolerance, linear_estimate=estimate,
                                    batch=None if args.batch is None else int(args.batch),
                                    revolutions=args.revolutions,
                                    progress=bar, method=args.method, initial_mode=mode)
    settings = describe(op, method=args.method, tolerance=args.tolerance,
                        revolutions_per_transient=args.revolutions, batch=args.batch,
                        start=result.start)
    out = {**settings, **result.to_dict(),
           "linear_critical_mass": linear.critical_mass,
           "linear_whirl_ratio": linear.whirl_ratio, "eccentricity": sol.eccentricity,
           "load": sol.load, "attitude_angle_deg": sol.attitude_angle_deg,
           "history": list(result.history), **point_fields(point)}
    critical_mass_in_si(out, op)                 # kg and N beside M̄ (a bearing file)
    emit(out, args.json, lambda: answer_text(
        f"gfbopt critical-mass — M̄_crit = {result.critical_mass:.5g} (bracket "
        f"{result.bracket[0]:.5g}–{result.bracket[1]:.5g}), whirl ratio "
        f"{result.whirl_ratio:.4g}; linear {linear.critical_mass:.5g} at "
        f"{linear.whirl_ratio:.4g}; {result.transients} transients × "
        f"{result.rotor_revolutions / max(result.transients, 1):.3g} revolutions "
        f"({args.method}, start: {result.start}), {result.wall_time_s:.1f} s"
        + _damping_text(result)
        + ("" if result.success else f"  ** FAILED: {result.message}"), out), settings)
    return 0 if result.success else 1


def _unstable_at_any_mass(args, op, sol, linear, point=None) -> int:
    """A linear threshold of 0: the massless journal already whirls, so every rotor mass is
    unstable (an answer, not an error): reported without a transient search, exit 0."""
    settings = describe(op, method=args.method, tolerance=args.tolerance,
                        revolutions_per_transient=args.revolutions, batch=args.batch,
                        start="none")
    out = {**settings, "critical_mass": 0.0, "bracket": [0.0, 0.0],
           "whirl_ratio": linear.whirl_ratio, "transients": 0, "rotor_revolutions": 0.0,
           "success": True, "message": linear.message, "linear_critical_mass": 0.0,
           "linear_whirl_ratio": linear.whirl_ratio, "eccentricity": sol.eccentricity,
           "load": sol.load, "attitude_angle_deg": sol.attitude_angle_deg,
           "history": [], "verdict": "unstable at every rotor mass", **point_fields(point)}
    critical_mass_in_si(out, op)
    emit(out, args.json, lambda: answer_text(
        f"gfbopt critical-mass — unstable at every rotor mass: M̄_crit = 0 (linear threshold "
        f"0: {linear.message}); no transient search", out), settings)
    return 0
