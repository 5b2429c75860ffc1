"""Bump-foil geometry for a target compliance: a geometric program (cvxpy, ``gp=True``).

Given the radial clearance, the foil material and ranges for the pitch s, half bump length l0
and bump thickness t_b, :func:`design_bump_foil` finds the geometry whose compliance
coefficient S = p_a α / c equals a target (or lies in a band) at the least bump bending stress
(or another monomial objective), subject to

* box bounds on s, l0, t_b (and on the top-foil thickness t_top when it is designed too),
* the bump closing within its pitch, 2 l0 + gap ≤ s, written (2 l0 + gap)/s ≤ 1,
* the bending stress limit σ_b = 3 Δp s l0 / t_b² ≤ σ_allow,
* optionally the top-foil sag Δp s⁴ (1 − ν²)/(32 E t_top³) ≤ κ_c c, the top-foil stress
  Δp s²/(2 t_top²) ≤ σ_top, and no bump flattening Δp α ≤ κ h_b.

Every quantity is a monomial in (s, l0, t_b, t_top) and every constraint a posynomial ≤ monomial,
so the problem is a geometric program: convex in the logarithms of the variables, solved to its
global optimum in milliseconds.  The formulas are those of :mod:`gfbopt.physics.bump`, evaluated
here on cvxpy variables and, for checking the answer, on the returned floats.

Two kinds of constraint are kept apart.  *Geometry* (the ranges and the bump closing) is what
the designer can make; a target compliance outside what the geometry allows is bad input
(``ParameterError``).  *Limits* (stresses, sag, flattening) are engineering judgement; when they
make the problem infeasible the result says so (``success=False``) and a relaxed GP — each
limit multiplied by a factor t_i ≥ 1, the product of the t_i minimised — says which limits must
move and by how much, with the geometry held.

With a bearing radius R the number of bumps N = 2πR/s must be a whole number: the continuous
optimum is rounded down and up, the pitch fixed to 2πR/N and the GP solved again; the better
feasible N is kept.  (The feasible pitches form an interval — the feasible set is convex in
log s — so if neither neighbour of the continuous optimum is feasible no whole N is.)

Speed.  A design search asks for many targets S on one spec: the compliance ranges are kept
per spec, and a target value is solved on a design GP whose target (and fixed pitch) are
cvxpy parameters, kept per spec, so that cvxpy compiles it once (DPP) and every later target
only sets the parameters — the compilation, not the conic solve, is most of a GP's cost.
The program parts live in :mod:`.gp_parts`.
"""
from __future__ import annotations

import functools
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import cvxpy as cp

from ..errors import ConvergenceError, ParameterError
from ..physics import bump
from .gp_parts import (
    _Geometry,
    _Limit,
    _limits,
    _objective,
    _quantities,
    _solve,
    _target_limits,
    _values,
    _variables,
)
from .spec import (
    OBJECTIVES,
    BumpDesign,
    BumpDesignSpec,
    Relaxation,
    _mm,
    _positive,
    _range,
)

__all__ = ["BINDING_TOLERANCE", "OBJECTIVES", "BumpDesign", "BumpDesignSpec", "Relaxation",
           "compliance_range", "design_bump_foil"]

#: A constraint g ≤ 1 is reported as binding when 1 − g < BINDING_TOLERANCE at the solution.
BINDING_TOLERANCE = 1e-6
# A returned geometry is accepted when it meets every constraint to this relative tolerance
# (Clarabel's own feasibility tolerance is 1e-8 in the logarithms of the variables).
_CHECK_TOLERANCE = 1e-5
# Ties: the second GP keeps the objective within this relative amount of its optimum.
_TIE_TOLERANCE = 1e-7
# A relaxation factor above 1 + this is reported as a limit that must move.
_RELAXATION_THRESHOLD = 1e-5
_SUCCESS_STATUSES = ("optimal", "optimal_inaccurate")


# ---------------------------------------------------------------- compliance range
@functools.lru_cache(maxsize=64)
def _compliance_range(spec: BumpDesignSpec, include_limits: bool) -> tuple[float, float]:
    """(S_min, S_max) of ``spec`` by two GPs; a function of the frozen spec alone, so it is
    kept per spec (a design search asks it for every target S: the same two GPs each
    time).  A solver failure raises and is not kept."""
    g = _variables(spec, None)
    q = _quantities(spec, g)
    constraints = [lim.ratio <= 1.0
                   for lim in _limits(spec, g, q, pitch_fixed=False,
                                      include_limits=include_limits)]
    ends = []
    for objective in (q["compliance"], 1.0 / q["compliance"]):
        status, _ = _solve(cp.Problem(cp.Minimize(objective), constraints))
        if status not in _SUCCESS_STATUSES:
            if include_limits:
                return (math.nan, math.nan)
            raise ConvergenceError("compliance range over the geometry ranges not found",
                                   status=status)
        ends.append(_quantities(spec, _values(g))["compliance"])
    return (ends[0], ends[1])


def compliance_range(spec: BumpDesignSpec, limits: bool = True) -> tuple[float, float]:
    """Least and greatest compliance coefficient S the spec allows, by two GPs.

    Parameters
    ----------
    spec : the design specification
    limits : True — under every constraint (geometry, stresses, sag, flattening);
        False — under the geometry constraints only (ranges, bump closing)

    Returns
    -------
    (S_min, S_max) [-]; (nan, nan) when the limits leave no feasible geometry.
    """
    return _compliance_range(spec, limits)


# --------------------------------------------------------------------- one design GP
@dataclass(frozen=True)
class _Solution:
    status: str
    solver: str
    geometry: _Geometry | None = None
    binding: tuple[str, ...] = ()
    objective: float = math.nan

    @property
    def ok(self) -> bool:
        return self.geometry is not None


def _binding(limits: Sequence[_Limit]) -> tuple[str, ...]:
    return tuple(lim.name for lim in limits if 1.0 - lim.ratio < BINDING_TOLERANCE)


def _check(spec: BumpDesignSpec, g: _Geometry, target: tuple[float, float],
           pitch_fixed: bool) -> tuple[str, ...]:
    """Re-evaluate the plain formulas on ``g``: the names of the constraints it violates."""
    q = _quantities(spec, g)
    bad = [lim.name for lim in _limits(spec, g, q, pitch_fixed)
           if lim.ratio > 1.0 + _CHECK_TOLERANCE]
    s = q["compliance"]
    if not target[0] * (1.0 - _CHECK_TOLERANCE) <= s <= target[1] * (1.0 + _CHECK_TOLERANCE):
        bad.append(f"compliance S = {s:.6g} on target")
    return tuple(bad)


def _thinnest_top_foil(spec: BumpDesignSpec, pitch: float) -> float:
    """The thinnest top foil in its range meeting the top-foil stress and sag limits [m].

    The stress scales as t_top⁻² and the sag as t_top⁻³, so each limit fixes a least
    thickness from the formula evaluated at t_top = 1 m.
    """
    dp, e, nu = spec.design_pressure, spec.effective_youngs_modulus, spec.effective_poisson_ratio
    low, high = spec.top_foil_thickness_range
    need = [low, (bump.top_foil_stress(dp, pitch, 1.0)
                  / spec.effective_top_foil_allowable_stress) ** 0.5]
    if spec.sag_limit is not None:
        need.append((bump.top_foil_sag(dp, pitch, 1.0, e, nu)
                     / (spec.sag_limit * spec.radial_clearance)) ** (1.0 / 3.0))
    return min(max(need), high)


@dataclass(frozen=True)
class _Program:
    """The design GP at a target S (and a fixed pitch) given as cvxpy parameters, so that
    cvxpy compiles it once and every later target only sets the parameters (DPP)."""

    problem: cp.Problem
    geometry: _Geometry
    quantities: dict
    objective: object
    constraints: list
    target: cp.Parameter
    pitch: cp.Parameter | None


def _design_objective(spec: BumpDesignSpec, g: _Geometry, q: dict):
    objective = _objective(spec, g, q)
    if not isinstance(objective, cp.Expression) or objective.is_constant():
        objective = q["stress"]  # the pitch is fixed: the pitch objectives are constants
    return objective


@functools.lru_cache(maxsize=64)
def _program(spec: BumpDesignSpec, pitch_fixed: bool) -> _Program:
    """The parametrised design GP of ``spec`` (kept per spec: a design search solves it for
    many targets S); the same constraints and objective as the unparametrised one."""
    target = cp.Parameter(pos=True, name="target_compliance")
    pitch = cp.Parameter(pos=True, name="pitch") if pitch_fixed else None
    g = _variables(spec, pitch)
    q = _quantities(spec, g)
    constraints = ([lim.ratio <= 1.0 for lim in _limits(spec, g, q, pitch_fixed)]
                   + [q["compliance"] == target])
    objective = _design_objective(spec, g, q)
    return _Program(cp.Problem(cp.Minimize(objective), constraints), g, q, objective,
                    constraints, target, pitch)


def _solve_design(spec: BumpDesignSpec, target: tuple[float, float],
                  pitch: float | None = None) -> tuple[_Solution, int]:
    """Minimise the objective at the target S (pitch fixed when given); (solution, GPs).
    A target value (not a band) is solved on the kept parametrised program (:func:`_program`)."""
    if target[0] == target[1]:
        program = _program(spec, pitch is not None)
        program.target.value = target[0]
        if program.pitch is not None:
            program.pitch.value = pitch
        g, q, objective = program.geometry, program.quantities, program.objective
        constraints = program.constraints
        status, solver = _solve(program.problem)
    else:
        g = _variables(spec, pitch)
        q = _quantities(spec, g)
        constraints = ([lim.ratio <= 1.0 for lim in _limits(spec, g, q, pitch is not None)]
                       + _target_limits(q, target))
        objective = _design_objective(spec, g, q)
        status, solver = _solve(cp.Problem(cp.Minimize(objective), constraints))
    solves = 1
    if status not in _SUCCESS_STATUSES:
        return _Solution(status, solver), solves
    values = _values(g)
    if objective is not q["stress"]:
        # Ties: among the optimal geometries take the one of least bump stress.
        cap = float(objective.value) * (1.0 + _TIE_TOLERANCE)
        status2, _ = _solve(cp.Problem(cp.Minimize(q["stress"]),
                                       constraints + [objective / cap <= 1.0]))
        solves += 1
        if status2 in _SUCCESS_STATUSES:
            values = _values(g)
    if (values.top_foil_thickness is not None
            and spec.objective not in ("top_foil_thickness", "top_foil_sag")):
        values = _Geometry(values.pitch, values.half_length, values.thickness,
                           _thinnest_top_foil(spec, values.pitch))
    violated = _check(spec, values, target, pitch is not None)
    if violated:
        return _Solution(f"{status}, but the answer violates {', '.join(violated)}",
                         solver), solves
    q_values = _quantities(spec, values)
    limits = _limits(spec, values, q_values, pitch is not None)
    binding = _binding(limits)
    if target[0] != target[1]:
        s = q_values["compliance"]
        binding += tuple(name for name, ratio in (("compliance >= lower target", target[0] / s),
                                                  ("compliance <= upper target", s / target[1]))
                         if 1.0 - ratio < BINDING_TOLERANCE)
    objective_value = _objective(spec, values, q_values)
    return _Solution(status, solver, values, binding, float(objective_value)), solves


def _relaxations(spec: BumpDesignSpec, target: tuple[float, float],
                 pitch: float | None = None) -> tuple[tuple[Relaxation, ...] | None, str]:
    """Least moves of the limits (geometry held) that make the design feasible.

    Each limit ratio_i ≤ 1 becomes ratio_i ≤ t_i, t_i ≥ 1, and ∏ t_i is minimised (a GP).
    Returns (relaxations, status); relaxations is None when even that GP has no solution
    (the geometry alone cannot reach the target).
    """
    g = _variables(spec, pitch)
    q = _quantities(spec, g)
    limits = _limits(spec, g, q, pitch is not None)
    constraints = _target_limits(q, target)
    factors = []
    for lim in limits:
        if lim.relax is None:
            constraints.append(lim.ratio <= 1.0)
        else:
            t = cp.Variable(pos=True)
            factors.append((lim, t))
            constraints += [lim.ratio <= t, t >= 1.0]
    product = factors[0][1]
    for _, t in factors[1:]:
        product = product * t
    status, _ = _solve(cp.Problem(cp.Minimize(product), constraints))
    if status not in _SUCCESS_STATUSES:
        return None, status
    moves = []
    for lim, t in factors:
        factor = float(t.value)
        if factor > 1.0 + _RELAXATION_THRESHOLD:
            label, value, scale, unit = lim.relax
            moves.append(Relaxation(label, factor, value * scale, value * factor * scale, unit))
    return tuple(moves), status


# --------------------------------------------------------------------------- design
def _check_target(target) -> tuple[float, float]:
    if isinstance(target, (tuple, list)):
        low, high = _range("target compliance band", target)
        return low, high
    value = _positive("target compliance S", target)
    return value, value


def _describe_target(target: tuple[float, float]) -> str:
    low, high = target
    return f"S = {low:.4g}" if low == high else f"S in [{low:.4g}, {high:.4g}]"


def _outputs(spec: BumpDesignSpec, g: _Geometry | None) -> dict:
    """The geometry and what the plain formulas give for it (NaN without a geometry)."""
    if g is None:
        top = math.nan if spec.top_foil_thickness_range is not None else None
        return {"pitch": math.nan, "half_length": math.nan, "thickness": math.nan,
                "top_foil_thickness": top, "compliance": math.nan,
                "bump_compliance": math.nan, "bump_stress": math.nan,
                "bump_deflection": math.nan, "top_foil_sag": top, "top_foil_stress": top}
    q = _quantities(spec, g)
    return {"pitch": g.pitch, "half_length": g.half_length, "thickness": g.thickness,
            "top_foil_thickness": g.top_foil_thickness, "compliance": q["compliance"],
            "bump_compliance": q["alpha"], "bump_stress": q["stress"],
            "bump_deflection": q["deflection"], "top_foil_sag": q.get("top_foil_sag"),
            "top_foil_stress": q.get("top_foil_stress")}


def _infeasible_message(target, pitch, moves, relax_status, with_limits) -> str:
    where = "" if pitch is None else f" with the pitch fixed at {_mm(pitch)}"
    if moves is None:
        return (f"infeasible: {_describe_target(target)} cannot be reached{where} within the "
                f"half-length and thickness ranges, whatever the limits "
                f"(relaxation GP: {relax_status})")
    text = (f"infeasible: {_describe_target(target)}{where} breaks the limits; with the "
            "geometry ranges held, " + "; ".join(m.describe() for m in moves))
    if pitch is None and math.isfinite(with_limits[0]):
        text += (f". Under the present limits S can range over "
                 f"[{with_limits[0]:.4g}, {with_limits[1]:.4g}]")
    elif pitch is None:
        text += ". Under the present limits no geometry is feasible at any S"
    return text


def design_bump_foil(spec: BumpDesignSpec,
                     target_compliance: float | tuple[float, float]) -> BumpDesign:
    """The bump-foil geometry that meets ``spec`` at the target compliance coefficient.

    Parameters
    ----------
    spec : the design specification (ranges, limits, material, objective)
    target_compliance : S [-], or a band (low, high)

    Returns
    -------
    BumpDesign with ``success=False`` and the limits that must move when the limits exclude
    every geometry (no exception for a valid but infeasible spec).

    Raises
    ------
    ParameterError
        bad target, or a target outside what the geometry ranges allow.
    ConvergenceError
        the solver failed on the (always feasible) geometry-range GPs.
    """
    start = time.perf_counter()
    target = _check_target(target_compliance)
    geometric = _compliance_range(spec, include_limits=False)
    low_ok = target[1] >= geometric[0] * (1.0 - 1e-9)
    high_ok = target[0] <= geometric[1] * (1.0 + 1e-9)
    if not (low_ok and high_ok):
        value = target[0] if target[0] == target[1] else target
        name = "target compliance S" if target[0] == target[1] else "target compliance band"
        raise ParameterError(
            name, value,
            f"outside the achievable range [{geometric[0]:.4g}, {geometric[1]:.4g}] under "
            "these limits (pitch, half-length and thickness ranges; bump closing within "
            "the pitch)")
    with_limits = _compliance_range(spec, include_limits=True)
    solves = 4

    def result(solution: _Solution, status: str, message: str, relaxations=(),
               number_of_bumps=None) -> BumpDesign:
        return BumpDesign(
            status=status, success=solution.ok, message=message, target_compliance=target,
            objective=spec.objective, number_of_bumps=number_of_bumps,
            binding_constraints=solution.binding, compliance_range=with_limits,
            geometric_compliance_range=geometric, relaxations=tuple(relaxations or ()),
            solver=solution.solver, solves=solves, wall_time_s=time.perf_counter() - start,
            **_outputs(spec, solution.geometry))

    continuous, used = _solve_design(spec, target)
    solves += used
    if not continuous.ok:
        moves, relax_status = _relaxations(spec, target)
        solves += 1
        return result(continuous, continuous.status,
                      _infeasible_message(target, None, moves, relax_status, with_limits),
                      moves)
    summary = (f"{continuous.status}: minimum {spec.objective.replace('_', ' ')} at "
               f"{_describe_target(target)}")
    if spec.radius is None:
        return result(continuous, continuous.status, summary)

    # A whole number of bumps: round the continuous optimum down and up, fix the pitch, solve.
    # At least one of the two lies in bump_count_range (the spec checked that a whole N fits
    # the pitch range, and the continuous pitch lies in it).
    n_cont = bump.number_of_bumps(spec.radius, continuous.geometry.pitch)
    n_min, n_max = spec.bump_count_range
    nearest = round(n_cont)
    candidates = ([nearest] if abs(n_cont - nearest) < 1e-9
                  else [math.floor(n_cont), math.ceil(n_cont)])
    tried = []
    for n in (n for n in candidates if n_min <= n <= n_max):
        solution, used = _solve_design(spec, target, pitch=2.0 * math.pi * spec.radius / n)
        solves += used
        tried.append((n, solution))
    feasible = [(sol.objective, abs(n - n_cont), n, sol) for n, sol in tried if sol.ok]
    if feasible:
        _, _, n, solution = min(feasible, key=lambda item: item[:3])
        return result(solution, solution.status,
                      f"{summary} with N = {n} bumps (pitch 2πR/N = "
                      f"{_mm(solution.geometry.pitch)}; the continuous optimum has "
                      f"N = {n_cont:.4g}, pitch {_mm(continuous.geometry.pitch)})",
                      number_of_bumps=n)
    n, failed = min(tried, key=lambda item: abs(item[0] - n_cont))
    pitch = 2.0 * math.pi * spec.radius / n
    moves, relax_status = _relaxations(spec, target, pitch)
    solves += 1
    message = (f"infeasible: no whole number of bumps meets the limits (the continuous "
               f"optimum has N = {n_cont:.4g}, pitch {_mm(continuous.geometry.pitch)}; tried "
               f"N = {', '.join(str(k) for k, _ in tried)}). For N = {n}: "
               + _infeasible_message(target, pitch, moves, relax_status, with_limits))
    return result(failed, "infeasible", message, moves)
