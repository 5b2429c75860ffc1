"""Command-line helpers for SI input: the formulation options a bearing file states, merged
with the command line, and the parsing of SI quantities (masses, loads, angles).

Rule for a bearing file's ``[model]`` table (film, seam_angle_deg, foil, deflection_law,
loss_factor; :func:`gfbopt.inputs.options.merge_options`): an option given on the command line
wins; an option the file states fills what the command line left out; what neither states
takes the default of :func:`gfbopt.inputs.options.resolve_model_options` (for a bump-foil
bearing, a seam with the welded end 180° from the load).  A flag replaces only what it
names:

* ``--film`` different from the file's film drops the file's seam angle too (it belonged to
  the file's film convention);
* ``--foil rigid`` (or ``beam``) keeps the file's film and seam (a rigid bearing with the
  file's seam; add ``--film periodic`` for the plain 360° bearing) and drops the file's
  deflection law with rigid (nothing deflects); a file's ``loss_factor``,
  ``friction_coefficient`` or ``hardening_exponent`` > 0 that the foil cannot carry is
  refused in one line naming ``--foil`` and the file key.

Without ``--bearing`` (non-dimensional input) the defaults stay those of the non-dimensional
model: periodic film, axial-mean law, no structural damping.
"""
from __future__ import annotations

import argparse
import math
from ..inputs.options import MAX_FILM, ModelOptions, merge_options


def seam_angle_text(text: str):
    """argparse type: degrees from the load line in [0, 360), or 'max_film'."""
    if text.strip().lower() in (MAX_FILM, "max-film"):
        return MAX_FILM
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--seam-angle = {text!r}: must be a number of degrees "
                                         "or 'max_film'") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"--seam-angle = {text!r}: must be finite" + (
            " (not NaN)" if math.isnan(value) else ""))
    return value


def stated_options(args) -> ModelOptions:
    """The formulation options given on the command line (None where not given).

    ``args.seam_angle`` is in degrees (or 'max_film'); a value outside [0, 360) is refused
    here with the option's name, before anything is solved.
    """
    angle = getattr(args, "seam_angle", None)
    if angle is not None and angle != MAX_FILM:
        from ..inputs.checks import check_seam_angle_deg

        angle = check_seam_angle_deg("--seam-angle", angle, allow_max_film=False)
    return ModelOptions(film=getattr(args, "film", None), seam_angle_deg=angle,
                        foil=getattr(args, "foil", None),
                        deflection_law=getattr(args, "deflection_law", None),
                        loss_factor=getattr(args, "loss_factor", None))


def fill_model_options(args) -> ModelOptions:
    """Fill ``args.film``, ``seam_angle`` (degrees, None for the maximum-film line), ``foil``,
    ``deflection_law`` and ``loss_factor`` in place for :func:`gfbopt.cli.common.operating_point`
    (bearing file and defaults with ``--bearing``; the non-dimensional defaults without), and
    return the complete options."""
    cli = stated_options(args)
    if getattr(args, "bearing", None) is not None:
        from ..inputs.bearing_file import load_bearing_file

        resolved = merge_options(cli, load_bearing_file(args.bearing)[1])
    else:
        resolved = ModelOptions(film=cli.film or "periodic", seam_angle_deg=cli.seam_angle_deg,
                                foil=cli.foil, deflection_law=cli.deflection_law or "mean",
                                loss_factor=0.0 if cli.loss_factor is None else cli.loss_factor)
    args.film = resolved.film
    args.deflection_law = resolved.deflection_law
    args.loss_factor = resolved.loss_factor
    if getattr(args, "bearing", None) is not None:
        args.foil = resolved.foil
        args.seam_angle = (None if resolved.seam_angle_deg in (None, MAX_FILM)
                           else resolved.seam_angle_deg)
    elif cli.seam_angle_deg == MAX_FILM:
        args.seam_angle = None
    return resolved


def orbit_in_si(table, out: dict, op) -> None:
    """A one-bearing orbit of a bearing file in SI beside its non-dimensional columns (as the
    rotor's orbit reads): ``time_s``, ``x_um``, ``y_um`` and ``min_film_thickness_um`` added to
    the trace ``table`` and the run's smallest film ``min_film_thickness_um`` to ``out``, from
    the clearance c and the shaft speed ω of the operating point; nothing without a bearing
    file (no clearance)."""
    import math

    from ..inputs.conversions import rpm_to_rad_per_s

    if op.geometry is None or op.speed_rpm is None:
        return
    c_um, omega = op.geometry.radial_clearance * 1e6, rpm_to_rad_per_s(op.speed_rpm)
    table["time_s"] = table["tau"] / omega
    table["x_um"], table["y_um"] = table["x"] * c_um, table["y"] * c_um
    table["min_film_thickness_um"] = table["min_film"] * c_um
    film = out.get("min_film")
    out["min_film_thickness_um"] = film * c_um if film is not None and math.isfinite(film) \
        else math.nan


def critical_mass_in_si(out: dict, op) -> None:
    """The critical mass of a bearing file in kg (M = M̄ W0/(c ω²), as ``gfbopt stability``
    gives it) and the static load in N beside the non-dimensional M̄_crit."""
    import math

    from ..inputs.conversions import mass_from_parameter, rpm_to_rad_per_s

    if op.geometry is None or op.speed_rpm is None or op.load_newton is None:
        return
    omega = rpm_to_rad_per_s(op.speed_rpm)
    c = op.geometry.radial_clearance
    out["load_newton"] = op.load_newton
    for key in ("critical_mass", "linear_critical_mass"):
        value = out.get(key)
        out[f"{key}_kg"] = (mass_from_parameter(value, c, omega, op.load_newton)
                            if value is not None and math.isfinite(value) else math.nan)
