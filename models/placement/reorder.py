"""Solving again with the objects of broken constraints first (not in the paper): a step-wise placer puts each object
where it is best among those placed before it, so an object placed late can find the floor it needs taken (in the
iTHOR room FloorPlan313 the chair belongs in the middle, near the desk, where the bed stands), and the polish, which
moves one object or one small group at a time, cannot undo a start like that.

`broken_first`: when the repaired episode leaves a constraint broken, the placer solves once more, from the same random
state, with the objects of the broken constraints and their relations' targets placed before all others (but fixed
ones), unless that order is the one it had (in the crowded rooms of `dense` every object is in a broken constraint).
The new steps get every repair only if they meet as many constraints as the first episode's steps did (on the
diagnosis plans every episode kept passed that screen, and 14 of the 24 not kept failed it). The new episode is kept
if it meets more constraints, its energy rises by at most the polish's `ALLOWANCE`, it places every object the first
one placed and it leaves no more task objects out of the robot's reach; its steps are then shown after the first
one's, each giving that reason before its own, the first marked as a `restart` (the studio empties the room there).
Measured in `app/bench/results/plan2place/broken-first/` (README, Plan2Place).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

from models.placement.base import PlacementStep, StepObserver
from models.placement.greedy import Episode
from models.placement.polish import ALLOWANCE, TOL, Standing, broken, met_among

ROUNDS = 1  # solves again at most this often (0: never)
AGAIN = "solved again with {} placed first"  # the reason shown on a kept episode's steps

Steps = Callable[[list[str], StepObserver], Episode]  # (ids to place first, observer) -> the episode's steps made
Repair = Callable[[Episode, StepObserver], object]  # the repairs (models.placement.repair.repair)


def met(ep: Episode) -> int:
    """Constraints met by the episode's layout (between placed objects)."""
    return met_among(ep, ep.placed, {p.id for p in ep.placed})


def better(new: Episode, old: Episode) -> bool:
    """The module's rule: more constraints met, within the allowance, nothing dropped, no task object walled off."""
    now, then = Standing(new), Standing(old)
    return (met(new) > met(old) and now.energy <= then.energy + ALLOWANCE + TOL
            and {p.id for p in old.placed} <= {p.id for p in new.placed} and now.out <= then.out)


def first_ids(ep: Episode) -> list[str]:
    """The objects of the broken constraints and the targets of their relations, in the plan's order."""
    objects, ids = ep.problem.constraints.objects, set(broken(ep))
    ids |= {c.target for oid in list(ids) for c in objects[oid].relations}
    return [o.id for o in ep.problem.plan.objects if o.id in ids and o.id not in ep.problem.fixed]


def broken_first(ep: Episode, repair: Repair, again: Steps, observer: StepObserver | None = None) -> Episode:
    """`ep`'s steps `repair`ed, or the episode solved again with the objects of broken constraints first if it is
    `better` (see the module). `again` makes a new episode's steps; it is repaired only if its steps meet as many
    constraints as `ep`'s did (a screen: the repairs cost about as much as the steps)."""
    stepped = met(ep)
    repair(ep, observer)
    best = ep
    for _ in range(ROUNDS):
        first = first_ids(best)
        if not first or best.problem.reordered(first) == best.problem.order:
            break
        steps: list[PlacementStep] = []
        new = again(first, steps.append)
        if met(new) < stepped:
            break
        repair(new, steps.append)
        if not better(new, best):
            break
        best, why = new, AGAIN.format(", ".join(first))
        for k, step in enumerate(steps if observer is not None else ()):
            observer(dataclasses.replace(step, why=f"{why}; {step.why}" if step.why else why, restart=k == 0))
    return best
