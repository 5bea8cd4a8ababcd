"""Repairs after the last object (not in the paper): a step-wise placer decides each object once, so what
an early choice costs later is only seen at the end. The passes run only when something is wrong, each
move is a placement step for the observer, fixed objects never move, and their time counts in PTO. The
later passes, the constraints' polish, its group moves and the companions' pass, are in models.placement.polish,
models.placement.groups and models.placement.habits.

- `make_room`: an object left out for want of room is placed where at most `MAX_BLOCKERS` placed objects
  stand in its way (fewest first, then its lowest energy; `TRIES` such poses; models.placement.moves), and
  those are placed again, largest first, each at its lowest-energy legal pose; if one finds none, the next
  pose is tried.
- `restore_access`: a task object placed early can have its access strip walled off by objects placed
  later (the energy's navigation term sees only the objects placed so far and is traded against the
  relations). When some task object cannot be reached from the doorway (Key_NAV's test: a free cell of
  its 0.6 m access strip connected to the doorway), up to `ROUNDS` objects are moved one at a time: an
  unreachable task object or one of `NEAR` others (first those whose removal alone reaches more task
  objects, wherever they stand, then the nearest to the unreachable ones), each tried at its `CHECKS` legal
  poses of lowest energy (hard filters as when placing, the others where they are); the move that
  leaves the fewest task objects out of reach, lowest energy first, is kept if it reaches more of them. In a
  room the robot crosses, a door it cannot reach counts as a task object out of reach (models.placement.reach).
"""

from __future__ import annotations

import numpy as np

from models.energy.vectorised import CandidateEnergy
from models.placement.base import StepObserver
from models.placement.greedy import Episode
from models.placement.groups import regroup
from models.placement.habits import keep_companions
from models.placement.moves import displacements, legal_poses, move_step, scored
from models.placement.polish import Move, Standing, exactly, polish
from models.placement.result import NO_ROOM
from models.placement.ties import steady

ROUNDS, NEAR, CHECKS = 3, 4, 40  # restore_access
CLEARING = "clearing the robot's way to the task objects"  # a restore_access move's reason (" and doors": crossed room)


def _best_move(ep: Episode, now: Standing, oid: str) -> Move | None:
    """The move of `oid` to its pose that leaves the fewest task objects out of reach (of its `CHECKS` legal
    poses of lowest energy, the first such), or None if no pose reaches more of them than now."""
    obj = ep.problem.plan.object(oid)
    others = [p for p in ep.placed if p.id != oid]
    cands = ep.scorer.bodies(obj)[0]
    legal = legal_poses(ep, obj, others, cands, ep.scorer.swept(obj), relax=False)
    if not len(legal):
        return None
    setup = now.setup.without(oid)
    terms = setup.score(obj, cands[legal])
    best = None
    for k in np.argsort(steady(terms["total"]), kind="stable")[:CHECKS]:
        pose = ep.scorer.place(obj, *(float(v) for v in cands[legal[k]]))
        left = now.reach.out_with(others, setup.blocked, pose)
        if left < now.out and (best is None or left < best.out):
            judged = exactly(setup, obj, cands, legal, terms, int(k))
            why = CLEARING + (" and doors" if now.reach.gates else "")
            step = move_step(oid, pose, cands, legal, int(k), judged, why)
            best = Move([pose if p.id == oid else p for p in ep.placed], [step], float(judged["total"][k]), left,
                        lambda pose=pose: setup.after(pose))
            if left == 0:
                break
    return best


def repair(ep: Episode, observer: StepObserver | None = None) -> list[str]:
    """Every pass on the finished episode `ep` (room for the left-out, access, the constraints' polish, its group
    moves and the companions' pass, which never lose access): the ids moved or placed, in order."""
    return make_room(ep, observer) + restore_access(ep, observer) + polish(ep, observer) + regroup(ep, observer) + \
        keep_companions(ep, observer)


def make_room(ep: Episode, observer: StepObserver | None = None) -> list[str]:
    """Place the objects `ep` left out for want of room: each at a pose where at most `MAX_BLOCKERS` placed
    objects stand in the way, which are then placed again, each at its lowest-energy legal pose; the ids
    placed or moved, in order."""
    done: list[str] = []
    for obj in [o for o in ep.order if ep.failed.get(o.id) == NO_ROOM and o.id not in ep.problem.fixed]:
        cands, swept = ep.scorer.bodies(obj)[0], ep.scorer.swept(obj)
        for i, blockers in displacements(ep, obj, cands, swept, ep.placed):
            pose = ep.scorer.place(obj, *(float(v) for v in cands[i]))
            placed = [p for p in ep.placed if p.id not in blockers]
            if i not in legal_poses(ep, obj, placed, cands, swept):
                continue
            placed.append(pose)
            steps = [None]  # the left-out object's, once the others are placed again
            for k, mover in enumerate(blockers):
                m_obj = ep.problem.plan.object(mover)
                m_cands, legal, terms = scored(ep, m_obj, placed, pending=set(blockers[k + 1:]))
                if not len(legal):
                    break
                best = int(np.argmin(steady(terms["total"])))
                placed.append(ep.scorer.place(m_obj, *(float(v) for v in m_cands[legal[best]])))
                steps.append(move_step(mover, placed[-1], m_cands, legal, best, terms, f"making way for {obj.id}"))
            else:
                # the left-out object's step shows the energy of the repaired layout
                terms = CandidateEnergy(ep.problem, [p for p in placed if p is not pose], pending=()).score(
                    obj, cands[[i]], nav_mode="exact")
                steps[0] = move_step(obj.id, pose, cands, np.array([i]), 0, terms,
                                     f"left out at first: room made by moving {', '.join(blockers)}")
                ep.placed = placed
                del ep.failed[obj.id]
                ep.energy, ep.terms = steps[0].terms["total"], steps[0].terms
                done += [s.object_id for s in steps]
                for step in steps if observer is not None else ():
                    observer(step)
                break
    return done


def _suspects(ep: Episode, now: Standing, out: list[str], free: list) -> list[str]:
    """The movable objects (other than `out`) most likely walling off the task objects `out`: first those
    whose removal alone lets the robot reach more of them (most first), then the others, nearest first (a crossed
    room's door out of reach is where its doorway is)."""
    pos = {p.id: (p.x, p.z) for p in ep.placed} | now.reach.gate_centres
    others = [p for p in free if p.id not in out]
    freed = {p.id: len(out) - len(now.reach.unreachable([q for q in ep.placed if q is not p])) for p in others}
    near = {p.id: min(abs(p.x - pos[o][0]) + abs(p.z - pos[o][1]) for o in out) for p in others}
    return sorted(freed, key=lambda i: (-freed[i], near[i]))


def restore_access(ep: Episode, observer: StepObserver | None = None) -> list[str]:
    """Move objects of the finished episode `ep` until every placed task object is reachable (or `ROUNDS`
    moves are spent, or no move helps); the ids moved, in order. Each move is a step for the observer."""
    now = Standing(ep)
    moved: list[str] = []
    for _ in range(ROUNDS):
        out = now.reach.unreachable(ep.placed)
        if not out:
            break
        free = [p for p in ep.placed if p.id not in ep.problem.fixed]
        movable = [p.id for p in free if p.id in out] + _suspects(ep, now, out, free)[:NEAR]
        moves = [m for m in (_best_move(ep, now, oid) for oid in movable) if m]
        if not moves:
            break
        move = min(moves, key=lambda m: (m.out, m.energy))
        now.moved(move)
        moved.append(move.steps[0].object_id)
        if observer is not None:
            observer(move.steps[0])
    return moved
