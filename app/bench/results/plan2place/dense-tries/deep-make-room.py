"""Tried for `dense`, not kept (deep-make-room.txt): make_room with a second level, where a blocker that finds no legal
pose may itself displace one object not yet moved in the attempt (of its `SECOND_TRIES` best poses), which then goes
to its lowest-energy legal pose; `--deep` turns it on (without it: make_room as shipped, re-written here), and then
an attempt must leave no more task objects out of reach. 20 diagnosis plans x 2 seeds.
PYTHONPATH=. python app/bench/results/plan2place/dense-tries/deep-make-room.py dense 20 [--deep]"""
import sys
from pathlib import Path

import numpy as np

import models.placement.repair as R
from models.energy.vectorised import CandidateEnergy
from models.placement.greedy import NO_ROOM
from models.placement.moves import displacements, legal_poses, scored

DEEP = "--deep" in sys.argv
SECOND_TRIES = 3
STATS = {"rescued": 0, "second": 0}

def place_lowest(ep, m_obj, placed, pending):
    m_cands, legal, terms = scored(ep, m_obj, placed, pending=pending)
    if not len(legal):
        return None
    best = int(np.argmin(terms["total"]))
    return ep.scorer.place(m_obj, *(float(v) for v in m_cands[legal[best]])), (m_cands, legal, best, terms)

def place_blocker(ep, m_obj, placed, pending, frozen):
    got = place_lowest(ep, m_obj, placed, pending)
    if got is not None:
        return [got[0]], [(m_obj.id, got)], placed
    if not DEEP:
        return None
    cands = ep.scorer.bodies(m_obj)[0]
    movable = [p for p in placed if p.id not in frozen]
    for i, second in displacements(ep, m_obj, cands, ep.scorer.swept(m_obj), movable, tries=SECOND_TRIES):
        if len(second) > 1:
            continue
        rest = [p for p in placed if p.id not in second]
        if i not in legal_poses(ep, m_obj, rest, cands, ep.scorer.swept(m_obj)):
            continue
        pose = ep.scorer.place(m_obj, *(float(v) for v in cands[i]))
        trial, out = [*rest, pose], []
        for k, s in enumerate(second):
            g = place_lowest(ep, ep.problem.plan.object(s), trial, set(pending) | set(second[k + 1:]))
            if g is None:
                break
            trial.append(g[0]); out.append((s, g))
        else:
            STATS["second"] += 1
            return [pose] + [g[0] for _, g in out], [(m_obj.id, None)] + out, trial
    return None

def make_room(ep, observer=None):
    done = []
    for obj in [o for o in ep.order if ep.failed.get(o.id) == NO_ROOM and o.id not in ep.problem.fixed]:
        cands, swept = ep.scorer.bodies(obj)[0], ep.scorer.swept(obj)
        for i, blockers in displacements(ep, obj, cands, swept, ep.placed):
            pose = ep.scorer.place(obj, *(float(v) for v in cands[i]))
            placed = [p for p in ep.placed if p.id not in blockers]
            if i not in legal_poses(ep, obj, placed, cands, swept):
                continue
            placed.append(pose)
            frozen = {obj.id, *blockers}
            ok = True
            for k, mover in enumerate(blockers):
                got = place_blocker(ep, ep.problem.plan.object(mover), placed, set(blockers[k + 1:]), frozen)
                if got is None:
                    ok = False; break
                new, _, base = got
                placed = [p for p in base if p.id not in {q.id for q in new}] + new if base is not placed else placed + new
                frozen |= {q.id for q in new}
            if ok and DEEP and len(ep.reach.unreachable(placed)) > len(ep.reach.unreachable(ep.placed)):
                STATS["reach refused"] = STATS.get("reach refused", 0) + 1
                ok = False
            if ok:
                ep.placed = placed
                del ep.failed[obj.id]
                ep.energy = CandidateEnergy(ep.problem, placed).terms()["total"]
                done.append(obj.id)
                STATS["rescued"] += 1
                break
    return done
R.make_room = make_room

sys.path.insert(0, str(Path(__file__).parent))
from diagnosis_runs import run  # noqa: E402
print(run(sys.argv[1], int(sys.argv[2]), "DEEP" if DEEP else "BASE", f"/tmp/deep-{sys.argv[1]}-{'on' if DEEP else 'off'}.npy"), STATS)
