"""The two search methods behind :func:`gfbopt.design.optimiser.optimise`, both ask/tell on
the unit cube of the design variables.

``nsga2`` — pymoo's constrained NSGA-II (Deb et al., IEEE Trans. Evol. Comput. 6(2) (2002)
182–197): a population evolved by simulated binary crossover and polynomial mutation,
ranked by non-domination and crowding, infeasible designs ranked by their summed constraint
violation behind every feasible one (Deb's constraint domination).  For several objectives
(the Pareto front) and for any number of variables; a generation is one batch, evaluated in
parallel.  The first population is a Latin hypercube (pymoo's LHS) with the given initial
designs (e.g. the baseline) in front.

``bayes`` — Gaussian-process Bayesian optimisation for ONE objective and few variables, where
each evaluation counts: the bayesian-optimization library (F. Nogueira et al., maintained;
scikit-learn's GaussianProcessRegressor with a Matérn-5/2 kernel) with expected improvement
weighted by the probability of meeting each constraint (Gardner et al., ICML 2014), every
constraint and the failure flag modelled by its own GP.  Start: a seeded Latin hypercube
(:mod:`gfbopt.doe.sampling`).  A batch of q > 1 points is proposed by the "kriging believer"
(each proposal is registered with the GP's own prediction before the next is chosen), so the
executors' workers are kept busy.  Why this library and these settings:
``benchmarks/bench_bayesian_choice.py`` (``results/benchmarks/bayesian_choice.json``).

``nsga2_refine`` — NSGA-II for a few generations, then a constrained pattern search of the
first objective from the best design, stopped on convergence with ``budget`` as the hard
maximum (:mod:`.refine`, which states the convergence rule).

All are deterministic for a seed: the proposals depend only on the seed and on the values
told, so a resumed run, answered from the store, asks the same designs again.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import ParameterError
from .problem import FAILED_VIOLATION, DesignProblem

METHODS = ("nsga2", "bayes", "nsga2_refine")


@dataclass(frozen=True)
class SearchSettings:
    """How to search.

    method : 'nsga2' or 'bayes' (one objective only)
    budget : number of designs asked (evaluated or answered from the store)
    population : NSGA-II population = designs per generation (nsga2)
    startup : Latin-hypercube designs before the GP proposes (bayes)
    batch : designs proposed at once (bayes; the number of workers is a good choice)
    seed : seed of every random choice (reproducible run)
    acquisition_samples, acquisition_starts : random points and L-BFGS-B starts of the
        acquisition search (bayes).  The library's default, 10,000 and 10, spends most of a
        step in the L-BFGS-B polishing (finite-difference gradients of the GP): on
        Hartmann-3 (32 designs, seeds 0-2) 5,000 random points and no polishing reached
        98.3-99.8 % of the optimum at 0.23 s a design against 1,000/2's 96.1-99.4 % at
        0.82 s (2 cores, load ~14): the default here (benchmarks/bench_optimiser.py)
    gp_restarts : restarts of the GP's hyper-parameter fit (bayes)
    generations : NSGA-II generations before the local refinement (nsga2_refine; ``budget``
        is then the hard maximum over both stages, :mod:`.refine`)
    first_step, step_tolerance : the refinement's first and last poll step, in unit-cube
        coordinates (fractions of each variable's range); converged when the step falls
        below ``step_tolerance``
    improvement : least relative improvement of the refined objective that moves the
        refinement (default 1e-3, the first onset's own resolution)
    """

    method: str = "nsga2"
    budget: int = 64
    population: int = 16
    startup: int = 8
    batch: int = 1
    seed: int = 0
    acquisition_samples: int = 5000
    acquisition_starts: int = 0
    gp_restarts: int = 5
    generations: int = 3
    first_step: float = 0.125
    step_tolerance: float = 1.0 / 64.0
    improvement: float = 1e-3

    def __post_init__(self) -> None:
        if self.method not in METHODS:
            raise ParameterError("method", self.method, f"must be one of {', '.join(METHODS)}")
        for key, low in (("budget", 1), ("population", 4), ("startup", 2), ("batch", 1),
                         ("acquisition_samples", 10), ("acquisition_starts", 0),
                         ("gp_restarts", 0)):
            value = getattr(self, key)
            if not isinstance(value, int) or isinstance(value, bool) or value < low:
                raise ParameterError(key, value, f"must be an integer >= {low}")
        if not isinstance(self.seed, int) or isinstance(self.seed, bool) or self.seed < 0:
            raise ParameterError("seed", self.seed, "must be an integer >= 0")
        if not isinstance(self.generations, int) or self.generations < 1:
            raise ParameterError("generations", self.generations, "must be an integer >= 1")
        if not 0.0 < self.step_tolerance <= self.first_step <= 0.5:
            raise ParameterError("step_tolerance", (self.step_tolerance, self.first_step),
                                 "must be 0 < step_tolerance <= first_step <= 0.5 (unit-cube "
                                 "steps)")
        if not 0.0 <= self.improvement < 0.1:
            raise ParameterError("improvement", self.improvement, "must be in [0, 0.1)")


class NSGA2Proposer:
    """pymoo NSGA-II driven by ask/tell (module docstring)."""

    def __init__(self, problem: DesignProblem, settings: SearchSettings,
                 initial: Optional[np.ndarray] = None):
        from pymoo.algorithms.moo.nsga2 import NSGA2
        from pymoo.core.problem import Problem
        from pymoo.operators.sampling.lhs import LHS

        d, p = problem.dimension, settings.population
        self._problem = Problem(n_var=d, n_obj=len(problem.objectives),
                                n_ieq_constr=len(problem.constraints) + 1,
                                xl=np.zeros(d), xu=np.ones(d))
        sampling = LHS()
        if initial is not None and len(initial):
            rng = np.random.default_rng(settings.seed)
            rest = sampling(self._problem, p, random_state=rng).get("X")
            sampling = np.vstack([np.clip(initial, 0, 1), rest])[:p]
        self._algorithm = NSGA2(pop_size=p, sampling=sampling, eliminate_duplicates=True)
        self._algorithm.setup(self._problem, termination=("n_gen", 10 ** 9),
                              seed=settings.seed, verbose=False)
        self._left = settings.budget
        self._pop = None

    def ask(self) -> Optional[np.ndarray]:
        if self._left <= 0:
            return None
        pop = self._algorithm.ask()
        if pop is None or len(pop) == 0:
            return None
        self._pop = pop[: self._left]
        self._left -= len(self._pop)
        return self._pop.get("X")

    def tell(self, F: np.ndarray, G: np.ndarray) -> None:
        from pymoo.problems.static import StaticProblem

        self._algorithm.evaluator.eval(StaticProblem(self._problem, F=F, G=G), self._pop)
        self._algorithm.tell(infills=self._pop)


class BayesProposer:
    """GP Bayesian optimisation of one objective with constraints (module docstring)."""

    def __init__(self, problem: DesignProblem, settings: SearchSettings,
                 initial: Optional[np.ndarray] = None):
        if len(problem.objectives) != 1:
            raise ParameterError("method", "bayes", f"optimises one objective; this problem "
                                 f"has {len(problem.objectives)} (use 'nsga2')")
        from ..doe.sampling import SamplePlan, Variable, sample

        self._settings = settings
        d = problem.dimension
        plan = SamplePlan(tuple(Variable(f"u{k}", 0.0, 1.0) for k in range(d)),
                          method="lhs", n=settings.startup, seed=settings.seed)
        start = sample(plan)[[f"u{k}" for k in range(d)]].to_numpy(float)
        if initial is not None and len(initial):
            start = np.vstack([np.clip(initial, 0, 1), start])[: settings.startup]
        self._start = list(start)
        self._rng = np.random.RandomState(settings.seed)
        self._X: list = []
        self._f: list = []
        self._g: list = []
        self._left = settings.budget
        self._asked: Optional[np.ndarray] = None

    def ask(self) -> Optional[np.ndarray]:
        if self._left <= 0:
            return None
        if self._start:
            n = min(len(self._start), self._left)
            X = np.array(self._start[:n])
            del self._start[:n]
        else:
            X = self._propose(min(self._settings.batch, self._left))
        self._left -= len(X)
        self._asked = X
        return X

    def tell(self, F: np.ndarray, G: np.ndarray) -> None:
        self._X += list(self._asked)
        self._f += list(F[:, 0])
        self._g += list(G)

    # ------------------------------------------------------------------ the GP step
    def _data(self):
        """Targets to MAXIMISE, standardised; constraint columns for the GPs (≤ 0 met)."""
        G = np.array(self._g)
        failed = G[:, -1] > 0
        f = np.array(self._f, float)
        worst = f[~failed].max() if (~failed).any() else 0.0
        f = np.where(failed, worst, f)          # a failed design counts as the worst seen
        y = -f
        y = (y - y.mean()) / (y.std() or 1.0)
        C = G[:, :-1]
        if C.size:
            finite = C[np.abs(C) < FAILED_VIOLATION]
            cap = max(1.0, float(finite.max()) if finite.size else 1.0)
            C = np.clip(C, -10.0, cap)          # a failed row's placeholder would swamp a GP
        if failed.any():
            C = np.hstack([C, np.where(failed, 1.0, -1.0)[:, None]])
        return y, C

    def _space(self, X, y, C):
        from bayes_opt import ConstraintModel, TargetSpace

        d, n = X.shape[1], C.shape[1]
        constraint = None
        if n:         # bayes_opt takes a scalar bound and value for a single constraint
            constraint = ConstraintModel(None, lb=-np.inf if n == 1 else np.full(n, -np.inf),
                                         ub=0.0 if n == 1 else np.zeros(n),
                                         random_state=self._rng)
        space = TargetSpace(None, {f"u{k}": (0.0, 1.0) for k in range(d)},
                            constraint=constraint, random_state=self._rng,
                            allow_duplicate_points=True)
        for x, t, c in zip(X, y, C):
            space.register(x, float(t), None if n == 0 else float(c[0]) if n == 1 else c)
        return space

    def _propose(self, q: int) -> np.ndarray:
        from bayes_opt import acquisition
        from sklearn.exceptions import ConvergenceWarning
        from sklearn.gaussian_process import GaussianProcessRegressor
        from sklearn.gaussian_process.kernels import Matern

        X = np.array(self._X)
        y, C = self._data()
        out = []
        for _ in range(q):
            gp = GaussianProcessRegressor(kernel=Matern(nu=2.5), alpha=1e-6,
                                          normalize_y=True,
                                          n_restarts_optimizer=self._settings.gp_restarts,
                                          random_state=self._rng)
            space = self._space(X, y, C)
            acq = acquisition.ExpectedImprovement(xi=0.01)
            with warnings.catch_warnings():
                # the GP's hyper-parameter fit warns when a length scale reaches its bound
                # (a flat direction, common with few points): expected, not an error
                warnings.simplefilter("ignore", ConvergenceWarning)
                x = acq.suggest(gp=gp, target_space=space,
                                n_random=self._settings.acquisition_samples,
                                n_smart=self._settings.acquisition_starts,
                                random_state=self._rng)
                x = np.clip(np.asarray(x, float), 0.0, 1.0)
                out.append(x)
                if len(out) < q:               # kriging believer for the next proposal
                    y_hat = float(gp.predict(x[None, :])[0])
                    c_hat = (np.asarray(space.constraint.approx(x[None, :]), float)
                             .reshape(1, -1)[0] if C.shape[1] else np.zeros(0))
                    X, y = np.vstack([X, x]), np.append(y, y_hat)
                    C = np.vstack([C, c_hat]) if C.shape[1] else np.zeros((len(X), 0))
        return np.array(out)


def proposer(problem: DesignProblem, settings: SearchSettings,
             initial: Optional[np.ndarray] = None):
    """The ask/tell object of ``settings.method``."""
    if settings.method == "nsga2_refine":
        import dataclasses

        from .refine import RefineProposer

        first = dataclasses.replace(settings, method="nsga2", budget=min(
            settings.budget, settings.population * settings.generations))
        return RefineProposer(problem, settings, NSGA2Proposer(problem, first, initial))
    kind = NSGA2Proposer if settings.method == "nsga2" else BayesProposer
    return kind(problem, settings, initial)

