"""Solving again with every task object kept reachable (not in the paper): in a crowded room the floor left is
mostly the robot's way, so placing every object can cut a task object off (the fridge of "put a chilled bread on
the counter" behind a chair), and the repairs, which move one object or a small group at a time, cannot open a way
through a room that full.

`solve_keeping`: when the repaired episode leaves a task object out of the robot's reach (placed and cut off, or
not placed), the placer solves once more from the same random state with `kept_step`: an object whose chosen pose
would cut a task object off is left out, with the reason `WALLS`; a task object or a fixed one (a designer's) is
always placed. The new episode is repaired (the pass that places the left-out objects leaves those alone) and kept
if it leaves fewer task objects out of reach at a lower energy: the judge's, which charges each object left out 8 / n
and each task object out of reach through E_nav, so it decides case by case whether a chair or the fridge's reach
weighs more. Where that solve leaves objects out for reach, it runs once more with those objects placed first (a
counter placed after the fridge may find no pose that leaves the fridge reachable, and the fridge one that leaves the
counter room); that episode replaces it if it leaves no more task objects out of reach at a lower energy
(`walls-first/`). The kept episode's steps are shown after the first one's, each giving its reason before its own,
the first marked as a `restart`. Going back a few steps to find such an object a pose that keeps the way open (as
models.placement.backtrack does for an object with no legal pose) placed a little more on the diagnosis plans, at a
higher energy and a quarter more time: not kept. Measured in `app/bench/results/plan2place/reach-kept/` (README,
Plan2Place).
"""

from __future__ import annotations

import collections
import dataclasses
from collections.abc import Callable

import numpy as np

from models.placement import backtrack as bt
from models.placement.base import PlacementStep, StepObserver
from models.placement.greedy import Choose, Episode, Options
from models.placement.polish import Standing
from models.placement.reorder import Repair

WALLS = "left out: each of its poses would cut a task object off from the robot"  # a left-out object's reason
AGAIN = "solved again keeping every task object reachable"  # the reason shown on a kept episode's steps
FIRST = ", with {} placed first"  # added to it where the objects left out for reach were placed first

Steps = Callable[[list[str], StepObserver], Episode]  # (ids to place first, observer) -> steps made with `kept_step`


def out_of_reach(ep: Episode) -> int:
    """Task objects the robot cannot reach: placed and cut off, or not placed (as Key_NAV counts them)."""
    return len(ep.reach.unreachable(ep.placed)) + sum(oid in ep.reach.task for oid in ep.failed)


def kept_step(ep: Episode, opts: Options, choose: Choose, rng: np.random.Generator,
              steps: collections.deque[bt.Taken]) -> tuple[Episode, collections.deque[bt.Taken], list[PlacementStep]]:
    """`backtrack.step`, but an object other than a task object or a fixed one whose pose would cut one more task
    object off is left out instead, with the reason `WALLS` (see the module)."""
    if not len(opts.feasible) or opts.obj.id in ep.reach.task or opts.obj.id in ep.problem.fixed:
        return bt.step(ep, opts, choose, rng, steps)
    before, cut = ep.fork(), len(ep.reach.unreachable(ep.placed))
    record = bt.take(ep, opts, choose, rng, steps)
    if len(ep.reach.unreachable(ep.placed)) <= cut:
        return ep, steps, [record]
    steps.pop()
    record = bt.take(before, dataclasses.replace(opts, feasible=opts.feasible[:0]), choose, rng, steps)
    before.failed[opts.obj.id] = WALLS
    return before, steps, [dataclasses.replace(record, why=WALLS)]


def better(new: Episode, old: Episode) -> bool:
    """The module's rule: fewer task objects out of reach, at a lower energy."""
    return out_of_reach(new) < out_of_reach(old) and Standing(new).energy < Standing(old).energy


def solve_keeping(ep: Episode, repair: Repair, again: Steps, observer: StepObserver | None = None) -> Episode:
    """`ep` (repaired), or the episode solved again by `again` with every task object kept reachable and repaired, if
    it is `better`; where that one leaves objects out for reach, solved once more with them placed first (see the
    module)."""
    if not out_of_reach(ep):
        return ep
    new, steps, why = *_solved(again, repair, []), AGAIN
    if walls := [oid for oid, reason in new.failed.items() if reason == WALLS]:
        third, third_steps = _solved(again, repair, walls)
        if out_of_reach(third) <= out_of_reach(new) and Standing(third).energy < Standing(new).energy:
            new, steps, why = third, third_steps, AGAIN + FIRST.format(", ".join(walls))
    if not better(new, ep):
        return ep
    for k, step in enumerate(steps if observer is not None else ()):
        observer(dataclasses.replace(step, why=f"{why}; {step.why}" if step.why else why, restart=k == 0))
    return new


def _solved(again: Steps, repair: Repair, first: list[str]) -> tuple[Episode, list[PlacementStep]]:
    """A repaired reach-kept episode with the objects of `first` placed first, and its steps."""
    steps: list[PlacementStep] = []
    ep = again(first, steps.append)
    repair(ep, steps.append)
    return ep, steps
