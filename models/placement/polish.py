"""Constraint polishing after the repairs (not in the paper): a step-wise placer meets an object's relations
only to the objects placed before it, and those placed later may break its global placement or leave a
relation to them unmet. Once every object is down, `polish` moves, one at a time, the objects with a broken
constraint to the legal pose that meets the most of their constraints, and only when the move is a strict
gain in met constraints that costs nothing elsewhere: the layout's energy does not rise and no task object
falls out of the robot's reach. Fixed objects never move; each move is a placement step; its time counts
in PTO.
"""

from __future__ import annotations

import numpy as np

from models.constraints.evaluate import Poses, placement, relation, wall_clearance
from models.energy.vectorised import CandidateEnergy
from models.placement.base import StepObserver
from models.placement.candidates import PlacedObject
from models.geometry import SweptBoxes
from models.placement.greedy import Episode, candidate_bodies
from models.placement.moves import MAX_BLOCKERS, TRIES, Reach, displacements, legal_poses, move_step, scored

ROUNDS, CHECKS = 2, 20
TOL = 1e-9  # energy: "does not rise"


def met(ep: Episode, oid: str, cands: np.ndarray, others: list[PlacedObject]) -> np.ndarray:
    """For each pose of `oid` in `cands` (N, 3): how many constraints that involve it are met with `others`
    where they are (its global placement, its relations to them, theirs to it), as the metric counts them."""
    obj, room = ep.problem.plan.object(oid), ep.problem.plan.room
    poses = Poses(cands[:, 0], cands[:, 1], cands[:, 2], obj.size.x, obj.size.z)
    objects = ep.problem.constraints.objects
    count = np.zeros(len(cands), int)
    if oid in objects:
        oc = objects[oid]
        clearance = wall_clearance(poses, room.width, room.depth)
        count += placement(oc.placement, poses, room.width, room.depth, clearance=clearance)[1]
        by_id = {p.id: p for p in others}
        for c in oc.relations:
            if c.target in by_id:
                count += relation(c.name, poses, _pose(by_id[c.target]))[1]
    for p in others:
        for c in objects[p.id].relations if p.id in objects else ():
            if c.target == oid:
                count += relation(c.name, _pose(p), poses)[1]
    return count


def _pose(p: PlacedObject) -> Poses:
    return Poses.one(p.x, p.z, p.rotation, p.width, p.depth)


def _here(p: PlacedObject) -> np.ndarray:
    return np.array([[p.x, p.z, p.rotation]])


def broken(ep: Episode) -> list[str]:
    """Placed, movable objects with at least one constraint not met, most broken first."""
    missing = {}
    for p in ep.placed:
        if p.id in ep.problem.fixed:
            continue
        others = [q for q in ep.placed if q is not p]
        total = _involved(ep, p.id, others)
        missing[p.id] = total - int(met(ep, p.id, _here(p), others)[0])
    return sorted((i for i, n in missing.items() if n > 0), key=lambda i: -missing[i])


def _involved(ep: Episode, oid: str, others: list[PlacedObject]) -> int:
    """Constraints that involve `oid` and only placed objects (the most `met` can count)."""
    objects, ids = ep.problem.constraints.objects, {p.id for p in others}
    own = objects.get(oid)
    n = 0 if own is None else 1 + sum(c.target in ids for c in own.relations)
    return n + sum(c.target == oid for p in others if p.id in objects for c in objects[p.id].relations)


def met_total(ep: Episode, placed: list[PlacedObject]) -> int:
    """Constraints met in the layout `placed` (globals and relations between placed objects)."""
    return sum(_own_met(ep, p, placed) for p in placed)


def _own_met(ep: Episode, p: PlacedObject, placed: list[PlacedObject]) -> int:
    oc, room = ep.problem.constraints.objects.get(p.id), ep.problem.plan.room
    if oc is None:
        return 0
    pose = _pose(p)
    n = int(placement(oc.placement, pose, room.width, room.depth)[1][0])
    by_id = {q.id: q for q in placed}
    return n + sum(int(relation(c.name, pose, _pose(by_id[c.target]))[1][0]) for c in oc.relations if c.target in by_id)


def layout_energy(ep: Episode, placed: list[PlacedObject]) -> float:
    """The energy of the finished layout `placed` (nothing pending), as the steps report it."""
    last = placed[-1]
    terms = CandidateEnergy(ep.problem, placed[:-1], pending=()).score(ep.problem.plan.object(last.id), _here(last))
    return float(terms["total"][0])


def _place_again(ep: Episode, movers: list[str], placed: list[PlacedObject]):
    """(`placed` with `movers` placed again in order, their steps): each at its legal pose meeting the most
    constraints, then of lowest energy (the later ones pending); None if one has no legal pose."""
    placed, steps = list(placed), []
    energy = CandidateEnergy(ep.problem, placed, pending=movers[1:]) if movers else None
    for k, oid in enumerate(movers):
        obj = ep.problem.plan.object(oid)
        cands, legal, terms = scored(ep, obj, placed, energy=energy)
        if not len(legal):
            return None
        best = int(np.lexsort((terms["total"], -met(ep, oid, cands[legal], placed)))[0])
        placed.append(ep.scorer.place(obj, *(float(v) for v in cands[legal[best]])))
        steps.append(move_step(oid, placed[-1], cands, legal, best, terms))
        energy = energy.after(placed[-1], pending=movers[k + 2:])
    return placed, steps


def _relocation(ep: Episode, reach: Reach, oid: str, energy: float, n_met: int, out: int):
    """(new layout, steps, its energy) meeting more constraints than `n_met`, with no more energy than
    `energy` and no more than `out` task objects out of reach, by moving `oid` to a pose that meets more of
    its constraints: a free pose if one will do, else one where at most `MAX_BLOCKERS` objects stand in the
    way, placed again (each where it meets the most constraints, then at its lowest energy; `TRIES` such
    poses); None if no move is found."""
    current = next(p for p in ep.placed if p.id == oid)
    others = [p for p in ep.placed if p is not current]
    obj = ep.problem.plan.object(oid)
    cands, body = candidate_bodies(ep.scorer, obj)
    gain = met(ep, oid, cands, others) - int(met(ep, oid, _here(current), others)[0])
    if not (gain > 0).any():
        return None
    swept = SweptBoxes(body)
    legal = legal_poses(ep, obj, others, cands, swept, relax=False)
    legal = legal[gain[legal] > 0]
    setup = CandidateEnergy(ep.problem, others, pending=())
    if len(legal):
        terms = setup.score(obj, cands[legal])
        for k in np.lexsort((terms["total"], -gain[legal]))[:CHECKS]:
            if terms["total"][k] > energy + TOL:
                continue
            pose = ep.scorer.place(obj, *(float(v) for v in cands[legal[k]]))
            if len(reach.unreachable([*others, pose])) <= out:
                return [*others, pose], [move_step(oid, pose, cands, legal, int(k), terms)], float(terms["total"][k])
    for i, blockers in displacements(ep, obj, cands, swept, others, among=gain > 0, rank=gain, energy=setup):
        placed = [p for p in others if p.id not in blockers]
        if i not in legal_poses(ep, obj, placed, cands, swept):
            continue
        pose = ep.scorer.place(obj, *(float(v) for v in cands[i]))
        again = _place_again(ep, blockers, [*placed, pose])
        if again is None:
            continue
        placed, steps = again
        if met_total(ep, placed) <= n_met or len(reach.unreachable(placed)) > out:
            continue
        new_energy = steps[-1].terms["total"]  # the last one placed again: nothing pending
        if new_energy <= energy + TOL:
            final = {t: np.array([v]) for t, v in steps[-1].terms.items()}  # its step shows the final layout's
            return placed, [move_step(oid, pose, cands, np.array([i]), 0, final), *steps], new_energy
    return None


def polish(ep: Episode, observer: StepObserver | None = None) -> list[str]:
    """Move objects of the finished episode `ep` whose constraints are broken while a move meets more of
    them at no cost (`ROUNDS` passes over the broken ones); the ids moved, in order."""
    moved: list[str] = []
    if not ep.placed:
        return moved
    reach = Reach(ep)
    energy, n_met, out = layout_energy(ep, ep.placed), met_total(ep, ep.placed), len(reach.unreachable(ep.placed))
    for _ in range(ROUNDS):
        before = len(moved)
        for oid in broken(ep):
            move = _relocation(ep, reach, oid, energy, n_met, out)
            if move is None:
                continue
            ep.placed, steps, energy = move
            n_met, out = met_total(ep, ep.placed), len(reach.unreachable(ep.placed))
            ep.energy, ep.terms = energy, {**ep.terms, "total": energy}
            moved += [s.object_id for s in steps]
            for step in steps if observer is not None else ():
                observer(step)
        if len(moved) == before:
            break
    return moved
