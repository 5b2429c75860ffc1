"""``gfbopt design``: bump-foil geometry for a target compliance coefficient S.

``register(subparsers)`` adds the sub-command; its handler :func:`run` solves the geometric
program of :mod:`gfbopt.design.geometry_program` and prints a readable report, or one JSON
object with ``--json``.  All inputs and outputs are SI (m, Pa).  Bad input raises
``ParameterError`` (the main command prints it on one line and exits with status 2); a valid
but infeasible specification prints which limits must move and returns 1.
"""
from __future__ import annotations

import argparse
import json

from ..design.materials import MATERIALS, get_material
from ..errors import ParameterError
from ..provenance import jsonable as _jsonable
from .common import number
from .csv_context import context_options

__all__ = ["register", "run"]

_DEFAULT_MATERIAL = "inconel-x750"
# gfbopt.design.geometry_program.OBJECTIVES, repeated so that --help does not import cvxpy
# (a test keeps the two equal).
_OBJECTIVES = ("stress", "pitch", "number_of_bumps", "thickness", "half_length",
               "top_foil_thickness", "top_foil_sag")
_REFERENCES = (
    "Heshmat, Walowit & Pinkus 1983, J. Lubr. Technol. 105(4):647-655 "
    "(bump compliance); Young & Budynas 2002, Roark's Formulas for Stress and Strain, 7th ed., "
    "Table 8.1 (top-foil sag and stress, clamped strip)")
_FORMULAS = {
    "bump_compliance": "alpha = 2 s l0^3 (1 - nu^2) / (E t_b^3) [m^3/N]",
    "compliance": "S = p_a alpha / c",
    "bump_stress": "sigma_b = 3 dp s l0 / t_b^2",
    "bump_closing": "2 l0 + gap <= s",
    "top_foil_sag": "dp s^4 (1 - nu^2) / (32 E t_top^3) <= kappa_c c",
    "top_foil_stress": "dp s^2 / (2 t_top^2)",
    "no_flattening": "dp alpha <= kappa h_b",
    "number_of_bumps": "N = 2 pi R / s, whole",
}


def register(subparsers) -> argparse.ArgumentParser:
    """Add the ``design`` sub-command to ``subparsers``; its handler is :func:`run`."""
    x750 = get_material(_DEFAULT_MATERIAL)
    p = subparsers.add_parser(
        "design", help="bump-foil geometry for a target compliance S (geometric program)",
        description=("Find the bump pitch s, half bump length l0 and bump thickness t_b that "
                     "give the compliance coefficient S = p_a alpha / c at the least bump "
                     "bending stress, within the given ranges and limits. SI units (m, Pa)."))
    p.add_argument("--target-compliance", type=number("target-compliance"), nargs="+",
                   required=True, metavar="S",
                   help="target compliance coefficient S [-]; two values give a band LOW HIGH")
    p.add_argument("--radial-clearance", type=number("radial-clearance"), required=True,
                   metavar="C_M", help="radial clearance c [m]")
    p.add_argument("--radius", type=number("radius"), default=None, metavar="R_M",
                   help="bearing radius R [m]: the number of bumps 2 pi R/s is made whole "
                        "(default: not rounded)")
    p.add_argument("--ambient-pressure", type=number("ambient-pressure"), default=101325.0,
                   metavar="PA", help="ambient pressure p_a [Pa] (default 101325, 1 atm)")
    p.add_argument("--material", default=_DEFAULT_MATERIAL, choices=tuple(MATERIALS),
                   help=f"foil material (default {_DEFAULT_MATERIAL}: E = "
                        f"{x750.youngs_modulus / 1e9:g} GPa, nu = {x750.poisson_ratio:g}, "
                        "Inconel X-750 at 20 C)")
    p.add_argument("--youngs-modulus", type=number("youngs-modulus"), default=None,
                   metavar="E", help="override the material's Young's modulus E [Pa]")
    p.add_argument("--poisson-ratio", type=number("poisson-ratio"), default=None,
                   metavar="NU", help="override the material's Poisson's ratio [-]")
    p.add_argument("--allowable-stress", type=number("allowable-stress"), default=None,
                   metavar="SIGMA",
                   help=f"bump allowable bending stress [Pa] (default: the material's; "
                        f"{_DEFAULT_MATERIAL}: {x750.allowable_stress / 1e6:g} MPa = 0.5 x the "
                        "620 MPa minimum yield strength of ASTM B637 UNS N07750 Type 1, a "
                        "design choice)")
    p.add_argument("--design-pressure", type=number("design-pressure"), default=1e5,
                   metavar="DP", help="film pressure above ambient on the foil dp [Pa] "
                                      "(default 1e5, 1 bar)")
    p.add_argument("--pitch-range", type=number("pitch-range"), nargs=2, default=[2e-3, 6e-3],
                   metavar=("A", "B"), help="bump pitch s range [m] (default 2e-3 6e-3)")
    p.add_argument("--half-length-range", type=number("half-length-range"), nargs=2,
                   default=[0.5e-3, 3e-3], metavar=("A", "B"),
                   help="half bump length l0 range [m] (default 5e-4 3e-3)")
    p.add_argument("--thickness-range", type=number("thickness-range"), nargs=2,
                   default=[50e-6, 200e-6], metavar=("A", "B"),
                   help="bump foil thickness t_b range [m] (default 5e-5 2e-4)")
    p.add_argument("--gap", type=number("gap"), default=0.2e-3, metavar="G",
                   help="flat length between bumps, 2 l0 + gap <= s [m] (default 2e-4)")
    p.add_argument("--top-foil-thickness-range", type=number("top-foil-thickness-range"),
                   nargs=2, default=None, metavar=("A", "B"),
                   help="design the top foil too, thickness range [m] (default: not designed)")
    p.add_argument("--sag-limit", type=number("sag-limit"), default=None, metavar="KAPPA_C",
                   help="top-foil sag <= KAPPA_C x c (needs --top-foil-thickness-range)")
    p.add_argument("--top-foil-allowable-stress", type=number("top-foil-allowable-stress"),
                   default=None, metavar="SIGMA",
                   help="top-foil allowable stress [Pa] (default: the bump allowable stress)")
    p.add_argument("--flattening-limit", type=number("flattening-limit"), default=None,
                   metavar="KAPPA", help="no flattening: dp alpha <= KAPPA x bump height")
    p.add_argument("--bump-height", type=number("bump-height"), default=None, metavar="H_M",
                   help="free bump height h_b [m] (with --flattening-limit)")
    p.add_argument("--objective", default="stress", choices=_OBJECTIVES,
                   help="quantity to minimise (default stress; ties go to the least stress)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(handler=run)
    return p


def _target(values):
    if len(values) == 1:
        return values[0]
    if len(values) == 2:
        return tuple(values)
    raise ParameterError("--target-compliance", values, "give one value S or a band LOW HIGH")


def _output(design, spec) -> dict:
    return {
        "status": design.status,
        "success": design.success,
        "message": design.message,
        "target_compliance": list(design.target_compliance),
        "objective": design.objective,
        "bump_pitch_m": design.pitch,
        "half_bump_length_m": design.half_length,
        "bump_thickness_m": design.thickness,
        "top_foil_thickness_m": design.top_foil_thickness,
        "compliance": design.compliance,
        "bump_compliance_m3_per_n": design.bump_compliance,
        "bump_stress_pa": design.bump_stress,
        "allowable_stress_pa": spec.effective_allowable_stress,
        "bump_deflection_m": design.bump_deflection,
        "top_foil_sag_m": design.top_foil_sag,
        "top_foil_stress_pa": design.top_foil_stress,
        "number_of_bumps": design.number_of_bumps,
        "binding_constraints": list(design.binding_constraints),
        "compliance_range": list(design.compliance_range),
        "geometric_compliance_range": list(design.geometric_compliance_range),
        "relaxations": design.to_dict()["relaxations"],
        "solver": design.solver,
        "solves": design.solves,
        "wall_time_s": design.wall_time_s,
        "options": spec.to_dict(),
        "conventions": {"units": "SI (m, Pa)", "formulas": _FORMULAS,
                        "references": _REFERENCES,
                        "material_source": spec.material.source},
    }


def _report(out: dict) -> str:
    o = out["options"]
    low, high = out["target_compliance"]
    target = f"S = {low:.4g}" if low == high else f"S in [{low:.4g}, {high:.4g}]"
    heading = (f"gfbopt design — {out['status']}, target {target}, minimum "
               f"{out['objective'].replace('_', ' ')} (c = {o['radial_clearance'] * 1e6:.4g} µm, "
               f"p_a = {o['ambient_pressure']:.6g} Pa, dp = {o['design_pressure']:.4g} Pa, "
               f"{o['material']['name']}, E = {o['youngs_modulus'] / 1e9:.4g} GPa, "
               f"nu = {o['poisson_ratio']:.3g})")
    lines = [heading]
    if out["success"]:
        lines += [f"  bump pitch s            {out['bump_pitch_m'] * 1e3:.4f} mm",
                  f"  half bump length l0     {out['half_bump_length_m'] * 1e3:.4f} mm",
                  f"  bump thickness t_b      {out['bump_thickness_m'] * 1e6:.2f} µm"]
        if out["top_foil_thickness_m"] is not None:
            lines.append(f"  top-foil thickness      {out['top_foil_thickness_m'] * 1e6:.2f} µm "
                         f"(sag {out['top_foil_sag_m'] * 1e6:.3g} µm, stress "
                         f"{out['top_foil_stress_pa'] / 1e6:.4g} MPa)")
        if out["number_of_bumps"] is not None:
            lines.append(f"  number of bumps N       {out['number_of_bumps']}")
        alpha = out["bump_compliance_m3_per_n"]
        stress, allowable = out["bump_stress_pa"] / 1e6, out["allowable_stress_pa"] / 1e6
        binding = ", ".join(out["binding_constraints"]) or "none"
        lines += [f"  compliance S            {out['compliance']:.6g}  (alpha = {alpha:.4g} m^3/N)",
                  f"  bump stress             {stress:.4g} MPa (allowable {allowable:.4g} MPa)",
                  f"  binding                 {binding}"]
    lines.append(f"  {out['message']}")
    low, high = out["compliance_range"]
    if out["success"] and low is not None:
        lines.append(f"  achievable S under the limits: [{low:.4g}, {high:.4g}]")
    lines.append(f"  {out['solves']} GPs ({out['solver'] or 'no solver'}), "
                 f"{out['wall_time_s']:.3f} s")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    """Design the bump foil from parsed ``args``; print it; 0 on success, 1 if infeasible."""
    from ..design.geometry_program import BumpDesignSpec, design_bump_foil
    from ..provenance import provenance

    top_range = args.top_foil_thickness_range
    spec = BumpDesignSpec(
        radial_clearance=args.radial_clearance, radius=args.radius,
        ambient_pressure=args.ambient_pressure, material=args.material,
        youngs_modulus=args.youngs_modulus, poisson_ratio=args.poisson_ratio,
        allowable_stress=args.allowable_stress, design_pressure=args.design_pressure,
        pitch_range=tuple(args.pitch_range), half_length_range=tuple(args.half_length_range),
        thickness_range=tuple(args.thickness_range), gap=args.gap,
        top_foil_thickness_range=None if top_range is None else tuple(top_range),
        sag_limit=args.sag_limit, top_foil_allowable_stress=args.top_foil_allowable_stress,
        flattening_limit=args.flattening_limit, bump_height=args.bump_height,
        objective=args.objective)
    design = design_bump_foil(spec, _target(args.target_compliance))
    out = _jsonable(_output(design, spec))
    if args.json:
        out["provenance"] = provenance(**context_options(
            args, command="design", objective=args.objective, material=args.material))
    print(json.dumps(out) if args.json else _report(out))
    return 0 if design.success else 1
