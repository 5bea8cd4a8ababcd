"""Meeting one more constraint in a room too large for the exact finish (not in the paper): Z3 moves a window of at
most `SIZE` objects, those of the broken constraints, their relations' targets and the objects nearest them, the
rest kept where they are, so that every constraint the layout meets stays met and one more is met too.

Asked as a satisfiability question (any such layout, not the best one), Z3 answers in a few hundred milliseconds
where its optimiser, asked the best layout of the same window, worked for seconds (a probe on `unseen_a`'s rooms:
0.3 s at the median against 0.4-3 s, finding a layout in 21 of 22 windows). Which constraints the layout meets is
read off the same model with every object pinned, so that Z3's and the question's notion of a met constraint are
one. The judge decides (`reorder.better`: more constraints met by its count, energy within the polish's
allowance, nothing left out, no more task objects out of reach).
"""

from __future__ import annotations

from models.placement.greedy import Episode
from models.placement.reorder import better, first_ids

SIZE = 9  # objects Z3 may move at most (the exact finish's `MAX_OBJECTS`)


def window(ep: Episode) -> dict[str, tuple[float, float, float]]:
    """The poses of the objects kept where they are: all but the objects of the broken constraints, their relations'
    targets and those nearest them, `SIZE` in all."""
    at = {p.id: p for p in ep.placed}
    first = first_ids(ep)[:SIZE]

    def gap(oid: str) -> float:
        return min((at[oid].x - at[i].x) ** 2 + (at[oid].z - at[i].z) ** 2 for i in first)

    movable = [i for i in at if i not in ep.problem.fixed and i not in first]
    free = set(first) | set(sorted(movable, key=gap)[:SIZE - len(first)])
    return {i: (p.x, p.z, p.rotation) for i, p in at.items() if i not in free}


def one_more(ep: Episode, seed: int, work: int, stall_s: float) -> Episode:
    """`ep`, or its layout with the window moved so that one more constraint is met, if the judge finds it better
    (Z3's budget: `work` units of its resource count per object in the room, `stall_s` seconds as a guard)."""
    from models.placement.smt import met_goals, one_more_met  # z3 loads only where it runs
    now = {p.id: (p.x, p.z, p.rotation) for p in ep.placed}
    kept = window(ep)
    poses = one_more_met(ep.problem.plan, kept, met_goals(ep.problem.plan, now), seed, work * len(now),
                         stall_s * len(now))
    if poses is None:
        return ep
    new = ep.fork()
    new.placed = [ep.scorer.place(o, *kept.get(o.id, poses[o.id])) for o in ep.order]
    new.repaired = None
    return new if better(new, ep) else ep
