"""The look-ahead placer (`--solver lookahead`; not in the paper, not learned): greedy's candidates, but at each step
the `LOOKAHEAD_K` of lowest immediate energy that keep the task objects within the robot's reach (the reach guard's
test) are each placed and the episode finished greedily (`Episode.judge`), and the one that ends lowest is taken;
then the same repairs as greedy and Plan2Place.

It is one step of policy improvement over greedy, computed at every step instead of learned: the judgment that
Plan2Place's training teacher makes, and that the network did not learn to predict (README, Plan2Place). Its
layouts have a lower energy than Plan2Place's on every set, for 4-7 x its time per object (13-24 ms), so it is
offered as a slower, better option, not as the default. Past its time budget (the solvers' shared rule,
`problem.time_budget`) it places like greedy.
"""

from __future__ import annotations

import time

import numpy as np

from models.placement.base import Fixed, StepObserver
from models.placement.greedy import Episode, Options, place_stepwise, tie_broken
from models.placement.problem import time_budget
from models.placement.ties import steady
from models.values import ConstraintPlan, Layout

LOOKAHEAD_K = 4  # candidates judged per step: the oracle measured (app/bench/results/plan2place/lookahead-bound)
HEAT = 0.05  # the heat-map's temperature over the judged candidates' final energies
BEST_LATER = "of its lowest-energy poses, the one after which the objects still to come fit best"


class LookaheadSolver:
    name = "lookahead"

    def __init__(self, k: int = LOOKAHEAD_K, repair: bool = True):
        """`k`: candidates judged per step (1: greedy's placing); `repair`: finish with the repairs."""
        if k < 1:
            raise ValueError(f"the look-ahead judges at least one candidate per step, not {k}")
        self.k, self.repair = k, repair

    def solve(self, plan: ConstraintPlan, seed: int = 0, time_budget_s: float | None = None,
              observer: StepObserver | None = None, fixed: Fixed | None = None) -> Layout:
        start = time.perf_counter()
        deadline = start + time_budget(plan, time_budget_s)

        def choose(ep: Episode, opts: Options, rng: np.random.Generator) -> tuple[int, np.ndarray, str]:
            k = 1 if time.perf_counter() > deadline else self.k
            judged = ep.first_kept(opts, np.argsort(tie_broken(opts, rng), kind="stable"), k)
            finals = ep.judge(opts, judged) if len(judged) > 1 else np.zeros(1)
            best = int(np.argmin(steady(finals)))
            probs = np.zeros(len(opts.feasible))
            probs[judged] = np.exp(-(finals - finals.min()) / HEAT)
            return int(judged[best]), probs / probs.sum(), BEST_LATER if best else ""

        ep = place_stepwise(plan, np.random.default_rng(seed), choose, fixed, observer, self.repair)
        return ep.layout(self.name, seed, time.perf_counter() - start)
