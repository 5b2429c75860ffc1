"""Plausibility limits of a rotor on two foil bearings: what no real rotor can be, refused
before anything is solved, as the bearing's ``c/R <= 0.01`` is (one
:class:`~gfbopt.errors.ParameterError` naming the file, the key, the value and the rule).

The limits are generous (a real rotor is one to three orders of magnitude inside each); they
catch units given by mistake (positions in millimetres, inertias in kg mm²) and values that
cannot be a machine (1e308 kg, 1e200 m).  With D the larger journal diameter, L a bearing's
length, p_a its ambient pressure, c the smaller radial clearance:

* **a flexible shaft** (``system.shaft``): every position on the shaft, and the shaft no
  thicker than a bearing's journal where it runs in it, instead of the reach, span and
  inertia limits below (:func:`_check_shaft`); the others apply.
* **reach**: every axial position (bearings, side loads, imbalance planes, stations) within
  :data:`MAX_REACH_DIAMETERS` D of the centre of gravity, and the span between the bearings
  at most that too.  A rigid-rotor model needs a shaft far stiffer than its bearings: a solid
  steel shaft of the journal's diameter with 50 D between its supports has its first bending
  critical at (π/50 D)² (D/4) √(E/ρ) ≈ 1,300 rpm for D = 38 mm, far below any foil bearing's
  speeds.  (``position = 80`` meant as 80 mm reads as 80 m = 2,100 D.)
* **no overlap**: span >= (L_A + L_B)/2 — two bearings cannot share an axial length.
* **inertia**: for an axisymmetric body reaching axially to ``a`` and radially to ``ρ``,
  I_t = ∫(z² + r²/2) dm <= m (a² + ρ²/2) and I_p = ∫ r² dm <= m ρ².  With the reach a = 50 D
  and a wheel radius up to ρ = :data:`MAX_RADIUS_DIAMETERS` D (impellers of 20 journal
  diameters): I_t <= m (2,500 + 50) D² and I_p <= 100 m D².  (The 3.2 kg blower: I_t = 0.012
  against a limit of 11.8 kg m²; the same inertia in kg cm² is 120 and is refused.)
* **load**: each bearing's static share (weight and side loads) between
  :data:`MIN_LOAD_RATIO` p_a R² (below it the rotor is unloaded: the statics of cancelling
  loads leave round-off, 1e-15 N) and :data:`MAX_SPECIFIC_LOAD_RATIO` p_a L D (100 bar on the
  projected area at 1 bar ambient; gas foil bearings carry at most about 10 bar); and the
  rotor's weight under standard gravity at most both bearings' ceiling, even with
  ``gravity = 0`` (1e308 kg is no rotor).
* **imbalance**: the planes' amounts together at most m c — the mass centre (or the tilted
  principal axis) displaced by more than the clearance: above its rigid-body criticals a
  rotor spins about its mass centre, so its journals would orbit through the clearance at
  every speed (ISO 21940 grade G6.3 at 10,000 rpm is an offset of 6 µm; the blower's 2 g mm
  on 3.2 kg is 0.6 µm).

Speeds are not in the rotor file; :func:`check_rotor_speeds` refuses, before any solve, a
speed no bearing of the rotor can run at: a journal surface speed ω R above
:data:`MAX_SURFACE_SPEED` (steel and titanium rotors burst near 600–700 m/s; foil bearing
journals run below about 300 m/s), or a bearing number Λ above the model's bound
:data:`~gfbopt.inputs.model.MAX_BEARING_NUMBER`, which the solve itself would refuse only
after the other speeds were computed; or a bearing number below :data:`MIN_BEARING_NUMBER`.
"""
from __future__ import annotations

import math

from ..errors import ParameterError
from .conversions import STANDARD_GRAVITY

#: largest axial distance from the centre of gravity, and largest span, in journal diameters
MAX_REACH_DIAMETERS = 50.0
#: largest radius of a wheel on the rotor, in journal diameters (used for the inertia bounds)
MAX_RADIUS_DIAMETERS = 10.0
#: smallest static load on a bearing, over p_a R² (W̄ = W/(p_a R²) >= 1e-4)
MIN_LOAD_RATIO = 1e-4
#: largest static load on a bearing, over p_a L D (the projected area)
MAX_SPECIFIC_LOAD_RATIO = 100.0
#: largest journal surface speed ω R [m/s]
MAX_SURFACE_SPEED = 1000.0
#: smallest bearing number Λ of a speed: the film force grows as Λ from zero, and a
#: millionth of its order-one value carries no rotor (1e-300 rpm is no speed)
MIN_BEARING_NUMBER = 1e-6
#: largest specific load W/(p_a L D) of a bearing per unit bearing number Λ at the lowest
#: speed.  At small Λ the film force grows as Λ (the incompressible limit); the short-bearing
#: theory of a rigid film with L = D carries W/(p_a L D) = (Λ/3) ε √(π²(1-ε²)+16ε²)/(4(1-ε²)²),
#: = 10 Λ only at ε ≈ 0.9: a film of a tenth of the clearance, ≈ 2 µm, under the statics'
#: 5 µm plausibility film (gfbopt.rotor.analysis.MIN_FILM_UM).  Below that speed the rotor is
#: not airborne: the foil deflects by clearances and the static solve creeps (the blower at
#: 0.01–10 rpm scanned for minutes); the blower's floor is 82 rpm (bearing A, 20.4 N).
MAX_LOAD_PER_BEARING_NUMBER = 10.0


def check_rotor_limits(system, where: str = "") -> None:
    """Refuse a :class:`~gfbopt.inputs.rotor_system.RotorSystem` no real rotor can be (module
    docstring); ``where`` prefixes the key (the file)."""
    a, b = system.bearings
    diameter = 2.0 * max(a.geometry.radius, b.geometry.radius)
    if getattr(system, "shaft", None) is not None:
        _check_shaft(system, where)
        return
    reach = MAX_REACH_DIAMETERS * diameter
    unit_hint = "; positions are metres from the centre of gravity"
    places = [(f"bearings[{k}].position", s.position) for k, s in enumerate((a, b), 1)]
    for table in ("side_loads", "imbalance", "stations"):
        places += [(f"{table}[{k}].position", item.position)
                   for k, item in enumerate(getattr(system, table), 1)]
    for key, z in places:
        if abs(z) > reach:
            raise ParameterError(f"{where}{key}", z, f"must lie within {MAX_REACH_DIAMETERS:g} "
                                 f"journal diameters ({reach:.4g} m) of the centre of gravity "
                                 f"(a rigid rotor{unit_hint})")
    span = system.span
    if span > reach:
        raise ParameterError(f"{where}bearings[2].position", b.position, f"gives a span of "
                             f"{span:.4g} m = {span / diameter:.4g} journal diameters, above "
                             f"{MAX_REACH_DIAMETERS:g} (a shaft that long is not rigid"
                             f"{unit_hint})")
    overlap = 0.5 * (a.geometry.length + b.geometry.length)
    if span < overlap:
        raise ParameterError(f"{where}bearings[2].position", b.position, f"gives a span of "
                             f"{span:.4g} m, below (L_A + L_B)/2 = {overlap:.4g} m: the two "
                             f"bearings overlap{unit_hint}")
    _check_inertia(system.body, diameter, where)
    _check_loads(system, where)
    _check_imbalance(system, where)


def _check_shaft(system, where: str) -> None:
    """A rotor with a flexible shaft: every position on the shaft (from its first end), the
    bearings apart by at least (L_A + L_B)/2, the loads and the imbalance as for a rigid
    rotor.  The reach, span and inertia limits of a rigid rotor do not apply: the shaft
    bends, and its inertia is computed from its elements and disks."""
    from .shaft_file import check_positions_on_shaft

    check_positions_on_shaft(system.shaft, [(t, getattr(system, t)) for t in
                                            ("bearings", "side_loads", "imbalance",
                                             "stations")], where)
    a, b = system.bearings
    _check_journals(system, where)
    overlap = 0.5 * (a.geometry.length + b.geometry.length)
    if system.span < overlap:
        raise ParameterError(f"{where}bearings[2].position", b.position, f"gives a span of "
                             f"{system.span:.4g} m, below (L_A + L_B)/2 = {overlap:.4g} m: the "
                             "two bearings overlap (positions are metres from the shaft's "
                             "first end)")
    _check_loads(system, where)
    _check_imbalance(system, where)


def _check_journals(system, where: str) -> None:
    """The shaft fits each bearing: the outer diameter of every element touching a bearing's
    position is at most its journal's 2R (a sleeve may make the journal larger, nothing
    makes it smaller; catches diameters in millimetres)."""
    ends = system.shaft.ends
    tol = 1e-9 * system.shaft.length
    for support in system.bearings:
        z, journal = support.position, 2.0 * support.geometry.radius
        for k, (el, a, b) in enumerate(zip(system.shaft.elements, ends, ends[1:]), 1):
            if a - tol <= z <= b + tol and el.outer_diameter > journal * (1 + 1e-9):
                raise ParameterError(f"{where}shaft[{k}].outer_diameter", el.outer_diameter,
                                     f"must be <= bearing {support.name}'s journal diameter "
                                     f"2R = {journal:.6g} m at z = {z:g} m (the shaft runs in "
                                     "the bearing; metres, not millimetres)")


def _check_inertia(body, diameter: float, where: str) -> None:
    reach, radius = MAX_REACH_DIAMETERS * diameter, MAX_RADIUS_DIAMETERS * diameter
    it_max = body.mass * (reach ** 2 + 0.5 * radius ** 2)
    if not body.transverse_inertia <= it_max:
        raise ParameterError(f"{where}rotor.transverse_inertia", body.transverse_inertia,
                             f"must be <= m (a² + ρ²/2) = {it_max:.4g} kg m² for a rotor "
                             f"within {MAX_REACH_DIAMETERS:g} journal diameters axially and "
                             f"{MAX_RADIUS_DIAMETERS:g} radially (kg m², about the centre of "
                             "gravity)")
    ip_max = body.mass * radius ** 2
    if not body.polar_inertia <= ip_max:
        raise ParameterError(f"{where}rotor.polar_inertia", body.polar_inertia,
                             f"must be <= m ρ² = {ip_max:.4g} kg m² for wheels of radius up to "
                             f"{MAX_RADIUS_DIAMETERS:g} journal diameters (kg m²)")


def _check_loads(system, where: str) -> None:
    ceilings = [MAX_SPECIFIC_LOAD_RATIO * s.geometry.ambient_pressure * s.geometry.length
                * 2.0 * s.geometry.radius for s in system.bearings]
    weight = system.body.mass * STANDARD_GRAVITY
    if not weight <= sum(ceilings):
        key = "rotor.mass" if getattr(system, "shaft", None) is None else "shaft (total mass)"
        raise ParameterError(f"{where}{key}", system.body.mass, f"weighs {weight:.4g} N "
                             f"under standard gravity, above what both bearings could carry "
                             f"({MAX_SPECIFIC_LOAD_RATIO:g} p_a L D each: {sum(ceilings):.4g} N)")
    for support, share, ceiling in zip(system.bearings, system.static_shares(), ceilings):
        load = math.hypot(*share)
        floor = MIN_LOAD_RATIO * support.geometry.ambient_pressure * support.geometry.radius ** 2
        if not load >= floor:
            raise ParameterError(f"{where}bearing {support.name} load", load, f"the rotor "
                                 f"leaves this bearing unloaded: its share of the weight and "
                                 f"side loads is below {MIN_LOAD_RATIO:g} p_a R² = {floor:.3g} "
                                 "N (a foil bearing's film needs a load to find its "
                                 "equilibrium); change the side loads or the centre of gravity")
        if not load <= ceiling:
            raise ParameterError(f"{where}bearing {support.name} load", load, f"above "
                                 f"{MAX_SPECIFIC_LOAD_RATIO:g} p_a L D = {ceiling:.4g} N "
                                 "(100 bar on the projected area at 1 bar ambient; foil "
                                 "bearings carry at most about a tenth of it)")


def _check_imbalance(system, where: str) -> None:
    if not system.imbalance:
        return
    total = sum(p.amount_kg_m for p in system.imbalance)
    clearance = min(s.geometry.radial_clearance for s in system.bearings)
    offset = total / system.body.mass
    if not offset <= clearance:
        k = max(range(len(system.imbalance)), key=lambda i: system.imbalance[i].amount_kg_m)
        raise ParameterError(f"{where}imbalance[{k + 1}].amount_kg_m",
                             system.imbalance[k].amount_kg_m,
                             f"the planes' imbalance {total:.4g} kg m over the mass "
                             f"{system.body.mass:g} kg displaces the mass centre by "
                             f"{offset * 1e6:.4g} µm, more than the clearance "
                             f"{clearance * 1e6:.4g} µm (the journals would orbit through it "
                             "at every speed above the rigid-body criticals)")


def check_surface_speed(bearing, speeds, name: str) -> None:
    """Every speed [rpm] of ``speeds`` moves the journal surface of ``bearing`` (a
    BearingGeometry, SI) at most :data:`MAX_SURFACE_SPEED`: the rotor's rule, for one bearing
    (``gfbopt stability``, ``capacity``, ``static``, ``linear``, ``orbit``); one ParameterError
    naming ``name``, before any solve."""
    for speed in speeds:
        if speed is None:
            continue
        surface = float(speed) * math.pi / 30.0 * bearing.radius
        if not surface <= MAX_SURFACE_SPEED:
            fastest = MAX_SURFACE_SPEED / bearing.radius * 30.0 / math.pi
            raise ParameterError(name, speed, f"moves the journal surface at {surface:.3g} m/s, "
                                 f"above {MAX_SURFACE_SPEED:g} m/s (rotors burst near 600–700 "
                                 f"m/s): at most {fastest:.6g} rpm")


def check_rotor_speeds(system, speeds, name: str = "--speed-range") -> tuple:
    """``speeds`` [rpm] as floats, each finite and > 0 and with every bearing's bearing
    number Λ at most :data:`~gfbopt.inputs.model.MAX_BEARING_NUMBER` (one ParameterError
    naming ``name``, before any solve)."""
    from .checks import check_positive
    from .model import MAX_BEARING_NUMBER

    values = tuple(check_positive(name, v) for v in speeds)
    top = max(values)
    for support, share in zip(system.bearings, system.static_shares()):
        slowest = support.geometry.bearing_number(min(values))
        if not slowest >= MIN_BEARING_NUMBER:
            raise ParameterError(name, list(speeds), f"{min(values):.6g} rpm gives bearing "
                                 f"{support.name} a bearing number Λ = {slowest:.3g}, below "
                                 f"{MIN_BEARING_NUMBER:g}: no film carries the rotor there")
        g = support.geometry
        specific = math.hypot(*share) / (g.ambient_pressure * g.length * 2.0 * g.radius)
        if not specific <= MAX_LOAD_PER_BEARING_NUMBER * slowest:
            lowest = min(values) * specific / (MAX_LOAD_PER_BEARING_NUMBER * slowest)
            raise ParameterError(name, list(speeds), f"{min(values):.6g} rpm gives bearing "
                                 f"{support.name} Λ = {slowest:.3g} under a specific load "
                                 f"W/(p_a L D) = {specific:.3g}, above "
                                 f"{MAX_LOAD_PER_BEARING_NUMBER:g} Λ: the film there is thinner "
                                 f"than a real surface (the rotor is not airborne); at least "
                                 f"{lowest:.4g} rpm")
        surface = top * math.pi / 30.0 * support.geometry.radius
        if not surface <= MAX_SURFACE_SPEED:
            fastest = MAX_SURFACE_SPEED / support.geometry.radius * 30.0 / math.pi
            raise ParameterError(name, list(speeds), f"{top:.6g} rpm moves bearing "
                                 f"{support.name}'s journal surface at {surface:.3g} m/s, "
                                 f"above {MAX_SURFACE_SPEED:g} m/s (rotors burst near 600–700 "
                                 f"m/s): at most {fastest:.6g} rpm")
        number = support.geometry.bearing_number(top)
        if not number <= MAX_BEARING_NUMBER:
            fastest = top * MAX_BEARING_NUMBER / number
            raise ParameterError(name, list(speeds), f"{top:.6g} rpm gives bearing "
                                 f"{support.name} a bearing number Λ = {number:.3g}, above "
                                 f"{MAX_BEARING_NUMBER:g} (real gas bearings run below Λ ≈ "
                                 f"100): at most {fastest:.6g} rpm")
    return values
