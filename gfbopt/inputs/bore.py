"""The bearing as it is built: bore profile (mechanical preload), top-foil pads and bump zones.

Two layers, as everywhere in :mod:`gfbopt.inputs`:

* SI descriptions a user writes (angles in degrees, lengths in metres): :class:`BoreSpec`,
  :class:`PadSpec`, :class:`ZoneSpec`, gathered in :class:`BearingBuild` (the ``[bore]``,
  ``[[pads]]`` and ``[[zones]]`` tables of a bearing file, :func:`build_from_tables`);
* the non-dimensional :class:`AsBuilt` a :class:`~gfbopt.inputs.model.BearingModel` carries
  (``BearingModel.as_built``; angles in radians inside the code, clearances over c).

Conventions (``docs/PHYSICS.md`` §5a): angles are measured from the static load line in the
direction of rotation, like the seam angle; the bore's clearance change B(θ) = Δc(θ)/c is
positive where the clearance grows, so a preload (shim or lobe) is negative B and the film is
H = 1 + B(θ) − X cos θ − Y sin θ + W.  A bore, pads and zones are fixed in the housing.

Bore profiles (preload ratio r = preload depth / c):

===========  ===============================================================================
kind         B(θ)
===========  ===============================================================================
round        0 (today's bearing)
shims        −r on each of N shims of angular width β centred at θ_off + 2πk/N (a shim under
             the bump strip raises the foil by its thickness over its width; sharp edges)
lobes        −r cos(N (θ − θ_off)): clearance c − d at the lobe centres, c + d between them
table        periodic linear interpolation of (angle, Δc) points
===========  ===============================================================================
"""
from __future__ import annotations

from typing import Optional

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ParameterError
from .checks import (FRICTION_COEFFICIENT_BELOW, WHY_FRICTION, check_finite,
                     check_positive)

BORE_KINDS = ("round", "shims", "lobes", "table")
TWO_PI = 2.0 * math.pi
#: two angles closer than this are the same [rad] (pads and zones meeting end to end)
ANGLE_TOLERANCE = 1e-9
#: the range of a starting angle (shim or lobe offset, pad leading end, zone start) [deg]: a
#: turn either way; 1e300° has no angle left after wrapping (the shims vanished)
START_RANGE_DEG = (-360.0, 360.0)
#: the range of a zone's end [deg] (above 360: through 0°)
END_RANGE_DEG = (-360.0, 720.0)
#: the range of any angle of the non-dimensional description [deg] (built in code, e.g. a
#: seam plus k × 120°): three turns either way, so that wrapping keeps the angle's digits
ANGLE_RANGE_DEG = (-1080.0, 1080.0)
#: most shims, lobes or pads: a bore of more is a surface finish, not a preload profile, and
#: the default grid's 144 rows resolve 12 of them at 12 rows each (10⁶ lobes on 36 rows were
#: aliased into a different bore)
MAX_FEATURES = 12
#: most bump zones (each zone at least a few grid rows on the default grid)
MAX_ZONES = 24
#: narrowest shim or pad [deg]: one row of the finest grid gfbopt builds (2000 rows round the
#: bearing); a narrower one cannot be represented on any grid
MIN_WIDTH_DEG = 360.0 / 2000
#: fewest θ rows of the grid per shim, lobe or pad period (below it the profile is aliased)
MIN_ROWS_PER_FEATURE = 3


def _deg(angle: float) -> float:
    """An angle [rad] in degrees, rounded to 1e-9° for outputs."""
    return round(math.degrees(angle), 9)


def _wrap(angle):
    """An angle (or array) in [0, 2π) [rad]."""
    return np.mod(angle, TWO_PI)


def degrees_in(name: str, value, low: float = -math.inf, high: float = math.inf,
             low_open: bool = False) -> float:
    v = check_finite(name, value)
    if v < low or (low_open and v == low) or v > high:
        bound = f"({low}, {high}]" if low_open else f"[{low}, {high}]"
        raise ParameterError(name, value, f"must lie in {bound} degrees")
    return v


# ------------------------------------------------------------------ non-dimensional
@dataclass(frozen=True)
class BoreProfile:
    """The bore's clearance change B(θ) = Δc/c (non-dimensional; module docstring).

    kind : 'round', 'shims', 'lobes' or 'table';  count : N shims or lobes;  preload :
    r = preload depth / c [-] (≥ 0);  width : each shim's angular width β [rad];  offset :
    centre of the first shim or lobe from the load line [rad];  table_angles [rad] and
    table_change [-] : the points of a 'table' profile (angles strictly increasing in [0, 2π)).
    """

    kind: str = "round"
    count: int = 0
    preload: float = 0.0
    width: float = 0.0
    offset: float = 0.0
    table_angles: tuple = ()
    table_change: tuple = ()

    def __post_init__(self) -> None:
        if self.kind not in BORE_KINDS:
            raise ParameterError("bore.kind", self.kind, f"must be one of {', '.join(BORE_KINDS)}")
        if self.kind in ("shims", "lobes"):
            if isinstance(self.count, bool) or not isinstance(self.count, int) or self.count < 1:
                raise ParameterError("bore.count", self.count, "must be a whole number >= 1")
            if self.count > MAX_FEATURES:
                raise ParameterError("bore.count", self.count, f"must be <= {MAX_FEATURES} "
                                     "(more shims or lobes are a surface finish, not a preload "
                                     "profile, and no grid of gfbopt's would resolve them)")
            degrees_in("bore.offset_deg", math.degrees(check_finite("bore.offset",
                                                                    self.offset)),
                       *ANGLE_RANGE_DEG)
            r = check_finite("bore.preload_ratio", self.preload)
            if r < 0:
                raise ParameterError("bore.preload_ratio", self.preload, "must be >= 0 (a "
                                     "preload reduces the clearance; use a table for a relief)")
        if self.kind == "shims":
            w = check_finite("bore.width_deg", math.degrees(self.width))
            if w <= 0:
                raise ParameterError("bore.width_deg", w, "must be > 0 (negative or zero "
                                     "shim width)")
            if w < MIN_WIDTH_DEG:
                raise ParameterError("bore.width_deg", w, f"must be >= {MIN_WIDTH_DEG:g} (one "
                                     "row of the finest grid: a narrower shim is on no grid)")
            if self.count * self.width > TWO_PI + ANGLE_TOLERANCE:
                raise ParameterError("bore.width_deg", round(w, 10), f"{self.count} shims of "
                                     "this width overlap (N × width must be <= 360°)")
        if self.kind == "table":
            a = np.asarray(self.table_angles, float)
            b = np.asarray(self.table_change, float)
            if a.size < 2 or a.size != b.size or not np.all(np.isfinite(a)) \
                    or not np.all(np.isfinite(b)):
                raise ParameterError("bore.table", (self.table_angles, self.table_change),
                                     "needs >= 2 finite (angle, clearance change) points")
            if np.any(np.diff(a) <= 0) or a[0] < 0 or a[-1] >= TWO_PI:
                raise ParameterError("bore.angle_deg", [round(math.degrees(x), 6) for x in a],
                                     "must increase strictly within [0, 360)")

    @property
    def is_round(self) -> bool:
        """True when B ≡ 0 (round bore, or a zero preload/table)."""
        if self.kind in ("shims", "lobes"):
            return self.preload == 0.0
        if self.kind == "table":
            return not any(self.table_change)
        return True

    def clearance_change(self, theta) -> np.ndarray:
        """B(θ) = Δc/c at the angles θ [rad] from the load line (numpy)."""
        theta = np.asarray(theta, float)
        if self.is_round:
            return np.zeros_like(theta)
        if self.kind == "lobes":
            return -self.preload * np.cos(self.count * (theta - self.offset))
        if self.kind == "shims":
            period = TWO_PI / self.count
            u = np.mod(theta - self.offset + 0.5 * period, period) - 0.5 * period
            return np.where(np.abs(u) <= 0.5 * self.width + ANGLE_TOLERANCE, -self.preload, 0.0)
        a = np.asarray(self.table_angles, float)
        b = np.asarray(self.table_change, float)
        return np.interp(_wrap(theta), a, b, period=TWO_PI)

    def smallest_film_at_centre(self) -> tuple[float, float]:
        """(min over θ of 1 + B, its angle [rad]) with the journal concentric (fine sampling
        plus the table points and shim/lobe centres)."""
        theta = np.linspace(0.0, TWO_PI, 7201)[:-1]
        extra = list(self.table_angles) + [self.offset + TWO_PI * k / max(self.count, 1)
                                           for k in range(max(self.count, 1))]
        theta = np.concatenate([theta, _wrap(np.asarray(extra, float))])
        h = 1.0 + self.clearance_change(theta)
        k = int(np.argmin(h))
        return float(h[k]), float(theta[k])

    def describe(self) -> dict:
        """The profile as outputs state it (angles in degrees, preload over c)."""
        out = {"bore": self.kind}
        if self.kind in ("shims", "lobes"):
            out.update(bore_count=self.count, bore_preload_ratio=self.preload,
                       bore_offset_deg=_deg(self.offset))
        if self.kind == "shims":
            out["bore_width_deg"] = _deg(self.width)
        if self.kind == "table":
            out.update(bore_angle_deg=[_deg(a) for a in self.table_angles],
                       bore_clearance_change=list(self.table_change))
        return out


@dataclass(frozen=True)
class Pad:
    """One top foil: its welded leading end from the load line [rad] and its arc [rad]; the
    journal drags the gas from the leading end towards the free end (leading + arc)."""

    leading_end: float
    arc: float


@dataclass(frozen=True)
class Zone:
    """A bump zone: from ``start`` to ``end`` [rad] (in the direction of rotation; it may
    wrap through 0), with compliance coefficient S = p_a α/c [-] (> 0) and the Coulomb
    friction coefficient of its bumps (None: the model's ``friction_coefficient``)."""

    start: float
    end: float
    compliance: float
    friction_coefficient: Optional[float] = None

    @property
    def span(self) -> float:
        """Angular extent [rad] in (0, 2π]."""
        s = float(_wrap(self.end - self.start))
        return TWO_PI if s < ANGLE_TOLERANCE else s


def check_pads(pads: tuple) -> tuple:
    """Pads sorted by leading end, checked: arcs > 0, no two overlapping, within 360°."""
    if len(pads) > MAX_FEATURES:
        raise ParameterError("pads", f"{len(pads)} pads", f"at most {MAX_FEATURES} top-foil "
                             "pads (segmented foil bearings have 2 to 8)")
    out = []
    for k, pad in enumerate(pads, 1):              # 1-based, as the rotor file's tables
        lead = degrees_in(f"pads[{k}].leading_end_deg", math.degrees(
            check_finite(f"pads[{k}].leading_end", pad.leading_end)), *ANGLE_RANGE_DEG)
        arc = check_finite(f"pads[{k}].arc_deg", math.degrees(pad.arc))
        if arc <= 0:
            raise ParameterError(f"pads[{k}].arc_deg", arc, "must be > 0 (negative or zero "
                                 "pad width)")
        if arc < MIN_WIDTH_DEG:
            raise ParameterError(f"pads[{k}].arc_deg", arc, f"must be >= {MIN_WIDTH_DEG:g} "
                                 "(one row of the finest grid: a narrower pad is on no grid)")
        if arc > 360.0 + 1e-9:
            raise ParameterError(f"pads[{k}].arc_deg", arc, "must be <= 360")
        out.append(Pad(float(_wrap(math.radians(lead))), math.radians(arc)))
    out.sort(key=lambda p: p.leading_end)
    for k, pad in enumerate(out):
        nxt = out[(k + 1) % len(out)]
        gap = float(_wrap(nxt.leading_end - pad.leading_end)) or (TWO_PI if len(out) == 1 else 0.0)
        if len(out) > 1 and gap < ANGLE_TOLERANCE:
            raise ParameterError("pads.leading_end_deg", math.degrees(pad.leading_end),
                                 "two pads share a leading end (overlapping pads)")
        if pad.arc > gap + ANGLE_TOLERANCE:
            raise ParameterError("pads", [round(math.degrees(p.leading_end), 6) for p in out],
                                 f"overlapping pads: the pad from "
                                 f"{math.degrees(pad.leading_end):.6g}° spans "
                                 f"{math.degrees(pad.arc):.6g}° but the next leading end is "
                                 f"{math.degrees(gap):.6g}° ahead")
    return tuple(out)


def check_zones(zones: tuple) -> tuple:
    """Zones sorted by start, checked: positive spans and S, no overlap, covering the bore."""
    if len(zones) > MAX_ZONES:
        raise ParameterError("zones", f"{len(zones)} zones", f"at most {MAX_ZONES} bump zones")
    out = []
    for k, z in enumerate(zones, 1):
        s = check_positive(f"zones[{k}].compliance", z.compliance)
        start, end = check_finite(f"zones[{k}].start_deg", z.start), check_finite(
            f"zones[{k}].end_deg", z.end)
        degrees_in(f"zones[{k}].start_deg", math.degrees(start), *ANGLE_RANGE_DEG)
        degrees_in(f"zones[{k}].end_deg", math.degrees(end), *ANGLE_RANGE_DEG)
        if end <= start:
            raise ParameterError(f"zones[{k}].end_deg", math.degrees(end), "must be greater "
                                 f"than start_deg = {math.degrees(start):.6g} (negative or "
                                 "zero zone width; a zone through 0° ends above 360°)")
        if end - start > TWO_PI + ANGLE_TOLERANCE:
            raise ParameterError(f"zones[{k}].end_deg", math.degrees(end), "a zone spans at "
                                 "most 360°")
        out.append(Zone(start, end, s, z.friction_coefficient))
    out.sort(key=lambda z: float(_wrap(z.start)))
    total = sum(z.end - z.start for z in out)
    for k, z in enumerate(out):
        nxt = out[(k + 1) % len(out)]
        ahead = float(_wrap(nxt.start - z.start))
        if len(out) > 1 and ahead + ANGLE_TOLERANCE < z.span:
            raise ParameterError("zones", f"{math.degrees(z.start):.6g}°–"
                                 f"{math.degrees(z.end):.6g}°", "overlapping zones: the next "
                                 f"zone starts at {math.degrees(nxt.start):.6g}°")
    if abs(total - TWO_PI) > 1e-7:
        raise ParameterError("zones", [(round(math.degrees(z.start), 6),
                                        round(math.degrees(z.end), 6)) for z in out],
                             f"must cover the bore exactly once (they span "
                             f"{math.degrees(total):.6g}° of 360°)")
    return tuple(out)


@dataclass(frozen=True)
class AsBuilt:
    """The bearing as built, non-dimensional: bore profile, pads and foundation zones.

    bore : :class:`BoreProfile` (round by default);  pads : :class:`Pad` tuple, or () for the
    single top foil of the model's film/seam options;  zones : :class:`Zone` tuple, or ()
    for a uniform foundation of the model's compliance.
    """

    bore: BoreProfile = field(default_factory=BoreProfile)
    pads: tuple = ()
    zones: tuple = ()

    def __post_init__(self) -> None:
        if not isinstance(self.bore, BoreProfile):
            raise ParameterError("bore", self.bore, "must be a BoreProfile")
        if self.pads:
            object.__setattr__(self, "pads", check_pads(tuple(self.pads)))
        if self.zones:
            object.__setattr__(self, "zones", check_zones(tuple(self.zones)))

    @property
    def uniform_foundation(self) -> bool:
        """True when every zone has the same S and friction (or there are none)."""
        return len({(z.compliance, z.friction_coefficient) for z in self.zones}) <= 1

    @property
    def single_pad(self) -> bool:
        """True without pads, or one pad spanning the whole bore (today's single seam)."""
        return not self.pads or (len(self.pads) == 1 and self.pads[0].arc >= TWO_PI - 1e-9)

    @property
    def housing_fixed(self) -> bool:
        """True when the film or foundation varies round the housing: the grid must then be
        fixed in the housing (no seam following the journal)."""
        return not (self.bore.is_round and self.uniform_foundation)

    @property
    def trivial(self) -> bool:
        """True when the bearing is today's: round bore, one pad, uniform foundation."""
        return not self.housing_fixed and self.single_pad

    def mean_compliance(self) -> float:
        """The arc-weighted mean S of the zones [-]."""
        return sum(z.compliance * (z.end - z.start) for z in self.zones) / TWO_PI

    def bore_rows(self, theta) -> np.ndarray:
        """B(θ) at the θ rows [-]."""
        return self.bore.clearance_change(theta)

    def compliance_rows(self, theta, compliance: float) -> np.ndarray:
        """S at the θ rows [-]: the zone containing each angle ([start, end)), or the model's
        uniform ``compliance`` without zones."""
        theta = _wrap(np.asarray(theta, float))
        if not self.zones or self.uniform_foundation:
            return np.full(theta.shape, float(compliance))
        out = np.full(theta.shape, np.nan)
        for z in self.zones:
            inside = _wrap(theta - z.start + ANGLE_TOLERANCE) < z.span
            out = np.where(inside & np.isnan(out), z.compliance, out)
        return out

    def friction_rows(self, theta, coefficient: float) -> np.ndarray:
        """μ_f at the θ rows [-]: the coefficient of the zone containing each angle, or the
        model's ``coefficient`` where the zone states none (and without zones)."""
        theta = _wrap(np.asarray(theta, float))
        out = np.full(theta.shape, np.nan)
        for z in self.zones:
            inside = _wrap(theta - z.start + ANGLE_TOLERANCE) < z.span
            mu = coefficient if z.friction_coefficient is None else z.friction_coefficient
            out = np.where(inside & np.isnan(out), mu, out)
        return np.where(np.isnan(out), float(coefficient), out)

    def fixed_rows(self, seam_angle: float, n_theta: int) -> tuple:
        """θ rows (0..n_theta, from the grid origin ``seam_angle`` [rad]) held at ambient
        pressure besides the seam rows 0 and n_theta: the other pads' leading ends and the
        gaps between pads.  Pad ends are taken at the nearest grid node."""
        if self.single_pad:
            return ()
        d = TWO_PI / n_theta
        fixed = set()
        for k, pad in enumerate(self.pads):
            nxt = self.pads[(k + 1) % len(self.pads)]
            start = int(round(float(_wrap(pad.leading_end - seam_angle + 1e-12)) / d))
            end = int(round((float(_wrap(pad.leading_end - seam_angle + 1e-12)) + pad.arc) / d))
            after = int(round(float(_wrap(nxt.leading_end - seam_angle + 1e-12)) / d))
            if after <= start:
                after += n_theta
            fixed.add(start % n_theta)
            fixed.update(i % n_theta for i in range(min(end, after), after + 1))
        return tuple(sorted(i for i in fixed if 0 < i < n_theta))

    def describe(self) -> dict:
        """Bore, pads and zones as every output states them (degrees)."""
        out = self.bore.describe()
        out["pads_leading_end_deg"] = [_deg(p.leading_end) for p in self.pads] or None
        out["pads_arc_deg"] = [_deg(p.arc) for p in self.pads] or None
        out["zones_deg"] = ([[_deg(z.start), _deg(z.end)] for z in self.zones]
                            or None)
        out["zones_compliance"] = [z.compliance for z in self.zones] or None
        if any(z.friction_coefficient is not None for z in self.zones):
            out["zones_friction_coefficient"] = [z.friction_coefficient for z in self.zones]
        return out


def check_grid_resolves(as_built, n_theta: int) -> None:
    """Refuse a grid of ``n_theta`` θ intervals too coarse for the bearing as built: fewer
    than :data:`MIN_ROWS_PER_FEATURE` rows per shim or lobe period or per pad, or a shim
    narrower than one row (the profile would be aliased into another bearing)."""
    if as_built is None:
        return
    bore = as_built.bore
    count = max(bore.count if bore.kind in ("shims", "lobes") and not bore.is_round else 0,
                len(as_built.pads) if not as_built.single_pad else 0)
    if count and n_theta < MIN_ROWS_PER_FEATURE * count:
        raise ParameterError("grid n_theta", n_theta, f"must be >= {MIN_ROWS_PER_FEATURE} × "
                             f"{count} = {MIN_ROWS_PER_FEATURE * count} to resolve {count} "
                             "shims, lobes or pads (the profile would be aliased)")
    if bore.kind == "shims" and not bore.is_round and bore.width < TWO_PI / n_theta:
        raise ParameterError("grid n_theta", n_theta, f"must give rows closer than the shim "
                             f"width {math.degrees(bore.width):.4g}° (rows every "
                             f"{360.0 / n_theta:.4g}°)")


def check_as_built(model) -> None:
    """Refuse an as-built description the model cannot represent (one line, before any
    solve): called by :class:`~gfbopt.inputs.model.BearingModel`."""
    ab = model.as_built
    if not isinstance(ab, AsBuilt):
        raise ParameterError("as_built", ab, "must be an AsBuilt (gfbopt.inputs.bore)")
    h0, where = ab.bore.smallest_film_at_centre()
    if h0 <= 0.0:
        raise ParameterError("bore.preload", ab.bore.preload if ab.bore.kind != "table" else
                             min(ab.bore.table_change), f"closes the film with the journal "
                             f"concentric: clearance c(1 + B) = {h0:.4g} c at "
                             f"{math.degrees(where):.4g}° (the preload must be < the clearance)")
    if ab.zones:
        if model.is_rigid:
            raise ParameterError("zones", len(ab.zones), "need a bump foundation (foil "
                                 "'simple' or 'beam' with S > 0)")
        for k, z in enumerate(ab.zones, 1):
            if z.friction_coefficient is not None:
                mu = check_finite(f"zones[{k}].friction_coefficient", z.friction_coefficient)
                if not 0.0 <= mu < FRICTION_COEFFICIENT_BELOW:
                    raise ParameterError(f"zones[{k}].friction_coefficient", mu, "must lie in "
                                         f"[0, {FRICTION_COEFFICIENT_BELOW:g}) ({WHY_FRICTION})")
        mean = ab.mean_compliance()
        if not math.isclose(model.compliance, mean, rel_tol=1e-12):
            raise ParameterError("compliance", model.compliance, "with foundation zones S is "
                                 f"their arc-weighted mean, {mean!r}; change the zones instead")
        if model.foil == "beam" and not ab.uniform_foundation:
            raise ParameterError("zones", len(ab.zones), "a varying foundation is modelled "
                                 "for the simple foil (both deflection laws), not under the "
                                 "beam top foil")
    if ab.housing_fixed and model.film == "seam" and model.seam_angle_rad is None:
        raise ParameterError("seam_angle", "max_film", "a bore profile or bump zones are "
                             "fixed in the housing, but the seam on the maximum-film line "
                             "moves with the journal: state a fixed seam angle")
    if ab.pads and model.film != "seam":
        raise ParameterError("pads", len(ab.pads), "top-foil pads end in seams at ambient "
                             "pressure: they need film = 'seam' (a periodic film has none)")
    if ab.pads and not ab.single_pad:
        if model.seam_angle_rad is None:
            raise ParameterError("pads", len(ab.pads), "several pads need film = 'seam' with "
                                 "a fixed seam angle (one pad's leading end)")
        if model.foil == "beam":
            raise ParameterError("pads", len(ab.pads), "several pads are modelled for the "
                                 "simple foil; the beam top foil is one pad")
    if ab.pads and model.film == "seam" and model.seam_angle_rad is not None:
        leads = [p.leading_end for p in ab.pads]
        if min(abs(float(_wrap(model.seam_angle_rad - a + math.pi)) - math.pi)
               for a in leads) > 1e-9:
            raise ParameterError("seam_angle_deg", math.degrees(model.seam_angle_rad), "must be "
                                 "one pad's leading end ("
                                 + ", ".join(f"{math.degrees(a):.6g}" for a in leads) + "°)")
