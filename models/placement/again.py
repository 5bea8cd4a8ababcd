"""Solving again with the objects left out placed first (not in the paper): a step-wise placer fills the room in its
order, so an object that comes late may find no room left, even after `repair.make_room`, where one placed earlier
would have fitted.

`left_out_first`: while the best episode so far leaves objects out for want of room, at most `ROUNDS` times, the
placer solves again with every object left out so far placed before all others (but fixed ones), and its room-making
and access repairs run; a new episode is kept if it places more objects and reaches no fewer task objects, or places as
many and reaches more (the reach guard's test, models.placement.reach). The steps of a kept episode are shown after
the first one's. In crowded rooms (`dense`) this places as many objects as DFS at a lower energy, with more task
objects reached and fewer constraints met (README, Plan2Place; `app/bench/results/plan2place/left-out-first/`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

from models.placement.base import PlacementStep, StepObserver
from models.placement.greedy import NO_ROOM, Episode

ROUNDS = 3
AGAIN = "solved again with {} placed first"  # the reason shown on a kept episode's steps

SolveAgain = Callable[[list[str], StepObserver], Episode]  # (ids to place first, observer) -> finished episode


def reached(ep: Episode) -> int:
    """Task objects placed and within the robot's reach."""
    return sum(p.id in ep.reach.task for p in ep.placed) - len(ep.reach.unreachable(ep.placed))


def left_out(ep: Episode) -> list[str]:
    return [oid for oid, why in ep.failed.items() if why == NO_ROOM]


def left_out_first(ep: Episode, again: SolveAgain, observer: StepObserver | None = None) -> Episode:
    """The best of `ep` and the episodes solved again with the objects left out first (see the module); `again`
    solves one, with the repairs that place objects and restore access."""
    if not left_out(ep):
        return ep
    best, latest, first = ep, ep, []
    score = (len(ep.placed), reached(ep))
    for _ in range(ROUNDS):
        new = [oid for oid in left_out(latest) if oid not in first]
        if not left_out(best) or not new:
            break
        first += new
        steps: list[PlacementStep] = []
        latest = again(list(first), steps.append)
        if (n := len(latest.placed)) >= score[0] and (r := reached(latest)) >= score[1] and (n, r) != score:
            best, score = latest, (n, r)
            why = AGAIN.format(", ".join(first))
            for step in steps if observer is not None else ():
                observer(dataclasses.replace(step, why=step.why or why))
    return best
