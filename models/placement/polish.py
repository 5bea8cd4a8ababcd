"""Constraints' polish after the repairs (not in the paper): a step-wise placer meets an object's relations
only to the objects placed before it, and those placed later may break its global placement or leave a
relation to them unmet. Once every object is down, `polish` takes the objects with a broken constraint, most
broken first, once each, and moves one if that meets strictly more constraints at little cost elsewhere: the
layout's energy rises by at most `ALLOWANCE` and no more task objects are out of the robot's reach.

- A free move: the legal pose that meets the most of its constraints, then of lowest energy (of the
  `CHECKS` best, the first that keeps reach).
- Else a make-way move: a pose that meets more, where at most `moves.MAX_BLOCKERS` objects stand in the way,
  by their bodies or by a front clearance (the pose's or theirs; `MAKE_WAY_POSES` such poses,
  models.placement.moves.displacements); those are placed again, each where it meets the most constraints, then
  at its lowest energy. A cheap screen (the same placing by constraints alone) drops the poses that cannot meet
  more before any energy is computed, and a floor of the energy (`CandidateEnergy.floor`) those that cannot stay
  within the allowance, before each of the objects making way is placed again.

In a `crowded` room, where moves free and fill floor for one another, the objects still broken get a second round
when the first moved anything (`second-round/`). Fixed objects never move; each move is a placement step; the time
counts in PTO. Crowded rooms once tried one pose per make-way move, for speed; three pay there too now (README,
Plan2Place; `crowded-poses/`). The allowance was once 0 (the energy might not rise at all); 0.05 meets more
constraints in crowded rooms (`energy-allowance/`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache, cached_property, lru_cache

import numpy as np

from models.constraints.evaluate import Poses, placement, relation_met
from models.energy.vectorised import CandidateEnergy
from models.energy.weights import WEIGHTS
from models.geometry import SweptBoxes
from models.placement.base import PlacementStep, StepObserver
from models.placement.candidates import PlacedObject
from models.placement.greedy import Episode, hard_filter
from models.placement.moves import displacements, legal_poses, move_step
from models.placement.ties import steady
from models.values import ConstraintPlan

CHECKS = 20
MAKE_WAY_POSES = 3  # poses tried per make-way move
TOL = 1e-9  # energy: "does not rise" (float sums in another order)
ALLOWANCE = 0.05  # how much one move meeting more constraints may raise the layout's energy
MORE_MET = "meeting more of its constraints"  # a moved object's step reason
CROWDED = 0.5  # share of the floor the plan's objects cover above which a room is `crowded`


def crowded(plan: ConstraintPlan) -> bool:
    """More than `CROWDED` of the floor covered by the plan's objects: every room of the `dense` set (50-65 %)
    and 6 of the 120 iTHOR rooms of `human`; the generated sets' rooms stay under 43 %."""
    return sum(o.size.x * o.size.z for o in plan.objects) > CROWDED * plan.room.width * plan.room.depth


def met(ep: Episode, oid: str, idx: np.ndarray | None, others: list[PlacedObject]) -> np.ndarray:
    """For each pose `idx` of `oid` (indices into `ep.scorer.bodies`; None: all): how many constraints that
    involve it are met with `others` where they are (its global placement, its relations to them, theirs to
    it), as the metric counts them."""
    obj, scorer = ep.problem.plan.object(oid), ep.scorer
    objects = ep.problem.constraints.objects
    count = np.zeros(len(scorer.bodies(obj)[0]), int)
    if oid in objects:
        oc = objects[oid]
        count += scorer.placement_met(obj, oc.placement)
        by_id = {p.id: p for p in others}
        for c in oc.relations:
            if c.target in by_id:
                count += scorer.relation_met(obj, c.name, _shape(by_id[c.target]))
    for p in others:
        for c in objects[p.id].relations if p.id in objects else ():
            if c.target == oid:
                count += scorer.relation_met(obj, c.name, _shape(p), reverse=True)
    return count if idx is None else count[idx]


def _key(p: PlacedObject) -> tuple:
    return p.id, p.x, p.z, p.rotation


def broken(ep: Episode) -> list[str]:
    """Placed, movable objects with at least one constraint not met, most broken first."""
    missing = {}
    for p in ep.placed:
        if p.id in ep.problem.fixed:
            continue
        others = [q for q in ep.placed if q is not p]
        missing[p.id] = _involved(ep, p.id, others) - met_among(ep, ep.placed, {p.id})
    return sorted((i for i, n in missing.items() if n > 0), key=lambda i: -missing[i])


def _involved(ep: Episode, oid: str, others: list[PlacedObject]) -> int:
    """Constraints that involve `oid` and only placed objects (the most `met` can count)."""
    objects, ids = ep.problem.constraints.objects, {p.id for p in others}
    own = objects.get(oid)
    n = 0 if own is None else 1 + sum(c.target in ids for c in own.relations)
    return n + sum(c.target == oid for p in others if p.id in objects for c in objects[p.id].relations)


def met_among(ep: Episode, placed: list[PlacedObject], ids: set[str]) -> int:
    """Constraints met in the layout `placed` (globals, relations between placed objects) that involve one of
    `ids`: a move of `ids` changes only these."""
    objects, room = ep.problem.constraints.objects, ep.problem.plan.room
    by_id = {p.id: p for p in placed}
    n = 0
    for p in placed:
        oc = objects.get(p.id)
        mine = p.id in ids
        if oc is None:
            continue
        if mine:
            n += _placement_met(oc.placement, _shape(p), room.width, room.depth)
        for c in oc.relations:
            if c.target in by_id and (mine or c.target in ids):
                n += _relation_met(c.name, _shape(p), _shape(by_id[c.target]))
    return n


def _shape(p: PlacedObject) -> tuple[float, float, float, float, float]:
    return p.x, p.z, p.rotation, p.width, p.depth


@lru_cache(maxsize=1 << 16)
def _placement_met(name: str, shape: tuple, width: float, depth: float) -> bool:
    """Is the global placement `name` met by one pose (x, z, rotation, width, depth)? Memoised: the make-way
    moves judge the same poses again and again."""
    return bool(placement(name, Poses.one(*shape), width, depth)[1][0])


@lru_cache(maxsize=1 << 16)
def _relation_met(name: str, a: tuple, b: tuple) -> bool:
    """Is `A name B` met by the poses a and b (x, z, rotation, width, depth)? Memoised as `_placement_met`."""
    return bool(relation_met(name, Poses.one(*a), Poses.one(*b))[0])


def _legal_among(ep: Episode, oid: str, placed: list[PlacedObject], memo: dict
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(every candidate pose of `oid`, the indices of its legal ones among `placed`, how many constraints each of
    those meets); `memo` keeps them per layout, for the screen and the placing of one move share most."""
    key = (oid, tuple(_key(p) for p in placed))
    if key not in memo:
        obj = ep.problem.plan.object(oid)
        cands = ep.scorer.bodies(obj)[0]
        legal = legal_poses(ep, obj, placed, cands, ep.scorer.swept(obj))
        memo[key] = cands, legal, met(ep, oid, legal, placed)
    return memo[key]


def _place_again(ep: Episode, movers: list[str], energy: CandidateEnergy, placed: list[PlacedObject], memo: dict,
                 why: str, within: Callable[[CandidateEnergy], bool]):
    """(`placed` with `movers` placed again in order, their steps, how to make the energy set-up of the result):
    each at its legal pose meeting the most constraints, then of lowest energy (the later ones pending; `energy`:
    the set-up of `placed` with `movers[1:]` pending; `why`: the steps' reason); None if one has no legal pose, or
    if before a mover is placed the set-up fails `within` (whether its energy's floor leaves the move a chance). A
    step shows the poses meeting the most, among which the energy chose. The last set-up is made only if asked
    for: most moves are refused on the last step's energy."""
    placed, steps = list(placed), []
    for k, oid in enumerate(movers):
        if not within(energy):
            return None
        obj = ep.problem.plan.object(oid)
        cands, legal, most = _legal_among(ep, oid, placed, memo)
        if not len(legal):
            return None
        top = legal[most == most.max()]  # only these need an energy
        terms = energy.score(obj, cands[top])
        best = int(np.argmin(steady(terms["total"])))
        if k == len(movers) - 1:  # the move is judged by this step's terms
            terms = exactly(energy, obj, cands, top, terms, best)
        placed.append(ep.scorer.place(obj, *(float(v) for v in cands[top[best]])))
        steps.append(move_step(oid, placed[-1], cands, top, best, terms, why))
        if k < len(movers) - 1:
            energy = energy.after(placed[-1], pending=movers[k + 2:])
    return placed, steps, cache(lambda: energy.after(placed[-1]))


def _most_met(ep: Episode, movers: list[str], placed: list[PlacedObject], memo: dict) -> list[PlacedObject] | None:
    """`placed` with `movers` placed again, each at its first legal pose meeting the most constraints (no
    energy computed: a cheap screen of what `_place_again` can reach); None if one has no legal pose."""
    placed = list(placed)
    for oid in movers:
        cands, legal, most = _legal_among(ep, oid, placed, memo)
        if not len(legal):
            return None
        best = legal[int(np.argmax(most))]
        placed.append(ep.scorer.place(ep.problem.plan.object(oid), *(float(v) for v in cands[best])))
    return placed


@dataclass
class Move:
    """A move found for the layout: the new layout, its steps, its energy, how many task objects it leaves out
    of reach, and how to make its energy set-up (incrementally, from the one the move was scored with)."""

    placed: list[PlacedObject]
    steps: list[PlacementStep]
    energy: float
    out: int
    setup: Callable[[], CandidateEnergy]


class Standing:
    """What a move of the layout `ep.placed` may not worsen: its energy and how many task objects are out of the
    robot's reach (each computed when first asked)."""

    def __init__(self, ep: Episode):
        self.ep, self.reach = ep, ep.reach

    @cached_property
    def energy(self) -> float:
        """The layout's energy with the free space labelled exactly. Not the episode's: its last step and the
        first repairs report the fast navigation term, which misses a way cut off elsewhere (README, Plan2Place)."""
        return self.setup.terms()["total"]

    @cached_property
    def out(self) -> int:
        return len(self.reach.unreachable(self.ep.placed))

    @cached_property
    def setup(self) -> CandidateEnergy:
        """The energy set-up of the layout: the one the last repair move or pass left (`Episode.repaired`), else the
        episode's last step's, if it is of this layout; else a fresh one, which the passes after share."""
        now = [_key(p) for p in self.ep.placed]
        for made in (self.ep.repaired, lambda: self.ep.setup):
            setup = made() if made is not None else None
            if setup is not None and [_key(p) for p in setup.placed] == now:
                return setup
        setup = CandidateEnergy(self.ep.problem, self.ep.placed)
        self.ep.repaired = lambda: setup
        return setup

    def within(self, energy: CandidateEnergy) -> bool:
        """Can the objects of `energy`'s set-up, completed by the others of this layout wherever they go, stay within
        the allowance? Judged by its floor (`CandidateEnergy.floor`; TOL twice: the float sums' order)."""
        return energy.floor(self.setup) <= self.energy + ALLOWANCE + 2 * TOL

    def moved(self, move: Move) -> None:
        self.ep.placed, self.ep.energy = move.placed, move.energy
        self.ep.terms = dict(move.steps[-1].terms)  # the last step's: the moved layout's, nothing pending
        self.energy, self.out, self.ep.repaired = move.energy, move.out, cache(move.setup)
        self.__dict__.pop("setup", None)

    def take(self, move: Move, moved: list[str], observer: StepObserver | None) -> None:
        """`move` made: the layout follows it, its objects join `moved` and the observer sees each of its steps."""
        self.moved(move)
        moved += [s.object_id for s in move.steps]
        for step in move.steps if observer is not None else ():
            observer(step)


def free_move(ep: Episode, now: Standing, obj, others: list[PlacedObject], cands: np.ndarray, legal: np.ndarray,
              gain: np.ndarray, setup: CandidateEnergy, why: Callable[[PlacedObject], str],
              accept: Callable[[PlacedObject], bool] = lambda _: True, allowance: float = 0.0) -> Move | None:
    """Move `obj` alone (`others` where they are; `setup`: their energy set-up) to the first of its `legal`
    poses, most `gain` then lowest energy first (of the `CHECKS` best), that raises the energy by at most
    `allowance`, passes `accept` and leaves no more task objects out of reach; its step says `why(pose)`. None if
    none does."""
    terms = setup.score(obj, cands[legal])
    for k in np.lexsort((steady(terms["total"]), -gain[legal]))[:CHECKS]:
        if terms["total"][k] > now.energy + allowance + TOL:
            continue
        pose = ep.scorer.place(obj, *(float(v) for v in cands[legal[k]]))
        if not accept(pose):
            continue
        if (out := now.reach.out_with(others, setup.blocked, pose)) > now.out:
            continue
        judged = exactly(setup, obj, cands, legal, terms, int(k))
        if judged["total"][k] <= now.energy + allowance + TOL:
            return Move([*others, pose], [move_step(obj.id, pose, cands, legal, int(k), judged, why(pose))],
                        float(judged["total"][k]), out, lambda: setup.after(pose))
    return None


def exactly(setup: CandidateEnergy, obj, cands: np.ndarray, legal: np.ndarray, terms: dict, k: int) -> dict:
    """`terms` (of the `legal` poses) with pose `k`'s navigation term labelled exactly, and its total: what a move
    is judged by. The fast navigation term, fine for ranking poses, misses a way that the pose closes."""
    judged = {t: v.copy() for t, v in terms.items()}
    judged["nav"][k] = setup.exact_navigation(obj, cands[legal[[k]]])[0]
    judged["total"][k] = sum(WEIGHTS[t] * judged[t][k] for t in WEIGHTS)  # as `score` sums them
    return judged


def _may_gain(ep: Episode, obj, others: list[PlacedObject], now_met: int) -> np.ndarray | None:
    """The poses of `obj` that could meet more than the `now_met` constraints it meets: where its relations alone
    cannot (they are no more than that), only the poses meeting its global placement; None (every pose) otherwise.
    It spares `met` most poses of an object whose one broken constraint is its wall (`edge`, the kind left unmet
    most often)."""
    oc = ep.problem.constraints.objects.get(obj.id)
    if oc is None or _involved(ep, obj.id, others) - 1 > now_met:
        return None
    return np.flatnonzero(ep.scorer.placement_met(obj, oc.placement))


def _relocation(ep: Episode, now: Standing, oid: str) -> Move | None:
    """A move meeting more constraints than `now`, raising the energy by at most `ALLOWANCE` and leaving no more task
    objects out of reach, by a free or a make-way move of `oid` (see the module); None if none is found."""
    current = next(p for p in ep.placed if p.id == oid)
    others = [p for p in ep.placed if p is not current]
    obj = ep.problem.plan.object(oid)
    cands, body = ep.scorer.bodies(obj)
    now_met = met_among(ep, ep.placed, {oid})
    may = _may_gain(ep, obj, others, now_met)
    gain = met(ep, oid, may, others) - now_met
    better = np.flatnonzero(gain > 0) if may is None else may[gain > 0]
    if not len(better):
        return None
    # from here on only the poses that meet more (the steps' heat-map shows those)
    cands, body, gain = cands[better], body[better], gain[gain > 0]
    swept = SweptBoxes(body)
    legal = legal_poses(ep, obj, others, cands, swept, relax=False)
    setup = cache(lambda: now.setup.without(oid))  # the energy set-up with the others where they are, when first needed

    if len(legal) and (move := free_move(ep, now, obj, others, cands, legal, gain, setup(), lambda _: MORE_MET,
                                              allowance=ALLOWANCE)):
        return move
    for i, blockers in displacements(ep, obj, cands, swept, others, rank=gain, energy=setup, tries=MAKE_WAY_POSES,
                                      strips=True):
        placed = [p for p in others if p.id not in blockers]
        if not hard_filter(ep.scorer, obj, placed, cands[[i]], SweptBoxes(body[[i]]))[0][0]:
            continue
        pose = ep.scorer.place(obj, *(float(v) for v in cands[i]))
        changed = {oid, *blockers}
        was = met_among(ep, ep.placed, changed)
        memo: dict = {}
        screen = _most_met(ep, blockers, [*placed, pose], memo)
        if screen is None or met_among(ep, screen, changed) <= was:
            continue
        base = setup()
        for b in blockers:
            base = base.without(b)
        again = _place_again(ep, blockers, base.after(pose, pending=blockers[1:]), [*placed, pose], memo,
                             f"making way for {oid}", now.within)
        if again is None:
            continue
        placed, steps, final_setup = again
        new_energy = steps[-1].terms["total"]  # the last one placed again: nothing pending
        if met_among(ep, placed, changed) <= was or new_energy > now.energy + ALLOWANCE + TOL or \
                (out := len(now.reach.unreachable(placed, reachable=final_setup().reach))) > now.out:
            continue
        final = {t: np.array([v]) for t, v in steps[-1].terms.items()}  # its step shows the final layout's
        first = move_step(oid, pose, cands, np.array([i]), 0, final, MORE_MET)
        return Move(placed, [first, *steps], new_energy, out, final_setup)
    return None


def polish(ep: Episode, observer: StepObserver | None = None) -> list[str]:
    """Move objects of the finished episode `ep` whose constraints are broken, each once, most broken first,
    when a move meets more of them at little cost; in a crowded room, the objects still broken once more if that
    moved anything (see the module); the ids moved, in order."""
    moved: list[str] = []
    tried: dict[str, int] = {}  # object -> how many ids had been moved when it was last tried
    for _ in range(2 if crowded(ep.problem.plan) else 1):
        if not _round(ep, observer, moved, tried):
            break
    return moved


def _round(ep: Episode, observer: StepObserver | None, moved: list[str], tried: dict[str, int]) -> bool:
    """One round of `polish` over the objects broken now, adding the ids it moves to `moved`; whether it moved any.
    An object tried before with nothing moved since is passed over: on the same layout it would fail again."""
    now, before = Standing(ep), len(moved)
    for oid in broken(ep):
        if tried.get(oid) == len(moved):
            continue
        tried[oid] = len(moved)
        move = _relocation(ep, now, oid)
        if move is not None:
            now.take(move, moved, observer)
    return len(moved) > before
