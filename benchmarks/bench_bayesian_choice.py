"""Which Bayesian optimiser for gfbopt's single-objective design option (a one-off choice).

Compares, on cheap 3-variable test functions with a budget of 32 evaluations (the budget
``../shared/DESIGN_NOTES.md`` measured on a real gfbopt objective, 1.5–6.6 s an evaluation):

* scikit-optimize 0.10.2 ``Optimizer`` (GP + EI; the library DESIGN_NOTES measured);
* bayesian-optimization 3.4 (GP + EI, scikit-learn's GaussianProcessRegressor);
* optuna 5.0 ``TPESampler`` (multivariate TPE; optuna's GPSampler needs torch, +950 MB);
* Sobol sampling (scipy) as the floor.

Measured: the best value reached after 16 and 32 evaluations (mean over seeds, as a
fraction of the known optimum of a positive merit, or the simple regret of Hartmann-3) and the
optimiser's own time per ask/tell step (the evaluations here cost nothing, so this is pure
overhead).  Needs the three libraries (not gfbopt dependencies)::

    python -m venv ../bo-venv && ../bo-venv/bin/pip install numpy scipy optuna \\
        bayesian-optimization scikit-optimize
    ../bo-venv/bin/python benchmarks/bench_bayesian_choice.py   # -> results/benchmarks/

The JSON goes to ``results/benchmarks/bayesian_choice.json``.  gfbopt's own Bayesian option
(:mod:`gfbopt.design.search`, this library's GP + EI with constraints) and the cost of its
acquisition settings are measured in ``benchmarks/bench_optimiser.py``.
"""
from __future__ import annotations

import json
import math
import os
import platform
import sys
import time
import warnings
from pathlib import Path

import numpy as np

BUDGET = 32
STARTUP = 8
SEEDS = (0, 1, 2, 3, 4)

# Hartmann-3 (Dixon & Szegö 1978): 4 local minima on [0, 1]^3, global min -3.86278
_A = np.array([[3.0, 10, 30], [0.1, 10, 35], [3.0, 10, 30], [0.1, 10, 35]])
_P = 1e-4 * np.array([[3689, 1170, 2673], [4699, 4387, 7470], [1091, 8732, 5547],
                      [381, 5743, 8828]])
_C = np.array([1.0, 1.2, 3.0, 3.2])


def hartmann3(x) -> float:
    """To MAXIMISE: minus Hartmann-3 (optimum 3.86278 at (0.1146, 0.5556, 0.8525))."""
    x = np.asarray(x, float)
    return float(np.sum(_C * np.exp(-np.sum(_A * (x - _P) ** 2, axis=1))))


def onset_like(x) -> float:
    """A positive merit shaped like an onset speed over (clearance, preload, compliance) in
    unit coordinates: rising towards one bound of x0, an interior optimum in x1, a weak,
    slightly wavy dependence on x2 (the bump foil).  Optimum found by a dense scan below."""
    x0, x1, x2 = x
    return float(1e4 * (1.0 + 0.5 * (1 - x0) ** 1.5 + 0.8 * x1 * math.exp(-2.5 * x1 ** 2)
                        + 0.04 * math.sin(6.0 * x2) + 0.03 * x2))


FUNCTIONS = {"hartmann3": (hartmann3, 3.86278), "onset_like": (onset_like, None)}


def _dense_optimum(f) -> float:
    g = np.linspace(0, 1, 81)
    X = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    return max(f(x) for x in X)


def run_skopt(f, seed):
    from skopt import Optimizer

    opt = Optimizer([(0.0, 1.0)] * 3, base_estimator="GP", acq_func="EI",
                    n_initial_points=STARTUP, random_state=seed)
    best, trace, t = -math.inf, [], 0.0
    for _ in range(BUDGET):
        t0 = time.perf_counter()
        x = opt.ask()
        t += time.perf_counter() - t0
        y = f(x)
        t0 = time.perf_counter()
        opt.tell(x, -y)
        t += time.perf_counter() - t0
        best = max(best, y)
        trace.append(best)
    return trace, t / BUDGET


def run_bayes_opt(f, seed):
    from bayes_opt import BayesianOptimization, acquisition

    opt = BayesianOptimization(f=None, pbounds={f"x{k}": (0.0, 1.0) for k in range(3)},
                               acquisition_function=acquisition.ExpectedImprovement(xi=0.01),
                               random_state=seed, verbose=0, allow_duplicate_points=True)
    rng = np.random.default_rng(seed)
    best, trace, t = -math.inf, [], 0.0
    for k in range(BUDGET):
        t0 = time.perf_counter()
        if k < STARTUP:
            p = {f"x{j}": float(v) for j, v in enumerate(rng.random(3))}
        else:
            p = opt.suggest()
        t += time.perf_counter() - t0
        y = f([p[f"x{j}"] for j in range(3)])
        t0 = time.perf_counter()
        opt.register(params=p, target=y)
        t += time.perf_counter() - t0
        best = max(best, y)
        trace.append(best)
    return trace, t / BUDGET


def run_optuna(f, seed):
    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    sampler = optuna.samplers.TPESampler(seed=seed, n_startup_trials=STARTUP,
                                         multivariate=True)
    study = optuna.create_study(direction="maximize", sampler=sampler)
    dist = {f"x{k}": optuna.distributions.FloatDistribution(0.0, 1.0) for k in range(3)}
    best, trace, t = -math.inf, [], 0.0
    for _ in range(BUDGET):
        t0 = time.perf_counter()
        trial = study.ask(dist)
        t += time.perf_counter() - t0
        y = f([trial.params[f"x{k}"] for k in range(3)])
        t0 = time.perf_counter()
        study.tell(trial, y)
        t += time.perf_counter() - t0
        best = max(best, y)
        trace.append(best)
    return trace, t / BUDGET


def run_sobol(f, seed):
    from scipy.stats import qmc

    X = qmc.Sobol(3, scramble=True, seed=seed).random(BUDGET)
    trace = np.maximum.accumulate([f(x) for x in X]).tolist()
    return trace, 0.0


RUNNERS = {"scikit-optimize GP+EI": run_skopt, "bayesian-optimization GP+EI": run_bayes_opt,
           "optuna TPE (multivariate)": run_optuna, "Sobol sampling": run_sobol}


def main() -> None:
    warnings.filterwarnings("ignore")
    out = {"budget": BUDGET, "startup_points": STARTUP, "seeds": list(SEEDS), "functions": {},
           "python": sys.version.split()[0], "machine": platform.machine(),
           "load_average": os.getloadavg()}
    for name, (f, known) in FUNCTIONS.items():
        best = known if known is not None else _dense_optimum(f)
        res = {"optimum": best}
        for label, run in RUNNERS.items():
            traces, overheads = [], []
            for seed in SEEDS:
                trace, overhead = run(f, seed)
                traces.append(trace)
                overheads.append(overhead)
            tr = np.array(traces)
            res[label] = {
                "fraction_of_optimum_after_16": float(np.mean(tr[:, 15]) / best),
                "fraction_of_optimum_after_32": float(np.mean(tr[:, 31]) / best),
                "worst_seed_fraction_after_32": float(np.min(tr[:, 31]) / best),
                "overhead_per_step_s": float(np.mean(overheads))}
            print(f"{name:11s} {label:30s} 16: {res[label]['fraction_of_optimum_after_16']:.4f}"
                  f"  32: {res[label]['fraction_of_optimum_after_32']:.4f}"
                  f"  worst: {res[label]['worst_seed_fraction_after_32']:.4f}"
                  f"  overhead {res[label]['overhead_per_step_s'] * 1e3:.1f} ms/step",
                  flush=True)
        out["functions"][name] = res
    import importlib.metadata as md

    out["versions"] = {p: md.version(p) for p in ("scikit-optimize", "bayesian-optimization",
                                                  "optuna", "scikit-learn", "numpy", "scipy")}
    path = Path(__file__).resolve().parents[1] / "results" / "benchmarks"
    path.mkdir(parents=True, exist_ok=True)
    (path / "bayesian_choice.json").write_text(json.dumps(out, indent=2))
    print(f"wrote {path / 'bayesian_choice.json'}")


if __name__ == "__main__":
    main()
