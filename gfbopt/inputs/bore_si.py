"""The bearing as built in SI, as a user writes it: the ``[bore]``, ``[[pads]]`` and
``[[zones]]`` tables of a bearing file (angles in degrees, lengths in metres), and their
non-dimensional :class:`~gfbopt.inputs.bore.AsBuilt` (conventions in :mod:`.bore`)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Optional

from ..errors import ParameterError
from .bore import BORE_KINDS, START_RANGE_DEG, AsBuilt, BoreProfile, Pad, Zone, degrees_in
from .checks import check_finite


# ------------------------------------------------------------------ SI descriptions
@dataclass(frozen=True)
class BoreSpec:
    """The bore in SI (a ``[bore]`` table): kind, N, preload depth [m] *or* preload ratio
    [-], shim width and offset [deg], or a table of angles [deg] and clearance changes [m]."""

    kind: str = "round"
    count: int = 0
    preload_depth: Optional[float] = None
    preload_ratio: Optional[float] = None
    width_deg: float = 0.0
    offset_deg: float = 0.0
    angle_deg: tuple = ()
    clearance_change: tuple = ()

    def profile(self, clearance: Optional[float]) -> BoreProfile:
        """The non-dimensional :class:`BoreProfile` for radial clearance c [m] (None: a
        non-dimensional model, which takes a preload ratio and no depths)."""
        if clearance is None and (self.preload_depth is not None or self.kind == "table"):
            raise ParameterError("bore.preload_depth" if self.kind != "table" else
                                 "bore.clearance_change", self.preload_depth,
                                 "needs the bearing's clearance: give preload_ratio for a "
                                 "non-dimensional model (gfbopt.inputs.bore.BoreProfile for "
                                 "a table over c)")
        if self.kind in ("shims", "lobes"):
            if (self.preload_depth is None) == (self.preload_ratio is None):
                raise ParameterError("bore.preload_depth/preload_ratio",
                                     (self.preload_depth, self.preload_ratio),
                                     "give exactly one of them")
            if self.preload_depth is not None:
                d = check_finite("bore.preload_depth", self.preload_depth)
                if d >= clearance:
                    raise ParameterError("bore.preload_depth", d, "closes the film with the "
                                         f"journal concentric: preload {d * 1e6:.4g} µm >= "
                                         f"clearance {clearance * 1e6:.4g} µm")
                ratio = d / clearance
            else:
                ratio = check_finite("bore.preload_ratio", self.preload_ratio)
            return BoreProfile(self.kind, self.count, ratio,
                               math.radians(degrees_in("bore.width_deg", self.width_deg,
                                                       0.0, 360.0, low_open=True))
                               if self.kind == "shims" else 0.0,
                               math.radians(degrees_in("bore.offset_deg", self.offset_deg,
                                                       *START_RANGE_DEG)))
        if self.kind == "table":
            angles = tuple(math.radians(degrees_in("bore.angle_deg", a, 0.0, 360.0))
                           for a in self.angle_deg)
            change = tuple(check_finite("bore.clearance_change", v) / clearance
                           for v in self.clearance_change)
            return BoreProfile("table", table_angles=angles, table_change=change)
        return BoreProfile(self.kind)

    def describe(self) -> dict:
        out = {"bore": self.kind}
        if self.kind in ("shims", "lobes"):
            out.update(bore_count=self.count, bore_preload_depth_m=self.preload_depth,
                       bore_preload_ratio=self.preload_ratio, bore_offset_deg=self.offset_deg)
        if self.kind == "shims":
            out["bore_width_deg"] = self.width_deg
        if self.kind == "table":
            out.update(bore_angle_deg=list(self.angle_deg),
                       bore_clearance_change_m=list(self.clearance_change))
        return out


@dataclass(frozen=True)
class PadSpec:
    """One top foil in SI: leading (welded) end [deg from the load line] and arc [deg]."""

    leading_end_deg: float
    arc_deg: float


@dataclass(frozen=True)
class ZoneSpec:
    """A bump zone in SI: from ``start_deg`` to ``end_deg`` [deg] (end > start; a zone
    through 0° ends above 360), with its bump pitch, half length and thickness [m] (None: the
    bearing's own)."""

    start_deg: float
    end_deg: float
    bump_pitch: Optional[float] = None
    bump_half_length: Optional[float] = None
    bump_thickness: Optional[float] = None
    friction_coefficient: Optional[float] = None


@dataclass(frozen=True)
class BearingBuild:
    """The as-built description of a bearing in SI (``BearingGeometry.build``)."""

    bore: BoreSpec = field(default_factory=BoreSpec)
    pads: tuple = ()
    zones: tuple = ()

    def nondimensional(self, geometry) -> AsBuilt:
        """The :class:`AsBuilt` of this build on ``geometry`` (a BearingGeometry): preload over
        c, and each zone's S from its bump geometry through :func:`gfbopt.physics.bump.
        bump_compliance` (the one bump formula)."""
        from ..physics.bump import bump_compliance, compliance_coefficient

        zones = []
        for k, z in enumerate(self.zones, 1):      # 1-based, as the rotor file's
            geo = {key: getattr(z, key) for key in ("bump_pitch", "bump_half_length",
                                                    "bump_thickness")
                   if getattr(z, key) is not None}
            try:        # one set of rules: the zone's bumps are checked as [bearing]'s are
                zoned = replace(geometry, build=None, **geo)
            except ParameterError as exc:
                raise ParameterError(f"zones[{k}].{exc.name}", exc.value, exc.rule) from None
            alpha = bump_compliance(zoned.bump_pitch, zoned.bump_half_length,
                                    zoned.bump_thickness, geometry.bump_youngs_modulus,
                                    geometry.poisson_ratio)
            s = compliance_coefficient(alpha, geometry.ambient_pressure,
                                       geometry.radial_clearance)
            zones.append(Zone(math.radians(check_finite(f"zones[{k}].start_deg", z.start_deg)),
                              math.radians(check_finite(f"zones[{k}].end_deg", z.end_deg)), s,
                              z.friction_coefficient))
        pads = tuple(Pad(math.radians(check_finite(f"pads[{k}].leading_end_deg",
                                                   p.leading_end_deg)),
                         math.radians(check_finite(f"pads[{k}].arc_deg", p.arc_deg)))
                     for k, p in enumerate(self.pads, 1))
        return AsBuilt(self.bore.profile(geometry.radial_clearance), pads, tuple(zones))

    def describe(self) -> dict:
        """Bore, pads and zones in SI as outputs state them."""
        out = self.bore.describe()
        out["pads_leading_end_deg"] = [p.leading_end_deg for p in self.pads] or None
        out["pads_arc_deg"] = [p.arc_deg for p in self.pads] or None
        out["zones"] = [{k: v for k, v in vars(z).items() if v is not None}
                        for z in self.zones] or None
        return out


_BORE_KEYS = ("kind", "count", "preload_depth", "preload_ratio", "width_deg", "offset_deg",
              "angle_deg", "clearance_change")
_PAD_KEYS = ("leading_end_deg", "arc_deg")
_ZONE_KEYS = ("start_deg", "end_deg", "bump_pitch", "bump_half_length", "bump_thickness",
              "friction_coefficient")


def _table(table, keys, where, required=()) -> dict:
    if not isinstance(table, dict):
        raise ParameterError(where, table, "must be a table")
    unknown = sorted(set(table) - set(keys))
    if unknown:
        raise ParameterError(f"{where}.{unknown[0]}", table[unknown[0]],
                             f"is not a key of this table (known: {', '.join(keys)})")
    for key in required:
        if key not in table:
            raise ParameterError(f"{where}.{key}", None, "is required but missing")
    for key, value in table.items():
        if key == "kind":
            continue
        items = value if isinstance(value, list) else [value]
        if any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in items):
            raise ParameterError(f"{where}.{key}", value, "must be a number (SI; angles in "
                                 "degrees)")
    return table


def build_from_tables(data: dict, where: str = "bearing file") -> Optional[BearingBuild]:
    """The :class:`BearingBuild` of a bearing file's ``[bore]``, ``[[pads]]`` and ``[[zones]]``
    tables, or None when it has none (today's round, single-pad, uniform bearing)::

        [bore]
        kind = "shims"          # round | shims | lobes | table
        count = 3
        preload_depth = 5e-6    # m (or preload_ratio = 0.25)
        width_deg = 60.0
        offset_deg = 0.0        # centre of the first shim from the load line

        [[pads]]                # one table per top foil
        leading_end_deg = 180.0 # welded end from the load line
        arc_deg = 120.0

        [[zones]]               # bump zones, covering 360° once
        start_deg = 0.0
        end_deg = 180.0
        bump_thickness = 80e-6  # m; pitch and half length default to [bearing]'s
    """
    if not any(k in data for k in ("bore", "pads", "zones")):
        return None
    bore = BoreSpec()
    if "bore" in data:
        t = _table(data["bore"], _BORE_KEYS, f"{where}: bore", required=("kind",))
        if t["kind"] not in BORE_KINDS:
            raise ParameterError(f"{where}: bore.kind", t["kind"],
                                 f"must be one of {', '.join(BORE_KINDS)}")
        count = t.get("count", 0)
        if t["kind"] in ("shims", "lobes") and (not isinstance(count, int) or count < 1):
            raise ParameterError(f"{where}: bore.count", count, "must be a whole number >= 1")
        if t["kind"] == "shims" and "width_deg" not in t:
            raise ParameterError(f"{where}: bore.width_deg", None, "is required for shims")
        bore = BoreSpec(t["kind"], count, t.get("preload_depth"), t.get("preload_ratio"),
                        t.get("width_deg", 0.0), t.get("offset_deg", 0.0),
                        tuple(t.get("angle_deg", ())), tuple(t.get("clearance_change", ())))
    lists = {}
    for name, keys, required in (("pads", _PAD_KEYS, _PAD_KEYS),
                                 ("zones", _ZONE_KEYS, ("start_deg", "end_deg"))):
        items = data.get(name, [])
        if not isinstance(items, list):
            raise ParameterError(f"{where}: {name}", items, f"must be an array of tables "
                                 f"([[{name}]])")
        lists[name] = [_table(t, keys, f"{where}: {name}[{k}]", required)
                       for k, t in enumerate(items, 1)]
    pads = tuple(PadSpec(**t) for t in lists["pads"])
    zones = tuple(ZoneSpec(**t) for t in lists["zones"])
    return BearingBuild(bore, pads, zones)


def as_built(bore: Optional[BoreSpec] = None, pads: tuple = (), zones: tuple = ()) -> AsBuilt:
    """A non-dimensional :class:`~gfbopt.inputs.bore.AsBuilt` from degrees, for
    ``BearingModel(as_built=...)``: ``bore`` a :class:`BoreSpec` with a preload ratio, ``pads``
    :class:`PadSpec` (degrees), ``zones`` (start_deg, end_deg, compliance S) triples."""
    profile = BoreProfile() if bore is None else bore.profile(None)
    pad_list = tuple(Pad(math.radians(check_finite(f"pads[{k}].leading_end_deg",
                                                   p.leading_end_deg)),
                         math.radians(check_finite(f"pads[{k}].arc_deg", p.arc_deg)))
                     for k, p in enumerate(pads, 1))
    zone_list = tuple(Zone(math.radians(check_finite(f"zones[{k}].start_deg", a)),
                           math.radians(check_finite(f"zones[{k}].end_deg", b)), s)
                      for k, (a, b, s) in enumerate(zones, 1))
    return AsBuilt(profile, pad_list, zone_list)
