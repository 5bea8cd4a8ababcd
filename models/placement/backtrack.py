"""Going back a few steps when an object finds no room (not in the paper; the way DFS places more, bounded): a
step-wise placer commits each pose for good, so in a crowded room the last objects can find the floor taken by
poses that had equally good neighbours.

When the object to place has no legal pose, `backtrack` goes back one step, then two, up to `DEPTH`. It passes over
a step back whose room (the objects placed before it) has no legal pose for the object either; otherwise it tries
that step's object at its next most wanted poses (the placer's probabilities, then energy), the first `TRIES` of
those that leave one of the object's legal poses clear and keep every task object reachable, and places the objects
after it again by the placer's own choice, each kept off the last of the object's legal poses if one of its 48 most
wanted poses leaves that clear (the reach guard's way, `Episode.guarded`). It takes the first try after which the
object has a legal pose and, once placed there by the placer, leaves no more task objects out of the robot's reach
and a lower step energy than leaving it out. It runs only when an object would be left out, and tries at most
`DEPTH` x `TRIES` poses.
Measured in `app/bench/results/plan2place/backtrack/` (README, Plan2Place).
"""

from __future__ import annotations

import collections
import dataclasses

import numpy as np

from models.geometry import overlap_many
from models.placement.base import PlacementStep
from models.placement.candidates import OVERLAP_TOL
from models.placement.greedy import GUARD_TRIES, Choose, Episode, Options
from models.placement.moves import legal_poses
from models.placement.ties import steady

DEPTH = 4  # steps gone back at most (0: never)
TRIES = 6  # poses tried per step gone back
ROOM_CHECKED = 200  # how many of the object's legal poses a tried pose is checked against (the first ones)
AGAIN = "placed again to make room for {}"  # the reason on the steps done again


@dataclasses.dataclass(frozen=True)
class Taken:
    """A step as it was taken: the episode before it, its options, the placer's probabilities and its pick (None:
    the object was left out)."""

    before: Episode
    opts: Options
    probs: np.ndarray
    pick: int | None


def recent() -> collections.deque[Taken]:
    """The last `DEPTH` steps taken, the ones `backtrack` may go back to."""
    return collections.deque(maxlen=DEPTH)


def take(ep: Episode, opts: Options, choose: Choose, rng: np.random.Generator, steps: collections.deque[Taken]
         ) -> PlacementStep:
    """One step of a step-wise placer: `choose` among the legal poses of `opts` (none: the object is left out), apply
    it to `ep`, remember it in `steps`; its record."""
    before, pick, probs, why = ep.fork(), None, np.zeros(0), ""
    if len(opts.feasible):
        pick, probs, why = choose(ep, opts, rng)
    ep.apply(opts, pick)
    steps.append(Taken(before, opts, probs, pick))
    return ep.step_record(opts, pick, probs, why)


def step(ep: Episode, opts: Options, choose: Choose, rng: np.random.Generator, steps: collections.deque[Taken]
         ) -> tuple[Episode, collections.deque[Taken], list[PlacementStep]]:
    """One step of a step-wise placer, going back if `opts`'s object has no legal pose and a try gives it room: (the
    episode, its recent steps, the records of the steps taken, this object's last)."""
    found = None if len(opts.feasible) else backtrack(ep, opts, steps, choose, rng)
    return found if found is not None else (ep, steps, [take(ep, opts, choose, rng, steps)])


def backtrack(ep: Episode, opts: Options, steps: collections.deque[Taken], choose: Choose,
              rng: np.random.Generator) -> tuple[Episode, collections.deque[Taken], list[PlacementStep]] | None:
    """`opts`'s object has no legal pose in `ep`: (an episode gone back and stepped again to it, with it placed; its
    recent steps; the records of the steps done again, it last) if a try gives it room (see the module), else None."""
    left_out = ep.fork()
    left_out.apply(opts, None)
    for d in range(1, len(steps) + 1):
        back = steps[-d]
        if back.pick is None or back.opts.obj.id in ep.problem.fixed:
            continue
        scorer = back.before.scorer
        cands, body = scorer.bodies(opts.obj)
        room = body[legal_poses(back.before, opts.obj, back.before.placed, cands, scorer.swept(opts.obj))]
        if not len(room):
            continue
        for alt in _alternatives(back, room[:ROOM_CHECKED]):
            again = collections.deque(list(steps)[:-d], maxlen=DEPTH)
            twin, records = _again(back, int(alt), ep.i, choose, rng, again, room)
            if twin is not None and _better(twin, left_out):
                why = AGAIN.format(opts.obj.id)
                return twin, again, [dataclasses.replace(r, why=f"{why}; {r.why}" if r.why else why) for r in records]
    return None


def _alternatives(back: Taken, room: np.ndarray) -> np.ndarray:
    """The poses `back`'s object may be tried at instead (indices into its feasible ones), most wanted first: those
    that leave one of the boxes `room` clear and keep every task object reachable, at most `TRIES`."""
    order = np.lexsort((steady(back.opts.terms["total"]), -back.probs))
    order = order[order != back.pick]
    order = order[_clear(_bodies(back.before, back.opts, order), room).any(axis=1)][:4 * TRIES]
    return order[back.before.keeping(back.opts, order)][:TRIES] if len(order) else order


def _again(back: Taken, alt: int, until: int, choose: Choose, rng: np.random.Generator,
           steps: collections.deque[Taken], room: np.ndarray) -> tuple[Episode | None, list[PlacementStep]]:
    """`back`'s object at its feasible pose `alt`, the objects after it placed again up to and including the one at
    `until` in the order (each step added to `steps`), those before it by `choose` kept off the last of the boxes
    `room` (the legal poses of the one at `until`): (the episode, the steps' records); (None, ...) if one of them finds
    no legal pose or the room is all taken."""
    twin = back.before.fork()
    twin.apply(back.opts, alt)
    steps.append(Taken(back.before, back.opts, back.probs, alt))
    records = [twin.step_record(back.opts, alt, back.probs)]
    room = room[_clear(twin.placed[-1].body[None], room)[0]]

    def off_the_room(ep: Episode, opts: Options, rng: np.random.Generator) -> tuple[int, np.ndarray, str]:
        pick, probs, why = choose(ep, opts, rng)
        if not _clear(_bodies(ep, opts, [pick]), room).any():  # it takes the last of the room: the most wanted that
            order = np.argsort(-probs, kind="stable")[:GUARD_TRIES]  # does not, if one of the first few
            clear = _clear(_bodies(ep, opts, order), room).any(axis=1)
            pick = int(order[clear][0]) if clear.any() else pick
        return pick, probs, why

    while twin.i <= until and len(room):
        opts = twin.options()
        if not len(opts.feasible):
            return None, records
        records.append(take(twin, opts, choose if twin.i == until else off_the_room, rng, steps))
        if twin.i <= until and twin.placed:
            room = room[_clear(twin.placed[-1].body[None], room)[0]]
    return (twin, records) if twin.i > until else (None, records)


def _bodies(ep: Episode, opts: Options, ks) -> np.ndarray:
    """The boxes of the feasible poses `ks` of `opts`'s object."""
    return ep.scorer.bodies(opts.obj)[1][opts.feasible[np.asarray(ks, int)]]


def _clear(boxes: np.ndarray, room: np.ndarray) -> np.ndarray:
    """(N, M): does box n leave room box m clear?"""
    return overlap_many(boxes, room) <= OVERLAP_TOL


def _better(twin: Episode, left_out: Episode) -> bool:
    """Does `twin`, which placed the object `left_out` left out, leave no more task objects out of reach (the left-out
    ones counted), at a lower step energy?"""
    def out(e: Episode) -> int:
        return len(e.reach.unreachable(e.placed)) + sum(oid in e.reach.task for oid in e.failed)
    return twin.energy < left_out.energy and out(twin) <= out(left_out)
