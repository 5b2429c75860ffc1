"""Checks of a study's results.

Two kinds, reported apart (``summary.json``, ``results/index.md``):

* **checks** — internal consistency: every solve converged, trends the physics requires,
  nonlinear against linear thresholds, grid convergence.  ``{what, value, limit, passed}``.
* **comparisons** — agreement with a published reference: ``{what, reference, value,
  limit, agrees}``, the deviation computed by :func:`gfbopt.glossary.deviation` (relative,
  or degrees for angles).
"""
from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..glossary import deviation


def check(what: str, value: float, limit: float) -> dict:
    """An internal check: passed when |value| ≤ limit (NaN fails)."""
    value = float(value)
    return {"what": what, "value": value, "limit": float(limit),
            "passed": bool(math.isfinite(value) and abs(value) <= limit)}


def comparison(what: str, reference: str, value: float, limit: float) -> dict:
    """A comparison with a published value: agrees when |deviation| ≤ limit (NaN: no)."""
    value = float(value)
    return {"what": what, "reference": reference, "value": value, "limit": float(limit),
            "agrees": bool(math.isfinite(value) and abs(value) <= limit)}


#: ``thermal_status`` of a row with no running state (gfbopt.thermal.running): a thermal
#: runaway or a closed clearance is an answer (docs/thermal.md), not a failed solve
NO_RUNNING_STATE = ("runaway", "closure")


def no_running_state(table: pd.DataFrame) -> pd.Series:
    """True on the rows whose running condition has no state (``thermal_status`` in
    :data:`NO_RUNNING_STATE`); all False on a table without the column."""
    if "thermal_status" not in table:
        return pd.Series(False, index=table.index)
    return table["thermal_status"].isin(NO_RUNNING_STATE)


def all_converged(table: pd.DataFrame, what: str = "all solves converged") -> dict:
    """Count of rows whose ``success`` is False (limit 0), solver failures only: a row with
    no running state (thermal runaway, closure: :func:`no_running_state`) is an answer and
    is not counted; the check's text states those rows apart (speed and load)."""
    limited = no_running_state(table)
    failures = float((~table["success"].astype(bool) & ~limited).sum())
    extra = (f"; not counted, answers: {running_limits_text(table[limited])}"
             if limited.any() else "")
    return check(f"{what} (count of failures{extra})", failures, 0)


def running_limits_text(rows: pd.DataFrame) -> str:
    """"N row(s) with no running state: thermal runaway at S rpm under W N; ..."."""
    where = []
    for _, row in rows.iterrows():
        kind = "closure" if row["thermal_status"] == "closure" else "thermal runaway"
        at = " under ".join(part for part in (
            f"{row['speed_rpm']:,.0f} rpm" if "speed_rpm" in row else "",
            f"{row['load_newton']:g} N" if "load_newton" in row else "") if part)
        label = f" ({row['variant']})" if "variant" in row else ""
        where.append((f"{kind} at {at}" if at else kind) + label)
    count = len(where)
    return (f"{count} row{'s' if count != 1 else ''} with no running state: "
            f"{'; '.join(where)}")


def add_published_columns(table: pd.DataFrame, published: list, references: tuple
                          ) -> pd.DataFrame:
    """Put each row's published values beside ours (``<quantity>_<reference>``) and their
    deviations (``<quantity>_error_<reference>``).  ``published``: per row, {reference:
    {quantity: value}}."""
    table = table.copy()
    for ref in references:
        quantities = sorted({q for p in published for q in p.get(ref, {})})
        for q in quantities:
            table[f"{q}_{ref}"] = [p.get(ref, {}).get(q, math.nan) for p in published]
        for q in quantities:
            table[f"{q}_error_{ref}"] = [deviation(q, ours, pub) for ours, pub in
                                         zip(table[q], table[f"{q}_{ref}"])]
    return table


def published_comparisons(table: pd.DataFrame, comparisons: list) -> list:
    """One comparison per (variant, reference, quantity) of the study's ``comparisons``:
    the largest |deviation| over the variant's rows."""
    out = []
    for c in comparisons:
        rows = table[table["variant"] == c["variant"]]
        for quantity, limit in c["tolerance"].items():
            errors = rows[f"{quantity}_error_{c['reference']}"].abs()
            worst = float(errors.max()) if errors.notna().all() else math.nan
            unit = "deg" if quantity.endswith("_deg") else "relative"
            out.append(comparison(f"{c['variant']}: {quantity} vs {c['reference']}, largest "
                                  f"deviation ({unit})", c["reference"], worst, limit))
    return out


def monotone(table: pd.DataFrame, column: str, along: str, rising: bool, by: list,
             what: str) -> list:
    """Per group of ``by``: the largest step of ``column`` against the required direction
    as ``along`` increases (limit 0), over the rows with a running state (a thermal
    runaway's row has no figures to follow: :func:`no_running_state`)."""
    out = []
    table = table[~no_running_state(table)]     # no running state: no trend to follow
    for key, sub in table.groupby(by, sort=False):
        steps = np.diff(sub.sort_values(along)[column].to_numpy())
        worst = float(max(-steps.min() if rising else steps.max(), 0.0)) if steps.size else 0.0
        label = ", ".join(f"{k:g}" if isinstance(k, float) else str(k)
                          for k in (key if isinstance(key, tuple) else (key,)))
        out.append(check(f"{label}: {what}", worst, 0))
    return out


def crossings(x: np.ndarray, a: np.ndarray, b: np.ndarray) -> list:
    """x where the curves a(x) and b(x) cross (linear interpolation of a − b)."""
    d = a - b
    out = []
    for k in range(len(x) - 1):
        if np.isfinite(d[k]) and np.isfinite(d[k + 1]) and d[k] * d[k + 1] < 0:
            out.append(float(x[k] - d[k] * (x[k + 1] - x[k]) / (d[k + 1] - d[k])))
    return out


def crossover_table(table: pd.DataFrame, variable: str, pairs: list, published: list
                    ) -> pd.DataFrame:
    """Where each [variant, against] pair of critical-mass curves cross, beside the
    published crossovers (``crossover_<reference>``, ``where``); NaN where none."""
    rows = []
    for label, against in pairs:
        base = table[table["variant"] == against].sort_values(variable)
        sub = table[table["variant"] == label].sort_values(variable)
        found = crossings(sub[variable].to_numpy(), sub["critical_mass"].to_numpy(),
                          base["critical_mass"].to_numpy())
        for xc in found or [math.nan]:
            rows.append({"variant": label, "against": against, "variable": variable,
                         "crossover": xc})
    out = pd.DataFrame.from_records(rows, columns=["variant", "against", "variable",
                                                   "crossover"])
    for p in published:
        col = f"crossover_{p['reference']}"
        if col not in out:
            out[col] = math.nan
        if "where" not in out:
            out["where"] = ""
        hit = (out["variant"] == p["variant"]) & (out["against"] == p["against"])
        if not hit.any():
            out = pd.concat([out, pd.DataFrame([{"variant": p["variant"],
                                                 "against": p["against"],
                                                 "variable": variable,
                                                 "crossover": math.nan}])],
                            ignore_index=True)
            hit = (out["variant"] == p["variant"]) & (out["against"] == p["against"])
        out.loc[hit, col] = p["crossover"]
        out.loc[hit, "where"] = p["where"]
    return out


def crossover_comparisons(crossovers: pd.DataFrame, published: list, titles: dict) -> list:
    """Our crossover against each published one (absolute, in the swept variable); a pair
    that does not cross in the swept range does not agree."""
    out = []
    for p in published:
        hit = crossovers[(crossovers["variant"] == p["variant"])
                         & (crossovers["against"] == p["against"])]
        ours = hit["crossover"].dropna()
        dev = float(min(abs(ours - p["crossover"]))) if len(ours) else math.nan
        name = (f"crossover of {titles.get(p['variant'], p['variant'])} with "
                f"{titles.get(p['against'], p['against'])} ({p['where']})")
        out.append(comparison(name, p["reference"], dev, p["tolerance"]))
    return out
