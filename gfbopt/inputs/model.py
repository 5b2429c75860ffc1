"""The non-dimensional bearing model: groups (Λ, S, C, L/D) and the formulation options."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Optional

from ..errors import ParameterError
from .bore import AsBuilt, check_as_built
from .checks import (FRICTION_COEFFICIENT_BELOW, WHY_FRICTION, check_choice, check_flag,
                     check_loss_factor, check_nonnegative, check_positive,
                     check_seam_angle_deg, refuse_radian_seam_angle)

FOIL_MODELS = ("rigid", "simple", "beam")
FILM_MODELS = ("periodic", "seam")
DEFLECTION_LAWS = ("mean", "local")
SUBAMBIENT_TREATMENTS = ("full", "gumbel")
#: largest top-foil coefficient C [-] accepted (BearingModel)
MAX_TOP_FOIL_COEFFICIENT = 1e4
#: largest bearing number Λ [-] accepted: real gas bearings run below Λ ≈ 100, and the
#: solver's scaling is checked up to Λ = 40 in the test suite
MAX_BEARING_NUMBER = 1e4
#: largest compliance S [-] accepted: a foundation 1000 times softer than the thesis's S = 1
MAX_COMPLIANCE = 1e3
#: largest stuck friction-element stiffness over the bump's, k_f/k_b [-] accepted
MAX_FRICTION_STIFFNESS_RATIO = 1e3
#: foil models whose bump foundation carries the friction element (the rigid surface has no
#: bumps; the beam's foundation has no per-unit factor yet, see physics/friction.py)
FRICTION_FOILS = ("simple",)
#: exponents n of the hardening bump k0/(1 − δ/δ_lim)^n accepted [-]: 0 (off) or in
#: [MIN, MAX] (n < 1 flattens the bump at a finite load; the file schema states the same)
MIN_HARDENING_EXPONENT = 1.0
MAX_HARDENING_EXPONENT = 10.0


#: the unit-less radian names of gfbopt <= 0.2 and what replaced them (degrees at the edge)
RADIAN_NAMES = ("attitude_angle", "seam_angle", "min_film_angle", "min_film_angle_from_seam")


def renamed_radian_attribute(owner: str, name: str) -> AttributeError:
    """The AttributeError for ``name`` on ``owner``: for an old unit-less radian name
    (:data:`RADIAN_NAMES`) it names the degree property and the radian field that replaced
    it, so ``sol.attitude_angle_rad`` can never be read as degrees by mistake."""
    if name in RADIAN_NAMES:
        return AttributeError(f"{owner}.{name} (radians in gfbopt <= 0.2) was renamed: angles "
                              f"are degrees at every public edge, {name}_deg [deg]; the "
                              f"numerics' radians are {name}_rad "
                              f"({name}_deg = math.degrees({name}_rad))")
    return AttributeError(f"{owner!r} object has no attribute {name!r}")


def radian_keyword_migration(name: str, value) -> str:
    """The rule shown for an old unit-less radian keyword ``name`` (e.g. ``attitude_angle`` of
    :func:`gfbopt.static.solve_static`): the degree keyword and the conversion.  Kept until
    gfbopt 0.4.0 (CHANGELOG, Deprecated); from then the keyword is refused as unknown."""
    text = (f"is no longer accepted: angles are given in degrees at every public edge, as "
            f"{name}_deg (from the load line in the direction of rotation)")
    if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
        text += (f"; if {value!r} was meant in radians (gfbopt <= 0.2), write "
                 f"{name}_deg={math.degrees(value):.6g}")
    return text


def film_convention(film: str, seam_angle_deg: Optional[float], foil: str = "simple") -> str:
    """One line naming the film convention (docs/PHYSICS.md §4), for every output.

    film : 'periodic' or 'seam'; seam_angle_deg : the welded end from the load line [deg], or
    None for the seam on the maximum-film line; foil : the foil model.
    """
    if film == "periodic":
        text = "periodic film: full 360° film, no seam (plain gas bearing idealisation)"
        if foil == "beam":
            text += ("; the beam's welded end on the maximum-film line" if seam_angle_deg is None
                     else f"; the beam's welded end {seam_angle_deg:.4g}° from the "
                     "load line")
        return text
    if seam_angle_deg is None:
        return ("seam on the maximum-film line (thesis convention: the seam follows the "
                "attitude angle in the static solution and is frozen for the dynamics)")
    return (f"seam at a fixed housing angle: top-foil welded end {seam_angle_deg:.4g}°"
            " from the load line in the direction of rotation")


@refuse_radian_seam_angle
@dataclass(frozen=True)
class BearingModel:
    """The non-dimensional bearing model solved by gfbopt.

    Attributes
    ----------
    bearing_number : Λ = 6 μ ω R²/(p_a c²) [-], > 0
    compliance : S = p_a α / c [-], ≥ 0 (0 = rigid plain gas bearing)
    length_ratio : L/D [-], > 0
    foil : 'rigid', 'simple' (W = S (P̄ − 1)) or 'beam' (1D FE top foil on the bumps)
    top_foil_coefficient : C [-], ≥ 0, used by the beam model only
    film : 'periodic' (no seam) or 'seam' (P = 1 at the top-foil ends)
    seam_angle_deg : angle of the welded (fixed) end of the top foil measured from the load
        line in the direction of rotation [deg], in [0, 360); ``None`` (or ``'max_film'``)
        puts the seam at the maximum-film line (the thesis's convention: θ measured from the
        line of centres, P = 1 at θ = 0, 2π).  For a periodic film it only places the fixed
        end of the beam foil.  Degrees, as on the command line and in files; the old radian
        keyword ``seam_angle`` is refused with the conversion (the solvers read the angle in
        radians from the :attr:`seam_angle_rad` property).
    compression_only : if True the bumps cannot pull the foil towards the journal (W ≥ 0
        for the simple model; the bump reaction acts only where W > 0 for the beam).
    deflection_law : 'mean' — the foil deflects with the axially averaged pressure,
        W = S (P̄ − 1) (thesis, Heshmat's strip model); 'local' — with the local pressure,
        W = S (P − 1) (simple model only).
    subambient : 'full' — the whole film pressure acts on the journal; 'gumbel' — gauge
        pressure below ambient is dropped from the force integral,
        F = −∬ max(P − 1, 0)(cos θ, sin θ) dθ dZ (the convention that reproduces the Λ = 1
        rows of thesis Table 3.2; docs/literature_table_3_2.md).  The pressure field itself
        is the full-film solution in both cases.
    loss_factor : structural loss factor η [-] of the bump foundation, 0 ≤ η ≤ 1 (default 0:
        no structural damping).  Hysteretic damping: for motion at whirl ratio γ the
        foundation stiffness is k (1 + iη sign γ), i.e. the compliance S/(1 + iη sign γ)
        (docs/PHYSICS.md §7).  It acts on the dynamics only (the static equilibrium does not
        depend on it) and needs a foundation: η > 0 is refused with foil='rigid' or S = 0.
        The linear analysis supports it (:mod:`gfbopt.linear`); an engine that does not is
        refused a damped model by :func:`gfbopt.physics.foil_laws.foil_law`.
    friction_coefficient : μ_f [-], 0 ≤ μ_f < 1, of the Coulomb slider beside each bump
        (default 0: no friction, today's elastic foundation exactly).  Each foil unit (θ row,
        or node for the local law) has a spring–slider (Jenkins) element in parallel with its
        bump (:mod:`gfbopt.physics.friction`): spring k_f = κ k_b, slip force per unit area
        μ_f (p − p_a)⁺ from the local gauge pressure, slip displacement x_s/c = μ_f q⁺ S/κ.
        Statics: friction does not hold a static deflection (the slider is relaxed at the
        equilibrium), so the equilibrium does not depend on it.  Linear analysis: stuck for
        small orbits (foundation stiffness k_b (1 + κ) where q > 0), the describing function
        at a stated orbit amplitude (:mod:`gfbopt.linear.friction_onset`).  Needs a bump
        foundation of foil 'simple' (refused with 'rigid', S = 0 and 'beam').
    friction_stiffness_ratio : κ = k_f/k_b [-], 0 < κ ≤ 1000 (default 1): the friction
        element's spring over the bump's stiffness (its stuck stiffness); used only when
        μ_f > 0.
    hardening_exponent : n [-] of the hardening bump k = k0/(1 − δ/δ_lim)^n
        (:mod:`gfbopt.physics.hardening`): 0 (default) is off, today's linear bump; else
        1 ≤ n ≤ 10 (n ≥ 1: the bump is flat only under an infinite load, the hard limit).
        Foil 'simple' with the axial-mean law only (the 'hardened' foil law).  Statics use the
        hardened law, the linear analysis its tangent at the static deflection.
    hardening_limit : W_lim = δ_lim/c [-], the deflection at which the bump is flat, in
        radial clearances (δ_lim ≤ the bump height h_b, checked where h_b is known: the
        bearing file's [model]); needed when n > 0.  Outputs state it as
        ``hardening_limit_ratio`` (:meth:`options`): ``hardening_limit`` is δ_lim in metres
        in the files and the glossary.
    as_built : the bearing as built (:class:`gfbopt.inputs.bore.AsBuilt`: bore profile,
        pads, bump zones), or None for a round bore, one top foil and a uniform foundation.
    """

    bearing_number: float
    compliance: float = 0.0
    length_ratio: float = 1.0
    foil: str = "simple"
    top_foil_coefficient: float = 0.0
    film: str = "periodic"
    seam_angle_deg: Optional[float] = None
    compression_only: bool = False
    deflection_law: str = "mean"
    subambient: str = "full"
    loss_factor: float = 0.0
    as_built: Optional[AsBuilt] = None
    friction_coefficient: float = 0.0
    friction_stiffness_ratio: float = 1.0
    hardening_exponent: float = 0.0
    hardening_limit: float = math.inf

    def __post_init__(self) -> None:
        object.__setattr__(self, "bearing_number",
                           check_positive("bearing_number", self.bearing_number))
        object.__setattr__(self, "compliance", check_nonnegative("compliance", self.compliance))
        for key, top, why in (("bearing_number", MAX_BEARING_NUMBER, "real gas bearings run "
                               "below Λ ≈ 100"),
                              ("compliance", MAX_COMPLIANCE, "a foundation 1000 times softer "
                               "than the thesis's S = 1")):
            if getattr(self, key) > top:
                raise ParameterError(key, getattr(self, key), f"must be <= {top:g} ({why})")
        object.__setattr__(self, "length_ratio", check_positive("length_ratio", self.length_ratio))
        object.__setattr__(self, "top_foil_coefficient",
                           check_nonnegative("top_foil_coefficient", self.top_foil_coefficient))
        if self.top_foil_coefficient > MAX_TOP_FOIL_COEFFICIENT:
            raise ParameterError("top_foil_coefficient", self.top_foil_coefficient,
                                 f"must be <= {MAX_TOP_FOIL_COEFFICIENT:g} (10^4 times the "
                                 "thesis's C = 1; beyond it the beam's stiffness matrix is "
                                 "singular in double precision)")
        check_choice("foil", self.foil, FOIL_MODELS)
        check_choice("film", self.film, FILM_MODELS)
        check_choice("deflection_law", self.deflection_law, DEFLECTION_LAWS)
        check_choice("subambient", self.subambient, SUBAMBIENT_TREATMENTS)
        if self.deflection_law == "local" and self.foil == "beam":
            raise ParameterError("deflection_law", self.deflection_law,
                                 "'local' applies to the simple foil model only (the beam is "
                                 "loaded by the axially averaged pressure)")
        object.__setattr__(self, "compression_only",
                           check_flag("compression_only", self.compression_only))
        if self.foil == "rigid" and self.compliance != 0.0:
            raise ParameterError("compliance", self.compliance,
                                 "must be 0 with foil='rigid' (a rigid bearing has no bump "
                                 "foundation); use foil='simple' or 'beam' for S > 0")
        if self.seam_angle_deg is not None:
            angle = check_seam_angle_deg("seam_angle_deg", self.seam_angle_deg)
            object.__setattr__(self, "seam_angle_deg", None if angle == "max_film" else angle)
        if self.length_ratio > 10.0:
            raise ParameterError("length_ratio", self.length_ratio, "must be <= 10")
        object.__setattr__(self, "loss_factor", check_loss_factor(self.loss_factor))
        if self.loss_factor > 0.0 and self.is_rigid:
            raise ParameterError("loss_factor", self.loss_factor, (
                "must be 0 with foil='rigid' (a rigid bearing has no bump foundation to damp)"
                if self.foil == "rigid" else
                "must be 0 when the compliance S = 0 (the foundation does not deflect, so "
                "there is nothing for its structural damping to act on)"))
        self._check_friction()
        self._check_hardening()
        if self.as_built is not None:
            check_as_built(self)

    def _check_friction(self) -> None:
        mu = check_nonnegative("friction_coefficient", self.friction_coefficient)
        if mu >= FRICTION_COEFFICIENT_BELOW:
            raise ParameterError("friction_coefficient", self.friction_coefficient,
                                 f"must be < {FRICTION_COEFFICIENT_BELOW:g} ({WHY_FRICTION})")
        kappa = check_positive("friction_stiffness_ratio", self.friction_stiffness_ratio)
        if kappa > MAX_FRICTION_STIFFNESS_RATIO:
            raise ParameterError("friction_stiffness_ratio", self.friction_stiffness_ratio,
                                 f"must be <= {MAX_FRICTION_STIFFNESS_RATIO:g} (k_f/k_b)")
        object.__setattr__(self, "friction_coefficient", mu)
        object.__setattr__(self, "friction_stiffness_ratio", kappa)
        if self.has_friction and not mu > 0.0:
            mu = max(z.friction_coefficient or 0.0 for z in self.as_built.zones)
        if mu > 0.0 and self.is_rigid:
            raise ParameterError("friction_coefficient", self.friction_coefficient, (
                "must be 0 with foil='rigid' (a rigid bearing has no bumps to rub)"
                if self.foil == "rigid" else "must be 0 when the compliance S = 0 (the bumps "
                "do not move, so nothing slides)"))
        if mu > 0.0 and self.foil not in FRICTION_FOILS:
            raise ParameterError("friction_coefficient", self.friction_coefficient,
                                 f"is not carried by the {self.foil} foil model (its "
                                 "foundation has no per-unit friction element yet); use "
                                 f"foil {', '.join(repr(f) for f in FRICTION_FOILS)}")

    def _check_hardening(self) -> None:
        n = check_nonnegative("hardening_exponent", self.hardening_exponent)
        object.__setattr__(self, "hardening_exponent", n)
        if n == 0.0:
            return
        if not MIN_HARDENING_EXPONENT <= n <= MAX_HARDENING_EXPONENT:
            raise ParameterError("hardening_exponent", self.hardening_exponent,
                                 f"must be 0 (off) or in [{MIN_HARDENING_EXPONENT:g}, "
                                 f"{MAX_HARDENING_EXPONENT:g}] (n < 1 flattens the bump at a "
                                 "finite load)")
        object.__setattr__(self, "hardening_limit",
                           check_positive("hardening_limit", self.hardening_limit))
        if self.is_rigid or self.foil != "simple" or self.deflection_law != "mean":
            raise ParameterError("hardening_exponent", self.hardening_exponent,
                                 "the hardening bump needs a bump foundation of foil 'simple' "
                                 "with deflection_law 'mean' (not rigid, S = 0, beam or the "
                                 "local law)")

    @property
    def has_friction(self) -> bool:
        """True when the bumps carry Coulomb friction (μ_f > 0, here or in a bump zone)."""
        zones = () if self.as_built is None else self.as_built.zones
        return self.friction_coefficient > 0.0 or any(
            (getattr(z, "friction_coefficient", None) or 0.0) > 0.0 for z in zones)

    @property
    def seam_angle_rad(self) -> Optional[float]:
        """The welded end from the load line in radians (the solvers' internal unit), or None
        for the seam on the maximum-film line.  Read-only: give ``seam_angle_deg``."""
        return None if self.seam_angle_deg is None else math.radians(self.seam_angle_deg)

    def __getattr__(self, name: str):
        raise renamed_radian_attribute(type(self).__name__, name)

    @property
    def is_rigid(self) -> bool:
        """True when the film sees no foil motion (foil='rigid' or S = 0)."""
        return self.foil == "rigid" or self.compliance == 0.0

    @property
    def foil_law(self) -> str:
        """Name of the foil law in :mod:`gfbopt.physics.foil_laws` this model uses:
        'rigid' (also any S = 0), 'simple' (axial-mean law), 'local', 'beam' or 'hardened'
        (the axial-mean law with hardening bumps)."""
        if self.is_rigid:
            return "rigid"
        if self.foil == "beam":
            return "beam"
        if self.deflection_law == "local":
            return "local"
        return "hardened" if self.hardening_exponent > 0.0 else "simple"

    def options(self) -> dict:
        """The formulation options, as every output states them (angles in degrees)."""
        no_seam = self.film == "periodic" and self.foil != "beam"   # nothing to place
        return {"foil": self.foil, "foil_law": self.foil_law, "film": self.film,
                "seam_angle_deg": (None if no_seam else "max_film" if self.seam_angle_deg is None
                                   else self.seam_angle_deg),
                "deflection_law": self.deflection_law,
                "compression_only": self.compression_only, "subambient": self.subambient,
                "loss_factor": self.loss_factor,
                "film_convention": film_convention(self.film, self.seam_angle_deg, self.foil),
                **({} if not self.has_friction else {
                    "friction_coefficient": self.friction_coefficient,
                    "friction_stiffness_ratio": self.friction_stiffness_ratio}),
                **({} if self.hardening_exponent == 0.0 else {
                    "hardening_exponent": self.hardening_exponent,
                    "hardening_limit_ratio": self.hardening_limit}),
                **({} if self.as_built is None else self.as_built.describe())}

    def groups(self) -> dict:
        """The non-dimensional groups Λ, S, C, L/D of this model."""
        return {"bearing_number": self.bearing_number, "compliance": self.compliance,
                "top_foil_coefficient": self.top_foil_coefficient,
                "length_ratio": self.length_ratio}

    def replace(self, **changes) -> "BearingModel":
        """A copy with ``changes`` applied (validated again)."""
        return replace(self, **changes)
