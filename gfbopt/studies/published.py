"""Files of published stability results (``problems/published/*.toml``).

Numbers that several studies compare with — the crossovers of the thesis's critical-mass
curves, the critical masses of its example orbits — are kept once, in such a file, and the
studies name it (``published = "published/mohan_2010_stability.toml"``).  The file labels
its curves with their models (``[curves]``); a study compares with a curve only through a
variant of the same label **and** the same model, so a label cannot silently mean another
bearing.
"""
from __future__ import annotations

from ..errors import ParameterError
from ..inputs import read_toml
from .base import Study, build_model, merged
from .spec import PUBLISHED_DATA, Where, check_table


def load_published(study: Study) -> dict:
    """The validated published-data file named by the study's ``published`` key."""
    path = study.directory / study.spec["published"]
    if not path.is_file():
        raise study.where("published").error(study.spec["published"],
                                             "must name an existing file (relative to the "
                                             "study file)")
    where = Where(str(path))
    try:
        data = check_table(read_toml(path), PUBLISHED_DATA, where)
    except ParameterError:
        raise
    curves = data["curves"]
    for k, c in enumerate(data["crossovers"]):
        for key in ("variant", "against"):
            if c[key] not in curves:
                raise (where / "crossovers" / k / key).error(
                    c[key], f"must be one of the curves: {', '.join(curves)}")
    for k, c in enumerate(data["critical_masses"]):
        if c["curve"] not in curves:
            raise (where / "critical_masses" / k / "curve").error(
                c["curve"], f"must be one of the curves: {', '.join(curves)}")
        if len(c["verdicts"]) != len(c["masses"]):
            raise (where / "critical_masses" / k / "verdicts").error(
                c["verdicts"], f"must have one verdict per mass ({len(c['masses'])})")
    return data


def curve_model(published: dict, curve: str, base: dict, groups: dict, where: Where):
    """The model of a published curve with the study's formulation ``base`` and ``groups``
    (Λ, L/D) filled in."""
    return build_model(merged(base, published["curves"][curve], groups), where)


def _same_bearing(a, b) -> bool:
    return (a.foil_law == b.foil_law and a.compliance == b.compliance
            and a.top_foil_coefficient == b.top_foil_coefficient)


def crossovers_for(study: Study, published: dict, models: dict) -> list:
    """The published crossovers this map compares with: same swept variable, same fixed
    value, both curves among the study's ``crossover_pairs``; each curve's model must be the
    study variant's of the same label (else one line naming both)."""
    spec = study.spec
    variable = spec["sweep"]["variable"]
    fixed = spec["fixed"]
    pairs = [tuple(p) for p in spec["crossover_pairs"]]
    out = []
    for k, c in enumerate(published["crossovers"]):
        other = "eccentricity" if variable == "bearing_number" else "bearing_number"
        if c["variable"] != variable or c.get(other) != fixed.get(other):
            continue
        if (c["variant"], c["against"]) not in pairs:
            continue
        for key in ("variant", "against"):
            label = c[key]
            ours = models[label][0]
            theirs = curve_model(published, label, spec["model"],
                                 {"bearing_number": ours.bearing_number,
                                  "length_ratio": ours.length_ratio},
                                 study.where("published"))
            if not _same_bearing(ours, theirs):
                raise study.where("variants").error(
                    label, f"is not the bearing of curve '{label}' in "
                    f"{spec['published']} ({published['curves'][label]})")
        out.append({**c, "reference": published["reference"]})
    return out
