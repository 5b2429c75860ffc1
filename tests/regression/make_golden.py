"""Regenerate the golden outputs that pin gfbopt against itself at coarse grids.

    python tests/regression/make_golden.py        # rewrites tests/regression/golden.json

Run it only when a change of numbers is intended, and review the diff of golden.json in the
same commit.  The cases cover every foil law, both films, both seam conventions, the Gümbel
force, compression-only bumps, linear coefficients and thresholds, and short RK4 transients.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent

# name: (model options, target, grid)
STATIC_CASES = {
    "rigid_periodic": (dict(bearing_number=3.0, foil="rigid", film="periodic"),
                       {"eccentricity": 0.6}, "36x10"),
    "simple_mean_seam_maxfilm": (dict(bearing_number=1.0, compliance=1.0, foil="simple",
                                      film="seam"), {"eccentricity": 0.5}, "36x10"),
    "simple_local_periodic": (dict(bearing_number=2.0, compliance=1.0, foil="simple",
                                   deflection_law="local"), {"eccentricity": 0.4}, "36x10"),
    "beam_seam_load": (dict(bearing_number=5.0, compliance=1.0, foil="beam",
                            top_foil_coefficient=1.0, film="seam"), {"load": 0.9}, "36x10"),
    "gumbel_compression_seam": (dict(bearing_number=1.0, compliance=1.0, foil="simple",
                                     film="seam", subambient="gumbel", compression_only=True),
                                {"eccentricity": 0.6}, "36x10"),
    "seam_fixed_angle": (dict(bearing_number=2.0, compliance=1.0, foil="simple", film="seam",
                              seam_angle_deg=200.0), {"eccentricity": 0.4}, "36x10"),
    "simple_mean_periodic_72": (dict(bearing_number=2.0, compliance=1.0, foil="simple"),
                                {"eccentricity": 0.4}, "72x20"),
}
LINEAR_CASES = ("rigid_periodic", "simple_mean_seam_maxfilm", "simple_local_periodic",
                "beam_seam_load", "seam_fixed_angle")
# name: (static case, mass over linear critical mass, revolutions)
TRANSIENT_CASES = {
    "simple_mean_seam_maxfilm": ("simple_mean_seam_maxfilm", 1.1, 2.0),
    "simple_local_periodic": ("simple_local_periodic", 0.9, 2.0),
    "beam_seam_load": ("beam_seam_load", 1.1, 1.0),
    "rigid_periodic": ("rigid_periodic", 1.2, 2.0),
}


def api():
    """The functions the golden outputs are computed with (one place to update on moves)."""
    from gfbopt import BearingModel, Grid, solve_static
    from gfbopt.linear import coefficients, linear_threshold, linearise
    from gfbopt.transient import integrate_orbits, transient_model
    from gfbopt.static import solver_for

    return dict(BearingModel=BearingModel, Grid=Grid, solve_static=solve_static,
                solver_for=solver_for, linearise=linearise, coefficients=coefficients,
                linear_threshold=linear_threshold, transient_model=transient_model,
                integrate_orbits=integrate_orbits)


def compute() -> dict:
    f = api()
    out = {"static": {}, "linear": {}, "transient": {}}
    solutions = {}
    for name, (opts, target, grid) in STATIC_CASES.items():
        model = f["BearingModel"](**opts)
        solver = f["solver_for"](model, f["Grid"].parse(grid))
        sol = f["solve_static"](model, solver=solver, **target)
        assert sol.success, (name, sol.message)
        solutions[name] = (sol, solver)
        out["static"][name] = {"load": sol.load, "eccentricity": sol.eccentricity,
                               "attitude_angle": sol.attitude_angle_rad, "min_film": sol.min_film,
                               "max_mean_pressure": float(sol.mean_pressure.max()),
                               "max_deflection": float(sol.deflection.max())}
    for name in LINEAR_CASES:
        sol, solver = solutions[name]
        lin = f["linearise"](sol, solver)
        c = f["coefficients"](lin, [0.0, 0.5, 1.0])
        thr = f["linear_threshold"](lin)
        out["linear"][name] = {"stiffness": c.stiffness.tolist(), "damping": c.damping.tolist(),
                               "critical_mass": thr.critical_mass,
                               "whirl_ratio": thr.whirl_ratio}
    for name, (case, ratio, revs) in TRANSIENT_CASES.items():
        sol, _ = solutions[case]
        mass = ratio * out["linear"][case]["critical_mass"]
        orbit = f["integrate_orbits"](f["transient_model"](sol), [mass], revs, kick=1e-3)
        out["transient"][name] = {"mass": mass, "x_end": float(orbit.x[0, -1]),
                                  "y_end": float(orbit.y[0, -1]),
                                  "min_film": float(np.nanmin(orbit.min_film[0])),
                                  "time_step": float(orbit.time_step)}
    return out


if __name__ == "__main__":
    (HERE / "golden.json").write_text(json.dumps(compute(), indent=1) + "\n")
    print(f"wrote {HERE / 'golden.json'}")
