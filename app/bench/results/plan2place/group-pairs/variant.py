"""Group moves whose first object's pose leaves its partners room to meet theirs: in place of
`models.placement.groups._orders`. Shipped, the screen puts each object of the group at its *first* legal pose meeting
the most constraints (and the move then at the lowest-energy one of those), whatever that does to the partners still
to come; on human-FloorPlan11 the garbage can could then meet 3 of its 4 constraints where another of the counter's
equally good poses lets it meet all 4. Here, for each object with others of the group still to place, its poses
meeting the most are narrowed to those after which the others, each on its own, can meet the most."""

import numpy as np

from models.placement import groups
from models.placement.groups import SCREENS, _Member

SHIPPED = groups._orders
SHIPPED_MOVE = groups.group_move
SPREAD = 8  # the cheap variant: at most this many of the first object's poses judged, spread over its list


def _for_the_rest(ep, members: dict, g: str, others: list[str], before: list, top: np.ndarray) -> np.ndarray:
    """The poses of `top` (indices into g's candidates) after which `others` can meet the most, summed."""
    scores = []
    if SPREAD and len(top) > SPREAD:
        top = top[np.linspace(0, len(top) - 1, SPREAD).round().astype(int)]
    for i in top:
        pose = ep.scorer.place(members[g].obj, *(float(v) for v in members[g].cands[i]))
        found = [members[h].most([*before, pose]) for h in others]
        scores.append(sum(-1_000 if f is None else f[1] for f in found))
    scores = np.asarray(scores)
    return top[scores == scores.max()]


def orders_paired(ep, group, rest, was, memo):
    """`groups._orders` with each object's poses narrowed by `_for_the_rest`."""
    members = {g: _Member(ep, g, rest) for g in group}
    objects, inside = ep.problem.constraints.objects, set(group)
    relations = {g: sum(c.target in inside for c in objects[g].relations) if g in objects else 0 for g in group}
    room = {g: int(m.count.max()) + relations[g] + sum(c.target == g for h in group if h in objects
                                                        for c in objects[h].relations) for g, m in members.items()}

    def search(order, placed, total):
        left = [g for g in group if g not in order]
        if not left:
            if total > was:
                yield order
            return
        if total + sum(room[g] for g in left) <= was:
            return
        for g in left:
            key = (g, tuple(groups._key(p) for p in placed))
            if key not in memo:
                if len(memo) >= SCREENS:
                    return
                before = placed[len(rest):]
                found = members[g].most(before)
                others = [h for h in left if h != g]
                if found is not None and others:
                    found = _for_the_rest(ep, members, g, others, before, found[0]), found[1]
                memo[key] = None if found is None else (members[g].cands, found[0], np.full(len(found[0]), found[1]))
            if memo[key] is None:
                continue
            cands, top, most = memo[key]
            pose = ep.scorer.place(members[g].obj, *(float(v) for v in cands[top[0]]))
            yield from search([*order, g], [*placed, pose], total + int(most[0]))

    return search([], list(rest), 0)


def move_fallback(ep, now, oid):
    """The cheap variant, in place of `groups.group_move`: the shipped move, and only where it finds none, the paired
    one with at most `SPREAD` poses judged per object."""
    move = SHIPPED_MOVE(ep, now, oid)
    if move is not None:
        return move
    groups._orders = orders_paired
    try:
        return SHIPPED_MOVE(ep, now, oid)
    finally:
        groups._orders = SHIPPED
