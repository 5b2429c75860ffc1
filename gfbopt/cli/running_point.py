"""``gfbopt static``, ``linear``, ``orbit`` and ``critical-mass`` on a bearing file with
``[journal]``/``[thermal]``: the operating point at the running condition of the file's speed
(the transients: the bearing held at that condition, constant speed, throughout).

The running point (:func:`gfbopt.thermal.running.running_point`: the centrifugal growth, and
with ``[thermal]`` the heat balance's fixed point of temperatures, growths, μ(T) and clearance
under the operating point's load) gives the warm bearing
(:func:`gfbopt.thermal.bearing.warm_bearing`: radial clearance = the running clearance,
viscosity = μ(T_f)); the command's model is that bearing's at ``--speed-rpm``, with the
formulation resolved as :func:`gfbopt.cli.common.operating_point` resolves it (the flags over
the file's ``[model]`` table, then the defaults).  The heat balance needs the load (the drag
depends on it): ``--load-newton`` or ``--load``; ``--eccentricity`` is refused with it.  A
file with neither table never comes here (:func:`running_operating_point` returns None): the
command's output is today's, unchanged.
"""
from __future__ import annotations

from typing import Callable, Optional

from ..errors import ParameterError
from ..thermal.running import HEAT_BALANCE, ISOTHERMAL, RunningPoint

#: the clearance at speed's fields added to ``gfbopt static/linear/orbit/critical-mass
#: --json`` for such a file
RUNNING_FIELDS = ("thermal_model", "cold_clearance_um", "running_clearance_um",
                  "centrifugal_growth_um", "thermal_growth_um", "film_temperature_c",
                  "viscosity_pa_s", "running")


class _OneSolver:
    """A solver cache that returns the command's own build (its IPOPT options) on the
    command's grid, and caches the others (the coarse start's grid)."""

    def __init__(self, grid, solver, model):
        from ..static import SolverCache
        from ..static.build import solver_key

        self.grid, self.solver, self.others = grid, solver, SolverCache(grid)
        self.key = solver_key(model, grid)

    def __call__(self, model, grid=None):
        from ..static.build import solver_key

        # one build per grid, film and structure: a warm model's key is the cold one's
        if solver_key(model, grid or self.grid) == self.key:
            return self.solver
        return self.others(model, grid)


def running_operating_point(args, ipopt_options: Optional[dict] = None,
                            check: Optional[Callable] = None):
    """None when ``args.bearing`` is not given or its file states neither ``[journal]`` nor
    ``[thermal]`` (the command's route of today).  Else (the OperatingPoint at the running
    condition or None when there is no running state, the RunningPoint, the solver of the
    command's grid): bad input refused in one line before any solve (``check(model)``, the
    command's own rules on the cold model, e.g. ``gfbopt orbit``'s method and damping, is
    called before anything is built)."""
    if getattr(args, "bearing", None) is None:
        return None
    from ..thermal.files import load_running_bearing

    bearing, spec = load_running_bearing(args.bearing)       # the tables checked
    from ..inputs.rotor_limits import check_surface_speed

    check_surface_speed(bearing, [getattr(args, "speed_rpm", None)], "--speed-rpm")
    if spec.model_name == ISOTHERMAL:
        return None
    from ..inputs.options import merge_options
    from ..static import solver_for
    from ..thermal.bearing import FilmCase
    from .common import OperatingPoint, _refuse_ignored_options, grid_of
    from .si import MAX_FILM, stated_options

    resolved = merge_options(stated_options(args), bearing.options)   # as fill_model_options
    args.film, args.deflection_law = resolved.film, resolved.deflection_law
    args.loss_factor, args.foil = resolved.loss_factor, resolved.foil
    args.seam_angle = (None if resolved.seam_angle_deg in (None, MAX_FILM)
                       else resolved.seam_angle_deg)
    _refuse_ignored_options(args)
    kwargs = dict(film=args.film, deflection_law=args.deflection_law,
                  subambient=args.subambient, compression_only=args.compression_only,
                  seam_angle_deg=args.seam_angle, loss_factor=args.loss_factor,
                  foil=args.foil or "simple")
    kwargs.update(resolved.bump_kwargs())   # friction and hardening, as operating_point
    if args.eccentricity is None and args.load is None and args.load_newton is None:
        raise ParameterError("--eccentricity/--load", None, "give one of them (or "
                             "--load-newton)")
    if spec.model_name == HEAT_BALANCE and args.eccentricity is not None:
        raise ParameterError("--eccentricity", args.eccentricity, "is not used with a "
                             "[thermal] table: the heat balance is solved under the "
                             "bearing's load (its drag depends on it); give --load-newton "
                             "or --load")
    grid = grid_of(args)
    speed = args.speed_rpm
    cold_model = _model(bearing, speed, kwargs, args)
    if check is not None:
        check(cold_model)
    solver = solver_for(cold_model, grid, ipopt_options=ipopt_options)
    load_newton = (args.load_newton if args.load_newton is not None else
                   None if args.load is None else bearing.load_newton(args.load))
    from ..rotor.running_bearing import Formulation, warm_under_load

    case = FilmCase(bearing, Formulation(tuple(sorted(kwargs.items()))), grid,
                    _OneSolver(grid, solver, cold_model), load_newton)
    found = warm_under_load(spec, case, speed)
    point, warm = found.point, found.warm
    if warm is None:
        return None, point, solver
    extra = dict(geometry=warm, speed_rpm=speed)
    if args.load_newton is not None:
        extra.update(load=warm.nondimensional_load(args.load_newton),
                     load_newton=args.load_newton)
    elif args.load is not None:
        extra["load"] = args.load
    else:
        extra["eccentricity"] = args.eccentricity
    return OperatingPoint(model=_model(warm, speed, kwargs, args), grid=grid, **extra), \
        point, solver


def _model(bearing, speed, kwargs, args):
    model = bearing.model(speed, **kwargs)
    if args.top_foil_coefficient is not None:
        model = model.replace(top_foil_coefficient=args.top_foil_coefficient)
    return model


def running_fields(point: RunningPoint) -> dict:
    """The clearance at speed's fields of the answer (RUNNING_FIELDS)."""
    d = point.to_dict()
    return {**{k: d[k] for k in RUNNING_FIELDS[:-1]}, "running": d}


def no_running_state(point: RunningPoint, command: str, as_json: bool) -> int:
    """The answer when there is no running state at the file's speed (thermal runaway, or
    the journal reaching the foil): the running point's fields and why, exit 1 (there is no
    equilibrium to report)."""
    import sys

    from .common import emit
    from .stability import running_lines

    out = {"speed_rpm": point.speed_rpm, **running_fields(point), "success": False,
           "message": point.message}
    emit(out, as_json, lambda: "\n".join([f"gfbopt {command} — no running state"]
                                         + running_lines(out["running"])),
         {"command": command})
    print(f"gfbopt: no equilibrium at {point.speed_rpm:,.0f} rpm: {point.message}",
          file=sys.stderr)
    return 1


def point_fields(point) -> dict:
    """The clearance at speed's fields (RUNNING_FIELDS) of a heated file's answer; for a
    file without the tables its clearance model alone (isothermal, cold clearance)."""
    if point is None:
        from ..thermal.running import ISOTHERMAL

        return {"thermal_model": ISOTHERMAL}
    return running_fields(point)


def answer_text(text: str, out: dict) -> str:
    """The answer's line, the model that made it (film, foil, friction, hardening, loss
    factor: the words of every text report), then the running point's lines for a heated
    file, else its clearance model."""
    from ..model_text import model_words

    lines = [text, f"  model: {out['film_convention']}; {model_words(out)}"]
    if out.get("running"):
        from .stability import running_lines

        lines += running_lines(out["running"])
    else:
        lines.append(f"  clearance model: {out['thermal_model']}")
    return "\n".join(lines)
