"""The blower rotor's answers on a small grid, as JSON: the reference that the structure
contract's n-degree-of-freedom code must reproduce to 1e-9 (tests/verification/
test_rotor_structure_reference.py).  Regenerate only from a commit whose rotor answers are the
shipped ones:  python tests/verification/rotor_structure_reference.py OUT.json"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path


from gfbopt.inputs.grid import Grid
from gfbopt.inputs.rotor_system import load_rotor
from gfbopt.rotor.diagrams import campbell_diagram, imbalance_response
from gfbopt.rotor.supports import resolve_rotor
from gfbopt.rotor.system import SpeedLine, rotor_onsets

ROOT = Path(__file__).resolve().parents[2]
ROTOR = ROOT / "problems" / "rotors" / "blower.toml"
GRID = Grid(36, 10)
RANGE = (4000.0, 40000.0)
CAMPBELL = (6000.0, 11000.0, 16000.0)
IMBALANCE = (8000.0, 12000.0)
CROSSING_SPEEDS = (9000.0, 14000.0, 32000.0, 48000.0)


def answers() -> dict:
    system = load_rotor(ROTOR)
    rotor = resolve_rotor(system, GRID)
    line = SpeedLine(rotor)
    onsets = rotor_onsets(system, RANGE, grid=GRID, line=line, show_progress=False,
                          coarse_grid=None)
    modes = [{"label": m.label, "status": m.status, "onset_speed_rpm": m.onset_speed_rpm,
              "whirl_frequency_hz": m.whirl_frequency_hz} for m in onsets.modes]
    ref = SpeedLine(rotor, local=False)
    found = {str(s): [{"label": c.label, "inertia_scale": c.inertia_scale,
                       "whirl_ratio": c.whirl_ratio} for c in ref.crossings(s)]
             for s in CROSSING_SPEEDS}
    camp = campbell_diagram(line, CAMPBELL, show_progress=False, onsets=onsets.modes)
    resp = imbalance_response(line, IMBALANCE, show_progress=False, refine_peaks=False)
    cols = ["speed_rpm", "mode", "track_label", "shape_label", "whirl_frequency_hz",
            "log_decrement"]
    return {"modes": modes, "crossings": found,
            "campbell": camp.table[cols].to_dict(orient="records"),
            "imbalance": resp.table[["speed_rpm", "station", "amplitude_um", "phase_x_deg",
                                     "phase_y_deg"]].to_dict(orient="records")}


def close(a, b, rel: float = 1e-9, where: str = "") -> list:
    """Paths where two answers differ (numbers beyond ``rel``, relative, or 1e-12 absolute)."""
    if isinstance(a, dict):
        if set(a) != set(b):
            return [f"{where}: keys {sorted(a)} != {sorted(b)}"]
        return [e for k in a for e in close(a[k], b[k], rel, f"{where}.{k}")]
    if isinstance(a, list):
        if len(a) != len(b):
            return [f"{where}: {len(a)} items != {len(b)}"]
        return [e for k, (x, y) in enumerate(zip(a, b)) for e in close(x, y, rel, f"{where}[{k}]")]
    if isinstance(a, float) or isinstance(b, float):
        if math.isnan(a) and math.isnan(b):
            return []
        ok = abs(a - b) <= rel * max(abs(a), abs(b)) + 1e-12
        return [] if ok else [f"{where}: {a!r} != {b!r}"]
    return [] if a == b else [f"{where}: {a!r} != {b!r}"]


if __name__ == "__main__":
    out = answers()
    Path(sys.argv[1]).write_text(json.dumps(out, indent=1, default=float))
