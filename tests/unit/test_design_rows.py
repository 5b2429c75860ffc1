"""The bump-design study's rows and notes say what they mean."""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

from gfbopt.design.stability_design import feasible
from gfbopt.studies.design import load_in_g

ROOT = Path(__file__).resolve().parents[2]

#: the first row of results/ruscitto_pitch_design/tradeoff.csv as 0.2.0 wrote it: the film
#: meets its 5 µm limit but no whole number of bumps realises S = 0.038
INFEASIBLE_GEOMETRY = {"compliance": 0.03804365, "min_film_thickness_um": 10.82522,
                       "bump_pitch_mm": math.nan, "geometry_message":
                       "infeasible: no whole number of bumps meets the limits"}


def test_a_row_without_a_bump_foil_is_not_feasible():
    assert not feasible(INFEASIBLE_GEOMETRY, 5.0)                  # 0.2.0: True
    realised = {**INFEASIBLE_GEOMETRY, "bump_pitch_mm": 3.069, "geometry_message": ""}
    assert feasible(realised, 5.0)
    assert not feasible({**realised, "min_film_thickness_um": 4.9}, 5.0)


def test_the_load_is_stated_in_g_from_the_numbers():
    """20 N on a 2 kg rotor is its weight, 1 g (20 / (2 × 9.80665) = 1.0197); the study's
    note said "2 g side load"."""
    assert "i.e. 1.02 g" in load_in_g(2.0, 20.0)
    notes = " ".join(tomllib.loads((ROOT / "problems" / "ruscitto_pitch_design.toml")
                                   .read_text())["notes"])
    assert "2 g side load" not in notes and "(1 g:" in notes


def test_the_tradeoff_table_marks_unrealisable_rows():
    """The table's `feasible` needs both limits; `meets_film_limit` keeps the film alone (what
    the search ranks S by)."""
    import pandas as pd

    from gfbopt.design.outer_search import Evaluation, SearchResult
    from gfbopt.design.stability_design import LawOptimum, tradeoff_frame

    rows = [INFEASIBLE_GEOMETRY, {**INFEASIBLE_GEOMETRY, "compliance": 0.1,
                                  "bump_pitch_mm": 3.069, "geometry_message": ""}]
    evals = tuple(Evaluation(r["compliance"], 14000.0, True, True, r) for r in rows)
    search = SearchResult(0.1, 14000.0, (0.1, 0.1), "", evals, True)
    frame = tradeoff_frame([LawOptimum("mean", 0.0, 0.1, 14000.0, (0.1, 0.1), "", search)])
    assert isinstance(frame, pd.DataFrame)
    assert frame["meets_film_limit"].tolist() == [True, True]
    assert frame["feasible"].tolist() == [False, True]
