"""Solving again from another random state where objects are left out (not in the paper): a step-wise placer's
episode, repairs and second solves included, follows from its random state (Plan2Place's candidate subsets, the
ties), and in a crowded room one state can fill the floor an object needs where another leaves it room. In the iTHOR
kitchen FloorPlan27, without this, the 2.9 m counter was left out in three of five seeds (every constraint met among
the six others) and placed in the other two.

`restarted`: while the episode leaves an object out, the placer solves the plan again, start to end (repairs and
second solves included), from another state drawn from the same seed (`salted`), `RESTARTS` times at most, each pose
drawn from the placer's own probabilities (`drawn`: a sampled episode, the policy's distribution as in training;
other states of the most probable poses alone differ only where a tie or a random candidate matters). A new episode
is kept if it places no fewer objects, leaves no more task objects out of the robot's reach and has a lower energy
(the judge's, which charges each object left out). A kept episode's steps are shown after the episode's before it,
each giving that reason before its own, the first marked as a `restart`. Where nothing is left out, nothing runs.
Measured in `app/bench/results/plan2place/restarts/` (README, Plan2Place).
"""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Callable

import numpy as np

from models.placement.base import PlacementStep, StepObserver
from models.placement.greedy import Choose, Episode, Options
from models.placement.polish import Standing
from models.placement.reach_kept import out_of_reach

RESTARTS = 2  # solves from another random state at most (0: never)
AGAIN = "solved again from another random state"  # the reason shown on a kept episode's steps

Solve = Callable[[int, StepObserver], Episode]  # (salt, observer) -> the episode solved from the state of that salt


def drawn(choose: Choose) -> Choose:
    """`choose` with its pick drawn from its own probabilities (a sampled episode: the policy's distribution as in
    training), a fixed or guarded pick kept, and a draw that would cut a task object off from the robot replaced by
    the pick."""
    def draw(ep: Episode, opts: Options, rng: np.random.Generator) -> tuple[int, np.ndarray, str]:
        pick, probs, why = choose(ep, opts, rng)
        if why or opts.obj.id in ep.problem.fixed:
            return pick, probs, why
        k = int(rng.choice(len(probs), p=probs / probs.sum()))
        return (k if k == pick or ep.keeping(opts, np.array([k]))[0] else pick), probs, why
    return draw


def salted(rng: np.random.Generator, salt: int) -> np.random.Generator:
    """Another random state, `salt` jumps ahead of `rng`'s (which it leaves as it is)."""
    return np.random.Generator(copy.deepcopy(rng.bit_generator).jumped(salt))


def better(new: Episode, old: Episode) -> bool:
    """The module's rule: no fewer objects placed, no more task objects out of reach, a lower energy."""
    return (len(new.placed) >= len(old.placed) and out_of_reach(new) <= out_of_reach(old)
            and Standing(new).energy < Standing(old).energy)


def restarted(ep: Episode, again: Solve, observer: StepObserver | None = None) -> Episode:
    """`ep`, or the last of the episodes `again` solves from other states, while an object is left out, that was
    `better` than the one before it (see the module)."""
    for salt in range(1, RESTARTS + 1):
        if not ep.failed:
            break
        steps: list[PlacementStep] = []
        new = again(salt, steps.append)
        if better(new, ep):
            ep = new
            for k, step in enumerate(steps if observer is not None else ()):
                observer(dataclasses.replace(step, why=f"{AGAIN}; {step.why}" if step.why else AGAIN,
                                             restart=k == 0))
    return ep
