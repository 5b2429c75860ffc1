"""Fuzz set of impossible and broken inputs for the rotor, the bearing as built, the load
capacity, design studies and output paths: rotor files (every key × wrong types, NaN/inf,
zero, negative, 1e-300, 1e300, millimetres), bearing ``[bore]`` / ``[[pads]]`` / ``[[zones]]``
tables, ``gfbopt rotor`` and ``gfbopt capacity`` flags, rotor design study files and output
paths that cannot be written.

Each input ends in an answer (exit 0 or 1) or one ``gfbopt: error:`` line with exit 2 —
never a traceback, an abort by a signal, or a run past :data:`LIMIT_S` that nobody asked for
(every run is given ``--max-minutes`` of :data:`LIMIT_S`: a run the memory and time guard lets
through under it must end within it, so a run past it is the guard's error);
an input marked ``REFUSE`` (impossible, or an option that would be ignored) must be refused
(exit 2) — an answer from it is a failure.  The CLI runs in this process (as
``tests/cli_inprocess.py`` does) under an alarm; the inputs that could exhaust memory run as
subprocesses with a timeout and an address-space limit, so that an abort is seen as one.
The whole set (several hundred inputs) is in the slow tier; :data:`FAST` runs by default.
"""
from __future__ import annotations

import math
import os
import re
import resource
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from tests.cli_inprocess import run_cli
from tests.integration.test_study_fuzz import toml_value

ROOT = Path(__file__).resolve().parents[2]
RUSCITTO = ROOT / "problems" / "bearings" / "ruscitto.toml"
DESIGN = ROOT / "problems" / "rotor_bearing_design.toml"
#: longest run of an input that does not ask for a long computation [s]
LIMIT_S = 120
#: a run past LIMIT_S: the guard estimated it within --max-minutes LIMIT_S/60 and let it run
PAST = f"ran past {LIMIT_S} s: the guard let it through under --max-minutes {LIMIT_S / 60:g}"
GRID = ("--grid", "12x4")
REFUSE, ANY = "refuse", "any"

#: the example rotor (problems/rotors/blower.toml) with a side load, an imbalance plane and a
#: station, every number a key of the fuzz
ROTOR = {
    "rotor": {"mass": 3.2, "transverse_inertia": 0.012, "polar_inertia": 0.002,
              "gravity": 9.80665, "gravity_direction_deg": 0.0},
    "bearings": [{"file": "bearing.toml", "position": -0.035, "name": "A"},
                 {"file": "bearing.toml", "position": 0.065, "name": "B"}],
    "side_loads": [{"force": 5.0, "direction_deg": 90.0, "position": 0.02}],
    "imbalance": [{"amount_g_mm": 2.0, "phase_deg": 0.0, "position": 0.065}],
    "stations": [{"name": "impeller", "position": 0.09}],
}
BAD = {"text": "big", "bool": True, "nan": math.nan, "inf": math.inf, "-inf": -math.inf,
       "list": [1.0, 2.0], "table": {"a": 1.0}, "zero": 0.0, "negative": -1.0,
       "tiny": 1e-300, "huge": 1e300, "huge_int": 10 ** 400, "mm": "×1000"}
#: (table, index, key) → the values (of BAD) that a real rotor may have: the others must be
#: refused (wrong types and non-finite values always)
ALLOWED = {
    ("rotor", None, "polar_inertia"): {"tiny"},
    ("rotor", None, "gravity"): {"zero", "tiny"},           # the side load carries the rotor
    ("rotor", None, "gravity_direction_deg"): {"zero", "negative", "tiny"},
    # -1 m: 28 D; a bearing at the CG keeps a share of the side load's moment
    ("bearings", 0, "position"): {"negative", "zero", "tiny"},
    ("bearings", 1, "position"): {"negative", "zero", "tiny"},
    ("side_loads", 0, "force"): {"tiny", "mm"},          # 5 kN: under 100 p_a L D
    ("side_loads", 0, "direction_deg"): {"zero", "negative", "tiny"},
    ("side_loads", 0, "position"): {"zero", "negative", "tiny"},
    ("imbalance", 0, "amount_g_mm"): {"tiny"},
    ("imbalance", 0, "phase_deg"): {"zero", "negative", "tiny"},
    ("imbalance", 0, "position"): {"zero", "negative", "tiny"},
    ("stations", 0, "position"): {"zero", "negative", "tiny"},
}


def _toml(data: dict) -> str:
    out = []
    for name, value in data.items():
        if isinstance(value, dict) and name in ("rotor", "bore", "bearing", "model", "search",
                                                "robustness"):
            out.append(f"[{name}]")
            out += [f"{k} = {toml_value(v)}" for k, v in value.items()]
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            for row in value:
                out.append(f"[[{name}]]")
                out += [f"{k} = {toml_value(v)}" for k, v in row.items()]
        else:
            out.insert(0, f"{name} = {toml_value(value)}")
    return "\n".join(out) + "\n"


def _copy(v):
    if isinstance(v, dict):
        return {k: _copy(x) for k, x in v.items()}
    return [_copy(x) for x in v] if isinstance(v, list) else v


# ------------------------------------------------------------------ the cases
CASES: dict = {}


def _add(label, expect, files, args, subprocess_run=False):
    assert label not in CASES, label
    CASES[label] = (expect, files, tuple(args), subprocess_run)


ROTOR_ARGS = ("rotor", "{dir}/rotor.toml", "--speed-range", "8000", "12000", *GRID)
STATIC_ARGS = ("static", "--bearing", "{dir}/bearing.toml", "--speed-rpm", "30000",
               "--load-newton", "10", *GRID)


def _rotor_cases():
    for (table, index, key) in [("rotor", None, k) for k in ROTOR["rotor"]] + [
            (t, i, k) for t in ("bearings", "side_loads", "imbalance", "stations")
            for i, row in enumerate(ROTOR[t]) for k, v in row.items()
            if not isinstance(v, str)]:
        for name, value in BAD.items():
            data = _copy(ROTOR)
            row = data[table] if index is None else data[table][index]
            if name == "mm":
                unit = 1e6 if "inertia" in key else 1e3
                value = row[key] * unit
                if value == 0.0:
                    continue
            row[key] = value
            allowed = ALLOWED.get((table, index, key), set())
            expect = ANY if name in allowed else REFUSE
            where = key if index is None else f"{table}[{index}].{key}"
            _add(f"rotor {where}={name}", expect, {"rotor.toml": _toml(data)}, ROTOR_ARGS)
    structure = {
        "no [rotor]": {k: v for k, v in ROTOR.items() if k != "rotor"},
        "one bearing": {**ROTOR, "bearings": ROTOR["bearings"][:1]},
        "three bearings": {**ROTOR, "bearings": ROTOR["bearings"] + [
            {"file": "bearing.toml", "position": 0.1, "name": "C"}]},
        "same positions": {**ROTOR, "bearings": [dict(ROTOR["bearings"][0]),
                                                 {**ROTOR["bearings"][1], "position": -0.035}]},
        "overlapping bearings": {**ROTOR, "bearings": [dict(ROTOR["bearings"][0]),
                                                       {**ROTOR["bearings"][1],
                                                        "position": -0.02}]},
        "same names": {**ROTOR, "bearings": [dict(ROTOR["bearings"][0]),
                                             {**ROTOR["bearings"][1], "name": "A"}]},
        "station named A": {**ROTOR, "stations": [{"name": "A", "position": 0.0}]},
        "bearing file missing": {**ROTOR, "bearings": [
            {**ROTOR["bearings"][0], "file": "none.toml"}, ROTOR["bearings"][1]]},
        "bearing file a folder": {**ROTOR, "bearings": [
            {**ROTOR["bearings"][0], "file": "."}, ROTOR["bearings"][1]]},
        "unknown rotor key": {**ROTOR, "rotor": {**ROTOR["rotor"], "masss": 3.0}},
        "misspelt table": {**{k: v for k, v in ROTOR.items() if k != "bearings"},
                           "bearing": ROTOR["bearings"]},
        "both amounts": {**ROTOR, "imbalance": [{**ROTOR["imbalance"][0],
                                                 "amount_kg_m": 2e-6}]},
        "no amount": {**ROTOR, "imbalance": [{"position": 0.0}]},
        "model loss factor 2": {**ROTOR, "bearings": [
            {**ROTOR["bearings"][0], "model": {"loss_factor": 2.0}}, ROTOR["bearings"][1]]},
        "side load cancels the weight": {**ROTOR, "side_loads": [
            {"force": 3.2 * 9.80665, "direction_deg": 180.0, "position": 0.0}]},
        "imbalance beyond the clearance": {**ROTOR, "imbalance": [
            {"amount_g_mm": 1e4, "phase_deg": 0.0, "position": 0.065}]},
        "positions in millimetres": {**ROTOR, "bearings": [
            {**ROTOR["bearings"][0], "position": -40.0},
            {**ROTOR["bearings"][1], "position": 80.0}]},
        "gravity 0 and no side load": {**ROTOR, "rotor": {**ROTOR["rotor"], "gravity": 0.0},
                                       "side_loads": []},
    }
    for label, data in structure.items():
        _add(f"rotor {label}", REFUSE, {"rotor.toml": _toml(data)}, ROTOR_ARGS)
    _add("rotor valid", ANY, {"rotor.toml": _toml(ROTOR)}, ROTOR_ARGS)
    _add("rotor bearing named A/B with --csv", ANY, {"rotor.toml": _toml(
        {**ROTOR, "bearings": [{**ROTOR["bearings"][0], "name": "A/B"},
                               ROTOR["bearings"][1]]})},
         (*ROTOR_ARGS, "--csv", "{dir}/out"))


BORE_SHIMS = {"kind": "shims", "count": 3, "preload_ratio": 0.2, "width_deg": 60.0,
              "offset_deg": 0.0}
HALVES = [{"start_deg": 0.0, "end_deg": 180.0, "bump_thickness": 80e-6},
          {"start_deg": 180.0, "end_deg": 360.0}]
PADS = [{"leading_end_deg": 180.0, "arc_deg": 110.0},
        {"leading_end_deg": 300.0, "arc_deg": 110.0},
        {"leading_end_deg": 60.0, "arc_deg": 110.0}]


def _bearing_text(**tables) -> str:
    text = RUSCITTO.read_text()
    if tables.pop("rigid", False):
        text = text.replace('foil = "simple"', 'foil = "rigid"')
    return text.replace("[model]", _toml(tables) + "\n[model]")


def _as_built_cases():
    allowed = {("preload_ratio", "zero"), ("preload_ratio", "tiny"),
               ("offset_deg", "zero"), ("offset_deg", "negative"), ("offset_deg", "tiny"),
               ("leading_end_deg", "zero"), ("leading_end_deg", "negative"),
               ("leading_end_deg", "tiny"), ("start_deg", "zero"), ("start_deg", "tiny")}
    for key in ("count", "preload_ratio", "width_deg", "offset_deg"):
        for name, value in BAD.items():
            if name == "mm":
                continue
            bore = {**BORE_SHIMS, key: value}
            expect = ANY if (key, name) in allowed else REFUSE
            _add(f"bore.{key}={name}", expect, {"bearing.toml": _bearing_text(bore=bore)},
                 STATIC_ARGS)
    for key in ("leading_end_deg", "arc_deg"):
        for name, value in BAD.items():
            if name == "mm":
                continue
            pads = _copy(PADS)
            pads[1][key] = value
            _add(f"pads[1].{key}={name}", REFUSE, {"bearing.toml": _bearing_text(pads=pads)},
                 STATIC_ARGS)
    for key in ("end_deg", "bump_pitch", "bump_half_length", "bump_thickness"):
        for name, value in BAD.items():
            if name == "mm":
                continue
            zones = _copy(HALVES)
            zones[0][key] = value
            _add(f"zones[0].{key}={name}", REFUSE, {"bearing.toml": _bearing_text(
                zones=zones)}, STATIC_ARGS)
    special = {
        "bore 1e6 lobes": dict(bore={"kind": "lobes", "count": 10 ** 6, "preload_ratio": 0.2}),
        "bore 3 x 200 deg shims": dict(bore={**BORE_SHIMS, "width_deg": 200.0}),
        "bore preload closes the film": dict(bore={**BORE_SHIMS, "preload_ratio": 1.0}),
        "bore depth above c": dict(bore={"kind": "lobes", "count": 3,
                                         "preload_depth": 30e-6}),
        "bore both preloads": dict(bore={**BORE_SHIMS, "preload_depth": 5e-6}),
        "bore kind oval": dict(bore={"kind": "oval"}),
        "bore table not increasing": dict(bore={"kind": "table", "angle_deg": [90.0, 10.0],
                                                "clearance_change": [1e-6, 0.0]}),
        "bore table lengths differ": dict(bore={"kind": "table", "angle_deg": [0.0, 90.0],
                                                "clearance_change": [1e-6]}),
        "100 pads": dict(pads=[{"leading_end_deg": 3.6 * k, "arc_deg": 3.0}
                               for k in range(100)]),
        "pads overlap": dict(pads=[{"leading_end_deg": 180.0, "arc_deg": 200.0},
                                   {"leading_end_deg": 300.0, "arc_deg": 100.0}]),
        "zones overlap": dict(zones=[{"start_deg": 0.0, "end_deg": 200.0},
                                     {"start_deg": 180.0, "end_deg": 360.0}]),
        "zones leave a gap": dict(zones=[{"start_deg": 0.0, "end_deg": 170.0},
                                         {"start_deg": 180.0, "end_deg": 360.0}]),
        "zones on a rigid foil": dict(zones=HALVES, rigid=True),
        "pads on a rigid foil": dict(pads=PADS, rigid=True),
        "zone thickness 1e-300": dict(zones=[{**HALVES[0], "bump_thickness": 1e-300},
                                             HALVES[1]]),
        "zone bump thicker than l0": dict(zones=[{**HALVES[0], "bump_thickness": 5e-3},
                                                 HALVES[1]]),
        "30 zones": dict(zones=[{"start_deg": 12.0 * k, "end_deg": 12.0 * (k + 1)}
                                for k in range(30)]),
    }
    for label, tables in special.items():
        _add(label, REFUSE, {"bearing.toml": _bearing_text(**tables)}, STATIC_ARGS)
    for label, tables in (("valid shims", dict(bore=BORE_SHIMS)),
                          ("valid pads", dict(pads=PADS)), ("valid zones", dict(zones=HALVES))):
        _add(label, ANY, {"bearing.toml": _bearing_text(**tables)}, STATIC_ARGS)
        _add(f"rotor on {label}", ANY, {"bearing.toml": _bearing_text(**tables),
                                        "rotor.toml": _toml(ROTOR)}, ROTOR_ARGS)
    _add("static --foil rigid on a zoned bearing", REFUSE,
         {"bearing.toml": _bearing_text(zones=HALVES)}, (*STATIC_ARGS, "--foil", "rigid"))


NUMBERS = {"nan": "nan", "inf": "inf", "zero": "0", "negative": "-1", "tiny": "1e-300",
           "huge": "1e300", "text": "abc", "fraction": "2.5"}
ROTOR_FILE = {"rotor.toml": _toml(ROTOR)}


def _flag_cases():
    base = ("rotor", "{dir}/rotor.toml", *GRID)
    speed = ("--speed-range", "8000", "12000")
    orbit = ("--orbit", "--speed-rpm", "10000", "--revolutions", "1")
    for low, high in (("1e-300", "1e300"), ("0", "1000"), ("-1", "1000"), ("30000", "5000"),
                      ("nan", "1000"), ("5000", "5000"), ("1", "1e12"), ("abc", "1"),
                      ("0.01", "10")):
        _add(f"rotor --speed-range {low} {high}", REFUSE, ROTOR_FILE,
             (*base, "--speed-range", low, high))
    flags = {
        ("--speed-rpm",): (speed, {"fraction"}),
        ("--campbell-speeds",): ((*speed, "--campbell"), set()),
        ("--imbalance-grade",): ((*speed, "--imbalance-response"), {"fraction", "tiny"}),
        ("--revolutions",): (("--orbit", "--speed-rpm", "10000"), {"fraction"}),
        ("--time-step",): (orbit, {"fraction"}),
        ("--stages",): (orbit, set()),
        ("--kick",): (orbit, {"zero", "tiny", "negative", "fraction"}),
        ("--rate",): (("--run-up", "8000", "9000"), set()),
        ("--window-revolutions",): (("--run-up", "8000", "9000", "--rate", "20000"), set()),
        ("--foil-travel-um",): (orbit, {"fraction", "huge"}),
    }
    for (flag,), (rest, allowed) in flags.items():
        for name, value in NUMBERS.items():
            if flag == "--rate" and name == "fraction":
                continue                  # 2.5 rpm/s over 1000 rpm: a long run, asked for
            _add(f"rotor {flag} {name}", ANY if name in allowed else REFUSE, ROTOR_FILE,
                 (*base, *rest, flag, value))
    for plane in (("nan", "0", "0.065"), ("1e300", "0", "0.065"), ("5", "0", "1e200"),
                  ("5", "1e300", "0.065"), ("-5", "0", "0.065"), ("0", "0", "0.065")):
        _add(f"rotor --imbalance-plane {' '.join(plane)}", REFUSE, ROTOR_FILE,
             (*base, *speed, "--imbalance-response", "--imbalance-plane", *plane))
    unused = {"--revolutions": ("5",), "--method": ("rk4",), "--stages": ("3",),
              "--rate": ("100",), "--kick": ("0.01",), "--time-step": ("0.1",),
              "--perturbation": ("conical",), "--window-revolutions": ("5",)}
    for flag, value in unused.items():
        _add(f"rotor --imbalance-response ignores {flag}", REFUSE, ROTOR_FILE,
             (*base, *speed, "--imbalance-response", flag, *value))
    _add("rotor --campbell-speeds without --campbell", REFUSE, ROTOR_FILE,
         (*base, *speed, "--campbell-speeds", "5"))
    _add("rotor --imbalance-plane without --imbalance-response", REFUSE, ROTOR_FILE,
         (*base, *speed, "--imbalance-plane", "5", "0", "0.065"))
    for grid in ("7x3", "big", "12x5"):
        _add(f"rotor --grid {grid}", REFUSE, ROTOR_FILE, ("rotor", "{dir}/rotor.toml",
                                                          *speed, "--grid", grid))
    # the memory and time guard: refused at once (run in a subprocess, with a memory limit)
    for label, args in (
            ("rotor --grid 2000x400", ("rotor", "{dir}/rotor.toml", *speed, "--grid",
                                       "2000x400")),
            ("rotor --campbell-speeds 100000", (*base, *speed, "--campbell",
                                                "--campbell-speeds", "100000")),
            ("rotor --orbit --time-step 1e-12", (*base, *orbit, "--time-step", "1e-12")),
            ("capacity --grid 2000x2000", ("capacity", "--bearing", "{dir}/bearing.toml",
                                           "--min-film-um", "5", "--speed-rpm", "30000",
                                           "--grid", "2000x2000"))):
        _add(label, REFUSE, {"rotor.toml": _toml(ROTOR), "bearing.toml": RUSCITTO.read_text()},
             args, subprocess_run=True)


def _capacity_cases():
    base = ("capacity", "--bearing", "{dir}/bearing.toml", *GRID)
    files = {"bearing.toml": RUSCITTO.read_text()}
    ok = {"--min-film-um": "5", "--speed-rpm": "30000"}
    for flag in ("--min-film-um", "--speed-rpm", "--max-minutes", "--max-memory-gb"):
        for name, value in NUMBERS.items():
            args = dict(ok)
            args[flag] = value
            flat = [x for kv in args.items() for x in kv]
            allowed = {"fraction"} | ({"huge"} if flag in ("--max-minutes",
                                                           "--max-memory-gb") else set())
            _add(f"capacity {flag} {name}", ANY if name in allowed else REFUSE, files,
                 (*base, *flat))
    _add("capacity film above the clearance", REFUSE, files,
         (*base, "--min-film-um", "25", "--speed-rpm", "30000"))
    for name, value in NUMBERS.items():
        _add(f"capacity --lift-off --load-newton {name}", ANY if name == "fraction" else REFUSE,
             files, (*base, "--min-film-um", "5", "--lift-off", "--load-newton", value))
    _add("capacity --load-newton without --lift-off", REFUSE, files,
         (*base, "--min-film-um", "5", "--speed-rpm", "30000", "--load-newton", "10"))


def _path_cases():
    files = {"bearing.toml": RUSCITTO.read_text(), "rotor.toml": _toml(ROTOR),
             "taken.csv": "x\n", "taken.png": "x"}
    cap = ("capacity", "--bearing", "{dir}/bearing.toml", "--min-film-um", "5",
           "--speed-rpm", "30000", *GRID)
    stab = ("stability", "--bearing", "{dir}/bearing.toml", "--rotor-mass-kg", "2",
            "--load-newton", "20", "--speed-rpm", "30000", *GRID)
    rotor = (*ROTOR_ARGS[:1], "{dir}/rotor.toml", *ROTOR_ARGS[2:], "--campbell",
             "--campbell-speeds", "3")
    for label, args in (
            ("capacity --figure /proc/f.png", (*cap, "--figure", "/proc/f.png")),
            ("capacity --csv /proc/c.csv", (*cap, "--csv", "/proc/c.csv")),
            ("capacity --csv into a missing folder", (*cap, "--csv", "{dir}/none/c.csv")),
            ("capacity --csv is a folder", (*cap, "--csv", "{dir}")),
            ("stability --csv /proc/x.csv", (*stab, "--csv", "/proc/x.csv")),
            ("rotor --plot /proc/p", (*rotor, "--plot", "/proc/p")),
            ("rotor --csv /proc/c", (*rotor, "--csv", "/proc/c")),
            ("rotor --csv is a file", (*rotor, "--csv", "{dir}/taken.csv")),
            ("rotor --plot is a file", (*rotor, "--plot", "{dir}/taken.png"))):
        _add(label, REFUSE, files, args)
    for label, args in (("capacity --csv an existing file", (*cap, "--csv", "{dir}/taken.csv")),
                        ("capacity --figure an existing file",
                         (*cap, "--figure", "{dir}/taken.png"))):
        _add(label, ANY, files, args)


def _design_cases():
    """Rotor design studies with an invalid fixed input: refused when planned."""
    rotor = (ROOT / "problems" / "rotors" / "blower.toml").as_posix()
    text = DESIGN.read_text().replace('rotor = "rotors/blower.toml"', f'rotor = "{rotor}"')

    def line(key):        # the study's own line for a search size (its value is tuned often)
        return re.search(rf"^{key} = \d+$", text, re.M).group(0)

    changes = {
        "bore.width_deg = 200": ("width_deg = 60.0", "width_deg = 200.0"),
        "bore.offset_deg = 1e300": ("offset_deg = 0.0", "offset_deg = 1e300"),
        "bore.count = 40": ("count = 3", "count = 40"),
        "bore.count = 2.5": ("count = 3", "count = 2.5"),
        "min_film_um = 1e300": ("min_film_um = 1.5", "min_film_um = 1e300"),
        "min_film_um = nan": ("min_film_um = 1.5", "min_film_um = nan"),
        "heaviest_load_factor = -2": ("heaviest_load_factor = 2.0",
                                      "heaviest_load_factor = -2.0"),
        "speed_range_rpm 1e-300 1e300": ("speed_range_rpm = [4000.0, 45000.0]",
                                         "speed_range_rpm = [1e-300, 1e300]"),
        "speed_range_rpm reversed": ("speed_range_rpm = [4000.0, 45000.0]",
                                     "speed_range_rpm = [45000.0, 4000.0]"),
        "search_grid 2000x2000": ('search_grid = "36x10"', 'search_grid = "2000x2000"'),
        "budget 1e9": (line("budget"), "budget = 1000000000"),
        "population 1e6": (line("population"), "population = 1000000"),
        "samples 1e9": (line("samples"), "samples = 1000000000"),
        "clearance low 1e-300": ("low = 15.0", "low = 1e-300"),
        "clearance high 1e300": ("high = 35.0", "high = 1e300"),
        "variable unknown": ('name = "A:radial_clearance_um"', 'name = "shaft_colour"'),
        "rotor missing": (f'rotor = "{rotor}"', 'rotor = "none.toml"'),
        "loss band above 1": ("loss_factor_band = [0.0, 0.2]", "loss_factor_band = [0.0, 2.0]"),
    }
    guarded = {"search_grid 2000x2000", "budget 1e9", "population 1e6", "samples 1e9"}
    for label, (old, new) in changes.items():
        assert old in text, old
        _add(f"design {label}", REFUSE, {"study.toml": text.replace(old, new, 1)},
             ("run", "{dir}/study.toml", "--results", "{dir}/results", "--workers", "1"),
             subprocess_run=label in guarded)
    mm = (ROOT / "problems" / "rotors" / "blower.toml").read_text().replace(
        "position = -0.035", "position = -40.0").replace(
        "../bearings/ruscitto.toml", RUSCITTO.as_posix())
    _add("design on a rotor in millimetres", REFUSE,
         {"rotor.toml": mm, "study.toml": text.replace(f'rotor = "{rotor}"',
                                                       'rotor = "rotor.toml"')},
         ("run", "{dir}/study.toml", "--results", "{dir}/results", "--workers", "1"))


_rotor_cases()
_as_built_cases()
_flag_cases()
_capacity_cases()
_path_cases()
_design_cases()

#: one input of every kind (default tier): refused in milliseconds, or a 12x4 answer
FAST = ("rotor mass=huge", "rotor bearings[1].position=mm", "rotor transverse_inertia=mm",
        "rotor bearings[0].position=nan", "rotor side_loads[0].direction_deg=huge",
        "rotor imbalance[0].amount_g_mm=huge", "rotor stations[0].position=huge",
        "rotor side load cancels the weight", "rotor three bearings",
        "rotor overlapping bearings", "rotor gravity 0 and no side load",
        "bore.offset_deg=huge", "bore.count=huge_int", "pads[1].arc_deg=negative",
        "zones[0].bump_thickness=tiny", "bore 1e6 lobes", "100 pads", "zones on a rigid foil",
        "zone bump thicker than l0", "30 zones", "static --foil rigid on a zoned bearing",
        "valid zones", "rotor --grid 7x3",
        "rotor --imbalance-plane 5 0 1e200", "rotor --imbalance-grade huge",
        "rotor --imbalance-response ignores --revolutions", "capacity --min-film-um nan",
        "capacity film above the clearance", "design bore.width_deg = 200",
        "design bore.offset_deg = 1e300", "design on a rotor in millimetres",
        "capacity --csv into a missing folder", "rotor --speed-rpm tiny",
        "rotor --stages fraction", "rotor --time-step huge", "rotor --kick huge",
        "rotor --window-revolutions huge", "rotor --window-revolutions fraction",
        "rotor --rate huge", "rotor --revolutions tiny", "rotor --foil-travel-um tiny",
        "rotor --speed-range 0.01 10")


class _Timeout(BaseException):
    """Raised by the alarm: the run passed LIMIT_S."""


def _alarm(signum, frame):
    raise _Timeout()


def _limit_memory():                   # in the child: an unguarded allocation fails at 3 GB
    resource.setrlimit(resource.RLIMIT_AS, (3 * 2 ** 30, 3 * 2 ** 30))


def _run(tmp_path: Path, label: str):
    """(exit status or None, stderr, what went wrong or None)."""
    expect, files, args, in_child = CASES[label]
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    if "bearing.toml" not in files:
        (tmp_path / "bearing.toml").write_text(RUSCITTO.read_text())
    argv = [a.replace("{dir}", str(tmp_path)) for a in args]
    if "--max-minutes" not in argv:             # the guard's time limit is the harness's
        argv += ["--max-minutes", f"{LIMIT_S / 60:g}"]
    if in_child:
        env = {**os.environ, "OMP_NUM_THREADS": "1"}
        try:
            out = subprocess.run([sys.executable, "-m", "gfbopt", *argv], capture_output=True,
                                 text=True, timeout=LIMIT_S, cwd=tmp_path, env=env,
                                 preexec_fn=_limit_memory)
        except subprocess.TimeoutExpired:
            return None, "", PAST
        if out.returncode < 0:
            return out.returncode, out.stderr, f"aborted by signal {-out.returncode}"
        return out.returncode, out.stderr, None
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(LIMIT_S)
    try:
        out = run_cli(*argv, cwd=tmp_path)
    except _Timeout:
        return None, "", PAST
    except Exception as exc:                          # noqa: BLE001 - the point of it
        return None, "", f"traceback {type(exc).__name__}: {str(exc)[:300]}"
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    return out.returncode, out.stderr, None


def _check(tmp_path: Path, label: str) -> None:
    expect = CASES[label][0]
    code, err, failure = _run(tmp_path, label)
    assert failure is None, f"{label}: {failure}"
    assert "Traceback" not in err, f"{label}: {err[-800:]}"
    assert code in (0, 1, 2), (label, code, err[-500:])
    if code == 2:
        errors = [line for line in err.splitlines() if line.startswith("gfbopt: error:")]
        assert len(errors) == 1, (label, err[-800:])
    if expect == REFUSE:
        assert code == 2, f"{label}: an impossible input was answered (exit {code}) " \
                          f"{err.strip()[-300:]!r}"


@pytest.mark.parametrize("label", FAST)
def test_fast_subset_of_impossible_inputs(tmp_path, label):
    _check(tmp_path, label)


@pytest.mark.slow
@pytest.mark.parametrize("label", sorted(set(CASES) - set(FAST)))
def test_every_impossible_input(tmp_path, label):
    _check(tmp_path, label)


def test_the_set_has_the_breadth_asked_for():
    assert len(CASES) >= 400
    assert set(FAST) <= set(CASES) and len(FAST) >= 30
    kinds = {label.split()[0].split(".")[0].split("[")[0] for label in CASES}
    assert {"rotor", "bore", "pads", "zones", "capacity", "design"} <= kinds
    assert sum(expect == REFUSE for expect, *_ in CASES.values()) >= 0.8 * len(CASES)
