"""Group moves after the constraints' polish (not in the paper): the polish moves one object at a time (with the
objects standing in its way), so a constraint whose partner stands where it cannot be met stays broken, and so
do chains (a sofa near the TV stand, a second sofa near the first, an armchair near that). Z3 and MILP place all
objects at once and meet those; `regroup` gives them a few joint moves.

For an object still broken, its group is it and its movable relation partners, breadth first along the
relations, at most `GROUP` objects. The group is taken up and placed again, one object at a time, each at its
legal pose meeting the most constraints, then of lowest energy (as the polish's make-way moves place objects
again), in the first order whose cheap screen (the same placing by constraints alone) meets more and whose
energy placing then meets more, raises the layout's energy by at most `ALLOWANCE` and leaves no more task
objects out of reach. The orders are searched depth first with a bound: the constraints met so far plus, for
each object still to place, the most it could meet with the others that stay and every relation inside the
group. At most `TRIES` objects, most broken first, per layout; fixed objects never move; each move is a
placement step and its time counts in PTO (`group-moves/` in the Plan2Place results).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from models.placement.base import StepObserver
from models.placement.candidates import PlacedObject
from models.placement.greedy import Episode, hard_filter
from models.placement.polish import ALLOWANCE, TOL, Move, Standing, _key, _place_again, broken, met, met_among

GROUP = 4  # objects in a group move
FEW = 3  # group moves are tried only in a layout with at most this many objects still broken
TRIES = 2  # objects, most broken first, whose group is tried per layout
SCREENS = 16  # objects placed by a group move's screen, at most, before it gives up
TOGETHER = "meeting more constraints together with the objects it relates to"  # a group move's step reason


def group_of(ep: Episode, oid: str) -> list[str]:
    """`oid` and its movable, placed relation partners, breadth first along the relations, at most `GROUP`."""
    objects, placed = ep.problem.constraints.objects, [p.id for p in ep.placed]
    group = [oid]
    for a in group:
        partners = [c.target for c in objects[a].relations] if a in objects else []
        partners += [b for b in placed if b in objects and any(c.target == a for c in objects[b].relations)]
        for b in partners:
            if b in placed and b not in ep.problem.fixed and b not in group and len(group) < GROUP:
                group.append(b)
    return group


class _Member:
    """One object of a group, against the objects that stay (`rest`): how many constraints each of its poses
    meets with them, and which poses are legal among them; both are kept per object placed before it."""

    def __init__(self, ep: Episode, oid: str, rest: list[PlacedObject]):
        self.ep, self.oid, self.rest = ep, oid, rest
        self.obj = ep.problem.plan.object(oid)
        self.cands = ep.scorer.bodies(self.obj)[0]
        self.count = met(ep, oid, None, rest)
        self.own = met(ep, oid, None, [])  # its global placement alone
        objects = ep.problem.constraints.objects
        self.partners = {c.target for c in objects[oid].relations} if oid in objects else set()
        self.partners |= {b for b, oc in objects.items() if any(c.target == oid for c in oc.relations)}
        self._legal: dict[tuple, np.ndarray] = {}
        self._with: dict[tuple, np.ndarray] = {}

    def _legal_among(self, placed: list[PlacedObject], strict: bool) -> np.ndarray:
        key = (tuple(_key(p) for p in placed), strict)
        if key not in self._legal:
            self._legal[key] = hard_filter(self.ep.scorer, self.obj, placed, self.cands, self.ep.scorer.swept(self.obj),
                                           strict)[0]
        return self._legal[key]

    def _met_with(self, p: PlacedObject) -> np.ndarray | int:
        """The relations between each pose and `p` that are met."""
        if p.id not in self.partners:
            return 0
        if _key(p) not in self._with:
            self._with[_key(p)] = met(self.ep, self.oid, None, [p]) - self.own
        return self._with[_key(p)]

    def most(self, before: list[PlacedObject]) -> tuple[np.ndarray, int] | None:
        """(its legal poses among `rest` and the group's objects placed `before` that meet the most, that
        count), by `legal_poses`'s rule (the front clearances relaxed only if no pose is legal with them); None
        if no pose is legal. Legality is a conjunction over the objects, so it is kept per object."""
        count = self.count + sum((self._met_with(p) for p in before), np.zeros(len(self.cands), int))
        for strict in (True, False):
            ok = self._legal_among(self.rest, strict)
            for p in before:
                ok = ok & self._legal_among([p], strict)
            idx = np.flatnonzero(ok)
            if len(idx):
                level = int(count[idx].max())
                return idx[count[idx] == level], level
        return None


def _orders(ep: Episode, group: list[str], rest: list[PlacedObject], was: int, memo: dict) -> Iterator[list[str]]:
    """The orders of `group` whose screen (each at its first legal pose meeting the most) meets more than `was`,
    depth first in permutation order, cut by the bound of the module; fills `memo` as `_place_again` reads it."""
    members = {g: _Member(ep, g, rest) for g in group}
    objects, inside = ep.problem.constraints.objects, set(group)
    relations = {g: sum(c.target in inside for c in objects[g].relations) if g in objects else 0 for g in group}
    room = {g: int(m.count.max()) + relations[g] + sum(c.target == g for h in group if h in objects
                                                        for c in objects[h].relations) for g, m in members.items()}

    def search(order: list[str], placed: list[PlacedObject], total: int) -> Iterator[list[str]]:
        left = [g for g in group if g not in order]
        if not left:
            if total > was:
                yield order
            return
        if total + sum(room[g] for g in left) <= was:
            return
        for g in left:
            key = (g, tuple(_key(p) for p in placed))
            if key not in memo:
                if len(memo) >= SCREENS:
                    return
                found = members[g].most(placed[len(rest):])
                memo[key] = None if found is None else (members[g].cands, found[0], np.full(len(found[0]), found[1]))
            if memo[key] is None:
                continue
            cands, top, most = memo[key]
            pose = ep.scorer.place(members[g].obj, *(float(v) for v in cands[top[0]]))
            yield from search([*order, g], [*placed, pose], total + int(most[0]))

    return search([], list(rest), 0)


def group_move(ep: Episode, now: Standing, oid: str) -> Move | None:
    """A move of `oid`'s group meeting more constraints (see the module), or None."""
    group = group_of(ep, oid)
    if len(group) < 2:
        return None
    rest = [p for p in ep.placed if p.id not in group]
    changed = set(group)
    was = met_among(ep, ep.placed, changed)
    memo: dict = {}
    order = next(_orders(ep, group, rest, was, memo), None)  # the first order the screen passes decides
    if order is None:
        return None
    start = now.setup  # the energy set-up of `rest`, the group pending but for the first of `order`
    for g in group:
        start = start.without(g, pending=order[1:])
    again = _place_again(ep, order, start, rest, memo, TOGETHER, now.within)
    if again is None:
        return None
    placed, steps, final_setup = again
    energy = steps[-1].terms["total"]  # the last one placed again: nothing pending
    if met_among(ep, placed, changed) <= was or energy > now.energy + ALLOWANCE + TOL or \
            (out := len(now.reach.unreachable(placed, reachable=final_setup().reach))) > now.out:
        return None
    return Move(placed, steps, energy, out, final_setup)


def regroup(ep: Episode, observer: StepObserver | None = None) -> list[str]:
    """Group moves for the first `TRIES` objects still broken after the polish (see the module); the ids moved,
    in order."""
    now, moved, left = Standing(ep), [], broken(ep)
    if len(left) > FEW:
        return moved
    for oid in left[:TRIES]:
        move = group_move(ep, now, oid)
        if move is not None:
            now.take(move, moved, observer)
    return moved
