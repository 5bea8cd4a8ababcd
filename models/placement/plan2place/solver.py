"""Plan2Place behind the Solver interface: the trained policy picks, object by object, the most probable
of the candidate poses; the studio's heat-map is the policy's probability of every candidate. It runs
the shipped weights in numpy (`policy`), without importing torch."""

from __future__ import annotations

import time

import numpy as np

from models.placement.base import Fixed, StepObserver
from models.placement.plan2place.policy import Policy, place, shipped_policy, shipped_weights
from models.values import ConstraintPlan, Layout


class Plan2PlaceSolver:
    name = "plan2place"

    def __init__(self, policy: Policy | None = None, name: str | None = None, use_global: bool = True,
                 repair: bool = True, guard: bool = True, keep_reach: bool = True, exact: bool = False):
        """`policy`: another network's (e.g. `agent.fast_policy` of a checkpoint); the shipped one by default.
        `repair`: finish with the repairs (models.placement.repair); `guard`: the reach guard
        (`Episode.guarded`); `keep_reach`: with the repairs, solve again leaving out what cuts a task object off
        from the robot, if the energy finds that better (models.placement.reach_kept); `exact`: with the repairs,
        finish with Z3 over the whole room where a constraint stays broken in a small room, if that is better
        (models.placement.exact_finish)."""
        self._policy, self._use_global, self.repair, self.guard = policy, use_global, repair, guard
        self.keep_reach, self.exact = keep_reach, exact
        if name:
            self.name = name

    def solve(self, plan: ConstraintPlan, seed: int = 0, time_budget_s: float | None = None,
              observer: StepObserver | None = None, fixed: Fixed | None = None) -> Layout:
        start = time.perf_counter()
        policy, use_global = self._policy, self._use_global
        if policy is None:
            policy, use_global = shipped_policy(), shipped_weights().use_global
        ep = place(policy, plan, np.random.default_rng(seed), use_global, fixed, observer, self.repair, self.guard,
                   self.keep_reach, self.exact)
        return ep.layout(self.name, seed, time.perf_counter() - start)


def untrained_solver(repair: bool = True) -> Plan2PlaceSolver:
    """The Plan2Place network with its initial weights (seed 0), `plan2place_untrained`: what training adds is
    measured against it (with `repair` False, the placer and its guard alone)."""
    from models.placement.plan2place.agent import fast_policy, untrained_network  # torch, only here
    return Plan2PlaceSolver(fast_policy(untrained_network()), repair=repair,
                            name="plan2place_untrained" + ("" if repair else ", no repair"))
