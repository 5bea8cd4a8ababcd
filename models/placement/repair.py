"""Repairs after the last object (not in the paper): a step-wise placer decides each object once, so what
an early choice costs later is only seen at the end. Both passes run only when something is wrong, each
move is a placement step for the observer, fixed objects never move, and their time counts in PTO.

- `make_room`: an object left out for want of room is placed where at most `MAX_BLOCKERS` placed objects
  stand in its way (fewest first, then its lowest energy; `TRIES` such poses), and those are placed again,
  largest first, each at its lowest-energy legal pose; if one finds none, the next pose is tried.
- `restore_access`: a task object placed early can have its access strip walled off by objects placed
  later (the energy's navigation term sees only the objects placed so far and is traded against the
  relations). When some task object cannot be reached from the doorway (Key_NAV's test: a free cell of
  its 0.6 m access strip connected to the doorway), up to `ROUNDS` objects are moved one at a time: an
  unreachable task object or one of the `NEAR` others nearest to them, each tried at its `CHECKS` legal
  poses of lowest energy (hard filters as when placing, the others where they are); the move that
  leaves the fewest task objects out of reach, lowest energy first, is kept if it reaches more of them.
"""

from __future__ import annotations

import numpy as np

from models.energy import navigation as nav
from models.energy.vectorised import CandidateEnergy
from models.energy.weights import ACCESS_DEPTH, WEIGHTS
from models.geometry import SweptBoxes
from models.placement.base import PlacementStep, StepObserver
from models.placement.candidates import OVERLAP_TOL, PlacedObject, front_boxes
from models.placement.greedy import NO_ROOM, Episode, candidate_bodies, hard_filter

ROUNDS, NEAR, CHECKS = 3, 4, 40  # restore_access
MAX_BLOCKERS, TRIES = 3, 5  # make_room


class Reach:
    """Which task objects the robot can reach, on the navigation grid of one room."""

    def __init__(self, ep: Episode):
        room = ep.problem.plan.room
        self.grid = nav.Grid(room.width, room.depth)
        self.mesh = self.grid.mesh()
        self.start = nav.door_cells(self.grid, room)
        self.task = {o.id for o in ep.problem.plan.objects if o.is_task}
        self._strips: dict[tuple, np.ndarray] = {}

    def strip(self, p: PlacedObject) -> np.ndarray:
        key = (p.x, p.z, p.rotation, p.width, p.depth)
        if key not in self._strips:
            self._strips[key] = nav.in_box_mask(self.grid, front_boxes(p.x, p.z, p.rotation, p.width, p.depth,
                                                                      ACCESS_DEPTH))
        return self._strips[key]

    def blocked(self, placed: list[PlacedObject]) -> np.ndarray:
        return nav.blocked_by_boxes(self.grid, np.array([p.body for p in placed]).reshape(-1, 4))

    def unreachable(self, placed: list[PlacedObject], blocked: np.ndarray | None = None) -> list[str]:
        reach = nav.reachable_from(self.blocked(placed) if blocked is None else blocked, self.start)
        return [p.id for p in placed if p.id in self.task and not (self.strip(p) & reach).any()]


def _best_move(ep: Episode, reach: Reach, placed: list[PlacedObject], oid: str, out_of_reach: int):
    """(task objects out of reach, energy, new pose, step) of the best pose for `oid`, or None if no pose
    reaches more of them than now."""
    obj = ep.problem.plan.object(oid)
    others = [p for p in placed if p.id != oid]
    cands, feasible, terms = _scored(ep, obj, others, relax=False)
    if not len(feasible):
        return None
    base = reach.blocked(others)
    best = None
    for k in np.argsort(terms["total"], kind="stable")[:CHECKS]:
        pose = ep.scorer.place(obj, *(float(v) for v in cands[feasible[k]]))
        left = len(reach.unreachable([*others, pose], nav.blocked_with(reach.mesh, base, pose.body)))
        if left < out_of_reach and (best is None or left < best[0]):
            best = (left, float(terms["total"][k]), pose, _step(oid, pose, cands, feasible, int(k), terms))
            if left == 0:
                break
    return best


def repair(ep: Episode, observer: StepObserver | None = None) -> list[str]:
    """Both passes on the finished episode `ep`: the ids moved or placed, in order."""
    return make_room(ep, observer) + restore_access(ep, observer)


def _legal(ep: Episode, obj, placed: list[PlacedObject], cands: np.ndarray, swept: SweptBoxes,
           relax: bool = True) -> np.ndarray:
    """Indices of the legal poses among `cands`; with `relax`, the front-clearance rules relaxed if none
    is legal with them (as `Episode.options` does)."""
    ok, _ = hard_filter(ep.scorer, obj, placed, cands, swept, True)
    if relax and not ok.any():
        ok, _ = hard_filter(ep.scorer, obj, placed, cands, swept, False)
    return np.flatnonzero(ok)


def _scored(ep: Episode, obj, placed: list[PlacedObject], pending=(), relax: bool = True):
    """(every candidate pose of `obj`, the indices of the legal ones, their energy terms with `placed` where
    they are and `pending` still to come); no terms when none is legal."""
    cands, body = candidate_bodies(ep.scorer, obj)
    legal = _legal(ep, obj, placed, cands, SweptBoxes(body), relax)
    terms = CandidateEnergy(ep.problem, placed, pending=pending).score(obj, cands[legal]) if len(legal) else {}
    return cands, legal, terms


def _step(obj_id: str, pose: PlacedObject, cands: np.ndarray, legal: np.ndarray, k: int, terms: dict) -> PlacementStep:
    scores = np.full(len(cands), -np.inf)
    scores[legal], scores[legal[k]] = 0.0, 1.0
    return PlacementStep(obj_id, pose.x, pose.z, pose.rotation, cands, scores, {t: float(v[k]) for t, v in terms.items()})


def _displacements(ep: Episode, obj, cands: np.ndarray, swept: SweptBoxes) -> list[tuple[int, list[str]]]:
    """Poses `obj` could take if at most `MAX_BLOCKERS` placed objects (none fixed) were moved away: (pose
    index, the ids in the way, largest first), fewest in the way first, then lowest energy (the overlap
    with them not counted), at most `TRIES`."""
    way: list[list[int]] = [[] for _ in cands]
    for j, p in enumerate(ep.placed):
        for idx, area in swept.overlaps(p.body[None]):
            for i in idx[area > OVERLAP_TOL]:
                way[i].append(j)
    fixed = {j for j, p in enumerate(ep.placed) if p.id in ep.problem.fixed}
    free = hard_filter(ep.scorer, obj, [], cands, swept, False)[0]  # inside, doorways clear
    options = np.array([i for i in np.flatnonzero(free) if 0 < len(way[i]) <= MAX_BLOCKERS and not fixed & set(way[i])],
                       int)
    if not len(options):
        return []
    terms = CandidateEnergy(ep.problem, ep.placed, pending=()).score(obj, cands[options])
    cost = terms["total"] - WEIGHTS["collision"] * terms["collision"]
    order = sorted(range(len(options)), key=lambda k: (len(way[options[k]]), cost[k]))[:TRIES]
    area = {p.id: p.width * p.depth for p in ep.placed}
    return [(int(options[k]), sorted((ep.placed[j].id for j in way[options[k]]), key=lambda i: -area[i]))
            for k in order]


def make_room(ep: Episode, observer: StepObserver | None = None) -> list[str]:
    """Place the objects `ep` left out for want of room: each at a pose where at most `MAX_BLOCKERS` placed
    objects stand in the way, which are then placed again, each at its lowest-energy legal pose; the ids
    placed or moved, in order."""
    done: list[str] = []
    for obj in [o for o in ep.order if ep.failed.get(o.id) == NO_ROOM and o.id not in ep.problem.fixed]:
        cands, body = candidate_bodies(ep.scorer, obj)
        swept = SweptBoxes(body)
        for i, blockers in _displacements(ep, obj, cands, swept):
            pose = ep.scorer.place(obj, *(float(v) for v in cands[i]))
            placed = [p for p in ep.placed if p.id not in blockers]
            if i not in _legal(ep, obj, placed, cands, swept):
                continue
            placed.append(pose)
            steps = [None]  # the left-out object's, once the others are placed again
            for k, mover in enumerate(blockers):
                m_obj = ep.problem.plan.object(mover)
                m_cands, legal, terms = _scored(ep, m_obj, placed, pending=set(blockers[k + 1:]))
                if not len(legal):
                    break
                best = int(np.argmin(terms["total"]))
                placed.append(ep.scorer.place(m_obj, *(float(v) for v in m_cands[legal[best]])))
                steps.append(_step(mover, placed[-1], m_cands, legal, best, terms))
            else:
                # the left-out object's step shows the energy of the repaired layout
                terms = CandidateEnergy(ep.problem, [p for p in placed if p is not pose], pending=()).score(
                    obj, cands[[i]])
                steps[0] = _step(obj.id, pose, cands, np.array([i]), 0, terms)
                ep.placed = placed
                del ep.failed[obj.id]
                ep.energy, ep.terms = steps[0].terms["total"], steps[0].terms
                done += [s.object_id for s in steps]
                for step in steps if observer is not None else ():
                    observer(step)
                break
    return done


def restore_access(ep: Episode, observer: StepObserver | None = None) -> list[str]:
    """Move objects of the finished episode `ep` until every placed task object is reachable (or `ROUNDS`
    moves are spent, or no move helps); the ids moved, in order. Each move is a step for the observer."""
    reach = Reach(ep)
    moved: list[str] = []
    for _ in range(ROUNDS):
        out = reach.unreachable(ep.placed)
        if not out:
            break
        pos = {p.id: p for p in ep.placed}
        free = [p for p in ep.placed if p.id not in ep.problem.fixed]
        near = sorted((p for p in free if p.id not in out),
                      key=lambda p: min(abs(p.x - pos[o].x) + abs(p.z - pos[o].z) for o in out))
        movable = [p.id for p in free if p.id in out] + [p.id for p in near[:NEAR]]
        moves = [m for m in (_best_move(ep, reach, ep.placed, oid, len(out)) for oid in movable) if m]
        if not moves:
            break
        _, energy, pose, step = min(moves, key=lambda m: m[:2])
        ep.placed = [pose if p.id == pose.id else p for p in ep.placed]
        ep.energy, ep.terms = energy, step.terms
        moved.append(pose.id)
        if observer is not None:
            observer(step)
    return moved
