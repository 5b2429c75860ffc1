"""The ``gfbopt`` command line.

``gfbopt static`` solves one static equilibrium (non-dimensional, or dimensional from a
bearing file with the speed in rpm and the load in newtons); ``gfbopt run`` runs named studies
from ``problems/``.  Bad input prints one line naming the parameter, its value and the rule,
and exits with status 2.  A solve that does not converge exits with status 1 and says why.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from typing import Optional, Sequence

import numpy as np

from .errors import GfboptError, ParameterError
from .inputs import DEFAULT_GRID, BearingModel, Grid


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, exit 2, no traceback
        self.exit(2, f"gfbopt: error: {message}\n")


def _float(name: str):
    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} = {text!r}: must be a number") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"{name} = {text!r}: must be finite (not NaN)")
        return value
    return parse


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="gfbopt", description="Gas foil bearing analysis.")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    st = sub.add_parser("static", help="static equilibrium at one operating point")
    _operating_point_arguments(st)

    lin = sub.add_parser("linear", help="stiffness, damping and linear stability threshold")
    _operating_point_arguments(lin)
    lin.add_argument("--whirl-ratio", type=_float("whirl-ratio"), nargs="+",
                     default=[0.0, 0.5, 1.0], help="whirl ratios γ for K and C (default 0 0.5 1)")
    lin.add_argument("--frame", default="load", choices=("load", "line-of-centres"),
                     help="axes of K and C (default: load frame)")
    lin.add_argument("--mass", type=_float("mass"), default=None,
                     help="also give the least stable eigenvalue at this M̄ = M c ω²/W0")

    orb = sub.add_parser("orbit", help="journal-centre orbit of a rigid rotor (RK4 transient)")
    _operating_point_arguments(orb)
    orb.add_argument("--mass", type=_float("mass"), required=True, help="M̄ = M c ω²/W0 [-]")
    orb.add_argument("--revolutions", type=_float("revolutions"), default=20.0,
                     help="shaft revolutions to integrate (default 20)")
    orb.add_argument("--kick", type=_float("kick"), default=1e-3,
                     help="initial journal speed dX/dτ = dY/dτ = kick/√2 (default 1e-3)")
    orb.add_argument("--time-step", type=_float("time-step"), default=None,
                     help="Δτ [rad] (default: 0.9 × the RK4 stability limit)")
    orb.add_argument("--plot", default=None, help="write the polar orbit plot to this PNG")
    orb.add_argument("--method", default="rk4", help="rk4 (default) | bdf")
    orb.add_argument("--csv", default=None, help="write the orbit table to this CSV")

    crit = sub.add_parser("critical-mass", help="nonlinear critical mass by RK4 transients")
    _operating_point_arguments(crit)
    crit.add_argument("--tolerance", type=_float("tolerance"), default=0.005,
                      help="relative tolerance on M̄_crit (default 0.005)")
    crit.add_argument("--revolutions", type=_float("revolutions"), default=5.0,
                      help="revolutions per transient (default 5)")
    crit.add_argument("--batch", type=int, default=8, help="rotors per batch (default 8)")
    crit.add_argument("--method", default="rk4", help="rk4 (default) | bdf")
    crit.add_argument("--no-linear-start", action="store_true",
                      help="do not centre the search on the linear threshold")

    run = sub.add_parser("run", help="run named studies: gfbopt run problems/NAME.toml ...")
    run.add_argument("problems", nargs="+", help="study files (problems/NAME.toml)")
    run.add_argument("--results", default="results", help="output folder (default results/)")
    return parser


def _operating_point_arguments(st: argparse.ArgumentParser) -> None:
    target = st.add_mutually_exclusive_group()
    target.add_argument("--eccentricity", type=_float("eccentricity"), help="ε = e/c [-]")
    target.add_argument("--load", type=_float("load"), help="W/(p_a R²) [-]")
    target.add_argument("--load-newton", type=_float("load-newton"), help="static load [N] "
                        "(with --bearing and --speed-rpm)")
    st.add_argument("--bearing-number", type=_float("bearing-number"), help="Λ [-]")
    st.add_argument("--compliance", type=_float("compliance"), default=None, help="S [-]")
    st.add_argument("--length-ratio", type=_float("length-ratio"), default=None, help="L/D [-]")
    st.add_argument("--top-foil-coefficient", type=_float("top-foil-coefficient"),
                    default=None, help="C [-] (beam model)")
    st.add_argument("--bearing", help="bearing TOML file (dimensional input, SI)")
    st.add_argument("--speed-rpm", type=_float("speed-rpm"), help="shaft speed [rpm]")
    st.add_argument("--foil", default=None, help="rigid | simple | beam (default: simple, "
                    "or rigid when S = 0)")
    st.add_argument("--film", default="periodic", help="periodic | seam")
    st.add_argument("--seam-angle", type=_float("seam-angle"), default=None,
                    help="welded end of the top foil, degrees from the load line in the "
                    "direction of rotation (default: at the maximum-film line)")
    st.add_argument("--deflection-law", default="mean", help="mean | local")
    st.add_argument("--subambient", default="full", help="full | gumbel")
    st.add_argument("--compression-only", action="store_true",
                    help="bumps cannot pull the foil inward (W >= 0)")
    st.add_argument("--grid", default=str(DEFAULT_GRID),
                    help=f"NTHETAxNZ (default {DEFAULT_GRID})")
    st.add_argument("--json", action="store_true", help="print one JSON object")


def _model_from_args(args) -> tuple[BearingModel, dict]:
    """The model and the target (eccentricity or load) from the parsed arguments."""
    extra: dict = {}
    common = dict(film=args.film, deflection_law=args.deflection_law,
                  subambient=args.subambient, compression_only=args.compression_only,
                  seam_angle=None if args.seam_angle is None else math.radians(args.seam_angle))
    if args.bearing is not None:
        from .inputs import load_bearing

        if args.speed_rpm is None:
            raise ParameterError("--speed-rpm", None, "is required with --bearing")
        geometry = load_bearing(args.bearing)
        model = geometry.model(args.speed_rpm, foil=args.foil or "simple", **common)
        if args.compliance is not None or args.bearing_number is not None:
            raise ParameterError("--bearing", args.bearing, "takes the compliance and bearing "
                                 "number from the file; do not also give them")
        if args.top_foil_coefficient is not None:
            model = model.replace(top_foil_coefficient=args.top_foil_coefficient)
        if args.load_newton is not None:
            extra["load"] = geometry.nondimensional_load(args.load_newton)
            extra["load_newton"] = args.load_newton
        extra["geometry"] = geometry
    else:
        if args.load_newton is not None:
            raise ParameterError("--load-newton", args.load_newton,
                                 "needs --bearing FILE.toml and --speed-rpm")
        if args.bearing_number is None:
            raise ParameterError("--bearing-number", None, "is required (or give --bearing)")
        compliance = 0.0 if args.compliance is None else args.compliance
        foil = args.foil or ("rigid" if compliance == 0.0 else "simple")
        if foil not in ("rigid", "simple", "beam"):
            raise ParameterError("--foil", foil, "must be one of rigid, simple, beam")
        model = BearingModel(bearing_number=args.bearing_number, compliance=compliance,
                             length_ratio=1.0 if args.length_ratio is None else args.length_ratio,
                             foil=foil, top_foil_coefficient=args.top_foil_coefficient or 0.0,
                             **common)
    if args.eccentricity is not None:
        extra["eccentricity"] = args.eccentricity
    elif args.load is not None:
        extra["load"] = args.load
    if "eccentricity" not in extra and "load" not in extra:
        raise ParameterError("--eccentricity/--load", None, "give one of them")
    return model, extra


def _static(args) -> int:
    from .static import solve_static

    model, extra = _model_from_args(args)
    grid = Grid.parse(args.grid)
    sol = solve_static(model, eccentricity=extra.get("eccentricity"), load=extra.get("load"),
                       grid=grid)
    out = sol.to_dict()
    out.update({"bearing_number": model.bearing_number, "compliance": model.compliance,
                "length_ratio": model.length_ratio, "foil": model.foil, "film": model.film,
                "top_foil_coefficient": model.top_foil_coefficient,
                "deflection_law": model.deflection_law, "subambient": model.subambient,
                "compression_only": model.compression_only, "grid": str(grid),
                "message": sol.message})
    geometry = extra.get("geometry")
    if geometry is not None:
        out["speed_rpm"] = args.speed_rpm
        out["min_film_thickness_um"] = sol.min_film * geometry.radial_clearance * 1e6
        out["load_newton"] = geometry.load_newton(sol.load)
    _emit(out, args.json, lambda: _report(out))
    if not sol.success:
        print(f"gfbopt: solve did not converge: {sol.message}", file=sys.stderr)
        return 1
    return 0


def _linear(args) -> int:
    from .linear import coefficients, linear_threshold, linearise
    from .static import solve_static, solver_for

    model, extra = _model_from_args(args)
    grid = Grid.parse(args.grid)
    t0 = time.perf_counter()
    solver = solver_for(model, grid)
    sol = solve_static(model, eccentricity=extra.get("eccentricity"), load=extra.get("load"),
                       solver=solver)
    if not sol.success:
        print(f"gfbopt: error: static equilibrium did not converge ({sol.message}); "
              "no linearisation", file=sys.stderr)
        return 1
    lin = linearise(sol, solver)
    threshold = linear_threshold(lin)
    coeffs = coefficients(lin, args.whirl_ratio)
    if args.frame == "line-of-centres":
        coeffs = coeffs.in_line_of_centres_frame()
    mode = None
    if args.mass is not None:
        from .linear import least_stable_mode

        if not args.mass > 0:
            raise ParameterError("--mass", args.mass, "must be > 0")
        mode = least_stable_mode(lin, args.mass, threshold)
    out = {"critical_mass": threshold.critical_mass, "whirl_ratio": threshold.whirl_ratio,
           "stable_for_all_masses": threshold.stable_for_all_masses,
           "threshold_message": threshold.message,
           "stiffness": {f"{g:g}": coeffs.stiffness[k].tolist()
                         for k, g in enumerate(coeffs.whirl_ratio)},
           "damping": {f"{g:g}": coeffs.damping[k].tolist()
                       for k, g in enumerate(coeffs.whirl_ratio)},
           "frame": args.frame, "load": sol.load, "eccentricity": sol.eccentricity,
           "attitude_angle_deg": math.degrees(sol.attitude_angle),
           "success": bool(sol.success and threshold.success),
           "bearing_number": model.bearing_number, "compliance": model.compliance,
           "length_ratio": model.length_ratio, "foil": model.foil, "film": model.film,
           "grid": str(grid), "wall_time_s": time.perf_counter() - t0}
    if mode is not None:
        out.update({"mass": args.mass, "growth_rate": mode.real,
                    "mode_whirl_ratio": mode.imag})
    def report() -> str:
        lines = [f"gfbopt linear — {model.foil} foil, {model.film} film, grid {grid}",
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
        return "\n".join(lines)

    _emit(out, args.json, report)
    return 0 if out["success"] else 1


def _progress_bar(label: str):
    """A one-line progress bar on a terminal; nothing when stderr is not a TTY (CI, pipes)."""
    if not sys.stderr.isatty():
        return None

    def show(fraction: float) -> None:
        n = int(30 * fraction)
        sys.stderr.write(f"\r{label} [{'#' * n}{'.' * (30 - n)}] {100 * fraction:5.1f} %")
        if fraction >= 1.0:
            sys.stderr.write("\n")
        sys.stderr.flush()
    return show


def _transient_setup(args):
    from .static import solve_static, solver_for
    from .transient import transient_model

    model, extra = _model_from_args(args)
    grid = Grid.parse(args.grid)
    solver = solver_for(model, grid)
    sol = solve_static(model, eccentricity=extra.get("eccentricity"), load=extra.get("load"),
                       solver=solver)
    return model, grid, solver, sol, transient_model(sol)


def _orbit(args) -> int:
    from .transient import integrate_orbits

    model, grid, _, sol, tm = _transient_setup(args)
    orbit = integrate_orbits(tm, [args.mass], args.revolutions, kick=args.kick,
                             time_step=args.time_step, progress=_progress_bar("orbit"),
                             method=args.method)
    table = orbit.to_frame(0)
    if args.csv:
        table.to_csv(args.csv, index=False, float_format="%.8g")
    if args.plot:
        from .plotting import plot_orbits

        plot_orbits({f"M̄ = {args.mass:g}: {orbit.verdict[0]}": table}, args.plot,
                    title=f"{model.foil}, ε0 = {sol.eccentricity:.3g}, Λ = "
                    f"{model.bearing_number:g}, S = {model.compliance:g}")
    out = {"verdict": orbit.verdict[0], "growth_rate": float(orbit.growth_rate[0]),
           "whirl_ratio": float(orbit.whirl_ratio[0]), "revolutions": orbit.revolutions,
           "min_film": float(np.nanmin(orbit.min_film[0])),
           "final_amplitude": float(orbit.amplitude[0]), "contact": bool(orbit.contact[0]),
           "contact_tau": float(orbit.contact_tau[0]), "mass": args.mass,
           "time_step": orbit.time_step, "wall_time_s": orbit.wall_time_s,
           "eccentricity": sol.eccentricity, "load": sol.load,
           "attitude_angle_deg": math.degrees(sol.attitude_angle), "grid": str(grid)}
    _emit(out, args.json, lambda: (
        f"gfbopt orbit — M̄ = {args.mass:g}: {out['verdict']}, growth rate "
        f"{out['growth_rate']:.3g} per rad, whirl ratio {out['whirl_ratio']:.4g}, "
        f"min film {out['min_film']:.4g}, {out['revolutions']:.1f} revolutions "
        f"(Δτ = {orbit.time_step:.3g}) in {orbit.wall_time_s:.1f} s"))
    return 0


def _critical_mass(args) -> int:
    from .linear import linear_threshold, linearise
    from .transient import find_critical_mass

    model, grid, solver, sol, tm = _transient_setup(args)
    linear = linear_threshold(linearise(sol, solver))
    estimate = None if args.no_linear_start else linear.critical_mass
    result = find_critical_mass(tm, tolerance=args.tolerance, linear_estimate=estimate,
                                batch=args.batch, revolutions=args.revolutions,
                                progress=_progress_bar("critical mass"), method=args.method)
    out = result.to_dict()
    out.update({"linear_critical_mass": linear.critical_mass,
                "linear_whirl_ratio": linear.whirl_ratio, "eccentricity": sol.eccentricity,
                "load": sol.load, "attitude_angle_deg": math.degrees(sol.attitude_angle),
                "grid": str(grid), "foil": model.foil, "film": model.film,
                "history": list(result.history)})
    _emit(out, args.json, lambda: (
        f"gfbopt critical-mass — M̄_crit = {result.critical_mass:.5g} (bracket "
        f"{result.bracket[0]:.5g}–{result.bracket[1]:.5g}), whirl ratio "
        f"{result.whirl_ratio:.4g}; linear {linear.critical_mass:.5g} at "
        f"{linear.whirl_ratio:.4g}; {result.transients} transients, "
        f"{result.wall_time_s:.1f} s" + ("" if result.success else
                                          f"  ** FAILED: {result.message}")))
    return 0 if result.success else 1


def _emit(out: dict, as_json: bool, report) -> None:
    """Print ``out`` as one JSON object, or the readable ``report()`` text."""
    print(json.dumps({k: _jsonable(v) for k, v in out.items()}) if as_json else report())


def _jsonable(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _report(out: dict) -> str:
    lines = [f"gfbopt static — {out['foil']} foil, {out['film']} film, grid {out['grid']}",
             f"  Λ = {out['bearing_number']:.4g}, S = {out['compliance']:.4g}, "
             f"L/D = {out['length_ratio']:.4g}, C = {out['top_foil_coefficient']:.4g}",
             f"  eccentricity ε          {out['eccentricity']:.5f}",
             f"  load W/(p_a R²)         {out['load']:.5f}",
             f"  attitude angle          {out['attitude_angle_deg']:.3f} deg",
             f"  minimum film h/c        {out['min_film']:.5f} at "
             f"{out['min_film_angle_deg']:.1f} deg from the load line"]
    if "min_film_thickness_um" in out:
        lines.append(f"  minimum film            {out['min_film_thickness_um']:.2f} µm "
                     f"(load {out['load_newton']:.2f} N at {out['speed_rpm']:.0f} rpm)")
    lines.append(f"  solver: {out['status']}, {out['iterations']} iterations, residual "
                 f"{out['residual']:.1e}, {out['solve_time_s']:.3f} s"
                 + ("" if out["success"] else "  ** NOT CONVERGED **"))
    return "\n".join(lines)


def _run(args) -> int:
    from .studies import run_study

    failed = 0
    for path in args.problems:
        summary = run_study(path, results_root=args.results)
        print(summary.report())
        failed += not summary.passed
    return 1 if failed else 0


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "static":
            return _static(args)
        if args.command == "linear":
            return _linear(args)
        if args.command == "orbit":
            return _orbit(args)
        if args.command == "critical-mass":
            return _critical_mass(args)
        return _run(args)
    except GfboptError as exc:
        print(f"gfbopt: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
