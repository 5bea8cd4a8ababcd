"""Finishing with an exact solve where a constraint stays broken (not in the paper): a step-wise placer and its repairs
move one object or a small group at a time, and some small rooms need every object elsewhere at once to meet their
last constraint (in the iTHOR room FloorPlan313 the bed, the desk and the shelves all stand on other walls in the
layout that meets everything). Z3's optimiser states the whole room as logic and searches the disjunctions itself, so
it finds such layouts where they exist, at 20-60 ms per object.

`finished_exactly`, the last of the repairs of every step-wise placer (greedy, look-ahead, Plan2Place): when the
repaired episode places every object, leaves a constraint broken, meets at least `MIN_MET` of the plan's constraints
and has at most `MAX_OBJECTS` objects to move, Z3 (models.placement.smt) solves the plan, the fixed objects kept,
within `WORK` of its resource count per object (not a time: a seed's layout does not hang on the machine's speed),
crowded rooms too. Its layout is kept if it places every object, leaves no more task objects out of the robot's
reach and has a lower energy (the judge's); its poses are then shown as steps after the episode's, each with the
reason `EXACT`, the first marked as a `restart`. Z3's model has no notion of reach, and which of its equally good
layouts it returns follows its seed: where the judge refuses one, Z3 solves the room again from another seed, `TRIES`
solves at most (`z3-retry/`). The time counts in PTO. The solver
`plan2place_exact` asks Z3 wherever a constraint stays broken in a small room, however many are. In a larger room
where at most `ONE_MORE_AT` constraints stay broken, Z3 moves a window of it instead (models.placement.window), its
steps shown with the reason `ONE_MORE`.

Why `MIN_MET`: where a layout meets under 60 % of its constraints the room is over-constrained (in the opt-in solver's
bench every such run was a crowded `dense` room); there Z3 took its whole budget and found a better layout in none of
88 runs. Tried as the default first at 0.1 s per object and never in a crowded room, it failed its gate (too few rooms
changed); with 0.25 s per object, crowded rooms allowed and `MIN_MET`, its gate on fresh plans met more constraints
(+0.44 points pooled over the five sets, `unseen_a` +1.73) with no clear loss, for at most 11 % more median time.
Measured in `app/bench/results/plan2place/exact-finish/` and `exact-default/` (README, Plan2Place).
"""

from __future__ import annotations

import numpy as np

from models.placement.base import PlacementStep, StepObserver
from models.placement.formulation import PIN
from models.placement.greedy import Episode
from models.placement.polish import Standing, broken
from models.placement.reorder import met
from models.placement.window import one_more
from models.values import ConstraintPlan

MAX_OBJECTS = 9  # objects to move at most for the exact solve to run (0: never)
MIN_MET = 0.6  # share of the plan's constraints the layout must meet for the repairs' finish to run
WORK = 1_000_000  # Z3's resource count per object (its rlimit; 0.15-0.3 s of this machine's CPU)
STALL_S = 1.0  # Z3's time per object at most, should a slower machine not get through `WORK` in it
TRIES = 3  # Z3 solves of a small room at most, each from another seed, until the judge keeps one
ONE_MORE_AT = 1  # constraints broken at most for Z3 to move a window of a larger room (0: never)
EXACT = "the whole room solved exactly by Z3 meets more of its constraints"  # the reason on a kept layout's steps
ONE_MORE = "Z3 moved the objects around a broken constraint so that one more is met"  # the same, in a larger room


def small(plan: ConstraintPlan, fixed: int = 0) -> bool:
    """A room the exact solve is tried in: at most `MAX_OBJECTS` objects free to move (`fixed`: how many are not)."""
    return 0 < len(plan.objects) - fixed <= MAX_OBJECTS


def wanted(ep: Episode, min_met: float = MIN_MET) -> bool:
    """Every object placed, a constraint broken, at least `min_met` of the plan's constraints met."""
    return not ep.failed and bool(broken(ep)) and met(ep) >= min_met * ep.problem.constraints.count()


def finished_exactly(ep: Episode, seed: int, observer: StepObserver | None = None, min_met: float = MIN_MET) -> Episode:
    """`ep`, or the layout Z3 finds for its plan if it is better (see the module; `min_met`: `wanted`'s)."""
    if not wanted(ep, min_met):
        return ep
    if not small(ep.problem.plan, sum(p.id in ep.problem.fixed for p in ep.placed)):
        few = ep.problem.constraints.count() - met(ep) <= ONE_MORE_AT
        new = one_more(ep, seed, WORK, STALL_S) if few else ep
        return ep if new is ep else _shown(Standing(new), observer, ONE_MORE)
    then = Standing(ep)
    for s in tries(seed):
        new = z3_episode(ep, s)
        if new is None:
            return ep
        now = Standing(new)
        if now.out <= then.out and now.energy < then.energy:
            return _shown(now, observer, EXACT)
    return ep


def z3_episode(ep: Episode, seed: int) -> Episode | None:
    """`ep` with its plan placed as Z3 solves it from `seed`, the fixed objects kept; None where Z3 leaves an object
    out or cannot complete the kept poses (the Z3 placer then places every object afresh)."""
    from models.placement.smt import Z3Solver  # z3 loads only where it runs
    problem = ep.problem
    layout = Z3Solver(STALL_S * len(problem.plan.objects), WORK).solve(problem.plan, seed, fixed=problem.fixed or None)
    poses = {p.id: (p.x, p.z, p.rotation) for p in layout.placements}
    if layout.unplaced or not all(_same(poses[oid], pose) for oid, pose in problem.fixed.items()):
        return None
    new = ep.fork()
    new.placed = [ep.scorer.place(o, *problem.fixed.get(o.id, poses[o.id])) for o in ep.order]
    new.repaired = None
    return new


def tries(seed: int) -> list[int]:
    """The seeds of Z3's solves of a small room, `TRIES` of them: `seed`, then seeds drawn from it."""
    return [seed, *(int(s) for s in np.random.default_rng(seed).integers(2**31, size=TRIES - 1))]


def _shown(now: Standing, observer: StepObserver | None, why: str) -> Episode:
    """The layout kept (`now`'s episode) with its energy, its poses shown as steps after the episode's, each with the
    reason `why`, the first marked as a `restart`."""
    new, terms = now.ep, now.setup.terms()
    new.energy, new.terms = terms["total"], dict(terms)
    for k, p in enumerate(new.placed if observer is not None else ()):
        observer(PlacementStep(p.id, p.x, p.z, p.rotation, np.empty((0, 3)), np.empty(0), dict(terms), why,
                               restart=k == 0))
    return new


def _same(a: tuple[float, float, float], b: tuple[float, float, float]) -> bool:
    """The same kept pose: within the model's pin (`formulation.PIN`) and the layout's rounding."""
    turn, near = (a[2] - b[2]) % 360, PIN + 1e-4
    return abs(a[0] - b[0]) <= near and abs(a[1] - b[1]) <= near and min(turn, 360 - turn) < 1e-6
