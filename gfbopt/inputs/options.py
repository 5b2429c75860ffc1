"""Formulation options a user states — film convention, foil law, structural damping — and
the defaults that fill what is not stated.

A bearing file may state them in an optional ``[model]`` table (:mod:`.bearing_file`); the
command line and the Python API may override them.  What is not stated anywhere is filled by
:func:`resolve_model_options`, whose docstring says which default applies and why.

The three film conventions (``docs/PHYSICS.md`` §4):

=====================================  ==========================================  ===========
convention                             represents                                  options
=====================================  ==========================================  ===========
periodic film                          a full 360° film with no seam: the plain    film =
                                       self-acting gas bearing, or a foil bearing  "periodic"
                                       idealised as seamless
seam at a fixed housing angle          a real top foil, welded at one end and      film = "seam",
                                       free at the other, the ambient gap between  seam_angle_deg
                                       them at a fixed angle from the load: the    = 0 … 360
                                       usual hardware
seam on the maximum-film line          the thesis's convention (Mohan 2010): the   film = "seam",
                                       seam follows the attitude angle in the      seam_angle_deg
                                       static solution (frozen for the dynamics)   = "max_film"
=====================================  ==========================================  ===========
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Optional, Union

from ..errors import ParameterError
from .checks import (check_choice, check_loss_factor, check_nonnegative, check_positive,
                     check_seam_angle_deg, refuse_radian_seam_angle)
from .model import DEFLECTION_LAWS, FILM_MODELS, FOIL_MODELS, film_convention
from ..physics.hardening import check_hardening_limit

#: ``seam_angle_deg`` value of the thesis's convention: the seam on the maximum-film line
MAX_FILM = "max_film"
#: default welded-end angle of a bump-foil bearing's top foil, from the load line [deg]
DEFAULT_SEAM_ANGLE_DEG = 180.0

#: the options of a ``[model]`` table, in the order outputs state them
OPTION_NAMES = ("film", "seam_angle_deg", "foil", "deflection_law", "loss_factor",
                "friction_coefficient", "friction_stiffness_ratio", "bump_height",
                "hardening_limit", "hardening_exponent")
#: the bump options (friction and hardening): stated in outputs only when stated
BUMP_OPTION_NAMES = OPTION_NAMES[5:]


@refuse_radian_seam_angle
@dataclass(frozen=True)
class ModelOptions:
    """Formulation options of a bearing model; each is None when not stated.

    Attributes
    ----------
    film : 'periodic' (no seam) or 'seam' (the top foil's ends, open to ambient)
    seam_angle_deg : welded end of the top foil, measured from the load line in the
        direction of rotation [deg] in [0, 360); or ``'max_film'`` (:data:`MAX_FILM`), the
        thesis's seam on the maximum-film line.  (Note: ``None`` here means *not stated*,
        whereas in :class:`~gfbopt.inputs.model.BearingModel` ``seam_angle_deg=None`` is the
        max-film seam.)  The old radian keyword ``seam_angle`` is refused.
    foil : 'rigid', 'simple' or 'beam'
    deflection_law : 'mean' (W = S(P̄ − 1)) or 'local' (W = S(P − 1))
    loss_factor : structural loss factor η of the bump foundation [-], 0 ≤ η ≤ 1
    friction_coefficient : μ_f [-] of the Coulomb slider beside each bump (0: none), and
    friction_stiffness_ratio : κ = k_f/k_b [-] of its spring
        (:class:`~gfbopt.inputs.model.BearingModel`, :mod:`gfbopt.physics.friction`)
    bump_height : h_b [m]; hardening_limit : δ_lim [m] (≤ h_b; default h_b);
    hardening_exponent : n [-] (0: off) of the hardening bump k0/(1 − δ/δ_lim)^n
        (:mod:`gfbopt.physics.hardening`).  Checked here; carried into every model built
        from these options (:meth:`bump_kwargs`: statics, linear analysis, transients).
    """

    film: Optional[str] = None
    seam_angle_deg: Union[float, str, None] = None
    foil: Optional[str] = None
    deflection_law: Optional[str] = None
    loss_factor: Optional[float] = None
    friction_coefficient: Optional[float] = None
    friction_stiffness_ratio: Optional[float] = None
    bump_height: Optional[float] = None
    hardening_limit: Optional[float] = None
    hardening_exponent: Optional[float] = None

    def __post_init__(self) -> None:
        if self.film is not None:
            check_choice("film", self.film, FILM_MODELS)
        if self.foil is not None:
            check_choice("foil", self.foil, FOIL_MODELS)
        if self.deflection_law is not None:
            check_choice("deflection_law", self.deflection_law, DEFLECTION_LAWS)
        if self.seam_angle_deg is not None:
            object.__setattr__(self, "seam_angle_deg",
                               check_seam_angle_deg("seam_angle_deg", self.seam_angle_deg))
        if self.loss_factor is not None:
            object.__setattr__(self, "loss_factor", check_loss_factor(self.loss_factor))
        self._check_bump_options()

    def _check_bump_options(self) -> None:
        """Friction and hardening: finite, in range, δ_lim ≤ h_b (one line each)."""
        for key, check in (("friction_coefficient", check_nonnegative),
                           ("friction_stiffness_ratio", check_positive),
                           ("bump_height", check_positive), ("hardening_limit", check_positive),
                           ("hardening_exponent", check_nonnegative)):
            if getattr(self, key) is not None:
                object.__setattr__(self, key, check(key, getattr(self, key)))
        if self.hardening_limit is not None:
            if self.bump_height is None:
                raise ParameterError("hardening_limit", self.hardening_limit, "needs "
                                     "bump_height (the limit may not exceed the bump height)")
            check_hardening_limit(self.hardening_limit, self.bump_height)
        if (self.hardening_exponent or 0.0) > 0.0 and self.bump_height is None:
            raise ParameterError("hardening_exponent", self.hardening_exponent, "needs "
                                 "bump_height [m] (the hard limit of the hardening bump)")

    @classmethod
    def from_table(cls, table: dict, where: str = "model") -> "ModelOptions":
        """Options from a ``[model]`` TOML table (keys :data:`OPTION_NAMES`; the table's
        schema, with units and allowed values, is :data:`gfbopt.inputs.file_schema.MODEL`)."""
        from .file_schema import MODEL, check_table

        return cls(**check_table(table, MODEL, where))

    def over(self, base: "ModelOptions") -> "ModelOptions":
        """These options where stated, else ``base``'s (e.g. command line over file)."""
        pick = {k: (getattr(self, k) if getattr(self, k) is not None else getattr(base, k))
                for k in OPTION_NAMES}
        return ModelOptions(**pick)

    @property
    def complete(self) -> bool:
        """True when every option that the film and foil need is stated."""
        needs_seam = self.film == "seam" or self.foil == "beam"
        return (None not in (self.film, self.foil, self.deflection_law, self.loss_factor)
                and (self.seam_angle_deg is not None or not needs_seam))

    def model_kwargs(self) -> dict:
        """Keyword arguments of :meth:`BearingGeometry.model` (options must be complete)."""
        if not self.complete:
            raise ParameterError("options", self, "are not complete: apply "
                                 "resolve_model_options first")
        seam = None if self.seam_angle_deg in (None, MAX_FILM) else self.seam_angle_deg
        return dict(foil=self.foil, film=self.film, seam_angle_deg=seam,
                    deflection_law=self.deflection_law, loss_factor=self.loss_factor,
                    **self.bump_kwargs())

    def bump_kwargs(self) -> dict:
        """The bumps' friction and hardening as keyword arguments of
        :meth:`BearingGeometry.model` (the hardening limit in SI), those stated only: every
        route that builds a model from a bearing file passes them (the command line's too)."""
        out = {key: getattr(self, key) for key in ("friction_coefficient",
                                                   "friction_stiffness_ratio")
               if getattr(self, key) is not None}
        if (self.hardening_exponent or 0.0) > 0.0:      # SI limit: BearingGeometry.model
            out.update(hardening_exponent=self.hardening_exponent,
                       hardening_limit_m=self.hardening_limit or self.bump_height)
        return out

    def convention(self) -> str:
        """One line naming the film convention, for every output."""
        if self.film is None or (self.film == "seam" and self.seam_angle_deg is None):
            return "film convention not stated"
        return film_convention(self.film, None if self.seam_angle_deg == MAX_FILM
                               else self.seam_angle_deg, self.foil or "simple")

    def to_dict(self) -> dict:
        """The options as outputs state them (angles in degrees)."""
        bump = {key: getattr(self, key) for key in BUMP_OPTION_NAMES
                if getattr(self, key) is not None}
        return {"film": self.film, "seam_angle_deg": self.seam_angle_deg,
                "foil": self.foil, "deflection_law": self.deflection_law,
                "loss_factor": self.loss_factor, **bump, "film_convention": self.convention()}


def merge_options(stated: ModelOptions, base: ModelOptions) -> ModelOptions:
    """``stated`` options (e.g. the command line or function arguments) over ``base`` (e.g. a
    bearing file's ``[model]`` table), then the defaults: complete options.

    An option stated replaces that option only; ``base`` fills what is not stated, except
    that a stated film other than the base's drops the base's seam angle too (it belonged to
    the base's convention).  A stated foil other than the base's keeps the base's film and
    seam (a rigid bearing has a film convention too: ``--foil rigid`` on a seamed file is a
    rigid bearing with that seam; state ``film='periodic'`` for the plain 360° bearing), and
    the defaults apply as :func:`resolve_model_options` says (a rigid bearing whose film
    nobody states: periodic).  The base's bump options do not pass to a foil that has none:
    with foil 'rigid' the base's deflection law is dropped (nothing deflects, so it changes
    no answer), and a base's loss_factor, friction_coefficient or hardening_exponent > 0
    (rigid), or friction_coefficient or hardening_exponent > 0 (beam), not overridden by
    ``stated`` is refused in one line naming the foil and the base's key — as the same
    combination stated in one file is (:class:`~gfbopt.inputs.model.BearingModel`).
    """
    if stated.film is not None and stated.film != base.film:
        base = ModelOptions(foil=base.foil, deflection_law=base.deflection_law,
                            loss_factor=base.loss_factor,
                            **{key: getattr(base, key) for key in BUMP_OPTION_NAMES})
    if stated.foil is not None and stated.foil != (base.foil or "simple"):
        _refuse_bump_options(stated, base)
        if stated.foil == "rigid":
            base = replace(base, deflection_law=None)
    return resolve_model_options(stated.over(base))


#: the base's options a stated foil cannot carry: {foil: (key, ...)} (each refused when > 0)
_NOT_CARRIED = {"rigid": ("loss_factor", "friction_coefficient", "hardening_exponent"),
                "beam": ("friction_coefficient", "hardening_exponent")}


def _refuse_bump_options(stated: ModelOptions, base: ModelOptions) -> None:
    """A stated foil that cannot carry a bump option the base states > 0: ParameterError
    naming the foil (``--foil`` on the command line) and the base's key."""
    for key in _NOT_CARRIED.get(stated.foil, ()):
        value = getattr(base, key)
        if getattr(stated, key) is None and (value or 0.0) > 0.0:
            what = ("has no bumps" if stated.foil == "rigid" else
                    "does not carry it (its foundation has no per-unit element yet)")
            raise ParameterError("foil", stated.foil, f"cannot keep the bearing file's "
                                 f"model.{key} = {value!r}: the {stated.foil} foil {what}; "
                                 f"remove {key} from the file or keep its foil "
                                 f"{base.foil or 'simple'!r}")


def resolve_model_options(stated: Optional[ModelOptions] = None) -> ModelOptions:
    """Fill the options nobody stated with gfbopt's defaults for a bump-foil bearing.

    Defaults: foil 'simple' (the bump foundation), deflection law 'mean' (Heshmat's strip
    model, the thesis's), loss factor 0 (no structural damping: the conservative choice),
    and the film convention below.  A stated option is never changed; contradictory ones
    (a seam angle with a periodic film and no beam) are refused.

    **Film default: a seam at a fixed housing angle, the top foil's welded end 180° from the
    load line (opposite the static load).**  A rigid bearing (foil='rigid') whose film nobody
    states has no top foil and gets the periodic film of a plain 360° gas bearing (a stated
    film, the command line's or the file's, is kept: :func:`merge_options`).  Why this
    default:

    * *A seam, not a periodic film.*  A bump-foil bearing has one top foil, welded at one end
      and free at the other; the gap between the ends is open to ambient pressure.  The
      periodic film ignores it, and that is not a detail: for the Ruscitto bearing at
      45,000 rpm and 20 N it puts the critical mass parameter at 0.63 against 3.3 with a
      seam (issue #9).
    * *Fixed in the housing.*  The foil is welded to the sleeve, so the seam does not follow
      the journal when the load or speed changes.  The thesis's seam on the maximum-film line
      moves with the attitude angle in the static solution, which no installed foil does; it
      stays available as ``seam_angle_deg='max_film'`` for the thesis's results.
    * *180° from the load.*  It puts the ambient gap in the unloaded arc, where the film is
      thickest (θ ≈ π + φ) and the gauge pressure small, so it cuts least into the
      load-carrying film; keeping the weld away from the load is what designers aim for and
      the installation docs/PHYSICS.md §4 calls common.  For small attitude angles it is the
      fixed-housing counterpart of the maximum-film seam and gives nearly its thresholds
      (Ruscitto, 20 N, 45,000 rpm, 72 × 20 grid: M̄c = 3.31 at 180° against 3.32).  And it
      sits in the middle of a broad optimum: for that bearing and load, with the welded end
      swept in 15° steps at 10,000, 20,000 and 45,000 rpm, 180° is within about 2 % of the
      highest critical mass (the best is 165°–195°), 270° gives a half to a third of it, and a
      welded end in or near the loaded arc (0°–90° at every speed, 300°–345° at the higher
      speeds) makes the massless journal's half-frequency mode grow, so the rotor whirls at
      every mass.  90° and 270° were considered and rejected for those reasons: a default on
      a steep slope, or past a cliff, would surprise a user.

    Users whose foil sits elsewhere must state ``seam_angle_deg``: the answer depends on it as
    strongly as on the physics, and every output prints the convention used.
    """
    s = stated or ModelOptions()
    foil = s.foil or "simple"
    film = s.film or ("periodic" if foil == "rigid" else "seam")
    seam = s.seam_angle_deg
    if film == "periodic" and seam == MAX_FILM:
        raise ParameterError("seam_angle_deg", seam, "'max_film' needs film = 'seam'")
    if film == "periodic" and seam is not None and foil != "beam":
        raise ParameterError("seam_angle_deg", seam, "is not used "
                             "with a periodic film (no seam) unless the beam foil needs its "
                             "welded end; state film = 'seam'")
    if seam is None and (film == "seam" or foil == "beam"):
        seam = DEFAULT_SEAM_ANGLE_DEG
    return ModelOptions(film=film, seam_angle_deg=seam, foil=foil,
                        deflection_law=s.deflection_law or "mean",
                        loss_factor=0.0 if s.loss_factor is None else s.loss_factor,
                        **{key: getattr(s, key) for key in BUMP_OPTION_NAMES})
