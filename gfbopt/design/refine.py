"""The converged search: the evolutionary front, then a constrained local refinement of its
best design, stopped on convergence (method ``nsga2_refine`` of :mod:`.search`).

Stage 1, ``search``: pymoo NSGA-II for ``generations`` generations of ``population`` designs
(:class:`~.search.NSGA2Proposer`): the front, and a feasible start.

Stage 2, ``refinement``: a pattern search on the FIRST objective (in minimisation form; for
the rotor study the first onset, maximised) in the unit cube of the variables, from the best
feasible design of everything evaluated so far (the least-violating one if none is
feasible), with an extreme barrier (an infeasible or failed design never replaces a feasible
centre).  Each iteration, at step ``h`` (unit-cube coordinates, a fraction of every
variable's range):

1. *poll*: the 2d designs x ± h e_i (a side that would leave [0, 1] is clipped to the bound,
   and skipped when that is the centre itself) — one batch, evaluated in parallel;
2. *model step*: when every poll design has finite values, a separable quadratic model of
   the objective and of every constraint from the poll (gradient and diagonal curvature by
   the three values along each axis; gradient only where one side exists), and its minimum
   inside the box |d_i| ≤ h, 0 ≤ x + d ≤ 1, every modelled constraint kept 1e-3 of a step's
   change inside its limit (scipy's SLSQP, from d = 0); the designs x + d and x + d/2 are
   asked as one batch.  The poll alone stalls on a limit that is not parallel to an axis
   (every axis direction either breaks it or worsens the objective) and creeps along a
   curved one; the model step slides along it.  (In the generalised pattern search of
   Torczon (SIAM J. Optim. 7 (1997) 1-25) and Audet & Dennis (SIAM J. Optim. 13 (2002)
   889-903) this is a *search step*: any trial point may be tried besides the poll without
   losing the poll's convergence.)
3. the best trial, if feasible and better than the centre by more than ``improvement`` ×
   |f(centre)|, becomes the centre (h kept); otherwise h is halved.

**Convergence rule**: converged when h < ``step_tolerance``, i.e. the last full poll at
step 2h and its model step found no design better than the best by more than
``improvement`` (0.1 % by default: the first onset's own resolution,
:data:`~gfbopt.design.rotor_objectives.ONSET_TOLERANCE`).  **Budget**: ``budget`` is the
hard maximum of designs asked over both stages; when it is reached first, the status is
``"not converged: budget N reached"`` and the best so far is reported as such.

Measured (tests/unit/test_search_convergence.py, seeds 0-2): a tilted valley, the pinched
bowl (optimum on an oblique limit) and a linear objective on a curved and an axis limit are
reached to ≤ 2.3e-5 in the unit cube with ``step_tolerance`` 1e-4 in 90-330 designs; the
blower's bearing pair (4 variables, 36x10) converges in 89-105 designs with 0.1 % and 1/64,
three seeds within 0.12 % (results/benchmarks/main_job.json, benchmarks/
rotor_design_reference.py).

Deterministic: every proposal depends only on the seed and on the values told (SLSQP from
d = 0 is deterministic), so a killed run, resumed from the store,
asks the same designs and evaluates only those it does not hold — in either stage.
"""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

from .problem import FAILED_VIOLATION, DesignProblem


def _merit(f: float, g: np.ndarray) -> tuple:
    """Sort key: feasible designs first by objective, then the others by total violation."""
    if np.all(g <= 0.0) and math.isfinite(f):
        return (0, f)
    return (1, float(np.sum(np.maximum(g, 0.0))))


class RefineProposer:
    """``first_stage`` (the ask/tell of NSGA-II for ``generations`` × ``population``
    designs, :func:`gfbopt.design.search.proposer`), then the pattern search of the module
    docstring; ask/tell on the unit cube.  ``stage`` names the stage of the batch
    last asked; ``status`` the convergence status (None while running)."""

    def __init__(self, problem: DesignProblem, settings, first_stage):
        self._settings = settings
        self._d = problem.dimension
        self._global = first_stage      # ask/tell of stage 1 (its own budget)
        self._left = settings.budget
        self._history: dict = {}            # tuple(x) -> (f, g)
        self._asked: Optional[np.ndarray] = None
        self._phase = "global"              # global -> poll -> model -> ... -> done
        self._centre = None
        self._h = settings.first_step
        self._poll: list = []
        self._trials: list = []
        self.stage = "search"
        self.status: Optional[str] = None
        self.steps: list = []               # (evaluations asked, h, best f) per iteration

    # ---------------------------------------------------------------- ask / tell
    def ask(self) -> Optional[np.ndarray]:
        if self._phase == "global":
            X = self._global.ask()
            if X is not None:
                self.stage = "search"
                return self._take(X)
            self._start()
        while self._phase in ("poll", "model"):
            if self._left <= 0:
                self.status = f"not converged: budget {self._settings.budget} reached"
                self._phase = "done"
                return None
            X = self._poll_designs() if self._phase == "poll" else self._model_design()
            if X is None:                   # nothing new to ask: decide from history
                self._advance()
                continue
            self.stage = "refinement"
            return self._take(X[: self._left])
        return None

    def tell(self, F: np.ndarray, G: np.ndarray) -> None:
        for x, f, g in zip(self._asked, F, G):
            self._history[tuple(x)] = (float(f[0]), np.asarray(g, float))
        if self.stage == "search":
            self._global.tell(F, G)
        else:
            self._advance()

    def _take(self, X: np.ndarray) -> np.ndarray:
        self._asked = np.asarray(X, float)
        self._left -= len(self._asked)
        return self._asked

    # ---------------------------------------------------------------- the pattern search
    def _start(self) -> None:
        best = min(self._history, key=lambda x: _merit(*self._history[x]), default=None)
        if best is None:
            self._phase, self.status = "done", "not converged: nothing evaluated"
            return
        self._centre = np.array(best)
        self._phase = "poll"
        self._trials = []

    def _value(self, x) -> tuple:
        return self._history[tuple(x)]

    def _poll_designs(self) -> Optional[np.ndarray]:
        """The poll around the centre at step h; only the designs not yet evaluated are
        asked (None: all known, the caller decides at once)."""
        c, h = self._centre, self._h
        points = []
        for i in range(self._d):
            for sign in (1.0, -1.0):
                x = c.copy()
                x[i] = min(max(c[i] + sign * h, 0.0), 1.0)
                if x[i] != c[i]:
                    points.append(x)
        self._poll = points
        self._trials = list(points)
        new = [x for x in points if tuple(x) not in self._history]
        unique = list({tuple(x): x for x in new}.values())
        return np.array(unique) if unique else None

    def _model_design(self) -> Optional[np.ndarray]:
        trial = _model_step(self._centre, self._h, self._value(self._centre), self._poll,
                             self._history) or []
        self._trials += trial
        new = list({tuple(x): x for x in trial if tuple(x) not in self._history}.values())
        return np.array(new) if new else None

    def _advance(self) -> None:
        """After the poll: ask the model step; after the model step: move or halve."""
        if self._phase == "poll":
            self._phase = "model"
            return
        f0, g0 = self._value(self._centre)
        key0 = _merit(f0, g0)
        trials = [x for x in self._trials if tuple(x) in self._history]
        best = min(trials, key=lambda x: _merit(*self._value(x)), default=None)
        better = False
        if best is not None:
            key = _merit(*self._value(best))
            if key0[0] == 1:
                better = key < key0
            else:
                better = key[0] == 0 and key[1] < f0 - self._settings.improvement * abs(f0)
        if better:
            self._centre = np.array(best)
        else:
            self._h /= 2.0
        self.steps.append((self._settings.budget - self._left, self._h,
                           self._value(self._centre)[0]))
        if self._h < self._settings.step_tolerance:
            self._phase = "done"
            self.status = (f"converged: step {self._h:.3g} < {self._settings.step_tolerance:g}"
                           f" of each range, no design better by more than "
                           f"{self._settings.improvement:g} of the best")
            return
        self._phase = "poll"


def _model_step(centre, h: float, value: tuple, poll: list, history: dict):
    """The model step of the module docstring: two trial designs, the step d of the
    quadratic model and d/2 (None when the poll has a failed or non-finite design, or the
    model predicts no decrease)."""
    from scipy.optimize import minimize

    f0, g0 = value
    if not poll or not math.isfinite(f0) or g0[-1] > 0.0 \
            or not np.all(np.abs(g0[:-1]) < FAILED_VIOLATION):
        return None
    d, m = len(centre), len(g0) - 1
    grad_f, curv_f = np.zeros(d), np.zeros(d)
    grad_g, curv_g = np.zeros((m, d)), np.zeros((m, d))
    for i in range(d):
        side = {}
        for x in poll:
            if x[i] != centre[i] and np.all(np.delete(x, i) == np.delete(centre, i)):
                side[bool(x[i] > centre[i])] = x
        if not side:
            return None
        values = {s: history.get(tuple(x)) for s, x in side.items()}
        if any(v is None or not math.isfinite(v[0]) or v[1][-1] > 0.0
               or not np.all(np.abs(v[1]) < FAILED_VIOLATION) for v in values.values()):
            return None
        if len(side) == 2:
            up, down = side[True][i] - centre[i], centre[i] - side[False][i]
            fu, fd = values[True][0], values[False][0]
            gu, gd = values[True][1][:-1], values[False][1][:-1]
            # the quadratic through the three values (unequal sides at a bound)
            grad_f[i] = (fu - f0) / up * down / (up + down) + (f0 - fd) / down * up / (up + down)
            curv_f[i] = 2.0 * ((fu - f0) / up - (f0 - fd) / down) / (up + down)
            grad_g[:, i] = (gu - g0[:-1]) / up * down / (up + down) \
                + (g0[:-1] - gd) / down * up / (up + down)
            curv_g[:, i] = 2.0 * ((gu - g0[:-1]) / up - (g0[:-1] - gd) / down) / (up + down)
        else:
            (s, x), = side.items()
            step = x[i] - centre[i]
            grad_f[i] = (values[s][0] - f0) / step
            grad_g[:, i] = (values[s][1][:-1] - g0[:-1]) / step
    if not np.any(grad_f):
        return None
    scale = float(np.max(np.abs(grad_f))) * h            # objective change of one step
    model_f = lambda s: float(grad_f @ s + 0.5 * curv_f @ (s * s)) / scale  # noqa: E731
    # each constraint model in units of its change over one step, kept 1e-3 of that inside
    # its limit (SLSQP ends a hair outside an active one, which the barrier would refuse)
    unit = [max(float(np.max(np.abs(grad_g[j]))) * h, 1e-300) for j in range(m)]
    cons = [{"type": "ineq",
             "fun": lambda s, j=j: -(g0[j] + grad_g[j] @ s + 0.5 * curv_g[j] @ (s * s))
             / unit[j] - 1e-3}
            for j in range(m)]
    bounds = [(max(-h, -c), min(h, 1.0 - c)) for c in centre]
    r = minimize(model_f, np.zeros(d), method="SLSQP", bounds=bounds, constraints=cons,
                 options={"maxiter": 100, "ftol": 1e-12})
    s = np.clip(np.asarray(r.x, float), [b[0] for b in bounds], [b[1] for b in bounds])
    if not model_f(s) < 0.0 or any(c["fun"](s) < -1e-3 for c in cons):
        return None
    return [np.clip(centre + s, 0.0, 1.0), np.clip(centre + 0.5 * s, 0.0, 1.0)]
