"""Access repair (not in the paper): after the last object, make the task objects reachable again.

A step-wise placer decides each object once. An object placed late can wall off the access strip of a
task object placed early, and the energy's navigation term, which sees only the objects placed so far, is
traded against the relations. This pass runs only when some task object cannot be reached from the
doorway (Key_NAV's test: a free cell of its 0.6 m access strip connected to the doorway). It then moves
one object at a time, up to `ROUNDS` moves: an unreachable task object or one of the `NEAR` others nearest
to them, never a fixed one. For each, its `CHECKS` legal poses of lowest energy are tried (hard filters as
when placing, the other objects where they are), and the move that leaves the fewest task objects out of
reach, lowest energy first, is kept if it reaches more of them. Its time counts in the solver's PTO.
"""

from __future__ import annotations

import numpy as np

from models.energy import navigation as nav
from models.energy.vectorised import CandidateEnergy
from models.energy.weights import ACCESS_DEPTH
from models.geometry import SweptBoxes
from models.placement.base import PlacementStep, StepObserver
from models.placement.candidates import PlacedObject, front_boxes
from models.placement.greedy import Episode, candidate_bodies, hard_filter

ROUNDS, NEAR, CHECKS = 3, 4, 40


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
    cands, body = candidate_bodies(ep.scorer, obj)
    ok, _ = hard_filter(ep.scorer, obj, others, cands, SweptBoxes(body), True)
    feasible = np.flatnonzero(ok)
    if not len(feasible):
        return None
    terms = CandidateEnergy(ep.problem, others, pending=()).score(obj, cands[feasible])
    base = reach.blocked(others)
    best = None
    for k in np.argsort(terms["total"], kind="stable")[:CHECKS]:
        pose = ep.scorer.place(obj, *(float(v) for v in cands[feasible[k]]))
        left = len(reach.unreachable([*others, pose], nav.blocked_with(reach.mesh, base, pose.body)))
        if left < out_of_reach and (best is None or left < best[0]):
            scores = np.full(len(cands), -np.inf)
            scores[feasible], scores[feasible[k]] = 0.0, 1.0
            step = PlacementStep(oid, pose.x, pose.z, pose.rotation, cands, scores,
                                 {t: float(v[k]) for t, v in terms.items()})
            best = (left, float(terms["total"][k]), pose, step)
            if left == 0:
                break
    return best


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
