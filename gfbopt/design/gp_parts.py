"""The parts of the bump-foil geometric programs (:mod:`.geometry_program`): the design
variables, every monomial of the design on floats or cvxpy variables alike, the constraints
as ``ratio <= 1`` and the GP solve with cvxpy's warnings recorded."""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import cvxpy as cp

from ..physics import bump
from .spec import BumpDesignSpec, _mm, _um

# ----------------------------------------------------------------- the program parts
@dataclass(frozen=True)
class _Limit:
    """One constraint, ``ratio <= 1``; a limit (relaxable) when ``relax`` is given."""

    name: str
    ratio: object  # cvxpy expression or float
    relax: tuple[str, float, float, str] | None = None  # (label, value, scale, unit)


@dataclass(frozen=True)
class _Geometry:
    """Design variables (cvxpy variables) or their values (floats)."""

    pitch: object
    half_length: object
    thickness: object
    top_foil_thickness: object = None


def _quantities(spec: BumpDesignSpec, g: _Geometry) -> dict:
    """Every monomial of the design, on floats or on cvxpy variables alike."""
    e, nu, dp = spec.effective_youngs_modulus, spec.effective_poisson_ratio, spec.design_pressure
    alpha = bump.bump_compliance(g.pitch, g.half_length, g.thickness, e, nu)
    q = {"alpha": alpha,
         "compliance": bump.compliance_coefficient(alpha, spec.ambient_pressure,
                                                   spec.radial_clearance),
         "stress": bump.bump_bending_stress(dp, g.pitch, g.half_length, g.thickness),
         "deflection": bump.bump_deflection(dp, alpha)}
    if g.top_foil_thickness is not None:
        q["top_foil_sag"] = bump.top_foil_sag(dp, g.pitch, g.top_foil_thickness, e, nu)
        q["top_foil_stress"] = bump.top_foil_stress(dp, g.pitch, g.top_foil_thickness)
    return q


def _objective(spec: BumpDesignSpec, g: _Geometry, q: dict):
    return {"stress": q["stress"], "pitch": g.pitch, "number_of_bumps": 1.0 / g.pitch,
            "thickness": g.thickness, "half_length": g.half_length,
            "top_foil_thickness": g.top_foil_thickness,
            "top_foil_sag": q.get("top_foil_sag")}[spec.objective]


def _limits(spec: BumpDesignSpec, g: _Geometry, q: dict, pitch_fixed: bool,
            include_limits: bool = True) -> list[_Limit]:
    """All constraints as ``ratio <= 1``: geometry first, then the (relaxable) limits."""
    out = []

    def box(label, var, bounds, fmt):
        out.append(_Limit(f"{label} >= {fmt(bounds[0])}", bounds[0] / var))
        out.append(_Limit(f"{label} <= {fmt(bounds[1])}", var / bounds[1]))

    if not pitch_fixed:
        box("pitch", g.pitch, spec.pitch_range, _mm)
    box("half length", g.half_length, spec.half_length_range, _mm)
    box("bump thickness", g.thickness, spec.thickness_range, _um)
    if spec.top_foil_thickness_range is not None:
        box("top-foil thickness", g.top_foil_thickness, spec.top_foil_thickness_range, _um)
    out.append(_Limit("bump closes within pitch", (2.0 * g.half_length + spec.gap) / g.pitch))
    if not include_limits:
        return out
    allowable = spec.effective_allowable_stress
    out.append(_Limit("bump stress <= allowable", q["stress"] / allowable,
                      ("allowable stress", allowable, 1e-6, "MPa")))
    if spec.top_foil_thickness_range is not None:
        top_allowable = spec.effective_top_foil_allowable_stress
        out.append(_Limit("top-foil stress <= allowable", q["top_foil_stress"] / top_allowable,
                          ("top-foil allowable stress", top_allowable, 1e-6, "MPa")))
        if spec.sag_limit is not None:
            out.append(_Limit("top-foil sag <= limit",
                              q["top_foil_sag"] / (spec.sag_limit * spec.radial_clearance),
                              ("top-foil sag limit κ_c", spec.sag_limit, 1.0, "")))
    if spec.flattening_limit is not None:
        allowed = spec.flattening_limit * spec.bump_height
        out.append(_Limit("no bump flattening", q["deflection"] / allowed,
                          ("no-flattening limit κ h_b", allowed, 1e6, "µm")))
    return out


def _target_limits(q: dict, target: tuple[float, float]) -> list:
    """cvxpy constraints putting S on the target (an equality) or in the band."""
    low, high = target
    if low == high:
        return [q["compliance"] == low]
    return [q["compliance"] / high <= 1.0, low / q["compliance"] <= 1.0]


def _variables(spec: BumpDesignSpec, pitch: float | None) -> _Geometry:
    top = (cp.Variable(pos=True, name="top_foil_thickness")
           if spec.top_foil_thickness_range is not None else None)
    return _Geometry(pitch if pitch is not None else cp.Variable(pos=True, name="pitch"),
                     cp.Variable(pos=True, name="half_length"),
                     cp.Variable(pos=True, name="thickness"), top)


def _values(g: _Geometry) -> _Geometry:
    def value(x):
        return None if x is None else float(x.value) if isinstance(x, cp.Expression) else x
    return _Geometry(value(g.pitch), value(g.half_length), value(g.thickness),
                     value(g.top_foil_thickness))


def _solve(problem: cp.Problem) -> tuple[str, str]:
    """Solve a GP; return (status, solver name).

    cvxpy's warnings (e.g. 'Solution may be inaccurate') are recorded, not raised: the status
    carries the same information and the answer is re-checked with the plain formulas.
    """
    with warnings.catch_warnings(record=True):
        warnings.simplefilter("always")
        try:
            problem.solve(gp=True)
        except cp.error.SolverError as exc:
            return f"solver_error: {exc}", ""
    status = str(problem.status)  # 'optimal_inaccurate' already flags a doubtful answer
    stats = problem.solver_stats
    return status, (stats.solver_name if stats is not None else "")
